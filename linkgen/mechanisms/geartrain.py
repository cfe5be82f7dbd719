"""Gear trains (``type = "gear-train"``): simple, compound and planetary trains of involute spur gears of one module
and pressure angle (unshifted); their ``[linkage]`` table, the checks, the ratio, the report, the sketch and the
parts.

Frames: a simple train's gears sit along +X from gear 0 (the input) at the origin, each at its working centre
distance from the one before; a compound train's shafts likewise; a planetary train's sun, carrier and ring turn
about the origin, planet k's centre at the carrier's angle + 360 k / planets degrees, ``carrier_radius`` from it.
Speeds and the ratio are :mod:`linkgen.kinematics.geartrain`'s; each mesh is a :class:`linkgen.gears.pair.GearPair`
(its checks are the gear pair's: contact ratio, tip clearance, an internal gear's interference, pointed teeth, and
outlines that overlap as the mesh turns through a pitch).

Checks of a train, each refused in one line naming the key: a ring whose teeth are not sun + 2 planet, planets that
cannot be spaced equally ((sun + ring) / planets not whole) or whose tips touch each other, a fixed member that is
also the input, and given centre distances (``centre_distances``, ``carrier_radius``) other than those the teeth
mesh at.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Annotated, Any, Literal

import numpy as np
from pydantic import Field, model_validator

from camgen.core.errors import DesignError, SpecError
from camgen.core.spec import MAX_LENGTH_MM, Model, notes, unit
from linkgen.gears.pair import GearPair
from linkgen.gears.tooth import BasicRack, ExternalTooth
from linkgen.kinematics.geartrain import CompoundTrain, PlanetaryTrain, SimpleTrain, angles
from linkgen.mechanisms.common import Figure, deg, num, omega, rpm, types_of
from linkgen.mechanisms.gearpair import CENTRE_TOLERANCE_MM, MAX_MODULE, MAX_TEETH, MIN_TEETH
from linkgen.parts import Layout, Stock

if TYPE_CHECKING:
    from camgen.core.parts import Drawing
    from linkgen.spec import PartsTable

#: the most gears of a simple train, stages of a compound one, planets of a planetary one
MAX_GEARS, MAX_STAGES, MAX_PLANETS = 12, 6, 12
#: the least gap (mm) between two neighbouring planets' tip circles
PLANET_GAP_MM = 0.5

Teeth = Annotated[int, Field(ge=MIN_TEETH, le=MAX_TEETH)]
Distance = Annotated[float, Field(gt=0, le=MAX_LENGTH_MM)]
Member = Literal["sun", "carrier", "ring"]


class GearTrainTable(Model):
    """``[linkage]`` of a gear train: its kind, the module and pressure angle all its gears share, their teeth, the
    backlash of every mesh."""

    type: Literal["gear-train"]
    kind: Literal["simple", "compound", "planetary"] = Field("simple", description="gears in a row on fixed axes "
                                                             "(simple), pairs whose driven gear shares a shaft with "
                                                             "the next driver (compound), or sun, planets and ring "
                                                             "(planetary)")
    module: float = Field(gt=0, le=MAX_MODULE, description="module m of every gear: reference diameter per tooth",
                          json_schema_extra=unit("mm"))
    pressure_angle: float = Field(20.0, ge=10.0, le=30.0, description="pressure angle of the basic rack",
                                  json_schema_extra=unit("degrees"))
    teeth: list[Teeth] | None = Field(None, min_length=2, max_length=MAX_GEARS,
                                      description=f"a simple train's gears' teeth in mesh order (2 to {MAX_GEARS} "
                                                  f"gears of {MIN_TEETH} to {MAX_TEETH} teeth), the first the input",
                                      json_schema_extra=notes(absent="compound and planetary trains"))
    stages: list[tuple[Teeth, Teeth]] | None = Field(None, min_length=1, max_length=MAX_STAGES,
                                                     description="a compound train's stages, each [driver, driven] "
                                                                 f"teeth (1 to {MAX_STAGES} stages)",
                                                     json_schema_extra=notes(absent="simple and planetary trains"))
    sun: Teeth | None = Field(None, description="a planetary train's sun's teeth",
                              json_schema_extra=notes(absent="simple and compound trains"))
    planet: Teeth | None = Field(None, description="each planet's teeth",
                                 json_schema_extra=notes(absent="simple and compound trains"))
    ring: Teeth | None = Field(None, description="the ring's (internal gear's) teeth",
                               json_schema_extra=notes(allowed="sun + 2 planet",
                                                       absent="simple and compound trains"))
    planets: int = Field(3, ge=1, le=MAX_PLANETS, description="how many planets, equally spaced on the carrier",
                         json_schema_extra=notes(allowed="(sun + ring) / planets whole, tips clear of each other"))
    fixed: Member = Field("ring", description="a planetary train's member held still")
    input: Member = Field("sun", description="a planetary train's driven member (the third is the output)")
    centre_distances: list[Distance] | None = Field(None, max_length=MAX_GEARS,
                                                    description="each mesh's centre distance (a simple train's "
                                                 "meshes in order, a compound train's stages), checked against the "
                                                 "one the teeth mesh at",
                                                 json_schema_extra=unit("mm", allowed=f"within {CENTRE_TOLERANCE_MM:g}"
                                                                        " mm of m (z1 + z2) / 2, each > 0",
                                                                        absent="the working centre distances"))
    carrier_radius: float | None = Field(None, gt=0, le=MAX_LENGTH_MM, description="a planetary train's distance "
                                         "from the sun's centre to each planet's, checked against m (sun + planet) "
                                         "/ 2", json_schema_extra=unit("mm", allowed=f"within {CENTRE_TOLERANCE_MM:g}"
                                                                       " mm of m (sun + planet) / 2",
                                                                       absent="m (sun + planet) / 2"))
    backlash: float = Field(0.1, gt=0, le=50.0, description="play between the teeth of every mesh along the pitch "
                            "circles: each gear's teeth are thinned by half of it", json_schema_extra=unit("mm"))
    rpm: float = rpm()

    @model_validator(mode="after")
    def _consistent(self) -> GearTrainTable:
        given = {"teeth": self.teeth is not None, "stages": self.stages is not None,
                 "sun": any(v is not None for v in (self.sun, self.planet, self.ring))}
        wanted = {"simple": "teeth", "compound": "stages", "planetary": "sun"}[self.kind]
        if not given[wanted]:
            hint = {"teeth": "teeth = [20, 35] (each gear's, in mesh order)",
                    "stages": "stages = [[15, 45], [15, 40]] (each stage's driver and driven teeth)",
                    "sun": "sun, planet and ring (teeth)"}[wanted]
            raise ValueError(f"{wanted}: a {self.kind} train needs {hint}")
        for key, present in given.items():
            if present and key != wanted:
                raise ValueError(f"{key}: not for a {self.kind} train (kind = \"{self.kind}\" takes {wanted})")
        if self.kind == "planetary":
            for key in ("sun", "planet", "ring"):
                if getattr(self, key) is None:
                    raise ValueError(f"{key}: missing: a planetary train needs sun, planet and ring teeth")
            assert self.sun is not None and self.planet is not None and self.ring is not None
            if self.ring != self.sun + 2 * self.planet:
                raise ValueError(f"ring: must have sun + 2 planet = {self.sun + 2 * self.planet} teeth for the planets "
                                 f"to mesh with both (got {self.ring})")
            if self.fixed == self.input:
                raise ValueError(f"input: the {self.fixed} is held still: drive another member (sun, carrier, ring)")
            if (self.sun + self.ring) % self.planets:
                raise ValueError(f"planets: {self.planets} planets cannot be spaced equally: (sun + ring) / planets "
                                 f"= {(self.sun + self.ring) / self.planets:g} must be whole")
        for key in ("centre_distances", "carrier_radius"):
            if getattr(self, key) is not None and (key == "carrier_radius") != (self.kind == "planetary"):
                raise ValueError(f"{key}: not for a {self.kind} train")
        if self.centre_distances is not None and len(self.centre_distances) != len(self.meshes):
            raise ValueError(f"centre_distances: give one for each of the {len(self.meshes)} meshes (got "
                             f"{len(self.centre_distances)})")
        widest = max(self.module * z for z in self.all_teeth)
        if not widest <= MAX_LENGTH_MM:
            raise ValueError(f"module: a gear would be {widest:g} mm across, over {MAX_LENGTH_MM:g} mm")
        return self

    @property
    def all_teeth(self) -> tuple[int, ...]:
        if self.kind == "simple":
            assert self.teeth is not None
            return tuple(self.teeth)
        if self.kind == "compound":
            assert self.stages is not None
            return tuple(z for stage in self.stages for z in stage)
        return tuple(z for z in (self.sun, self.planet, self.ring) if z is not None)

    @property
    def meshes(self) -> tuple[tuple[int, int], ...]:
        """Each mesh's (pinion, gear) teeth: a simple train's neighbours, a compound train's stages, a planetary
        train's sun-planet and planet-ring (internal) meshes."""
        if self.kind == "simple":
            assert self.teeth is not None
            return tuple(zip(self.teeth[:-1], self.teeth[1:], strict=True))
        if self.kind == "compound":
            assert self.stages is not None
            return tuple((a, b) for a, b in self.stages)
        assert self.sun is not None and self.planet is not None and self.ring is not None
        return ((self.sun, self.planet), (self.planet, self.ring))

    def lengths_mm(self) -> dict[str, float]:
        """The report's lengths: the module and each mesh's centre distance (mm)."""
        return {"module": self.module, **{f"mesh{k + 1}": round(p.centre_distance, 9)
                                          for k, p in enumerate(pairs(self))}}


