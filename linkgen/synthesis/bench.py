"""The synthesis rows of ``linkgen bench``: published test problems, solved here, timed here, beside a plain
differential evolution given the same budget in the same run.

* six points on a straight line, (20, 20) to (20, 45), at crank angles 30 to 105 degrees (the
  issue's ``line6``: links 5 to 60 mm, a Grashof crank);
* eighteen points on a closed curve without timing (the curve of Kunjur and Krishnamurty, 1997);
* y = log10(x) over 1..10 by Freudenstein's equation at three Chebyshev points, and by least squares at nine.

The baseline searches all ten unknowns of a path (pivot, ground line, lengths, coupler point,
branch; and without timing the crank angles) with the same constraints as a penalty and no
polish, for as many designs as ours evaluated. Nothing here is asserted about time.

The published rows (:func:`published_rows`) put each paper's reported linkage beside ours, both
scored by the same metric (:mod:`linkgen.synthesis.published`), with our wall and CPU time.
"""
from __future__ import annotations

import statistics
import time
from typing import Any

import numpy as np

from linkgen.synthesis import path
from linkgen.synthesis.run import synthesize
from linkgen.synthesis.task import validate_task

LINE6 = {"kind": "path", "points": [[20, 20], [20, 25], [20, 30], [20, 35], [20, 40], [20, 45]],
         "input_angles": [30, 45, 60, 75, 90, 105], "crank": True, "link_range": [5, 60]}
#: Kunjur, A. and Krishnamurty, S. (1997), "Genetic algorithms in mechanism synthesis", Journal of Applied
#: Mechanisms and Robotics 4(2), 18-24: eighteen points of a closed curve, no timing (checked against the list as
#: four-bar-rs quotes it from Bulatovic et al. 2016, KmolYuan/four-bar-rs test-fb/mkh1.closed.csv at 045135a)
CURVE18 = {"kind": "path", "closed": True, "link_range": [0.05, 5.0],
           "points": [[0.5, 1.1], [0.4, 1.1], [0.3, 1.1], [0.2, 1.0], [0.1, 0.9], [0.05, 0.75], [0.02, 0.6],
                      [0.0, 0.5], [0.0, 0.4], [0.03, 0.3], [0.1, 0.25], [0.15, 0.2], [0.2, 0.3], [0.3, 0.4],
                      [0.4, 0.5], [0.5, 0.7], [0.6, 0.9], [0.6, 1.0]]}
#: the textbook's log10 problem as posed: its linkage's transmission angle falls to 2.8 degrees over the input range,
#: so it is measured here with no transmission limit (templates/synth-log10.toml asks for a rocker 105 to 165 degrees)
LOG10 = {"kind": "function", "function": "log10(x)", "x_range": [1, 10], "input_angles": [30, 120],
         "output_angles": [90, 180], "min_transmission": 0}


def plain_objective(x: np.ndarray, p: path.Problem) -> np.ndarray:
    """The baseline's objective over all the unknowns (x0, y0, theta0, r1..r4, cx, cy, branch, [angles]): the same
    error and constraints, as one penalty, evaluated for the whole population at once."""
    searched = np.vstack([x[2:7], x[9:]])             # the projected search's layout: theta0, lengths, branch, ...
    th = path.angles(searched, p)
    err = path.squared_errors(x[:9], x[9], th, p).sum(axis=1)
    broken = (np.sum(np.maximum(0.0, -path.hard_constraints(x[:9], th, p)), axis=0)
              + np.sum(np.maximum(0.0, -path.soft_constraints(x[:9], p)), axis=0))
    return np.where(broken > 0, path.BIG * (1.0 + broken), err)


