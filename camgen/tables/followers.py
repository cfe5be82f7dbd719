"""Each follower's ``[follower]`` table, one per follower type and drive, built from the pieces they share.

A follower's table declares the keys its type takes on the cams that drive it, and nothing else
(``extra="forbid"``): a key another type takes is refused by the model itself, in one line naming the key and the
follower (its ``title``) and listing what it takes. The pieces are mixins: :class:`Dynamics` (its mass, loads and
material: every follower), :class:`Spring` (a return spring and the contact it keeps: the spring-held followers of a
disc or a plate cam), :class:`Roller` and :class:`RollerWidth`, :class:`Offset` (a translating follower's axis off
the cam centre), :class:`Pivot` and :class:`Arm` (an oscillating follower), :class:`Face` (a flat face) and
:class:`Cone` (a barrel's conical roller).

A kind's spec declares the tables it drives as a union chosen by ``type`` (:data:`SprungFollower` for a disc cam,
:data:`PlateFollower` for a plate cam, :data:`DrivenFollower` for the positive drives of a grooved cam and a
conjugate pair, :data:`BarrelFollower` for a barrel cam). Keys a type needs are required, not optional.

A table that lacks a piece answers for it with what its absence means, as class constants that are no keys
(:class:`Unsprung`: no spring; :class:`Centred`: an offset of 0; :class:`Rollerless`: no roller; :class:`Armless`
and :class:`Unpivoted`: no arm, no pivot), so the code that reads any follower (its loading, its report) reads one
shape; a key that is not a field stays refused. The groups: :class:`Sprung` and :class:`Driven` (held by a spring,
or driven both ways), :class:`Straight` and :class:`OnCentre` (translating, and on the cam centre's line).
"""
from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal, get_args

from pydantic import Field, model_validator

from camgen.core.spec import MAX_LENGTH_MM, Model, length, notes, unit
from camgen.tables import Material
from camgen.tables.rows import load_rows, read_table


class Dynamics(Model):
    """What every follower carries into the dynamics: its moving mass, the loads on it, its orientation and the
    material of its roller (or face)."""

    mass: float | None = Field(None, gt=0, le=1000, description="moving mass of the follower",
                               json_schema_extra=unit("kg"))
    load: float | None = Field(None, ge=-1e6, le=1e6, description="external force pressing the follower onto the "
                               "cam (negative pulls it off)", json_schema_extra=unit("N"))
    orientation: float | None = Field(None, ge=-180, le=180, description="the rise's direction from straight up: "
                                      "the weight counts by its cosine",
                                      json_schema_extra=unit("degrees", absent="straight up without a spring; the "
                                                             "weight neglected with one, on a positive drive and for "
                                                             "an arm"))
    material: Material = Field("steel", description="the roller's (or face's) material, for the contact pressure")
    load_table: str | list[tuple[float, float]] | None = Field(
        None, description="a CSV of cam angle (degrees), load (N) rows (or the rows themselves): an external load "
        "against cam angle, added to follower.load, interpolated linearly and periodic over the turn",
        json_schema_extra=notes(allowed="angles increasing in 0 to 360 (a row at 360 must repeat the one at 0); "
                                "|load| <= 1e6 N; at least 2 rows (a file: 4, at most 10000 rows and 2 MB); not with "
                                "motion[i].load"))

    @model_validator(mode="before")
    @classmethod
    def _read_load_table(cls, data: Any) -> Any:
        """A ``load_table`` file read into its rows (a path relative to the current folder; :func:`load_spec` makes a
        template's relative to the template)."""
        if isinstance(data, Mapping) and isinstance(data.get("load_table"), str):
            try:
                return {**data, "load_table": read_table(Path(data["load_table"]))}
            except ValueError as exc:
                raise ValueError(f"load_table: {str(exc).removeprefix('file: ')}") from None
        return data

    @model_validator(mode="after")
    def _table_rows(self) -> Dynamics:
        if isinstance(self, Arm) and self.arm_mass and self.orientation is None:
            raise ValueError("arm_mass: its weight needs follower.orientation (degrees of the drawing's +Y from "
                             "straight up)")
        if isinstance(self.load_table, list):
            if len(self.load_table) < 2:
                raise ValueError("load_table: give at least 2 rows of cam angle (degrees), load (N)")
            try:
                load_rows(self.load_table)
            except ValueError as exc:
                raise ValueError(f"load_table: {exc}") from None
        return self

    @property
    def load_table_rows(self) -> list[tuple[float, float]] | None:
        """The load table's (cam angle in degrees, load in N) rows, a row at 360 dropped, or None."""
        return None if not isinstance(self.load_table, list) else load_rows(self.load_table)


