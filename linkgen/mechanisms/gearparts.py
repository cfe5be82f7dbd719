"""A gear pair's parts and drawings, and the check that its outlines never overlap as it turns.

Parts (all in the gears' plane on one layer, their pins from the base plate below): an external pair is the base
plate with both pivots, the pinion and the gear; a rack pair the base plate with the pinion's pivot and the guide slot
the rack's two pins run in (its travel), the pinion and the rack; an internal pair the base plate with the ring's
pivot, the ring's web (a disc on that pivot, layer 1), the ring (its toothed rim, layer 2, bolted to the web by three
pins on the rim's mid circle) with the pinion inside it on the same layer, and a top plate above them (layer 3, posts
to the base plate are the kit's) holding the pinion's pivot, which cannot pass the web. Each gear's hole is the
linkage's pin hole (pin + clearance), with an optional printed hub boss and set screw.

Frames: each gear's own frame has its centre at the origin and tooth 0 on +X (:mod:`linkgen.gears.outline`); the
rack's its datum line's middle, teeth up. Placed as :class:`linkgen.gears.pair.GearPair` places them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import DesignError
from camgen.core.parts import Drawing, preview_stroke
from camgen.core.shapes import Circle, Contour, Polyline, rounded_hull
from linkgen.gears.outline import gear_outline, rack_outline, ring_outline
from linkgen.gears.pair import GearPair
from linkgen.gears.tooth import DEDENDUM
from linkgen.mechanisms.shaped import Pieces, ShapedPart
from linkgen.parts import Layout, LinkPart, Placement, Stock

#: the resolution of the overlap check, in modules: the outlines' tolerance and the step of the tips along their path
CHECK_RESOLUTION = 2e-3
#: how many bolts hold an internal gear's ring to its web
RING_BOLTS = 3
#: poses of the parts' sweep over one pitch of the pinion (a kit's bolt heads are kept clear of it)
SWEEP_POSES = 13


@dataclass(frozen=True)
class Outlines:
    """The pair's outlines in their own frames at one tolerance: the pinion, the other member (an external gear, an
    internal gear's toothed hole, a rack), and a rack's length (mm) and teeth."""

    pinion: Pieces
    other: Pieces
    rack_teeth: int = 0


def rack_teeth(pair: GearPair, travel: float) -> int:
    """The teeth (an even number) a rack needs to stay in mesh over ``travel`` mm: the travel and the stretch of its
    tip line inside the pinion's tip circle, and a tooth more at each end."""
    p = pair.pinion_tooth
    inside = p.tip_radius**2 - (pair.centre_distance - pair.module) ** 2
    span = travel + 2 * math.sqrt(max(inside, 0.0))
    teeth = math.ceil(span / (math.pi * pair.module)) + 2
    return teeth + teeth % 2


def outlines(pair: GearPair, tolerance: float, travel: float = 0.0, back: float = 0.0) -> Outlines:
    """Both members' outlines within ``tolerance`` mm (a rack's for ``travel`` mm, on a back ``back`` mm deep below
    its root line, one module if 0)."""
    pinion = gear_outline(pair.pinion_tooth, tolerance)
    gear = pair.gear_tooth
    if pair.kind == "rack":
        teeth = rack_teeth(pair, travel)
        return Outlines(pinion, rack_outline(pair.rack, teeth, pair.rack_thinning, back or pair.module), teeth)
    assert gear is not None
    if pair.kind == "external":
        return Outlines(pinion, gear_outline(gear, tolerance))
    return Outlines(pinion, ring_outline(gear, pair.ring_tip_radius, tolerance))


def _flat(pieces: Pieces, tolerance: float) -> np.ndarray:
    return Contour(*pieces).flatten(tolerance)


