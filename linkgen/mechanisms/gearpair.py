"""Involute spur gear pairs (``type = "gear-pair"``): an external pair, an internal gear with its pinion, a rack and
pinion; their ``[linkage]`` table, the designer's checks, the report, the figures and the parts.

The pinion drives, its centre at the origin, its angle counter-clockwise from +X (tooth 0 centred there at angle 0);
the gear's centre is at (c, 0), c the working centre distance (:mod:`linkgen.gears.pair`); a rack runs below the
pinion along +X. The geometry is :mod:`linkgen.gears`; the parts :mod:`linkgen.mechanisms.gearparts`.

Checks, each refused in one line naming the key to change: the module and the teeth in range, pointed teeth (tip
thickness <= 0), a flank that cannot start below the tip, a contact ratio under 1, tips that touch the other member's
root (tip clearance <= 0), an internal gear's tips reaching past the pinion's base circle on the line of action
(involute interference), a ring with too few teeth more than its pinion, outlines that overlap anywhere as the pair
turns through a pitch (:func:`linkgen.mechanisms.gearparts.overlap`: undercut, trochoid and tip interference), and a
given centre distance other than the one the teeth and shifts mesh at. Warnings: undercut, a contact ratio under 1.2,
a tip thinner than a quarter module.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field, model_validator

from camgen.core.errors import DesignError, SpecError
from camgen.core.spec import MAX_LENGTH_MM, Model, notes, unit
from linkgen.gears.involute import inv
from linkgen.gears.pair import GearPair
from linkgen.gears.tooth import BasicRack, ExternalTooth
from linkgen.mechanisms.common import Figure, deg, num, omega, rpm, types_of
from linkgen.parts import Layout, Stock

if TYPE_CHECKING:
    from camgen.core.parts import Drawing
    from linkgen.spec import PartsTable

#: the fewest and the most teeth a gear may have, and the largest module (mm)
MIN_TEETH, MAX_TEETH, MAX_MODULE = 4, 1000, 100.0
#: a given centre distance may differ from the one the teeth mesh at by this much (mm)
CENTRE_TOLERANCE_MM = 1e-3
#: a contact ratio below this is warned of
CONTACT_WARNING = 1.2
#: a tip thinner than this share of the module is warned of
TIP_WARNING = 0.25
#: the inch (mm), for a diametral pitch
INCH = 25.4


class GearTable(Model):
    """One gear of a pair (``[linkage.pinion]``, ``[linkage.gear]``): its teeth, its profile shift and its printed
    hub."""

    teeth: int = Field(ge=MIN_TEETH, le=MAX_TEETH, description="number of teeth (an internal gear's: its ring's)")
    shift: float = Field(0.0, ge=-1.0, le=0.8, description="profile shift coefficient x: the cutter's datum line "
                         "x modules outside the reference circle (thicker teeth, fewer without undercut); for an "
                         "internal gear, the shift of the external gear its spaces are",
                         json_schema_extra=unit("modules"))
    boss_diameter: float = Field(0.0, ge=0, le=MAX_LENGTH_MM, description="printed hub boss diameter, 0 for none",
                                 json_schema_extra=unit("mm", allowed="> the pin hole, within the root circle (an "
                                                        "internal gear's: on its web), with boss_height"))
    boss_height: float = Field(0.0, ge=0, le=1000.0, description="printed hub boss height above the gear",
                               json_schema_extra=unit("mm", allowed="with boss_diameter"))
    set_screw: float = Field(0.0, ge=0, le=100.0, description="radial set-screw hole diameter through the boss, 0 "
                             "for none", json_schema_extra=unit("mm", allowed="< boss_height"))

    @model_validator(mode="after")
    def _hub(self) -> GearTable:
        if (self.boss_diameter > 0) != (self.boss_height > 0):
            raise ValueError("boss_height: give both boss_diameter and boss_height (mm), or neither")
        if self.set_screw > 0 and not self.set_screw < self.boss_height:
            raise ValueError(f"set_screw: needs a boss taller than the screw ({self.set_screw:g} mm)")
        return self


class SliderTable(Model):
    """The slider a rack rides on (``[linkage.slider]``): the rack's travel along its guide, centred under the
    pinion."""

    travel: float = Field(gt=0, le=MAX_LENGTH_MM, description="the rack's travel along its guide",
                          json_schema_extra=unit("mm"))


class GearPairTable(Model):
    """``[linkage]`` of a gear pair: an external pair, an internal gear and its pinion, or a rack and pinion; the
    module (or diametral pitch), the pressure angle, the pinion and the other member, the backlash."""

    type: Literal["gear-pair"]
    kind: Literal["external", "internal", "rack"] = Field("external", description="external pair, internal gear "
                                                          "with its pinion, or rack and pinion")
    module: float | None = Field(None, gt=0, le=MAX_MODULE, description="module m: reference diameter per tooth",
                                 json_schema_extra=unit("mm", absent="diametral_pitch"))
    diametral_pitch: float | None = Field(None, gt=25.4 / MAX_MODULE, le=1000.0,
                                          description="diametral pitch: teeth per inch of reference diameter "
                                                      "(module 25.4 / P), instead of module",
                                          json_schema_extra=unit("1/inch", absent="module"))
    pressure_angle: float = Field(20.0, ge=10.0, le=30.0, description="pressure angle of the basic rack",
                                  json_schema_extra=unit("degrees"))
    pinion: GearTable = Field(description="the driving pinion: [linkage.pinion]")
    gear: GearTable | None = Field(None, description="the driven gear (external or internal): [linkage.gear]",
                                   json_schema_extra=notes(absent="a rack and pinion"))
    slider: SliderTable | None = Field(None, description="the slider a rack rides on: [linkage.slider]",
                                       json_schema_extra=notes(absent="external and internal pairs"))
    centre_distance: float | None = Field(None, gt=0, le=MAX_LENGTH_MM,
                                          description="the centres' distance (a rack's datum line's from the "
                                                      "pinion's centre), checked against the one the teeth and "
                                                      "shifts mesh at",
                                          json_schema_extra=unit("mm", allowed=f"within {CENTRE_TOLERANCE_MM:g} mm "
                                                                 "of the working centre distance",
                                                                 absent="the working centre distance"))
    backlash: float = Field(0.1, gt=0, le=50.0, description="play between the teeth along the working pitch "
                            "circles: each member's teeth are thinned by half of it (a cut pair needs the kerf's "
                            "spread, a printed pair about the printer's clearance)",
                            json_schema_extra=unit("mm", allowed="<= pi m / 8"))
    rpm: float = rpm()

    @model_validator(mode="after")
    def _consistent(self) -> GearPairTable:
        if (self.module is None) == (self.diametral_pitch is None):
            raise ValueError("module: give module (mm) or diametral_pitch (teeth per inch), one of them")
        m = self.m
        if self.kind == "rack":
            if self.slider is None:
                raise ValueError("slider: a rack rides on a slider: give [linkage.slider] with its travel (mm)")
            if self.gear is not None:
                raise ValueError("gear: a rack and pinion has no gear: leave [linkage.gear] out (the rack's teeth "
                                 "follow from its travel)")
        else:
            if self.gear is None:
                raise ValueError(f"gear: missing: give [linkage.gear] with its teeth (an {self.kind} pair)")
            if self.slider is not None:
                raise ValueError("slider: only a rack rides on a slider (kind = \"rack\")")
        for key, gear in (("pinion", self.pinion), ("gear", self.gear)):
            if gear is not None and not m * gear.teeth <= MAX_LENGTH_MM:
                raise ValueError(f"{key}.teeth: the reference diameter m z must be at most {MAX_LENGTH_MM:g} mm "
                                 f"(got {m * gear.teeth:g})")
        if not self.backlash <= math.pi * m / 8:
            raise ValueError(f"backlash: must be > 0 and <= {math.pi * m / 8:.6g} mm (pi m / 8; got {self.backlash:g})")
        if self.kind == "internal":
            assert self.gear is not None
            if self.gear.teeth <= self.pinion.teeth:
                raise ValueError(f"gear.teeth: an internal gear needs more teeth than its pinion (> "
                                 f"{self.pinion.teeth}; got {self.gear.teeth})")
        check(self)
        return self

    @property
    def m(self) -> float:
        """The module (mm): as given, or 25.4 / the diametral pitch."""
        return self.module if self.module is not None else INCH / float(self.diametral_pitch or 1.0)

    @cached_property
    def pair(self) -> GearPair:
        """The pair this table describes."""
        other = self.gear
        return GearPair(self.kind, BasicRack(self.m, math.radians(self.pressure_angle)), self.pinion.teeth,
                        self.pinion.shift, other.teeth if other is not None else 0,
                        other.shift if other is not None else 0.0, self.backlash)

    @property
    def travel(self) -> float:
        return self.slider.travel if self.slider is not None else 0.0

    def lengths_mm(self) -> dict[str, float]:
        """The report's lengths: the module, the working centre distance and the working pitch diameters (mm)."""
        p = self.pair
        r1, r2 = p.working_pitch_radii
        out = {"module": round(self.m, 12), "centre_distance": round(p.centre_distance, 9),
               "pinion_pitch_diameter": round(2 * r1, 9)}
        if math.isfinite(r2):
            out["gear_pitch_diameter"] = round(2 * r2, 9)
        if self.slider is not None:
            out["travel"] = self.slider.travel
        return out


