"""The barrel (cylindrical) cam's template: its ``[cam]`` table (:class:`BarrelTable`, ``kind = "barrel"``: the
cylinder and its groove or rib, :class:`Cylinder`) and its spec (:class:`BarrelSpec`: a roller on the pitch cylinder,
developed flat as a plate cam's), with the rules of its geometry: the groove's floor holding the roller, the bore
inside it, the length holding the travel, an arm's chordal error, a rib's rollers.

The cylinder is ``cam.length`` long with the groove ``cam.groove_depth`` deep about the pitch cylinder of
radius ``cam.pitch_radius`` (the groove's mid-depth); the roller's centre runs on the pitch cylinder at
z = z0 + s, z0 putting the groove in the middle of the length. Developed (x = Rm theta) the pitch curve is
a plate cam's of travel 2 pi Rm, so the pressure angle is atan(s' / Rm).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any, ClassVar, Literal

from pydantic import ConfigDict, Field

from camgen.core.features import KEYS, bore_reach
from camgen.core.spec import Model, length, notes, unit
from camgen.followers.barrel import BarrelGeometry, DevelopedRoller
from camgen.followers.plate import PlateRoller
from camgen.rig import Mount, developed_mount
from camgen.spec import CamSpec
from camgen.tables import Speeds
from camgen.tables.followers import BarrelFollower


class Cylinder(Model):
    """A barrel's cylinder and its groove (or rib), its bore and its sense of rotation."""

    pitch_radius: float = length("the radius of the pitch cylinder, the groove's mid-depth")
    groove_depth: float = length(
        "the depth of the groove about the pitch cylinder (a rib's height)",
        allowed="the floor, pitch_radius - groove_depth / 2 from the axis, wider than the roller there (roller_radius "
                "+ running_clearance / 2 for a cylindrical roller) and outside the bore as printed")
    running_clearance: float = length("the groove's width less the roller's diameter", 0.2, zero=True, le=100.0)
    bore: float = length("bore diameter, 0 for none", 0.0, zero=True,
                         allowed="leaving material: inside the groove's floor, as printed")
    max_pressure_angle: float | None = Field(None, ge=1, lt=90, description="pressure-angle limit of the report's "
                                             "check (default 30, oscillating 40)",
                                             json_schema_extra=unit("degrees", absent="30; 40 for an oscillating "
                                                                    "follower"))
    barrel_form: Literal["groove", "rib"] = Field("groove", description="a groove the roller runs in, or a rib (a "
                                                  "ridge) between two rollers",
                                                  json_schema_extra=notes(allowed="a rib: a translating-roller "
                                                                          "follower with cylindrical rollers"))
    rib_width: float | None = length("a rib's axial width where the track runs level (the rollers' centres are "
                                     "rib_width + 2 roller_radius + running_clearance apart)", None,
                                     allowed="the rib keeps a width where the track is steepest",
                                     absent="required for a rib")
    rotation: Literal["ccw", "cw"] = Field("ccw", description="sense of rotation seen from +Z")
    length: float = length("the cylinder's axial length",
                           allowed="> the follower's travel + the groove's width at the rim (2 roller_radius "
                                   "+ running_clearance for a cylindrical roller); an arm: > 2 arm_length "
                                   "sin(swing / 2) + that width; a rib: > the travel + rib_width + 2 (2 "
                                   "roller_radius + running_clearance)")


class BarrelTable(Speeds, Cylinder):
    """A barrel (cylindrical) cam: a groove (or a rib) round a cylinder, sized by ``pitch_radius`` and ``length``."""

    model_config = ConfigDict(title="a barrel cam")

    kind: Literal["barrel"] = Field(description="cam kind")


def geometry(spec: Any) -> BarrelGeometry:
    """The barrel's geometry from the template's tables (:class:`~camgen.followers.barrel.BarrelGeometry`)."""
    return BarrelGeometry.of(spec.cam, spec.follower, spec.motion)


def _check_arm(spec: Any, g: BarrelGeometry, room: float, rw: float) -> None:
    """An arm's swing, stroke and chordal error fit the cylinder and the groove: ``room`` (mm) is how far the roller's
    axis may pass the cam's axis (the floor's radius less the cutter's there), ``rw`` the groove's half-width."""
    f, turn = spec.follower, g.swing
    if not turn < 180:
        raise ValueError(f"motion: an arm on a barrel cam swings less than 180 degrees in all (got {turn:.6g})")
    stroke = 2 * f.arm_length * math.sin(math.radians(turn / 2))
    if not spec.cam.length > stroke + 2 * rw:
        raise ValueError(f"cam.length: must be > {stroke + 2 * rw:.6g} mm, the roller's axial stroke 2 arm_length "
                         f"sin(swing / 2) and the groove's width (got {spec.cam.length:g})")
    low, high = f.arm_length - room, f.arm_length * math.cos(math.radians(turn / 2)) + room
    if not low < high:
        most = 2 * room / (1 - math.cos(math.radians(turn / 2)))
        raise ValueError(f"follower.arm_length: must be < {most:.6g} mm, so the arm's chordal error (half of "
                         f"arm_length (1 - cos(swing / 2)) at best) leaves the roller in the groove (got "
                         f"{f.arm_length:g})")
    if not low < f.pivot_distance < high:
        best = f.arm_length * (1 + math.cos(math.radians(turn / 2))) / 2
        raise ValueError(f"follower.pivot_distance: must be over {low:.6g} and under {high:.6g} mm, so the roller's "
                         "axis passes the cam's axis (the arm's chordal error) by less than the groove's floor radius "
                         f"less the roller's; the error is least at {best:.6g} mm (got {f.pivot_distance:g})")


