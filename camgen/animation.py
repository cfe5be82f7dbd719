"""A disc cam's animation: one full turn of the cam with its follower riding it. Pure: returns frames as arrays
(:mod:`camgen.core.frames`); the command writes them (:mod:`camgen.core.writers.animation`).

Frame k shows the cam turned by theta_k = 2 pi k / n in its sense of rotation (``cam.rotation``) from its drawing at
theta = 0 (the fixed frame is the cam's frame turned by sense * theta, sense = +1 counter-clockwise), its pitch curve
turning with it (dashed), and the follower where the cam puts it: a roller or knife edge on its axis, a flat face
level, an arm on its pivot. The path traced is the follower's pitch point (roller centre or contact) in the fixed
frame over the turn, drawn whole.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.frames import bounds, cycle, render
from camgen.core.errors import SpecError
from camgen.flat import FlatCamDesign
from camgen.followers.base import rotate


def disc_design(design: Any) -> FlatCamDesign:
    """``design`` if it is a disc cam's (a flat cam turning on its shaft); a :class:`SpecError` naming ``cam.kind``
    otherwise (plate, barrel, grooved, conjugate cams and Geneva drives are not animated)."""
    if not isinstance(design, FlatCamDesign) or design.cam.is_plate:
        kind = getattr(getattr(design.spec, "cam", None), "kind", None) or type(design).__name__
        raise SpecError(f"camgen animates disc cams (a flat cam turning on its shaft), not {kind}", "cam.kind")
    return design


def cam_angles(n: int) -> np.ndarray:
    """The ``n`` cam angles (rad) of one turn, 2 pi k / n: the last one step before the first."""
    return cycle(n, True, 0.0, 0.0)


def frames_at(design: FlatCamDesign, theta: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    """The cam at each angle of ``theta`` (rad, the cam's turn in its sense of rotation) with its follower,
    ``size`` (width, height) pixels; the region shown holds the cam, the follower and its path over a whole turn.
    Returns (len(theta), height, width, 3) uint8."""
    cam = design.cam
    f = cam.follower
    sense = 1.0 if design.spec.cam.rotation == "ccw" else -1.0
    theta = np.asarray(theta, dtype=float)
    ring = design.outline.contour.flatten(design.tolerance)
    ring = np.vstack([ring, ring[:1]])
    turn = np.linspace(0.0, 2 * math.pi, 721)
    pitch = cam.pitch(turn).point
    path = rotate(pitch, sense * turn)                    # the pitch point in the fixed frame over a turn
    at = rotate(cam.pitch(theta).point, sense * theta)    # ... at each frame
    rr = cam.contact_radius
    pivot = np.asarray(f.pivot, dtype=float) if hasattr(f, "pivot") else None
    reach = float(np.max(np.linalg.norm(ring, axis=1)))
    top = float(path[:, 1].max()) + max(2 * rr, 0.3 * reach)
    lo, hi = float(path[:, 0].min()) - 0.2 * reach, float(path[:, 0].max()) + 0.2 * reach
    disc = np.column_stack([np.cos(turn), np.sin(turn)])
    extra = [np.array([[lo, top], [hi, top]])] + ([pivot[None, :]] if pivot is not None else [])
    box = bounds(np.array([[-reach, -reach], [reach, reach]]), path, *extra)

    def draw(ax: Any, k: int) -> None:
        a = np.full(len(ring), sense * theta[k])
        shape = rotate(ring, a)
        ax.fill(shape[:, 0], shape[:, 1], color="0.85", lw=0)
        ax.plot(shape[:, 0], shape[:, 1], color="k", lw=1.2)
        p = rotate(pitch, np.full(len(pitch), sense * theta[k]))
        ax.plot(p[:, 0], p[:, 1], "--", color="C0", lw=0.8)
        ax.plot(path[:, 0], path[:, 1], "-", color="C1", lw=1.2)
        ax.plot([0.0], [0.0], "+", color="k", ms=8)
        c = at[k]
        style = {"color": "C2", "lw": 2.5}
        if pivot is not None:
            end = pivot + 1.2 * (c - pivot) if f.flat else c
            ax.plot([pivot[0], end[0]], [pivot[1], end[1]], **style)
            ax.plot(*pivot, "^", color="0.3", ms=9)
        elif f.flat:
            ax.plot([lo, hi], [c[1], c[1]], **style)
            ax.plot([0.0, 0.0], [c[1], top], **style)
        else:
            ax.plot([c[0], c[0]], [c[1], top], **style)
        if rr > 0:
            ax.plot(c[0] + rr * disc[:, 0], c[1] + rr * disc[:, 1], color="C2", lw=1.5)

    return render(draw, len(theta), size, box)


def cam_frames(design: FlatCamDesign, n: int, size: tuple[int, int]) -> np.ndarray:
    """The ``n`` frames of one turn (:func:`cam_angles`), ``size`` pixels: (n, height, width, 3) uint8."""
    return frames_at(design, cam_angles(n), size)