def pairs(table: GearTrainTable) -> tuple[GearPair, ...]:
    """Each mesh as a gear pair (unshifted teeth, the table's backlash); a planetary train's second is internal."""
    rack = BasicRack(table.module, math.radians(table.pressure_angle))
    out = []
    for k, (z1, z2) in enumerate(table.meshes):
        kind: Literal["external", "internal"] = "internal" if table.kind == "planetary" and k == 1 else "external"
        out.append(GearPair(kind, rack, z1, 0.0, z2, 0.0, table.backlash))
    return tuple(out)


@dataclass(frozen=True)
class Gear:
    """One gear of a train: its name, teeth, tooth (an internal gear's master), centre at the input angle 0 (mm),
    speed per unit input speed, phase (rad: its angle at input angle 0), whether it is internal, and the names of
    the carrier it rides on (or '') and of the gear sharing its shaft (or '')."""

    name: str
    teeth: int
    tooth: ExternalTooth
    centre: tuple[float, float]
    speed: float
    phase: float
    internal: bool = False
    carrier: str = ""
    shaft: str = ""


def _delta(direction: float, angle: float, teeth: int) -> float:
    """Where a gear at ``angle`` (tooth 0 centred on +X at 0) has its teeth at ``direction`` (rad): 0 a tooth
    centred there, 1/2 a space, in [0, 1)."""
    return ((direction - angle) * teeth / (2 * math.pi)) % 1.0


