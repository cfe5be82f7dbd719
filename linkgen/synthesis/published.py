"""Published path-synthesis problems and the linkages their papers reported, scored by our own metric.

Each problem's targets and its paper's linkage are as KmolYuan/four-bar-rs keeps them with their
citations (test-fb/NAME.closed.csv and test-fb/refer/NAME.closed.ron at commit 045135a), read
there and typed here as data. A linkage there is the crank pivot (p1x, p1y), the ground line's
direction a (rad), the lengths l1 (ground), l2 (crank), l3 (coupler), l4 (rocker), the coupler
point at l5 from the crank pin at angle g (rad, counter-clockwise) from the coupler line A -> B,
and its circuit: c1 puts B left of the line from A to O4, as ``branch = +1`` does here
(:mod:`linkgen.synthesis.geometry`), c2 right. So (cx, cy) = l5 (cos g, sin g).

The targets are scaled by a stated factor (mm per unit of the paper) so that each curve spans
about 100 mm; errors then scale with its square and their ratios not at all.

The metric (untimed): the sum over the targets of the squared distance (mm^2) from each to the
nearest point of the whole coupler curve the crank's full turn makes (each paper's linkage here is
a Grashof crank). Timed problems are scored at their crank angles instead.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkgen.synthesis.fourier_path import errors
from linkgen.synthesis.geometry import worst_transmission
from linkgen.synthesis.run import synthesize
from linkgen.synthesis.task import validate_task

#: where the data come from
SOURCE = "KmolYuan/four-bar-rs test-fb/ at 045135a"


@dataclass(frozen=True)
class Published:
    """One problem: ``key`` (its four-bar-rs name), ``title``, ``citation``, the targets (paper units), the scale
    (mm per unit), and the paper's linkage (p1x, p1y, a, l1, l2, l3, l4, l5, g; paper units and rad) and circuit
    (1 or 2)."""

    key: str
    title: str
    citation: str
    points: tuple[tuple[float, float], ...]
    scale: float
    linkage: tuple[float, float, float, float, float, float, float, float, float]
    circuit: int

    def targets(self) -> np.ndarray:
        """The targets (n, 2) in mm."""
        return np.array(self.points, dtype=float) * self.scale

    def design(self) -> tuple[np.ndarray, float]:
        """The paper's linkage in mm as this package's design (x0, y0, theta0, r1, r2, r3, r4, cx, cy) and branch."""
        p1x, p1y, a, l1, l2, l3, l4, l5, g = self.linkage
        k = self.scale
        v = np.array([k * p1x, k * p1y, a, k * l1, k * l2, k * l3, k * l4, k * l5 * math.cos(g),
                      k * l5 * math.sin(g)])
        return v, 1.0 if self.circuit == 1 else -1.0


_BULATOVIC = ("Bulatovic, R. R., Miodragovic, G. and Boskovic, M. S. (2016), Modified Krill Herd (MKH) algorithm "
              "and its application in dimensional synthesis of a four-bar linkage, Mechanism and Machine Theory 95, "
              "1-21")
_YU = ("Yu, H., Tang, D. and Wang, Z. (2007), Study on a new computer path synthesis method of a four-bar linkage, "
       "Mechanism and Machine Theory 42(4), 383-392")

PROBLEMS: tuple[Published, ...] = (
    Published("mkh1", "eighteen points of Kunjur and Krishnamurty (1997), the linkage of Bulatovic et al. (2016)",
              _BULATOVIC,
              ((0.5, 1.1), (0.4, 1.1), (0.3, 1.1), (0.2, 1.0), (0.1, 0.9), (0.05, 0.75), (0.02, 0.6), (0.0, 0.5),
               (0.0, 0.4), (0.03, 0.3), (0.1, 0.25), (0.15, 0.2), (0.2, 0.3), (0.3, 0.4), (0.4, 0.5), (0.5, 0.7),
               (0.6, 0.9), (0.6, 1.0)),
              100.0, (0.26886, 0.17715, 0.29294, 1.00429, 0.42180, 0.87821, 0.58013, 0.5234, 0.8148), 1),
    Published("yu1", "Yu et al. (2007), first curve: twenty points", _YU,
              ((-27.0, 1.0), (-21.857, -3.214), (-16.7, -7.428), (-11.571, -11.642), (-6.428, -15.857),
               (-1.285, -20.071), (3.857, -24.285), (9.0, -28.5), (15.0, -29.9), (20.0, -30.0), (27.2, -25.0),
               (29.2, -20.0), (28.0, -10.0), (22.7, 2.0), (15.0, 10.6), (5.0, 16.5), (-10.0, 19.6), (-22.0, 17.0),
               (-28.0, 11.0), (-29.0, 5.0)),
              2.0, (-11.55, -20.14, 2.981022362406315, 65.87, 17.43, 25.46, 64.57, 23.47, 2.834414705238791), 1),
    Published("mkh3", "Bulatovic et al. (2016): twenty-five points", _BULATOVIC,
              ((7.03, 5.99), (6.95, 5.45), (6.77, 5.03), (6.4, 4.6), (5.91, 4.03), (5.43, 3.56), (4.93, 2.94),
               (4.67, 2.6), (4.38, 2.2), (4.04, 1.67), (3.76, 1.22), (3.76, 1.97), (3.76, 2.78), (3.76, 3.56),
               (3.76, 4.34), (3.76, 4.91), (3.76, 5.47), (3.8, 5.98), (4.07, 6.4), (4.53, 6.75), (5.07, 6.85),
               (5.05, 6.84), (5.89, 6.83), (6.41, 6.8), (6.92, 6.58)),
              20.0, (-2.31301, 2.86189, -0.61763, 9.99432, 1.93027, 4.57242, 7.36674, 8.0425, 0.1874), 1),
)


def score(v: np.ndarray, branch: float, targets: np.ndarray) -> float:
    """The metric (see the module): the sum of squared distances (mm^2) from ``targets`` (n, 2) mm to the nearest
    points of the whole coupler curve of design ``v`` (9,) on ``branch`` (grid of FINE_GRID crank angles, then
    golden section: :func:`linkgen.synthesis.fourier_path.errors`)."""
    return float(errors(np.asarray(v, dtype=float), branch, targets, True)[0].sum())


def worst_transmission_deg(v: np.ndarray) -> float:
    """The smallest transmission angle (degrees, min(gamma, 180 - gamma)) over a full turn of the crank, exact."""
    _, _, _, r1, r2, r3, r4, _, _ = (float(x) for x in v)
    return math.degrees(float(worst_transmission(r1, r2, r3, r4, 0.0, 2.0 * math.pi)))


def task_of(problem: Published, atlas_folder: str | None = None) -> dict[str, Any]:
    """The synthesis task that poses ``problem`` here: its targets in mm, untimed and closed, a Grashof crank, the
    Fourier method, and a transmission limit no stricter than the paper's linkage keeps (30 degrees, or that
    linkage's worst rounded down to a whole degree where it is lower)."""
    v, _ = problem.design()
    limit = min(30.0, math.floor(worst_transmission_deg(v)))
    task: dict[str, Any] = {"kind": "path", "closed": True, "crank": True, "method": "fourier",
                            "points": problem.targets().tolist(), "min_transmission": limit, "candidates": 1}
    if atlas_folder is not None:
        task["atlas_folder"] = atlas_folder
    return {"name": problem.key, "task": task}


