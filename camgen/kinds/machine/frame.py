"""The machine's frame (``machine.frame``): one plate under the moving parts, or two (under and over them) held
apart by spacers, carrying every shaft and pivot pin. No I/O.

Every shaft sits in a seat: the ball bearing ``machine.bearing`` names (its outside diameter; its bore must be the
shaft's diameter, the smallest ``cam.bore`` on the shaft) or a plain hole the shaft runs in (the shaft's diameter
plus :data:`~camgen.core.hardware.RUNNING_PLAY`). Every pivot pin (a follower arm's pivot, a four-bar's rocker
pivot: the pins of the clash check, :func:`camgen.kinds.machine.clash.machine_parts`) goes through a hole: the ISO
273 medium clearance hole of the bolt of the pin's diameter (:data:`~camgen.core.hardware.BOLTS`), else the pin
plus the running play. The plate's outline is the rounded hull of every seat's centre at ``machine.frame_margin``.
The cut files carry a plate as a laser cuts it (``output.kerf``: outline grown and holes shrunk by half of it), the
printed ones as printed (``output.clearance``: holes opened by it), as :class:`~camgen.core.parts.Allowances` applies
them to every part.

A shaft stands in the bottom plate only (the parts over its cams, a four-bar's links, may cross its axis). A second
plate (``"two"``, the same outline) carries the pins that hang from it (a four-bar's rocker pivot) and, through a
spacer, every pin standing on the bottom plate: a printed tube :data:`SPACER_WALL_MM` thick round its pin, from the
top of the highest part on that pin up to the top plate, filling the planes between so that the clash check sees it.
"""
from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.hardware import BEARINGS, BOLTS, RUNNING_PLAY, Bearing
from camgen.core.kit import Plate
from camgen.core.parts import Allowances, Part
from camgen.core.shapes import rounded_hull
from camgen.kinds.machine.clash import Body, Joint, circle, fixed, still
from camgen.kinds.machine import barrel_parts, conjugate_parts

#: (mm) the least plate left between two holes, and between a hole and the plate's edge; a spacer's wall round its
#: pin's hole; the vertical gap between two planes of parts, and between the plates and the parts next to them
MIN_WALL_MM, SPACER_WALL_MM, PLANE_GAP_MM = 2.0, 3.0, 1.0
#: a shaft's diameter where no cam on it gives one (a shaft carrying only gears): the smallest cam bore of the
#: machine, else this (mm)
SHAFT_MM = 8.0


@dataclass(frozen=True)
class Seat:
    """A hole of the frame: what it carries (``shafts.<name>`` or ``pins.<i>``), its ``centre`` (mm, the machine's
    frame), the ``diameter`` of what it carries (mm), its nominal hole ``hole`` (mm) and the ``bearing`` in it
    (None: a plain hole, or a pin's); whether the bottom plate holds it and whether the top plate does."""

    name: str
    centre: tuple[float, float]
    diameter: float
    hole: float
    bearing: Bearing | None = None
    bottom: bool = True
    top: bool = False


@dataclass(frozen=True)
class Spacer:
    """A spacer of a two-plate frame: its ``name``, its pin's ``centre`` (mm), the planes ``low`` to ``high`` it
    fills, its ``outside`` diameter and its ``bore`` (mm)."""

    name: str
    pin: str
    centre: tuple[float, float]
    low: int
    high: int
    outside: float
    bore: float

    def body(self) -> Body:
        """The spacer as the clash check places it: a disc round its pin, fixed."""
        return Body(self.name, self.low, self.high, circle(self.outside / 2), fixed(self.centre))


@dataclass(frozen=True)
class Stack:
    """Heights (mm, up from the bottom plate's bottom face) of the clash check's planes: plane ``p``'s parts stand
    on ``bottom[p]`` and the thickest reaches ``top[p]``; plane ``roof`` is the top plate's (two plates). The
    planes of a linkage behind the frame (``side = "back"``) are negative, stacked down from the plate's bottom
    face."""

    thickness: float
    bottom: Mapping[int, float]
    top: Mapping[int, float]

    @property
    def roof(self) -> int:
        return max(self.bottom)


