"""What a cam does at a speed, as typed records: the peak rates in time, the contact check, the forces on the shaft
and the contact, and the table of them over a range of speeds.

:func:`camgen.dynamics.speed_report` builds a :class:`Speed`; :mod:`camgen.forces` builds its :class:`Forces` and
:class:`SpeedTable`. Each record's ``as_report()`` gives the JSON report's dict (keys carry their units; the
report's keys are the user-facing contract, so they stay as they were when these figures were dicts). Units: mm, N,
N*m, W, MPa, rpm, rad/s and degrees of cam angle; an oscillating follower's rates in degrees (``Speed.unit``).
Signs: a contact force presses the follower onto the cam; a torque is what the shaft supplies in the cam's sense of
turning (:mod:`camgen.forces`).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

#: the stress of a knife edge, which touches on a line of no width
KNIFE_NOTE = "a knife edge touches the cam on a line of no width: no Hertz pressure"


@dataclass(frozen=True)
class Unanalysed:
    """A contact the check does not cover (an oscillating follower but a roller's arm held by a spring, a load or
    its weight): ``note`` says so."""

    note: str
    mode: ClassVar[str | None] = None
    holds: ClassVar[bool | None] = None

    def as_report(self) -> dict[str, Any]:
        """The report's ``speed.contact``."""
        return {"mode": None, "note": self.note}


@dataclass(frozen=True)
class GravityHold:
    """A translating follower held on its cam by its weight alone (no spring, load, tilt nor margin): it leaves
    where it must decelerate faster than g.

    Attributes
    ----------
    liftoff_rpm : float or None
        The speed (rpm) above which it leaves; None where it never decelerates (held at any speed).
    liftoff_at_deg : float or None
        The cam angle (degrees) where it leaves first; None where it never does.
    holds : bool
        Whether it stays on at the design's speed.
    """

    liftoff_rpm: float | None
    liftoff_at_deg: float | None
    holds: bool
    mode: ClassVar[str | None] = "gravity"

    def as_report(self) -> dict[str, Any]:
        """The report's ``speed.contact``."""
        return {"mode": "gravity", "liftoff_rpm": self.liftoff_rpm, "liftoff_at_deg": self.liftoff_at_deg,
                "holds": self.holds}


@dataclass(frozen=True)
class LoadRange:
    """A load table's least and largest load (N) and its number of rows, read linearly and periodically."""

    least: float
    most: float
    rows: int

    def as_report(self) -> dict[str, Any]:
        """The report's ``speed.contact.load_table_n``."""
        return {"min": self.least, "max": self.most, "rows": self.rows,
                "interpolation": "linear, periodic over the turn"}


@dataclass(frozen=True)
class HeldContact:
    """The contact force of a follower held on its cam (by a spring, its weight, a load), from the
    :class:`~camgen.dynamics.Loading` at the design's speed.

    Attributes
    ----------
    mode : str
        ``"spring"`` with a spring rate or preload, ``"gravity"`` without.
    spring_rate, preload, load, weight, margin : float
        The loading: spring rate (N/mm), preload (N), constant external load (N, + pressing on), the weight's part
        along the follower's path at rest (N) and the least force wanted (N).
    force_min, force_min_at_deg : float
        The least contact force over the turn (N; < 0: the follower leaves) and where (degrees).
    holds : bool
        Whether the least force stays above the margin.
    preload_needed : float
        The preload (N) that would keep the least force at the margin with this rate.
    rate_needed : float or None
        The rate (N/mm) that would do so with this preload; None where no rate can (only a preload helps).
    rate_needed_at_deg : float or None
        Where (degrees) that rate is needed (the largest of shortfall / travel over the points away from rest);
        None when no rate is needed (0) or none can help.
    liftoff_rpm : float or None
        The speed (rpm) above which the follower leaves; 0 if it leaves at rest, None if held at any speed.
    load_table : LoadRange or None
        The load table's range, with one.
    segment_loads : tuple of float or None
        Each segment's own load (N, by index), with them.
    """

    mode: str
    spring_rate: float
    preload: float
    load: float
    weight: float
    margin: float
    force_min: float
    force_min_at_deg: float
    holds: bool
    preload_needed: float
    rate_needed: float | None
    liftoff_rpm: float | None
    load_table: LoadRange | None = None
    segment_loads: tuple[float, ...] | None = None
    rate_needed_at_deg: float | None = None

    def as_report(self) -> dict[str, Any]:
        """The report's ``speed.contact``."""
        out: dict[str, Any] = {
            "mode": self.mode, "spring_rate_n_mm": self.spring_rate, "preload_n": self.preload, "load_n": self.load,
            "weight_n": self.weight, "margin_n": self.margin, "force_min_n": self.force_min,
            "force_min_at_deg": self.force_min_at_deg, "holds": self.holds, "preload_needed_n": self.preload_needed,
            "rate_needed_n_mm": self.rate_needed,
            "rate_needed_at_deg": self.rate_needed_at_deg, "liftoff_rpm": self.liftoff_rpm}
        if self.load_table is not None:
            out["load_table_n"] = self.load_table.as_report()
        if self.segment_loads is not None:
            out["segment_loads_n"] = [{"segment": i, "load_n": v} for i, v in enumerate(self.segment_loads)]
        return out


