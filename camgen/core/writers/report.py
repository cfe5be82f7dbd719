"""The JSON writer: a report (a JSON-ready dict, keys carrying their units) as indented JSON."""
from __future__ import annotations

import json
from pathlib import Path
from typing import Any


def report_json(report: dict[str, Any]) -> str:
    """``report`` as JSON text (two-space indent, a final newline); NaN or infinity is an error, not a value."""
    return json.dumps(report, indent=2, allow_nan=False) + "\n"


def write_json(report: dict[str, Any], path: Path, options: Any = None) -> None:
    path.write_text(report_json(report), encoding="utf-8")


WRITERS = {"json": write_json}