def _shift_for(table: GearPairTable, distance: float) -> str:
    """What makes the pair mesh at ``distance`` mm: the sum (difference) of shifts, or the rack's pinion shift."""
    p, a = table.pair, math.radians(table.pressure_angle)
    m, z1 = table.m, table.pinion.teeth
    if p.kind == "rack":
        return f"a pinion shift of {(distance - m * z1 / 2) / m:.6g}"
    z2 = p.gear_teeth
    span = (z1 + z2) if p.kind == "external" else (z2 - z1)
    ratio = m * span / 2 * math.cos(a) / distance
    if not ratio < 1:
        return "no shifts (it is too short for these teeth)"
    total = (float(inv(math.acos(ratio))) - float(inv(a))) * span / (2 * math.tan(a))
    what = "x1 + x2" if p.kind == "external" else "x2 - x1"
    return f"shifts with {what} = {total:.6g}"


def check(table: GearPairTable) -> None:
    """The designer's checks that refuse a pair (see the module's notes), each a ValueError naming the key."""
    p = table.pair
    members: list[tuple[str, ExternalTooth]] = [("pinion", p.pinion_tooth)]
    if p.kind == "external" and p.gear_tooth is not None:
        members.append(("gear", p.gear_tooth))
    for key, tooth in members:
        try:
            tooth.check()
        except DesignError as exc:
            raise ValueError(f"{key}.shift: {exc} (teeth {tooth.teeth}, shift {tooth.shift:g})") from None
    if p.kind == "internal":
        g = p.gear_tooth
        assert g is not None
        if not p.ring_tip_radius > g.base_radius:
            raise ValueError(f"gear.shift: the internal gear's tips (radius {p.ring_tip_radius:.6g} mm) lie inside "
                             f"its base circle ({g.base_radius:.6g} mm), where no involute is; raise its shift")
        if not g.tip_thickness > 0:
            raise ValueError(f"gear.shift: the internal gear's tooth spaces close before its root circle (their "
                             f"width there {g.tip_thickness:.4g} mm); lower its shift (got {g.shift:g})")
        if p.ring_interference < 0:
            raise ValueError(f"gear.teeth: the internal gear's tips reach {-p.ring_interference:.4g} mm past the "
                             "point where the line of action touches the pinion's base circle (involute "
                             "interference): give the pinion more teeth or shift, or the gear a larger shift")
    if table.centre_distance is not None and abs(table.centre_distance - p.centre_distance) > CENTRE_TOLERANCE_MM:
        raise ValueError(f"centre_distance: these teeth and shifts mesh at {p.centre_distance:.6f} mm (got "
                         f"{table.centre_distance:g}); leave it out, give that, or make it with "
                         f"{_shift_for(table, table.centre_distance)}")
    first, second = p.tip_clearance
    for key, clearance, whose in (("pinion.shift", first, "pinion's"), ("gear.shift", second, "other member's")):
        if not clearance > 0:
            raise ValueError(f"{key}: the {whose} tips reach the other's root circle (clearance {clearance:.4g} mm); "
                             "lower that shift")
    if not p.contact_ratio >= 1:
        raise ValueError(f"pinion.teeth: the contact ratio is {p.contact_ratio:.4f} < 1: a pair of teeth leaves "
                         "contact before the next meets; give more teeth or a smaller pressure angle")


