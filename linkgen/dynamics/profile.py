"""The input's speed over the motion the dynamics runs at (``dynamics.speed_profile``): constant, a profile through
rows, or the steady turn a motor reaches. No I/O.

* **constant**: ``linkage.rpm`` (a crank) or ``dynamics.speed`` (a slide) at every pose, with the constant
  ``dynamics.input_acceleration``;
* **profile**: rows ``[[crank_deg, rpm], ...]`` over one turn, interpolated by a periodic cubic spline
  (``scipy.interpolate.CubicSpline``, ``bc_type="periodic"``) of the speed w (rad/s) against the crank angle theta
  (rad); the acceleration is alpha = w dw/dtheta with dw/dtheta the spline's exact derivative. A slide: rows
  ``[[position_mm, speed_mm_s], ...]`` over its travel, a natural cubic spline of v against x (not periodic), the
  acceleration a = v dv/dx; the rows must cover the travel analysed;
* **motor**: the last, steady turn of the ``[dynamics.motor]`` run (:mod:`linkgen.dynamics.forward`): at each crank
  angle the speed the run has there (its dense output inverted for the time, by Newton's method on theta(t)) and the
  acceleration its equation of motion gives at that angle and speed.

The crank angle is the input's value as the report gives it (the crank's direction, degrees counter-clockwise from
+X); a slide's position its travel (mm) from the drawing. A speed's **mean** is over time: a turn (or the travel
analysed) over the time it takes, 2 pi / integral(dtheta / w), as the motor's steady mean is; its least and largest
are the spline's own extremes (its derivative's roots), or the run's over the turn.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

from camgen.core.errors import SpecError
from linkgen.dynamics.table import MAX_PROFILE_RPM, MAX_SPEED_MM_S
from linkgen.kinematics.inertia import MM

if TYPE_CHECKING:
    from scipy.interpolate import CubicSpline

    from linkgen.dynamics.forward import Motion
    from linkgen.dynamics.table import DynamicsTable

TWO_PI = 2.0 * math.pi
RPM = TWO_PI / 60.0
FIELD = "dynamics.speed_profile"
#: Gauss-Legendre points a spline's piece is integrated on for the time it takes (exact to the spline's own error)
GAUSS = 8
#: Newton steps that find the time of a crank angle in the motor's last turn, and the angle's tolerance (rad)
NEWTON, ANGLE_TOL = 8, 1e-12

Kind = Literal["constant", "profile", "motor"]


@dataclass(frozen=True)
class SpeedProfile:
    """The input's speed and acceleration as functions of its value (see the module's note).

    Attributes
    ----------
    kind : {"constant", "profile", "motor"}
        Where the speed comes from.
    crank : bool
        A crank (speeds rad/s, values rad) or a slide (m/s, values mm).
    mean, slowest, fastest : float
        The speed's mean over time, least and largest (rad/s or m/s).
    speed, acceleration : float
        The constant speed and acceleration (SI; ``kind == "constant"`` only).
    spline : CubicSpline or None
        The profile's spline of speed (rad/s or m/s) against the input (rad or mm).
    motion : Motion or None
        The motor's run (``kind == "motor"``).
    """

    kind: Kind
    crank: bool
    mean: float
    slowest: float
    fastest: float
    speed: float = 0.0
    acceleration: float = 0.0
    spline: CubicSpline | None = None
    motion: Motion | None = None

    def at(self, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The speed and acceleration (rad/s and rad/s^2, or m/s and m/s^2) at input values ``values`` (rad or
        mm)."""
        x = np.asarray(values, dtype=float)
        if self.spline is not None:
            w = self.spline(x)
            slope = self.spline(x, 1)                   # d(speed)/d(input) per rad, or per mm
            return w, w * slope * (1.0 if self.crank else 1.0 / MM)
        if self.motion is not None:
            return _motor_at(self.motion, x)
        return np.full(x.shape, self.speed), np.full(x.shape, self.acceleration)

    @property
    def varies(self) -> bool:
        """Whether the speed changes over the motion."""
        return self.kind != "constant"


def constant(speed: float, acceleration: float, crank: bool) -> SpeedProfile:
    """A constant ``speed`` and ``acceleration`` (SI) at every pose."""
    return SpeedProfile("constant", crank, speed, speed, speed, speed, acceleration)


def _time_over(spline: CubicSpline, lo: float, hi: float) -> float:
    """integral(dx / v) over [lo, hi] on the spline's pieces there, by Gauss-Legendre (the spline's unit of x over
    its unit of speed)."""
    knots = spline.x
    edges = np.unique(np.concatenate([[lo, hi], knots[(knots > lo) & (knots < hi)]]))
    u, wts = np.polynomial.legendre.leggauss(GAUSS)
    a, b = edges[:-1, None], edges[1:, None]
    x = 0.5 * (b - a) * u + 0.5 * (a + b)
    return float(np.sum(0.5 * (b - a) * wts / spline(x)))


def _extremes(spline: CubicSpline, lo: float, hi: float) -> tuple[float, float, float, float]:
    """The spline's least and largest values over [lo, hi] and where (its derivative's roots, its knots and the
    ends)."""
    roots = spline.derivative().roots(extrapolate=False)
    where = np.concatenate([[lo, hi], spline.x, np.real(roots)])
    where = where[(where >= lo) & (where <= hi)]
    v = spline(where)
    i, k = int(np.argmin(v)), int(np.argmax(v))
    return float(v[i]), float(where[i]), float(v[k]), float(where[k])