def check(spec: Any) -> None:
    """The barrel's rules across its tables and of its geometry (:meth:`BarrelSpec.kind_rules`)."""
    cam, follower = spec.cam, spec.follower
    if follower.oscillating and follower.orientation is not None:
        raise ValueError("follower.orientation: not modelled for a barrel's arm (it swings in a plane through the "
                         "cam's axis): give the weights as follower.load, or leave them out")
    if "material" in cam.model_fields_set and (cam.rpm is None or follower.mass is None):
        raise ValueError("cam.material: a barrel cam's contact pressure is at cam.rpm with follower.mass; give both")
    for key in sorted(spec.hub.model_fields_set - {"keyway"}):
        raise ValueError(f"hub.{key}: not used by a barrel cam (it takes cam.bore and hub.keyway)")
    if spec.output.kerf:
        raise ValueError("output.kerf: a barrel cam is printed; its drawing is a developed template, not a cut file")
    floor = cam.pitch_radius - cam.groove_depth / 2
    if follower.roller_shape == "conical" and not follower.roller_radius < cam.pitch_radius:
        raise ValueError(f"follower.roller_radius: a conical roller's must be < cam.pitch_radius = "
                         f"{cam.pitch_radius:g} mm, its apex on the cam's axis (got {follower.roller_radius:g})")
    g = geometry(spec)
    _check_floor(spec, g, floor)
    _check_bore(spec, g, floor)
    widest = g.cutter_at(cam.pitch_radius + cam.groove_depth / 2)          # the groove's half-width at the rim
    if _rib(spec, g, widest):
        return
    if follower.oscillating:
        _check_arm(spec, g, floor - g.cutter_at(floor), widest)
    elif not g.rest_height > widest:
        travel = cam.length - 2 * g.rest_height
        raise ValueError(f"cam.length: must be > {travel + 2 * widest:.6g} mm, the follower's travel and the groove's "
                         f"width (got {cam.length:g})")


def _limit(fits: Any, good: float, bad: float) -> float:
    """Where ``fits`` (true at ``good``, false at ``bad``, changing once between) stops holding, to 1e-12 or so of
    the span: the last value found on the good side."""
    for _ in range(80):
        mid = (good + bad) / 2
        good, bad = (mid, bad) if fits(mid) else (good, mid)
    return good


def _check_floor(spec: Any, g: BarrelGeometry, floor: float) -> None:
    """The groove's floor (a rib's core) wider than the cutter there. Refused naming cam.groove_depth (with the pitch
    radius that would do); where no depth will do (the roller as wide as the pitch cylinder), follower.roller_radius;
    where no roller will do either, cam.pitch_radius."""
    cam, follower = spec.cam, spec.follower
    least = g.floor_room
    if floor > least:
        return
    what = "the rib's core" if cam.barrel_form == "rib" else "the groove's floor"

    def fits_pitch(radius: float) -> bool:
        return radius - cam.groove_depth / 2 > dataclasses.replace(g, pitch_radius=radius).floor_room

    def fits_roller(radius: float) -> bool:
        return floor > dataclasses.replace(g, roller_radius=radius).floor_room

    pitch = _limit(fits_pitch, 2 * cam.pitch_radius + cam.groove_depth + 4 * least, cam.pitch_radius)
    if cam.pitch_radius > least:
        raise ValueError(f"cam.groove_depth: must be < {2 * (cam.pitch_radius - least):.6g} mm, so {what} "
                         f"(cam.pitch_radius - groove_depth / 2 from the axis) stays wider than the roller there, "
                         f"{least:.6g} mm (got {cam.groove_depth:g}); or cam.pitch_radius > {pitch:.6g} mm")
    if fits_roller(1e-9 * follower.roller_radius):
        most = _limit(fits_roller, 1e-9 * follower.roller_radius, follower.roller_radius)
        raise ValueError(f"follower.roller_radius: must be < {most:.6g} mm, so the roller fits on {what}, "
                         f"cam.pitch_radius - groove_depth / 2 = {floor:.6g} mm from the axis (got "
                         f"{follower.roller_radius:g})")
    raise ValueError(f"cam.pitch_radius: must be > {pitch:.6g} mm, so {what} (cam.pitch_radius - groove_depth / 2 "
                     f"from the axis) holds the roller, {least:.6g} mm there (got {cam.pitch_radius:g})")


