"""The ``[dynamics]`` table: what a linkage is made of, how fast it runs, and what acts on it besides its loads.

Every key has its unit and range here (the template reference is made from these descriptions); the cross-key rules
(a link that exists, a spring's joints, a flywheel on a crank) are checked where the linkage is known
(:func:`linkgen.dynamics.run.dynamics_of`), each in one line naming the key.
"""
from __future__ import annotations

import math
from typing import Any, Literal

from pydantic import Field, field_validator, model_validator

from camgen.core.spec import MAX_LENGTH_MM, Model, length, notes, unit
from linkgen.dynamics.materials import SHEETS, PinName, SheetName
from linkgen.dynamics.motor import MotorTable

#: the heaviest link (kg) and the largest inertia (kg*mm^2) a user may give
MAX_MASS_KG, MAX_INERTIA = 10_000.0, 1e12
#: the densest material (kg/m^3): osmium is 22 590
MAX_DENSITY = 25_000.0
#: the stiffest spring (N/mm)
MAX_STIFFNESS = 1e6
#: the fastest slide input (mm/s) and the largest input acceleration (rad/s^2 or mm/s^2)
MAX_SPEED_MM_S, MAX_ACCELERATION = 1e5, 1e6
#: the fastest crank speed a profile's row may give (rpm), as linkage.rpm's bound (``linkgen.spec.MAX_RPM``); the
#: fewest and the most rows of a profile
MAX_PROFILE_RPM, MIN_ROWS, MAX_ROWS = 100_000.0, 4, 3600
#: the most poses over the motion
MAX_POSES = 20_000
#: the largest allowable stress a user may give (MPa)
MAX_STRESS = 10_000.0


class LinkMassTable(Model):
    """One link's mass properties given instead of computed from its part (``[dynamics.links.<link>]``): any of them;
    the others come from the link's part (all three when the template has no ``[parts]``)."""

    mass: float | None = Field(None, ge=0, le=MAX_MASS_KG, description="the link's mass, its pins and hardware "
                               "included", json_schema_extra=unit("kg", absent="the part's"))
    centre: tuple[float, float] | None = Field(None, description="its centre of mass in the link's own frame: the "
                                               "origin at its first joint, +x towards its second (a slider's block: "
                                               "along its guide)",
                                               json_schema_extra=unit("mm", absent="the part's centroid"))
    inertia: float | None = Field(None, ge=0, le=MAX_INERTIA, description="its moment of inertia about its centre "
                                  "of mass", json_schema_extra=unit("kg*mm^2", absent="the part's"))

    @model_validator(mode="after")
    def _centre_bounded(self) -> LinkMassTable:
        if self.centre is not None and not all(abs(v) <= MAX_LENGTH_MM for v in self.centre):
            raise ValueError(f"centre: must lie within {MAX_LENGTH_MM:g} mm of the link's first joint "
                             f"(got {list(self.centre)})")
        return self


class SpringTable(Model):
    """A spring between two joints (``[[dynamics.springs]]``): it pulls them together with stiffness x (length -
    free length), and pushes them apart when shorter."""

    between: tuple[str, str] = Field(description="the two joints it joins (a ground joint anchors it)")
    links: tuple[str, str] | None = Field(None, description="the links its ends are on, in the same order",
                                          json_schema_extra=notes(absent="each joint's first moving link, or the "
                                                                         "ground for a ground joint"))
    stiffness: float = Field(gt=0, le=MAX_STIFFNESS, description="spring rate", json_schema_extra=unit("N/mm"))
    free_length: float = length("its length when it pulls nothing", zero=True)


class FlywheelTable(Model):
    """A flywheel on the crank's shaft (``[dynamics.flywheel]``), sized for a coefficient of speed fluctuation and
    made as a part of the sheet's material, behind the frame."""

    fluctuation: float = Field(gt=0, le=0.5, description="coefficient of speed fluctuation (max - min speed) / "
                               "mean speed it must keep the crank within")
    shape: Literal["disc", "rim"] = Field("disc", description="a plain disc, or a rim on four spokes (lighter for "
                                          "the same inertia)")
    plates: int = Field(1, ge=1, le=20, description="plates of the sheet stacked to make it")
    rim_width: float | None = Field(None, gt=0, le=1000.0, description="the rim's and the spokes' width (rim only)",
                                    json_schema_extra=unit("mm", absent="twice parts.width"))


