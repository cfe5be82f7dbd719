"""A gear train's parts (:mod:`linkgen.mechanisms.geartrain`), with their motion over one turn of the input.

* **Simple**: the base plate with every gear's pivot (layer 0) and the gears, all in one plane (layer 1).
* **Compound**: stage k's pair on layer k + 1; the two gears of a shared shaft on neighbouring layers, bolted
  together by two pins halfway between the pin hole and the smaller one's root circle. Each shaft's pin rises from
  the base plate: refused where a gear of a lower stage reaches over it.
* **Planetary**: the base plate with the central pivot (layer 0); the ring's web (a disc on the central pivot,
  layer 1) bolted by three pins to the ring (its toothed rim, layer 2); the sun and the planets in the ring's plane
  (layer 2); the carrier (layer 3): a plate on the central pivot holding each planet's pin. A fixed member simply
  does not turn.

Gears' own frames: centre at the origin, tooth 0 on +X (:mod:`linkgen.gears.outline`).
"""
from __future__ import annotations

import math

import numpy as np

from camgen.core.errors import DesignError
from linkgen.mechanisms.geartrain import Gear, Train, _outline
from linkgen.mechanisms.gearparts import ring_rim
from linkgen.mechanisms.shaped import ShapedPart
from linkgen.parts import SWEEP, Layout, LinkPart, Placement, Stock


def _local(points: dict[str, np.ndarray], angle: np.ndarray, origin: np.ndarray) -> dict[str, np.ndarray]:
    """Points given in a part's frame placed at each pose (n, 2)."""
    c, s = np.cos(angle), np.sin(angle)
    return {j: origin + np.column_stack([c * x - s * y, s * x + c * y]) for j, (x, y) in points.items()}


def _gear_part(g: Gear, stock: Stock, half: float, holes: np.ndarray | None = None) -> ShapedPart:
    if not g.internal and stock.hole / 2 + 1.0 > g.tooth.root_radius:
        raise DesignError(f"parts.pin_diameter: {g.name}'s hole ({stock.hole:g} mm: pin + clearance) leaves less than "
                          f"1 mm inside its root circle ({2 * g.tooth.root_radius:.4g} mm across)")
    return ShapedPart(g.name, np.zeros((1, 2)) if holes is None else holes, half, stock,
                      shape=_outline(g, stock.tolerance))


def _bolts(small: Gear, stock: Stock, count: int = 2) -> dict[str, np.ndarray]:
    """Bolt points (in the gear's frame) joining two gears of one shaft: halfway between the hole and the smaller
    one's root circle; a DesignError where they do not fit."""
    hole = stock.hole / 2
    radius = (hole + small.tooth.root_radius) / 2
    if radius - hole < 2 * hole + 0.5 or small.tooth.root_radius - radius < hole + 0.5:
        raise DesignError(f"parts.pin_diameter: the bolts joining {small.name} to its shaft's other gear do not fit "
                          f"inside its root circle ({2 * small.tooth.root_radius:.4g} mm across) with "
                          f"{stock.hole:g} mm holes")
    return {f"{small.name}-bolt{k + 1}": radius * np.array([math.cos(a), math.sin(a)])
            for k, a in enumerate(2 * math.pi * np.arange(count) / count + math.pi / 2)}