def _meshing(direction: float, angle: float, teeth: int, other: int, internal: bool = False) -> float:
    """The angle of a gear of ``other`` teeth meshing at ``direction`` (from the first gear's centre to the
    contact) with a gear of ``teeth`` at ``angle``, sharing the backlash: externally a space of the one on a tooth of
    the other (its own direction to the contact is the opposite); internally (``other`` a ring's master, whose
    teeth are the ring's spaces) the gear's tooth in the ring's space, at the same direction."""
    d = _delta(direction, angle, teeth)
    pitch = 2 * math.pi / other
    if internal:
        return direction - pitch * d
    return direction + math.pi - pitch * (0.5 - d)


@dataclass(frozen=True)
class Train:
    """A gear train built from its table: its gears at the input angle 0, its ratio and each mesh as a pair."""

    table: GearTrainTable

    @cached_property
    def pairs(self) -> tuple[GearPair, ...]:
        return pairs(self.table)

    @cached_property
    def kinematics(self) -> SimpleTrain | CompoundTrain | PlanetaryTrain:
        t = self.table
        if t.kind == "simple":
            assert t.teeth is not None
            return SimpleTrain(tuple(t.teeth))
        if t.kind == "compound":
            assert t.stages is not None
            return CompoundTrain(tuple((a, b) for a, b in t.stages))
        assert t.sun is not None and t.planet is not None and t.ring is not None
        return PlanetaryTrain(t.sun, t.planet, t.ring, t.fixed, t.input)

    @property
    def ratio(self) -> float:
        """The output's speed per unit input speed."""
        return self.kinematics.ratio

    @cached_property
    def gears(self) -> tuple[Gear, ...]:
        t, ps = self.table, self.pairs
        if t.kind == "planetary":
            return self._planetary()
        speeds = self.kinematics.speeds
        assert isinstance(speeds, tuple)
        out: list[Gear] = []
        x, angle = 0.0, 0.0
        for k, p in enumerate(ps):
            if t.kind == "simple":
                if k == 0:
                    out.append(Gear("gear1", p.pinion_teeth, p.pinion_tooth, (0.0, 0.0), speeds[0], 0.0))
                driver = out[-1]
            else:
                shaft = f"gear{2 * k}" if k else ""
                driver = Gear(f"gear{2 * k + 1}", p.pinion_teeth, p.pinion_tooth, (x, 0.0), speeds[k], angle,
                              shaft=shaft)
                if k:
                    out[-1] = Gear(out[-1].name, out[-1].teeth, out[-1].tooth, out[-1].centre, out[-1].speed,
                                   out[-1].phase, shaft=driver.name)
                out.append(driver)
            x += p.centre_distance
            gear = p.gear_tooth
            assert gear is not None
            angle = _meshing(0.0, driver.phase, driver.teeth, p.gear_teeth)
            out.append(Gear(f"gear{len(out) + 1}", p.gear_teeth, gear, (x, 0.0), speeds[k + 1], angle))
        return tuple(out)

    def _planetary(self) -> tuple[Gear, ...]:
        t = self.table
        outer, inner = self.pairs
        speeds = self.kinematics.speeds
        assert isinstance(speeds, dict) and t.planets >= 1
        a = outer.centre_distance
        gears = [Gear("sun", outer.pinion_teeth, outer.pinion_tooth, (0.0, 0.0), speeds["sun"], 0.0)]
        planet_tooth = outer.gear_tooth
        assert planet_tooth is not None and inner.gear_tooth is not None
        for k in range(t.planets):
            psi = 2 * math.pi * k / t.planets
            phase = _meshing(psi, 0.0, outer.pinion_teeth, outer.gear_teeth)
            gears.append(Gear(f"planet{k + 1}", outer.gear_teeth, planet_tooth, (a * math.cos(psi), a * math.sin(psi)),
                              speeds["planet"], phase, carrier="carrier"))
        ring = _meshing(0.0, gears[1].phase, inner.pinion_teeth, inner.gear_teeth, internal=True)
        gears.append(Gear("ring", inner.gear_teeth, inner.gear_tooth, (0.0, 0.0), speeds["ring"], ring, internal=True))
        return tuple(gears)

    @property
    def carrier_speed(self) -> float:
        """The carrier's speed per unit input speed (0 for a train on fixed axes)."""
        speeds = self.kinematics.speeds
        return speeds["carrier"] if isinstance(speeds, dict) else 0.0

    def poses(self, theta: np.ndarray) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
        """Each gear's angle (n,) rad and centre (n, 2) mm, and the carrier's, at input angles ``theta`` (rad)."""
        g = self.gears
        turned = angles([x.speed for x in g], theta, [x.phase for x in g])
        carrier = self.carrier_speed * np.asarray(theta, dtype=float)
        c, s = np.cos(carrier), np.sin(carrier)
        out_angles = {x.name: turned[k] for k, x in enumerate(g)}
        centres = {}
        for x in g:
            cx, cy = x.centre
            centres[x.name] = (np.column_stack([c * cx - s * cy, s * cx + c * cy]) if x.carrier else
                               np.tile([cx, cy], (len(carrier), 1)))
        out_angles["carrier"] = carrier
        centres["carrier"] = np.zeros((len(carrier), 2))
        return out_angles, centres


