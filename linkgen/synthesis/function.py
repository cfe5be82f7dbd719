"""Function generation (Freudenstein): a four-bar whose rocker angle follows y = f(x) while its crank follows x.

x over [x0, xn] maps linearly onto the crank angles ``input_angles`` and y = f(x) over [f(x0),
f(xn)] onto the rocker angles ``output_angles`` (degrees from the ground line O2 -> O4). At the
precision points, at Chebyshev spacing x_j = (x0 + xn)/2 - (xn - x0)/2 cos((2j - 1) pi / 2N),
Freudenstein's equation K1 cos t4 - K2 cos t2 + K3 = cos(t2 - t4) is linear in K1 = d/a, K2 = d/c,
K3 = (a^2 - b^2 + c^2 + d^2) / 2ac (a crank, b coupler, c rocker, d ground, given as the scale):
three points are met exactly, more in the least-squares sense. A negative a (or c) is a crank (or
rocker) pointing the other way: it is made positive and its angles turned by 180 degrees. The
linkage is then analysed as a four-bar: the assembly that meets the precision points, a branch
defect if they lie on different assemblies, the crank's whole range checked for a toggle, and its
worst transmission angle over that range against ``min_transmission`` (30 degrees by default;
the linkage is offered below it as the nearest, with a ``bound`` line naming the limit); the
structural error y_generated - f(x) is measured over the whole range (501 points).
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.spec import MAX_LENGTH_MM, MIN_LENGTH_MM
from linkgen.kinematics.fourbar import ASSEMBLIES, FourBar
from linkgen.synthesis.candidates import Candidate, Sketch, deg, fits_template, fourbar_table
from linkgen.synthesis.defects import defects
from linkgen.synthesis.formula import evaluate
from linkgen.synthesis.geometry import worst_transmission
from linkgen.synthesis.task import MAX_FUNCTION_VALUE

TWO_PI = 2.0 * math.pi
#: points the structural error is measured at
FINE = 501
#: precision points the figure draws the linkage at, at most (spread over them)
POSES = 5


def chebyshev(x0: float, xn: float, n: int) -> np.ndarray:
    """The n Chebyshev precision points of [x0, xn], in increasing order."""
    j = np.arange(1, n + 1)
    return (x0 + xn) / 2.0 - (xn - x0) / 2.0 * np.cos((2 * j - 1) * math.pi / (2 * n))


def freudenstein(t2: np.ndarray, t4: np.ndarray) -> np.ndarray:
    """K1, K2, K3 of Freudenstein's equation through the (crank, rocker) angle pairs (rad): exact for three,
    least squares for more."""
    m = np.column_stack([np.cos(t4), -np.cos(t2), np.ones(len(t2))])
    rhs = np.cos(t2 - t4)
    if len(t2) == 3:
        if abs(np.linalg.det(m)) < 1e-12:
            raise SpecError("the three precision points give a singular system: choose other angles",
                            "task.output_angles")
        return np.linalg.solve(m, rhs)
    return np.linalg.lstsq(m, rhs, rcond=None)[0]


def _function(task: Any) -> tuple[tuple[float, float], Any]:
    """The range of x and y = f(x) (a formula, or the table interpolated linearly)."""
    if task.table is not None:
        tx, ty = np.array(task.table, dtype=float).T
        x0, xn = task.x_range if task.x_range is not None else (tx[0], tx[-1])
        if x0 < tx[0] or xn > tx[-1]:
            raise SpecError(f"must lie within the table's x, [{tx[0]:g}, {tx[-1]:g}]", "task.x_range")
        return (x0, xn), lambda x: np.interp(x, tx, ty)
    return task.x_range, lambda x: evaluate(task.function, np.asarray(x, dtype=float))


def _bounded(y: np.ndarray, task: Any) -> None:
    """Refuse a function whose values over the range leave +-MAX_FUNCTION_VALUE (their differences would
    overflow)."""
    big = np.abs(y) > MAX_FUNCTION_VALUE
    if np.any(big):
        raise SpecError(f"y must stay within +-{MAX_FUNCTION_VALUE:g} over the range (it reaches "
                        f"{float(y[big][0]):.3g})", "task.function" if task.function else "task.table")


def solve(task: Any) -> tuple[list[Candidate], dict[str, Any]]:
    """The four-bar of a validated function task and how it was found."""
    (x0, xn), f = _function(task)
    _bounded(f(np.linspace(x0, xn, FINE)), task)
    y0, yn = (float(v) for v in f(np.array([x0, xn])))
    if y0 == yn:
        raise SpecError(f"y is {y0:g} at both ends of the range, so it cannot be mapped onto the rocker's angles",
                        "task.function" if task.function else "task.table")
    (s2, e2), (s4, e4) = (np.radians(task.input_angles), np.radians(task.output_angles))

    def crank_of(x: np.ndarray) -> np.ndarray:
        return s2 + (x - x0) / (xn - x0) * (e2 - s2)

    def rocker_of(y: np.ndarray) -> np.ndarray:
        return s4 + (y - y0) / (yn - y0) * (e4 - s4)

    xs = chebyshev(x0, xn, task.precision_points)
    t2, t4 = crank_of(xs), rocker_of(f(xs))
    k1, k2, k3 = freudenstein(t2, t4)
    d = task.ground
    if abs(k1) < 1e-12 or abs(k2) < 1e-12:
        raise SpecError("the precision points ask for an infinitely long crank or rocker: choose other angles",
                        "task.output_angles")
    a, c = d / k1, d / k2
    b2 = a * a + c * c + d * d - 2.0 * a * c * k3
    if b2 <= 0:
        raise SpecError(f"the precision points ask for a coupler of imaginary length (b^2 = {b2:.6g} mm^2): choose "
                        "other input_angles or output_angles", "task.output_angles")
    turn2, turn4 = (math.pi if a < 0 else 0.0), (math.pi if c < 0 else 0.0)
    lengths = (float(d), float(abs(a)), float(math.sqrt(b2)), float(abs(c)))
    if not fits_template(lengths):
        shown = ", ".join(f"{v:.4g}" for v in lengths)
        raise SpecError(f"the linkage through the precision points has links of {shown} mm (ground, crank, coupler, "
                        f"rocker); a template holds {MIN_LENGTH_MM:g} to {MAX_LENGTH_MM:g} mm: scale the ground",
                        "task.ground")
    try:
        fb = FourBar(*lengths)
    except SpecError:
        raise SpecError("the precision points ask for links that cannot close a loop: choose other angles",
                        "task.output_angles") from None
    ends = np.concatenate([[s2], t2, [e2]]) + turn2
    if defects(lengths, ends, np.ones(len(ends)), crank=False):
        starts = [(math.degrees(lo - turn2) % 360.0, math.degrees(hi - lo)) for lo, hi in fb.input_ranges() or ()]
        reach = "; ".join(f"{start:.4g} to {start + span:.4g}" for start, span in starts)
        raise SpecError(f"the linkage through the precision points meets a toggle inside the input range: its crank "
                        f"reaches {reach} degrees only: choose other input_angles or output_angles",
                        "task.input_angles")
    # how far each assembly's rocker is from the asked angle at each precision point (rad)
    off = {asm: np.abs(np.remainder(fb.positions(t2 + turn2, asm).theta4 - turn4 - t4 + math.pi, TWO_PI) - math.pi)
           for asm in ASSEMBLIES}
    assembly = min(off, key=lambda asm: float(off[asm].sum()))
    if len(t2) == 3 and off[assembly].max() > 1e-6:
        raise SpecError("the precision points lie on different assemblies of the linkage through them (a branch "
                        "defect): choose other input_angles or output_angles, or more precision points",
                        "task.input_angles")
    worst = math.degrees(float(worst_transmission(*lengths, s2 + turn2, e2 + turn2)))
    bound = [] if worst >= task.min_transmission else [
        f"task.min_transmission: the linkage through the precision points, the only one, lets its transmission angle "
        f"fall to {worst:.3g} degrees over the input range (at least {task.min_transmission:g} asked); it is offered "
        "as the nearest: choose other input_angles or output_angles, or lower min_transmission"]
    x = np.linspace(x0, xn, FINE)
    generated = fb.sweep(crank_of(x) + turn2, assembly).theta4 - turn4
    angle_error = np.remainder(generated - rocker_of(f(x)) + math.pi, TWO_PI) - math.pi
    y_error = angle_error / (e4 - s4) * (yn - y0)
    at = int(np.argmax(np.abs(y_error)))
    row = {"ground_pivots": [[0.0, 0.0], [d, 0.0]], "ground": d, "crank": lengths[1], "coupler": lengths[2],
           "rocker": lengths[3], "coupler_point": [0.0, 0.0], "input_angles": [deg(t) for t in t2 + turn2],
           "output_angles": [deg(t) for t in t4 + turn4], "precision_x": xs.tolist(),
           "precision_y": [float(v) for v in f(xs)], "freudenstein_k": [float(k1), float(k2), float(k3)],
           "crank_turned_deg": math.degrees(turn2), "rocker_turned_deg": math.degrees(turn4), "assembly": assembly,
           "structural_error_max": float(abs(y_error[at])),
           "structural_error_percent": float(100.0 * abs(y_error[at]) / abs(yn - y0)),
           "structural_error_deg": float(np.degrees(np.abs(angle_error).max())),
           "structural_error_at_x": float(x[at]), "transmission_worst_deg": worst}
    poses = fb.positions(t2 + turn2, assembly)
    drawn = np.unique(np.linspace(0, len(xs) - 1, min(len(xs), POSES)).round().astype(int))
    sketch = Sketch(paths=(("rocker pin", fb.sweep(crank_of(x) + turn2, assembly).b),),
                    poses=tuple((f"x = {xs[k]:.4g}", np.array([[0.0, 0.0], poses.a[k], poses.b[k], [d, 0.0]]))
                                for k in drawn),
                    reached=poses.b, error=(x, y_error, xs, "structural error (units of y)"))
    table = fourbar_table(*lengths, assembly=assembly)
    info = {"method": "Freudenstein's equation at Chebyshev precision points: "
                      + ("exact" if task.precision_points == 3 else "least squares"),
            "precision_points": task.precision_points, "bound": bound}
    return [Candidate(table, row, row["structural_error_max"], lengths, sketch)], info
