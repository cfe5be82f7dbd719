"""The outlines of a counter's Geneva step (:mod:`linkgen.gears.counter`): the tens wheel and the locking disc, exact
lines and arcs (pure numpy).

**The tens wheel**, in its own frame about its axis, +X towards the units wheel's axis at its rest (between two
slots). Slot k's centre line runs at s_k = pi / n + 2 pi k / n; its flanks are lines h either side (h half the
slot's width: the pin's hole over 2), from the rim, a circle of radius R_w = sqrt(b^2 + h^2) (b = C cos(pi / n),
so that a flank ends where the pin's centre enters), down to a half circle of radius h about the point C - a out
(the pin's deepest). Between slots k and k + 1 the rim carries a concave locking arc of radius R_l (the locking
disc's radius plus its clearance) about the point C out on the bisector s_k + pi / n, where the units wheel's axis
stands while the tens wheel dwells; it meets the rim delta either side of the bisector,
cos(delta) = (R_w^2 + C^2 - R_l^2) / (2 R_w C).

**The locking disc**, in the units wheel's frame: a circle of radius r_l about the axis less a cutout, an arc of
radius r_c about the point C out along the pin's direction at mid-transfer (where the tens wheel's axis stands
then in this frame), which lets the tens wheel's tips pass while it turns; it meets the disc's circle eta either
side of that direction, cos(eta) = (r_l^2 + C^2 - r_c^2) / (2 r_l C). r_c is :func:`cutout_radius`: the farthest
from that point any point of the tens wheel comes inside the lock's clearance round the disc's circle, over the
window, plus the clearance.

Contours are counter-clockwise vertices (k, 2) mm and bulges (k,) (tan of a quarter of an arc's turn, positive
counter-clockwise), LWPOLYLINE form.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkgen.gears.counter import Transfer

#: the pin's angles over the window at which the tens wheel is placed to size the cutout
CUTOUT_POSES = 361
#: a wheel's point nearer the axis than the lock's clearance circle by this fraction of C needs the cutout
NEAR = 1e-9
#: points a rim or locking arc is sampled at to size the cutout, a degree of arc (0.001 mm off the arc at 100 mm)
ARC_SAMPLES = 2


def _unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


def _bulge(start: np.ndarray, end: np.ndarray, centre: np.ndarray, ccw: bool) -> float:
    """The bulge of the arc about ``centre`` from ``start`` to ``end``, counter-clockwise or not."""
    a0 = math.atan2(*(start - centre)[::-1])
    a1 = math.atan2(*(end - centre)[::-1])
    sweep = (a1 - a0) % (2 * math.pi) if ccw else -((a0 - a1) % (2 * math.pi))
    return math.tan(sweep / 4)


@dataclass(frozen=True)
class GenevaStep:
    """The step's parts: the ``transfer``, the slot's half-width ``half_width`` h (mm), the locking disc's radius
    ``lock_radius`` r_l (mm) and the lock's ``clearance`` (mm)."""

    transfer: Transfer
    half_width: float
    lock_radius: float
    clearance: float

    @property
    def rim_radius(self) -> float:
        """R_w = sqrt(b^2 + h^2) (mm)."""
        return math.hypot(self.transfer.entry_radius, self.half_width)

    @property
    def arc_radius(self) -> float:
        """R_l = r_l + the clearance (mm)."""
        return self.lock_radius + self.clearance

    @property
    def flank_angle(self) -> float:
        """How far (rad) from a slot's centre line its flank meets the rim: atan(h / b)."""
        return math.atan2(self.half_width, self.transfer.entry_radius)

    @property
    def lock_angle(self) -> float:
        """delta (rad): the locking arc's half-angle on the rim about the wheel's axis; NaN where the arc misses the
        rim."""
        c, r, rl = self.transfer.centre_distance, self.rim_radius, self.arc_radius
        cosine = (r * r + c * c - rl * rl) / (2 * r * c)
        return math.acos(cosine) if -1.0 <= cosine <= 1.0 else math.nan

    @property
    def land(self) -> float:
        """The rim's angle (rad) left between a flank and the locking arc: pi / n - atan(h / b) - delta (> 0 for a
        wheel that can be drawn)."""
        return math.pi / self.transfer.slots - self.flank_angle - self.lock_angle

    def wheel(self) -> tuple[np.ndarray, np.ndarray]:
        """The tens wheel's outline (see the module's notes): for each slot its flank in, its bottom, its flank out,
        the rim, the locking arc and the rim again."""
        t, h = self.transfer, self.half_width
        n, b, d, rw = t.slots, t.entry_radius, t.deepest, self.rim_radius
        points: list[np.ndarray] = []
        bulges: list[float] = []
        origin = np.zeros(2)
        for k in range(n):
            s = math.pi / n + 2 * math.pi * k / n
            u, v = _unit(s), _unit(s + math.pi / 2)
            m = s + math.pi / n
            q = t.centre_distance * _unit(m)
            lock_in, lock_out = rw * _unit(m - self.lock_angle), rw * _unit(m + self.lock_angle)
            nxt = rw * _unit(s + 2 * math.pi / n - self.flank_angle)
            mouth_in, bottom_in, bottom_out, mouth_out = b * u - h * v, d * u - h * v, d * u + h * v, b * u + h * v
            points += [mouth_in, bottom_in, bottom_out, mouth_out, lock_in, lock_out]
            bulges += [0.0, -1.0, 0.0, _bulge(mouth_out, lock_in, origin, True),
                       _bulge(lock_in, lock_out, q, False), _bulge(lock_out, nxt, origin, True)]
        return np.array(points), np.array(bulges)

    def disc(self, cutout: float, direction: float) -> tuple[np.ndarray, np.ndarray]:
        """The locking disc's outline with its cutout of radius ``cutout`` r_c about the point C out at
        ``direction`` (rad, the pin's direction at mid-transfer): its circle from eta past that direction round to
        eta before it (two arcs), then the cutout's concave arc."""
        c, rl = self.transfer.centre_distance, self.lock_radius
        eta = math.acos((rl * rl + c * c - cutout * cutout) / (2 * rl * c))
        q = c * _unit(direction)
        start, half, end = (rl * _unit(direction + a) for a in (eta, math.pi, 2 * math.pi - eta))
        origin = np.zeros(2)
        return (np.array([start, half, end]),
                np.array([_bulge(start, half, origin, True), _bulge(half, end, origin, True),
                          _bulge(end, start, q, False)]))

    def wheel_points(self) -> np.ndarray:
        """Points (k, 2) mm on the tens wheel's outline: its vertices and, along its arcs, :data:`ARC_SAMPLES` a
        degree (what the cutout is sized from)."""
        vertices, bulges = self.wheel()
        out = [vertices]
        for i, bulge in enumerate(bulges):
            if bulge == 0.0:
                continue
            p0, p1 = vertices[i], vertices[(i + 1) % len(vertices)]
            sweep = 4 * math.atan(bulge)
            chord = p1 - p0
            length = math.hypot(*chord)
            radius = length / (2 * abs(math.sin(sweep / 2)))
            mid = (p0 + p1) / 2
            normal = np.array([-chord[1], chord[0]]) / length
            centre = mid + normal * radius * math.cos(sweep / 2) * math.copysign(1.0, sweep)
            a0 = math.atan2(*(p0 - centre)[::-1])
            count = max(2, math.ceil(abs(math.degrees(sweep)) * ARC_SAMPLES))
            angles = a0 + np.linspace(0.0, sweep, count)
            out.append(centre + radius * np.column_stack([np.cos(angles), np.sin(angles)]))
        return np.vstack(out)

    def wheel_in_driver(self, points: np.ndarray, alpha: np.ndarray) -> np.ndarray:
        """The tens wheel's ``points`` (k, 2) in the units wheel's frame, turned so that the pin lies on +X, at the
        pin's angles ``alpha`` (m,) from the centre line: (m, k, 2) mm."""
        alpha = np.asarray(alpha, dtype=float)
        c = self.transfer.centre_distance
        turn = np.pi - self.transfer.in_slot(alpha)
        # the wheel's +X towards the units axis at its dwell before entry, turned clockwise by its step's progress;
        # the frame turned by -alpha so that the pin stays on +X
        spin = turn - alpha
        centre = c * np.stack([np.cos(-alpha), np.sin(-alpha)], axis=-1)
        cs, sn = np.cos(spin), np.sin(spin)
        x = cs[:, None] * points[None, :, 0] - sn[:, None] * points[None, :, 1]
        y = sn[:, None] * points[None, :, 0] + cs[:, None] * points[None, :, 1]
        return np.stack([x, y], axis=-1) + centre[:, None, :]

    def cutout_radius(self) -> float:
        """r_c (mm): over :data:`CUTOUT_POSES` pin angles across the window, the farthest from (C, 0) (the pin on
        +X) that a point of the tens wheel within r_l + clearance of the axis comes, plus the clearance; the wheel's
        rim radius where none comes inside."""
        w = self.transfer.window
        placed = self.wheel_in_driver(self.wheel_points(), np.linspace(-w / 2, w / 2, CUTOUT_POSES))
        # a locking arc lies on the disc's clearance circle at entry and exit: inside it only past rounding
        near = np.hypot(placed[..., 0], placed[..., 1]) < self.arc_radius - NEAR * self.transfer.centre_distance
        far = np.hypot(placed[..., 0] - self.transfer.centre_distance, placed[..., 1])
        return float(np.max(far[near], initial=self.rim_radius - self.clearance)) + self.clearance
