"""The JSON writer: a report (a JSON-ready dict, keys carrying their units) as indented JSON; and tables the report
holds (a kit's bill of materials) as CSV beside it."""
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


def write_csv(rows: Any, path: Path, options: Any = None) -> None:
    """A table (a sequence of dicts with the same keys, the first's keys the header) as CSV: comma-separated,
    quoted where needed, ``\\n`` line ends, UTF-8; or a finished CSV text, written as it is."""
    import csv

    if isinstance(rows, str):
        path.write_text(rows, encoding="utf-8")
        return
    with path.open("w", encoding="utf-8", newline="") as stream:
        table = csv.DictWriter(stream, fieldnames=list(rows[0]), lineterminator="\n")
        table.writeheader()
        table.writerows(rows)


WRITERS = {"json": write_json, "csv": write_csv}
