"""Each cam kind's ``[cam]`` table, built from the pieces the kinds share.

A kind's table declares the keys it takes and nothing else (``extra="forbid"``), so a key of another kind is
refused by the model itself, in one line naming the key and this kind (its ``title``) and listing what it takes.
The pieces are mixins: :class:`FlatSize` (a cam cut from a flat plate: its base radius and thickness),
:class:`Turning` (a bore and a sense of rotation) and :class:`Limits` (sizing limits), the three together
:class:`FlatBody`; :class:`Speeds` (its speed and material); :class:`GrooveBody` (a grooved cam's groove); and the
barrel's and the conjugate pair's own, :class:`Cylinder` and :class:`SecondCam`. Keys a kind needs are required,
not optional; the rules that tie a key to another table (a groove shallower than the plate, a bore inside the
groove's floor) are the kind's checks (:attr:`camgen.kinds.shared.SharedTableKind.check`).
"""
from __future__ import annotations

import math
from typing import Any, Literal

from pydantic import ConfigDict, Field, field_validator

from camgen.contact_stress import MaterialName
from camgen.core.spec import MAX_LENGTH_MM, Model, length, notes, unit

#: a cam's (or a follower's) material, for the contact pressure (:data:`camgen.contact_stress.MATERIALS`)
Material = MaterialName


def _auto_radius(value: Any) -> Any:
    """A radius in mm or ``"auto"``, checked: a ValueError saying what is allowed otherwise."""
    if value == "auto":
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f'must be a number of mm or "auto" (got {value!r})')
    if not (math.isfinite(value) and 0 < value <= MAX_LENGTH_MM):
        raise ValueError(f'must be > 0 and <= {MAX_LENGTH_MM:g} mm, or "auto" (got {value!r})')
    return float(value)


class Speeds(Model):
    """A cam's speed (for velocities, accelerations, forces and contact) and its material."""

    rpm: float | None = Field(None, gt=0, le=100_000, description="cam speed for velocities, accelerations and "
                              "contact", json_schema_extra=unit("rpm"))
    material: Material | None = Field(None, description="the cam's material, for the contact pressure")
    rpm_range: tuple[float, float] | None = Field(
        None, description="[lowest, highest] cam speed of the report's speeds table and figure",
        json_schema_extra=unit("rpm", allowed="0 < lowest < highest <= 100000; needs cam.rpm and follower.mass"))
    rpm_steps: int = Field(21, ge=2, le=201, description="speeds evenly spaced over cam.rpm_range (both ends; the "
                           "lift-off speed is added where it lies inside)")


class Limits(Model):
    """The sizing limits of a cam whose base radius may be ``"auto"``: its pressure angle and its least convex
    radius."""

    max_pressure_angle: float | None = Field(None, ge=1, lt=90, description="pressure-angle limit for sizing "
                                             "(default 30, oscillating 40)",
                                             json_schema_extra=unit("degrees", absent="30; 40 for an oscillating "
                                                                    "follower"))
    min_rho_margin: float = length("sizing: least convex radius of the cam surface", 0.0, zero=True)


class FlatSize(Model):
    """A cam cut from a flat plate: its base radius (or ``"auto"``), its thickness and whether an undercut is cut
    as the cutter's envelope."""

    base_radius: float | Literal["auto"] = Field(
        description="base circle radius, or \"auto\" for the smallest that meets the limits",
        json_schema_extra=unit("mm", allowed=f"a number > 0 and <= {MAX_LENGTH_MM:g}; \"auto\": the smallest that "
                               "meets max_pressure_angle and min_rho_margin"))
    thickness: float = length("plate thickness (STL extrusion)", le=1000.0)
    allow_undercut: bool = Field(False, description="export the cutter's envelope instead of refusing an undercut")

    @field_validator("base_radius", mode="before")
    @classmethod
    def _radius(cls, value: Any) -> Any:
        return _auto_radius(value)


class Turning(Model):
    """A cam turning on a shaft: its bore and its sense of rotation."""

    bore: float = length("bore diameter, 0 for none", 0.0, zero=True, allowed="leaving material: inside the outline")
    rotation: Literal["ccw", "cw"] = Field("ccw", description="sense of rotation seen from +Z")


