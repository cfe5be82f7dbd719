"""A machine's cam followers as parts of their own: each oscillating roller follower's arm and roller, cut and
printed as the machine's frame is (``<machine>-<cam>-arm.dxf|-cut.svg|.stl|.3mf``, ``<machine>-<cam>-roller...``),
listed in the machine's kit with the roller's axle bought, and the axle drawn in the assembly. No I/O.

The parts are the ones the clash check and the assembly place (:func:`camgen.kinds.machine.clash.machine_parts`):

* the arm: a bar of half the roller's radius round its ends, from the pivot (its origin) to the roller's centre
  (``follower.arm_length`` on +X), with the pivot pin's hole at its origin, the roller's axle hole at its far end
  and, where the arm is a coupled four-bar's crank, the crank pin's hole ``crank`` mm out along it; as thick as the
  clash check makes it (the cam's, or the four-bar's crank's);
* the roller: a disc of ``follower.roller_radius`` (a grooved cam's groove is wider by its running clearance) with
  the axle's hole, as thick as its cam, on the cam's plane;
* the axle: a bolt of :data:`AXLE_MM` (bought) from the roller's bottom face up through the arm.

Each hole is the pin's ISO 273 medium clearance hole (:func:`camgen.kinds.machine.frame.pin_hole`). The outlines
are exact (lines and arcs); the clash check's bodies are these outlines split into chords within the cam's
tolerance. A translating follower's stem, roller, flat face and guide rails are parts too
(:mod:`camgen.kinds.machine.stem_kit`), listed and written with these.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.bundle import Item, mesh_files, part_files
from camgen.core.hardware import BOLTS, bolt_length
from camgen.core.kit import BomLine, Plate, bolt_line
from camgen.core.parts import Allowances, Drawing, Part
from camgen.core.shapes import Contour, rounded_hull
from camgen.kinds.machine.flat_arm_part import FlatArmPart
from camgen.kinds.machine.slabs import Slab

#: the roller's axle (mm): an M4 bolt, as a follower's pivot pin where no linkage gives one
AXLE_MM = 4.0


def arm_outline(length: float, half_width: float) -> Contour:
    """A follower arm's outline (mm, its own frame): round ends of ``half_width`` about the pivot (0, 0) and the
    roller's centre (``length``, 0), counter-clockwise."""
    return rounded_hull(np.array([[0.0, 0.0], [length, 0.0]]), half_width)


def roller_outline(radius: float) -> Contour:
    """A roller's outline (mm): a circle of ``radius`` about its axle (0, 0), two exact half arcs."""
    return rounded_hull(np.zeros((1, 2)), radius)


def arm_holes(length: float | None, pivot_pin: float, pins: tuple[tuple[float, float], ...] = ()) -> tuple[
        tuple[tuple[float, float], float], ...]:
    """An arm's holes as (centre, radius) pairs (mm, its own frame): the pivot pin's (``pivot_pin`` mm across) at
    the origin, the roller's axle's at (``length``, 0) (none where ``length`` is None: a flat face's arm), and each
    of ``pins`` ((distance out along the arm, pin diameter) mm: a coupled crank's pin) unless it falls on one of
    these (within 1e-9 mm: the larger hole is kept)."""
    from camgen.kinds.machine.frame import pin_hole

    holes: dict[float, float] = {0.0: pin_hole(pivot_pin) / 2}
    axle = () if length is None else ((length, AXLE_MM),)
    for x, d in (*axle, *pins):
        key = next((k for k in holes if abs(k - x) <= 1e-9), x)
        holes[key] = max(holes.get(key, 0.0), pin_hole(d) / 2)
    return tuple(((x, 0.0), r) for x, r in holes.items())


def made_radius(cam_design: Any, radius: float) -> float:
    """The roller's radius as made (mm): the cam spec's ``follower.roller_radius``, which a grooved cam's follower
    (``radius``, its island's roller, grown by half the groove's running clearance) does not give."""
    return float(getattr(cam_design.spec.follower, "roller_radius", radius))


def roller_hole() -> tuple[tuple[float, float], float]:
    """The roller's axle hole: (centre, radius) mm."""
    from camgen.kinds.machine.frame import pin_hole

    return (0.0, 0.0), pin_hole(AXLE_MM) / 2