def member_report(tooth: ExternalTooth, working_radius: float) -> dict[str, Any]:
    """One external gear's figures (mm unless named)."""
    m, a = tooth.module, tooth.pressure_angle
    return {"teeth": tooth.teeth, "shift": tooth.shift, "pitch_radius_mm": num(tooth.pitch_radius),
            "base_radius_mm": num(tooth.base_radius), "tip_radius_mm": num(tooth.tip_radius),
            "root_radius_mm": num(tooth.root_radius), "working_pitch_radius_mm": num(working_radius),
            "tooth_thickness_mm": num(m * (math.pi / 2 + 2 * tooth.shift * math.tan(a))),
            "thinning_mm": num(tooth.thinning), "tooth_thickness_as_made_mm": num(tooth.thickness),
            "tip_thickness_mm": num(tooth.tip_thickness), "form_radius_mm": num(tooth.form_radius),
            "fewest_teeth_without_undercut": num(tooth.fewest_teeth), "undercut": tooth.undercut}


def ring_report(pair: GearPair) -> dict[str, Any]:
    """An internal gear's figures: its tips inside, its roots outside, its teeth's thickness (mm)."""
    g = pair.gear_tooth
    assert g is not None
    m, a, z = pair.module, pair.pressure_angle, pair.gear_teeth
    tip = pair.ring_tip_radius
    thickness = m * (math.pi / 2 - 2 * g.shift * math.tan(a))
    return {"teeth": z, "shift": g.shift, "pitch_radius_mm": num(g.pitch_radius),
            "base_radius_mm": num(g.base_radius), "tip_radius_mm": num(tip), "root_radius_mm": num(g.tip_radius),
            "working_pitch_radius_mm": num(pair.working_pitch_radii[1]), "tooth_thickness_mm": num(thickness),
            "thinning_mm": num(-g.thinning), "tooth_thickness_as_made_mm": num(thickness + g.thinning),
            "tip_thickness_mm": num(2 * math.pi * tip / z - g.thickness_at(tip))}


