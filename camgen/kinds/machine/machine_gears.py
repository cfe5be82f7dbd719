"""A machine's gear pairs (``[[gears]]``) as real involute spur gears, designed by linkgen's own gear-pair design
(:mod:`linkgen.mechanisms.gearpair`, :mod:`linkgen.gears`, :mod:`linkgen.mechanisms.gearparts`): their checks,
their parts, their clash bodies and their places in the machine. No I/O.

Each pair is linkgen's external pair with the driver's gear as its pinion and the driven gear as its gear: the same
module, pressure angle, shifts and backlash, so its outlines, contact ratio, undercut and interference checks are
linkgen's. A refusal of linkgen's is given again naming the machine's field (``gears[i].driver_shift`` for the
pinion's shift, ``gears[i].driven_teeth`` for the gear's teeth, ...).

**Placing.** linkgen's pair has the pinion's centre at the origin and the gear's at (c, 0); the machine turns that
frame by beta, the direction from the driver's shaft to the driven one's, and moves it onto the driver's shaft. At
main shaft angle phi (radians) the driver's gear stands at beta + theta1 with theta1 = theta_m + Q1(phi) (theta_m
linkgen's mesh phase: a pinion tooth centred on the line of centres, the gear's space there too; Q1 the driver
shaft's angle, :mod:`camgen.kinds.machine.shaft_motion`: n1 phi, n1 its turns per main turn, counter-clockwise
positive, or an indexing shaft's intermittent angle) and the driven gear at beta + g(theta1), g linkgen's
:meth:`~linkgen.gears.pair.GearPair.gear_angle`: its shaft's n2 = -n1 z1 / z2 turns a main turn, and the backlash is
shared between both flanks at phi = 0. Angles counter-clockwise, lengths mm.

**Planes.** A gear pair stands on one plane along both shafts: plane 2 ``layer`` as a cam's, or with no ``layer``
the lowest plane from 0 up that no other part sweeps into and none crosses either shaft under (:func:`plane_of`); a
hub (``hub_diameter``, ``hub_height``) fills the plane over it, round the shaft. Each gear's hole is its shaft's
diameter (:func:`camgen.kinds.machine.frame.shaft_diameters`), made with the machine's kerf (cut) and clearance
(printed).
"""
from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from linkgen.gears.pair import GearPair
from linkgen.mechanisms.gearpair import CONTACT_WARNING, TIP_WARNING, GearPairTable
from linkgen.mechanisms.shaped import ShapedPart
from linkgen.parts import Stock

#: the pair's members: the driver's gear (linkgen's pinion) and the driven gear (linkgen's gear)
MEMBERS = ("driver", "driven")
#: linkgen's gear-pair keys and the machine's [[gears]] fields they are
_FIELDS = {"pinion.teeth": "driver_teeth", "pinion.shift": "driver_shift", "gear.teeth": "driven_teeth",
           "gear.shift": "driven_shift", "backlash": "backlash", "centre_distance": "module",
           "pressure_angle": "pressure_angle", "module": "module", "boss_height": "hub_height",
           "boss_diameter": "hub_diameter", "set_screw": "set_screw"}
#: the least wall (mm) a gear's hole leaves inside its root circle (linkgen's rule for a gear pair's pin hole)
HOLE_WALL_MM = 1.0


def pair_table(gear: Any, index: int) -> GearPairTable:
    """linkgen's ``[linkage]`` table of the machine's ``gears[index]`` (``gear``: a
    :class:`~camgen.kinds.machine.spec.GearTable`), validated and checked there; a :class:`ValueError` naming
    ``gears[index].<field>`` where linkgen refuses it."""
    from pydantic import ValidationError

    hub = {"boss_diameter": gear.hub_diameter, "boss_height": gear.hub_height, "set_screw": gear.set_screw}
    raw = {"type": "gear-pair", "kind": "external", "module": gear.module, "pressure_angle": gear.pressure_angle,
           "backlash": gear.backlash, "pinion": {"teeth": gear.driver_teeth, "shift": gear.driver_shift, **hub},
           "gear": {"teeth": gear.driven_teeth, "shift": gear.driven_shift, **hub}}
    try:
        return GearPairTable.model_validate(raw)
    except ValidationError as exc:
        error = exc.errors()[0]
        text = str(error["msg"]).removeprefix("Value error, ")
        where = ".".join(str(p) for p in error["loc"])
        found = re.match(r"([a-z_.]+): (.*)", text, re.S)
        if found and found[1] in _FIELDS:
            where, text = found[1], found[2]
        field = _FIELDS.get(where, _FIELDS.get(where.split(".")[-1], "module"))
        raise ValueError(f"gears[{index}].{field}: {text} (linkgen's pinion is the driver's gear, its gear the "
                         "driven one)") from None