@dataclass(frozen=True)
class FollowerPart:
    """A follower's part: the clash check's and the assembly's ``body`` name (``cams.<cam>.arm``), what it is, and
    its nominal part maker ``plate`` (named ``<cam>-arm``, its own frame, holes at their nominal sizes)."""

    body: str
    what: str
    plate: Plate | Slab | FlatArmPart

    @property
    def key(self) -> str:
        """The report's key of its files (``<cam>_arm``: ``<cam>_arm_dxf``...)."""
        return self.plate.name.replace("-", "_")


def _oscillating(design: Any) -> list[tuple[Any, Any]]:
    """The machine's cams with an oscillating roller follower whose arm the clash check placed: (cam, follower)."""
    from camgen.followers.oscillating_roller import OscillatingRoller
    from camgen.kinds.machine.design import _cam_of

    names = {b.name for b in design.bodies}
    out = []
    for cam in design.cams:
        f = _cam_of(cam.design).follower
        if isinstance(f, OscillatingRoller) and f"cams.{cam.name}.arm" in names:
            out.append((cam, f))
    return out


def _flat_arms(design: Any, bodies: dict[str, Any], thick: dict[str, float]) -> list[FollowerPart]:
    """Each oscillating flat face's arm the clash check placed (:mod:`camgen.kinds.machine.flat_arm`), as its
    exact part: its holes the ones its body carries."""
    from camgen.followers.oscillating_flat import OscillatingFlat
    from camgen.kinds.machine.design import _cam_of
    from camgen.kinds.machine.flat_arm import arm_part, face_geometry

    out = []
    for cam in design.cams:
        f, arm = _cam_of(cam.design).follower, bodies.get(f"cams.{cam.name}.arm")
        if isinstance(f, OscillatingFlat) and arm is not None:
            far, side = face_geometry(cam.design, f)
            out.append(FollowerPart(arm.name, "follower arm", arm_part(
                f"{cam.name}-arm", far, side, arm.holes, thick[arm.name], float(cam.design.tolerance))))
    return out


def follower_parts(design: Any) -> tuple[FollowerPart, ...]:
    """Each oscillating follower's arm and roller of ``design`` (a
    :class:`~camgen.kinds.machine.design.MachineDesign`), in the cams' order, then each oscillating flat face's arm
    (:mod:`camgen.kinds.machine.flat_arm_part`), then each translating follower's
    parts (:func:`camgen.kinds.machine.stem_kit.stem_parts`): their outlines exact, their holes the ones the clash
    check's bodies carry, as thick as the assembly makes them; then each ratchet's wheel and pawls
    (:func:`camgen.kinds.machine.ratchet_parts.ratchet_parts`)."""
    from camgen.kinds.machine.frame import thicknesses

    thick = thicknesses(design)
    bodies = {b.name: b for b in design.bodies}
    out = []
    for cam, f in _oscillating(design):
        tol, name = float(cam.design.tolerance), f"cams.{cam.name}"
        arm, r = bodies[f"{name}.arm"], float(f.roller_radius)
        out.append(FollowerPart(arm.name, "follower arm", Plate(
            f"{cam.name}-arm", arm_outline(float(f.arm_length), r / 2), tuple((c, 2 * hr) for c, hr in arm.holes),
            thick[arm.name], tol)))
        roller = bodies[f"{name}.roller"]
        outline = roller_outline(made_radius(cam.design, r))
        out.append(FollowerPart(roller.name, "roller", Plate(
            f"{cam.name}-roller", outline, tuple((c, 2 * hr) for c, hr in roller.holes), thick[name], tol)))
    out += _flat_arms(design, bodies, thick)
    from camgen.kinds.machine.ratchet_parts import ratchet_parts
    from camgen.kinds.machine.stem_kit import stem_parts

    return (*out, *stem_parts(design), *ratchet_parts(design))


@dataclass(frozen=True)
class Axle:
    """A roller's axle in the assembly: its ``name`` (``cams.<cam>.axle``), its ``centre`` at the assembly's angle
    (mm), its ``bottom`` and ``top`` (mm, up from the bottom plate's bottom face: the roller's bottom face to the
    arm's top)."""

    name: str
    centre: tuple[float, float]
    bottom: float
    top: float

    def part(self, tolerance: float) -> Part:
        """The axle as a rod of :data:`AXLE_MM` as long as it stands."""
        return Part(self.name, roller_outline(AXLE_MM / 2).moved(0.0, np.asarray(self.centre)), (),
                    self.top - self.bottom, tolerance)


