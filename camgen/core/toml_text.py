"""A raw template (what :func:`tomllib.loads` gives) as TOML text that reads back to the same values.

The one TOML writer of both products: the designer's "save", the candidates ``linkgen synthesize`` writes, the
template ``linkgen import`` reads from a sketch and the starters' values all go through it, so a template saved by
one reads back, with :mod:`tomllib`, to the values another wrote.
"""
from __future__ import annotations

import json
import math
import re
from collections.abc import Mapping
from typing import Any

import numpy as np

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def toml_key(key: str) -> str:
    """``key`` bare where TOML allows, else quoted (``O-A`` is bare, ``"a b"`` is not)."""
    return key if _BARE.match(key) else json.dumps(key)


def toml_value(value: Any) -> str:
    """``value`` (a bool, int, float, str, list, tuple or a mapping for an inline table; numpy scalars too) as TOML
    on one line; floats in full (``repr``), so that they read back to equal values.

    Raises
    ------
    ValueError
        For a float that is not finite (TOML's ``inf`` and ``nan`` are never a template's value).
    TypeError
        For a value with no TOML form.
    """
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        x = float(value)
        if not math.isfinite(x):
            raise ValueError(f"a template holds only finite numbers (got {x})")
        return repr(x)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{toml_key(k)} = {toml_value(v)}" for k, v in value.items()) + " }"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"no TOML form for {type(value).__name__}")


def _tables(value: Any) -> bool:
    """Whether ``value`` is a non-empty list of tables (an array of tables, ``[[motion]]``)."""
    return isinstance(value, list) and bool(value) and all(isinstance(v, Mapping) for v in value)


def _table(lines: list[str], path: str, table: Mapping[str, Any], header: str) -> None:
    """Append ``table``'s keys under ``header`` (``[path]`` or ``[[path]]``), then its sub-tables."""
    if header:
        lines += ["", header]
    for k, v in table.items():
        if not isinstance(v, Mapping) and not _tables(v):
            lines.append(f"{toml_key(k)} = {toml_value(v)}")
    for k, v in table.items():
        name = f"{path}.{toml_key(k)}" if path else toml_key(k)
        if isinstance(v, Mapping):
            _table(lines, name, v, f"[{name}]")
        elif _tables(v):
            for entry in v:
                _table(lines, name, entry, f"[[{name}]]")


def dumps(raw: Mapping[str, Any], comment: str = "") -> str:
    """``raw`` as TOML text.

    Parameters
    ----------
    raw
        The template's tables of numbers, strings, booleans and lists.
    comment
        Lines written first, each as a ``#`` comment; none when empty.

    Returns
    -------
    str
        The top-level keys first, then each table (``[cam]``), each entry of a list of tables (``[[motion]]``) and
        each nested table (``[linkage.joints]``) under its own heading, ending in one newline.
    """
    lines: list[str] = []
    _table(lines, "", raw, "")
    body = "\n".join(lines).lstrip("\n")
    head = "".join(f"# {line}\n" for line in comment.splitlines())
    return head + body + "\n"
