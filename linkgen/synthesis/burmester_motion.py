"""The ``burmester`` task: four-bars whose coupler passes four or five positions of a line.

Four positions: the centre-point and circle-point curves (:mod:`linkgen.synthesis.burmester`) are
sampled at ``samples`` values of their parameter (the dyad link's turn from position 1 to 2); the
dyads the task's region keeps (``centre_region``, ``circle_region``, ``curve_range``) are paired
with each other, either as the crank, and every pair is screened and checked as motion generation's
(:func:`linkgen.synthesis.motion.paired`: Grashof when a crank is asked for, order, branch, and the
worst transmission angle over the motion at least ``min_transmission``, 30 degrees by default),
then ranked by that worst transmission angle. Five positions: the same with the Ball-Burmester
dyads, of which there are at most four. Each candidate's figure draws the curves of positions 1-4.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.spec import MAX_LENGTH_MM
from linkgen.synthesis.burmester import TWO_PI, Dyads, burmester_points, four_position_dyads, poses
from linkgen.synthesis.candidates import Candidate
from linkgen.synthesis.motion import inside, paired

#: samples of the curves' parameter a candidate's figure draws them with
FIGURE_SAMPLES = 1441
#: a step between samples longer than this share of the figure's view is drawn as a gap
JUMP = 0.05


def _in_box(z: np.ndarray, box: Any) -> np.ndarray:
    (x0, y0), (x1, y1) = box
    return (z.real >= x0) & (z.real <= x1) & (z.imag >= y0) & (z.imag <= y1)


def picked(dyads: Dyads, task: Any) -> Dyads:
    """The dyads a template can hold that the task's region keeps; a one-line :class:`SpecError` naming the
    region's field when it keeps fewer than two."""
    keep = np.isfinite(dyads.centre) & np.isfinite(dyads.circle)
    keep &= inside(np.where(keep, dyads.centre, 0), np.where(keep, dyads.circle, 0))
    count = int(np.count_nonzero(keep))
    what = "Ball-Burmester dyads" if dyads.betas.shape[1] == 4 else "sampled dyads of the curves"
    for key in ("centre_region", "circle_region", "curve_range"):
        region = getattr(task, key)
        if region is None:
            continue
        if key == "curve_range":
            degrees = np.degrees(dyads.beta2)
            keep &= (degrees >= region[0]) & (degrees <= region[1])
        else:
            keep &= _in_box(dyads.centre if key == "centre_region" else dyads.circle, region)
        if np.count_nonzero(keep) < 2:
            raise SpecError(f"{np.count_nonzero(keep)} of the {count} {what} within {MAX_LENGTH_MM:g} mm of the "
                            "origin lie in it, and a four-bar pairs two: widen it or leave it out", f"task.{key}")
    if np.count_nonzero(keep) < 2:
        raise SpecError(f"{count} of the {what} lie within {MAX_LENGTH_MM:g} mm of the origin, and a four-bar pairs "
                        "two: move the positions nearer the origin or give other positions", "task.positions")
    return dyads.take(keep)


def curves(p: np.ndarray, alpha: np.ndarray, view: tuple[complex, float]) -> tuple[tuple[str, np.ndarray], ...]:
    """The centre-point and circle-point curves of positions 1-4 as figure paths ((m, 2) mm, NaN between the
    branches, at leaps and outside the square of half-width ``view[1]`` about ``view[0]``)."""
    beta2 = np.linspace(0.0, TWO_PI, FIGURE_SAMPLES)
    d = four_position_dyads(p, alpha, beta2)
    centre, size = view
    out = []
    for label, z in (("centre-point curve (ground pivots)", d.centre),
                     ("circle-point curve (moving pivots at position 1)", d.circle)):
        z = np.where(np.maximum(abs((z - centre).real), abs((z - centre).imag)) <= size, z, np.nan)
        # a gap between the branches, and wherever the curve leaps between samples (it passes far away there)
        cuts = np.flatnonzero(np.abs(np.diff(z)) > JUMP * size) + 1
        z = np.insert(z, np.union1d(cuts, [FIGURE_SAMPLES]), np.nan)
        out.append((label, np.column_stack([z.real, z.imag])))
    return tuple(out)


def _drawn(c: Candidate, p: np.ndarray, alpha: np.ndarray) -> Candidate:
    """The candidate with the curves added to its figure, in a view holding the positions and its pivots."""
    pts = np.concatenate([p, [complex(*xy) for xy in c.row["ground_pivots"] + c.row["moving_pivots"]]])
    lo, hi = complex(pts.real.min(), pts.imag.min()), complex(pts.real.max(), pts.imag.max())
    size = max((hi - lo).real, (hi - lo).imag, 1.0)
    view = ((lo + hi) / 2, size)
    return dataclasses.replace(c, sketch=dataclasses.replace(c.sketch, paths=c.sketch.paths + curves(p, alpha, view)))


def solve(task: Any) -> tuple[list[Candidate], dict[str, Any]]:
    """The four-bars of a validated ``burmester`` task (unranked) and how they were found."""
    p, alpha = poses(np.array(task.positions))
    if len(p) == 4:
        dyads = four_position_dyads(p, alpha, np.linspace(0.0, TWO_PI, task.samples, endpoint=False))
        mode = "the centre-point and circle-point curves, sampled"
    else:
        dyads = burmester_points(p, alpha)
        mode = "the Ball-Burmester points"
        if len(dyads.beta2) < 2:
            raise SpecError(f"these five positions have {len(dyads.beta2)} real Ball-Burmester dyads (the centre-point "
                            "curves of positions 1-4 and 1, 2, 3, 5 meet in fewer than two points), and a four-bar "
                            "pairs two: give four positions, or other positions", "task.positions")
    chosen = picked(dyads, task)
    side = (chosen.centre, chosen.circle, chosen.betas)
    found, tried, bound = paired(p, alpha, [side, side], True, task, mode)
    info: dict[str, Any] = {
        "method": "Burmester theory: the compatibility linkage's loop closed at each curve parameter, the dyad "
                  "form solved by Cramer's rule; pairs screened for Grashof, order and branch defects",
        "free_choices": mode, "dyads": len(dyads.beta2), "dyads_picked": len(chosen.beta2), "pairs_tried": tried,
        "offered": len(found), "bound": bound}
    if len(p) == 5:
        info["burmester_points"] = [{"centre": [float(z.real), float(z.imag)], "circle": [float(c.real), float(c.imag)],
                                     "curve_parameter_deg": math.degrees(float(b))}
                                    for z, c, b in zip(dyads.centre, dyads.circle, dyads.beta2, strict=True)]
    return [_drawn(c, p, alpha) for c in found], info
