"""The dynamics at a speed that varies over the turn (``dynamics.speed_profile``, :mod:`linkgen.dynamics.profile`):
a constant profile against ``linkage.rpm``; a profile w0 (1 + e sin theta) against its closed-form acceleration, the
spline's error bounds and their order, and against the energy method; a slide's profile; the motor's steady turn
against the motor's torque; the report's speed; bad input refused in one line."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.interpolate import CubicSpline

from linkgen import spec as linkgen_spec
from linkgen.cli import main
from linkgen.linkage_design import design_linkage
from linkgen.dynamics.profile import rows_profile
from linkgen.dynamics.run import Dynamics
from linkgen.dynamics.table import MAX_PROFILE_RPM
from linkgen.spec import load_spec
from tests.conftest import ROOT
from tests.support.refusals import assert_refused
from tests.linkgen.test_linkage_dynamics import _energy_torque

JANSEN = ROOT / "templates" / "jansen-dynamics.toml"
PUMP = ROOT / "templates" / "pendulum-pump.toml"
RPM = 2 * math.pi / 60
#: the sine profile's mean speed (rpm) and its relative swing
W0, E = 60.0, 0.3


def _rows(count: int, w0: float = W0, e: float = E) -> list[list[float]]:
    """``count`` rows [crank_deg, rpm] of w0 (1 + e sin theta), uniform over a turn from 0."""
    return [[360.0 * k / count, w0 * (1 + e * math.sin(2 * math.pi * k / count))] for k in range(count)]


def _jansen(*sets: str) -> Dynamics:
    dyn = design_linkage(load_spec(JANSEN, sets)).dynamics
    assert dyn is not None
    return dyn


def test_the_profiles_bound_is_linkage_rpms():
    assert MAX_PROFILE_RPM == linkgen_spec.MAX_RPM


def test_a_constant_profile_is_linkage_rpm():
    """Jansen's leg with 12 rows all at 60 rpm (its linkage.rpm): every joint's force, the driving torque, the
    shaking, the flywheel and the counterweight are the constant speed's to 1e-12 of their peaks; the report says
    which speed was used."""
    const = _jansen()
    rows = [[30.0 * k, 60.0] for k in range(12)]
    prof = _jansen(f"dynamics.speed_profile={rows}")
    assert prof.profile is not None and prof.profile.kind == "profile" and const.profile is None
    a, b = const.result, prof.result

    def same(x: np.ndarray, y: np.ndarray) -> None:
        assert np.abs(x - y).max() <= 1e-12 * np.abs(x).max()

    same(a.effort, b.effort)
    same(a.shaking_force, b.shaking_force)
    same(a.shaking_moment, b.shaking_moment)
    for p, q in zip(a.pairs, b.pairs, strict=True):
        same(p.force, q.force)
    assert const.flywheel is not None and prof.flywheel is not None
    assert prof.flywheel.needed == pytest.approx(const.flywheel.needed, rel=1e-12)
    assert const.counterweight is not None and prof.counterweight is not None
    assert prof.counterweight.mass_radius == pytest.approx(const.counterweight.mass_radius, rel=1e-12)
    assert prof.profile.mean == pytest.approx(60 * RPM, rel=1e-12)


@pytest.mark.parametrize("count", [12, 24, 48, 96])
def test_the_acceleration_is_the_closed_forms_within_the_splines_error(count):
    """w = w0 (1 + e sin theta) through ``count`` rows: at every one of 720 poses the speed is within the periodic
    cubic spline's bound (5/384) h^4 max|w''''| and the acceleration alpha = w w' within |s - w| |s'| + |w|
    (1/24) h^3 max|w''''| (the derivative's bound; w'''' = w0 e sin theta, so max|w''''| = w0 e) of the closed form
    w0^2 e cos theta (1 + e sin theta). The spline's own min, max and the mean over time are w0 (1 -+ e) and
    w0 sqrt(1 - e^2) (2 pi over integral dtheta / w) within the same bounds."""
    w0 = W0 * RPM
    rows = tuple((float(a), float(r)) for a, r in _rows(count))
    profile = rows_profile(rows, True, 0.0, 2 * math.pi)
    theta = 0.123 + 2 * math.pi * np.arange(720) / 720
    w, alpha = profile.at(theta)
    h = 2 * math.pi / count
    top = w0 * E
    speed_bound = 5 / 384 * h**4 * top
    exact_w = w0 * (1 + E * np.sin(theta))
    assert np.abs(w - exact_w).max() <= speed_bound
    slope_bound = h**3 / 24 * top
    bound = speed_bound * (w0 * E + slope_bound) + w0 * (1 + E) * slope_bound
    exact = w0**2 * E * np.cos(theta) * (1 + E * np.sin(theta))
    assert np.abs(alpha - exact).max() <= bound
    assert np.abs(alpha - exact).max() > 1e-6 * bound                   # the spline's error, not rounding
    assert profile.slowest == pytest.approx(w0 * (1 - E), abs=speed_bound)
    assert profile.fastest == pytest.approx(w0 * (1 + E), abs=speed_bound)
    assert profile.mean == pytest.approx(w0 * math.sqrt(1 - E * E), abs=2 * speed_bound)


def test_the_acceleration_error_falls_as_h4_at_the_rows_and_h3_between():
    """The order of the spline's error with the row count (12 to 192 rows, doubling): at the rows the acceleration
    (and everywhere the speed) falls 16-fold a doubling (h^4); between the rows the acceleration, a derivative of
    the spline, falls 8-fold (h^3), as the bounds of the test above say."""
    w0 = W0 * RPM
    theta = 0.123 + 2 * math.pi * np.arange(720) / 720
    at_rows, between, speed = [], [], []
    for count in (12, 24, 48, 96, 192):
        rows = tuple((float(a), float(r)) for a, r in _rows(count))
        profile = rows_profile(rows, True, 0.0, 2 * math.pi)
        knots = 2 * math.pi * np.arange(count) / count
        for where, out in ((knots, at_rows), (theta, between)):
            got = profile.at(where)[1]
            out.append(np.abs(got - w0**2 * E * np.cos(where) * (1 + E * np.sin(where))).max())
        speed.append(np.abs(profile.at(theta)[0] - w0 * (1 + E * np.sin(theta))).max())
    for errors, order in ((at_rows, 4), (between, 3), (speed, 4)):
        ratios = np.asarray(errors[:-1]) / np.asarray(errors[1:])
        assert np.all(np.abs(np.log2(ratios) - order) < 0.25), (order, ratios)


def test_the_driving_torque_at_a_varying_speed_is_the_energy_methods():
    """Jansen's leg (its plywood parts, gravity upright) at w0 (1 + e sin theta) through 36 rows: at the middles of
    the rows (where the spline is one cubic over the differences' stencil) the Newton-Euler torque equals the energy
    method's d(T + V)/dtheta, the kinetic energy 1/2 J(theta) s(theta)^2 at each differenced pose's own speed (no
    acceleration is given it), to 1e-8 of its peak; the torque differs from the constant speed's by far more."""
    dyn = _jansen(f"dynamics.speed_profile={_rows(36)}")
    assert dyn.profile is not None
    theta = np.radians(5.0 + 10.0 * np.arange(36))
    got = dyn.at(theta).effort
    linkage = dyn.analysis.linkage
    want = _energy_torque(linkage, theta, dict(dyn.masses.drawn), dyn.loads, lambda x: dyn.profile.at(x)[0])
    scale = np.abs(want).max()
    assert np.abs(got - want).max() <= 1e-8 * scale, np.abs(got - want).max() / scale
    steady = _jansen().at(theta).effort
    assert np.abs(steady - got).max() > 0.01 * scale


def test_the_flywheel_is_sized_at_the_profiles_mean_speed():
    """With a profile the flywheel is sized at a constant speed, the profile's mean: the same flywheel as a constant
    linkage.rpm at that mean gives."""
    dyn = _jansen(f"dynamics.speed_profile={_rows(24)}")
    assert dyn.profile is not None and dyn.flywheel is not None
    mean_rpm = dyn.profile.mean / RPM
    const = _jansen(f"linkage.rpm={mean_rpm!r}")
    assert const.flywheel is not None
    assert dyn.flywheel.needed == pytest.approx(const.flywheel.needed, rel=1e-9)
    assert dyn.flywheel.energy == pytest.approx(const.flywheel.energy, rel=1e-9)


def test_a_slides_profile():
    """The slide-driven pump: rows at 50 mm/s all over its travel give the constant 50 mm/s forces exactly; rows on
    a line v = 60 + 0.5 x mm/s (a natural spline of a line is the line) give a = v dv/dx = 0.5 v at every pose to
    1e-12, and its mean over time is the travel over integral dx / v = L / (2 ln(v1 / v0)); rows short of the
    travel are refused."""
    const = design_linkage(load_spec(PUMP, ["dynamics.speed=50"])).dynamics
    rows = [[-40.0, 50.0], [-10.0, 50.0], [10.0, 50.0], [40.0, 50.0]]
    flat = design_linkage(load_spec(PUMP, [f"dynamics.speed_profile={rows}"])).dynamics
    assert const is not None and flat is not None
    assert np.abs(flat.result.effort - const.result.effort).max() <= 1e-12 * np.abs(const.result.effort).max()
    line = [[x, 60.0 + 0.5 * x] for x in (-40.0, -15.0, 5.0, 40.0)]
    dyn = design_linkage(load_spec(PUMP, [f"dynamics.speed_profile={line}"])).dynamics
    assert dyn is not None and dyn.profile is not None
    x = dyn.result.inputs
    v = (60.0 + 0.5 * x) * 1e-3
    assert np.abs(np.asarray(dyn.result.speed) - v).max() <= 1e-12
    assert np.abs(np.asarray(dyn.result.acceleration) - 0.5 * v).max() <= 1e-12
    lo, hi = float(x[0]), float(x[-1])
    v0, v1 = 60.0 + 0.5 * lo, 60.0 + 0.5 * hi
    assert dyn.profile.mean == pytest.approx((hi - lo) * 1e-3 * 0.5 / math.log(v1 / v0), rel=1e-9)


def test_the_motors_steady_turn():
    """Jansen's leg with its flywheel, a motor line of 0.006 N*m stall and 90 rpm no-load through its shaft with a
    rotor, 0.0005 N*m and 0.001 N*m at 1000 rpm of friction, ``speed_profile = "motor"``: at every pose the
    kinetostatics' driving torque (plus the flywheel's and rotor's J alpha) is the motor's torque less the friction
    at the run's own speed there, to 1e-6 of its peak (the tolerance of the run's tabulated J, J' and Q); the
    profile's turn takes the run's last turn's time (integral dtheta / w) to 1e-7 and its extremes are the run's."""
    dyn = _jansen('dynamics.speed_profile="motor"', "dynamics.motor.stall_torque=0.006",
                  "dynamics.motor.no_load_speed=90", "dynamics.motor.friction=0.0005", "dynamics.motor.viscous=0.001",
                  "dynamics.motor.rotor_inertia=20", "dynamics.motor.time=120")
    motion, profile = dyn.motion, dyn.profile
    assert motion is not None and motion.outcome == "steady" and profile is not None and profile.kind == "motor"
    eq, m = motion.equation, motion.equation.motor
    w = np.asarray(dyn.result.speed)
    alpha = np.asarray(dyn.result.acceleration)
    drive = m.stall - m.slope * w - (m.friction + m.viscous * w)
    effort = dyn.result.effort + eq.added * alpha
    assert eq.added > m.rotor > 0
    assert np.abs(drive - effort).max() <= 1e-6 * np.abs(effort).max()
    assert np.ptp(w) > 0.01 * w.mean()                                 # a speed that varies over the turn
    spline = CubicSpline(np.append(dyn.result.inputs, dyn.result.inputs[0] + 2 * math.pi), np.append(1 / w, 1 / w[0]),
                         bc_type="periodic")
    turn = float(spline.integrate(dyn.result.inputs[0], dyn.result.inputs[0] + 2 * math.pi))
    assert turn == pytest.approx(motion.turn_ends[-1] - motion.turn_ends[-2], rel=1e-7)
    assert motion.last is not None
    assert (profile.mean, profile.slowest, profile.fastest) == (motion.last.mean, motion.last.slowest,
                                                                motion.last.fastest)


def test_the_report_and_console_say_the_speed_used(tmp_path):
    """``linkgen analyze`` with the sine profile: the report's speed section says "profile" with its rows and its
    min, mean and max in rpm (w0 (1 - e), w0 sqrt(1 - e^2), w0 (1 + e) within the spline's error), the console's
    dynamics line says it and the torque's figure is drawn; without a profile it says "constant"."""
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["analyze", str(JANSEN), "-o", str(out), "--figures", "--set",
                                       f"dynamics.speed_profile={_rows(72)}"])
    assert result.exit_code == 0, result.output
    assert (out / "jansen-dynamics-torque.png").stat().st_size > 10_000
    d = json.loads((out / "jansen-dynamics.json").read_text())["dynamics"]
    s = d["speed"]
    assert s["used"] == "profile" and s["rows"] == 72 and "input_acceleration_rad_s2" not in d
    assert s["min_rpm"] == pytest.approx(W0 * (1 - E), rel=1e-6)
    assert s["max_rpm"] == pytest.approx(W0 * (1 + E), rel=1e-6)
    assert s["mean_rpm"] == pytest.approx(W0 * math.sqrt(1 - E * E), rel=1e-6)
    assert f"dynamics at {s['min_rpm']:.4g} to {s['max_rpm']:.4g} rpm (profile, mean {s['mean_rpm']:.4g})" in \
        result.output
    plain = tmp_path / "plain"
    result = CliRunner().invoke(main, ["analyze", str(JANSEN), "-o", str(plain)])
    assert result.exit_code == 0, result.output
    s = json.loads((plain / "jansen-dynamics.json").read_text())["dynamics"]["speed"]
    assert s == {"used": "constant", "rpm": 60.0, "min_rpm": 60.0, "mean_rpm": 60.0, "max_rpm": 60.0}
    assert "dynamics at 60 rpm:" in result.output


