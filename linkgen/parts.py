"""Linkage parts for any mechanism: bars, plates and blocks with pin holes, their layers, a cut sheet and the
assembly drawn at the dead centres. No I/O.

Every part is the rounded hull of its hole centres: straight edges offset by the
half-width and exact arcs round each centre, so a two-hole bar has its holes exactly
one link length apart. Parts are defined in their own frame (first hole at the origin,
second on +X) and placed by a rigid motion (turned counter-clockwise by an angle in
radians about their first hole, which then moves to its position in mm), which keeps
arcs exact.

A mechanism gives its parts and their motion as a :class:`Layout`; :func:`build_parts`
does the rest; the cut sheets are nested by :mod:`camgen.core.nesting`. Allowances
(:class:`camgen.core.parts.Allowances`, applied there only): a part's nominal hole is
pin + clearance in diameter; a cut hole is that less the kerf and a cut outline grows
by kerf / 2; a printed hole is the nominal one.
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from camgen.core.errors import DesignError
from camgen.core.nesting import Nest, SheetRules, nest
from camgen.core.parts import Allowances, Drawing, Part, preview_stroke
from camgen.core.shapes import Circle, Contour, Polyline, rounded_hull

if TYPE_CHECKING:
    from linkgen.spec import PartsTable

#: chord tolerance (mm) of the outlines checked for collisions between moving parts
COLLISION_TOLERANCE_MM = 0.05
#: poses over the motion at which collisions are checked
SWEEP = 181


@dataclass(frozen=True)
class Stock:
    """What every part of one linkage shares (mm): the nominal hole diameter (pin + clearance), the plate
    thickness and the chord tolerance of meshes and sheets."""

    hole: float
    thickness: float
    tolerance: float

    @classmethod
    def of(cls, table: PartsTable) -> Stock:
        """The stock a ``[parts]`` table asks for."""
        return cls(table.pin_diameter + table.clearance, table.thickness, table.tolerance)


@dataclass(frozen=True)
class LinkPart:
    """A part in its own frame: hole centres (k, 2) mm, outline half-width (mm), its stock, its guide slots (each
    its two end centres), whether it moves, and the points its outline rounds if not the hole centres.

    A :class:`camgen.core.parts.PartMaker`: :meth:`part` makes it with any allowance.
    """

    name: str
    centres: np.ndarray
    half_width: float
    stock: Stock
    slots: tuple[tuple[np.ndarray, np.ndarray], ...] = ()
    moving: bool = True
    body: np.ndarray | None = None
    #: holes of their own size ((x, y), nominal diameter; mm): a kit's base plate's mounting holes
    mounts: tuple[tuple[tuple[float, float], float], ...] = ()

    def outline(self, grow: float = 0.0) -> Contour:
        """The nominal outline moved outwards by ``grow`` mm."""
        return rounded_hull(self.centres if self.body is None else self.body, self.half_width + grow)

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        """The part with its outline moved out by ``outline_grow`` and its holes' edges by ``hole_grow`` (mm)."""
        hole = (self.stock.hole + 2 * hole_grow) / 2
        holes: list = [Circle(tuple(c), hole) for c in self.centres]
        holes += [rounded_hull(np.array(slot), hole) for slot in self.slots]
        holes += [Circle(centre, diameter / 2 + hole_grow) for centre, diameter in self.mounts]
        return Part(self.name, self.outline(outline_grow), tuple(holes), self.stock.thickness, self.stock.tolerance)


@dataclass(frozen=True)
class Placement:
    """Where each part sits at each pose: angle (rad, counter-clockwise) and the position of its first hole (mm),
    and each joint: the two parts it joins and its positions (n, 2) mm."""

    angles: dict[str, np.ndarray]
    origins: dict[str, np.ndarray]
    joints: dict[str, tuple[tuple[str, str], np.ndarray]]