class DynamicsTable(Model):
    """``[dynamics]``: the links' materials and masses, the speed, gravity and springs; the report gives every joint's
    force, the driving torque, the shaking, the power, a flywheel and a counterweight, and whether the holes and pins
    hold (see docs/guides/dynamics.md)."""

    material: SheetName = Field("plywood", description="the parts' material: its density, how they "
                                             "are made (laser-cut or printed) and its allowable bearing pressure")
    density: float | None = Field(None, gt=0, le=MAX_DENSITY, description="the parts' density, instead of the "
                                  "material's", json_schema_extra=unit("kg/m^3", absent="the material's"))
    infill: float = Field(1.0, gt=0, le=1, description="printed parts (pla, petg): their solid fraction, walls and "
                          "skins counted (a 3 mm plate with two perimeters at 20 % infill is about 0.5)")
    pins: PinName = Field("steel", description="the pins' material (a kit's bolts are steel)")
    speed: float = Field(100.0, gt=0, le=MAX_SPEED_MM_S, description="a slide input's speed (a crank runs at "
                         "linkage.rpm; not with speed_profile)", json_schema_extra=unit("mm/s"))
    input_acceleration: float = Field(0.0, ge=-MAX_ACCELERATION, le=MAX_ACCELERATION,
                                      description="the input's acceleration at every pose: rad/s^2 for a crank, "
                                                  "mm/s^2 for a slide (not with speed_profile)",
                                      json_schema_extra=unit("rad/s^2 or mm/s^2"))
    speed_profile: tuple[tuple[float, float], ...] | Literal["motor"] | None = Field(
        None, description=f"the input's speed over the motion instead of a constant one: rows [[crank_deg, rpm], ...] "
        f"over one turn ({MIN_ROWS} to {MAX_ROWS} rows, the crank angles strictly increasing and less than 360 "
        f"degrees past the first, each rpm > 0 and <= {MAX_PROFILE_RPM:g}), a periodic cubic spline through them "
        f"with the acceleration w dw/dtheta; a slide's rows [[position_mm, speed_mm_s], ...] over the travel "
        f"analysed (speeds > 0 and <= {MAX_SPEED_MM_S:g} mm/s, a natural cubic spline); or \"motor\": the steady "
        "turn the [dynamics.motor] run reaches", json_schema_extra=unit(
            "degrees and rpm, or mm and mm/s", absent="constant: linkage.rpm (a crank) or speed (a slide), at "
            "input_acceleration"))
    incline: float = Field(90.0, ge=0, le=90, description="the mechanism's plane against the horizontal: 90 "
                           "upright (all of gravity in its plane), 0 lying flat (none)",
                           json_schema_extra=unit("degrees"))
    gravity_angle: float = Field(-90.0, ge=-360, le=360, description="the direction gravity pulls in the drawing, "
                                 "counter-clockwise from +X (-90: down the drawing's y)",
                                 json_schema_extra=unit("degrees"))
    links: dict[str, LinkMassTable] = Field(default_factory=dict, description="links' masses given instead of "
                                            "computed: [dynamics.links.coupler] mass = 0.05")
    springs: tuple[SpringTable, ...] = Field((), max_length=50, description="springs between joints")
    flywheel: FlywheelTable | None = Field(None, description="a flywheel for a coefficient of speed fluctuation")
    motor: MotorTable | None = Field(None, description="a motor on the crank: the motion from rest, its steady "
                                     "speed and its fluctuation, or where it stalls")
    allowable_bearing: float | None = Field(None, gt=0, le=MAX_STRESS, description="the bearing pressure a hole may "
                                            "carry, instead of the material's",
                                            json_schema_extra=unit("MPa", absent="the material's"))
    allowable_shear: float | None = Field(None, gt=0, le=MAX_STRESS, description="the shear stress a pin may carry, "
                                          "instead of its material's",
                                          json_schema_extra=unit("MPa", absent="the pins' material's"))
    poses: int = Field(720, ge=36, le=MAX_POSES, description="poses over the motion (a crank's turn, or the input's "
                       "range) the forces are computed at")

    @field_validator("speed_profile", mode="before")
    @classmethod
    def _profile_rows(cls, value: Any) -> Any:
        if value is None or value == "motor":
            return value
        if isinstance(value, str) or not isinstance(value, (list, tuple)):
            raise ValueError(f'must be "motor" or rows [[crank_deg, rpm], ...] (got {value!r})')
        if not MIN_ROWS <= len(value) <= MAX_ROWS:
            raise ValueError(f"needs {MIN_ROWS} to {MAX_ROWS} rows [[crank_deg, rpm], ...] (got {len(value)})")
        rows: list[tuple[float, float]] = []
        for k, row in enumerate(value):
            if not (isinstance(row, (list, tuple)) and len(row) == 2 and all(
                    isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and abs(v) <= 1e6
                    for v in row)):
                raise ValueError(f"{k}: a row is two finite numbers [crank_deg, rpm] (or [position_mm, speed_mm_s]) "
                                 f"within 1e6 in size (got {row!r})")
            if row[1] <= 0:
                raise ValueError(f"{k}: a speed must be > 0 rpm (or mm/s) (got {row[1]:g})")
            if k and row[0] <= rows[-1][0]:
                raise ValueError(f"{k}: the rows' crank angles (or positions) must increase strictly (got "
                                 f"{row[0]:g} after {rows[-1][0]:g})")
            rows.append((float(row[0]), float(row[1])))
        return tuple(rows)

    @model_validator(mode="after")
    def _one_speed(self) -> DynamicsTable:
        if self.speed_profile is None:
            return self
        for key in ("input_acceleration", "speed"):
            if key in self.model_fields_set:
                raise ValueError(f"{key}: dynamics.speed_profile gives the input's speed and acceleration at every "
                                 f"pose: give dynamics.speed_profile or dynamics.{key}, not both")
        if self.speed_profile == "motor" and self.motor is None:
            raise ValueError('speed_profile: "motor" is the steady turn the [dynamics.motor] run reaches: give a '
                             "[dynamics.motor], or rows [[crank_deg, rpm], ...]")
        return self

    @model_validator(mode="after")
    def _infill_printed(self) -> DynamicsTable:
        if self.infill != 1 and SHEETS[self.material].made != "printed":
            printed = ", ".join(k for k, m in SHEETS.items() if m.made == "printed")
            raise ValueError(f"infill: is for printed parts ({printed}); a {self.material} sheet is solid: leave "
                             f"it at 1 (got {self.infill:g})")
        return self
