"""Forward dynamics: a crank driven by a motor (:mod:`linkgen.dynamics.motor`), from rest, with the linkage's
configuration-dependent inertia. No I/O.

The equation of motion of a one-input linkage (crank angle theta, rad, counter-clockwise; speed w = theta', rad/s) is

    J(theta) w' + 1/2 J'(theta) w^2 = T_motor(w) - T_friction(w) - Q(theta)

with J the generalised inertia (:func:`linkgen.kinematics.inertia.generalised_inertia`: sum of m |v_G|^2 + I_G
omega^2 per unit crank speed, kg*m^2, and its exact derivative from the acceleration coefficients) plus the
flywheel's and the motor's rotor's (constant), and Q the torque that holds the linkage at rest against its weights,
loads and springs (the kinetostatics at zero speed and acceleration, i.e. the virtual-work statics). J, J' and Q
are tabulated once on :data:`POSES` crank angles over a turn and interpolated by one periodic cubic Hermite spline
(J with its exact J' as the slopes, so that the J' integrated is the derivative of the J whose kinetic energy
1/2 J w^2 is reported; Q with a periodic cubic spline's slopes). scipy's ``solve_ivp`` (:func:`method`: explicit
DOP853, or LSODA, stiff-safe, where a steep motor line on a light linkage makes the motion stiff; :data:`RTOL`)
integrates (theta, w) with the motor's, the friction's and the loads' work as three more states, one turn at a time,
from rest at the drawn crank angle, until:

* **stall**: the speed falls to 0 (the motor cannot pass a peak of the need); the crank then turns back (the need
  exceeds the motor's stall torque and the friction) or stays;
* **steady**: a turn's mean speed (2 pi over the turn's time) changed by less than :data:`STEADY_CHANGE` of itself
  over each of the last :data:`STEADY_TURNS` turns;
* **runaway**: a constant torque with no viscous friction has completed a turn (each turn then adds the same
  energy, 2 pi (T - friction - mean Q), so the crank speeds up without bound; the run is kept to
  :data:`RUNAWAY_TURNS` turns), or the speed passed :data:`RUNAWAY_RPM`;
* the simulated time ``dynamics.motor.time`` or :data:`MAX_TURNS` turns (not steady yet).

The time to steady speed is the end of the first turn from which every turn's mean speed stays within
:data:`SETTLED` (1 %) of the last turn's; the steady speed's fluctuation is (max - min) / mean over the last turn.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from camgen.core.errors import SolverError, SpecError
from linkgen.dynamics.motor import Motor
from linkgen.kinematics.inertia import LinkMass, generalised_inertia
from linkgen.kinematics.kinetostatics import Loads, kinetostatics
from linkgen.kinematics.linkage import Linkage

if TYPE_CHECKING:
    from scipy.interpolate import PPoly

    from linkgen.dynamics.flywheel import FlywheelSize
    from linkgen.dynamics.table import DynamicsTable

TWO_PI = 2.0 * math.pi
#: crank angles over a turn J, J' and Q are tabulated at
POSES = 4096
#: the integrator and its tolerances (relative; absolute on theta (rad), w (rad/s) and the works (J))
RTOL, ATOL = 1e-8, 1e-12
#: steps a turn an explicit method needs here: the motor's time constant J / (slope + viscous) shorter than this
#: fraction of a turn at the speed it heads for makes the motion stiff (see :func:`method`)
STEPS = 40
#: a speed is steady when a turn's mean changed by less than this fraction over each of this many turns
STEADY_CHANGE, STEADY_TURNS = 1e-5, 3
#: settled: a turn's mean speed within this fraction of the final one
SETTLED = 0.01
#: the most turns integrated, and the speed (rpm) past which the crank runs away
MAX_TURNS, RUNAWAY_RPM, RUNAWAY_TURNS = 500, 100_000.0, 4
#: samples of the last turn the fluctuation is measured on, and the most samples of the run kept for the figure
LAST_TURN, KEPT = 4097, 20_000

Outcome = Literal["steady", "stall", "time", "turns", "runaway"]


@dataclass(frozen=True)
class EquationOfMotion:
    """J, J' and Q of a crank over a turn from ``start`` (rad) as one periodic piecewise cubic ``table`` (see the
    module's note) whose columns are J, Q and their derivatives, the constant inertia ``added`` to J (kg*m^2: the
    flywheel and the rotor), and the motor."""

    start: float
    table: PPoly
    added: float
    motor: Motor

    def terms(self, theta: np.ndarray | float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """J (kg*m^2, the added inertia included), J' (kg*m^2/rad) and Q (N*m) at crank angles ``theta`` (rad)."""
        value = self.table(theta)
        return value[..., 0] + self.added, value[..., 2], value[..., 1]

    def acceleration(self, theta: np.ndarray | float, speed: np.ndarray | float) -> np.ndarray:
        """The crank's acceleration w' (rad/s^2) at angle ``theta`` (rad) and speed ``speed`` >= 0 (rad/s)."""
        j, dj, q = self.terms(theta)
        m = self.motor
        drive = m.stall - m.slope * speed - m.friction - m.viscous * speed
        return np.asarray((drive - q - 0.5 * dj * np.square(speed)) / j)

    def derivatives(self, _t: float, y: np.ndarray) -> np.ndarray:
        """d/dt of (theta, w, motor work, friction work, load work): the state solve_ivp integrates (SI)."""
        theta, w = y[0], y[1]
        j, dj, q = self.terms(theta)
        m = self.motor
        motor, friction = m.torque(w), m.resistance(w)
        return np.array([w, (motor - friction - q - 0.5 * dj * w * w) / j, motor * w, friction * w, q * w])

    def kinetic(self, theta: float, speed: float) -> float:
        """The kinetic energy 1/2 J w^2 (J) at ``theta`` (rad) and ``speed`` (rad/s)."""
        return 0.5 * float(self.terms(theta)[0]) * speed * speed