#: the contact check of :func:`camgen.dynamics.speed_report` (None there without a mass)
ContactCheck = Unanalysed | GravityHold | HeldContact


@dataclass(frozen=True)
class Stress:
    """The largest Hertz contact pressure over the turn (:mod:`camgen.contact_stress`).

    Attributes
    ----------
    cam_material, follower_material : str
        The materials in contact (names of :data:`~camgen.contact_stress.MATERIALS`).
    length : float
        The contact's length (mm).
    e_star : float
        The effective modulus (MPa).
    pressure_max, pressure_max_at_deg : float
        The largest pressure (MPa) and where (degrees).
    half_width : float
        The contact strip's half-width there (mm).
    allowable : float
        The lower of the materials' allowable pressures (MPa).
    holds : bool
        Whether the largest pressure stays within the allowable.
    on : str or None
        Of a positive drive: the side (a flank, a wall, a cam of a pair) carrying it there.
    cams : tuple of Stress or None
        Of a conjugate pair: each cam's own (this record is the larger of them).
    """

    cam_material: str
    follower_material: str
    length: float
    e_star: float
    pressure_max: float
    pressure_max_at_deg: float
    half_width: float
    allowable: float
    holds: bool
    on: str | None = None
    cams: tuple[Stress, ...] | None = None

    def as_report(self) -> dict[str, Any]:
        """The report's ``speed.forces.stress``."""
        out: dict[str, Any] = {
            "cam_material": self.cam_material, "follower_material": self.follower_material,
            "length_mm": self.length, "e_star_MPa": self.e_star, "pressure_max_MPa": self.pressure_max,
            "pressure_max_at_deg": self.pressure_max_at_deg, "half_width_mm": self.half_width,
            "allowable_MPa": self.allowable, "holds": self.holds}
        if self.on is not None:
            out["on"] = self.on
        if self.cams is not None:
            out["cams"] = [cam.as_report() for cam in self.cams]
        return out


@dataclass(frozen=True)
class KnifeEdge:
    """The stress of a knife edge with materials given: none (it touches on a line of no width)."""

    note: ClassVar[str] = KNIFE_NOTE

    def as_report(self) -> dict[str, Any]:
        """The report's ``speed.forces.stress``."""
        return {"note": self.note}


@dataclass(frozen=True)
class SideChange:
    """Where (``at_deg``, degrees of cam angle) the force of a positive drive moves to the side ``to``."""

    at_deg: float
    to: str

    def as_report(self) -> dict[str, Any]:
        """One of the report's ``speed.forces.side_changes``."""
        return {"at_deg": self.at_deg, "to": self.to}


@dataclass(frozen=True)
class Drive:
    """Which side of a positive drive (a groove, a rib, a conjugate pair) carries the force: ``force_positive``
    where it presses the follower against its rise, ``force_negative`` where it pulls, and where it changes side
    (``changes``)."""

    force_positive: str
    force_negative: str
    changes: tuple[SideChange, ...]