@dataclass(frozen=True)
class Frame:
    """A machine's frame: its nominal plates (part makers, holes at their nominal sizes: the bottom ``plate`` and a
    two-plate frame's ``top``, the same outline), its ``seats`` (each plate's holes are those of the seats it
    holds, in this order), the ``spacers`` (two plates), the plane heights ``stack`` and the process
    ``allowances``."""

    plate: Plate
    top: Plate | None
    seats: tuple[Seat, ...]
    spacers: tuple[Spacer, ...]
    stack: Stack
    allowances: Allowances
    margin: float

    @property
    def plates(self) -> tuple[Plate, ...]:
        """The bottom plate, and the top one of a two-plate frame."""
        return (self.plate,) if self.top is None else (self.plate, self.top)

    def cut(self, plate: Plate) -> Part:
        """``plate`` as its cut files carry it (kerf applied)."""
        return self.allowances.cut(plate)

    def printed(self, plate: Plate) -> Part:
        """``plate`` as its printed files carry it (clearance applied)."""
        return self.allowances.printed(plate)

    def spacer_heights(self) -> tuple[tuple[float, float], ...]:
        """Each spacer's bottom and top (mm): from the top of the parts of the plane under it (or the bottom plate)
        to the bottom of the plane over it (or the top plate)."""
        s = self.stack
        return tuple((s.top[sp.low - 1] if sp.low else s.thickness, s.bottom[sp.high + 1]) for sp in self.spacers)

    def spacer_parts(self) -> tuple[Plate, ...]:
        """Each spacer as a part maker: a disc of its outside diameter with its bore, as high as it stands."""
        from camgen.core.kit import disc

        return tuple(disc(sp.name.replace("spacers.", "spacer-"), sp.outside, sp.bore, top - bottom,
                          self.plate.tolerance)
                     for sp, (bottom, top) in zip(self.spacers, self.spacer_heights(), strict=True))


def pins(bodies: Sequence[Body]) -> list[tuple[str, tuple[float, float], float, int, int]]:
    """The clash check's pins among ``bodies``: (name, centre mm, diameter mm, lowest plane, highest plane)."""
    out = []
    for b in bodies:
        if b.name.startswith("pins."):
            centre = b.place(np.zeros(1))[1][0]
            out.append((b.name, (float(centre[0]), float(centre[1])), 2 * float(np.abs(b.outline).max()), b.low,
                        b.high))
    return out


def roof_plane(bodies: Sequence[Body]) -> int:
    """The top plate's plane: one over every moving part's (the plane the clash check hangs pins from)."""
    return max((b.high for b in bodies if not b.name.startswith(("pins.", "shafts.", "spacers."))), default=-1) + 1


def front_pins(bodies: Sequence[Body], joints: Sequence[Joint]) -> set[str]:
    """The pins among ``bodies`` that carry a part in front of the bottom plate (a part on a plane >= 0 meeting the
    pin in one of ``joints``): those a top plate can hold through a spacer. A pin of a linkage behind the frame
    alone (``side = "back"``) comes up through the bottom plate from below and carries nothing in front."""
    plane = {b.name: b.low for b in bodies if not b.name.startswith(("pins.", "spacers."))}
    out = set()
    for j in joints:
        for pin, part in ((j.a, j.b), (j.b, j.a)):
            if pin.startswith("pins.") and plane.get(part, -1) >= 0:
                out.add(pin)
    return out


def spacers(bodies: Sequence[Body], joints: Sequence[Joint]) -> tuple[Spacer, ...]:
    """A spacer round each pin standing on the bottom plate or passing through it (its lowest plane 0 or behind
    the frame) that carries a part in front (:func:`front_pins`): the planes from the one over the pin's highest
    part to the one under the top plate (none where its part is the highest: then it is :data:`PLANE_GAP_MM`
    high). A pin of the back side alone has none: it stands in the bottom plate, as with one plate."""
    roof = roof_plane(bodies)
    front = front_pins(bodies, joints)
    out: list[Spacer] = []
    for name, centre, diameter, low, high in pins(bodies):
        if low <= 0 and high < roof and name in front:
            bore = diameter + RUNNING_PLAY
            out.append(Spacer(f"spacers.{len(out)}", name, centre, high + 1, roof - 1, bore + 2 * SPACER_WALL_MM,
                              bore))
    return tuple(out)