def solve_row(problem: Published, atlas_folder: str | None = None) -> dict[str, Any]:
    """``problem`` solved here and its paper's linkage scored by the same metric: the bench's row (errors mm^2,
    wall and CPU seconds of the whole synthesis, the worst transmission angles in degrees, our best candidate's
    row)."""
    v, branch = problem.design()
    targets = problem.targets()
    raw = task_of(problem, atlas_folder)
    clock, cpu = time.perf_counter(), time.process_time()
    result = synthesize(validate_task(raw))
    seconds, cpu_seconds = time.perf_counter() - clock, time.process_time() - cpu
    best = result.candidates[0].row
    published = score(v, branch, targets)
    return {"problem": problem.title, "key": problem.key, "points": len(targets), "timed": False,
            "scale_mm": problem.scale, "published_error": published, "ours_error": best["error_mm2"],
            "ratio": best["error_mm2"] / published, "ours_seconds": seconds, "cpu_seconds": cpu_seconds,
            "published_transmission_deg": worst_transmission_deg(v),
            "ours_transmission_deg": best["transmission_worst_deg"],
            "min_transmission_deg": raw["task"]["min_transmission"], "method": "fourier",
            "atlas": result.search["atlas"], "candidate": best, "unit": "mm^2 (sum of squared distances to the curve)"}
