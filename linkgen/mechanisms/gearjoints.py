"""Gears as joints of a general linkage (``type = "linkage"``): ``[linkage.gears.NAME]`` and ``[linkage.racks.NAME]``.

A gear pair fixes a gear to each of two links, each about one of its link's joints (its centre), meshing with the
other; a rack rides on a slider's sliding link and meshes with a pinion fixed to a link that turns about a joint of
the slider's guide. Each is a higher pair (:class:`~linkgen.kinematics.structure.Gear`,
:class:`~linkgen.kinematics.structure.Rack`): Gruebler counts it once, and the solve plan places one of its links
from the other (:mod:`linkgen.kinematics.gearing`)::

    [linkage.gears.mesh]
    a = { link = "crank", centre = "O2", teeth = 40 }
    b = { link = "crank2", centre = "O5", teeth = 20 }
    module = 1.5                 # the centres must be drawn m (z_a + z_b) / 2 apart (internal: m (z_b - z_a) / 2)

    [linkage.racks.drive]
    slider = "ram"               # the rack is fixed to this slider's sliding link
    pinion = { link = "pinion", centre = "O", teeth = 20 }
    module = 2.0                 # the centre must be drawn m z / 2 from the rack's pitch line
    offset = 0.0                 # the pitch line's distance (mm) from the slider's guide line, to its left

Teeth are unshifted involute teeth (:mod:`linkgen.gears`); the designer's checks of ``type = "gear-pair"`` (pointed
teeth, tip clearance, contact ratio, an internal gear's interference) apply to each pair.
"""
from __future__ import annotations

import math
from typing import Any, Literal

import numpy as np
from pydantic import Field, ValidationError, model_validator

from camgen.core.errors import SpecError
from camgen.core.spec import MAX_LENGTH_MM, Model, unit
from linkgen.gears.pair import GearPair
from linkgen.gears.tooth import BasicRack
from linkgen.kinematics.linkage import Linkage, Solution, input_angle
from linkgen.kinematics.structure import GROUND, MESH_TOL_MM, Gear, Rack, Structure, check_whole_turns, plan
from linkgen.mechanisms.gearpair import MAX_MODULE, MAX_TEETH, MIN_TEETH, GearPairTable

#: the most gear pairs, and racks, a linkage may have
MAX_PAIRS = 50


class GearMember(Model):
    """One gear of a pair: the link it is fixed to, the joint it turns about with that link, its teeth."""

    link: str = Field(description="the link the gear is fixed to ('ground' for a fixed gear)")
    centre: str = Field(description="the joint of that link at the gear's centre")
    teeth: int = Field(ge=MIN_TEETH, le=MAX_TEETH, description="number of teeth (an internal gear's: its ring's)")


def _module() -> Any:
    return Field(gt=0, le=MAX_MODULE, description="module m: reference diameter per tooth",
                 json_schema_extra=unit("mm", allowed="m z <= 10000 mm for every gear"))


def _pressure_angle() -> Any:
    return Field(20.0, ge=10.0, le=30.0, description="pressure angle of the basic rack",
                 json_schema_extra=unit("degrees"))


def _backlash() -> Any:
    return Field(0.1, gt=0, le=50.0, description="play between the teeth along the pitch circles (each member "
                 "thinned by half of it)", json_schema_extra=unit("mm", allowed="<= pi m / 8"))