def pair_report(table: GearPairTable, pair: GearPair, angle: float | None) -> dict[str, Any]:
    """The report's gear-pair section (mm and degrees)."""
    p = pair.pinion_tooth
    r1, _ = pair.working_pitch_radii
    aw = pair.working_pressure_angle
    report: dict[str, Any] = {"kind": pair.kind, "module_mm": num(pair.module),
                              "pressure_angle_deg": table.pressure_angle,
                              "working_pressure_angle_deg": num(math.degrees(aw)),
                              "centre_distance_mm": num(pair.centre_distance), "speed_ratio": num(pair.speed_ratio),
                              "contact_ratio": num(pair.contact_ratio), "backlash_mm": table.backlash,
                              "normal_backlash_mm": num(table.backlash * math.cos(aw)),
                              "tip_clearance_mm": [num(c) for c in pair.tip_clearance]}
    members: dict[str, Any] = {"pinion": member_report(p, r1)}
    if pair.kind == "external":
        assert pair.gear_tooth is not None
        members["gear"] = member_report(pair.gear_tooth, pair.working_pitch_radii[1])
    elif pair.kind == "internal":
        members["gear"] = ring_report(pair)
        report["ring_interference_margin_mm"] = num(pair.ring_interference)
    else:
        from linkgen.mechanisms.gearparts import rack_teeth

        teeth = rack_teeth(pair, table.travel)
        members["rack"] = {"teeth": teeth, "length_mm": num(teeth * math.pi * pair.module),
                           "tooth_thickness_mm": num(math.pi * pair.module / 2),
                           "thinning_mm": num(pair.rack_thinning), "travel_mm": table.travel}
    report["gears"] = members
    report["input_range_deg"] = _range_deg(table, pair)
    report["warnings"] = warnings_of(pair)
    if angle is not None:
        report["positions"] = positions(table, pair, angle)
    return report


