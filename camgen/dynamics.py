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


def _peak(cam: Cam, func: Callable[[np.ndarray], np.ndarray]) -> Peak:
    """Largest value over the cycle of ``func`` of the motion (its four rows: s and three derivatives)."""
    segments = cam.program.segments
    return Peak(*cam.program.peak(lambda i, t: func(segments[i].evaluate(t))))


def speed_report(cam: Cam, rpm: float, mass: float | None, spring_rate: float | None,
                 preload: float | None, parabolic: list[tuple[int, float]]) -> dict[str, Any]:
    """Peak velocity, acceleration and jerk at ``rpm``; contact with ``mass`` kg and an optional spring."""
    omega = rpm * 2 * math.pi / 60
    unit = cam.follower.lift_unit
    v, a, j = (_peak(cam, lambda m, k=k: np.abs(m[k])) for k in (1, 2, 3))
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
    if unit != "mm":
        out["contact"] = {"mode": None, "note": "contact is analysed for translating followers; an oscillating "
                                                 "arm needs its moment of inertia"}
        return out
    decel = _peak(cam, lambda m: -m[2])                      # largest -s'' (mm/rad^2)
    if spring_rate is None and preload is None:
        limit = math.inf if decel.value <= 0 else math.sqrt(G_MM / decel.value) * 60 / (2 * math.pi)
        out["contact"] = {"mode": "gravity", "liftoff_rpm": None if math.isinf(limit) else limit,
                          "liftoff_at_deg": decel.at_deg if decel.value > 0 else None, "holds": rpm < limit}
        return out
    rate, load = spring_rate or 0.0, preload or 0.0
    # N(theta) = load + rate s + mass omega^2 s'' / 1000: its minimum and where
    low = _peak(cam, lambda m: -(load + rate * m[0] + mass * omega**2 * m[2] / 1000))
    need_preload = _peak(cam, lambda m: -(rate * m[0] + mass * omega**2 * m[2] / 1000)).value
    # the rate that would do with this preload: max of -(preload + m a) / s where s > 0; where s = 0 only the
    # preload can help (sentinel +BIG), and where the force is positive there is no demand (sentinel -BIG)
    big = 1e30

    def demand(m: np.ndarray) -> np.ndarray:
        short = -(load + mass * omega**2 * m[2] / 1000)
        lifted = m[0] > 1e-9 * max(cam.program.max_lift, 1e-300)
        return np.where(lifted, short / np.where(lifted, m[0], 1.0), np.where(short > 0, big, -big))

    worst = _peak(cam, demand).value
    need_rate = None if worst >= big else max(0.0, worst)
    out["contact"] = {"mode": "spring", "spring_rate_n_mm": rate, "preload_n": load,
                      "force_min_n": -low.value, "force_min_at_deg": low.at_deg, "holds": -low.value > 0,
                      "preload_needed_n": max(0.0, need_preload), "rate_needed_n_mm": need_rate}
    return out