@dataclass(frozen=True)
class Layout:
    """What a mechanism gives to make its parts.

    ``parts``: the parts, the ground first; ``sweep``: their placement over the motion (collisions
    are checked there); ``positions``: the dead centres drawn in the assembly, (kind, input angle
    rad); ``poses``: the placement at each of them (one pose each); ``paths``: the points (n, 2) mm
    of each path drawn with them (a coupler point's, a slider's); ``layers``: each part's layer where
    the mechanism knows its stack (gears that mesh share a layer), else None for :func:`layer_order`'s.
    """

    parts: tuple[LinkPart, ...]
    sweep: Placement
    positions: tuple[tuple[str, float], ...]
    poses: tuple[Placement, ...]
    paths: tuple[np.ndarray, ...]
    layers: dict[str, int] | None = None


#: partial layer assignments the layer search may try before it gives up
LAYER_SEARCH_BUDGET = 200_000


def _posed(points: np.ndarray, angle: np.ndarray, origin: np.ndarray) -> np.ndarray:
    """Polygons (n,) of ``points`` (m, 2) mm, a part's outline flattened once in its own frame, turned by each
    ``angle`` (n,) rad counter-clockwise and moved by each ``origin`` (n, 2) mm (one outline, n poses: flattening the
    moved outline at each pose gives the same chords, turned)."""
    import shapely

    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    x, y = points[:, 0], points[:, 1]
    o = np.asarray(origin, float)
    return shapely.polygons(np.stack([c * x - s * y + o[:, 0, None], s * x + c * y + o[:, 1, None]], -1))


def layer_order(parts: tuple[LinkPart, ...], placement: Placement,
                pin_radius: float) -> tuple[dict[str, int], tuple[str, ...]]:
    """Layers (0 = the ground plate and any other fixed part, then upwards) so that no two moving parts on one
    layer ever overlap, parts joined by a pin are on different layers, and no part crosses a pin passing through
    its layer; and the ground pivots that must come down from a top plate instead (none unless no order works
    with the one base plate: a crank sweeping over another ground pivot).

    A graph colouring: the parts that clash (joined, or overlapping at some pose) are the graph's edges; the
    search assigns the moving parts in order, the lowest layer first, with the fewest layers first, pruning as
    soon as a clash or a crossed pin appears, so the first order it finds is the lexicographically first of the
    fewest layers. Collisions and pin crossings are found once over all poses (vectorised).
    """
    import shapely

    moving = [p.name for p in parts if p.moving]
    fixed = {p.name: 0 for p in parts if not p.moving}
    shapes = {p.name: _posed(p.outline().flatten(COLLISION_TOLERANCE_MM), placement.angles[p.name],
                             placement.origins[p.name]) for p in parts if p.moving}
    joined = {frozenset(names) for names, _ in placement.joints.values()}
    clash = {frozenset((a, b)): frozenset((a, b)) in joined or bool(shapely.intersects(shapes[a], shapes[b]).any())
             for a, b in itertools.combinations(moving, 2)}
    # each pin: its two parts and the parts it would cross if it passed through their layers
    # (a part that holds the pin's point itself, or guides it in a slot, is crossed by design: the pin goes
    # through its hole)
    pins = {}
    for joint, ((first, second), where) in placement.joints.items():
        circles = shapely.buffer(shapely.points(where), pin_radius)
        through = {name for (a, b), other in placement.joints.values() if {a, b} & {first, second}
                   and other.shape == where.shape and np.allclose(other, where, rtol=0, atol=1e-9) for name in (a, b)}
        pins[joint] = (first, second, tuple(name for name in moving if name not in (first, second)
                                            and name not in through
                                            and shapely.intersects(shapes[name], circles).any()))
    for from_above in (False, True):
        for top in range(1, len(moving) + 1):
            order = _colour(moving, fixed, top, clash, pins, from_above)
            if order is not None:
                return order, _top_pins(order, pins, fixed) if from_above else ()
    crossed = [f"{joint} ({first}-{second}) by {', '.join(crossers)}" for joint, (first, second, crossers)
               in pins.items() if crossers]
    raise DesignError("parts.width: no layer order keeps the moving parts and pins clear of each other"
                      + (f"; pins other parts sweep over: {'; '.join(crossed[:4])}" if crossed else "")
                      + "; narrow the parts (parts.width) where they only overlap, or move those joints apart")


