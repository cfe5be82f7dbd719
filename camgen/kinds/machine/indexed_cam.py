"""A cam on an indexing shaft (a Geneva drive's wheel's, or one geared to it) at its real rates.

A cam's own design (its speed report, its contact check) runs at its shaft's mean speed, ``machine.rpm`` times its
mean turns. On an indexing shaft the cam stands still while the wheel is locked and turns far faster than that mean
while it indexes: its follower's rates per radian of the main shaft are, by the chain rule through its shaft's
angle Q (its own sense, :mod:`camgen.kinds.machine.shaft_motion`),

    ds/dphi = s'(theta) Q',        d^2s/dphi^2 = s''(theta) Q'^2 + s'(theta) Q''

(theta = Q - phase its program angle; s', s'' per radian of the program), and in time, the main shaft turning
steadily at omega rad/s, v = omega ds/dphi and a = omega^2 d^2s/dphi^2 (mm or degrees of swing per s, per s^2).
The contact force at the real rates is the cam's own :class:`~camgen.dynamics.Loading` (spring, preload, loads,
weight) with that acceleration in place of the mean speed's: ``Loading.force`` of (s, s' Q', s'' Q'^2 + s' Q'') at
omega. It can be lost where the mean-speed check holds. Main shaft angles in degrees from the machine's start.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.dynamics import spec_loading
from camgen.speed import HeldContact


@dataclass(frozen=True)
class IndexedCam:
    """A cam on an indexing shaft at its real rates.

    Attributes
    ----------
    name, unit : str
        Its mount's name and its follower's unit (``"mm"`` or ``"deg"``).
    acceleration_max, acceleration_max_at_deg : float
        The follower's peak |acceleration| at the real rates (unit/s^2) and where (main shaft degrees).
    mean_acceleration_max : float or None
        The same at its shaft's mean speed (the cam's own speed report), None without one.
    force_min, force_min_at_deg : float or None
        The least contact force at the real rates (N) and where (main shaft degrees); None where its contact is not
        analysed (no mass, a positive drive).
    mean_force_min, margin : float or None
        The cam's own check's least contact force at the mean speed (N), and the least force wanted (N).
    """

    name: str
    unit: str
    acceleration_max: float
    acceleration_max_at_deg: float
    mean_acceleration_max: float | None = None
    force_min: float | None = None
    force_min_at_deg: float | None = None
    mean_force_min: float | None = None
    margin: float | None = None

    @property
    def holds(self) -> bool | None:
        """Whether the least contact force at the real rates stays above the margin (None: not analysed)."""
        return None if self.force_min is None or self.margin is None else self.force_min > self.margin

    @property
    def mean_holds(self) -> bool | None:
        """Whether the mean-speed check holds (None: not analysed)."""
        return None if self.mean_force_min is None or self.margin is None else self.mean_force_min > self.margin

    def as_report(self) -> dict[str, Any]:
        """The report's ``cams.<name>.indexed``."""
        out: dict[str, Any] = {
            "acceleration_max": _num(self.acceleration_max),
            "acceleration_max_at_deg": _num(self.acceleration_max_at_deg),
            "mean_speed_acceleration_max": None if self.mean_acceleration_max is None
            else _num(self.mean_acceleration_max),
            "unit": f"{self.unit}/s^2"}
        if self.force_min is not None:
            out["contact"] = {"least_contact_force_n": _num(self.force_min), "at_deg": _num(self.force_min_at_deg),
                              "holds": self.holds, "mean_speed_least_contact_force_n": _num(self.mean_force_min),
                              "mean_speed_holds": self.mean_holds, "margin_n": self.margin}
        return out

    def warning(self) -> str | None:
        """A warning where the real rates lose the contact the mean-speed check keeps (else None)."""
        if self.holds is not False:
            return None
        mean = "holds" if self.mean_holds else "is lost too"
        return (f"cams.{self.name}: at its indexing shaft's real rates the follower leaves its cam (least contact "
                f"force {self.force_min:.4g} N at {self.force_min_at_deg:.4g} degrees of the main shaft, margin "
                f"{self.margin:g} N); the cam's own check at the shaft's mean speed {mean}: give it more preload or "
                "a stiffer spring")


def speed_of(design: Any) -> Any:
    """A cam kind's design's speed report (:class:`~camgen.speed.Speed`): its own, or its profile's; None without."""
    speed = getattr(design, "speed", None)
    return speed if speed is not None else getattr(getattr(design, "profile", None), "speed", None)


def indexed_cam(cam: Any, kin: Any, omega: float, phi: np.ndarray) -> IndexedCam | None:
    """``cam`` (a :class:`~camgen.kinds.machine.design.CamMotion`, its kinematic cam ``kin``) at the real rates of
    its indexing shaft, the main shaft at ``omega`` rad/s and angles ``phi`` (rad, the machine's samples), against
    its design's own speed report at the shaft's mean speed; None on a shaft that turns steadily."""
    if cam.indexer is None:
        return None
    speed = speed_of(cam.design)
    rows = cam.rates
    acc = np.abs(rows[2]) * omega ** 2
    k = int(np.argmax(acc))
    out = IndexedCam(cam.name, cam.unit, float(acc[k]), math.degrees(float(phi[k])),
                     None if speed is None else float(speed.acceleration_max))
    contact = None if speed is None else speed.contact
    if not isinstance(contact, HeldContact):
        return out
    table = cam.design.spec.follower
    ld = spec_loading(table, kin.follower, motion=cam.design.spec.motion, program=kin.program)
    force = np.asarray(ld.force(rows, omega, cam.theta), dtype=float)
    low = int(np.argmin(force))
    return IndexedCam(out.name, out.unit, out.acceleration_max, out.acceleration_max_at_deg, out.mean_acceleration_max,
                      float(force[low]), math.degrees(float(phi[low])), float(contact.force_min), float(ld.margin))


def _num(value: float | None) -> float | None:
    """``value`` to 1e-9 for the report (-0 written as 0)."""
    return None if value is None else round(float(value), 9) + 0.0