class GearJointTable(Model):
    """``[linkage.gears.NAME]``: a gear pair between two links; its centres drawn at the distance it meshes at."""

    a: GearMember = Field(description="the first gear: {link, centre, teeth}")
    b: GearMember = Field(description="the second gear (an internal pair's ring): {link, centre, teeth}")
    kind: Literal["external", "internal"] = Field("external", description="external pair, or b an internal gear "
                                                  "(a ring) with a inside it")
    module: float = _module()
    pressure_angle: float = _pressure_angle()
    backlash: float = _backlash()

    @model_validator(mode="after")
    def _design(self) -> GearJointTable:
        _designer_checks({"kind": self.kind, "pinion": {"teeth": self.a.teeth}, "gear": {"teeth": self.b.teeth}},
                         self, {"pinion": "a", "gear": "b"})
        return self

    @property
    def distance(self) -> float:
        """The centre distance the teeth mesh at (mm): m (z_a + z_b) / 2, or m (z_b - z_a) / 2 for an internal
        pair."""
        span = self.b.teeth - self.a.teeth if self.kind == "internal" else self.a.teeth + self.b.teeth
        return self.module * span / 2

    @property
    def pair(self) -> GearPair:
        """The pair as :mod:`linkgen.gears` makes it: a's gear the pinion."""
        return GearPair(self.kind, BasicRack(self.module, math.radians(self.pressure_angle)), self.a.teeth, 0.0,
                        self.b.teeth, 0.0, self.backlash)


class RackJointTable(Model):
    """``[linkage.racks.NAME]``: a rack on a slider's sliding link, meshing with a pinion turning about a joint of
    the slider's guide; the pinion's centre drawn its pitch radius from the rack's pitch line."""

    slider: str = Field(description="the slider whose sliding link carries the rack")
    pinion: GearMember = Field(description="the pinion: {link, centre, teeth}; the centre a joint of the guide")
    module: float = _module()
    pressure_angle: float = _pressure_angle()
    backlash: float = _backlash()
    offset: float = Field(0.0, ge=-MAX_LENGTH_MM, le=MAX_LENGTH_MM,
                          description="the rack's pitch line's distance from the slider's guide line through its "
                                      "point, to the left of the guide's direction",
                          json_schema_extra=unit("mm"))

    @model_validator(mode="after")
    def _design(self) -> RackJointTable:
        _designer_checks({"kind": "rack", "pinion": {"teeth": self.pinion.teeth}, "slider": {"travel": 1.0}}, self,
                         {"pinion": "pinion"})
        return self

    @property
    def pair(self) -> GearPair:
        """The rack pair as :mod:`linkgen.gears` makes it."""
        return GearPair("rack", BasicRack(self.module, math.radians(self.pressure_angle)), self.pinion.teeth, 0.0, 0,
                        0.0, self.backlash)


def _designer_checks(members: dict[str, Any], t: GearJointTable | RackJointTable, keys: dict[str, str]) -> None:
    """The checks of a ``gear-pair`` on this pair's teeth (a ValueError naming this table's key otherwise)."""
    try:
        GearPairTable.model_validate({"type": "gear-pair", "module": t.module, "pressure_angle": t.pressure_angle,
                                      "backlash": t.backlash, **members})
    except ValidationError as exc:
        err = exc.errors(include_url=False)[0]
        text = str(err.get("ctx", {}).get("error", err["msg"]))
        head, sep, rest = text.partition(": ")
        if sep and " " not in head:
            first, dot, tail = head.partition(".")
            text = f"{keys.get(first, first)}{dot}{tail}: {rest}"
        raise ValueError(text) from None


def gears_of(gears: dict[str, GearJointTable]) -> tuple[Gear, ...]:
    """The structure's gear pairs."""
    return tuple(Gear(name, (t.a.link, t.b.link), (t.a.centre, t.b.centre), (t.a.teeth, t.b.teeth),
                      t.kind == "internal", t.distance) for name, t in gears.items())


