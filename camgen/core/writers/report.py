"""The JSON writer: a report (a JSON-ready dict, keys carrying their units) as indented JSON."""
from __future__ import annotations

import json
from pathlib import Path
from typing import Any


def report_json(report: dict[str, Any]) -> str:
    """``report`` as JSON text (two-space indent, a final newline); NaN or infinity is an error, not a value, and a
    negative zero is written as 0.0 (a rounded -1e-13 is nothing to sign)."""
    return json.dumps(unsigned_zeros(report), indent=2, allow_nan=False) + "\n"


def unsigned_zeros(value: Any) -> Any:
    """``value`` (JSON-ready: dicts, lists, tuples, numbers, strings) with every -0.0 made 0.0."""
    if isinstance(value, float):
        return value + 0.0                               # -0.0 + 0.0 is 0.0; every other float is unchanged
    if isinstance(value, dict):
        return {k: unsigned_zeros(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [unsigned_zeros(v) for v in value]
    return value


def write_json(report: dict[str, Any], path: Path, options: Any = None) -> None:
    path.write_text(report_json(report), encoding="utf-8")


WRITERS = {"json": write_json}