def rows_profile(rows: tuple[tuple[float, float], ...], crank: bool, lo: float, hi: float) -> SpeedProfile:
    """The profile through ``rows`` (``dynamics.speed_profile``: degrees and rpm, or mm and mm/s) for the input
    values analysed, ``lo`` to ``hi`` (rad or mm).

    Raises
    ------
    SpecError
        On ``dynamics.speed_profile``: a crank's rows spanning a turn or more, faster than the bound, a slide's
        rows faster than theirs or not covering the travel analysed, or a spline that leaves the bounds between the
        rows.
    """
    from scipy.interpolate import CubicSpline        # here: scipy's interpolation is 0.3 s of a command's start

    a = np.array([r[0] for r in rows], dtype=float)
    v = np.array([r[1] for r in rows], dtype=float)
    if crank:
        if a[-1] - a[0] >= 360.0:
            raise SpecError(f"the rows' crank angles must lie within one turn: the last less than 360 degrees past "
                            f"the first (got {a[0]:g} to {a[-1]:g})", FIELD)
        _bounded(v, MAX_PROFILE_RPM, "rpm")
        theta = np.radians(np.append(a, a[0] + 360.0))
        spline = CubicSpline(theta, np.append(v, v[0]) * RPM, bc_type="periodic")
        lo_s, hi_s = float(theta[0]), float(theta[0]) + TWO_PI
        slowest, at_slow, fastest, at_fast = _extremes(spline, lo_s, hi_s)
        unit, scale = "rpm", 1.0 / RPM
        mean = TWO_PI / _time_over(spline, lo_s, hi_s)
    else:
        _bounded(v, MAX_SPEED_MM_S, "mm/s")
        tiny = 1e-9 * max(1.0, abs(lo), abs(hi))
        if a[0] > lo + tiny or a[-1] < hi - tiny:
            raise SpecError(f"the rows' positions must cover the travel analysed, {lo:.6g} to {hi:.6g} mm (they "
                            f"cover {a[0]:g} to {a[-1]:g} mm)", FIELD)
        spline = CubicSpline(a, v * MM, bc_type="natural", extrapolate=False)
        slowest, at_slow, fastest, at_fast = _extremes(spline, lo, hi)
        unit, scale = "mm/s", 1.0 / MM
        mean = (hi - lo) / _time_over(spline, lo, hi) if hi > lo else slowest      # mm over mm*s/m: m/s
    bound = MAX_PROFILE_RPM if crank else MAX_SPEED_MM_S
    for value, where in ((slowest, at_slow), (fastest, at_fast)):
        if not 0.0 < value * scale <= bound:
            shown = f"{math.degrees(where) % 360.0:.6g} degrees" if crank else f"{where:.6g} mm"
            raise SpecError(f"the spline through the rows reaches {value * scale:.6g} {unit} at {shown}: it must stay "
                            f"> 0 and <= {bound:g} {unit}; give rows closer together where the speed changes fast",
                            FIELD)
    return SpeedProfile("profile", crank, mean, slowest, fastest, spline=spline)


def _bounded(v: np.ndarray, bound: float, unit: str) -> None:
    bad = np.flatnonzero(v > bound)
    if bad.size:
        k = int(bad[0])
        raise SpecError(f"a speed must be > 0 and <= {bound:g} {unit} (got {v[k]:g})", f"{FIELD}[{k}]")


def motor_profile(table: DynamicsTable, motion: Motion | None) -> SpeedProfile:
    """The steady turn of the motor's run ``motion`` (``speed_profile = "motor"``).

    Raises
    ------
    SpecError
        On ``dynamics.speed_profile``: no motor, or a run that stalls or does not reach a steady speed.
    """
    if motion is None or table.motor is None:
        raise SpecError('"motor" is the steady turn the [dynamics.motor] run reaches: give a [dynamics.motor], or '
                        "rows [[crank_deg, rpm], ...]", FIELD)
    if motion.outcome != "steady" or motion.last is None or motion.last_turn is None:
        if motion.stall is not None:
            why = f"stalls at {math.degrees(motion.stall.angle) % 360.0:.6g} degrees after {motion.stall.time:.6g} s"
        else:
            why = {"runaway": "runs away (its speed grows without bound)",
                   "time": f"is not steady within dynamics.motor.time = {table.motor.time:g} s",
                   "turns": "is not steady within the turns the run is kept to"}.get(motion.outcome, motion.outcome)
        raise SpecError(f'"motor" needs the steady speed of the [dynamics.motor] run, which {why}: give rows '
                        "[[crank_deg, rpm], ...] or a stronger motor (or a longer dynamics.motor.time)", FIELD)
    last = motion.last
    return SpeedProfile("motor", True, last.mean, last.slowest, last.fastest, motion=motion)


def _motor_at(motion: Motion, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The speed (rad/s) and acceleration (rad/s^2) the motor's last turn has at crank angles ``x`` (rad)."""
    eq, sol = motion.equation, motion.last_turn
    t0, t1 = float(motion.turn_ends[-2]) if len(motion.turn_ends) > 1 else 0.0, float(motion.turn_ends[-1])
    first = float(sol(t0)[0])
    target = first + np.mod(x - first, TWO_PI)
    samples = np.linspace(t0, t1, 4097)
    theta = sol(samples)[0]
    t = np.interp(target, theta, samples)
    for _ in range(NEWTON):
        y = sol(t.ravel())
        miss = y[0].reshape(t.shape) - target
        if np.all(np.abs(miss) <= ANGLE_TOL):
            break
        t = np.clip(t - miss / y[1].reshape(t.shape), t0, t1)
    w = sol(t.ravel())[1].reshape(t.shape)
    return w, eq.acceleration(target, w)
