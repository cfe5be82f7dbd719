"""The assembled drive checked over a whole turn of the driver: the locking disc's and the pin's clearance to the
wheel, the pin's tangential entry, and the lock over the dwell. Lengths in mm, angles in degrees of driver angle.

Everything is measured in the driver's frame, where the locking disc and the pin stand still and the wheel moves
(:meth:`~camgen.kinds.geneva.geometry.GenevaGeometry.in_driver_frame`), at 3600 driver angles over the turn (the
engagement's ends and middle among them), each least gap then refined round its worst angle
(:func:`camgen.numeric.maximise` on its negative). The locking disc's gap is exact to the disc (a circle less a
circular cutout, its signed distance in closed form) from points of the wheel's exact outline, 1e-3 mm apart
in the turn's pass and 1e-5 mm in the refinement, worked only at the points that can hold an angle's least
(:func:`least_disc_gaps`); the pin's is the distance from its centre to the wheel's outline (chords within 1e-5
mm; its nearest edge's, from a tree of the edges: :func:`edge_distances`) less its radius.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

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


def least_disc_gaps(g: GenevaGeometry, ring: np.ndarray, alpha: np.ndarray) -> np.ndarray:
    """The least :func:`disc_gap` (mm) of the wheel's outline points ``ring`` (m, 2, the wheel's frame) at each
    driver angle ``alpha`` (k,), exact wherever it is the least of them all: an array (k,) whose argmin and minimum
    are those of the gaps worked at every point, with every other entry larger than that minimum.

    The disc less its cutout lies inside the disc's circle, so a point's gap is at least r - R (r its distance from
    the driver's axis, R the disc's radius). In each block of 200 angles that bound is worked at every point, the
    gap itself at each angle's point of least bound (the least of those gaps bounds the block's least from above),
    and then only at the points whose bound (less 1e-9 mm for rounding) does not exceed it: about one point in
    twenty (an angle whose every point is out keeps its least bound, larger than the least found)."""
    out = np.empty(len(alpha))
    for k in range(0, len(alpha), 200):
        points = g.in_driver_frame(ring, alpha[k:k + 200])                          # (b, m, 2)
        bound = np.hypot(points[..., 0], points[..., 1]) - g.lock_radius
        rows = np.arange(len(points))
        nearest = disc_gap(g, points[rows, bound.argmin(axis=1)])                  # (b,): a gap at each angle
        pose, point = (bound - 1e-9 <= nearest.min()).nonzero()                    # row by row, in order
        least = bound.min(axis=1)
        found = disc_gap(g, points[pose, point])
        starts = np.flatnonzero(np.r_[True, pose[1:] != pose[:-1]]) if pose.size else pose
        least[pose[starts]] = np.minimum.reduceat(found, starts) if pose.size else least[:0]
        out[k:k + 200] = least
    return out


def edge_tree(ring: np.ndarray) -> Any:
    """A shapely STRtree of the edges of the closed ``ring`` (m, 2; its last point joined to its first), for
    :func:`edge_distances`."""
    import shapely

    closed = np.vstack([ring, ring[:1]])
    return shapely.STRtree(shapely.linestrings(np.stack([closed[:-1], closed[1:]], axis=1)))


def edge_distances(tree: Any, points: np.ndarray) -> np.ndarray:
    """The distance (mm, (n,)) from each shapely point of ``points`` (n,) to the ring of :func:`edge_tree` ``tree``:
    its nearest edge's, which is shapely's distance to the whole ring (worked edge by edge, the same numbers) found
    from the tree in about a fifth of the time at 3 600 points against 13 500 edges."""
    (which, _), distance = tree.query_nearest(points, return_distance=True, all_matches=False)
    out = np.empty(len(points))
    out[which] = distance
    return out


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
    edges = edge_tree(rings[True])
    body = shapely.Polygon(rings[True])
    shapely.prepare(body)

    def lock_gap(a: np.ndarray, fine: bool) -> np.ndarray:
        return least_disc_gaps(g, rings[fine], a)

    def pin_gap(a: np.ndarray, fine: bool) -> np.ndarray:
        # the pin's centre in the wheel's frame: turn the driver's frame back into the wheel's
        turn = -(math.pi - g.law.motion(a)[0] - a)
        x, y = g.crank_radius - g.centre_distance * np.cos(-a), -g.centre_distance * np.sin(-a)
        centres = shapely.points(np.cos(turn) * x - np.sin(turn) * y, np.sin(turn) * x + np.cos(turn) * y)
        gap = edge_distances(edges, centres) - g.pin_diameter / 2
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
