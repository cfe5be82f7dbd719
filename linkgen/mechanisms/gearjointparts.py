"""The gears and racks of a general linkage as parts, and their layers in the stack.

Each gear of a pair is a part of its own (its outline :func:`linkgen.mechanisms.gearparts.outlines`'s, within the
stock's tolerance), on the pivot pin at its centre, turning with its link (fixed to it: glued, or by a second pin
through both); a rack is a part fixed to its slider's sliding link, long enough for the travel either way of the
drawing. Meshing members share a layer: the links are stacked first (:func:`linkgen.parts.layer_order`), then each
group of meshing gears and racks gets a layer of its own above them, so nothing else sweeps through its plane; a part
of a layer between a gear's and its link's that crosses the gear's pin is refused (``parts.width``). An internal
gear's ring is not made as a part (its web and bolts are the gear-pair type's): analysed, not cut.

Phases: at the drawing each pair has a tooth of one member and a space of the other centred on the line of centres
(:attr:`linkgen.gears.pair.GearPair.mesh_phases`), and each part then turns with its link.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from camgen.core.errors import DesignError
from linkgen.gears.outline import rack_outline
from linkgen.gears.pair import GearPair
from linkgen.gears.tooth import DEDENDUM
from linkgen.kinematics.structure import GROUND
from linkgen.mechanisms.gearparts import outlines, rack_teeth
from linkgen.mechanisms.general import Analysis, _frame, _turned
from linkgen.mechanisms.shaped import ShapedPart
from linkgen.parts import COLLISION_TOLERANCE_MM, Layout, LinkPart, Placement, Stock, layer_order, with_top_plate

if TYPE_CHECKING:
    from linkgen.spec import PartsTable


@dataclass(frozen=True)
class Member:
    """A gear or rack part: its body, where its frame sits in the drawing (origin, mm; angle, rad), the joint at its
    centre (a gear's; None for a rack) and the pairs it meshes in."""

    part: ShapedPart
    body: str
    origin: np.ndarray
    angle: float
    centre: str | None
    pairs: tuple[str, ...]


Key = tuple[str, str, int]


def members(a: Analysis, table: PartsTable) -> tuple[Member, ...]:
    """The gear and rack parts of the linkage, one gear however many pairs it meshes in."""
    s, stock = a.linkage.structure, Stock.of(table)
    half = table.width / 2
    out: dict[Key, Member] = {}

    def gear(key: Key, pair: GearPair, shape: tuple[np.ndarray, np.ndarray], origin: np.ndarray, angle: float,
             name: str) -> Member:
        if key in out:
            out[key] = replace(out[key], pairs=(*out[key].pairs, name))
            return out[key]
        _hole_fits(pair, key[2], stock, name)
        count = sum(1 for m in out.values() if m.body == key[0])
        part = ShapedPart(f"{key[0]}-gear{count + 1 if count else ''}", np.zeros((1, 2)), half, stock, shape=shape,
                          moving=key[0] != GROUND)
        out[key] = Member(part, key[0], origin, angle, key[1], (name,))
        return out[key]

    for name, t in a.table.gears.items():
        if t.kind == "internal":
            raise DesignError(f"parts: gear pair {name} has an internal gear, whose ring (its web and bolts) only type "
                              "= \"gear-pair\" makes; analyse this linkage without [parts], or make the pair external")
        pair = t.pair
        shapes = outlines(pair, stock.tolerance)
        ca, cb = (np.asarray(s.points[c], dtype=float) for c in (t.a.centre, t.b.centre))
        line = math.atan2(cb[1] - ca[1], cb[0] - ca[0])
        first, second = pair.mesh_phases
        gear((t.a.link, t.a.centre, t.a.teeth), pair, shapes.pinion, ca, line + first, name)
        gear((t.b.link, t.b.centre, t.b.teeth), pair, shapes.other, cb, line + second, name)
    racks = []
    for name, r in a.table.racks.items():
        pair = r.pair
        rack = next(x for x in s.racks if x.name == name)
        sl = s.slider_by_name[rack.slider]
        u = np.array([math.cos(sl.angle), math.sin(sl.angle)])
        up = np.array([-u[1], u[0]]) * math.copysign(1.0, rack.lead)
        along = math.atan2(-up[0], up[1])               # the rack's +X: the pinion's left (its teeth up) seen along it
        centre = np.asarray(s.points[rack.centre], dtype=float)
        first, _ = pair.mesh_phases
        pinion = gear((r.pinion.link, r.pinion.centre, r.pinion.teeth), pair,
                      outlines(pair, stock.tolerance).pinion, centre, along + first, name)
        # a pinion drawn at another phase (by a gear pair) shifts the rack by as much as it rolls
        shift = abs(rack.lead) * (pinion.angle - along - first)
        origin = centre - abs(rack.lead) * up + shift * np.array([math.cos(along), math.sin(along)])
        racks.append(_rack(a, name, pair, stock, half, origin, along, abs(shift)))
    return (*out.values(), *racks)


def _hole_fits(pair: GearPair, teeth: int, stock: Stock, pair_name: str) -> None:
    root = pair.module * (teeth / 2 - 1.25)
    if stock.hole / 2 + 1.0 > root:
        raise DesignError(f"parts.pin_diameter: the hole ({stock.hole:g} mm: pin + clearance) of the {teeth}-tooth "
                          f"gear of pair {pair_name} leaves less than 1 mm inside its root circle ({2 * root:.4g} mm "
                          "across)")


def _rack(a: Analysis, name: str, pair: GearPair, stock: Stock, half: float, origin: np.ndarray, angle: float,
          shift: float) -> Member:
    """A rack's part, its datum line's middle at ``origin`` in the drawing (``shift`` mm from the pitch point) along
    ``angle``, long enough for the slider's travel either way over the motion; two holes on its back fix it to the
    slider's link."""
    s = a.linkage.structure
    sl = s.slider_by_name[next(x.slider for x in s.racks if x.name == name)]
    u = np.array([math.cos(sl.angle), math.sin(sl.angle)])
    sweep = a.travel
    first = s.bodies[sl.guide][0]
    drawn = np.asarray(s.points[first]) + _turned(sweep.points[sl.point] - sweep.points[first],
                                                  -sweep.angles[sl.guide])
    along = (drawn - np.asarray(s.points[sl.point])) @ u              # the travel relative to the guide
    teeth = rack_teeth(pair, 2 * (float(np.max(np.abs(along), initial=0.0)) + shift) + math.pi * pair.module)
    shape = rack_outline(pair.rack, teeth, pair.rack_thinning, 2 * half)
    pin_y = -DEDENDUM * pair.module - half
    spread = teeth * math.pi * pair.module / 4
    part = ShapedPart(f"{name}-rack", np.array([[-spread, pin_y], [spread, pin_y]]), half, stock, shape=shape)
    return Member(part, sl.body, origin, angle, None, (name,))


def _placed(a: Analysis, place: Placement, m: Member) -> tuple[np.ndarray, np.ndarray]:
    """A member's angles (rad) and origins (mm) over a placement, from its body's part's."""
    if m.body == GROUND:
        n = len(next(iter(place.angles.values())))
        return np.full(n, m.angle), np.tile(m.origin, (n, 1))
    p0, beta = _frame(a, m.body)
    phi = place.angles[m.body] - beta
    c, sn = np.cos(phi), np.sin(phi)
    d = m.origin - p0
    origin = place.origins[m.body] + np.column_stack([c * d[0] - sn * d[1], sn * d[0] + c * d[1]])
    return m.angle + phi, origin


def _extended(a: Analysis, place: Placement, ms: tuple[Member, ...]) -> Placement:
    angles, origins, joints = dict(place.angles), dict(place.origins), dict(place.joints)
    for m in ms:
        angles[m.part.name], origins[m.part.name] = _placed(a, place, m)
        if m.centre is not None:
            joints[f"{m.centre}-{m.part.name}"] = ((m.body, m.part.name), origins[m.part.name])
    return Placement(angles, origins, joints)


def _groups(ms: tuple[Member, ...]) -> list[list[Member]]:
    """The members that mesh together, directly or through others (a gear in two pairs joins them)."""
    groups: list[list[Member]] = []
    for m in ms:
        joined = [g for g in groups if any(set(m.pairs) & set(other.pairs) for other in g)]
        merged = [x for g in joined for x in g] + [m]
        groups = [g for g in groups if g not in joined] + [merged]
    return groups


def with_gears(a: Analysis, table: PartsTable, layout: Layout) -> Layout:
    """The layout with the gears and racks added, each group of meshing ones on a layer of its own: above the links,
    else below them (see the module's notes); a DesignError naming ``parts.width`` where a pin crosses a part
    either way."""
    ms = members(a, table)
    order, top = layer_order(layout.parts, layout.sweep, table.pin_diameter / 2)
    layout, order = with_top_plate(layout, order, top, table.width_of("ground"))
    plate = order.pop("ground-top", None)
    groups = _groups(ms)
    parts = (*layout.parts, *(m.part for m in ms))
    sweep = _extended(a, layout.sweep, ms)
    crossing = ""
    for below in (False, True):
        stack = {name: layer + (len(groups) if below and layer > 0 else 0) for name, layer in order.items()}
        base = 0 if below else max(order.values())
        for k, group in enumerate(groups):
            stack.update({m.part.name: base + k + 1 for m in group})
        if plate is not None:
            stack["ground-top"] = max(stack.values()) + 1
        crossing = _crossing(sweep, parts, stack, table.pin_diameter / 2)
        if not crossing:
            return replace(layout, parts=parts, sweep=sweep, poses=tuple(_extended(a, p, ms) for p in layout.poses),
                           layers=stack)
    raise DesignError(f"parts.width: with the gears above the links or below them, {crossing}; narrow the parts or "
                      "move the gears' centres")


def _crossing(sweep: Placement, parts: tuple[LinkPart, ...], order: dict[str, int], pin_radius: float) -> str:
    """The first pin that a moving part on a layer between its two parts' sweeps over (said in words), or ''. A part
    on the pin's own axis (a gear on its link's pivot) is threaded by it, not crossed."""
    import shapely

    by_name = {p.name: p for p in parts}
    n = len(next(iter(sweep.angles.values())))
    shapes: dict[str, np.ndarray] = {}

    def swept(name: str) -> np.ndarray:
        """The moving part's outline at every angle of the sweep (polygons), made when a pin first needs it."""
        if name not in shapes:
            p, angles, origins = by_name[name], sweep.angles[name], sweep.origins[name]
            shapes[name] = np.array([shapely.Polygon(p.outline().moved(angles[k], origins[k])
                                                     .flatten(COLLISION_TOLERANCE_MM)) for k in range(n)])
        return shapes[name]

    moving = {p.name for p in parts if p.moving}
    for joint, ((first, second), where) in sweep.joints.items():
        low, high = sorted((order[first], order[second]))
        between = [name for name, layer in order.items() if low < layer < high and name in moving]
        if not between:
            continue
        threaded = {name for (x, y), other in sweep.joints.values() if other.shape == where.shape
                    and np.allclose(other, where, rtol=0, atol=1e-9) for name in (x, y)}
        pins = shapely.buffer(shapely.points(where), pin_radius)
        for name in between:
            if name not in threaded and shapely.intersects(swept(name), pins).any():
                return (f"{by_name[name].name} (layer {order[name]}) sweeps over the pin {joint} between {first} "
                        f"(layer {order[first]}) and {second} (layer {order[second]})")
    return ""