def _between(order: dict[str, int], low: int, high: int, parts: tuple[str, ...]) -> bool:
    """Whether any of ``parts`` lies strictly between layers low and high."""
    low, high = sorted((low, high))
    return any(low < order[p] < high for p in parts)


def _top_pins(order: dict[str, int], pins: dict, fixed: dict[str, int]) -> tuple[str, ...]:
    """The ground pins a part crosses on their way up from the base plate: they come down from a top plate."""
    return tuple(joint for joint, (first, second, crossers) in pins.items()
                 if (first in fixed) != (second in fixed)
                 and _between(order, 0, order[second if first in fixed else first], crossers))


def _colour(moving: list[str], fixed: dict[str, int], top: int, clash: dict, pins: dict,
            from_above: bool) -> dict[str, int] | None:
    """The first assignment of layers 1..top to ``moving`` (in order, depth first) with no clash on a layer and no
    part between the layers of a pin it crosses (with ``from_above``, a ground pin may instead come down from a
    plate above layer ``top``); None if there is none; a DesignError past the search budget."""
    order = dict(fixed)
    tried = 0

    def pin_clear(first: str, second: str, crossers: tuple[str, ...], name: str) -> bool:
        grounded = (first in fixed) != (second in fixed)
        if not (from_above and grounded):
            return not any(name in (first, second, c) and all(x in order for x in (first, second, c))
                           and _between(order, order[first], order[second], (c,)) for c in crossers)
        if not all(x in order for x in (first, second, *crossers)):
            return True
        part = order[second if first in fixed else first]
        return not _between(order, 0, part, crossers) or not _between(order, part, top + 1, crossers)

    def fits(name: str) -> bool:
        layer = order[name]
        if any(order.get(other) == layer and clash[frozenset((name, other))] for other in moving
               if other != name and other in order):
            return False
        return all(pin_clear(first, second, crossers, name) for first, second, crossers in pins.values()
                   if name in (first, second, *crossers))

    def place(i: int) -> bool:
        nonlocal tried
        if i == len(moving):
            return True
        for layer in range(1, top + 1):
            tried += 1
            if tried > LAYER_SEARCH_BUDGET:
                raise DesignError(f"parts.width: no layer order found within {LAYER_SEARCH_BUDGET} tries; narrow the "
                                  "parts (parts.width) so fewer of them overlap")
            order[moving[i]] = layer
            if fits(moving[i]) and place(i + 1):
                return True
            del order[moving[i]]
        return False

    return order if place(0) else None


def with_top_plate(layout: Layout, order: dict[str, int], top_pins: tuple[str, ...],
                   half_width: float) -> tuple[Layout, dict[str, int]]:
    """The layout and layers with a top plate (``ground-top``, above every moving part) holding the pivots
    ``top_pins``, which come down to their parts from above; the layout as it is when there are none."""
    if not top_pins:
        return layout, order
    ground = next(p for p in layout.parts if not p.moving)
    centres = np.array([layout.sweep.joints[j][1][0] for j in top_pins])
    plate = LinkPart("ground-top", centres, half_width, ground.stock, moving=False)
    # the base plate keeps its shape but not the holes of the pivots that now come from above
    below = np.array([c for c in ground.centres if not any(np.allclose(c, t, atol=1e-9) for t in centres)])
    base = replace(ground, centres=below if len(below) else ground.centres,
                   body=ground.centres if ground.body is None else ground.body)

    def fixed_too(place: Placement) -> Placement:
        n = len(next(iter(place.angles.values())))
        def on(part: str, joint: str) -> str:
            return plate.name if joint in top_pins and part == ground.name else part

        joints = {j: ((on(a, j), on(b, j)), where) for j, ((a, b), where) in place.joints.items()}
        return Placement({**place.angles, plate.name: np.zeros(n)},
                         {**place.origins, plate.name: np.zeros((n, 2))}, joints)

    parts = tuple(base if p is ground else p for p in layout.parts)
    layout = Layout((*parts, plate), fixed_too(layout.sweep), layout.positions,
                    tuple(fixed_too(p) for p in layout.poses), layout.paths)
    return layout, {**order, plate.name: max(order.values()) + 1}