def check(table: GearTrainTable, train: Train) -> None:
    """Every mesh's checks (a gear pair's) and the given centre distances, each a ValueError naming the key."""
    where = {"simple": "teeth", "compound": "stages", "planetary": "planet"}[table.kind]
    for k, p in enumerate(train.pairs):
        teeth = [p.pinion_tooth] + ([p.gear_tooth] if p.kind == "external" and p.gear_tooth is not None else [])
        for tooth in teeth:
            try:
                tooth.check()
            except DesignError as exc:
                raise ValueError(f"{where}: {exc} ({tooth.teeth} teeth)") from None
        if not p.contact_ratio >= 1:
            raise ValueError(f"{where}: mesh {k + 1}'s contact ratio is {p.contact_ratio:.4f} < 1: give more teeth")
        if not min(p.tip_clearance) > 0:
            raise ValueError(f"{where}: mesh {k + 1}'s tips reach the other gear's root circle")
        if p.kind == "internal" and p.ring_interference < 0:
            raise ValueError(f"ring: its tips reach {-p.ring_interference:.4g} mm past the planet's base circle on the "
                             "line of action (involute interference): give the planets more teeth")
    given = table.centre_distances if table.kind != "planetary" else (
        None if table.carrier_radius is None else [table.carrier_radius])
    key = "centre_distances" if table.kind != "planetary" else "carrier_radius"
    for k, c in enumerate(given or ()):
        want = train.pairs[k].centre_distance
        if abs(c - want) > CENTRE_TOLERANCE_MM:
            raise ValueError(f"{key}: mesh {k + 1}'s teeth mesh at {want:.6f} mm (got {c:g}); leave it out or give "
                             "that")
    if table.kind == "planetary":
        a, tip = train.pairs[0].centre_distance, train.pairs[0].gear_tooth
        assert tip is not None
        gap = 2 * a * math.sin(math.pi / table.planets) - 2 * tip.tip_radius if table.planets > 1 else math.inf
        if gap < PLANET_GAP_MM:
            raise ValueError(f"planets: neighbouring planets' tips come {gap:.4g} mm apart (at least "
                             f"{PLANET_GAP_MM:g} mm): give fewer planets or a larger sun")