class Spring(Model):
    """A return spring holding the follower on its cam, and the least contact force its sizing keeps."""

    spring_rate: float | None = Field(None, ge=0, le=1e6, description="return spring rate",
                                      json_schema_extra=unit("N/mm", absent="none: no spring (without preload "
                                                             "either, the follower's weight holds it on the cam)"))
    preload: float | None = Field(None, ge=0, le=1e6, description="return spring force at s = 0",
                                  json_schema_extra=unit("N"))
    contact_margin: float | None = Field(None, ge=0, le=1e6, description="least contact force the spring sizing "
                                         "keeps", json_schema_extra=unit("N", absent="0"))


class Unsprung:
    """A follower the cam drives both ways (a groove, a conjugate pair): no spring, no contact margin."""

    spring_rate: ClassVar[None] = None
    preload: ClassVar[None] = None
    contact_margin: ClassVar[None] = None


class Roller(Model):
    """A roller: its radius."""

    roller_radius: float = length("roller radius", le=1000.0,
                                  allowed="below the pitch curve's least convex radius, else the cam undercuts "
                                          "(refused unless cam.allow_undercut)")

    @property
    def contact_radius(self) -> float:
        """The roller's radius (mm)."""
        return self.roller_radius


class RollerWidth(Model):
    """A flat cam's roller: its width along its axis, for the contact pressure."""

    roller_width: float | None = length("the roller's width along its axis (default: the cam's thickness)", None,
                                        le=1000.0, absent="cam.thickness")


class Rollerless:
    """A knife edge or a flat face: no roller, so a contact radius of 0."""

    roller_radius: ClassVar[None] = None
    roller_width: ClassVar[None] = None
    #: the contact is a point of the follower (mm)
    contact_radius: ClassVar[float] = 0.0


class Offset(Model):
    """A translating follower's axis, off the cam centre."""

    offset: float = Field(0.0, ge=-MAX_LENGTH_MM, le=MAX_LENGTH_MM, description="follower axis offset, + to the right "
                          "(+X)", json_schema_extra=unit("mm", allowed="|offset| < base_radius + roller_radius (the "
                                                         "prime radius)"))


class Centred:
    """A follower on the cam centre's line (a flat face, a plate cam's, a barrel's, an arm's): an offset of 0."""

    #: the follower's axis passes through the cam centre (mm)
    offset: ClassVar[float] = 0.0


class Pivot(Model):
    """An oscillating follower's pivot: its lift is the swing in degrees."""

    pivot_distance: float = length(
        "oscillating: cam centre to arm pivot",
        allowed="a roller: |pivot_distance - arm_length| < base_radius + roller_radius < pivot_distance + arm_length; "
                "a flat face: > base_radius; on a barrel, the cam's axis to the pivot's: the arm's chordal error "
                "leaving the roller in the groove")

    oscillating: ClassVar[bool] = True