@dataclass(frozen=True)
class Extreme:
    """A largest value over the turn (in the unit its name gives) and where (``at_deg``, degrees)."""

    value: float
    at_deg: float


@dataclass(frozen=True)
class Forces:
    """What the cam and its shaft carry at the design's speed (:mod:`camgen.forces`).

    Attributes
    ----------
    torque_max, torque_max_at_deg, torque_min, torque_min_at_deg : float
        The shaft torque's extremes (N*m) and where (degrees).
    torque_rms : float
        Its RMS over the turn (N*m).
    power_max : float
        The largest power (W) in either direction.
    contact_force_max, contact_force_max_at_deg : float
        The largest normal contact force (N) and where (degrees).
    drive : Drive or None
        Of a positive drive: the sides carrying the force.
    pair : tuple of two Extreme or None
        Of a conjugate pair: each cam's largest normal contact force (N) and where.
    stress : Stress, KnifeEdge or None
        With materials: the largest Hertz pressure (a knife edge has none).
    """

    torque_max: float
    torque_max_at_deg: float
    torque_min: float
    torque_min_at_deg: float
    torque_rms: float
    power_max: float
    contact_force_max: float
    contact_force_max_at_deg: float
    drive: Drive | None = None
    pair: tuple[Extreme, Extreme] | None = None
    stress: Stress | KnifeEdge | None = None

    @property
    def hertz(self) -> Stress | None:
        """The Hertz pressure's figures, where there are some (materials given and no knife edge)."""
        return self.stress if isinstance(self.stress, Stress) else None

    def as_report(self) -> dict[str, Any]:
        """The report's ``speed.forces``."""
        out: dict[str, Any] = {
            "torque_max_N_m": self.torque_max, "torque_max_at_deg": self.torque_max_at_deg,
            "torque_min_N_m": self.torque_min, "torque_min_at_deg": self.torque_min_at_deg,
            "torque_rms_N_m": self.torque_rms, "power_max_W": self.power_max,
            "contact_force_max_N": self.contact_force_max, "contact_force_max_at_deg": self.contact_force_max_at_deg}
        if self.drive is not None:
            out["carried_by"] = {"force_positive": self.drive.force_positive,
                                 "force_negative": self.drive.force_negative}
            out["side_changes"] = [change.as_report() for change in self.drive.changes]
        for which, most in enumerate(self.pair or ()):
            out[f"cam_{which + 1}_contact_force_max_N"] = most.value
            out[f"cam_{which + 1}_contact_force_max_at_deg"] = most.at_deg
        if self.stress is not None:
            out["stress"] = self.stress.as_report()
        return out


@dataclass(frozen=True)
class SpeedRow:
    """One speed of a :class:`SpeedTable`.

    Attributes
    ----------
    rpm : float
        The cam's speed (rpm).
    torque_max, torque_min, torque_rms : float
        The shaft torque's extremes and RMS (N*m).
    power_max : float
        The largest power (W).
    contact_force_max : float
        The largest normal contact force (N).
    contact_force_min, contact_force_min_at_deg : float or None
        Of a follower held on (not a positive drive): the least axial contact force (N) and where (degrees).
    holds : bool or None
        Of a follower held on: whether that least force stays above the margin.
    pressure_max : float or None
        With materials: the largest Hertz pressure (MPa).
    """

    rpm: float
    torque_max: float
    torque_min: float
    torque_rms: float
    power_max: float
    contact_force_max: float
    contact_force_min: float | None = None
    contact_force_min_at_deg: float | None = None
    holds: bool | None = None
    pressure_max: float | None = None

    def as_report(self) -> dict[str, Any]:
        """One of the report's ``speed.speeds.rows``."""
        out: dict[str, Any] = {"rpm": self.rpm, "torque_max_N_m": self.torque_max, "torque_min_N_m": self.torque_min,
                               "torque_rms_N_m": self.torque_rms, "power_max_W": self.power_max,
                               "contact_force_max_N": self.contact_force_max}
        if self.holds is not None:
            out.update(contact_force_min_N=self.contact_force_min,
                       contact_force_min_at_deg=self.contact_force_min_at_deg, holds=self.holds)
        if self.pressure_max is not None:
            out["pressure_max_MPa"] = self.pressure_max
        return out