def equation_of(linkage: Linkage, masses: Mapping[str, LinkMass], loads: Loads, start: float, added: float,
                motor: Motor, poses: int = POSES) -> EquationOfMotion:
    """The equation of motion of the crank-driven ``linkage`` (turning fully) with ``masses`` and ``loads``, over a
    turn from ``start`` (rad), with ``added`` kg*m^2 on the crank and ``motor``; a :class:`SpecError` on
    ``dynamics.motor`` where the linkage locks (its inertia or its need not finite)."""
    theta = start + TWO_PI * np.arange(poses + 1) / poses
    sol = linkage.solve(theta[:-1])
    j, dj = generalised_inertia(linkage.structure, sol, masses)
    q = kinetostatics(linkage, sol, masses, 0.0, 0.0, loads).effort
    if not (np.isfinite(j).all() and np.isfinite(dj).all() and np.isfinite(q).all()):
        raise SpecError("the linkage locks somewhere over the turn (its inertia or the torque it needs is not "
                        "finite): it cannot be driven through it", "dynamics.motor")
    # scipy's splines and integrators are imported where a motion is worked out (they and what they import, scipy's
    # special functions and optimisers, are about 0.35 s of every linkage command's start that never needs them)
    from scipy.interpolate import CubicHermiteSpline, CubicSpline, PPoly

    j, dj, q = (np.append(v, v[0]) for v in (j, dj, q))
    dq = CubicSpline(theta, q, bc_type="periodic")(theta, 1)
    spline = CubicHermiteSpline(theta, np.column_stack([j, q]), np.column_stack([dj, dq]))
    slopes = spline.derivative().c                      # quadratics: written as cubics with no cubic term
    c = np.concatenate([spline.c, np.concatenate([np.zeros((1, *slopes.shape[1:])), slopes])], axis=-1)
    return EquationOfMotion(start, PPoly(c, theta, extrapolate="periodic"), added, motor)


@dataclass(frozen=True)
class Stall:
    """Where the speed fell to 0: the crank angle (rad, as the input's), the time (s), and whether the crank then
    turns back (the need exceeds the motor's stall torque and the friction) rather than stays."""

    angle: float
    time: float
    turns_back: bool


@dataclass(frozen=True)
class Steady:
    """The last turn's motion: its mean speed (rad/s, 2 pi over its time), the fastest and slowest (rad/s), the
    coefficient of fluctuation (max - min) / mean, the time to steady speed (s; see the module's note), the motor's
    and the friction's mean torque over the turn (N*m, work over 2 pi) and the motor's mean power (W)."""

    mean: float
    fastest: float
    slowest: float
    fluctuation: float
    settled: float | None
    motor_torque: float
    friction_torque: float
    power: float