@pytest.mark.parametrize(("change", "message"), [
    ({"dynamics.speed_profile": [[0, 60], [90, 70], [180, 60]]}, "dynamics.speed_profile: needs 4 to 3600 rows"),
    ({"dynamics.speed_profile": [[0, 60], [90, 70], [80, 60], [270, 50]]},
     "dynamics.speed_profile[2]: the rows' crank angles (or positions) must increase strictly (got 80 after 90)"),
    ({"dynamics.speed_profile": [[0, 60], [90, 0], [180, 60], [270, 50]]},
     "dynamics.speed_profile[1]: a speed must be > 0 rpm (or mm/s) (got 0)"),
    ({"dynamics.speed_profile": [[0, 60], [90, 70], [180, 60], [360, 50]]},
     "dynamics.speed_profile: the rows' crank angles must lie within one turn"),
    ({"dynamics.speed_profile": [[0, 60], [90, 2e5], [180, 60], [270, 50]]},
     "dynamics.speed_profile[1]: a speed must be > 0 and <= 100000 rpm (got 200000)"),
    ({"dynamics.speed_profile": [[0, 1], [10, 1000], [20, 1], [30, 1]]},
     "dynamics.speed_profile: the spline through the rows reaches"),
    ({"dynamics.speed_profile": "fast"}, 'dynamics.speed_profile: must be "motor" or rows'),
    ({"dynamics.speed_profile": [[0, 60]] * 3601}, "dynamics.speed_profile: needs 4 to 3600 rows"),
    ({"dynamics.speed_profile": "motor"}, 'dynamics.speed_profile: "motor" is the steady turn the [dynamics.motor] '
                                          "run reaches: give a [dynamics.motor]"),
    ({"dynamics.speed_profile": [[0, 60], [90, 70], [180, 60], [270, 50]], "dynamics.input_acceleration": 5.0},
     "dynamics.input_acceleration: dynamics.speed_profile gives the input's speed and acceleration at every pose: "
     "give dynamics.speed_profile or dynamics.input_acceleration, not both"),
    ({"dynamics.speed_profile": "motor", "dynamics.motor.torque": 0.0003, "dynamics.motor.flywheel": False,
      "dynamics.motor.friction": 0.0002}, 'dynamics.speed_profile: "motor" needs the steady speed of the '
                                          "[dynamics.motor] run, which stalls at"),
    ({"dynamics.speed_profile": "motor", "dynamics.motor.stall_torque": 0.006, "dynamics.motor.no_load_speed": 90,
      "dynamics.motor.time": 0.5}, 'dynamics.speed_profile: "motor" needs the steady speed of the [dynamics.motor] '
                                   "run, which is not steady within dynamics.motor.time = 0.5 s"),
])
def test_bad_profiles_are_refused_in_one_line(tmp_path, change, message):
    assert_refused(JANSEN, change, message, tmp_path, main, "analyze")


def test_a_slides_rows_short_of_its_travel_are_refused(tmp_path):
    assert_refused(PUMP, {"dynamics.speed_profile": [[-30, 50], [-10, 50], [10, 50], [40, 50]]},
                   "dynamics.speed_profile: the rows' positions must cover the travel analysed, -39.2 to 39.2 mm "
                   "(they cover -30 to 40 mm)", tmp_path, main, "analyze")


def test_a_slides_speed_with_a_profile_is_refused(tmp_path):
    assert_refused(PUMP, {"dynamics.speed_profile": [[-40, 50], [-10, 50], [10, 50], [40, 50]], "dynamics.speed": 50},
                   "dynamics.speed: dynamics.speed_profile gives the input's speed and acceleration at every pose: "
                   "give dynamics.speed_profile or dynamics.speed, not both", tmp_path, main, "analyze")
