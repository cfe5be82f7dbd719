"""What both benches share: medians of repeated runs, hard cases, and their results written as JSON and Markdown.

Every figure is measured in this process on this machine; no test asserts a time.
"""
from __future__ import annotations

import json
import resource
import statistics
import sys
import time
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

from camgen.core.errors import CamgenError


def timed(func: Callable[[], Any], repeats: int) -> tuple[Any, float]:
    """``func()``'s result and the median of ``repeats`` wall times (seconds)."""
    times, result = [], None
    for _ in range(max(1, repeats)):
        start = time.perf_counter()
        result = func()
        times.append(time.perf_counter() - start)
    return result, statistics.median(times)


def hard_cases(cases: Iterable[tuple[str, Callable[[], str]]]) -> list[dict[str, str]]:
    """Each case's outcome: what its function says (a sound value, or ``WRONG...``), or a clean refusal (the
    project's error, as ``refused: ...``). Anything else escapes: a hard case must never crash."""
    rows = []
    for name, func in cases:
        try:
            rows.append({"case": name, "outcome": func()})
        except CamgenError as exc:
            rows.append({"case": name, "outcome": f"refused: {exc}"})
    return rows


def finish(out: Path, results: dict[str, Any], markdown: Callable[[dict[str, Any]], list[str]]) -> dict[str, Any]:
    """Add the Python version and the peak memory to ``results``; write ``results.json`` and ``RESULTS.md``
    (``markdown(results)``'s lines, then the memory and the hard cases) into ``out``; return the results."""
    results = {"python": sys.version.split()[0], **results,
               "peak_memory_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}
    lines = [*markdown(results), "", f"Peak resident memory: {results['peak_memory_mb']:.0f} MB.", "",
             "## Hard cases", "", "| case | outcome |", "|---|---|",
             *(f"| {row['case']} | {row['outcome']} |" for row in results.get("hard_cases", []))]
    out.mkdir(parents=True, exist_ok=True)
    (out / "results.json").write_text(json.dumps(results, indent=2, default=str) + "\n")
    (out / "RESULTS.md").write_text("\n".join(lines) + "\n")
    return results