def _fixed_axes(train: Train, stock: Stock, width: float, theta: np.ndarray,
                layers: dict[str, int]) -> tuple[tuple[LinkPart, ...], Placement]:
    half = width / 2
    gears = train.gears
    turned, centres = train.poses(theta)
    n = len(theta)
    shafts: list[list[Gear]] = []
    for g in gears:
        if shafts and shafts[-1][-1].shaft == g.name:
            shafts[-1].append(g)
        else:
            shafts.append([g])
    bolts: dict[str, dict[str, np.ndarray]] = {}
    holes: dict[str, np.ndarray] = {g.name: np.zeros((1, 2)) for g in gears}
    joints: dict[str, tuple[tuple[str, str], np.ndarray]] = {}
    for k, shaft in enumerate(shafts):
        first = shaft[0]
        joints[f"O{k + 1}"] = (("ground", first.name), centres[first.name])
        if len(shaft) == 2:
            small = min(shaft, key=lambda g: g.tooth.root_radius)
            points = _bolts(small, stock)
            for g in shaft:
                holes[g.name] = np.vstack([[0.0, 0.0], *points.values()])
            bolts[first.name] = points
            for j, where in _local(points, turned[first.name], centres[first.name]).items():
                joints[j] = ((shaft[0].name, shaft[1].name), where)
    parts: list[LinkPart] = [LinkPart("ground", np.array([g.centre for g in (s[0] for s in shafts)]), half, stock,
                                      moving=False)]
    parts += [_gear_part(g, stock, half, holes[g.name]) for g in gears]
    # a shaft's pin rises from the base plate through every layer below its lowest gear: no gear may reach over it
    for k, shaft in enumerate(shafts):
        top = min(layers[g.name] for g in shaft)
        for g in gears:
            if 0 < layers[g.name] < top and math.dist(g.centre, shaft[0].centre) < g.tooth.tip_radius + stock.hole:
                raise DesignError(f"linkage.stages: {g.name} reaches over shaft {k + 1}'s pin, which rises from the "
                                  "base plate past it: give that stage larger gears or the next one smaller")
    placement = Placement({"ground": np.zeros(n), **{g.name: turned[g.name] for g in gears}},
                          {"ground": np.zeros((n, 2)), **{g.name: centres[g.name] for g in gears}}, joints)
    return tuple(parts), placement


def _planetary(train: Train, stock: Stock, width: float,
               theta: np.ndarray) -> tuple[tuple[LinkPart, ...], Placement]:
    half = width / 2
    gears = {g.name: g for g in train.gears}
    ring, sun = gears["ring"], gears["sun"]
    planets = [g for g in train.gears if g.carrier]
    turned, centres = train.poses(theta)
    n = len(theta)
    extras, circle = ring_rim(ring.tooth.tip_radius, width, stock)
    bolts = np.array(list(extras.values()))
    planet_centres = np.array([p.centre for p in planets])
    parts: tuple[LinkPart, ...] = (
        LinkPart("ground", np.zeros((1, 2)), half, stock, moving=False),
        ShapedPart("ring-web", np.vstack([[0.0, 0.0], bolts]), half, stock, shape=circle),
        ShapedPart("ring", bolts, half, stock, shape=circle, windows=(_outline(ring, stock.tolerance),)),
        _gear_part(sun, stock, half), *(_gear_part(p, stock, half) for p in planets),
        LinkPart("carrier", np.vstack([[0.0, 0.0], planet_centres]), half, stock,
                 body=np.vstack([[0.0, 0.0], planet_centres]) if len(planets) > 1 else None))
    zero = np.zeros((n, 2))
    joints: dict[str, tuple[tuple[str, str], np.ndarray]] = {
        "O": (("ground", "sun"), zero), "O#ring": (("ground", "ring-web"), zero),
        "O#carrier": (("ground", "carrier"), zero)}
    joints.update({p.name: (("carrier", p.name), centres[p.name]) for p in planets})
    joints.update({j: (("ring-web", "ring"), w) for j, w in _local(extras, turned["ring"], zero).items()})
    names = ["sun", "ring", *(p.name for p in planets)]
    angles = {"ground": np.zeros(n), "ring-web": turned["ring"], "carrier": turned["carrier"],
              **{name: turned[name] for name in names}}
    origins = {"ground": zero, "ring-web": zero, "carrier": zero, **{name: centres[name] for name in names}}
    return parts, Placement(angles, origins, joints)


def train_layout(train: Train, stock: Stock, width: float) -> Layout:
    """The train's parts (see the module's notes) over one turn of the input, drawn at input angle 0."""
    kind = train.table.kind
    theta = np.linspace(0.0, 2 * math.pi, SWEEP)
    if kind == "planetary":
        layers = {"ground": 0, "ring-web": 1, "ring": 2, "sun": 2, "carrier": 3,
                  **{g.name: 2 for g in train.gears if g.carrier}}

        def place(t: np.ndarray) -> tuple[tuple[LinkPart, ...], Placement]:
            return _planetary(train, stock, width, t)
    else:
        layers = {"ground": 0}
        for k, g in enumerate(train.gears):
            layers[g.name] = 1 if kind == "simple" else k // 2 + 1

        def place(t: np.ndarray) -> tuple[tuple[LinkPart, ...], Placement]:
            return _fixed_axes(train, stock, width, t, layers)
    parts, sweep = place(theta)
    positions = (("mesh", 0.0),)
    poses = (place(np.zeros(1))[1],)
    return Layout(parts, sweep, positions, poses, (), layers)
