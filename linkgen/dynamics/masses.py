"""Each moving link's mass, centre of mass and inertia from the parts as made, with its pins and hardware.

A link's part is the general parts layer's (:func:`linkgen.mechanisms.general.general_parts`: the same outline as
the dedicated mechanisms cut), made as its material is: laser-cut with the kerf (outline grown by kerf / 2, holes
shrunk by as much) or printed (the holes at pin + clearance); its section (:mod:`linkgen.dynamics.section`, exact for
the arcs) times the plate's thickness and the material's density (times the infill for a printed part) is its mass,
centre and inertia. The hardware of each pivot point the link carries is added as point masses at the joint: the
pin through the stack as the layer order builds it (a shank of ``parts.pin_diameter`` as long as the stack and 1 mm
more, under a head 1.8 diameters wide and half a diameter high, as :mod:`linkgen.outputs` prints it; with a
``[kit]``, the ISO 4762 bolt of the grip's length with its ISO 4032 nut and ISO 7089 washer, all steel) and the
printed spacers on it. A pin that joins a link to the frame stays where it is (its own spin is not counted). A
pivot's hardware goes to the first moving link that holds it. ``[dynamics.links.<link>]`` replaces any of the
link's totals; a link given a mass alone keeps its part's centre and its inertia scaled by the masses' ratio.

Units: kg, mm, kg*mm^2; centres in the link's own frame (:func:`linkgen.kinematics.inertia.link_frame`) and, for the
kinematics, in the drawing's frame.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from camgen.core.errors import SpecError
from camgen.core.hardware import bolt_length
from camgen.core.parts import Allowances
from linkgen.dynamics.materials import PINS, SHEETS, SPACER, Material
from linkgen.dynamics.section import part_section
from linkgen.kinematics.inertia import LinkMass, combined, link_frame, moving_links
from linkgen.kinematics.structure import GROUND, Structure
from linkgen.mechanisms.general import Analysis, general_parts
from linkgen.parts import Layout, LinkageBuild, Pivot, layer_order, pivots_of, spacers_of, with_top_plate

if TYPE_CHECKING:
    from camgen.core.kit import KitTable
    from linkgen.dynamics.table import DynamicsTable
    from linkgen.spec import PartsTable

#: kg/mm^3 in a kg/m^3
PER_MM3 = 1e-9


@dataclass(frozen=True)
class Stack:
    """How the parts stack on their pins, as the layer order builds them: the layers' count above the frame
    (``top``: a printed pin is ``top`` plates and 1 mm long), the pivot points, the spacers ((joint, its two parts,
    its layers, its lowest)) and their inner and outer diameters (mm)."""

    top: int
    pivots: tuple[Pivot, ...]
    spacers: tuple[tuple[str, tuple[str, str], int, int], ...]
    spacer_diameters: tuple[float, float]

    @classmethod
    def of_build(cls, build: LinkageBuild) -> Stack:
        """The stack of a build (its layers, pivots and spacers)."""
        return cls(max(build.layers.values()) + 1, build.pivots, build.spacers, build.spacer_diameters)

    @classmethod
    def of_layout(cls, layout: Layout, parts: PartsTable) -> Stack:
        """The stack the layer order gives a mechanism's layout (as :func:`linkgen.parts.build_parts` finds it)."""
        layers, top = layer_order(layout.parts, layout.sweep, parts.pin_diameter / 2)
        layout, layers = with_top_plate(layout, layers, top, parts.width_of(GROUND))
        narrowest = min(2 * p.half_width for p in layout.parts)
        return cls(max(layers.values()) + 1, pivots_of(layout.sweep, layers), spacers_of(layout.sweep, layers),
                   (parts.pin_diameter + parts.clearance, min(2 * parts.pin_diameter, narrowest)))


@dataclass(frozen=True)
class LinkMasses:
    """One moving link's mass properties (kg, mm, kg*mm^2; the link's frame): its part as made (None without
    ``[parts]``), its hardware ((what, mass) pairs), and the total the dynamics uses (the given values where
    ``[dynamics.links.<link>]`` gives them)."""

    link: str
    part: LinkMass | None
    hardware: tuple[tuple[str, LinkMass], ...]
    total: LinkMass
    given: tuple[str, ...]