def train_report(table: GearTrainTable, train: Train, angle: float | None) -> dict[str, Any]:
    """The report's gear-train section (mm, degrees, rpm at the table's rpm)."""
    gears = [{"name": g.name, "teeth": g.teeth, "pitch_diameter_mm": num(table.module * g.teeth),
              "centre_mm": [num(g.centre[0]), num(g.centre[1])], "speed_ratio": num(g.speed),
              "rpm": num(g.speed * table.rpm), "internal": g.internal,
              **({"on": g.carrier} if g.carrier else {}), **({"shaft_with": g.shaft} if g.shaft else {})}
             for g in train.gears]
    meshes = [{"teeth": [p.pinion_teeth, p.gear_teeth], "kind": p.kind, "centre_distance_mm": num(p.centre_distance),
               "contact_ratio": num(p.contact_ratio)} for p in train.pairs]
    report: dict[str, Any] = {"kind": table.kind, "module_mm": table.module, "ratio": num(train.ratio),
                              "gears": gears, "meshes": meshes, "backlash_mm": table.backlash,
                              "input_range_deg": None, "warnings": _warnings(train)}
    k = train.kinematics
    if isinstance(k, PlanetaryTrain):
        report["planetary"] = {"fixed": k.fixed, "input": k.driven, "output": k.output,
                               "carrier_radius_mm": num(train.pairs[0].centre_distance), "planets": table.planets,
                               "willis": "(w_sun - w_carrier) / (w_ring - w_carrier) = -ring / sun",
                               "speeds": {m: num(v) for m, v in k.speeds.items()}}
    if angle is not None:
        theta = np.array([math.radians(angle)])
        turned, centres = train.poses(theta)
        w = math.degrees(omega(table.rpm))
        report["positions"] = {
            "input_deg": deg(theta[0]),
            "gears": {g.name: {"angle_deg": deg(turned[g.name][0]), "speed_deg_s": num(g.speed * w),
                               "centre_mm": [num(centres[g.name][0, 0]), num(centres[g.name][0, 1])]}
                      for g in train.gears},
            **({"carrier_deg": deg(turned["carrier"][0])} if table.kind == "planetary" else {})}
    return report


def _warnings(train: Train) -> list[str]:
    seen, out = set(), []
    for g in train.gears:
        if not g.internal and g.tooth.undercut and g.teeth not in seen:
            seen.add(g.teeth)
            out.append(f"{g.name} is undercut: {g.teeth} teeth, fewer than the {g.tooth.fewest_teeth:.4g} an "
                       "unshifted gear cuts whole")
    return out