@dataclass(frozen=True)
class SpeedTable:
    """The forces over a range of speeds (:func:`camgen.forces.speeds_report`).

    Attributes
    ----------
    rpm_range : tuple of two float
        The range asked for (rpm).
    liftoff_rpm : float or None
        The lift-off speed (rpm; None: held at any speed, or a positive drive).
    rows : tuple of SpeedRow
        The speeds, ascending.
    margin : float or None
        Of a follower held on: the contact margin the figure draws (N); None for a positive drive.
    allowable : float or None
        With materials: the allowable contact pressure (MPa).
    """

    rpm_range: tuple[float, float]
    liftoff_rpm: float | None
    rows: tuple[SpeedRow, ...]
    margin: float | None = None
    allowable: float | None = None

    def as_report(self) -> dict[str, Any]:
        """The report's ``speed.speeds``."""
        out: dict[str, Any] = {"rpm_range": list(self.rpm_range), "liftoff_rpm": self.liftoff_rpm,
                               "rows": [row.as_report() for row in self.rows]}
        if self.margin is not None:
            out["margin_N"] = self.margin
        if self.allowable is not None:
            out["allowable_MPa"] = self.allowable
        return out


@dataclass(frozen=True)
class Speed:
    """A cam at a speed: the follower's peak rates in time, and with a mass its contact check, forces and speeds
    table.

    Attributes
    ----------
    rpm, omega : float
        The cam's speed (rpm) and in rad/s.
    unit : str
        The follower's lift unit, ``"mm"`` (translating) or ``"deg"`` (oscillating): the rates are in it per s,
        s^2 and s^3.
    velocity_max, acceleration_max, jerk_max : float
        The largest |velocity|, |acceleration| and |jerk| over the turn (unit/s, unit/s^2, unit/s^3).
    velocity_max_at_deg, acceleration_max_at_deg, jerk_max_at_deg : float
        Where they are (degrees of cam angle).
    parabolic : tuple of (int, float)
        Each parabolic segment's index and acceleration ratio.
    contact : ContactCheck or None
        The contact check (None without a mass, or for a positive drive: it cannot lose contact).
    forces : Forces or None
        With a mass whose contact is analysed, or of a positive drive: the forces at ``rpm``.
    speeds : SpeedTable or None
        With ``cam.rpm_range``: the forces over it.
    """

    rpm: float
    omega: float
    unit: str
    velocity_max: float
    velocity_max_at_deg: float
    acceleration_max: float
    acceleration_max_at_deg: float
    jerk_max: float
    jerk_max_at_deg: float
    parabolic: tuple[tuple[int, float], ...]
    contact: ContactCheck | None = None
    forces: Forces | None = None
    speeds: SpeedTable | None = None

    def as_report(self) -> dict[str, Any]:
        """The report's ``speed``."""
        unit = self.unit
        out: dict[str, Any] = {
            "rpm": self.rpm, "omega_rad_s": self.omega,
            f"velocity_max_{unit}_s": self.velocity_max, "velocity_max_at_deg": self.velocity_max_at_deg,
            f"acceleration_max_{unit}_s2": self.acceleration_max,
            "acceleration_max_at_deg": self.acceleration_max_at_deg,
            f"jerk_max_{unit}_s3": self.jerk_max, "jerk_max_at_deg": self.jerk_max_at_deg,
            "parabolic_acceleration_ratios": [{"segment": i, "ratio": r} for i, r in self.parabolic],
            "contact": None if self.contact is None else self.contact.as_report(),
        }
        if self.forces is not None:
            out["forces"] = self.forces.as_report()
        if self.speeds is not None:
            out["speeds"] = self.speeds.as_report()
        return out
