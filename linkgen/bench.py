"""``linkgen bench``: linkage positions against a plain closed form and pylinkage, measured in the same run,
and the linkages' hard cases.

Every figure is measured here, on this machine, in this run; nothing is asserted about time.
Results go to ``RESULTS.md`` and ``results.json``.
"""
from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from camgen.core import bench as core_bench
from camgen.core.bench import timed
from linkgen.kinematics.fourbar import FourBar
from linkgen.kinematics.slidercrank import SliderCrank


def linkage_speed(repeats: int) -> list[dict]:
    """Rocker-pin positions of the reference crank-rocker at 360 and 100 000 crank angles: ours, a plain numpy
    closed form (arccos), and pylinkage (plain steps, and its numba-compiled steps), with their accuracy."""
    fb = FourBar(180, 80, 200, 150)
    rows = []
    for n in (360, 100_000):
        t = 2 * math.pi / n * np.arange(1, n + 1)
        exact, ours = timed(lambda t=t: fb.positions(t).b, repeats)

        def plain(t: np.ndarray = t) -> np.ndarray:
            ax, ay = 80 * np.cos(t), 80 * np.sin(t)
            dx, dy = 180 - ax, -ay
            z = np.hypot(dx, dy)
            alpha = np.arccos(np.clip((200**2 + z**2 - 150**2) / (2 * 200 * z), -1, 1))
            th3 = np.arctan2(dy, dx) + alpha
            return np.column_stack([ax + 200 * np.cos(th3), ay + 200 * np.sin(th3)])

        naive, seconds = timed(plain, repeats)
        rows += [{"method": "linkgen closed form (stable at toggles)", "angles": n, "seconds": ours,
                  "max_error_mm": 0.0},
                 {"method": "plain numpy closed form (arccos)", "angles": n, "seconds": seconds,
                  "max_error_mm": float(np.abs(naive - exact).max())}]
        rows += _pylinkage(n, exact, repeats)
    return rows


def _pylinkage(n: int, exact: np.ndarray, repeats: int) -> list[dict]:
    try:
        import pylinkage as pl
    except ImportError:
        return [{"method": "pylinkage", "angles": n, "seconds": None,
                 "status": "not installed (pip install '.[bench]')"}]
    try:
        import numba  # noqa: F401 - pylinkage compiles its fast steps with it where it installs
        fast_name = "pylinkage step_fast (numba)"
    except ImportError:
        fast_name = "pylinkage step_fast (numba not installed)"

    def linkage() -> Any:
        o2, o4 = pl.Ground(0, 0), pl.Ground(180, 0)
        crank = pl.Crank(o2, 80, angular_velocity=2 * math.pi / n, initial_angle=0.0)
        return pl.Linkage([o2, o4, crank, pl.RRRDyad(crank, o4, 200, 150, x=245, y=135)])

    rows = []
    for name, run in (("pylinkage step (plain Python)", lambda: np.array([c[3] for c in linkage().step(iterations=n)],
                                                                      dtype=float)),
                      (fast_name, lambda: linkage().step_fast(iterations=n)[:, 3, :])):
        start = time.perf_counter()
        run()
        first = time.perf_counter() - start
        result, seconds = timed(run, repeats)
        rows.append({"method": name, "angles": n, "seconds": seconds, "first_call_seconds": first,
                     "max_error_mm": float(np.abs(result - exact).max())})
    return rows


def hard_cases() -> list[dict]:
    """Each hard case with what happened: a sound value, or a clean refusal (never NaN or garbage)."""
    return core_bench.hard_cases(_cases())


def _cases() -> Iterator[tuple[str, Callable[[], str]]]:
    fb = FourBar(100, 70, 60, 80)
    _, hi = fb.input_ranges()[0]
    for offset in (0.0, 1e-12):
        def toggle(offset: float = offset) -> str:
            p = fb.positions([hi - offset])
            closes = abs(np.linalg.norm(p.b[0] - p.a[0]) - 60) < 1e-9
            return f"{'ok' if closes and np.isfinite(p.theta4).all() else 'WRONG'}: transmission " \
                   f"{math.degrees(p.gamma[0]):.6f} deg"

        yield f"four-bar {offset:g} rad inside its toggle", toggle
    yield "four-bar 1e-6 rad beyond its toggle", lambda: str(fb.positions([hi + 1e-6]).theta3)
    par = FourBar(100, 40, 100, 40)
    yield "parallelogram through its change points", lambda: "ok" if np.abs(np.sin(par.sweep(
        np.radians(np.linspace(10, 730, 1441)), "open").theta3)).max() < 1e-12 else "WRONG"
    sc = SliderCrank(50.0, 50.0 + 1e-9)
    yield "slider-crank with rod = crank + 1e-9", lambda: "ok" if np.isfinite(sc.motion(
        np.linspace(0, 2 * math.pi, 721), 1.0).a).all() else "WRONG"


def run_bench(out: str | Path, quick: bool = False) -> dict:
    """Run everything; write RESULTS.md and results.json into ``out``; return the results."""
    repeats = 1 if quick else 5
    return core_bench.finish(Path(out), {"quick": quick, "linkages": linkage_speed(repeats),
                                         "hard_cases": hard_cases()}, _markdown)


def _markdown(r: dict) -> list[str]:
    lines = ["# linkgen bench", "", f"Python {r['python']}; {'quick run' if r['quick'] else 'full run'}; "
             "median of repeats.", "",
             "## Linkage positions (rocker pin of the reference crank-rocker)", "",
             "| method | angles | seconds | max error (mm) | status |", "|---|---|---|---|---|"]
    for row in r["linkages"]:
        sec = "-" if row.get("seconds") is None else f"{row['seconds']:.5f}"
        err = "-" if row.get("max_error_mm") is None else f"{row['max_error_mm']:.1e}"
        status = row.get("status", "measured")
        lines.append(f"| {row['method']} | {row.get('angles') or '-'} | {sec} | {err} | {status} |")
    return [*lines, "", "Errors of linkage positions are against linkgen's closed form (which the tests check "
                    "against 50-digit references); pylinkage's first call includes its compilation: "
                    + "; ".join(f"{row['method']} at {row['angles']}: {row['first_call_seconds']:.3f} s"
                                for row in r["linkages"] if "first_call_seconds" in row) + "."]