@dataclass(frozen=True)
class MachineGear:
    """One gear pair of the machine, designed (see the module's notes).

    Attributes
    ----------
    index, name : int, str
        Its place in ``[[gears]]`` and its name (``<driver>-<driven>`` unless given): its files are
        ``<machine>-<name>-driver...`` and ``-driven...``.
    table : GearPairTable
        linkgen's gear-pair table of it.
    shafts : tuple of str
        The driver's and the driven shaft's names.
    centres : ndarray
        (2, 2) mm: the two shafts' centres.
    turns : tuple of float
        Each shaft's turns per main turn (negative: clockwise).
    makers : tuple of ShapedPart
        Each gear as linkgen's gear-pair parts make it (nominal: its outline, its hole the shaft's diameter, its hub).
    thickness, hub_height : float
        The gears' thickness and their hubs' height (mm; 0: no hub).
    layer : int or None
        The ``layer`` given (plane 2 layer), or None: the lowest free plane (:func:`plane_of`).
    """

    index: int
    name: str
    table: GearPairTable
    shafts: tuple[str, str]
    centres: np.ndarray
    turns: tuple[float, float]
    makers: tuple[ShapedPart, ShapedPart]
    thickness: float
    hub_height: float
    layer: int | None
    #: the driver shaft's motion (:class:`~camgen.kinds.machine.shaft_motion.ShaftMotion`), None: uniform
    driver_motion: Any = None

    @property
    def pair(self) -> GearPair:
        """linkgen's pair (the driver's gear its pinion)."""
        return self.table.pair

    @property
    def beta(self) -> float:
        """The direction (radians) from the driver's shaft to the driven one's: linkgen's +X in the machine."""
        d = self.centres[1] - self.centres[0]
        return math.atan2(float(d[1]), float(d[0]))

    def angles(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Each gear's angle (radians, counter-clockwise from the machine's +X to its tooth 0) at main shaft angles
        ``phi`` (radians)."""
        phi = np.asarray(phi, dtype=float)
        turned = self.turns[0] * phi if self.driver_motion is None else self.driver_motion.angles(phi)[0]
        theta = self.pair.mesh_phases[0] + turned
        return self.beta + theta, self.beta + self.pair.gear_angle(theta)

    def placement(self, member: int) -> Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]:
        """The clash check's placement of gear ``member`` (0 the driver's, 1 the driven): phi -> (M, t)."""
        from camgen.kinds.machine.clash import rotation

        centre = self.centres[member]

        def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            return rotation(self.angles(phi)[member]), np.broadcast_to(centre, (len(phi), 2))

        return place

    def part_name(self, member: int) -> str:
        """The clash check's (and the assembly's) name of gear ``member``: ``gears.<name>.driver`` or ``.driven``."""
        return f"gears.{self.name}.{MEMBERS[member]}"


def designed(spec: Any, tolerance: float, shafts: dict[str, Any] | None = None) -> tuple[MachineGear, ...]:
    """Every gear pair of ``spec`` (a :class:`~camgen.kinds.machine.spec.MachineSpec`) designed, its outlines within
    ``tolerance`` mm, each turned by its driver shaft's motion in ``shafts`` (name to
    :class:`~camgen.kinds.machine.shaft_motion.ShaftMotion`: an indexing shaft's gear indexes; none: uniform).

    Raises
    ------
    SpecError
        Naming ``gears[i].driver_teeth``: the teeth's outlines overlap as the pair turns (undercut, trochoid or tip
        interference, linkgen's :func:`~linkgen.mechanisms.gearparts.overlap`); naming ``gears[i].<member>_teeth``
        or ``.hub_diameter``: a shaft's hole that leaves under 1 mm inside the gear's root circle, a hub that does
        not fit between the hole and the root circle.
    """
    from camgen.kinds.machine.frame import shaft_diameters
    from linkgen.mechanisms.gearparts import outlines, overlap

    at = {s.name: np.asarray(s.at, dtype=float) for s in spec.shafts}
    bores = shaft_diameters(spec)
    out = []
    for i, g in enumerate(spec.gears):
        table = pair_table(g, i)
        pair = table.pair
        where = overlap(pair)
        if where is not None:
            raise SpecError(f"the teeth's outlines overlap as the pair turns (at the driver's gear's angle "
                            f"{math.degrees(where):.4f} degrees from its mesh phase): undercut, tip or trochoid "
                            "interference; give the gears more teeth or shifts", f"gears[{i}].driver_teeth")
        shapes = outlines(pair, tolerance)
        makers = []
        for k, (member, tooth, shape) in enumerate(zip(MEMBERS, (pair.pinion_tooth, pair.gear_tooth),
                                                       (shapes.pinion, shapes.other), strict=True)):
            assert tooth is not None
            shaft = (g.driver, g.driven)[k]
            hole = bores[shaft]
            if hole / 2 + HOLE_WALL_MM > tooth.root_radius:
                raise SpecError(f"shaft {shaft}'s {hole:g} mm hole leaves less than {HOLE_WALL_MM:g} mm inside the "
                                f"{member} gear's root circle ({2 * tooth.root_radius:.4g} mm across): give it more "
                                "teeth or a larger module", f"gears[{i}].{member}_teeth")
            if g.hub_height > 0 and not hole < g.hub_diameter < 2 * tooth.root_radius:
                raise SpecError(f"a hub wider than shaft {shaft}'s {hole:g} mm hole and within the {member} gear's "
                                f"root circle ({2 * tooth.root_radius:.4g} mm across; got {g.hub_diameter:g})",
                                f"gears[{i}].hub_diameter")
            boss = (g.hub_diameter, g.hub_height) if g.hub_height > 0 else None
            makers.append(ShapedPart(f"{gear_name(g)}-{member}", np.zeros((1, 2)), tooth.root_radius,
                                     Stock(hole, g.thickness, tolerance), shape=shape, boss=boss,
                                     set_screw=g.set_screw))
        out.append(MachineGear(i, gear_name(g), table, (g.driver, g.driven), np.array([at[g.driver], at[g.driven]]),
                               (spec.turns[g.driver], spec.turns[g.driven]), (makers[0], makers[1]), g.thickness,
                               g.hub_height, g.layer, _indexing(shafts, g.driver)))
    return tuple(out)


def _indexing(shafts: dict[str, Any] | None, name: str) -> Any:
    """The motion of shaft ``name`` in ``shafts`` where it indexes (a Geneva drive before it), else None."""
    motion = None if shafts is None else shafts.get(name)
    return None if motion is None or motion.uniform else motion


def gear_name(gear: Any) -> str:
    """A ``[[gears]]`` entry's name: its own, else ``<driver>-<driven>``."""
    return gear.name if gear.name is not None else f"{gear.driver}-{gear.driven}"