def _range(table: GearPairTable, pair: GearPair) -> tuple[float, float] | None:
    """A rack pinion's reachable angles (rad): its travel centred on the mesh phase; None for gears (full turns)."""
    if pair.kind != "rack":
        return None
    first, _ = pair.mesh_phases
    half = table.travel / (2 * pair.working_pitch_radii[0])
    return first - half, first + half


def _range_deg(table: GearPairTable, pair: GearPair) -> list[float] | None:
    rng = _range(table, pair)
    return None if rng is None else [round(math.degrees(x), 9) for x in rng]


def positions(table: GearPairTable, pair: GearPair, angle: float) -> dict[str, Any]:
    """Where the pair is at pinion ``angle`` (degrees) and how fast it moves at the table's rpm; a SpecError on
    ``angle`` outside a rack's travel."""
    rng = _range(table, pair)
    theta = math.radians(angle)
    if rng is not None and not rng[0] - 1e-12 <= theta <= rng[1] + 1e-12:
        lo, hi = (math.degrees(x) for x in rng)
        raise SpecError(f"the rack's travel takes the pinion from {lo:.6g} to {hi:.6g} degrees (got {angle:g})",
                        "angle")
    speed = omega(table.rpm)
    where = float(pair.gear_angle(np.array([theta]))[0])
    out: dict[str, Any] = {"pinion_deg": deg(theta), "pinion_speed_deg_s": num(math.degrees(speed))}
    if pair.kind == "rack":
        out.update({"rack_mm": num(where), "rack_speed_mm_s": num(pair.speed_ratio * speed)})
    else:
        out.update({"gear_deg": deg(where), "gear_speed_deg_s": num(math.degrees(pair.speed_ratio * speed))})
    return out


def _least_shift(tooth: ExternalTooth) -> float:
    """The least profile shift (modules) at which ``tooth``'s teeth are cut without undercut: h - z sin^2 a / 2."""
    return tooth.rack.straight_depth - tooth.teeth * math.sin(tooth.pressure_angle) ** 2 / 2


def warnings_of(pair: GearPair) -> list[str]:
    """What a designer would want to know of a pair that is still made: undercut, a low contact ratio, thin tips."""
    out = []
    members = [("pinion", pair.pinion_tooth)] + ([("gear", pair.gear_tooth)] if pair.kind == "external" else [])
    for name, tooth in members:
        assert tooth is not None
        if tooth.undercut:
            out.append(f"the {name} is undercut: {tooth.teeth} teeth at shift {tooth.shift:g}, fewer than the "
                       f"{tooth.fewest_teeth:.4g} that shift cuts whole (the rack's fillet takes the involute's foot "
                       f"away, below radius {tooth.form_radius:.4g} mm); a shift of {_least_shift(tooth):.4g} or "
                       "more avoids it")
        if tooth.tip_thickness < TIP_WARNING * pair.module:
            out.append(f"the {name}'s tips are {tooth.tip_thickness:.4g} mm thick, under a quarter module")
    if pair.contact_ratio < CONTACT_WARNING:
        out.append(f"contact ratio {pair.contact_ratio:.4f}: under {CONTACT_WARNING:g}, the pair runs rough")
    return out


