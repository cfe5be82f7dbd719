"""Forward dynamics with a motor (``[dynamics.motor]``, :mod:`linkgen.dynamics.forward`): a disc crank against the
closed-form exponential approach to the motor line's steady speed, a pendulum crank's stall against its energy
equation, the energy balance of a run of Jansen's leg, the flywheel's coefficient met from rest, the steady motor
torque against the kinetostatics, and bad input refused."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import quad, simpson
from scipy.optimize import brentq

from linkgen.cli import main
from linkgen.linkage_design import design_linkage
from linkgen.dynamics.forward import SETTLED, equation_of, method, simulate
from linkgen.dynamics.motor import Motor, MotorTable
from linkgen.kinematics import equivalents
from linkgen.kinematics.fourbar import FourBar
from linkgen.kinematics.inertia import LinkMass, generalised_inertia
from linkgen.kinematics.kinetostatics import G0, Loads, kinetostatics
from linkgen.kinematics.linkage import Linkage
from linkgen.spec import load_spec
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

JANSEN = ROOT / "templates" / "jansen-dynamics.toml"
RPM = 2 * math.pi / 60


def _fourbar() -> Linkage:
    """A crank-rocker whose crank alone will carry mass (its coupler and rocker massless)."""
    return Linkage.of(equivalents.fourbar(FourBar(100.0, 30.0, 90.0, 70.0), 0.0))


def _jansen(*sets: str):
    return design_linkage(load_spec(JANSEN, sets)).dynamics


def _settled(ends: np.ndarray, means: np.ndarray) -> float:
    """The issue's time to steady speed, from the turns' ends and means: the end of the first turn from which
    every turn's mean stays within 1 % of the last's."""
    inside = np.abs(means - means[-1]) <= 0.01 * means[-1]
    k = len(inside)
    while k > 0 and inside[k - 1]:
        k -= 1
    return float(ends[k])


@pytest.mark.parametrize(("disc", "rotor", "integrator"), [(5000.0, 2.0, "DOP853"), (5.0, 0.0, "LSODA")])
def test_a_disc_crank_approaches_the_motor_lines_speed_as_the_closed_form(disc, rotor, integrator):
    """A balanced disc on the crank (0.5 kg, ``disc`` kg*mm^2 about its centre on the pivot: J constant, gravity
    holds nothing) driven through a 10:1 gear by a motor of 0.02 N*m stall torque and 3000 rpm no-load speed, with a
    rotor of ``rotor`` kg*mm^2, 0.01 N*m of friction and 0.005 N*m at 1000 rpm of viscous friction. By hand at the
    crank: the torque 10 x 0.02 (1 - 10 w / 100 pi) = 0.2 - (2 / 100 pi) w N*m, the viscous c = 0.005 / (1000
    rpm), J = disc + 10^2 rotor, so J w' = 0.19 - (2 / 100 pi + c) w: w = w_s (1 - exp(-t / tau)) with w_s =
    0.19 / k, tau = J / k (k = 2 / 100 pi + c), and theta = w_s (t - tau (1 - exp(-t / tau))). The integrated speed
    follows it to 1e-6 of w_s, each turn ends when theta = 2 pi k does (1e-7 of its time), and the time to steady
    speed and the steady speed are the closed form's: a time constant of 4 turns (explicit DOP853), and of 1/270 of
    a turn (stiff: LSODA)."""
    table = MotorTable(stall_torque=0.02, no_load_speed=3000.0, gear_ratio=10.0, rotor_inertia=rotor, friction=0.01,
                       viscous=0.005, time=60.0)
    motor = Motor.of(table)
    c = 0.005 / (1000 * RPM)
    k = 2 / (100 * math.pi) + c
    big_j = (disc + 100 * rotor) * 1e-6
    assert (motor.stall, motor.slope, motor.rotor, motor.viscous) == pytest.approx((0.2, 2 / (100 * math.pi),
                                                                                    100 * rotor * 1e-6, c), rel=1e-12)
    linkage = _fourbar()
    masses = {"crank": LinkMass(0.5, (0.0, 0.0), disc)}
    eq = equation_of(linkage, masses, Loads((0.0, -G0)), 0.0, motor.rotor, motor)
    assert method(eq) == integrator
    motion = simulate(eq, table.time)
    w_s, tau = 0.19 / k, big_j / k

    def theta(t: float) -> float:
        return w_s * (t - tau * (1 - math.exp(-t / tau)))

    assert motion.outcome == "steady" and 3 < len(motion.turn_ends) < 200
    exact = w_s * (1 - np.exp(-motion.time / tau))
    assert np.abs(motion.speed - exact).max() <= 1e-6 * w_s
    ends = np.array([brentq(lambda t, n=n: theta(t) - 2 * math.pi * n, 0.0, 1e3, xtol=1e-14)
                     for n in range(1, len(motion.turn_ends) + 1)])
    assert np.abs(motion.turn_ends - ends).max() <= 1e-7 * ends[-1]
    means = 2 * math.pi / np.diff(np.concatenate([[0.0], ends]))
    assert motion.turn_means == pytest.approx(means, rel=1e-7)
    last = motion.last
    assert last is not None and last.settled == pytest.approx(_settled(ends, means), rel=1e-9)
    assert last.settled == pytest.approx(_settled(motion.turn_ends, motion.turn_means), rel=1e-12)
    assert last.mean == pytest.approx(w_s, rel=1e-4)
    assert last.fluctuation < 1e-4                                     # a constant inertia: no ripple
    assert last.motor_torque == pytest.approx(0.2 - (2 / (100 * math.pi)) * w_s, rel=1e-3)


def test_a_motor_below_the_peak_need_stalls_where_the_energy_runs_out():
    """A crank carrying 0.1 kg at 40 mm, a quarter turn behind its line (it hangs below the pivot at the start),
    upright, driven by a constant 0.5 m g r: the energy 1/2 J w^2 = T dtheta - m g r (1 - cos dtheta) falls back to
    0 at dtheta = the root of dtheta / 2 = 1 - cos dtheta, before the peak need m g r at a quarter turn; the run
    stops there (not at its 60 s bound), reports the angle to 1e-6 rad and the time (the integral of dtheta / w,
    by quad with the ends' square-root weights) to 1e-6, and the crank turns back (its need there exceeds the
    motor's torque). A motor that cannot lift its need at the start stalls at once."""
    m, r = 0.1, 40.0
    mgr = m * G0 * r * 1e-3
    inertia = 20.0
    big_j = (inertia + m * r * r) * 1e-6
    linkage = _fourbar()
    masses = {"crank": LinkMass(m, (0.0, -r), inertia)}
    eq = equation_of(linkage, masses, Loads((0.0, -G0)), 0.0, 0.0, Motor.of(MotorTable(torque=0.5 * mgr)))
    assert float(eq.terms(0.5 * math.pi)[2]) == pytest.approx(mgr, rel=1e-9)        # the peak need
    motion = simulate(eq, 60.0)
    stop = brentq(lambda d: 0.5 * d - (1 - math.cos(d)), 0.5, 3.0, xtol=1e-15)

    def speed(d: float) -> float:
        return math.sqrt(max(2 * (0.5 * mgr * d - mgr * (1 - math.cos(d))) / big_j, 0.0))

    def smooth(d: float) -> float:
        """sqrt(d (stop - d)) / w(d): smooth on [0, stop] (taken just inside at the ends, where both vanish)."""
        d = min(max(d, 1e-9), stop - 1e-9)
        return math.sqrt(d * (stop - d)) / speed(d)

    when, _ = quad(smooth, 0.0, stop, weight="alg", wvar=(-0.5, -0.5), epsabs=0, epsrel=1e-12)
    assert motion.outcome == "stall" and motion.stall is not None and not motion.turn_ends.size
    assert motion.stall.angle == pytest.approx(stop, abs=1e-6)
    assert motion.stall.time == pytest.approx(when, rel=1e-6) and motion.end < 60.0
    assert motion.stall.turns_back and math.sin(stop) > 0.5
    weak = equation_of(linkage, {"crank": LinkMass(m, (r, 0.0), inertia)}, Loads((0.0, -G0)), 0.0, 0.0,
                       Motor.of(MotorTable(torque=0.5 * mgr)))
    held = simulate(weak, 60.0)
    assert held.outcome == "stall" and held.stall is not None and (held.stall.angle, held.stall.time) == (0.0, 0.0)
    assert held.stall.turns_back


def test_the_energy_balances_over_a_run():
    """Jansen's leg from its template (no flywheel: its inertia varies by a factor over a turn) under a constant
    0.004 N*m against 0.0005 N*m of friction for 0.19 s (mid-turn, its third): the kinetic energy at the end,
    1/2 J(theta) w^2 with J from the inertia's own function at that pose, equals the motor's work T dtheta less the
    friction's Tf dtheta less the loads' (the integral of the need at rest Q over the angle turned: whole turns by
    the turn's mean of 4096 poses, the rest by 64-point Gauss-Legendre) to 1e-6 of the motor's work; the run's own
    tallies agree."""
    dyn = _jansen("dynamics.motor.torque=0.004", "dynamics.motor.friction=0.0005", "dynamics.motor.flywheel=false",
                  "dynamics.motor.time=0.19")
    motion = dyn.motion
    assert motion is not None and motion.outcome == "time" and len(motion.turn_ends) >= 2
    linkage, masses = dyn.analysis.linkage, dyn.masses.drawn
    start, end = motion.equation.start, float(motion.angle[-1])
    w = float(motion.speed[-1])
    j_end = generalised_inertia(linkage.structure, linkage.solve(np.array([end])), masses)[0][0]
    assert np.ptp(generalised_inertia(linkage.structure, linkage.solve(np.linspace(0, 6.28, 90)), masses)[0]) > \
        0.3 * j_end
    turned = end - start
    full = math.floor(turned / (2 * math.pi))
    grid = start + 2 * math.pi * np.arange(4096) / 4096
    per_turn = 2 * math.pi * float(kinetostatics(linkage, linkage.solve(grid), masses, 0.0, 0.0,
                                                 dyn.loads).effort.mean())
    x, wts = np.polynomial.legendre.leggauss(64)
    a, b = start + 2 * math.pi * full, end
    nodes = 0.5 * (b - a) * x + 0.5 * (a + b)
    rest = 0.5 * (b - a) * float(wts @ kinetostatics(linkage, linkage.solve(nodes), masses, 0.0, 0.0,
                                                     dyn.loads).effort)
    loads = full * per_turn + rest
    motor, friction = 0.004 * turned, 0.0005 * turned
    kinetic = 0.5 * j_end * w * w
    assert kinetic == pytest.approx(motor - friction - loads, abs=1e-6 * motor)
    got_motor, got_friction, got_loads, got_kinetic = motion.work
    assert (got_motor, got_friction) == pytest.approx((motor, friction), rel=1e-9)
    assert got_loads == pytest.approx(loads, abs=1e-6 * motor)
    assert got_kinetic == pytest.approx(kinetic, rel=1e-6)


def test_a_constant_torque_with_nothing_to_hold_it_back_runs_away():
    """Jansen's leg (no flywheel) under a constant 0.0006 N*m, a quarter of its peak need, against 0.0001 N*m of
    friction and no viscous friction: once it has passed a turn, every turn adds the same energy, 2 pi (T - Tf - the
    mean need), so the run stops as a runaway after four turns instead of running to its bound; at the fourth turn's
    end (the start's pose again) 1/2 J w^2 is four turns' gain to 1e-6, and the report warns."""
    dyn = _jansen("dynamics.motor.torque=0.0006", "dynamics.motor.friction=0.0001", "dynamics.motor.flywheel=false")
    motion = dyn.motion
    assert motion is not None and motion.outcome == "runaway" and len(motion.turn_ends) == 4
    assert motion.end == motion.turn_ends[-1] < dyn.table.motor.time
    linkage, masses = dyn.analysis.linkage, dyn.masses.drawn
    start = motion.equation.start
    grid = start + 2 * math.pi * np.arange(4096) / 4096
    held = kinetostatics(linkage, linkage.solve(grid), masses, 0.0, 0.0, dyn.loads).effort
    need = float(held.mean())
    assert float(np.abs(held).max()) > 0.0006 / 0.3                    # well below the peak need
    j = generalised_inertia(linkage.structure, linkage.solve(np.array([start])), masses)[0][0]
    assert 0.5 * j * float(motion.speed[-1]) ** 2 == pytest.approx(4 * 2 * math.pi * (0.0006 - 0.0001 - need),
                                                                   rel=1e-6)
    report = design_linkage(load_spec(JANSEN, ("dynamics.motor.torque=0.0006", "dynamics.motor.friction=0.0001",
                                               "dynamics.motor.flywheel=false"))).report["dynamics"]
    assert report["motor"]["ended"] == "runaway"
    assert any(w.startswith("the crank speeds up without bound") for w in report["warnings"])


def test_the_flywheel_sized_for_a_coefficient_meets_it_from_rest():
    """Jansen's leg with the flywheel the dynamics sizes for Cs = 0.05 at 60 rpm, driven from rest by a motor line
    whose no-load speed is 60 rpm (with no loads but gravity, the mean need is 0, so the steady mean speed is the
    no-load speed) and whose 0.003 N*m stall torque is flat enough (time constant J / slope = 1.6 s, ten radians of
    crank) not to damp the ripple: the steady run keeps (max - min) / mean within 1 % of 0.05, at 60 rpm."""
    dyn = _jansen("dynamics.motor.stall_torque=0.003", "dynamics.motor.no_load_speed=60",
                  "dynamics.motor.time=120")
    motion = dyn.motion
    assert motion is not None and motion.outcome == "steady" and dyn.flywheel is not None
    assert motion.equation.added == pytest.approx(dyn.flywheel.inertia, rel=1e-12)
    last = motion.last
    assert last is not None
    assert last.fluctuation == pytest.approx(0.05, rel=0.01)
    assert last.mean == pytest.approx(60 * RPM, rel=1e-3)
    assert last.settled is not None and 0 < last.settled < motion.end


def test_the_steady_motor_torque_is_the_kinetostatics_driving_torque():
    """At steady state (Jansen's leg with its flywheel, a motor of 0.006 N*m stall torque and 90 rpm no-load speed,
    0.0005 N*m of friction and 0.001 N*m at 1000 rpm of viscous friction), over the last turn: at every sample the
    motor's torque less the friction is the kinetostatics' driving torque at the run's own speed and acceleration
    (plus the flywheel's J w') to 1e-6 of its peak, so its mean over the turn (work / 2 pi) is the kinetostatics'
    mean with the friction to 1e-6; and it is the kinetostatics' mean at the constant steady speed, with the
    friction, within 1e-3 (what a turn's last change of speed leaves)."""
    dyn = _jansen("dynamics.motor.stall_torque=0.006", "dynamics.motor.no_load_speed=90",
                  "dynamics.motor.friction=0.0005", "dynamics.motor.viscous=0.001", "dynamics.motor.time=120")
    motion = dyn.motion
    assert motion is not None and motion.outcome == "steady" and motion.last is not None
    eq, motor, last = motion.equation, motion.equation.motor, motion.last
    t = np.linspace(motion.turn_ends[-2], motion.turn_ends[-1], 4097)
    theta, w = motion.last_turn(t)[:2]
    accel = eq.acceleration(theta, w)
    linkage, masses = dyn.analysis.linkage, dyn.masses.drawn
    effort = kinetostatics(linkage, linkage.solve(theta), masses, w, accel, dyn.loads).effort + eq.added * accel
    drive = motor.stall - motor.slope * w - (motor.friction + motor.viscous * w)
    assert np.abs(drive - effort).max() <= 1e-6 * np.abs(effort).max()
    friction = simpson((motor.friction + motor.viscous * w) * w, x=t) / (2 * math.pi)
    mean_effort = simpson(effort * w, x=t) / (2 * math.pi)
    assert last.motor_torque == pytest.approx(mean_effort + friction, rel=1e-6)
    assert last.friction_torque == pytest.approx(friction, rel=1e-6)
    grid = 2 * math.pi * np.arange(720) / 720
    steady = kinetostatics(linkage, linkage.solve(grid), masses, last.mean, 0.0, dyn.loads).effort.mean()
    assert last.motor_torque == pytest.approx(steady + friction, rel=1e-3)


def test_the_report_console_figure_and_family_of_a_motor(tmp_path):
    """``linkgen analyze --figures`` of Jansen's leg with a motor: the report's ``dynamics.motor`` section, the
    console's line of it, the motor's figure; a stall gives its line and its warning; the family's columns."""
    from linkgen.dynamics.report import family_columns

    out = tmp_path / "out"
    args = ["analyze", str(JANSEN), "-o", str(out), "--figures", "--set", "dynamics.motor.stall_torque=0.003",
            "--set", "dynamics.motor.no_load_speed=60"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    report = json.loads((out / "jansen-dynamics.json").read_text())
    d = report["dynamics"]["motor"]
    assert d["ended"] == "steady" and d["steady_within"] == SETTLED
    assert d["steady"]["fluctuation"] == pytest.approx(0.05, rel=0.01)
    assert d["work_J"]["kinetic_at_end"] == pytest.approx(d["work_J"]["motor"] - d["work_J"]["loads"], rel=1e-6)
    line = next(x for x in result.output.splitlines() if x.startswith("  motor from rest"))
    assert f"steady after {d['time_to_steady_s']:.4g} s at {d['steady']['mean_rpm']:.5g} rpm" in line
    assert (out / "jansen-dynamics-motor.png").stat().st_size > 10_000
    columns = family_columns(report)
    assert columns["motor_steady_rpm"] == d["steady"]["mean_rpm"] and columns["motor_stall_deg"] is None
    stalled = tmp_path / "stalled"
    result = CliRunner().invoke(main, ["analyze", str(JANSEN), "-o", str(stalled), "--set",
                                       "dynamics.motor.torque=0.0003", "--set", "dynamics.motor.flywheel=false",
                                       "--set", "dynamics.motor.friction=0.0002"])
    assert result.exit_code == 0, result.output
    s = json.loads((stalled / "jansen-dynamics.json").read_text())["dynamics"]["motor"]
    assert s["ended"] == "stall" and s["stall"]["then"] == "turns back"
    assert 0 < s["stall"]["after_s"] < 20.0 and s["simulated_s"] == s["stall"]["after_s"]
    said = f"stalls at theta = {s['stall']['at_input_deg']:.4g} degrees after {s['stall']['after_s']:.4g} s"
    assert f"{said} and turns back" in result.output
    assert f"warning: the motor {said}" in result.output


@pytest.mark.parametrize(("change", "message"), [
    ({"dynamics.motor.friction": 0.01}, "dynamics.motor.stall_torque: give the motor's stall torque and no-load "
                                        "speed"),
    ({"dynamics.motor.stall_torque": 0.0, "dynamics.motor.no_load_speed": 60.0},
     "dynamics.motor.stall_torque: must be > 0 and <= 100000 N*m (got 0"),
    ({"dynamics.motor.stall_torque": 0.01, "dynamics.motor.no_load_speed": -100.0},
     "dynamics.motor.no_load_speed: must be > 0 and <= 100000 rpm (got -100"),
    ({"dynamics.motor.stall_torque": 0.01}, "dynamics.motor.no_load_speed: a torque-speed line needs"),
    ({"dynamics.motor.torque": 0.01, "dynamics.motor.stall_torque": 0.01}, "dynamics.motor.torque: a constant "
                                                                           "torque is instead of"),
    ({"dynamics.motor.torque": 0.01, "dynamics.motor.time": 600.001}, "dynamics.motor.time: must be > 0 and <= "
                                                                      "600 s (got 600.001"),
    ({"dynamics.motor.torque": 0.01, "dynamics.motor.gear_ratio": 1e5}, "dynamics.motor.gear_ratio: must be"),
    ({"dynamics.motor.torque": 0.01, "dynamics.motor.viscous": -1.0}, "dynamics.motor.viscous: must be >= 0"),
])
def test_bad_motors_are_refused_in_one_line(tmp_path, change, message):
    assert_refused(JANSEN, change, message, tmp_path, main, "analyze")


def test_a_motor_on_a_slide_input_is_refused(tmp_path):
    """A slide-driven pump: the motor drives a crank turning fully only, refused naming the table."""
    assert_refused(ROOT / "templates" / "pendulum-pump.toml", {"dynamics.motor.torque": 1.0},
                   "dynamics.motor: a motor drives a crank that turns fully", tmp_path, main, "analyze")