def spacer_joints(found: Sequence[Spacer]) -> list[Joint]:
    """Each spacer meets its pin by design (the pin runs through it)."""
    return [Joint(s.name, s.pin, still(s.centre), 1.01 * s.outside / 2 + 0.05) for s in found]


def shaft_diameters(spec: Any) -> dict[str, float]:
    """Each shaft's diameter (mm): the smallest ``cam.bore`` of the cams on it (a Geneva drive's ``driver_bore`` or
    ``wheel_bore`` among them); a shaft without a cam, the
    smallest bore of the shaft-driven linkages' cranks on it (their ``parts.pin_diameter``: a crank bar
    ``parts.width`` wide has no room for a larger bore, so the shaft is the crank's bore); a shaft carrying
    neither takes the smallest bore of the machine's cams (:data:`SHAFT_MM` without any)."""
    bores: dict[str, list[float]] = {}
    for mount, cam_spec in zip(spec.cams, spec.cam_specs, strict=True):
        bore = getattr(cam_spec.cam, "bore", None)
        if bore:
            bores.setdefault(mount.shaft, []).append(float(bore))
    for mount, drive in zip(getattr(spec, "genevas", ()), getattr(spec, "geneva_specs", ()), strict=True):
        for shaft, bore in ((mount.driver, drive.geneva.driver_bore), (mount.wheel, drive.geneva.wheel_bore)):
            if bore:                                        # a Geneva drive's bores: its shafts'
                bores.setdefault(shaft, []).append(float(bore))
    least = min((min(b) for b in bores.values()), default=SHAFT_MM)
    cranks: dict[str, list[float]] = {}
    for mount, linkage_spec in zip(spec.linkages, spec.linkage_specs, strict=True):
        parts = getattr(linkage_spec, "parts", None)
        if getattr(mount, "shaft", None) and parts is not None:
            cranks.setdefault(mount.shaft, []).append(float(parts.pin_diameter))
    return {s.name: min(bores.get(s.name) or cranks.get(s.name) or [least]) for s in spec.shafts}


def pin_hole(diameter: float) -> float:
    """The frame's hole (mm, nominal) for a pin of ``diameter`` mm: the ISO 273 medium clearance hole of the bolt
    of that diameter, else the pin plus the running play."""
    bolt = next((b for b in BOLTS.values() if b.diameter == diameter), None)
    return bolt.clearance_hole if bolt is not None else diameter + RUNNING_PLAY


def seats(spec: Any, bodies: Sequence[Body], joints: Sequence[Joint]) -> tuple[Seat, ...]:
    """Every shaft's seat and every pin's hole, shafts first (in ``[[shafts]]``' order), each once: a shaft in the
    bottom plate, a pin in the plate it stands on or hangs from, and in the top plate too when a spacer stands
    round it.

    Raises
    ------
    SpecError
        Naming ``machine.bearing``: a bearing whose bore is not a shaft's diameter.
    """
    bearing = None if spec.machine.bearing == "none" else BEARINGS[spec.machine.bearing]
    out = []
    for shaft in spec.shafts:
        d = shaft_diameters(spec)[shaft.name]
        if bearing is not None and bearing.bore != d:
            fits = [b.name for b in BEARINGS.values() if b.bore == d] + ["none"]
            raise SpecError(f"a {bearing.name} bearing has a {bearing.bore:g} mm bore; shaft {shaft.name} is {d:g} mm "
                            f"(the smallest cam.bore on it): give one of {', '.join(fits)}", "machine.bearing")
        hole = bearing.outside if bearing is not None else d + RUNNING_PLAY
        out.append(Seat(f"shafts.{shaft.name}", (float(shaft.at[0]), float(shaft.at[1])), d, hole, bearing))
    roof = roof_plane(bodies)
    spaced = {sp.pin for sp in spacers(bodies, joints)} if spec.machine.frame == "two" else set()
    out += [Seat(name, centre, d, pin_hole(d), None, low <= 0, high == roof or name in spaced)
            for name, centre, d, low, high in pins(bodies)]
    return tuple(out)