class FlatBody(Limits, Turning, FlatSize):
    """A disc cut from a flat plate, turning on a shaft: the body a disc, a grooved and a conjugate cam share."""


class GrooveBody(Model):
    """A grooved face cam's groove: its depth in the face, the roller's running clearance and the rim outside it."""

    groove_depth: float = length("the depth of the groove the roller runs in (< thickness)",
                                 allowed="< cam.thickness")
    running_clearance: float = length("the groove's width less the roller's diameter", 0.2, zero=True, le=100.0)
    rim: float = length("wall outside the groove's outer flank", 5.0)


class DiscTable(Speeds, FlatBody):
    """A disc cam: a plate turning about its centre, cut to a profile."""

    model_config = ConfigDict(title="a disc cam")

    kind: Literal["disc"] = Field("disc", description="cam kind")


class PlateTable(Speeds, Limits, FlatSize):
    """A plate (linear) cam: a plate sliding along +X as the program runs, cut to a profile; ``base_radius`` is its
    height under the profile. It does not turn, so it has no bore and no sense of rotation."""

    model_config = ConfigDict(title="a plate cam")

    kind: Literal["plate"] = Field(description="cam kind")
    travel: float = length("the distance the plate slides over the program's 360 degrees")

    @property
    def bore(self) -> float:
        """A plate has no bore (mm)."""
        return 0.0

    @property
    def rotation(self) -> Literal["ccw"]:
        """A plate does not turn; its program runs as it slides along +X, as a counter-clockwise disc's does."""
        return "ccw"


class GroovedTable(Speeds, GrooveBody, FlatBody):
    """A grooved face cam: a disc whose face carries a groove the roller runs in, driving it both ways."""

    model_config = ConfigDict(title="a grooved cam")

    kind: Literal["grooved"] = Field(description="cam kind")


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


class SecondCam(Model):
    """A conjugate pair's second cam and how its roller is placed."""

    second_base_radius: float | Literal["auto"] | None = Field(
        None, description="the second cam's base circle radius (default: base_radius), or \"auto\"",
        json_schema_extra=unit("mm", allowed=f"a number > 0 and <= {MAX_LENGTH_MM:g}, within the second roller's "
                               "reach on its side of the cam; \"auto\": the smallest that meets max_pressure_angle and "
                               "min_rho_margin; not with yoke_span or arm_angle", absent="cam.base_radius"))
    yoke_span: float | None = length("translating yoke: distance between the two rollers' centres", None,
                                     allowed="> d0 + the largest lift + sqrt(Rr2^2 - offset^2) (d0 the first "
                                             "roller's rest height, Rr2 the second roller's radius), so the second "
                                             "roller stays beyond the shaft; not with a base_radius of \"auto\"",
                                     absent="from second_base_radius")
    arm_angle: float | None = Field(None, gt=0, lt=360, description="oscillating arm: angle at the pivot from the "
                                    "first arm to the second, turning towards the cam",
                                    json_schema_extra=unit("degrees", allowed="keeps the second roller on its side of "
                                                           "the line from the pivot to the cam centre over the swing; "
                                                           "not with a base_radius of \"auto\"",
                                                           absent="from second_base_radius"))
    second_arm_length: float | None = length("oscillating arm: pivot to the second roller's centre", None,
                                             absent="follower.arm_length")
    second_roller_radius: float | None = length("the second roller's radius (default: follower.roller_radius)",
                                                None, le=1000.0, absent="follower.roller_radius")

    @field_validator("second_base_radius", mode="before")
    @classmethod
    def _second_radius(cls, value: Any) -> Any:
        return _auto_radius(value)


class ConjugateTable(Speeds, SecondCam, FlatBody):
    """A conjugate (dual) cam: two discs on one shaft, each driving one of the follower's two rollers."""

    model_config = ConfigDict(title="a conjugate cam")

    kind: Literal["conjugate"] = Field(description="cam kind")


#: every kind's ``[cam]`` table by the kind's name
CAM_TABLES: dict[str, type[Model]] = {"disc": DiscTable, "plate": PlateTable, "grooved": GroovedTable,
                                      "barrel": BarrelTable, "conjugate": ConjugateTable}