class Arm(Pivot):
    """An oscillating roller's arm: its length, and its inertia and weight."""

    arm_length: float = length("oscillating roller: pivot to roller centre",
                               allowed="puts the roller on the prime circle (see pivot_distance)")
    inertia: float | None = Field(None, ge=0, le=1e9, description="oscillating roller: the arm's moment of inertia "
                                  "about the pivot, entering as a mass I / L^2 at the roller",
                                  json_schema_extra=unit("kg*mm^2", absent="0"))
    arm_mass: float | None = Field(None, ge=0, le=1000, description="oscillating roller: the arm's own mass, for its "
                                   "weight (with follower.orientation)",
                                   json_schema_extra=unit("kg", allowed="with arm_com and orientation"))
    arm_com: float | None = Field(None, ge=0, le=MAX_LENGTH_MM, description="oscillating roller: pivot to the arm's "
                                  "centre of mass, on the line to the roller's centre",
                                  json_schema_extra=unit("mm", allowed="with arm_mass"))

    @model_validator(mode="after")
    def _weight(self) -> Arm:
        if (self.arm_mass is None) != (self.arm_com is None):
            raise ValueError("arm_com: give both arm_mass (kg) and arm_com (mm from the pivot), or neither")
        return self


class Armless:
    """A follower without an arm (translating, or a flat face on a pivot): no arm length, inertia or weight."""

    arm_length: ClassVar[None] = None
    inertia: ClassVar[None] = None
    arm_mass: ClassVar[None] = None
    arm_com: ClassVar[None] = None


class Unpivoted:
    """A translating follower: no pivot; its lift is in mm."""

    pivot_distance: ClassVar[None] = None
    oscillating: ClassVar[bool] = False


class Face(Model):
    """A flat face: the face beyond the contact's travel."""

    face_margin: float = length("flat face: extra face beyond the contact's travel, each side", 2.0, zero=True,
                                le=1000.0)


class Cone(Model):
    """A barrel cam's roller: a cylinder, or a cone with its apex on the cam's axis."""

    roller_shape: Literal["cylindrical", "conical"] = Field(
        "cylindrical", description="barrel cam: the roller's shape, a cylinder or a cone with its apex on the cam's "
        "axis", json_schema_extra=notes(allowed="conical: roller_radius < cam.pitch_radius, on the pitch cylinder"))


class Sprung(Dynamics, Spring):
    """A follower held on its cam by a spring (or its weight, or a load): a disc cam's, a plate cam's."""


class Driven(Dynamics, Unsprung):
    """A follower its cam drives both ways (a groove, a conjugate pair, a barrel's groove): no spring."""


class Straight(Armless, Unpivoted):
    """A translating follower: no arm, no pivot."""


class OnCentre(Straight, Centred):
    """A translating follower whose axis passes through the cam centre (a face's, a plate cam's, a barrel's)."""


# --- a disc cam's followers, held on by a spring (or their weight, or a load) ---------------------------------------

class TranslatingRollerTable(Sprung, RollerWidth, Offset, Roller, Straight, title="a translating-roller follower"):
    """A translating roller follower, held on by a spring (its weight, or a load)."""


    type: Literal["translating-roller"] = Field(description="follower type")


class KnifeEdgeTable(Sprung, Offset, Straight, Rollerless, title="a knife-edge follower"):
    """A knife-edge follower: a point on the follower's axis."""


    type: Literal["knife-edge"] = Field(description="follower type")


class TranslatingFlatTable(Sprung, Face, OnCentre, Rollerless, title="a translating-flat follower"):
    """A translating flat-faced follower, its face square to its motion."""


    type: Literal["translating-flat"] = Field(description="follower type")


class OscillatingRollerTable(Sprung, RollerWidth, Arm, Roller, Centred, title="an oscillating-roller follower"):
    """A roller on a swinging arm, held on by a spring (its weight, or a load)."""


    type: Literal["oscillating-roller"] = Field(description="follower type")


class OscillatingFlatTable(Sprung, Face, Pivot, Armless, Centred, Rollerless, title="an oscillating-flat follower"):
    """A flat face swinging about a pivot."""


    type: Literal["oscillating-flat"] = Field(description="follower type")


# --- a plate cam's: on the plate's normal, no offset ----------------------------------------------------------------