def plain_search(p: path.Problem, designs: int, seed: int) -> tuple[float, float]:
    """Plain differential evolution (scipy's defaults, vectorised) for about ``designs`` designs: (best error
    mm^2, seconds)."""
    from scipy.optimize import differential_evolution

    bounds = [*p.box, (-1.0, 1.0), *p.bounds[6:]]
    population = 15 * len(bounds)
    clock = time.perf_counter()
    r = differential_evolution(plain_objective, bounds, args=(p,), vectorized=True, updating="deferred", seed=seed,
                               maxiter=max(1, designs // population - 1), popsize=15, tol=0, polish=False)
    return float(r.fun), time.perf_counter() - clock


def _path_row(name: str, keys: dict[str, Any], starts: int, generations: int, runs: int = 1) -> dict[str, Any]:
    """Our synthesis of a path problem and the plain search given as many designs, run as ``runs`` pairs in turn
    (ours, then the baseline: both see the same machine); each one's seconds as the median, least and largest over
    the pairs; the errors are the last pair's (both searches seeded)."""
    raw = {"name": "bench", "task": {**keys, "starts": starts, "generations": generations, "candidates": 1}}
    spec = validate_task(raw)
    ours, cpus, theirs = [], [], []
    for _ in range(max(1, runs)):
        clock, cpu = time.perf_counter(), time.process_time()
        result = synthesize(spec)
        ours.append(time.perf_counter() - clock)
        cpus.append(time.process_time() - cpu)
        baseline, plain_seconds = plain_search(path.problem_of(spec.task), result.search["designs_evaluated"], seed=1)
        theirs.append(plain_seconds)
    best = result.candidates[0].row
    return {"problem": name, "ours_error": best["error_mm2"], "ours_seconds": statistics.median(ours),
            "ours_seconds_min": min(ours), "ours_seconds_max": max(ours), "cpu_seconds": statistics.median(cpus),
            "designs": result.search["designs_evaluated"], "baseline_error": baseline,
            "baseline_seconds": statistics.median(theirs), "baseline_seconds_min": min(theirs),
            "baseline_seconds_max": max(theirs), "runs": len(ours), "published_error": None,
            "unit": "mm^2 (sum of squared distances)"}


def _function_row(points: int) -> dict[str, Any]:
    clock = time.perf_counter()
    result = synthesize(validate_task({"name": "log10", "task": {**LOG10, "precision_points": points}}))
    row = result.candidates[0].row
    return {"problem": f"log10(x), 1..10, {points} Chebyshev points" + (" (exact)" if points == 3 else
                                                                         " (least squares)"),
            "ours_error": row["structural_error_max"], "ours_seconds": time.perf_counter() - clock,
            "structural_error_percent": row["structural_error_percent"], "baseline_error": None,
            "published_error": None, "unit": "largest |y - log10 x| over the range"}


def synthesis_rows(quick: bool) -> list[dict[str, Any]]:
    """The bench's synthesis rows (quick: one search of at most 200 and 100 generations, one pair; else at most 4
    starts of 1500 and 3000 generations, three pairs in turn; the searches stop sooner where they stall or the
    starts agree: :mod:`linkgen.synthesis.stop`)."""
    starts, line6, curve, runs = (1, 200, 100, 1) if quick else (4, 1500, 3000, 3)
    return [_path_row("six points on a line, timed (line6)", LINE6, starts, line6, runs),
            _path_row("eighteen points on a closed curve, untimed (Kunjur and Krishnamurty 1997)", CURVE18,
                      starts, curve, runs),
            _function_row(3), _function_row(9)]


def published_rows(atlas_folder: str | None = None, quick: bool = False) -> list[dict[str, Any]]:
    """The published untimed problems (:data:`linkgen.synthesis.published.PROBLEMS`), each solved by the Fourier
    method and scored beside its paper's linkage (the atlas from ``atlas_folder``, default the user's cache);
    ``quick``: the first only (the one that builds the atlas where it is not kept yet)."""
    from linkgen.synthesis.published import PROBLEMS, solve_row

    return [solve_row(problem, atlas_folder) for problem in PROBLEMS[:1 if quick else None]]


def published_markdown(rows: list[dict[str, Any]], synthesis: list[dict[str, Any]]) -> list[str]:
    """The published rows as a Markdown table, with the timed six-point line from the ``synthesis`` rows (no
    linkage of its paper is in the data used)."""
    lines = ["| problem | points | timed | paper's linkage (mm^2) | ours (mm^2) | ours / paper | wall (s) | CPU (s) "
             "| worst transmission, paper / ours (deg) |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        built = f" (atlas built: {r['atlas']['seconds']:.1f})" if r["atlas"]["built"] else ""
        lines.append(f"| {r['problem']} (x{r['scale_mm']:g} mm) | {r['points']} | no | {r['published_error']:.4g} "
                     f"| {r['ours_error']:.4g} | {r['ratio']:.3f} | {r['ours_seconds']:.1f}{built} | "
                     f"{r['cpu_seconds']:.1f} | {r['published_transmission_deg']:.1f} / "
                     f"{r['ours_transmission_deg']:.1f} |")
    for r in synthesis:
        if r["problem"].startswith("six points"):
            cpu = f"{r['cpu_seconds']:.1f}" if "cpu_seconds" in r else "-"
            lines.append(f"| {r['problem']} | 6 | yes | not in the data used | {r['ours_error']:.4g} | - | "
                         f"{r['ours_seconds']:.1f} | {cpu} | - |")
    return [*lines, "", "Untimed: the sum of squared distances from each target to the nearest point of the whole "
            "coupler curve; timed: to the coupler point at the target's crank angle. Our transmission limit is the "
            "paper's linkage's worst, rounded down, where that is below 30 degrees."]


def markdown(rows: list[dict[str, Any]]) -> list[str]:
    """The rows as a Markdown table."""
    lines = ["| problem | ours | time (s): median (least - largest) | plain DE, same designs | its time (s) | pairs "
             "| unit |", "|---|---|---|---|---|---|---|"]

    def spread(r: dict[str, Any], key: str) -> str:
        if r.get(key) is None:
            return "-"
        return f"{r[key]:.2f}" + (f" ({r[key + '_min']:.2f} - {r[key + '_max']:.2f})" if key + "_min" in r else "")

    for r in rows:
        base = "-" if r["baseline_error"] is None else f"{r['baseline_error']:.4g}"
        lines.append(f"| {r['problem']} | {r['ours_error']:.4g} | {spread(r, 'ours_seconds')} | {base} | "
                     f"{spread(r, 'baseline_seconds')} | {r.get('runs', 1)} | {r['unit']} |")
    return [*lines, "", "Path rows run as pairs in turn, ours then the plain search, so that both see the same "
            "machine."]

