"""The motor that drives a crank (``[dynamics.motor]``): its torque against its speed, the gearing to the crank and the
friction the crank turns against, as the forward dynamics (:mod:`linkgen.dynamics.forward`) integrates them.

A motor is a torque-speed line, T(n) = stall_torque (1 - n / no_load_speed) at motor speed n (the line a DC motor
with a fixed supply voltage follows; it goes on, negative, past the no-load speed, where the crank drives the
motor), or a constant ``torque``. Through a gear of ratio i (motor turns per crank turn; 1 without) the crank feels
i T(i w) at crank speed w, and the rotor's inertia i^2 I_rotor. The friction opposes the crank's turning:
``friction`` (constant, Coulomb) plus ``viscous`` times its speed. Signs: the motor drives the crank
counter-clockwise, the way its input angle grows; a crank that turns the other way has stalled (the integration ends
there).

Units here: the table's (N*m, rpm, N*m per 1000 rpm, kg*mm^2, s); :class:`Motor` holds the same in SI (N*m, rad/s,
N*m*s/rad, kg*m^2) at the crank.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from pydantic import Field, model_validator

from camgen.core.spec import Model, unit

#: the strongest motor torque (N*m) and friction (N*m), the fastest no-load speed (rpm), the largest gear ratio, the
#: largest rotor inertia (kg*mm^2), the longest simulated time (s)
MAX_TORQUE, MAX_NO_LOAD_RPM, MAX_GEAR, MAX_ROTOR, MAX_TIME = 1e5, 100_000.0, 10_000.0, 1e9, 600.0
#: viscous friction: N*m at 1000 rpm at most
MAX_VISCOUS = 1e5
RPM = 2.0 * math.pi / 60.0


class MotorTable(Model):
    """A motor on the crank (``[dynamics.motor]``): a torque-speed line (``stall_torque`` and ``no_load_speed``) or a
    constant ``torque``, geared to the crank, against friction; the motion from rest is integrated for at most
    ``time`` s (see docs/guides/dynamics.md, "A motor and the motion from rest"). A crank that turns fully only."""

    stall_torque: float | None = Field(None, gt=0, le=MAX_TORQUE, description="the motor's torque at rest, on its "
                                       "own shaft (with no_load_speed: a torque-speed line)",
                                       json_schema_extra=unit("N*m", absent="a constant torque instead"))
    no_load_speed: float | None = Field(None, gt=0, le=MAX_NO_LOAD_RPM, description="the motor's speed where its "
                                        "torque falls to 0, on its own shaft", json_schema_extra=unit(
                                            "rpm", absent="required with stall_torque"))
    torque: float | None = Field(None, gt=0, le=MAX_TORQUE, description="a constant torque on the motor's shaft "
                                 "at any speed, instead of a torque-speed line",
                                 json_schema_extra=unit("N*m", absent="the torque-speed line"))
    gear_ratio: float = Field(1.0, ge=1e-3, le=MAX_GEAR, description="motor turns per crank turn (a gearbox of "
                              "60:1 is 60): the crank gets ratio x the motor's torque at 1 / ratio its speed")
    rotor_inertia: float = Field(0.0, ge=0, le=MAX_ROTOR, description="the motor's rotor (and gears') inertia on "
                                 "its own shaft; the crank feels gear_ratio^2 times it",
                                 json_schema_extra=unit("kg*mm^2"))
    friction: float = Field(0.0, ge=0, le=MAX_TORQUE, description="a constant friction torque on the crank, "
                            "against its turning (bearings, a belt)", json_schema_extra=unit("N*m"))
    viscous: float = Field(0.0, ge=0, le=MAX_VISCOUS, description="a friction torque on the crank in proportion to "
                           "its speed, given at 1000 rpm of the crank", json_schema_extra=unit("N*m at 1000 rpm"))
    flywheel: bool = Field(True, description="turn the flywheel of [dynamics.flywheel] with the crank (when the "
                           "table has one)")
    time: float = Field(60.0, gt=0, le=MAX_TIME, description="the longest simulated time from rest: the run ends "
                        "there, at a stall, or once the speed is steady", json_schema_extra=unit("s"))

    @model_validator(mode="after")
    def _one_motor(self) -> MotorTable:
        line = self.stall_torque is not None
        if self.torque is None and not line:
            raise ValueError("stall_torque: give the motor's stall torque and no-load speed (a torque-speed line), "
                             "or a constant torque: > 0 and <= 1e+05 N*m")
        if self.torque is not None and (line or self.no_load_speed is not None):
            raise ValueError("torque: a constant torque is instead of a torque-speed line (stall_torque, "
                             "no_load_speed): give one of them")
        if line and self.no_load_speed is None:
            raise ValueError(f"no_load_speed: a torque-speed line needs the motor's no-load speed: > 0 and <= "
                             f"{MAX_NO_LOAD_RPM:g} rpm")
        return self


@dataclass(frozen=True)
class Motor:
    """A motor and friction as the crank feels them (SI): torque ``stall`` (N*m) at rest falling by ``slope``
    (N*m*s/rad) per rad/s of crank speed (0: a constant torque), the rotor's inertia at the crank (kg*m^2), the
    constant and viscous friction (N*m, N*m*s/rad)."""

    stall: float
    slope: float
    rotor: float
    friction: float
    viscous: float

    @classmethod
    def of(cls, table: MotorTable) -> Motor:
        """The motor of ``table`` at the crank."""
        i = table.gear_ratio
        viscous = table.viscous / (1000.0 * RPM)
        rotor = i * i * table.rotor_inertia * 1e-6
        if table.torque is not None:
            return cls(i * table.torque, 0.0, rotor, table.friction, viscous)
        assert table.stall_torque is not None and table.no_load_speed is not None
        return cls(i * table.stall_torque, i * i * table.stall_torque / (table.no_load_speed * RPM), rotor,
                   table.friction, viscous)

    def torque(self, speed: float) -> float:
        """The motor's torque on the crank (N*m) at crank speed ``speed`` (rad/s)."""
        return self.stall - self.slope * speed

    def resistance(self, speed: float) -> float:
        """The friction torque against a crank turning forward at ``speed`` >= 0 (rad/s), N*m."""
        return self.friction + self.viscous * speed

    @property
    def constant(self) -> bool:
        """Whether the torque is the same at every speed."""
        return self.slope == 0.0