def _largest_bore(spec: Any, floor: float) -> tuple[float, bool]:
    """The largest bore (mm) that reaches less far than ``floor`` as printed, and whether that value itself is
    allowed (a keyed bore at the top of a key's range) or only those below it."""
    room = floor - spec.output.clearance / 2
    if not spec.hub.keyway:
        return 2 * room, False
    best = (0.0, False)
    for low, high, _, t2 in KEYS:
        if 2 * (room - t2) > high:
            best = (float(high), True)
        elif 2 * (room - t2) > low:
            best = (2 * (room - t2), False)
    return best


def _check_bore(spec: Any, g: BarrelGeometry, floor: float) -> None:
    """The bore as printed (grown by output.clearance / 2, with its keyway's seat where hub.keyway is set) inside
    the groove's floor (a rib's core). Refused naming cam.bore with the largest bore that leaves material there, and
    the depth of groove that would; where no bore will do, hub.keyway (no keyed bore fits) or output.clearance (the
    clearance alone reaches the floor). A thin wall is the design's warning."""
    cam = spec.cam
    reach = bore_reach(cam.bore, spec.hub.keyway, spec.output.clearance)
    if reach < floor:
        return
    what = "the rib's core" if cam.barrel_form == "rib" else "the groove's floor"
    where = f"{what}, cam.pitch_radius - groove_depth / 2 = {floor:.6g} mm from the axis"
    most, inclusive = _largest_bore(spec, floor)
    plain = 2 * (floor - spec.output.clearance / 2)
    if plain <= 0:
        raise ValueError(f"output.clearance: must be < {2 * floor - cam.bore:.6g} mm, so the bore as printed (its "
                         f"diameter grown by the clearance) stays inside {where} (got {spec.output.clearance:g})")
    if spec.hub.keyway and most <= KEYS[0][0]:
        raise ValueError(f"hub.keyway: no keyed bore (DIN 6885-1: over {KEYS[0][0]} mm) fits inside {where}; leave "
                         f"the keyway out (a plain bore must be < {plain:.6g} mm)")
    deeper = 2 * (cam.pitch_radius - reach)
    also = (f"; or cam.groove_depth < {deeper:.6g} mm" if deeper > 0 and cam.pitch_radius - deeper / 2 >
            g.floor_room else "")
    seat = ", and its keyway's seat" if spec.hub.keyway else ""
    limit = f"at most {most:.6g}" if inclusive else f"< {most:.6g}"
    raise ValueError(f"cam.bore: must be {limit} mm, so the bore (its radius grown by output.clearance / 2{seat}: "
                     f"{reach:.6g} mm from the axis) stays inside {where} (got {cam.bore:g}){also}")


def _rib(spec: Any, g: BarrelGeometry, rw: float) -> bool:
    """A rib's keys checked (True), or False for a groove: its width given, a translating cylindrical roller, and
    the length holding the rib and both rollers (``rw`` the rollers' reach beyond their axes)."""
    cam, follower = spec.cam, spec.follower
    if cam.barrel_form != "rib":
        if cam.rib_width is not None:
            raise ValueError('cam.rib_width: only for a barrel rib (cam.barrel_form = "rib")')
        return False
    if cam.rib_width is None:
        raise ValueError("cam.rib_width: required for a barrel rib (mm, > 0): the rib's axial width where the track "
                         "runs level")
    if follower.oscillating or follower.roller_shape != "cylindrical":
        raise ValueError("cam.barrel_form: a rib takes a translating-roller follower with cylindrical rollers (got "
                         f"{follower.type}, {follower.roller_shape})")
    travel, span = cam.length - 2 * g.rest_height, g.rib_span
    assert span is not None                         # a rib with its width: its span is known
    need = travel + 2 * (span + rw)
    if not cam.length > need:
        raise ValueError(f"cam.length: must be > {need:.6g} mm, the follower's travel, the rib and both rollers "
                         f"(got {cam.length:g})")
    return True


class BarrelSpec(CamSpec):
    """A barrel cam's template (``cam.kind = "barrel"``), validated."""

    cam: BarrelTable
    follower: BarrelFollower

    noun: ClassVar[str] = "a barrel cam"  # its table's title

    def kind_rules(self) -> None:
        check(self)

    def mount(self) -> Mount:
        """The roller on the developed pitch cylinder (:func:`camgen.rig.developed_mount`)."""
        return developed_mount(self.follower, geometry(self))

    def follower_at(self, base_radius: Any, roller_radius: float) -> PlateRoller | DevelopedRoller:
        """The developed pitch curve on the pitch cylinder (:meth:`~camgen.followers.barrel.BarrelGeometry.developed`):
        a plate cam of travel 2 pi Rm whose roller centre runs at z0 + s, or where an arm's roller's axis pierces the
        pitch cylinder. A barrel has no base radius (``base_radius`` is not used): the developed plate's height under
        the roller is z0 - Rr."""
        g = geometry(self)
        return g.developed(g.rest_height - roller_radius, roller_radius)

    def rest_height(self, roller_radius: float) -> float:
        """The developed plate's height under the roller (mm): z0 - Rr, as :func:`design_barrel` builds it."""
        return geometry(self).rest_height - roller_radius
