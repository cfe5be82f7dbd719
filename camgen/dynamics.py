"""Speed and contact of a translating follower at a given cam speed (constant).

Time derivatives: v = omega s', a = omega^2 s'', j = omega^3 s''' (omega in rad/s).
The follower's axis is +Y (its rise is upward).

* Gravity return: the weight alone holds the follower down; contact is lost where
  the follower must decelerate faster than g, a < -g, so the largest speed is
  omega_max = sqrt(g / -min s'').
* Spring return (spring weight and the follower's own weight neglected): contact
  force N = preload + rate s + m a (newtons, s in mm, a in m/s^2); contact holds
  while N > 0. Reported: its smallest value and where, the preload that would hold
  contact with this rate, and the rate that would with this preload.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.cam import Cam

#: standard gravity, mm/s^2
G_MM = 9806.65


@dataclass(frozen=True)
class Peak:
    value: float     # largest value
    at_deg: float


def peak_of(cam: Cam, func: Callable[[np.ndarray], np.ndarray]) -> Peak:
    """Largest value over the cycle of ``func`` of the motion (its four rows: s and three derivatives)."""
    segments = cam.program.segments
    return Peak(*cam.program.peak(lambda i, t: func(segments[i].evaluate(t))))


@dataclass(frozen=True)
class Loading:
    """What presses a translating follower onto its cam along its axis, in N: ``preload + rate s + load + weight +
    mass a`` (s in mm, a = omega^2 s'' in m/s^2). ``mass`` kg, ``rate`` N/mm; ``load`` an external force pressing
    the follower onto the cam (negative pulls it off); ``weight`` the part of its weight that does; ``margin`` the
    least contact force wanted (N)."""

    mass: float
    rate: float = 0.0
    preload: float = 0.0
    load: float = 0.0
    weight: float = 0.0
    margin: float = 0.0
    #: mm of the contact's path per unit of s: 1 for a translating follower, L pi / 180 for an arm of length L
    #: (whose s is its swing in degrees: the forces then act at the roller's centre along its path)
    scale: float = 1.0

    def still(self, m: np.ndarray) -> np.ndarray:
        """The force (N) at rest: everything but the inertia."""
        return self.preload + self.rate * self.scale * m[0] + self.load + self.weight

    def force(self, m: np.ndarray, omega: float) -> np.ndarray:
        """The force (N) pressing the follower onto the cam at ``omega`` rad/s."""
        return self.still(m) + self.mass * omega ** 2 * self.scale * m[2] / 1000.0


def loading(mass: float, spring_rate: float | None, preload: float | None, load: float | None = None,
            orientation: float | None = None, margin: float | None = None, arm: float | None = None) -> Loading:
    """The loading of a follower table's keys: with no spring (no rate, no preload) gravity holds the follower, its
    rise pointing straight up unless ``orientation`` (degrees from straight up) says otherwise; with a spring its
    weight counts only when ``orientation`` is given. For an ``arm`` (its length, mm) the mass sits at the roller's
    centre and the spring and load act there along its path; no weight."""
    gravity = spring_rate is None and preload is None and arm is None
    tilt = 0.0 if orientation is None and gravity else orientation
    weight = 0.0 if tilt is None else mass * G_MM / 1000.0 * math.cos(math.radians(tilt))
    scale = 1.0 if arm is None else arm * math.pi / 180.0
    return Loading(mass, spring_rate or 0.0, preload or 0.0, load or 0.0, weight, margin or 0.0, scale)


def speed_report(cam: Cam, rpm: float, mass: float | None, spring_rate: float | None,
                 preload: float | None, parabolic: list[tuple[int, float]], load: float | None = None,
                 orientation: float | None = None, margin: float | None = None) -> dict[str, Any]:
    """Peak velocity, acceleration and jerk at ``rpm``; contact with ``mass`` kg, an optional spring (N/mm, N), an
    external ``load`` (N), the follower's ``orientation`` (degrees from straight up) and a contact ``margin`` (N).
    An oscillating roller's arm carries its mass, spring and load at the roller's centre, along its path."""
    omega = rpm * 2 * math.pi / 60
    unit = cam.follower.lift_unit
    v, a, j = (peak_of(cam, lambda m, k=k: np.abs(m[k])) for k in (1, 2, 3))
    out: dict[str, Any] = {
        "rpm": rpm, "omega_rad_s": omega,
        f"velocity_max_{unit}_s": v.value * omega, "velocity_max_at_deg": v.at_deg,
        f"acceleration_max_{unit}_s2": a.value * omega**2, "acceleration_max_at_deg": a.at_deg,
        f"jerk_max_{unit}_s3": j.value * omega**3, "jerk_max_at_deg": j.at_deg,
        "parabolic_acceleration_ratios": [{"segment": i, "ratio": r} for i, r in parabolic],
    }
    if mass is None:
        out["contact"] = None
        return out
    arm = getattr(cam.follower, "arm_length", None) if unit != "mm" else None
    if unit != "mm" and (arm is None or (spring_rate is None and preload is None and not load)):
        out["contact"] = {"mode": None, "note": "contact is analysed for translating followers and for an "
                                                 "oscillating roller's arm held by a spring or a load"}
        return out
    ld = loading(mass, spring_rate, preload, load, orientation, margin, arm)
    if arm is None and spring_rate is None and preload is None and not load and orientation is None and not margin:
        decel = peak_of(cam, lambda m: -m[2])                      # largest -s'' (mm/rad^2)
        limit = math.inf if decel.value <= 0 else math.sqrt(G_MM / decel.value) * 60 / (2 * math.pi)
        out["contact"] = {"mode": "gravity", "liftoff_rpm": None if math.isinf(limit) else limit,
                          "liftoff_at_deg": decel.at_deg if decel.value > 0 else None, "holds": rpm < limit}
        return out
    out["contact"] = _contact(cam, ld, omega, "gravity" if spring_rate is None and preload is None else "spring")
    return out


def _contact(cam: Cam, ld: Loading, omega: float, mode: str) -> dict[str, Any]:
    """The contact force's least value and where, the preload and the rate that keep it at the margin at this
    speed, and the speed at which this loading lets the follower go."""
    low = peak_of(cam, lambda m: -ld.force(m, omega))
    need_preload = peak_of(cam, lambda m: ld.margin - (ld.force(m, omega) - ld.preload)).value
    # the rate that would do with this preload: max of (margin - rest) / s where s > 0; where s = 0 only the
    # preload can help (sentinel +BIG), and where the force is enough there is no demand (sentinel -BIG)
    big = 1e30

    def demand(m: np.ndarray) -> np.ndarray:
        short = ld.margin - (ld.force(m, omega) - ld.rate * ld.scale * m[0])
        lifted = m[0] > 1e-9 * max(cam.program.max_lift, 1e-300)
        return np.where(lifted, short / np.where(lifted, ld.scale * m[0], 1.0), np.where(short > 0, big, -big))

    worst = peak_of(cam, demand).value
    need_rate = None if worst >= big else max(0.0, worst)
    # lift-off: the force is still(s) + mass omega^2 s'' / 1000, so omega^2 <= 1000 still / (mass * -s'') wherever
    # s'' < 0; the least of that over the cycle (0 if the follower leaves at rest)
    rest = -peak_of(cam, lambda m: -ld.still(m)).value
    slowest = -peak_of(cam, lambda m: np.where(m[2] < 0, -1000.0 * ld.still(m) / (ld.mass * ld.scale * np.where(
        m[2] < 0, -m[2], 1.0)), -big)).value
    liftoff = 0.0 if rest <= 0 else (None if slowest >= big else math.sqrt(max(slowest, 0.0)) * 60 / (2 * math.pi))
    return {"mode": mode, "spring_rate_n_mm": ld.rate, "preload_n": ld.preload, "load_n": ld.load,
            "weight_n": ld.weight, "margin_n": ld.margin,
            "force_min_n": -low.value, "force_min_at_deg": low.at_deg, "holds": -low.value > ld.margin,
            "preload_needed_n": max(0.0, need_preload), "rate_needed_n_mm": need_rate, "liftoff_rpm": liftoff}