def _check(found: tuple[Seat, ...], margin: float) -> None:
    """Refuse a margin that leaves less than :data:`MIN_WALL_MM` round the largest hole, and two holes with less
    than that between them."""
    need = max(s.hole for s in found) / 2 + MIN_WALL_MM
    if margin < need:
        raise SpecError(f"at least {need:g} mm (the largest seat's radius + {MIN_WALL_MM:g} mm of wall; got "
                        f"{margin:g} mm), at most 200 mm", "machine.frame_margin")
    for a, b in itertools.combinations(found, 2):
        left = math.dist(a.centre, b.centre) - (a.hole + b.hole) / 2
        if left < MIN_WALL_MM:
            raise SpecError(f"the holes of {a.name} and {b.name} leave {left:.3g} mm of plate between them (at least "
                            f"{MIN_WALL_MM:g} mm): move a shaft or a pivot", "machine.frame")


def stack(spec: Any, design: Any, bodies: Sequence[Body]) -> Stack:
    """The heights of the clash check's planes (see :class:`Stack`): the bottom plate ``machine.frame_thickness``
    thick, then each plane :data:`PLANE_GAP_MM` over the one under it and as high as its thickest part (a plane of
    pins, rollers and spacers alone is 0 high), the top plate's plane last."""
    t = spec.machine.frame_thickness
    thick = thicknesses(design)
    roof = roof_plane(bodies)
    floor = min((b.low for b in bodies), default=0)
    high = dict.fromkeys(range(min(floor, 0), roof + 1), 0.0)
    for b in bodies:
        if b.low == b.high and b.name in thick:
            high[b.low] = max(high[b.low], thick[b.name])
    bottom: dict[int, float] = {}
    top: dict[int, float] = {}
    z = t
    for p in range(0, roof + 1):
        bottom[p], top[p] = z + PLANE_GAP_MM, z + PLANE_GAP_MM + high[p]
        z = top[p]
    z = 0.0
    for p in range(-1, min(floor, 0) - 1, -1):                    # behind the frame: down from its bottom face
        top[p], bottom[p] = z - PLANE_GAP_MM, z - PLANE_GAP_MM - high[p]
        z = bottom[p]
    return Stack(t, dict(sorted(bottom.items())), dict(sorted(top.items())))


def thicknesses(design: Any) -> dict[str, float]:
    """Each flat moving part's thickness (mm) by its clash-check name: a cam's, its follower arm's or stem's (the
    cam's, or the crank's of the four-bar it drives), a four-bar's coupler and rocker and every moving link of a
    shaft- or follower-driven general linkage (their parts'), each gear and hub of a gear pair, and each ratchet's
    wheel and pawls (their arm's)."""
    out: dict[str, float] = {}
    for cam in design.cams:
        for suffix, part in conjugate_parts.plates(cam.design):      # a conjugate pair's two plates
            out[f"cams.{cam.name}{suffix}"] = out[f"cams.{cam.name}.arm"] = float(part.thickness)
        if conjugate_parts.is_conjugate(cam.design):
            out[f"cams.{cam.name}.yoke"] = out[f"cams.{cam.name}"]
    for m in design.linkages:
        build = m.design.build
        if build is None:
            continue
        cut = {p.name: p for p in build.cut}
        for which in ("coupler", "rocker"):
            out[f"linkages.{m.name}.{which}"] = float(cut[which].thickness)
        out[f"cams.{m.cam}.arm"] = float(cut["crank"].thickness)
    for m in (*getattr(design, "cranked", ()), *getattr(design, "slid", ())):   # a shaft's or a follower's linkage
        if m.design.build is None:
            continue
        for part in m.design.build.cut:
            if part.name != "ground":
                out[f"linkages.{m.name}.{part.name}"] = float(part.thickness)
    out.update(barrel_parts.thicknesses(design))                # a barrel's drum: as long as it is
    for cam in design.cams:                                     # a translating follower's stem: as its cam
        if f"cams.{cam.name}" in out:
            out[f"cams.{cam.name}.stem"] = out[f"cams.{cam.name}"]
    from camgen.kinds.machine.machine_gears import thicknesses as gear_thicknesses

    out.update(gear_thicknesses(design))
    from camgen.kinds.machine.geneva_bodies import thicknesses as geneva_thicknesses

    out.update(geneva_thicknesses(design))
    from camgen.kinds.machine.ratchet_bodies import thicknesses as ratchet_thicknesses

    out.update(ratchet_thicknesses(design, out))
    return out