@dataclass(frozen=True)
class MassModel:
    """Every moving link's masses (:class:`LinkMasses`), the parts' material and density (kg/m^3), the totals in the
    drawing's frame (what :mod:`linkgen.kinematics.kinetostatics` takes) and the parts' solid fraction."""

    links: dict[str, LinkMasses]
    material: Material
    density: float
    drawn: dict[str, LinkMass]
    #: the parts' solid fraction (the infill of printed parts; 1 for a sheet)
    fill: float = 1.0

    @property
    def total_mass(self) -> float:
        """The moving links' mass (kg)."""
        return sum(m.total.mass for m in self.links.values())


def mass_model(table: DynamicsTable, analysis: Analysis, parts: PartsTable | None, stack: Stack | None = None,
               kit: KitTable | None = None) -> MassModel:
    """The moving links' mass properties for the ``[dynamics]`` ``table`` of the linkage ``analysis`` draws, from
    its ``[parts]`` (and ``[kit]``) when it has them, the pins and spacers as ``stack`` has them (none without);
    a :class:`SpecError` naming the key for a link the linkage has not, or for a link whose values neither a part
    nor the table gives."""
    s = analysis.linkage.structure
    moving = moving_links(s)
    for name in table.links:
        if name not in moving:
            raise SpecError(f"no moving link {name!r} (links: {', '.join(moving)})", f"dynamics.links.{name}")
    material = SHEETS[table.material]
    density = table.density if table.density is not None else material.density
    computed = _from_parts(table, analysis, parts, stack, kit, material, density) if parts is not None else {}
    links, drawn = {}, {}
    for body in moving:
        part, hardware = computed.get(body, (None, ()))
        given = table.links.get(body)
        total = _total(body, part, hardware, given, parts is not None)
        names = tuple(k for k in ("mass", "centre", "inertia") if given is not None and getattr(given, k) is not None)
        links[body] = LinkMasses(body, part, hardware, total, names)
        origin, angle = link_frame(s, body)
        drawn[body] = total.moved(origin, angle)
    return MassModel(links, material, density, drawn, table.infill if material.made == "printed" else 1.0)


def _total(body: str, part: LinkMass | None, hardware: tuple[tuple[str, LinkMass], ...], given: Any,
           have_parts: bool) -> LinkMass:
    """The link's total: its part and hardware combined, with the given values in their place."""
    if not have_parts:
        missing = [k for k in ("mass", "centre", "inertia") if given is None or getattr(given, k) is None]
        if missing:
            said = missing[0] if len(missing) == 1 else f"{', '.join(missing[:-1])} and {missing[-1]}"
            raise SpecError(f"give its {said}: with no [parts] table there is no part to compute them from (or "
                            "add a [parts] table)", f"dynamics.links.{body}")
        return LinkMass(given.mass, tuple(given.centre), given.inertia)
    own = combined([m for m in ([part] if part is not None else [])] + [m for _, m in hardware])
    if given is None:
        return own
    mass = own.mass if given.mass is None else given.mass
    centre = own.centre if given.centre is None else tuple(given.centre)
    scaled = own.inertia * (mass / own.mass) if own.mass > 0 else 0.0
    inertia = scaled if given.inertia is None else given.inertia
    return LinkMass(mass, centre, inertia)