def warnings_of(gear: MachineGear) -> list[str]:
    """What a gear designer would want to know of a pair that is still made (linkgen's warnings: undercut, thin tips,
    a low contact ratio), each naming the field to change."""
    pair, i = gear.pair, gear.index
    out = []
    for member, tooth in zip(MEMBERS, (pair.pinion_tooth, pair.gear_tooth), strict=True):
        assert tooth is not None
        if tooth.undercut:
            least = tooth.rack.straight_depth - tooth.teeth * math.sin(tooth.pressure_angle) ** 2 / 2
            out.append(f"gears[{i}].{member}_shift: the {member} gear is undercut: {tooth.teeth} teeth at shift "
                       f"{tooth.shift:g}, fewer than the {tooth.fewest_teeth:.4g} that shift cuts whole; a shift of "
                       f"{least:.4g} or more avoids it")
        if tooth.tip_thickness < TIP_WARNING * pair.module:
            out.append(f"gears[{i}].{member}_shift: the {member} gear's tips are {tooth.tip_thickness:.4g} mm thick, "
                       "under a quarter module")
    if pair.contact_ratio < CONTACT_WARNING:
        out.append(f"gears[{i}].driver_teeth: contact ratio {pair.contact_ratio:.4f}: under {CONTACT_WARNING:g}, "
                   "the pair runs rough")
    return out


def gear_report(gear: MachineGear, plane: int | None) -> dict[str, Any]:
    """The report's entry of one pair: linkgen's gear-pair figures (contact ratio, working pressure angle, each
    member's radii, undercut), its shafts, its speed ratio against the teeth's, its plane and its files' prefix."""
    from linkgen.mechanisms.gearpair import pair_report

    linkgen_report = pair_report(gear.table, gear.pair, None)
    members = linkgen_report.pop("gears")
    linkgen_report.pop("input_range_deg", None)
    linkgen_report["warnings"] = warnings_of(gear)
    return {"name": gear.name, "driver": gear.shafts[0], "driven": gear.shafts[1],
            **linkgen_report, "driver_gear": members["pinion"], "driven_gear": members["gear"],
            "shaft_turns": [round(t, 12) for t in gear.turns], "thickness_mm": gear.thickness,
            "hub_height_mm": gear.hub_height, "plane": plane}