@dataclass(frozen=True)
class Motion:
    """The motion from rest (see the module's note).

    Attributes
    ----------
    equation : EquationOfMotion
        What was integrated.
    outcome : {"steady", "stall", "time", "turns", "runaway"}
        What ended the run.
    time, angle, speed : ndarray
        The run at the integrator's steps (s, rad, rad/s; at most :data:`KEPT`, evenly thinned).
    turn_ends, turn_means : ndarray
        The time each full turn ended (s) and its mean speed (rad/s).
    last : Steady or None
        The last full turn's motion (a steady one when ``outcome`` is ``steady``).
    stall : Stall or None
        Where it stalled.
    work : tuple of float
        The motor's, the friction's and the loads' work over the run (J; the loads' is what it took to lift the
        weights, stretch the springs and push the loads), and the kinetic energy at its end (J).
    """

    equation: EquationOfMotion
    outcome: Outcome
    time: np.ndarray
    angle: np.ndarray
    speed: np.ndarray
    turn_ends: np.ndarray
    turn_means: np.ndarray
    last: Steady | None
    stall: Stall | None
    work: tuple[float, float, float, float]
    last_turn: Any = field(default=None, repr=False)

    @property
    def end(self) -> float:
        """The simulated time (s)."""
        return float(self.time[-1])


def _event(fn: Any, terminal: bool, direction: float) -> Any:
    fn.terminal, fn.direction = terminal, direction
    return fn


def _stops(eq: EquationOfMotion, target: float) -> list[Any]:
    """The run's events: the speed falling to 0, past the runaway speed, and the crank reaching ``target`` (rad)."""
    runaway = RUNAWAY_RPM * TWO_PI / 60.0
    return [_event(lambda _t, y: y[1], True, -1.0), _event(lambda _t, y: y[1] - runaway, True, 1.0),
            _event(lambda _t, y: y[0] - target, True, 1.0)]


def _settled(ends: np.ndarray, means: np.ndarray) -> float | None:
    """The end of the first turn from which every turn's mean stays within :data:`SETTLED` of the last's."""
    off = np.abs(means - means[-1]) > SETTLED * means[-1]
    if not off.any():
        return float(ends[0])
    k = int(np.flatnonzero(off)[-1]) + 1
    return float(ends[k]) if k < len(ends) else None


def _is_steady(means: list[float]) -> bool:
    if len(means) < STEADY_TURNS + 1:
        return False
    m = np.asarray(means[-STEADY_TURNS - 1:])
    return bool(np.all(np.abs(np.diff(m)) < STEADY_CHANGE * m[-1]))


def method(eq: EquationOfMotion) -> str:
    """The integrator for ``eq``: DOP853 (explicit, 8th order) unless the motor's own time constant
    J_min / (slope + viscous) is shorter than 1 / :data:`STEPS` of a turn at the speed it heads for (the stall torque
    less the friction over slope + viscous), where the motion is stiff: LSODA (it switches to BDF)."""
    m = eq.motor
    damping = m.slope + m.viscous
    if damping <= 0:
        return "DOP853"
    heads = max(m.stall - m.friction, 0.0) / damping
    least = float(np.min(eq.table(eq.table.x)[:, 0])) + eq.added
    return "LSODA" if least / damping * STEPS * heads < TWO_PI else "DOP853"