def _place(part: Part, angle: float, shift: np.ndarray) -> tuple[Contour, list]:
    """The part's outline and holes turned by ``angle`` (rad) and moved by ``shift`` (mm)."""
    return part.outline.moved(angle, shift), [hole.moved(angle, shift) for hole in part.holes]


def assembly(printed: tuple[Part, ...], layout: Layout, tolerance: float) -> Drawing:
    """The printed parts at each dead centre, each pose on its own layer (``DC1-extended``, ...), and the path on
    ``PATH``."""
    items: list = []
    for i, ((kind, _), place) in enumerate(zip(layout.positions, layout.poses, strict=True)):
        layer = f"DC{i + 1}-{kind}"
        for part in printed:
            outline, holes = _place(part, float(place.angles[part.name][0]), place.origins[part.name][0])
            items += [(layer, outline), *((layer, h) for h in holes)]
    items += [("PATH", Polyline(path, np.zeros(len(path) - 1))) for path in layout.paths]
    return Drawing(tuple(items), tolerance, stroke=preview_stroke(items))


@dataclass(frozen=True)
class LinkageBuild:
    """A linkage's parts: nominal, as cut and as printed, their layers (0 = the ground, then upwards), the cut sheets
    (one drawing a sheet, nested by :func:`camgen.core.nesting.nest`), the assembly drawing and the dead centres it
    shows ((kind, input angle rad)), and the nesting's figures."""

    parts: tuple[LinkPart, ...]
    table: Any
    allowances: Allowances
    layers: dict[str, int]
    cut: tuple[Part, ...]
    printed: tuple[Part, ...]
    sheets: tuple[Drawing, ...]
    assembly: Drawing
    positions: tuple[tuple[str, float], ...]
    #: the placement of the first dead centre the assembly drawing shows (its layers ``DC1-...``), or of the
    #: motion's first pose where it shows none (a rhombus): the parts as assembled (its first pose is the one used)
    pose: Placement
    #: (joint, the two parts, how many layers it fills, the lowest of them) for each run of empty layers a pin
    #: crosses between the two parts it joins: a spacer fills it
    spacers: tuple[tuple[str, tuple[str, str], int, int], ...] = ()
    nesting: Nest | None = None
    #: the pivot points: the joints that share one (over the whole motion), each one pin through all their parts
    pivots: tuple[Pivot, ...] = ()

    @property
    def spacer_diameters(self) -> tuple[float, float]:
        """A spacer's inner (the printed hole) and outer diameter (twice the pin, at most the narrowest part), mm."""
        table = self.table
        narrowest = min(2 * p.half_width for p in self.parts)
        return table.pin_diameter + table.clearance, min(2 * table.pin_diameter, narrowest)

    @property
    def layer_names(self) -> list[str]:
        """The parts' names from the bottom layer up."""
        return sorted(self.layers, key=lambda k: self.layers[k])

    @property
    def report(self) -> dict[str, Any]:
        """The report's parts section: each part's holes, width and layer, the layer order, the allowances."""
        table, allow = self.table, self.allowances
        entries = []
        for link in self.parts:
            holes = [{"x_mm": round(c[0], 9), "y_mm": round(c[1], 9)} for c in link.centres]
            entry = {"name": link.name, "layer": self.layers[link.name], "holes": holes,
                     "width_mm": 2 * link.half_width, "thickness_mm": link.stock.thickness,
                     "cut_hole_diameter_mm": allow.cut_diameter(link.stock.hole),
                     "printed_hole_diameter_mm": allow.printed_diameter(link.stock.hole)}
            if len(link.centres) >= 2:
                entry["hole_distance_mm"] = float(np.linalg.norm(link.centres[1] - link.centres[0]))
            entries.append(entry)
        return {"parts": entries, "layer_order": self.layer_names, "layers": dict(self.layers),
                "allowances": {"kerf_mm": table.kerf, "clearance_mm": table.clearance,
                               "cut_holes": "pin + clearance - kerf", "cut_outlines": "grown by kerf / 2",
                               "printed_holes": "pin + clearance"},
                "assembly_layers": [f"DC{i + 1}-{k}" for i, (k, _) in enumerate(self.positions)],
                **({"spacers": self._spacer_report()} if self.spacers else {}),
                **({"sheet": self.nesting.report} if self.nesting is not None else {})}

    def _spacer_report(self) -> list[dict[str, Any]]:
        inner, outer = self.spacer_diameters
        return [{"joint": joint, "between": list(parts), "height_mm": run * self.table.thickness,
                 "inner_diameter_mm": inner, "outer_diameter_mm": outer} for joint, parts, run, _ in self.spacers]