#: the mount names that the machine's own files take (``<machine>-frame.dxf``, ``<machine>-assembly.3mf``...)
RESERVED = ("frame", "frame-top", "kit", "assembly")


def check_names(spec: Any) -> None:
    """Refuse a cam or linkage named as the machine's own files are (:data:`RESERVED`, ``spacer-<i>``): their files
    would be the same."""
    for key, mounts in (("cams", spec.cams), ("linkages", spec.linkages), ("ratchets", spec.ratchets)):
        for i, mount in enumerate(mounts):
            if mount.name in RESERVED or mount.name.startswith("spacer-"):
                raise SpecError(f"{mount.name!r} names the machine's own files (<machine>-{mount.name}...): give the "
                                "mount another name", f"{key}[{i}].name")


def machine_frame(design: Any, bodies: Sequence[Body], joints: Sequence[Joint]) -> Frame | None:
    """The frame ``machine.frame`` asks for (None for ``"none"``), its pins those of the clash check's ``bodies``
    (with a two-plate frame's spacers among them) and ``joints``.

    Raises
    ------
    SpecError
        Naming ``machine.frame_margin``, ``machine.frame`` or ``machine.bearing``: a margin that leaves too little
        round a hole, two holes too close, a bearing that does not fit a shaft, two plates without a pin to stand
        a spacer on.
    """
    spec = design.spec
    table = spec.machine
    if table.frame == "none":
        return None
    found = seats(spec, bodies, joints)
    _check(found, table.frame_margin)
    outline = rounded_hull(np.array([s.centre for s in found]), table.frame_margin)
    tol = min((*(float(c.design.tolerance) for c in design.cams),        # a machine of shaft-driven linkages only
               *(float(m.design.spec.parts.tolerance) for m in getattr(design, "cranked", ()))))
    plate = Plate("frame", outline, tuple((s.centre, s.hole) for s in found if s.bottom), table.frame_thickness, tol)
    kept = spacers(bodies, joints) if table.frame == "two" else ()
    if table.frame == "two" and not kept:
        raise SpecError("two plates need a pin standing on the bottom plate with room over it for a spacer (none "
                        'here): set machine.frame = "one"', "machine.frame")
    top = Plate("frame-top", outline, tuple((s.centre, s.hole) for s in found if s.top), table.frame_thickness,
                tol) if kept else None
    allow = Allowances(spec.output.kerf, spec.output.clearance, "output.kerf", spec.output.elephant_foot)
    return Frame(plate, top, found, kept, stack(spec, design, bodies), allow, table.frame_margin)


def with_top_plate(bodies: Sequence[Body], joints: Sequence[Joint]) -> tuple[tuple[Body, ...], tuple[Joint, ...]]:
    """The clash check's ``bodies`` and ``joints`` with a top plate: the :func:`spacers` round the pins standing on
    the bottom plate, each meeting its pin. (A shaft stays in the bottom plate only: the parts over its cams, a
    four-bar's links, may cross its axis.)"""
    found = spacers(bodies, joints)
    return (*bodies, *(s.body() for s in found)), (*joints, *spacer_joints(found))