def _from_parts(table: DynamicsTable, analysis: Analysis, parts: PartsTable, stack: Stack | None,
                kit: KitTable | None, material: Material,
                density: float) -> dict[str, tuple[LinkMass, tuple[tuple[str, LinkMass], ...]]]:
    """Each moving link's part as made and the hardware of the pivots it carries (the link's frame)."""
    s = analysis.linkage.structure
    allowances = Allowances(kerf=parts.kerf, kerf_field="parts.kerf")
    fill = table.infill if material.made == "printed" else 1.0
    per_mm2 = density * PER_MM3 * parts.thickness * fill
    out: dict[str, tuple[LinkMass, tuple[tuple[str, LinkMass], ...]]] = {}
    for link in general_parts(analysis, parts):
        if link.name not in s.bodies or link.name == GROUND:
            continue
        made = allowances.cut(link) if material.made == "cut" else allowances.printed(link)
        section = part_section(made)
        out[link.name] = (LinkMass(per_mm2 * section.area, section.centroid,
                                   per_mm2 * section.polar_about_centroid), ())
    if stack is not None:
        for body, items in _hardware(table, analysis, parts, stack, kit).items():
            part, _ = out[body]
            out[body] = (part, items)
    return out


def _hardware(table: DynamicsTable, analysis: Analysis, parts: PartsTable, stack: Stack,
              kit: KitTable | None) -> dict[str, tuple[tuple[str, LinkMass], ...]]:
    """The pins (or bolts) and spacers of each pivot point that moves, as point masses (kg) at their joint in the
    frame of the first moving link that holds it."""
    s = analysis.linkage.structure
    t, d = parts.thickness, parts.pin_diameter
    pin = PINS[table.pins]
    out: dict[str, list[tuple[str, LinkMass]]] = {}
    inner, outer = stack.spacer_diameters
    for pivot in stack.pivots:
        if any(p not in s.bodies or p == GROUND for p in pivot.parts):
            continue                               # on the frame: it does not move
        point = _point_of(s, pivot.parts)
        body = next(p for p in pivot.parts if point in s.bodies[p])
        if kit is not None:
            mass = _bolt_mass(kit, (pivot.high - pivot.low + 1) * t)
        else:
            shank = math.pi * d**2 / 4 * (stack.top * t + 1.0) + math.pi * (0.9 * d) ** 2 * d / 2
            mass = shank * pin.density * PER_MM3
        items = [(f"{'bolt' if kit is not None else 'pin'} {point}", mass)]
        for joint, _, run, _ in stack.spacers:
            if joint in pivot.joints:
                ring = math.pi / 4 * (outer**2 - inner**2) * run * t
                items.append((f"spacer {point}", ring * SPACER.density * PER_MM3))
        origin, angle = link_frame(s, body)
        x, y = s.points[point]
        c, sn = math.cos(angle), math.sin(angle)
        local = (c * (x - origin[0]) + sn * (y - origin[1]), -sn * (x - origin[0]) + c * (y - origin[1]))
        out.setdefault(body, []).extend((what, LinkMass(m, local, 0.0)) for what, m in items)
    return {b: tuple(items) for b, items in out.items()}


def _point_of(s: Structure, parts: tuple[str, ...]) -> str:
    """The drawing's joint a pivot's pin is at: the point every one of its parts holds, else (a pin in a slot) the
    point of the slider between them."""
    held = [p for p in s.bodies[parts[0]] if all(p in s.bodies[b] for b in parts if b in s.bodies)]
    if held:
        return held[0]
    return next(sl.point for sl in s.sliders if {sl.body, sl.guide} <= set(parts))


def _bolt_mass(kit: KitTable, grip: float) -> float:
    """A kit pin's steel (kg): the ISO 4762 bolt of the shortest preferred length for ``grip`` mm, its head, the ISO
    4032 nut and the ISO 7089 washer."""
    bolt = kit.hardware
    length = bolt_length(bolt, grip)
    length = grip + bolt.washer_thickness + bolt.nut_height + 1.0 if math.isinf(length) else length
    d = bolt.diameter
    volume = (math.pi * d**2 / 4 * length + math.pi * bolt.head_diameter**2 / 4 * bolt.head_height
              + (math.sqrt(3) / 2 * bolt.nut_across_flats**2 - math.pi * d**2 / 4) * bolt.nut_height
              + math.pi / 4 * (bolt.washer_outside**2 - d**2) * bolt.washer_thickness)
    return volume * PINS["steel"].density * PER_MM3
