"""Linkage parts: bars, plates and blocks with pin holes, their layers, and their poses over the motion.

Every part is the rounded hull of its hole centres: straight edges offset by the
half-width and exact arcs round each centre, so a two-hole bar has its holes exactly
one link length apart. Parts are defined in their own frame (first hole at the origin,
second on +X) and placed by a rigid motion, which keeps arcs exact.

Allowances (documented in the README): a cut hole is pin + clearance - kerf in
diameter and a cut outline grows by kerf / 2; a printed hole is pin + clearance.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from camgen.core.errors import DesignError, SpecError
from camgen.core.parts import Part
from camgen.core.shapes import Circle, Contour, rounded_hull
from linkgen.fourbar import FourBar
from linkgen.slidercrank import SliderCrank


#: chord tolerance (mm) of the outlines checked for collisions between moving parts
COLLISION_TOLERANCE_MM = 0.05


@dataclass(frozen=True)
class PartsSpec:
    """Dimensions (mm) shared by all parts, with per-link width overrides."""

    width: float
    thickness: float
    pin_diameter: float
    clearance: float = 0.0
    kerf: float = 0.0
    widths: tuple[tuple[str, float], ...] = ()

    def width_of(self, link: str) -> float:
        return dict(self.widths).get(link, self.width)


@dataclass(frozen=True)
class LinkPart:
    """A part in its own frame: hole centres (k, 2) mm, outline half-width, extra holes (slots), kind."""

    name: str
    centres: np.ndarray
    half_width: float
    slot: tuple[np.ndarray, np.ndarray] | None = None     # a guide slot's two end centres, in the part's frame
    moving: bool = True
    body: np.ndarray | None = None                        # points the outline rounds, if not the hole centres

    def outline(self, grow: float = 0.0) -> Contour:
        return rounded_hull(self.centres if self.body is None else self.body, self.half_width + grow)

    def part(self, spec: PartsSpec, cut: bool, tolerance: float) -> Part:
        """The part as cut (kerf applied) or as printed (clearance only)."""
        kerf = spec.kerf if cut else 0.0
        hole = (spec.pin_diameter + spec.clearance - kerf) / 2
        holes: list = [Circle(tuple(c), hole) for c in self.centres]
        if self.slot is not None:
            holes.append(rounded_hull(np.array(self.slot), hole))
        return Part(self.name, self.outline(kerf / 2), tuple(holes), spec.thickness, tolerance)


def fourbar_parts(fb: FourBar, spec: PartsSpec) -> tuple[LinkPart, ...]:
    """Ground plate, crank, coupler (a plate when it carries a coupler point) and rocker."""
    half = {k: spec.width_of(k) / 2 for k in ("ground", "crank", "coupler", "rocker")}
    coupler = [[0.0, 0.0], [fb.coupler, 0.0]]
    if fb.point_distance > 0:
        coupler.append([fb.point_distance * math.cos(fb.point_angle), fb.point_distance * math.sin(fb.point_angle)])
    return (LinkPart("ground", np.array([[0.0, 0.0], [fb.ground, 0.0]]), 2 * half["ground"], moving=False),
            LinkPart("crank", np.array([[0.0, 0.0], [fb.crank, 0.0]]), half["crank"]),
            LinkPart("coupler", np.array(coupler), half["coupler"]),
            LinkPart("rocker", np.array([[0.0, 0.0], [fb.rocker, 0.0]]), half["rocker"]))


def slidercrank_parts(sc: SliderCrank, spec: PartsSpec) -> tuple[LinkPart, ...]:
    """Base plate (crank pivot and a guide slot along the slider's travel), crank, rod and slider block."""
    dead = sc.dead_centres()
    if len(dead) != 2:
        raise SpecError("parts need a crank that turns fully (rod >= crank + |offset|)", "linkage.rod")
    x_top, x_bottom = dead[0][2], dead[1][2]
    w = spec.width_of("crank") / 2
    ends = (np.array([x_bottom, sc.offset]), np.array([x_top, sc.offset]))
    base = LinkPart("ground", np.array([[0.0, 0.0], ends[0], ends[1]]), 2 * w, slot=ends, moving=False)
    block = spec.width_of("slider")
    return (base, LinkPart("crank", np.array([[0.0, 0.0], [sc.crank, 0.0]]), w),
            LinkPart("rod", np.array([[0.0, 0.0], [sc.rod, 0.0]]), spec.width_of("rod") / 2),
            LinkPart("slider", np.array([[0.0, 0.0]]), block / 2, body=np.array([[-block, 0.0], [block, 0.0]])))


@dataclass(frozen=True)
class Placement:
    """Where each moving part sits at each pose: angle (rad) and the position of its first hole (mm)."""

    angles: dict[str, np.ndarray]
    origins: dict[str, np.ndarray]
    joints: dict[str, tuple[tuple[str, str], np.ndarray]]   # joint name -> (the two parts it joins, positions)


def fourbar_placement(fb: FourBar, theta2: np.ndarray, assembly: str) -> Placement:
    p = fb.sweep(theta2, assembly)
    o4 = np.tile([fb.ground, 0.0], (len(theta2), 1))
    return Placement(
        angles={"ground": np.zeros(len(theta2)), "crank": p.theta2, "coupler": p.theta3, "rocker": p.theta4},
        origins={"ground": np.zeros((len(theta2), 2)), "crank": np.zeros((len(theta2), 2)), "coupler": p.a,
                 "rocker": o4},
        joints={"O2": (("ground", "crank"), np.zeros((len(theta2), 2))), "A": (("crank", "coupler"), p.a),
                "B": (("coupler", "rocker"), p.b), "O4": (("ground", "rocker"), o4)})


def slidercrank_placement(sc: SliderCrank, theta: np.ndarray) -> Placement:
    m = sc.motion(theta, 1.0)
    a = np.column_stack([sc.crank * np.cos(theta), sc.crank * np.sin(theta)])
    b = np.column_stack([m.x, np.full_like(m.x, sc.offset)])
    zero = np.zeros(len(theta))
    return Placement(
        angles={"ground": zero, "crank": theta, "rod": m.rod, "slider": zero},
        origins={"ground": np.zeros((len(theta), 2)), "crank": np.zeros((len(theta), 2)), "rod": a, "slider": b},
        joints={"O": (("ground", "crank"), np.zeros((len(theta), 2))), "A": (("crank", "rod"), a),
                "B": (("rod", "slider"), b)})


def layer_order(parts: tuple[LinkPart, ...], placement: Placement, pin_radius: float) -> dict[str, int]:
    """Layers (0 = the ground plate, then upwards) so that no two moving parts on one layer ever overlap,
    parts joined by a pin are on different layers, and no part crosses a pin passing through its layer.

    Tries every assignment of the moving parts to layers 1..n, fewest layers first, over all poses.
    """
    import shapely

    moving = [p for p in parts if p.moving]
    n = len(placement.angles["crank"])
    shapes = {p.name: [shapely.Polygon(p.outline().moved(placement.angles[p.name][k], placement.origins[p.name][k])
                                       .flatten(COLLISION_TOLERANCE_MM)) for k in range(n)]
              for p in moving}
    joined = {frozenset(names) for names, _ in placement.joints.values()}
    clash = {}
    for a, b in itertools.combinations(moving, 2):
        clash[frozenset((a.name, b.name))] = frozenset((a.name, b.name)) in joined or any(
            shapes[a.name][k].intersects(shapes[b.name][k]) for k in range(n))
    for top in range(1, len(moving) + 1):
        for layers in itertools.product(range(1, top + 1), repeat=len(moving)):
            order = {"ground": 0, **{p.name: layer for p, layer in zip(moving, layers, strict=True)}}
            if any(order[a] == order[b] and clash[frozenset((a, b))] for a, b in
                   itertools.combinations([p.name for p in moving], 2)):
                continue
            if _pins_clear(order, shapes, placement, pin_radius):
                return order
    raise DesignError("no layer order keeps the moving parts and pins clear of each other; narrow the parts")


def _pins_clear(order: dict[str, int], shapes: dict, placement: Placement, pin_radius: float) -> bool:
    """No part crosses a pin that passes through its layer (a pin spans the layers of the parts it joins)."""
    import shapely

    for (first, second), where in placement.joints.values():
        low, high = sorted((order[first], order[second]))
        for name, poses in shapes.items():
            if name in (first, second) or not low < order[name] < high:
                continue
            if any(poses[k].intersects(shapely.Point(where[k]).buffer(pin_radius)) for k in range(len(where))):
                return False
    return True


def check_spec(spec: PartsSpec) -> None:
    for name, value in (("parts.width", spec.width), ("parts.thickness", spec.thickness),
                        ("parts.pin_diameter", spec.pin_diameter)):
        if not (value > 0 and math.isfinite(value)):
            raise SpecError(f"must be a finite length > 0 mm (got {value})", name)
    if spec.pin_diameter + spec.clearance - spec.kerf >= spec.width:
        raise SpecError(f"holes of {spec.pin_diameter + spec.clearance - spec.kerf:g} mm leave no material in bars "
                        f"{spec.width:g} mm wide", "parts.pin_diameter")
