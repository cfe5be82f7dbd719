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


def process_seconds(command: list[str], cwd: Path | None = None) -> float:
    """CPU seconds (user + system) a child process running ``command`` takes, start-up included: on a shared
    machine a process's own CPU time moves far less than its wall time. Raises CalledProcessError if it fails.

    The child runs as an installed program would: with its modules' bytecode cached (see :func:`child_env`), and
    each command once untimed first so that the cache is there. Installed packages (numpy, ezdxf: the yardstick)
    ship their bytecode; a checkout run with PYTHONDONTWRITEBYTECODE set compiled its own ~70 modules every run,
    measured as 0.17x of the yardstick on ``camgen build``."""
    import subprocess

    def run() -> None:
        subprocess.run(command, cwd=cwd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       env=child_env())

    if tuple(command) not in _WARM:
        run()
        _WARM.add(tuple(command))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


#: commands :func:`process_seconds` has run once (the bytecode cache they need is written)
_WARM: set[tuple[str, ...]] = set()


def child_env() -> dict[str, str]:
    """This process's environment for a timed child, bytecode caching allowed: PYTHONDONTWRITEBYTECODE dropped,
    the cache kept under the system's temporary folder (PYTHONPYCACHEPREFIX), never in the checkout."""
    import os
    import tempfile

    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPYCACHEPREFIX"] = str(Path(tempfile.gettempdir()) / "camgen-bench-bytecode")
    return env


def call_seconds(func: Callable[[], Any], inner: int = 1) -> float:
    """The least of ``inner`` wall times of ``func()`` (seconds)."""
    best = float("inf")
    for _ in range(max(1, inner)):
        start = time.perf_counter()
        func()
        best = min(best, time.perf_counter() - start)
    return best


def ratio_row(what: str, reference: str, measure: Callable[[], float], measure_reference: Callable[[], float],
              repeats: int, unit: str = "s", warm: int = 0, **extra: Any) -> dict[str, Any]:
    """``what`` against ``reference``, measured alternately ``repeats`` times in this run (so that both see the
    same machine), after ``warm`` untimed pairs (an in-process call's first runs load modules and fill the
    processor's caches); each one's median (in ``unit``: "s" wall seconds in this process, "cpu s" a process's CPU
    seconds), and the ratio's median and spread (its least and largest over the pairs)."""
    for _ in range(warm):
        measure()
        measure_reference()
    ours, theirs = [], []
    for _ in range(max(1, repeats)):
        ours.append(measure())
        theirs.append(measure_reference())
    ratios = sorted(a / b for a, b in zip(ours, theirs, strict=True))
    return {"what": what, "reference": reference, "unit": unit, "runs": len(ratios),
            "seconds": statistics.median(ours), "reference_seconds": statistics.median(theirs),
            "ratio": statistics.median(ratios), "ratio_min": ratios[0], "ratio_max": ratios[-1], **extra}


def ratio_markdown(rows: list[dict[str, Any]]) -> list[str]:
    """The ratio rows as a Markdown table."""
    lines = ["| what | reference (same run) | time | reference | ratio: median (least - largest) | runs | goal |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        scale, unit = (1e3, "ms") if r["seconds"] < 0.1 else (1.0, r["unit"])
        lines.append(f"| {r['what']} | {r['reference']} | {r['seconds'] * scale:.3g} {unit} | "
                     f"{r['reference_seconds'] * scale:.3g} {unit} | {r['ratio']:.2f}x ({r['ratio_min']:.2f} - "
                     f"{r['ratio_max']:.2f}) | {r['runs']} | {r.get('goal', '-')} |")
    return lines
