"""Starter templates (``camgen new``, ``linkgen new``): a template as TOML text, each key commented with what its
field means and its unit, read from the template's own models (so the comments say what validation says).

A starter is a header (comment lines) and tables in order: ``("", {...})`` for top-level keys,
``("cam", {...})`` for ``[cam]``, ``("[motion]", {...})`` for one ``[[motion]]`` entry,
``("linkage.joints", {...})`` for a nested table. ``models`` maps a table's name (without
brackets) to the pydantic model whose fields describe its keys.
"""
from __future__ import annotations

import textwrap
import types
import typing
from collections.abc import Mapping, Sequence
from typing import Any

from camgen.core.toml_text import toml_value

#: the column comments start at, and the widest a line is made (a longer comment goes on in that column)
COMMENT_COLUMN, WIDTH = 28, 118


def field_comment(model: Any, key: str) -> str | None:
    """What field ``key`` of ``model`` means, with its unit (``mm: base circle radius``); None if it has none."""
    fields = getattr(model, "model_fields", {})
    info = fields.get(key)
    if info is None or not info.description:
        return None
    extra = info.json_schema_extra if isinstance(info.json_schema_extra, dict) else {}
    unit = extra.get("unit")
    return f"{unit}: {info.description}" if unit else info.description


def table_models(spec: Any) -> dict[str, Any]:
    """The model of each table of the template model ``spec`` (a pydantic model class), by its key: a field whose
    type is a model (``[cam]``), an optional one (``[kit]``) or a list of them (``[[motion]]``); what
    :func:`render` comments a starter's keys from."""
    models = {}
    for key, info in spec.model_fields.items():
        kind = info.annotation
        if typing.get_origin(kind) in (typing.Union, types.UnionType):
            kind = next((arg for arg in typing.get_args(kind) if arg is not type(None)), kind)
        if typing.get_origin(kind) is list:
            kind = typing.get_args(kind)[0]
        if isinstance(kind, type) and hasattr(kind, "model_fields"):
            models[key] = kind
    return models


def render(header: str, tables: Sequence[tuple[str, Mapping[str, Any]]], models: Mapping[str, Any],
           notes: Mapping[str, str] | None = None) -> str:
    """The template's TOML text: ``header`` as comment lines, then each table with its keys commented from
    ``models`` (``notes`` gives a comment of its own for a ``table.key``, and one under a table's heading)."""
    notes = notes or {}
    lines = [f"# {line}".rstrip() for line in header.strip().splitlines()]
    for name, keys in tables:
        table = name.strip("[]")
        if name:
            lines += ["", f"[{name}]"]                   # "[motion]" makes [[motion]], an entry of a list
            if table in notes:
                lines += [f"# {line}" for line in textwrap.wrap(notes[table], WIDTH - 2)]
        for key, value in keys.items():
            text = f"{key} = {toml_value(value)}"
            comment = notes.get(f"{table}.{key}" if table else key) or field_comment(models.get(table), key)
            lines += _commented(text, comment) if comment else [text]
    return "\n".join(lines) + "\n"


def _commented(text: str, comment: str) -> list[str]:
    """The line ``text`` with ``comment`` from :data:`COMMENT_COLUMN`, continued on comment lines in that column when
    it would pass :data:`WIDTH` characters."""
    start = max(COMMENT_COLUMN - 1, len(text) + 1)
    parts = textwrap.wrap(comment, WIDTH - start - 2) or [comment]
    first = f"{text.ljust(COMMENT_COLUMN - 1)} # {parts[0]}"
    return [first, *(f"{' ' * (COMMENT_COLUMN - 1)} # {part}" for part in parts[1:])]