def axles(design: Any, stack: Any) -> tuple[Axle, ...]:
    """Each oscillating follower's roller axle placed at ``machine.assembly_angle`` on the planes of ``stack``
    (:class:`camgen.kinds.machine.frame.Stack`), then each translating roller's
    (:func:`camgen.kinds.machine.stem_kit.stem_axles`), then each ratchet's arm's pawl's pin
    (:func:`camgen.kinds.machine.ratchet_parts.pawl_pins`)."""
    from camgen.kinds.machine.frame import thicknesses

    thick = thicknesses(design)
    phi = np.array([math.radians(design.spec.machine.assembly_angle)])
    bodies = {b.name: b for b in design.bodies}
    out = []
    for cam, _ in _oscillating(design):
        roller, arm = bodies[f"cams.{cam.name}.roller"], bodies[f"cams.{cam.name}.arm"]
        centre = roller.place(phi)[1][0]
        out.append(Axle(f"cams.{cam.name}.axle", (float(centre[0]), float(centre[1])), stack.bottom[roller.low],
                        stack.bottom[arm.low] + thick[arm.name]))
    from camgen.kinds.machine.ratchet_parts import pawl_pins
    from camgen.kinds.machine.stem_kit import stem_axles

    return (*out, *stem_axles(design, stack), *pawl_pins(design, stack))


def bom_lines(design: Any, stack: Any) -> tuple[BomLine, ...]:
    """The kit's lines of the followers: each arm and roller (made, its own files), each axle (a bolt through the
    roller and the arm, bought; the bolt of :data:`AXLE_MM`), each ratchet's arm's pawl's pin as one."""
    lines = []
    for p in follower_parts(design):
        n = len(p.plate.holes)
        lines.append(BomLine(p.plate.name, 1, f"{p.what} of {p.body.rsplit('.', 1)[0]}, {p.plate.thickness:g} mm, "
                             f"{n} hole{'s' if n > 1 else ''} (its own files)", "laser or fdm"))
    bolt = next(b for b in BOLTS.values() if b.diameter == AXLE_MM)
    for a in axles(design, stack):
        what = "arm's pawl pin" if a.name.startswith("ratchets.") else "roller axle"
        lines.append(bolt_line(bolt, bolt_length(bolt, a.top - a.bottom), 1,
                               f"{what} {a.name} at ({a.centre[0]:.4g}, {a.centre[1]:.4g}) mm"))
    return tuple(lines)


def allowances(design: Any) -> Allowances:
    """The process allowances the followers are made with: the frame's, else ``output.kerf`` and
    ``output.clearance`` as the frame would take them."""
    if design.frame is not None:
        return design.frame.allowances
    out = design.spec.output
    return Allowances(out.kerf, out.clearance, "output.kerf", out.elephant_foot)


def follower_items(design: Any, formats: tuple[str, ...]) -> list[Item | None]:
    """Each follower part's files: cut (``<machine>-<cam>-arm.dxf`` and ``-cut.svg``, the kerf applied) and printed
    (``.stl``, ``.3mf``, the clearance applied)."""
    from camgen.core.solids import checked_mesh

    name, allow = design.spec.name, allowances(design)
    meshes = bool({"stl", "3mf"} & set(formats))
    items: list[Item | None] = []
    for p in follower_parts(design):
        stem = f"{name}-{p.plate.name}"
        items.append(part_files(Drawing.of_part(allow.cut(p.plate)), stem, p.key))
        items.append(mesh_files(checked_mesh(allow.printed(p.plate), stem)[0] if meshes else None, stem, p.key))
    return [i.only(formats) if i is not None else None for i in items]


def followers_report(design: Any) -> list[dict[str, Any]]:
    """The report's ``followers``: each part's name, the assembly's body it is, its thickness and its holes
    (centre and nominal diameter, mm in its own frame)."""
    return [{"name": p.plate.name, "body": p.body, "thickness_mm": p.plate.thickness,
             "holes": [{"x_mm": round(c[0], 9), "y_mm": round(c[1], 9), "nominal_mm": round(d, 9)}
                       for c, d in p.plate.holes]} for p in follower_parts(design)]