#: main shaft angles over the turn at which the default plane's search sweeps the other parts
SWEEP_SAMPLES = 72
#: how far (mm) the default plane's search keeps the other parts from the gears' tip circles and the shafts
SWEEP_CLEARANCE_MM = 0.5


def plane_of(gear: MachineGear, bodies: Any, joints: Any) -> int:
    """The plane gear pair ``gear`` stands on: 2 ``layer``, or with none the lowest plane from 0 up where no other
    part of the clash check's ``bodies`` (gear pairs placed before it too) sweeps (over :data:`SWEEP_SAMPLES`
    angles, within :data:`SWEEP_CLEARANCE_MM`) into either gear's tip circle, nor, on the planes under it, across
    either shaft (but the parts it carries, meeting it in ``joints``); where none is, the plane over every part (the
    clash check then names what meets it)."""
    if gear.layer is not None:
        return 2 * gear.layer
    tips = [(c, t.tip_radius) for c, t in zip(gear.centres, (gear.pair.pinion_tooth, gear.pair.gear_tooth),
                                              strict=True) if t]
    axes = [(c, m.stock.hole / 2) for c, m in zip(gear.centres, gear.makers, strict=True)]
    return free_plane(bodies, joints, tips, axes, gear.shafts)


def free_plane(bodies: Any, joints: Any, discs: Any, axes: Any, shafts: Any, height: int = 1) -> int:
    """The lowest plane p from 0 up such that no part of the clash check's ``bodies`` on planes p to p + ``height``
    - 1 sweeps (over :data:`SWEEP_SAMPLES` main shaft angles, within :data:`SWEEP_CLEARANCE_MM`) into any of the
    ``discs`` ((centre, radius) mm: the area a mechanism fills), and none on the planes under p crosses any of the
    ``axes`` ((centre, radius) mm: its shafts), but the parts those ``shafts`` (names) carry (meeting them in
    ``joints``) and the pins; where none is, the plane over every part."""
    import shapely

    from camgen.kinds.machine.clash import outlines

    phi = np.arange(SWEEP_SAMPLES) * (2 * math.pi / SWEEP_SAMPLES)
    others = [b for b in bodies if not b.name.startswith(("shafts.", "spacers."))]
    # a part's sweep meets a disc where one of its placed outlines does: no union of them needed
    swept = [(b, outlines(b, phi)) for b in others]
    filled = [shapely.Point(*c).buffer(r + SWEEP_CLEARANCE_MM) for c, r in discs]
    carried = {j.a for j in joints if j.b in {f"shafts.{s}" for s in shafts}}
    crossed = [shapely.Point(*c).buffer(r + SWEEP_CLEARANCE_MM) for c, r in axes]
    top = max((b.high for b in others), default=-1) + 1
    for plane in range(0, top + 1):
        on = [area for b, area in swept if b.low <= plane + height - 1 and plane <= b.high]
        if any(shapely.intersects(area, t).any() for area in on for t in filled):
            continue
        under = [area for b, area in swept if b.low <= plane - 1 and b.high >= 0 and b.name not in carried
                 and not b.name.startswith("pins.")]
        if any(shapely.intersects(area, a).any() for area in under for a in crossed):
            continue
        return plane
    return top