def racks_of(racks: dict[str, RackJointTable], joints: dict[str, tuple[float, float]],
             sliders: dict[str, Any]) -> tuple[Rack, ...]:
    """The structure's racks, each pinion's centre checked against the rack's pitch line (a :class:`SpecError` naming
    the rack); a rack on no slider, or a centre not drawn, is left for the structure's checks to name."""
    out = []
    for name, t in racks.items():
        radius = t.module * t.pinion.teeth / 2
        sl = sliders.get(t.slider)
        lead = radius
        if sl is not None and sl.point in joints and t.pinion.centre in joints:
            u = np.array([math.cos(math.radians(sl.angle)), math.sin(math.radians(sl.angle))])
            n = np.array([-u[1], u[0]])
            side = float(n @ (np.asarray(joints[t.pinion.centre]) - np.asarray(joints[sl.point]))) - t.offset
            if abs(abs(side) - radius) > MESH_TOL_MM:
                raise SpecError(f"the pinion's centre {t.pinion.centre} is drawn {abs(side):.9g} mm from the rack's "
                                f"pitch line, not its pitch radius m z / 2 = {radius:.9g} mm (within "
                                f"{MESH_TOL_MM:g} mm): move it or change offset", f"linkage.racks.{name}")
            lead = math.copysign(radius, side)
        out.append(Rack(name, t.slider, t.pinion.link, t.pinion.centre, lead))
    return tuple(out)


def check_turns(s: Structure, given: tuple[float, float] | None) -> None:
    """Refuse pairs that make a link turn a fraction of a turn (or a rack run away) per turn of a crank input
    (:func:`~linkgen.kinematics.structure.check_whole_turns`), unless the input's range ``given`` (degrees) lies
    within the one turn from its drawn angle, which the solve reads as it is."""
    if len(s.inputs) != 1 or s.inputs[0].kind != "crank":
        return
    try:
        check_whole_turns(s, plan(s).steps)
    except SpecError as exc:
        drawn = math.degrees(input_angle(s, s.inputs[0]))
        if given is not None and drawn - 1e-9 <= given[0] and given[1] <= drawn + 360.0 + 1e-9:
            return
        raise SpecError(f"{exc.detail}; or give the input range = [from, to] within the turn from its drawn "
                        f"{drawn:.9g} degrees", exc.field) from None


def check_meshes(linkage: Linkage, sol: Solution) -> None:
    """Refuse a gear pair whose centres no one link holds (no rigid carrier) and which come apart from the distance
    their teeth mesh at anywhere over the poses ``sol`` (by more than 1e-6 mm)."""
    s = linkage.structure
    for g in s.gears:
        if s.carrier(g) is not None:
            continue
        ok = sol.ok
        d = np.hypot(*(sol.points[g.centres[1]][ok] - sol.points[g.centres[0]][ok]).T)
        worst = float(np.max(np.abs(d - g.distance), initial=0.0))
        if worst > MESH_TOL_MM:
            raise SpecError(f"no one link holds both centres {g.centres[0]} and {g.centres[1]}, and as the input "
                            f"moves they come {worst:.6g} mm off the {g.distance:.9g} mm the teeth mesh at; give the "
                            "pair a carrier (a link holding both centres)", f"linkage.gears.{g.name}")


def pairs_report(linkage: Linkage) -> list[dict[str, Any]]:
    """Each higher pair: its links, centres and ratio (a gear pair's: b's turn relative to the line of centres per
    a's), or a rack's lead (mm of travel per rad of its pinion relative to the guide)."""
    s = linkage.structure
    out: list[dict[str, Any]] = []
    for g in s.gears:
        carrier = s.carrier(g)
        out.append({"pair": g.name, "kind": "internal" if g.internal else "external", "links": list(g.bodies),
                    "centres": list(g.centres), "teeth": list(g.teeth), "ratio": round(g.ratio, 12),
                    "carrier": carrier if carrier is not None else "the line of centres",
                    "centre_distance_mm": round(g.distance, 9)})
    for r in s.racks:
        sl = s.slider_by_name[r.slider]
        out.append({"pair": r.name, "kind": "rack", "slider": r.slider, "rack_link": sl.body, "pinion": r.pinion,
                    "centre": r.centre, "lead_mm_per_rad": round(r.lead, 12),
                    "guide": sl.guide if sl.guide != GROUND else "ground"})
    return out