def overlap(pair: GearPair, travel: float = 0.0) -> float | None:
    """The first pinion angle (rad) over one pinion pitch from its mesh phase at which a vertex of one member's
    outline (flattened within :data:`CHECK_RESOLUTION` modules) lies inside the other's, the pinion stepping so that
    its tips move that much a step; None where they never do. One pitch is every relative position of the teeth."""
    import shapely

    res = CHECK_RESOLUTION * pair.module
    shapes = outlines(pair, res, travel)
    p_pts, o_pts = _flat(shapes.pinion, res), _flat(shapes.other, res)
    pinion_poly = shapely.Polygon(p_pts)
    if pair.kind == "internal":
        g = pair.gear_tooth
        assert g is not None
        rim = Circle((0.0, 0.0), g.tip_radius + 2 * pair.module).flatten(res)
        other_poly = shapely.Polygon(rim, [o_pts])
    else:
        other_poly = shapely.Polygon(o_pts)
    shapely.prepare(pinion_poly)
    shapely.prepare(other_poly)
    first, _ = pair.mesh_phases
    pitch = 2 * math.pi / pair.pinion_teeth
    steps = math.ceil(pitch * pair.pinion_tooth.tip_radius / res)
    theta = first + pitch * np.arange(steps + 1) / steps
    where = pair.gear_angle(theta)
    reach = pair.pinion_tooth.tip_radius + res
    o_keep, p_keep = _reachable(pair, o_pts, p_pts, other_poly, theta, where, reach, res)
    o_pts, p_pts = o_pts[o_keep], p_pts[p_keep]
    # the steps in blocks, each block's vertices placed and tested at once; the first step of the first block with a
    # vertex inside is the answer, as it was of the loop over the steps one at a time
    block = max(1, min(BLOCK_STEPS, 400_000 // max(1, len(o_pts) + len(p_pts))))
    for lo in range(0, len(theta), block):
        ks = np.arange(lo, min(lo + block, len(theta)))
        turns, centres = _other_poses(pair, where[ks])
        # the other member's vertices in the pinion's frame, and the pinion's in the other's: (steps, vertices, 2)
        o_in_p = _turned(_turned(o_pts[None], turns) + centres[:, None], -theta[ks])
        near = np.hypot(o_in_p[..., 0], o_in_p[..., 1]) <= reach
        p_in_o = _turned(_turned(p_pts[None], theta[ks]) - centres[:, None], -turns)
        hit = shapely.contains_xy(other_poly, p_in_o[..., 0], p_in_o[..., 1]).any(axis=1)
        step, _ = np.nonzero(near)
        hit[step[shapely.contains_xy(pinion_poly, o_in_p[near][:, 0], o_in_p[near][:, 1])]] = True
        if hit.any():
            return float(theta[ks[np.argmax(hit)]])
    return None


#: the most steps of :func:`overlap` tested at once (an overlap found early wastes at most a block)
BLOCK_STEPS = 64


def _turned(points: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """``points`` (k or 1, m, 2) mm each turned counter-clockwise by its own of ``angles`` (k,) rad: (k, m, 2)."""
    c, s = np.cos(angles)[:, None], np.sin(angles)[:, None]
    x, y = points[..., 0], points[..., 1]
    return np.stack([x * c - y * s, x * s + y * c], axis=-1)


def _other_poses(pair: GearPair, positions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The other member's angle (rad) and origin (mm) at each of ``positions`` (k,) (its angle, or a rack's shift):
    angles (k,) and origins (k, 2)."""
    if pair.kind == "rack":
        return np.zeros(len(positions)), np.column_stack([positions, np.full(len(positions), -pair.centre_distance)])
    return np.asarray(positions, float), np.tile([pair.centre_distance, 0.0], (len(positions), 1))


def _in_arc(angle: np.ndarray, lo: Any, hi: Any) -> np.ndarray:
    """Whether each of ``angle`` (rad) lies on the arc from ``lo`` counter-clockwise to ``hi`` (numbers, or arrays
    of ``angle``'s shape: an arc each; all of the circle when that is a turn or more, none when it is empty)."""
    return (hi - lo >= 2 * math.pi) | (np.mod(angle - lo, 2 * math.pi) <= hi - lo)


def _swept(gamma: np.ndarray, centre: float, half: np.ndarray, t0: float, t1: float) -> np.ndarray:
    """Whether a vertex at angle ``gamma`` (rad) turned by some angle from ``t0`` to ``t1`` comes within ``half``
    (rad, each vertex its own; negative: never) of the direction ``centre``."""
    return (half >= 0) & _in_arc(gamma, centre - half - t1, centre + half - t0)


def _half_width(q: np.ndarray) -> np.ndarray:
    """The half-width (rad) of the arc where cos(psi) >= -q about psi = 0 (of cos(phi) <= q about pi): arccos(-q),
    that is pi - arccos(q); pi for q >= 1 or not finite (a vertex at the centre: kept), and -1 (no arc) for
    q < -1."""
    keep = (q >= 1.0) | ~np.isfinite(q)
    return np.where(keep, math.pi, np.where(q < -1.0, -1.0, math.pi - np.arccos(np.clip(q, -1.0, 1.0))))


def _reachable(pair: GearPair, o_pts: np.ndarray, p_pts: np.ndarray, other_poly: Any, theta: np.ndarray,
               where: np.ndarray, reach: float, res: float) -> tuple[np.ndarray, np.ndarray]:
    """Which vertices :func:`overlap` need test, as masks of ``o_pts`` and ``p_pts``: those of the other member that
    come within ``reach`` of the pinion's centre at some step (the pinion at angles ``theta``, the other at
    ``where``), and those of the pinion that come within the other's outline's ring about its centre (its farthest
    vertex; its nearest, less ``res`` for an edge's chord, where the outline does not hold its centre). The others
    can never be inside: leaving them out changes no step's answer, and the steps test a tenth of the vertices or
    fewer. Worked from each vertex's radius and angle over the sweep's range of turns (a rack's of shifts), with
    1e-6 mm and rad to spare."""
    import shapely

    spare = 1e-6
    cd = pair.centre_distance
    o_r = np.hypot(*np.asarray(shapely.get_coordinates(other_poly)).T)
    outer = float(o_r.max()) + spare
    inner = 0.0 if shapely.contains_xy(other_poly, 0.0, 0.0) else float(o_r.min()) - res - spare
    r_p, gamma = np.hypot(p_pts[:, 0], p_pts[:, 1]), np.arctan2(p_pts[:, 1], p_pts[:, 0])
    t0, t1 = float(theta.min()), float(theta.max())
    if pair.kind == "rack":                      # the rack at (shift, -cd): its teeth below the pinion's centre
        lo, hi = float(where.min()), float(where.max())
        ox, oy = o_pts[:, 0], o_pts[:, 1]
        o_keep = (ox + hi >= -reach - spare) & (ox + lo <= reach + spare) & (np.abs(oy - cd) <= reach + spare)
        # the rack's material lies at y <= top - cd (plus res) in the pinion's frame: a pinion vertex at radius r
        # reaches it only where r sin(phi) <= that, an arc about -pi/2
        _, _, _, top = other_poly.bounds
        with np.errstate(divide="ignore", invalid="ignore"):
            q = (top - cd + res + spare) / r_p
        # sin(phi) <= q: cos(phi + pi / 2) >= -q, an arc about -pi / 2
        return o_keep, _swept(gamma, -math.pi / 2, _half_width(q) + spare, t0, t1)
    rho, alpha = np.hypot(o_pts[:, 0], o_pts[:, 1]), np.arctan2(o_pts[:, 1], o_pts[:, 0])
    w0, w1 = float(where.min()), float(where.max())
    o_keep = np.abs(rho - cd) <= reach + spare
    if reach < cd:              # the pinion's disc, seen from the other's centre, within asin(reach / cd) of -x
        beta = math.asin(reach / cd) + spare
        o_keep &= _in_arc(alpha, math.pi - beta - w1, math.pi + beta - w0)
    if pair.kind == "internal":     # inside the ring: at least `inner` from its centre (cd along +x), an arc about pi
        with np.errstate(divide="ignore", invalid="ignore"):
            q = (r_p**2 + cd**2 - inner**2) / (2 * r_p * cd)                 # |w - C| >= inner: cos(phi) <= q
        return o_keep, _swept(gamma, math.pi, _half_width(q) + spare, t0, t1)
    p_keep = np.abs(r_p - cd) <= outer
    if outer < cd:              # the other's disc, seen from the pinion's centre, within asin(outer / cd) of +x
        beta = math.asin(outer / cd) + spare
        p_keep &= _in_arc(gamma, -beta - t1, beta - t0)
    return o_keep, p_keep


def placement(pair: GearPair, theta: np.ndarray, fixed: tuple[str, ...], others: tuple[str, ...],
              extras: dict[str, np.ndarray]) -> Placement:
    """Where the parts sit at pinion angles ``theta`` (rad): the ``fixed`` ones (the ground, a top plate) still, the
    pinion turned, the ``others`` (the other member; an internal gear's ring and its web together) turned or shifted;
    the joints at the pivots, and at the ring's bolts or the rack's pins (``extras``: each such joint's point in the
    other member's frame)."""
    n = len(theta)
    zero, origin = np.zeros(n), np.zeros((n, 2))
    position = pair.gear_angle(theta)
    if pair.kind == "rack":
        turn, centres = zero, np.column_stack([position, np.full(n, -pair.centre_distance)])
    else:
        turn, centres = position, np.tile([pair.centre_distance, 0.0], (n, 1))
    angles = {**{name: zero for name in fixed}, "pinion": theta, **{name: turn for name in others}}
    origins = {**{name: origin for name in fixed}, "pinion": origin, **{name: centres for name in others}}
    c, s = np.cos(turn), np.sin(turn)
    moved = {j: centres + np.column_stack([c * x - s * y, s * x + c * y]) for j, (x, y) in extras.items()}
    joints: dict[str, tuple[tuple[str, str], np.ndarray]] = {"O1": ((fixed[-1], "pinion"), origin)}
    if pair.kind == "rack":
        joints.update({j: (("ground", others[0]), where) for j, where in moved.items()})
    else:
        joints["O2"] = (("ground", others[0]), centres.copy())
        joints.update({j: ((others[0], others[-1]), where) for j, where in moved.items()})
    return Placement(angles, origins, joints)


def ring_rim(root_radius: float, width: float, stock: Stock) -> tuple[dict[str, np.ndarray], Pieces]:
    """An internal gear's rim round its root circle (``root_radius`` mm, its master's tip) and ``width`` mm wide: the
    :data:`RING_BOLTS` bolt points (``B1``, ...) on its mid circle, in the ring's frame, and the rim's (and its web's)
    outer circle; a DesignError naming ``parts.width`` where the rim leaves under 0.5 mm round a bolt hole."""
    if stock.hole / 2 >= width / 2 - 0.5:
        raise DesignError(f"parts.width: the ring's rim ({width:g} mm) leaves under 0.5 mm round its bolt holes "
                          f"({stock.hole:g} mm)")
    bolt = root_radius + width / 2
    extras = {f"B{k + 1}": bolt * np.array([math.cos(a), math.sin(a)])
              for k, a in enumerate(2 * math.pi * np.arange(RING_BOLTS) / RING_BOLTS)}
    disc = rounded_hull(np.zeros((1, 2)), root_radius + width)
    return extras, (disc.vertices, disc.bulges)


def pair_layout(pair: GearPair, stock: Stock, width: float, travel: float,
                hubs: dict[str, tuple[tuple[float, float] | None, float]]) -> Layout:
    """The parts of ``pair`` (see the module's notes) for a stock whose bars are ``width`` mm wide, a rack's
    ``travel`` (mm), and each gear's hub (``hubs[name]``: the boss (diameter, height; mm) or None, and the set
    screw's diameter, mm)."""
    shapes = outlines(pair, stock.tolerance, travel, width)
    half, c = width / 2, pair.centre_distance
    for name, tooth in (("pinion", pair.pinion_tooth), ("gear", pair.gear_tooth)):
        if tooth is not None and not (pair.kind == "internal" and name == "gear") and \
                stock.hole / 2 + 1.0 > tooth.root_radius:
            raise DesignError(f"parts.pin_diameter: the {name}'s hole ({stock.hole:g} mm: pin + clearance) leaves "
                              f"less than 1 mm inside its root circle ({2 * tooth.root_radius:.4g} mm across)")
    pinion = ShapedPart("pinion", np.zeros((1, 2)), half, stock, shape=shapes.pinion, boss=hubs["pinion"][0],
                        set_screw=hubs["pinion"][1])
    extras: dict[str, np.ndarray] = {}
    positions: list[tuple[str, float]] = [("mesh", pair.mesh_phases[0])]
    if pair.kind == "external":
        ground = LinkPart("ground", np.array([[0.0, 0.0], [c, 0.0]]), half, stock, moving=False)
        gear = ShapedPart("gear", np.zeros((1, 2)), half, stock, shape=shapes.other, boss=hubs["gear"][0],
                          set_screw=hubs["gear"][1])
        parts: tuple[LinkPart, ...] = (ground, pinion, gear)
        layers = {"ground": 0, "pinion": 1, "gear": 1}
    elif pair.kind == "rack":
        length = shapes.rack_teeth * math.pi * pair.module
        pin_y = -DEDENDUM * pair.module - half                # the pins on the middle of the rack's back
        spread = length / 4
        extras = {"R1": np.array([-spread, pin_y]), "R2": np.array([spread, pin_y])}
        rack = ShapedPart("rack", np.array(list(extras.values())), half, stock, shape=shapes.other)
        ends = (np.array([-spread - travel / 2, pin_y - c]), np.array([spread + travel / 2, pin_y - c]))
        ground = LinkPart("ground", np.zeros((1, 2)), half, stock, slots=(ends,), moving=False,
                          body=np.array([[0.0, 0.0], ends[0], ends[1]]))
        parts = (ground, pinion, rack)
        layers = {"ground": 0, "pinion": 1, "rack": 1}
        r1 = pair.working_pitch_radii[0]
        positions = [("travel-start", positions[0][1] - travel / (2 * r1)), positions[0],
                     ("travel-end", positions[0][1] + travel / (2 * r1))]
    else:
        g = pair.gear_tooth
        assert g is not None
        extras, circle = ring_rim(g.tip_radius, width, stock)
        bolts = np.array(list(extras.values()))
        web = ShapedPart("ring-web", np.vstack([[0.0, 0.0], bolts]), half, stock, shape=circle,
                         boss=hubs["gear"][0], set_screw=hubs["gear"][1])
        ring = ShapedPart("ring", bolts, half, stock, shape=circle, windows=(shapes.other,))
        ground = LinkPart("ground", np.array([[c, 0.0]]), half, stock, moving=False)
        top = LinkPart("ground-top", np.zeros((1, 2)), half, stock, moving=False, body=np.array([[0.0, 0.0], [c, 0.0]]))
        parts = (ground, top, pinion, web, ring)
        layers = {"ground": 0, "ring-web": 1, "ring": 2, "pinion": 2, "ground-top": 3}
    fixed = tuple(p.name for p in parts if not p.moving)
    others = tuple(p.name for p in parts if p.moving and p.name != "pinion")
    theta = positions[0][1] + 2 * math.pi / pair.pinion_teeth * np.arange(SWEEP_POSES) / (SWEEP_POSES - 1)
    if pair.kind == "rack":
        first, last = positions[0][1], positions[-1][1]
        theta = np.linspace(first, last, SWEEP_POSES)
    sweep = placement(pair, theta, fixed, others, extras)
    poses = tuple(placement(pair, np.array([t]), fixed, others, extras) for _, t in positions)
    return Layout(parts, sweep, tuple(positions), poses, (), layers)


def pair_drawing(pair: GearPair, shapes: Outlines, theta: float) -> Drawing:
    """The pair at pinion angle ``theta`` (rad): both outlines, their base and working pitch circles, and the line of
    action through the pitch point (to its ends on the base circles' tangents)."""
    turns, centres = _other_poses(pair, pair.gear_angle(np.array([theta])))
    turn, centre = float(turns[0]), centres[0]
    items: list = [("pinion", Contour(*shapes.pinion).moved(theta, np.zeros(2)))]
    other = Contour(*shapes.other).moved(turn, centre)
    name = {"external": "gear", "internal": "ring", "rack": "rack"}[pair.kind]
    items.append((name, other))
    p, g = pair.pinion_tooth, pair.gear_tooth
    r1, r2 = pair.working_pitch_radii
    items += [("base circles", Circle((0.0, 0.0), p.base_radius)), ("pitch circles", Circle((0.0, 0.0), r1))]
    if g is not None:
        items += [("base circles", Circle((centre[0], centre[1]), g.base_radius)),
                  ("pitch circles", Circle((centre[0], centre[1]), r2))]
    line = _line_of_action(pair)
    items.append(("line of action", Polyline(line, np.zeros(1))))
    return Drawing(tuple(items), pair.module * CHECK_RESOLUTION * 10, stroke=preview_stroke(items))


def _line_of_action(pair: GearPair) -> np.ndarray:
    """The line of action (2, 2) mm for the pinion driving counter-clockwise: from its tangent point on the other
    member's base circle (a rack's: as far beyond the pitch point as the pinion's is before it) to the pinion's (an
    internal pair's: on through the pitch point, which lies beyond it)."""
    aw = pair.working_pressure_angle
    rb1, c = pair.pinion_tooth.base_radius, pair.centre_distance
    g = pair.gear_tooth
    if pair.kind == "rack":
        t1 = rb1 * np.array([-math.sin(aw), -math.cos(aw)])
        pitch_point = np.array([0.0, -pair.working_pitch_radii[0]])
        return np.array([2 * pitch_point - t1, t1])
    assert g is not None
    if pair.kind == "external":
        t1 = rb1 * np.array([math.cos(aw), -math.sin(aw)])
        return np.array([np.array([c, 0.0]) + g.base_radius * np.array([-math.cos(aw), math.sin(aw)]), t1])
    t2 = np.array([c, 0.0]) + g.base_radius * np.array([-math.cos(aw), math.sin(aw)])
    pitch_point = np.array([-pair.working_pitch_radii[0], 0.0])
    t1 = rb1 * np.array([-math.cos(aw), math.sin(aw)])
    return np.array([t2, 2 * pitch_point - t1])
