"""The pieces the cam kinds' ``[cam]`` tables are built from; each kind's own table and spec live in its package
(``camgen/kinds/<kind>/table.py``).

A kind's table declares the keys it takes and nothing else (``extra="forbid"``), so a key of another kind is
refused by the model itself, in one line naming the key and this kind (its ``title``) and listing what it takes.
The pieces are mixins: :class:`FlatSize` (a cam cut from a flat plate: its base radius and thickness),
:class:`Turning` (a bore and a sense of rotation) and :class:`Limits` (sizing limits), the three together
:class:`FlatBody`; :class:`Speeds` (its speed and material); :class:`GrooveBody` (a grooved cam's groove). Keys a
kind needs are required, not optional; the rules that tie a key to another table (a groove shallower than the
plate, a bore inside the groove's floor) are the kind's spec's (:meth:`camgen.spec.CamSpec.kind_rules`). No kind is
named here.
"""
from __future__ import annotations

import math
from typing import Any, Literal, Protocol

from pydantic import Field, field_validator

from camgen.contact_stress import MaterialName
from camgen.core.spec import MAX_LENGTH_MM, Model, length, unit

#: a cam's (or a follower's) material, for the contact pressure (:data:`camgen.contact_stress.MATERIALS`)
Material = MaterialName


def auto_radius(value: Any) -> Any:
    """A radius in mm or ``"auto"``, checked: a ValueError saying what is allowed otherwise."""
    if value == "auto":
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f'must be a number of mm or "auto" (got {value!r})')
    if not (math.isfinite(value) and 0 < value <= MAX_LENGTH_MM):
        raise ValueError(f'must be > 0 and <= {MAX_LENGTH_MM:g} mm, or "auto" (got {value!r})')
    return float(value)


class CamBody(Protocol):
    """What every kind's ``[cam]`` table gives, read only: its kind, bore (mm; 0 for none), sense of rotation, speed
    (rpm) and material, which the checks and the speeds every kind shares read (:class:`camgen.spec.CamSpec`)."""

    @property
    def kind(self) -> str: ...
    @property
    def bore(self) -> float: ...
    @property
    def rotation(self) -> Literal["ccw", "cw"]: ...
    @property
    def rpm(self) -> float | None: ...
    @property
    def rpm_range(self) -> tuple[float, float] | None: ...
    @property
    def rpm_steps(self) -> int: ...
    @property
    def material(self) -> Material | None: ...


class FlatCamBody(CamBody, Protocol):
    """What a flat cam's ``[cam]`` table gives beyond :class:`CamBody`: its base radius (mm, or ``"auto"``), thickness
    (mm), sizing limits and whether an undercut is cut as an envelope (:class:`camgen.spec.FlatSpec`)."""

    @property
    def base_radius(self) -> float | Literal["auto"]: ...
    @property
    def thickness(self) -> float: ...
    @property
    def allow_undercut(self) -> bool: ...
    @property
    def max_pressure_angle(self) -> float | None: ...
    @property
    def min_rho_margin(self) -> float: ...


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
        return auto_radius(value)


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