class PlateRollerTable(Sprung, RollerWidth, Roller, OnCentre, title="a plate cam's translating-roller follower"):
    """A plate cam's translating roller: it moves square to the plate's slide, so it has no offset."""


    type: Literal["translating-roller"] = Field(description="follower type")


class PlateKnifeEdgeTable(Sprung, OnCentre, Rollerless, title="a plate cam's knife-edge follower"):
    """A plate cam's knife edge: a point moving square to the plate's slide."""


    type: Literal["knife-edge"] = Field(description="follower type")


# --- positive drives: a groove or a conjugate pair drives the roller both ways, no spring ---------------------------

class DrivenTranslatingRollerTable(Driven, RollerWidth, Offset, Roller, Straight,
                                   title="a positive-drive translating-roller follower (driven both ways, no spring)"):
    """A translating roller driven both ways (a grooved cam's, a conjugate pair's yoke): no spring."""


    type: Literal["translating-roller"] = Field(description="follower type")


class DrivenOscillatingRollerTable(Driven, RollerWidth, Arm, Roller, Centred,
                                   title="a positive-drive oscillating-roller follower (driven both ways, no spring)"):
    """A roller on an arm driven both ways (a grooved cam's, a conjugate pair's bell crank): no spring."""


    type: Literal["oscillating-roller"] = Field(description="follower type")


# --- a barrel cam's: along the cam's axis, in its groove ------------------------------------------------------------

class BarrelTranslatingRollerTable(Driven, Cone, Roller, OnCentre,
                                   title="a barrel cam's translating-roller follower (driven both ways, no spring)"):
    """A barrel cam's roller moving along the cam's axis, driven both ways by the groove."""


    type: Literal["translating-roller"] = Field(description="follower type")

    #: a barrel's roller has no width of its own to give: its contact is along the groove's depth
    roller_width: ClassVar[None] = None


class BarrelOscillatingRollerTable(Driven, Cone, Arm, Roller, Centred,
                                   title="a barrel cam's oscillating-roller follower (driven both ways, no spring)"):
    """A barrel cam's roller on an arm swinging along the cam's axis, driven both ways by the groove."""


    type: Literal["oscillating-roller"] = Field(description="follower type")

    #: a barrel's roller has no width of its own to give: its contact is along the groove's depth
    roller_width: ClassVar[None] = None


def follower_types(spec: Any) -> tuple[str, ...]:
    """The follower types a kind's spec (a model class) takes: the tags of its ``follower`` union, in its order;
    none for a spec without a follower (a Geneva drive's)."""
    field = getattr(spec, "model_fields", {}).get("follower")
    members = get_args(field.annotation) if field is not None else ()
    return tuple(tag for member in members for tag in get_args(member.model_fields["type"].annotation))


#: a disc cam's followers
SprungFollower = Annotated[TranslatingRollerTable | KnifeEdgeTable | TranslatingFlatTable | OscillatingRollerTable
                           | OscillatingFlatTable, Field(discriminator="type")]
#: a plate cam's followers
PlateFollower = Annotated[PlateRollerTable | PlateKnifeEdgeTable, Field(discriminator="type")]
#: the followers a grooved cam and a conjugate pair drive both ways
DrivenFollower = Annotated[DrivenTranslatingRollerTable | DrivenOscillatingRollerTable, Field(discriminator="type")]
#: a barrel cam's followers
BarrelFollower = Annotated[BarrelTranslatingRollerTable | BarrelOscillatingRollerTable, Field(discriminator="type")]
#: any cam's follower (the shared spec's; each kind's spec narrows it to the union it drives)
AnyFollower = (TranslatingRollerTable | KnifeEdgeTable | TranslatingFlatTable | OscillatingRollerTable
               | OscillatingFlatTable | PlateRollerTable | PlateKnifeEdgeTable | DrivenTranslatingRollerTable
               | DrivenOscillatingRollerTable | BarrelTranslatingRollerTable | BarrelOscillatingRollerTable)
