"""A page's mechanism as the frames of an animation: the :class:`~camgen.core.page.Scene` a kind's page shows (its
bodies posed frame by frame, its movers), drawn with matplotlib at ``n`` of the page's frames evenly over its cycle,
the path of every circle it moves (a roller's centre, a Geneva drive's pin) traced whole. Pure: returns the frames
(:func:`camgen.core.frames.render`); the command writes them (:mod:`camgen.core.writers.animation`).

A page draws its cycle at :data:`~camgen.core.page.FRAMES` (360) frames, one a degree of its input from its first
frame; frame k of an animation of ``n`` frames is the page's frame k * 360 / n, so ``n`` divides 360 (a refusal on
``--frames`` otherwise): the animation shows exactly what the page does, no pose interpolated.
"""
from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.frames import render
from camgen.core.page import Mover, Page, Scene

#: how each outline style of a page is drawn: (fill colour or None, line colour, line width, line style)
STYLES: dict[str, tuple[str | None, str, float, str]] = {
    "part": ("0.85", "k", 1.2, "-"), "wheel": ("0.85", "k", 1.2, "-"), "island": ("0.85", "k", 1.2, "-"),
    "lock": ("0.75", "k", 1.0, "-"), "crank": ("0.7", "k", 1.0, "-"), "groove": ("white", "k", 1.0, "-"),
    "hole": ("white", "k", 0.8, "-"), "second": ("0.7", "k", 1.0, "-"), "pitch": (None, "C0", 0.8, "--"),
    "path": (None, "C1", 1.0, "-"),
    "ground": (None, "0.3", 1.5, "-"), "guide": (None, "0.5", 0.8, "-"),
}
#: how a style the table does not name is drawn (a follower's pieces, links)
OTHER = (None, "C2", 2.0, "-")
#: the colour a traced path is drawn in, and a roller's or pin's circle
TRACE, CIRCLE = "C1", "C2"


