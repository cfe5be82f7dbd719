"""A linkage's animation: one full cycle of its input, the linkage drawn at each step and its tracers' paths (every
moving joint's when it has none) drawn whole. Pure: returns frames as arrays (:mod:`camgen.core.frames`); the
command writes them (:mod:`camgen.core.writers.animation`).

A crank that turns fully makes one turn from the drawing, frame k at the drawn angle + 2 pi k / n (counter-clockwise);
an input that cannot (a rocker, a slide, a crank limited by a toggle or a ``range``) goes from one end of the range
analysed to the other and back, the frames spaced as a cosine so that it slows to a stop at each end.

A dedicated mechanism that cannot be drawn as a general linkage (a gear pair, a gear train) draws itself: its
mechanism is an :class:`~linkgen.mechanisms.AnimatedMechanism`, found through the mechanisms' registry
(:func:`design_frames`).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.core.frames import bounds, cycle, render
from camgen.core.errors import SpecError
from linkgen.linkage_design import LinkageDesign, pose_of
from linkgen.mechanisms import AnimatedMechanism
from linkgen.mechanisms.general import Analysis


def analysis_for_animation(design: LinkageDesign) -> Analysis:
    """The general-linkage analysis that draws ``design`` (its own, or its mechanism drawn as one); a
    :class:`SpecError` naming ``linkage.type`` or ``linkage.input`` for what cannot be animated."""
    table = design.spec.linkage
    got = pose_of(design.kinematics, table, 0.0)
    if got is None:
        kind = getattr(table, "type", "mechanism")
        raise SpecError(f"linkgen animates linkages it can draw as general ones: type = \"linkage\" and the "
                        f"crank-driven dedicated mechanisms, not this {kind}", "linkage.type")
    a = got[0]
    if len(a.table.inputs) != 1:
        raise SpecError("linkgen animates a linkage of one input", "linkage.input")
    return a


def cycle_inputs(a: Analysis, n: int) -> np.ndarray:
    """The ``n`` input values (rad, or mm for a slide) of one cycle (see the module docstring): the last is one
    step before the first."""
    lo, hi = float(a.span[0, 0]), float(a.span[0, -1])
    full = a.crank and a.ranges is None and a.table.inputs[0].range is None
    return cycle(n, full, lo, hi)


def _traced(a: Analysis) -> tuple[str, ...]:
    s = a.linkage.structure
    return a.table.tracers or tuple(p for p in s.points if p not in s.bodies["ground"])


def frames_at(a: Analysis, values: np.ndarray, size: tuple[int, int],
              box: tuple[float, float, float, float] | None = None) -> np.ndarray:
    """The linkage drawn at each input value of ``values`` (rad, or mm), ``size`` (width, height) pixels: the paths
    of its tracers over the motion analysed, then its links (plates for links of three or more joints), ground
    pivots as triangles. ``box`` (x0, y0, x1, y1 mm) is the region shown (default: every joint over the motion
    analysed and at ``values``). Returns (len(values), height, width, 3) uint8."""
    s = a.linkage.structure
    poses = a.linkage.solve(np.asarray(values, dtype=float)).points
    paths = [np.asarray(a.sweep.points[p]) for p in _traced(a)]
    if box is None:
        box = bounds(*(np.asarray(v) for v in poses.values()), *(np.asarray(v) for v in a.sweep.points.values()))

    def draw(ax: Any, k: int) -> None:
        for j, path in enumerate(paths):
            ax.plot(path[:, 0], path[:, 1], "-", color=f"C{(j + 1) % 10}", lw=1.2, alpha=0.8)
        for i, (body, pts) in enumerate(s.bodies.items()):
            xy = np.array([poses[p][k] for p in pts])
            if body == "ground":
                ax.plot(xy[:, 0], xy[:, 1], "^", color="0.3", ms=9)
                continue
            if len(pts) > 2:
                ax.fill(xy[:, 0], xy[:, 1], color=f"C{i % 10}", alpha=0.25, lw=0)
                xy = np.vstack([xy, xy[:1]])
            ax.plot(xy[:, 0], xy[:, 1], "-o", color=f"C{i % 10}", lw=2.5, ms=4)

    return render(draw, len(values), size, box)


def linkage_frames(a: Analysis, n: int, size: tuple[int, int]) -> np.ndarray:
    """The ``n`` frames of one cycle (:func:`cycle_inputs`), ``size`` pixels: (n, height, width, 3) uint8."""
    return frames_at(a, cycle_inputs(a, n), size)


def design_inputs(design: LinkageDesign, n: int) -> np.ndarray:
    """The ``n`` input values (rad, or mm) of one cycle of ``design``: its mechanism's own
    (:class:`~linkgen.mechanisms.AnimatedMechanism`), or its general linkage's (:func:`cycle_inputs`); the
    :class:`SpecError` of :func:`analysis_for_animation` for what cannot be animated."""
    m = design.mechanism
    if isinstance(m, AnimatedMechanism):
        return np.asarray(m.animation_inputs(design.spec.linkage, design.kinematics, n), dtype=float)
    return cycle_inputs(analysis_for_animation(design), n)


def design_frames_at(design: LinkageDesign, values: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    """``design`` drawn at input values ``values`` (:func:`design_inputs`), ``size`` pixels: (n, height, width, 3)
    uint8, by its mechanism where it draws itself, else as a general linkage (:func:`frames_at`)."""
    m = design.mechanism
    if isinstance(m, AnimatedMechanism):
        return np.asarray(m.animation_frames(design.spec.linkage, design.kinematics, values, size))
    return frames_at(analysis_for_animation(design), values, size)


def design_frames(design: LinkageDesign, n: int, size: tuple[int, int]) -> np.ndarray:
    """The ``n`` frames of one cycle of ``design``, ``size`` pixels: (n, height, width, 3) uint8."""
    return design_frames_at(design, design_inputs(design, n), size)