def gear_bodies(design: Any, bodies: list[Any], joints: list[Any],
                shafts: dict[str, list[tuple[int, float]]]) -> None:
    """Add every gear of ``design`` (a :class:`~camgen.kinds.machine.design.MachineDesign`) to the clash check's
    ``bodies`` (its nominal outline within the pair's tolerance, turned as :meth:`MachineGear.angles` turns it, its
    hole at its centre; its hub, a disc round the shaft on the plane over it), each meeting its shaft in a joint,
    and its seat to ``shafts`` (plane, hole radius). The two gears of a pair meet in no joint: their teeth must not
    overlap."""
    from camgen.kinds.machine.clash import Body, Joint, circle, still

    for gear in getattr(design, "gears", ()):
        plane = plane_of(gear, bodies, joints)                # the pairs placed before it among the others
        for k, maker in enumerate(gear.makers):
            name, shaft = gear.part_name(k), gear.shafts[k]
            r = maker.stock.hole / 2
            outline = maker.outline().flatten(maker.stock.tolerance)
            bodies.append(Body(name, plane, plane, outline, gear.placement(k), (((0.0, 0.0), r),)))
            joints.append(Joint(name, f"shafts.{shaft}", still(gear.centres[k]), 1.01 * r + 0.05))
            shafts.setdefault(shaft, []).append((plane, r))
            if gear.hub_height > 0 and maker.boss is not None:
                hub = maker.boss[0] / 2
                bodies.append(Body(f"{name}.hub", plane + 1, plane + 1, circle(hub, maker.stock.tolerance),
                                   gear.placement(k), (((0.0, 0.0), r),)))
                joints.append(Joint(f"{name}.hub", f"shafts.{shaft}", still(gear.centres[k]), 1.01 * hub + 0.05))
                shafts.setdefault(shaft, []).append((plane + 1, r))


def thicknesses(design: Any) -> dict[str, float]:
    """Each gear's and hub's thickness (mm) by its clash-check name."""
    out: dict[str, float] = {}
    for gear in getattr(design, "gears", ()):
        for k in range(2):
            out[gear.part_name(k)] = gear.thickness
            if gear.hub_height > 0:
                out[f"{gear.part_name(k)}.hub"] = gear.hub_height
    return out


def report_entries(design: Any) -> list[dict[str, Any]]:
    """The report's ``gears``: each ``[[gears]]`` entry as given, with its design (:func:`gear_report`) where the
    machine was designed with its gears."""
    spec = design.spec
    made = {g.index: g for g in getattr(design, "gears", ())}
    planes = {b.name: b.low for b in getattr(design, "bodies", ())}
    out = []
    for i, g in enumerate(spec.gears):
        entry = g.model_dump()
        if i in made:
            entry.update(gear_report(made[i], planes.get(made[i].part_name(0))))
        out.append(entry)
    return out


def gear_parts(design: Any) -> tuple[tuple[str, Any, Any], ...]:
    """Each gear of ``design`` as its files carry it: (its files' stem ``<machine>-<name>-<member>``, the part as
    cut with the machine's ``output.kerf``, as printed with its ``output.clearance``)."""
    from camgen.core.parts import Allowances

    out = design.spec.output
    allow = Allowances(out.kerf, out.clearance, "output.kerf", out.elephant_foot)
    return tuple((f"{design.spec.name}-{maker.name}", allow.cut(maker), allow.printed(maker))
                 for gear in getattr(design, "gears", ()) for maker in gear.makers)


def gear_items(design: Any, formats: tuple[str, ...]) -> list[Any]:
    """The gears' files of ``formats``: each gear's cut file (``<machine>-<name>-<member>.dxf`` and ``-cut.svg``)
    and its printed one (``.stl``, ``.3mf``), their keys ``gears.<name>-<member>_dxf`` ..."""
    from camgen.core.bundle import mesh_files, part_files
    from camgen.core.parts import Drawing
    from camgen.core.solids import checked_mesh

    items: list[Any] = []
    meshes = bool({"stl", "3mf"} & set(formats))
    for stem, cut, printed in gear_parts(design):
        key = "gears." + stem.removeprefix(f"{design.spec.name}-")
        items.append(part_files(Drawing.of_part(cut), stem, key))
        items.append(mesh_files(checked_mesh(printed, stem)[0] if meshes else None, stem, key))
    return [i.only(formats) if i is not None else None for i in items]


def bom_lines(design: Any) -> tuple[Any, ...]:
    """The bill of materials' line of each gear: its teeth, module, thickness, hole and hub."""
    from camgen.core.kit import BomLine

    out = []
    for gear in getattr(design, "gears", ()):
        for k, (maker, tooth) in enumerate(zip(gear.makers, (gear.pair.pinion_tooth, gear.pair.gear_tooth),
                                               strict=True)):
            assert tooth is not None
            hub = f", hub {maker.boss[0]:g} x {maker.boss[1]:g} mm" if maker.boss is not None else ""
            out.append(BomLine(f"gear {maker.name}", 1, f"{tooth.teeth} teeth, module {gear.pair.module:g} mm, "
                               f"{gear.thickness:g} mm thick, {maker.stock.hole:g} mm hole{hub}, on shaft "
                               f"{gear.shafts[k]} (its own files)", "laser or fdm"))
    return tuple(out)