def frame_indices(total: int, n: int, what: str) -> np.ndarray:
    """The page frames (of ``total``) an animation of ``n`` frames shows: k * total / n for k = 0 .. n - 1; a
    :class:`SpecError` naming ``--frames`` (``what`` the kind's title) where ``n`` does not divide ``total``."""
    if n < 1 or total % n:
        divisors = ", ".join(str(d) for d in range(2, total + 1) if total % d == 0)
        raise SpecError(f"{what}'s animation shows its page's {total} frames: give one of {divisors} (got {n})",
                        "--frames")
    return np.arange(n) * (total // n)


def _pose(points: np.ndarray, motion: np.ndarray | None, frame: int) -> np.ndarray:
    """``points`` (k, 2; mm) in a body's frame placed at its pose of ``frame`` (turned about its origin, moved)."""
    if motion is None:
        return points
    turn, dx, dy = motion[frame]
    c, s = np.cos(np.radians(turn)), np.sin(np.radians(turn))
    return np.column_stack([c * points[:, 0] - s * points[:, 1] + dx, s * points[:, 0] + c * points[:, 1] + dy])


def scene_frames(page: Page, n: int, size: tuple[int, int], what: str) -> np.ndarray:
    """``page``'s scene at ``n`` frames evenly over its cycle (:func:`frame_indices`; ``what`` names the kind in a
    refusal), ``size`` (width, height) pixels, the view the page's (:meth:`~camgen.core.page.Scene.bounds`).
    Returns (n, height, width, 3) uint8. The traced paths are one line (a NaN between each two), and so is each
    run of the movers' circles: one path to draw instead of one a point (the same colour and width, so the same
    picture; where two of them cross, the edge's antialiasing rounds differently)."""
    scene: Scene = page.scene
    index = frame_indices(len(page.inputs), n, what)
    ring = np.linspace(0.0, 2 * np.pi, 73)
    disc = np.column_stack([np.cos(ring), np.sin(ring)])
    traces = [m.points[:, j] for m in scene.movers if m.radius > 0 for j in range(m.points.shape[1])]

    #: what moves: (its points at a page frame, None where it has no pose; its fill or None; its line)
    moving: list[tuple[Callable[[int], np.ndarray | None], Any, Any]] = []

    def build(ax: Any) -> None:
        """Every artist of the scene, each moving one listed in ``moving`` (placed by :func:`_place`)."""
        for body in scene.bodies:
            for o in body.outlines:
                fill, colour, width, line = STYLES.get(o.style, OTHER)
                at = partial(_outline_at, np.asarray(o.points, dtype=float), body.motion, o.closed)
                p = at(0)
                patch = ax.fill(p[:, 0], p[:, 1], color=fill, lw=0)[0] if fill is not None else None
                (drawn,) = ax.plot(p[:, 0], p[:, 1], line, color=colour, lw=width)
                if body.motion is not None:
                    moving.append((at, patch, drawn))
        if traces:                                  # one line of every trace (NaN between): one path to draw
            joined = _joined(traces)
            ax.plot(joined[:, 0], joined[:, 1], "-", color=TRACE, lw=0.8)
        for group in _runs(scene.movers):
            if group[0].radius > 0:                 # a run of circles, one line of them all (NaN between)
                circles = [partial(_circle_at, m, j, disc) for m in group for j in range(m.points.shape[1])]
                moving.append((partial(_circles_at, tuple(circles)), None, ax.plot([], [], color=CIRCLE, lw=1.5)[0]))
            else:
                (m,) = group
                _, colour, width, line = STYLES.get(m.style, OTHER)
                moving.append((partial(_path_at, m), None, ax.plot([], [], line, color=colour, lw=width)[0]))

    def draw(ax: Any, k: int) -> None:
        if k == 0:
            build(ax)
        frame = int(index[k])
        for at, patch, line in moving:
            _place(at(frame), patch, line)

    return render(draw, n, size, scene.bounds(), clear=False)


def _outline_at(points: np.ndarray, motion: np.ndarray | None, closed: bool, frame: int) -> np.ndarray:
    """A body's outline ``points`` (k, 2; mm) at its pose of ``frame``, its first point repeated if ``closed``."""
    p = _pose(points, motion, frame)
    return np.vstack([p, p[:1]]) if closed else p


def _circle_at(mover: Mover, j: int, disc: np.ndarray, frame: int) -> np.ndarray | None:
    """The circle (``disc``: unit circle's points) of ``mover``'s point ``j`` at ``frame`` (mm); None without a
    pose there."""
    centre = mover.points[frame, j]
    return centre + mover.radius * disc if np.isfinite(centre).all() else None


def _runs(movers: tuple[Mover, ...]) -> list[list[Mover]]:
    """``movers`` in order, each run of those drawn as circles (a radius) in one group, each other alone."""
    out: list[list[Mover]] = []
    for m in movers:
        if m.radius > 0 and out and out[-1][0].radius > 0:
            out[-1].append(m)
        else:
            out.append([m])
    return out


def _joined(lines: list[np.ndarray]) -> np.ndarray:
    """Polylines (each (k, 2) mm) as one, a row of NaN between each two (matplotlib draws it as one path of as
    many pieces)."""
    gap = np.full((1, 2), np.nan)
    return np.concatenate([part for line in lines for part in (gap, line)][1:])


def _circles_at(circles: tuple[Callable[[int], np.ndarray | None], ...], frame: int) -> np.ndarray | None:
    """The circles ``circles`` give at ``frame`` as one polyline (:func:`_joined`), those without a pose left out;
    None where none has one."""
    shown = [c for c in (at(frame) for at in circles) if c is not None]
    return _joined(shown) if shown else None


def _path_at(mover: Mover, frame: int) -> np.ndarray:
    """``mover``'s polyline at ``frame`` (mm), its first point repeated if it is closed."""
    pts = mover.points[frame]
    return np.vstack([pts, pts[:1]]) if mover.closed else pts


def _place(p: np.ndarray | None, patch: Any, line: Any) -> None:
    """A moving artist's fill (if any) and line set to the points ``p`` (k, 2; mm); hidden for None."""
    line.set_visible(p is not None)
    if p is None:
        return
    if patch is not None:
        patch.set_xy(p)
    line.set_data(p[:, 0], p[:, 1])
