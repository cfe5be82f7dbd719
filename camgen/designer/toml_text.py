"""A raw template (what :func:`tomllib.loads` gives) as TOML text that reads back to the same values."""
from __future__ import annotations

import json
import re
from collections.abc import Mapping
from typing import Any

from camgen.core.starter import toml_value

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(key: str) -> str:
    """``key`` bare where TOML allows, else quoted (``"O-A"`` is bare, ``"a b"`` is not)."""
    return key if _BARE.match(key) else json.dumps(key)


def _tables(value: Any) -> bool:
    """Whether ``value`` is a non-empty list of tables (an array of tables, ``[[motion]]``)."""
    return isinstance(value, list) and bool(value) and all(isinstance(v, Mapping) for v in value)


def _plain(value: Any) -> str:
    """A value on one line: nested tables inline (``{ link = "crank", pivot = "O" }``)."""
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{_key(k)} = {_plain(v)}" for k, v in value.items()) + " }"
    if isinstance(value, list):
        return "[" + ", ".join(_plain(v) for v in value) + "]"
    return toml_value(value)


def _table(lines: list[str], path: str, table: Mapping[str, Any], header: str) -> None:
    """Append ``table``'s keys under ``header`` (``[path]`` or ``[[path]]``), then its sub-tables."""
    if header:
        lines += ["", header]
    for k, v in table.items():
        if not isinstance(v, Mapping) and not _tables(v):
            lines.append(f"{_key(k)} = {_plain(v)}")
    for k, v in table.items():
        name = f"{path}.{_key(k)}" if path else _key(k)
        if isinstance(v, Mapping):
            _table(lines, name, v, f"[{name}]")
        elif _tables(v):
            for entry in v:
                _table(lines, name, entry, f"[[{name}]]")


def dumps(raw: Mapping[str, Any]) -> str:
    """``raw`` as TOML text: top-level keys first, then each table (``[cam]``), each entry of a list of tables
    (``[[motion]]``) and each nested table (``[linkage.joints]``) under its own heading; floats in full (``repr``),
    so the text reads back to equal values."""
    lines: list[str] = []
    _table(lines, "", raw, "")
    return "\n".join(lines).lstrip("\n") + "\n"