def simulate(eq: EquationOfMotion, time: float, turns: int = MAX_TURNS, settle: bool = True) -> Motion:
    """The motion of ``eq`` from rest at its start angle for at most ``time`` s and ``turns`` turns (see the
    module's note); ``settle=False`` runs on past a steady speed (to time a given number of turns)."""
    m = eq.motor
    y = np.array([eq.start, 0.0, 0.0, 0.0, 0.0])
    net = m.stall - float(eq.terms(eq.start)[2])
    if net <= m.friction:                                 # it does not start: the motor cannot lift its need there
        return Motion(eq, "stall", np.zeros(1), np.array([eq.start]), np.zeros(1), np.zeros(0), np.zeros(0), None,
                      Stall(eq.start, 0.0, net < -m.friction), (0.0, 0.0, 0.0, 0.0))
    t = 0.0
    times, angles, speeds = [np.zeros(1)], [np.array([eq.start])], [np.zeros(1)]
    ends: list[float] = []
    means: list[float] = []
    marks: list[np.ndarray] = [y]
    outcome: Outcome = "time"
    stall = None
    last_turn = None
    step: float | None = None
    from scipy.integrate import solve_ivp

    how = method(eq)
    endless = m.constant and m.viscous == 0
    while t < time:
        target = eq.start + TWO_PI * (len(ends) + 1)
        first = {} if step is None else {"first_step": min(step, time - t)}
        out = solve_ivp(eq.derivatives, (t, time), y, method=how, rtol=RTOL, atol=ATOL, dense_output=True,
                        events=_stops(eq, target), **first)
        if out.status < 0:
            raise SolverError(f"dynamics.motor: the motion from rest could not be integrated past t = "
                              f"{float(out.t[-1]):.6g} s ({out.message})")
        times.append(out.t[1:])
        angles.append(out.y[0, 1:])
        speeds.append(out.y[1, 1:])
        t, y = float(out.t[-1]), out.y[:, -1]
        if len(out.t) > 2:
            step = float(min(out.t[-1] - out.t[-2], out.t[-2] - out.t[-3]))
        if out.status != 1:                                   # the time bound
            break
        if out.t_events[0].size:
            stall = Stall(float(y[0]), t, float(eq.terms(y[0])[2]) - m.stall > m.friction)
            outcome = "stall"
            break
        if out.t_events[1].size:
            outcome = "runaway"
            break
        ends.append(t)
        means.append(TWO_PI / (t - (ends[-2] if len(ends) > 1 else 0.0)))
        marks.append(y)
        last_turn = out.sol
        if settle and _is_steady(means):
            outcome = "steady"
            break
        if endless and len(ends) >= RUNAWAY_TURNS:
            outcome = "runaway"
            break
        if len(ends) >= turns:
            outcome = "turns"
            break
    ends_a, means_a = np.asarray(ends), np.asarray(means)
    last = None
    if ends and last_turn is not None:
        last = _last_turn(eq, last_turn, ends[-2] if len(ends) > 1 else 0.0, ends[-1], marks[-2], marks[-1],
                          _settled(ends_a, means_a) if outcome == "steady" else None)
    tt, aa, ss = (np.concatenate(v) for v in (times, angles, speeds))
    if len(tt) > KEPT:
        keep = np.unique(np.linspace(0, len(tt) - 1, KEPT).round().astype(int))
        tt, aa, ss = tt[keep], aa[keep], ss[keep]
    work = (float(y[2]), float(y[3]), float(y[4]), eq.kinetic(float(y[0]), float(y[1])))
    return Motion(eq, outcome, tt, aa, ss, ends_a, means_a, last, stall, work, last_turn)


def _last_turn(eq: EquationOfMotion, sol: Any, t0: float, t1: float, y0: np.ndarray, y1: np.ndarray,
               settled: float | None) -> Steady:
    """The last full turn's motion, sampled at :data:`LAST_TURN` times of its dense output."""
    w = sol(np.linspace(t0, t1, LAST_TURN))[1]
    mean = TWO_PI / (t1 - t0)
    motor, friction = (float(y1[k] - y0[k]) for k in (2, 3))
    return Steady(mean, float(w.max()), float(w.min()), float((w.max() - w.min()) / mean), settled,
                  motor / TWO_PI, friction / TWO_PI, motor / (t1 - t0))


def motion_of(table: DynamicsTable, linkage: Linkage, masses: Mapping[str, LinkMass], loads: Loads, start: float,
              turns: bool, flywheel: FlywheelSize | None) -> Motion | None:
    """The motion from rest of ``table.motor`` (None without one) driving ``linkage``'s crank from ``start`` (rad),
    the flywheel's inertia added when ``table.motor.flywheel`` (as made, else as needed); a :class:`SpecError` on
    ``dynamics.motor`` for an input that does not turn fully (a slide, a crank over a limited range)."""
    if table.motor is None:
        return None
    if not turns:
        raise SpecError("a motor drives a crank that turns fully; this input (a slide, or a crank over a limited "
                        "range) is not one: leave [dynamics.motor] out", "dynamics.motor")
    motor = Motor.of(table.motor)
    added = motor.rotor
    if flywheel is not None and table.motor.flywheel:
        added += flywheel.inertia if flywheel.inertia is not None else flywheel.needed
    eq = equation_of(linkage, masses, loads, start, added, motor)
    return simulate(eq, table.motor.time)
