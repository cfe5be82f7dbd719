"""Whole outlines: an external gear, an internal gear's toothed hole, a rack, as exact arcs and lines.

Every outline is a closed counter-clockwise contour in LWPOLYLINE form (vertices (n, 2) mm, bulges (n,), see
:mod:`linkgen.gears.offset`) in the part's own frame. A gear's centre is its origin with tooth 0 centred on +X; its
tip and root circles are exact arcs, its flanks and root trochoids biarcs within the tolerance
(:mod:`linkgen.gears.fit`). A rack's datum line is y = 0 with its teeth pointing to +Y and a tooth space centred on
x = 0; it is all lines and exact fillet arcs.
"""
from __future__ import annotations

import math

import numpy as np

from camgen.core.errors import DesignError
from linkgen.gears.fit import fit_arcs
from linkgen.gears.involute import roll_of
from linkgen.gears.tooth import ADDENDUM, DEDENDUM, BasicRack, ExternalTooth


def _turned(points: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s], [-s, c]])


def _ring_of_teeth(side: tuple[np.ndarray, np.ndarray], teeth: int) -> tuple[np.ndarray, np.ndarray]:
    """The outline of ``teeth`` teeth whose right side (clockwise of tooth 0, from its foot on the circle between
    teeth up to its tip corner on the tip circle) is ``side`` (vertices, bulges; the last vertex the tip corner):
    the side, the tip arc to its mirror image, the mirrored side down, the arc along the circle between teeth to the
    next tooth, round the whole gear."""
    v, b = side
    foot, corner = v[0], v[-1]
    tip_half = -math.atan2(corner[1], corner[0])
    foot_half = -math.atan2(foot[1], foot[0])
    gap = 2 * math.pi / teeth - 2 * foot_half
    if not tip_half > 0:
        raise DesignError("the teeth come to a point inside the tip circle")
    if not gap > 0:
        raise DesignError("the teeth's roots run into each other")
    mirrored = v[::-1] * np.array([1.0, -1.0])
    block_v = np.vstack([v, mirrored])
    block_b = np.concatenate([b[:-1], [math.tan(tip_half / 2)], b[-2::-1], [math.tan(gap / 4)]])
    pitch = 2 * math.pi / teeth
    vertices = np.vstack([_turned(block_v, k * pitch) for k in range(teeth)])
    return vertices, np.tile(block_b, teeth)


def gear_outline(tooth: ExternalTooth, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """The outline of an external gear: root trochoids, involute flanks and tip arcs of all its teeth, the root
    circle's arcs between them; flanks and roots within ``tolerance`` mm."""
    tooth.check()
    return _ring_of_teeth(tooth.side(tolerance), tooth.teeth)


def ring_outline(master: ExternalTooth, tip_radius: float, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """The toothed hole of an internal gear whose tooth spaces are the teeth of ``master`` (an external gear whose tip
    circle is the ring's root circle) and whose tips lie on ``tip_radius`` (mm, inside the ring's root circle and
    outside its base circle): the master's involutes from that circle up to its tips, the master's tip arcs (the
    ring's roots, sharp corners) and the arcs of ``tip_radius`` between (the ring's tips); counter-clockwise."""
    if not master.base_radius < tip_radius < master.tip_radius:
        raise DesignError("the internal gear's tip circle must lie between its base circle and its root circle")
    if master.tip_thickness <= 0:
        raise DesignError("the internal gear's tooth spaces close before its root circle")
    chain = fit_arcs(master.flank, float(roll_of(tip_radius, master.base_radius)), master.tip_roll, tolerance)
    corner, _ = master.flank(np.array([master.tip_roll]))
    side = (np.vstack([chain[0], corner]), np.concatenate([chain[1], [0.0]]))
    return _ring_of_teeth(side, master.teeth)


def _rack_tooth(rack: BasicRack, thinning: float) -> tuple[np.ndarray, np.ndarray]:
    """One pitch of a rack's top edge from the middle of a space (x = 0) to the next (x = p), left to right: the
    root line, the fillet, the flank up to the tip line, the tip, the other flank and fillet down: vertices (k, 2) mm
    (the last, at x = p, left out) and bulges (k,) in the order travelled."""
    m, a, rho = rack.module, rack.pressure_angle, rack.fillet_radius
    p = math.pi * m
    half = math.pi * m / 4 - thinning / 2             # half the tooth's thickness on the datum line
    root, top = -DEDENDUM * m, ADDENDUM * m
    yc = root + rho
    xc = p / 2 - half + yc * math.tan(a) - rho / math.cos(a)
    if not xc > 0:
        raise DesignError("the rack's root fillets run into each other")
    foot = np.array([xc + rho * math.cos(a), yc - rho * math.sin(a)])
    tip = np.array([p / 2 - half + top * math.tan(a), top])
    if not tip[0] < p / 2:
        raise DesignError("the rack's teeth come to a point below their tip line")
    turn = math.pi / 2 - a                             # the fillet turns from along the root line to up the flank
    left = np.array([[0.0, root], [xc, root], foot, tip])
    right = (np.array([p, 0.0]) + left[::-1] * np.array([-1.0, 1.0]))[:-1]
    vertices = np.vstack([left, right])
    bulges = np.array([0.0, math.tan(turn / 4), 0.0, 0.0, 0.0, math.tan(turn / 4), 0.0])
    return vertices, bulges


def rack_outline(rack: BasicRack, teeth: int, thinning: float, back: float) -> tuple[np.ndarray, np.ndarray]:
    """The outline of a rack of ``teeth`` (even) teeth of ``rack``'s profile, each ``thinning`` mm thinner than
    pi m / 2 on the datum line, on a bar ``back`` mm deep below the root line: the teeth from x = -teeth p / 2 to
    teeth p / 2 (a space centred on x = 0 and one at each end), counter-clockwise."""
    v, b = _rack_tooth(rack, thinning)
    p = math.pi * rack.module
    start = -teeth * p / 2
    top_v = np.vstack([v + np.array([start + k * p, 0.0]) for k in range(teeth)] + [[[-start, v[0, 1]]]])
    top_b = np.tile(b, teeth)
    bottom = v[0, 1] - back
    # counter-clockwise: along the bottom to the right, up the right end, the top from right to left, down the left
    top_v, top_b = top_v[::-1], -top_b[::-1]
    vertices = np.vstack([[[start, bottom], [-start, bottom]], top_v])
    bulges = np.concatenate([[0.0, 0.0], top_b, [0.0]])
    return vertices, bulges