def _outline(g: Gear, tolerance: float) -> Any:
    from linkgen.gears.outline import gear_outline, ring_outline

    if g.internal:
        return ring_outline(g.tooth, g.tooth.pitch_radius - g.tooth.module, tolerance)
    return gear_outline(g.tooth, tolerance)


def train_sketch(train: Train, tolerance: float) -> Drawing:
    """The train at input angle 0: every gear's outline (a ring's teeth), its pitch circle, the carrier's arms."""
    from camgen.core.parts import Drawing, preview_stroke
    from camgen.core.shapes import Circle, Contour, Polyline

    turned, centres = train.poses(np.zeros(1))
    items: list[tuple[str, Any]] = []
    for g in train.gears:
        c = centres[g.name][0]
        items.append((g.name if not g.carrier else "planets", Contour(*_outline(g, tolerance)).moved(
            float(turned[g.name][0]), c)))
        items.append(("pitch circles", Circle((float(c[0]), float(c[1])), g.tooth.pitch_radius)))
        if g.carrier:
            items.append(("carrier", Polyline(np.array([[0.0, 0.0], c]), np.zeros(1))))
    return Drawing(tuple(items), tolerance, stroke=preview_stroke(items))


@dataclass(frozen=True)
class GearTrainMechanism:
    """The gear-train mechanism (:class:`linkgen.mechanisms.Mechanism`)."""

    table: type[Model] = GearTrainTable

    @property
    def types(self) -> tuple[str, ...]:
        return types_of(self.table)

    def build(self, table: GearTrainTable) -> Train:
        """The train; a SpecError naming the key where a check fails or a mesh's outlines overlap as it turns."""
        from linkgen.mechanisms.gearparts import overlap

        train = Train(table)
        try:
            check(table, train)
        except ValueError as exc:
            key, _, what = str(exc).partition(": ")
            raise SpecError(what, f"linkage.{key}") from None
        for k, p in enumerate(train.pairs):
            where = overlap(p)
            if where is not None:
                raise SpecError(f"mesh {k + 1}'s outlines overlap as it turns (at its pinion's angle "
                                f"{math.degrees(where):.4f} degrees): undercut, tip or trochoid interference; give "
                                "its gears more teeth", "linkage.teeth" if table.kind == "simple" else
                                f"linkage.{'stages' if table.kind == 'compound' else 'planet'}")
        return train

    def report(self, table: GearTrainTable, kinematics: Train, angle: float | None, method: str) -> dict[str, Any]:
        if method == "newton":
            raise SpecError("the Newton-Raphson table is for four-bars; a gear train is solved in closed form",
                            "--method")
        return train_report(table, kinematics, angle)

    def figures(self, name: str, table: GearTrainTable, kinematics: Train) -> tuple[Figure, ...]:
        def draw() -> Any:
            from camgen.core.figures import drawing_figure

            return drawing_figure(train_sketch(kinematics, 0.01 * table.module),
                                  f"{name}: the {table.kind} train, ratio {kinematics.ratio:.6g}")

        return (("train", draw),)

    def layout(self, table: GearTrainTable, kinematics: Train, parts: PartsTable) -> Layout:
        from linkgen.mechanisms.geartrainparts import train_layout

        return train_layout(kinematics, Stock.of(parts), parts.width)

    def family_row(self, table: GearTrainTable, kinematics: Train, report: dict[str, Any]) -> dict[str, Any]:
        return {"ratio": report["ratio"]}

    def sketch(self, table: GearTrainTable, kinematics: Train) -> Drawing | None:
        return train_sketch(kinematics, 0.01 * table.module)

    def animation_inputs(self, table: GearTrainTable, kinematics: Train, n: int) -> np.ndarray:
        from linkgen.mechanisms.geartrainframes import train_inputs

        return train_inputs(kinematics, n)

    def animation_frames(self, table: GearTrainTable, kinematics: Train, values: np.ndarray,
                         size: tuple[int, int]) -> np.ndarray:
        from linkgen.mechanisms.geartrainframes import train_frames

        return train_frames(kinematics, values, size)


REGISTER = (GearTrainMechanism(),)
