"""The assembled drive checked over a whole turn of the driver: the locking disc's and the pin's clearance to the
wheel, the pin's tangential entry, and the lock over the dwell. Lengths in mm, angles in degrees of driver angle.

Everything is measured in the driver's frame, where the locking disc and the pin stand still and the wheel moves
(:meth:`~camgen.kinds.geneva.geometry.GenevaGeometry.in_driver_frame`), at 3600 driver angles over the turn (the
engagement's ends and middle among them), each least gap then refined round its worst angle
(:func:`camgen.numeric.maximise` on its negative). The locking disc's gap is exact to the disc (a circle less a
circular cutout, its signed distance in closed form) from points of the wheel's exact outline, 1e-3 mm apart
in the turn's pass and 1e-5 mm in the refinement; the pin's is shapely's distance from its centre to the wheel's
outline (chords within 1e-5 mm) less its radius.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from camgen.kinds.geneva.geometry import GenevaGeometry, cosine_rule
from camgen.numeric import maximise

#: driver angles over a turn
_POSES = 3600
#: chord tolerances (mm) of the wheel's outline: the turn's pass, and the refinement round the worst angle
_COARSE, _FINE = 1e-3, 1e-5


@dataclass(frozen=True)
class AssemblyCheck:
    """The clearances of the assembled drive over a turn (mm, at driver angles in degrees), and its entry.

    ``lock_clearance_min_mm``: the least gap between the locking disc and the wheel (the lock clearance by
    design: exact while they are concentric in the dwell; negative: they overlap). ``pin_clearance_min_mm``: the
    least gap between the pin and the wheel (half the slot clearance by design, in the slot). ``entry_angle_deg``:
    between the crank and the slot's centre line where the pin enters (90: tangential entry), and
    ``slot_offset_mm`` the distance of a slot's centre line from the wheel's axis (0: radial slots), both from the
    wheel's outline. ``lock_overlap_deg``: how far the locking disc still covers a locking arc at the dwell's ends
    (positive: the wheel is held over the whole dwell).
    """

    lock_clearance_min_mm: float
    lock_clearance_at_deg: float
    pin_clearance_min_mm: float
    pin_clearance_at_deg: float
    entry_angle_deg: float
    slot_offset_mm: float
    lock_overlap_deg: float


def disc_gap(g: GenevaGeometry, points: np.ndarray) -> np.ndarray:
    """Signed distance (mm) of ``points`` (..., 2), in the driver's frame, from the locking disc: a circle of radius
    R about the origin less the cutout's circle of radius R_c about (C, 0); negative inside the disc."""
    c, disc, cut = g.centre_distance, g.lock_radius, g.cutout_radius
    eta, zeta = cosine_rule(disc, c, cut), cosine_rule(c, cut, disc)
    x, y = points[..., 0], points[..., 1]
    r, q = np.hypot(x, y), np.hypot(x - c, y)
    corner = np.hypot(np.abs(y) - disc * math.sin(eta), x - disc * math.cos(eta))   # nearer of the two corners
    rim = np.where(np.abs(np.arctan2(y, x)) >= eta, np.abs(r - disc), corner)
    cutout = np.where(np.abs(np.arctan2(y, x - c)) >= math.pi - zeta, np.abs(q - cut), corner)
    gap = np.minimum(rim, cutout)
    return np.where((r <= disc) & (q >= cut), -gap, gap)


def _least(gap: Callable[[np.ndarray, bool], np.ndarray], alpha: np.ndarray) -> tuple[float, float]:
    """The least of ``gap(alpha, fine)`` over a turn: coarse on the grid ``alpha``, then fine between the worst's
    neighbours."""
    values = gap(alpha, False)
    i = int(np.argmin(values))
    lo, hi = alpha[max(i - 1, 0)], alpha[min(i + 1, len(alpha) - 1)]
    at, value = maximise(lambda a: -gap(a, True), lo, hi, n=33, rounds=4)
    return -value, math.degrees(at)


def check_assembly(g: GenevaGeometry) -> AssemblyCheck:
    """The assembly checks of the drive ``g`` describes (see :class:`AssemblyCheck`)."""
    import shapely

    e = g.law.engagement
    alpha = np.unique(np.concatenate([np.linspace(-math.pi, math.pi, _POSES + 1)[1:], [-e, 0.0, e]]))
    outline = g.wheel()
    rings = {False: outline.flatten(_COARSE), True: outline.flatten(_FINE)}
    edge = shapely.LinearRing(rings[True])
    body = shapely.Polygon(rings[True])
    shapely.prepare(edge)

    def lock_gap(a: np.ndarray, fine: bool) -> np.ndarray:
        return np.concatenate([disc_gap(g, g.in_driver_frame(rings[fine], a[k:k + 200])).min(axis=1)
                               for k in range(0, len(a), 200)])

    def pin_gap(a: np.ndarray, fine: bool) -> np.ndarray:
        # the pin's centre in the wheel's frame: turn the driver's frame back into the wheel's
        turn = -(math.pi - g.law.motion(a)[0] - a)
        x, y = g.crank_radius - g.centre_distance * np.cos(-a), -g.centre_distance * np.sin(-a)
        centres = shapely.points(np.cos(turn) * x - np.sin(turn) * y, np.sin(turn) * x + np.cos(turn) * y)
        gap = shapely.distance(edge, centres) - g.pin_diameter / 2
        return np.where(shapely.contains(body, centres), -gap - g.pin_diameter, gap)

    lock = _least(lock_gap, alpha)
    pin = _least(pin_gap, alpha)
    # slot 0's centre line from the outline (its flanks' ends: vertices 0 and 3 at the rim, 1 and 2 at the bottom)
    v = outline.vertices
    mouth, bottom = (v[0] + v[3]) / 2, (v[1] + v[2]) / 2
    axis = (mouth - bottom) / np.linalg.norm(mouth - bottom)
    offset = abs(float(bottom[0] * axis[1] - bottom[1] * axis[0]))
    # at entry (driver angle -e) the crank points along -e; the slot's direction is turned by pi - beta = pi + pi/n
    slot = math.pi - float(g.law.motion(np.array([-e]))[0, 0]) + math.atan2(axis[1], axis[0])
    entry = math.degrees(abs(math.remainder(slot - (-e), math.pi)))
    return AssemblyCheck(lock[0], lock[1], pin[0], pin[1], entry, offset, math.degrees(g.lock_overlap))
