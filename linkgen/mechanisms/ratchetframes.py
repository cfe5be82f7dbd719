"""A ratchet's animation (``type = "ratchet"``): the wheel, the holding pawl, the lever and the lever's pawl over one
stroke of the lever, the handle's arc traced.

The input is the stroke's phase u (rad, as of a crank driving the lever): the lever swings out and back as
swing (1 - cos u) / 2. On the way out (u <= pi) its pawl drives the wheel with it; on the way back the wheel, pulled
back by its load, follows the lever until the holding pawl catches it, a whole number of teeth on
(:attr:`~linkgen.mechanisms.ratchet.Ratchet.teeth_per_stroke`), and the lever goes back alone. Each stroke adds that
index: after one stroke the wheel shows the same teeth where they were, so one cycle is one stroke. A pawl that a
tooth passes under is drawn lifted about its pivot just clear of the wheel's outline (the least turn away from the
wheel, found by bisection to :data:`LIFT_TOLERANCE`), as its spring lets it ride over the tooth.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.frames import bounds, cycle, fill, render
from camgen.core.shapes import Contour
from linkgen.mechanisms.ratchet import Ratchet, pawl_shape

#: the lift of a pawl riding over a tooth is found to this (rad)
LIFT_TOLERANCE = 1e-4
#: the outlines are flattened within this share of the teeth's depth (mm)
RESOLUTION = 0.01


def _turned(points: np.ndarray, angle: float, about: np.ndarray | None = None) -> np.ndarray:
    """``points`` (m, 2) turned by ``angle`` (rad, counter-clockwise) about ``about`` (the origin if None)."""
    o = np.zeros(2) if about is None else np.asarray(about, dtype=float)
    c, s = math.cos(angle), math.sin(angle)
    return (np.asarray(points, dtype=float) - o) @ np.array([[c, s], [-s, c]]) + o


def stroke_inputs(n: int) -> np.ndarray:
    """The ``n`` stroke phases (rad) of one cycle, one stroke: 2 pi k / n."""
    return cycle(n, True, 0.0, 0.0)


def lever_wheel(ratchet: Ratchet, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The lever's and the wheel's turns (rad, counter-clockwise from rest) at stroke phases ``values`` (rad; see the
    module docstring)."""
    u = np.asarray(values, dtype=float)
    strokes = np.floor(u / (2 * math.pi) + 1e-12)
    local = u - 2 * math.pi * strokes
    lever = ratchet.swing * (1 - np.cos(local)) / 2
    index = ratchet.teeth_per_stroke * ratchet.wheel.pitch
    wheel = np.where(local <= math.pi, lever, np.maximum(lever, index))
    return lever, wheel + strokes * index


def lift(pawl: np.ndarray, pivot: np.ndarray, wheel: np.ndarray) -> float:
    """The least turn (rad) of the outline ``pawl`` (m, 2) about ``pivot`` away from the wheel's outline ``wheel``
    (k, 2) that clears it (0 where it already does); the sense away is the one that takes the pawl's point nearest
    the axis outwards."""
    import shapely

    teeth = shapely.Polygon(wheel)
    nearest = pawl[int(np.argmin(np.hypot(*pawl.T)))]
    sense = 1.0 if np.hypot(*_turned(nearest[None], 1e-3, pivot)[0]) > np.hypot(*nearest) else -1.0

    def clear(beta: float) -> bool:
        return not shapely.Polygon(_turned(pawl, sense * beta, pivot)).intersects(teeth)

    if clear(0.0):
        return 0.0
    hi = math.radians(2.0)
    while not clear(hi):
        hi *= 2
        if hi > math.pi:
            return sense * math.pi
    lo = 0.0
    while hi - lo > LIFT_TOLERANCE:
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if clear(mid) else (mid, hi)
    return sense * hi


def _rest(ratchet: Ratchet, width: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """At rest (mm): the wheel's outline, the holding pawl's, the lever's pawl's, its pivot and the handle."""
    wheel, pawl = ratchet.wheel, ratchet.pawl
    res = RESOLUTION * wheel.depth
    pawl_xy = Contour(*pawl_shape(ratchet, width, res)).flatten(res)
    turn = ratchet.drive_turn
    drive_pivot = _turned(pawl.pivot[None], turn)[0]
    handle = ratchet.lever_length * drive_pivot / float(np.hypot(*drive_pivot))
    return Contour(*wheel.outline()).flatten(res), pawl_xy, _turned(pawl_xy, turn), drive_pivot, handle


def handle_arc(ratchet: Ratchet, width: float) -> np.ndarray:
    """The handle's path (91, 2) mm over the lever's swing."""
    handle = _rest(ratchet, width)[4]
    return np.array([_turned(handle[None], float(a))[0] for a in np.linspace(0.0, ratchet.swing, 91)])


def view(ratchet: Ratchet, width: float) -> tuple[float, float, float, float]:
    """The region (x0, y0, x1, y1 mm) every frame shows: the wheel, both pawls at rest, the axis and the handle's
    arc, with a margin (:func:`camgen.core.frames.bounds`) for a lifted pawl."""
    wheel_xy, pawl_xy, drive_xy, _, _ = _rest(ratchet, width)
    swung = _turned(drive_xy, ratchet.swing)
    return bounds(wheel_xy, pawl_xy, drive_xy, swung, handle_arc(ratchet, width), np.zeros((1, 2)))


def ratchet_frames(ratchet: Ratchet, width: float, values: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    """The ratchet at stroke phases ``values`` (rad), ``size`` (width, height) pixels, its pawls ``width`` mm wide:
    the handle's arc, the wheel turned, the holding pawl and the lever's pawl each lifted clear of it, the lever from
    the axis over its pawl's pivot to the handle. Returns (n, height, width, 3) uint8."""
    pawl = ratchet.pawl
    wheel_xy, pawl_xy, drive_xy, drive_pivot, handle = _rest(ratchet, width)
    lever, turned = lever_wheel(ratchet, values)
    path = handle_arc(ratchet, width)
    poses = []
    for phi, w in zip(lever, turned, strict=True):
        teeth = _turned(wheel_xy, float(w))
        holding = _turned(pawl_xy, lift(pawl_xy, pawl.pivot, teeth), pawl.pivot)
        on_lever, pivot = _turned(drive_xy, float(phi)), _turned(drive_pivot[None], float(phi))[0]
        driving = _turned(on_lever, lift(on_lever, pivot, teeth), pivot)
        poses.append((teeth, holding, driving, np.array([[0.0, 0.0], pivot, _turned(handle[None], float(phi))[0]])))
    box = view(ratchet, width)

    def draw(ax: Any, k: int) -> None:
        teeth, holding, driving, bar = poses[k]
        ax.plot(path[:, 0], path[:, 1], "-", color="C1", lw=1.2)
        for xy, colour in ((teeth, "C0"), (holding, "C2"), (driving, "C2")):
            fill(ax, xy, color=colour, alpha=0.45, lw=0)
            ring = np.vstack([xy, xy[:1]])
            ax.plot(ring[:, 0], ring[:, 1], "-", color="k", lw=0.6)
        ax.plot(bar[:, 0], bar[:, 1], "-o", color="C4", lw=3.0, ms=4)
        ax.plot([0.0, pawl.pivot[0]], [0.0, pawl.pivot[1]], "^", color="0.3", ms=8)

    return render(draw, len(lever), size, box)
