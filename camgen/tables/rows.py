"""Rows read from a CSV file or a template: a table law's (angle, value) rows and a follower's load table.

The one reader of a table's file (:func:`read_table`) and the check of a load table's rows (:func:`load_rows`),
shared by a motion segment's ``file`` and a follower's ``load_table``.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

from camgen.core.reading import read_regular

#: the most rows a table law reads, and the largest CSV file (bytes)
MAX_TABLE_ROWS = 10_000
MAX_TABLE_BYTES = 2_000_000


def read_table(path: Path) -> list[tuple[float, float]]:
    """The (angle, value) rows of a CSV file: two numbers a line, separated by a comma (or a semicolon, a tab or
    spaces); a first line of names, blank lines and lines starting with # are passed over. A ValueError naming
    ``file`` (and the line) otherwise."""
    try:
        raw = read_regular(path, MAX_TABLE_BYTES)       # a FIFO or a device is refused, never waited on
    except OSError as exc:
        raise ValueError(f"file: cannot read {str(path)!r} ({exc.strerror or exc})") from None
    if len(raw) > MAX_TABLE_BYTES:
        raise ValueError(f"file: {str(path)!r} is larger than {MAX_TABLE_BYTES // 1_000_000} MB")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ValueError(f"file: {str(path)!r} is not UTF-8 text") from None
    rows: list[tuple[float, float]] = []
    names = False
    for number, line in enumerate(text.splitlines(), 1):
        fields = [f for f in re.split(r"[,;\t ]+", line.strip()) if f]
        if not fields or fields[0].startswith("#"):
            continue
        try:
            values = [float(f) for f in fields]
        except ValueError:
            if not rows and not names:
                names = True                             # a first line of column names
                continue
            raise ValueError(f"file: line {number}: expected two numbers, angle and value (got {line.strip()[:40]!r})"
                             ) from None
        if len(values) != 2 or not all(math.isfinite(v) for v in values):
            raise ValueError(f"file: line {number}: expected two finite numbers, angle and value")
        rows.append((values[0], values[1]))
        if len(rows) > MAX_TABLE_ROWS:
            raise ValueError(f"file: more than {MAX_TABLE_ROWS} rows")
    if len(rows) < 4:
        raise ValueError(f"file: {str(path)!r} holds {len(rows)} rows of angle, value; a table needs at least 4")
    return rows


def load_rows(rows: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """A load table's (cam angle in degrees, load in N) rows checked: angles strictly increasing from >= 0 to <= 360,
    a row at 360 only if one at 0 gives the same load (it is then dropped: the table is periodic over a turn), loads
    within 1e6 N; a ValueError saying what is wrong otherwise."""
    angles = [a for a, _ in rows]
    loads = [v for _, v in rows]
    if angles[0] < 0 or angles[-1] > 360:
        raise ValueError(f"cam angles must lie in 0 to 360 degrees (got {min(angles):g} to {max(angles):g})")
    bad = next((i for i in range(1, len(angles)) if not angles[i] > angles[i - 1]), None)
    if bad is not None:
        raise ValueError(f"cam angles must increase row by row (row {bad + 1}: {angles[bad]:g} after "
                         f"{angles[bad - 1]:g} degrees)")
    if any(not abs(v) <= 1e6 for v in loads):
        raise ValueError("loads must lie in -1e6 to 1e6 N")
    if angles[-1] == 360:
        if angles[0] != 0 or abs(loads[-1] - loads[0]) > 1e-9 * max(1.0, max(abs(v) for v in loads)):
            raise ValueError(f"the row at 360 degrees ({loads[-1]:g} N) must repeat the one at 0 degrees"
                             + (f" ({loads[0]:g} N)" if angles[0] == 0 else " (there is none)")
                             + ": the load is periodic over a turn")
        rows = list(rows[:-1])
    return list(rows)

