"""The conjugate (dual) cam's template: its ``[cam]`` table (:class:`ConjugateTable`, ``kind = "conjugate"``: the
first cam's body and the second cam's, :class:`SecondCam`) and its spec (:class:`ConjugateSpec`: two rollers of one
follower, driven both ways), with the rules across its tables: which of the second roller's keys the follower's type
takes, and which key places that roller."""
from __future__ import annotations

from typing import Any, ClassVar, Literal

from pydantic import ConfigDict, Field, field_validator

from camgen.core.spec import MAX_LENGTH_MM, Model, length, unit
from camgen.spec import FlatSpec
from camgen.tables import FlatBody, Speeds, auto_radius
from camgen.tables.followers import DrivenFollower

#: the key that places the second roller instead of ``cam.second_base_radius``, by follower type
PLACES = {"translating-roller": "yoke_span", "oscillating-roller": "arm_angle"}
#: the second roller's own ``[cam]`` keys that only one follower type takes, by that type
SECOND_ROLLER_KEYS = {"translating-roller": ("yoke_span",), "oscillating-roller": ("arm_angle", "second_arm_length")}


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
        return auto_radius(value)


class ConjugateTable(Speeds, SecondCam, FlatBody):
    """A conjugate (dual) cam: two discs on one shaft, each driving one of the follower's two rollers."""

    model_config = ConfigDict(title="a conjugate cam")

    kind: Literal["conjugate"] = Field(description="cam kind")


class ConjugateSpec(FlatSpec):
    """A conjugate pair's template (``cam.kind = "conjugate"``), validated."""

    cam: ConjugateTable
    follower: DrivenFollower

    noun: ClassVar[str] = "a conjugate cam"  # its table's title

    def kind_rules(self) -> None:
        """No undercut; the second roller's keys of the follower's type only (``cam.arm_angle`` places an arm's
        roller, not a yoke's); one key placing that roller; a fixed placement with two sized cams refused."""
        cam, follower = self.cam, self.follower
        if cam.allow_undercut:
            raise ValueError("cam.allow_undercut: both contacts of a conjugate pair must hold over the whole turn, so "
                             "an undercut is refused, never cut as an envelope")
        for owner, keys in SECOND_ROLLER_KEYS.items():
            for key in keys:
                if owner != follower.type and key in cam.model_fields_set:
                    article = "an" if owner[0] in "aeiou" else "a"
                    raise ValueError(f"cam.{key}: only for a conjugate cam with {article} {owner} follower")
        place = PLACES[follower.type]
        if place in cam.model_fields_set and "second_base_radius" in cam.model_fields_set:
            raise ValueError(f"cam.{place}: give cam.{place} or cam.second_base_radius (either places the second "
                             "roller), not both")
        if place in cam.model_fields_set and cam.base_radius == "auto":
            raise ValueError(f"cam.base_radius: \"auto\" sizes each cam by its base circle; with cam.{place} fixed "
                             "the second cam changes with the first, so give cam.second_base_radius (or \"auto\") "
                             f"instead of cam.{place}, or a base radius")