@dataclass(frozen=True)
class Pivot:
    """A pivot point: the joints that lie on it at every pose, the parts they join (in the order met) and the lowest
    and highest of those parts' layers (one pin passes them all)."""

    joints: tuple[str, ...]
    parts: tuple[str, ...]
    low: int
    high: int


def pivots_of(placement: Placement, layers: dict[str, int]) -> tuple[Pivot, ...]:
    """The pivot points of ``placement`` (its joints grouped where they coincide at every pose, to 1e-9 mm), in the
    order of their first joints."""
    points: list[tuple[np.ndarray, list[str], list[str]]] = []
    for joint, (parts, where) in placement.joints.items():
        same = next((p for p in points if p[0].shape == where.shape and np.allclose(p[0], where, rtol=0, atol=1e-9)),
                    None)
        if same is None:
            same = (where, [], [])
            points.append(same)
        same[1].append(joint)
        same[2].extend(p for p in parts if p not in same[2])
    return tuple(Pivot(tuple(joints), tuple(parts), min(layers[p] for p in parts), max(layers[p] for p in parts))
                 for _, joints, parts in points)


def spacers_of(placement: Placement, layers: dict[str, int]) -> tuple[tuple[str, tuple[str, str], int, int], ...]:
    """For every pin, each run of empty layers between the two parts it joins (a layer is not empty where a part
    holds or guides the same point: the pin goes through it): (joint, the two parts, the run's layers, its lowest
    layer)."""
    out = []
    for joint, (parts, where) in placement.joints.items():
        low, high = sorted(layers[p] for p in parts)
        through = {layers[name] for (a, b), other in placement.joints.values() if {a, b} & set(parts)
                   and other.shape == where.shape and np.allclose(other, where, rtol=0, atol=1e-9)
                   for name in (a, b)}
        run = 0
        for layer in range(low + 1, high + 1):
            if layer in through or layer == high:
                if run:
                    out.append((joint, parts, run, layer - run))
                run = 0
            else:
                run += 1
    return tuple(out)


def build_parts(layout: Layout, table: PartsTable, elephant_foot: float = 0.0) -> LinkageBuild:
    """Layers, cut and printed parts, cut sheet and assembly drawing of a mechanism's ``layout``, for its
    ``[parts]`` table; the printed parts' bed faces chamfered by ``elephant_foot`` mm (``output.elephant_foot``)."""
    allowances = Allowances(kerf=table.kerf, clearance=0.0, kerf_field="parts.kerf", elephant_foot=elephant_foot)
    if layout.layers is not None:
        layers = dict(layout.layers)
    else:
        layers, top_pins = layer_order(layout.parts, layout.sweep, table.pin_diameter / 2)
        layout, layers = with_top_plate(layout, layers, top_pins, table.width_of("ground"))
    cut = tuple(allowances.cut(p) for p in layout.parts)
    printed = tuple(allowances.printed(p) for p in layout.parts)
    nested = nest(cut, SheetRules.of(table, table.kerf, "parts.sheet"))
    spacers = spacers_of(layout.sweep, layers)
    return LinkageBuild(layout.parts, table, allowances, layers, cut, printed, nested.drawings(table.tolerance),
                        assembly(printed, layout, table.tolerance), layout.positions,
                        layout.poses[0] if layout.poses else layout.sweep, spacers, nested,
                        pivots_of(layout.sweep, layers))