@dataclass(frozen=True)
class GearPairMechanism:
    """The gear-pair mechanism (:class:`linkgen.mechanisms.Mechanism`)."""

    table: type[Model] = GearPairTable

    @property
    def types(self) -> tuple[str, ...]:
        return types_of(self.table)

    def build(self, table: GearPairTable) -> GearPair:
        """The pair; a SpecError naming ``linkage.pinion.teeth`` where the outlines overlap as it turns."""
        from linkgen.mechanisms.gearparts import overlap

        pair = table.pair
        where = overlap(pair, table.travel)
        if where is not None:
            raise SpecError(f"the teeth's outlines overlap as the pair turns (at pinion angle "
                            f"{math.degrees(where):.4f} degrees): undercut, tip or trochoid interference; give the "
                            "pinion more teeth or a larger shift", "linkage.pinion.teeth")
        return pair

    def report(self, table: GearPairTable, kinematics: GearPair, angle: float | None,
               method: str) -> dict[str, Any]:
        return pair_report(table, kinematics, angle)

    def figures(self, name: str, table: GearPairTable, kinematics: GearPair) -> tuple[Figure, ...]:
        """The pair with its base and pitch circles and its line of action, and a close view of the mesh."""
        def draw(close: bool) -> Any:
            from camgen.core.figures import drawing_figure

            drawing = _mesh_drawing(table, kinematics, close)
            what = "the mesh" if close else "the pair"
            return drawing_figure(drawing, f"{name}: {what}, with base and working pitch circles and the line of "
                                           "action")

        return (("pair", lambda: draw(False)), ("mesh", lambda: draw(True)))

    def layout(self, table: GearPairTable, kinematics: GearPair, parts: PartsTable) -> Layout:
        from linkgen.mechanisms.gearparts import pair_layout

        hubs = {key: ((gear.boss_diameter, gear.boss_height) if gear.boss_height > 0 else None, gear.set_screw)
                for key, gear in (("pinion", table.pinion), ("gear", table.gear)) if gear is not None}
        hubs.setdefault("gear", (None, 0.0))
        return pair_layout(kinematics, Stock.of(parts), parts.width, table.travel, hubs)

    def family_row(self, table: GearPairTable, kinematics: GearPair, report: dict[str, Any]) -> dict[str, Any]:
        return {"contact_ratio": report["contact_ratio"], "centre_distance_mm": report["centre_distance_mm"]}

    def sketch(self, table: GearPairTable, kinematics: GearPair) -> Drawing | None:
        return _mesh_drawing(table, kinematics, False)

    def animation_inputs(self, table: GearPairTable, kinematics: GearPair, n: int) -> np.ndarray:
        from linkgen.mechanisms.gearpairframes import pair_inputs

        return pair_inputs(kinematics, n)

    def animation_frames(self, table: GearPairTable, kinematics: GearPair, values: np.ndarray,
                         size: tuple[int, int]) -> np.ndarray:
        from linkgen.mechanisms.gearpairframes import pair_frames

        return pair_frames(kinematics, values, size)


def _mesh_drawing(table: GearPairTable, pair: GearPair, close: bool) -> Drawing:
    """The pair drawn at its mesh phase (outlines within 1 % of a module); ``close``: only what lies within three
    modules of the pitch point."""
    from camgen.core.parts import Drawing, preview_stroke
    from camgen.core.shapes import Contour, Polyline
    from linkgen.mechanisms.gearparts import outlines, pair_drawing

    shapes = outlines(pair, 0.01 * pair.module, table.travel)
    drawing = pair_drawing(pair, shapes, pair.mesh_phases[0])
    if not close:
        return drawing
    r1 = pair.working_pitch_radii[0]
    centre = {"external": (r1, 0.0), "internal": (-r1, 0.0), "rack": (0.0, -r1)}[pair.kind]
    reach = 3 * pair.module + math.sqrt(max(pair.pinion_tooth.tip_radius**2 - pair.pinion_tooth.base_radius**2, 0))
    items: list = []
    for layer, shape in drawing.items:
        points = shape.flatten(drawing.tolerance)
        if isinstance(shape, Contour) or not isinstance(shape, Polyline):
            points = np.vstack([points, points[:1]])
        inside = np.hypot(points[:, 0] - centre[0], points[:, 1] - centre[1]) <= reach
        # each run of points inside the window, as an open line
        edges = np.flatnonzero(np.diff(np.concatenate([[0], inside.astype(int), [0]])))
        for start, stop in zip(edges[::2], edges[1::2], strict=True):
            if stop - start >= 2:
                items.append((layer, Polyline(points[start:stop], np.zeros(stop - start - 1))))
    return Drawing(tuple(items), drawing.tolerance, stroke=preview_stroke(items))


REGISTER = (GearPairMechanism(),)
