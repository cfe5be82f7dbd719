"""The spring rate that keeps a follower on its cam ("rate needed") and the lift-off speed, against references
computed here from the motion laws' closed forms: the least rate is max over s > 0 of (margin - F_rest) / s
(F_rest the force without the spring's rate: preload + inertia + loads), found on a dense grid and refined with a
bounded scalar minimise; the lift-off speed is min over s'' < 0 of sqrt(1000 F_still / (m -s'')).

Also the cases the search used to lose to its +-1e30 sentinels: a machine cam with a massive linkage behind it
(its reflected inertia as a load table), a follower only a preload can hold, one that needs no rate at all.
"""
from __future__ import annotations

import copy
import math
import tomllib

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from camgen.api import design_cam
from camgen.speed import HeldContact
from tests.conftest import ROOT, template

H, BETA = 20.0, math.radians(120.0)        # the test template's rise and return: 20 mm over 120 degrees each
RISE_END, TOP_END = BETA, BETA + math.radians(60.0)


def _motion(theta: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """s (mm) and s'' (mm/rad^2) of the test template (tests.conftest.RDRD) in closed form: a cycloidal rise over
    0..120 degrees, a dwell at the top, a harmonic return over 180..300 degrees, a dwell at rest."""
    t = np.atleast_1d(np.asarray(theta, dtype=float))
    s, a = np.zeros_like(t), np.zeros_like(t)
    rise = t < RISE_END
    x = t[rise] / BETA
    s[rise] = H * (x - np.sin(2 * math.pi * x) / (2 * math.pi))
    a[rise] = 2 * math.pi * H / BETA ** 2 * np.sin(2 * math.pi * x)
    top = (t >= RISE_END) & (t < TOP_END)
    s[top] = H
    back = (t >= TOP_END) & (t < TOP_END + BETA)
    x = (t[back] - TOP_END) / BETA
    s[back] = H / 2 * (1 + np.cos(math.pi * x))
    a[back] = -H * math.pi ** 2 / (2 * BETA ** 2) * np.cos(math.pi * x)
    return s, a


def _refined_max(func, grid: np.ndarray) -> tuple[float, float]:
    """The largest value of ``func`` (of an angle in radians) and where (degrees): the best point of ``grid``,
    refined by a bounded minimise over the grid steps either side."""
    values = func(grid)
    i = int(np.nanargmax(values))
    step = grid[1] - grid[0]
    found = minimize_scalar(lambda t: -func(np.array([t]))[0], bounds=(grid[i] - step, grid[i] + step),
                            method="bounded", options={"xatol": 1e-12})
    best = max((float(-found.fun), float(found.x)), (float(values[i]), float(grid[i])))
    return best[0], math.degrees(best[1])


def _contact(rpm: float, mass: float, rate: float, preload: float, margin: float = 0.0) -> HeldContact:
    contact = design_cam(template({"cam.rpm": rpm, "follower.mass": mass, "follower.spring_rate": rate,
                                   "follower.preload": preload, "follower.contact_margin": margin})).speed.contact
    assert isinstance(contact, HeldContact)
    return contact


def _demand(rpm: float, mass: float, preload: float, margin: float):
    """(margin - F_rest) / s (N/mm) of an angle array, NaN at rest (s = 0)."""
    omega = rpm * math.pi / 30

    def ratio(theta: np.ndarray) -> np.ndarray:
        s, a = _motion(theta)
        short = margin - preload - mass * omega ** 2 * a / 1000.0
        out = np.full_like(s, np.nan)
        out[s > 0] = short[s > 0] / s[s > 0]
        return out

    return ratio


GRID = np.linspace(1e-9, 2 * math.pi, 360_001)[:-1]


@pytest.mark.parametrize("rpm, mass, preload, margin", [(300.0, 0.5, 2.0, 0.5), (400.0, 0.8, 3.0, 0.0),
                                                        (250.0, 1.5, 5.0, 1.0)])
def test_the_rate_needed_and_where_against_the_closed_form_laws(rpm, mass, preload, margin):
    """Where the inertia dominates, the report's rate and its angle are the closed form's maximum of
    (margin - F_rest) / s to 1e-9 (relative) and 1e-5 degrees; that rate holds the least force at the margin, and
    a spring a little stiffer holds (the rate needed is the whole rate, whatever the spring's own)."""
    contact = _contact(rpm, mass, 0.05, preload, margin)
    rate, at = _refined_max(_demand(rpm, mass, preload, margin), GRID)
    assert rate > 0.05 and contact.holds is False
    assert contact.rate_needed == pytest.approx(rate, rel=1e-9)
    assert contact.rate_needed_at_deg == pytest.approx(at, abs=1e-5)
    omega = rpm * math.pi / 30
    s, a = _motion(GRID)
    least = (preload + contact.rate_needed * s + mass * omega ** 2 * a / 1000.0).min()
    assert least == pytest.approx(margin, abs=1e-7)
    held = _contact(rpm, mass, contact.rate_needed * (1 + 1e-6), preload, margin)
    assert held.holds is True and held.rate_needed == pytest.approx(contact.rate_needed, rel=1e-12)


def test_the_liftoff_speed_against_the_closed_form_laws():
    """The speed at which the spring (2 N, 0.2 N/mm) lets a 0.5 kg follower go: min over s'' < 0 of
    sqrt(1000 (P + k s) / (m -s'')) (rad/s), to 1e-9; just below it the follower is held, just above it leaves."""
    contact = _contact(300.0, 0.5, 0.2, 2.0)

    def omega_squared_inverse(theta: np.ndarray) -> np.ndarray:
        s, a = _motion(theta)
        return np.where(a < 0, 0.5 * -a / (1000.0 * (2.0 + 0.2 * s)), 0.0)

    top, _ = _refined_max(omega_squared_inverse, GRID)
    liftoff = math.sqrt(1.0 / top) * 30 / math.pi
    assert contact.liftoff_rpm == pytest.approx(liftoff, rel=1e-9)
    assert _contact(liftoff * 0.999, 0.5, 0.2, 2.0).holds is True
    assert _contact(liftoff * 1.001, 0.5, 0.2, 2.0).holds is False


def test_only_the_preload_can_help_where_the_follower_rests_short():
    """A margin of 3 N over a preload of 2 N: at rest (s = 0, no inertia in the dwell) the force is 1 N short,
    and no spring rate adds anything there: the rate is None (null in the report), its angle too; the preload
    needed is the margin (the dwell asks for it, the inertia of this slow cam less)."""
    design = design_cam(template({"cam.rpm": 20.0, "follower.mass": 0.5, "follower.spring_rate": 0.2,
                                  "follower.preload": 2.0, "follower.contact_margin": 3.0}))
    contact = design.speed.contact
    assert isinstance(contact, HeldContact) and contact.holds is False
    assert contact.rate_needed is None and contact.rate_needed_at_deg is None
    assert contact.preload_needed == pytest.approx(3.0, abs=1e-12)
    report = design.speed.as_report()["contact"]
    assert report["rate_needed_n_mm"] is None and report["rate_needed_at_deg"] is None


def test_no_rate_is_needed_where_the_preload_holds_everywhere():
    """A slow cam on a stiff preload: (margin - F_rest) / s < 0 everywhere it moves, so no rate is needed (0)."""
    contact = _contact(30.0, 0.5, 0.0, 5.0, 1.0)
    worst, _ = _refined_max(_demand(30.0, 0.5, 5.0, 1.0), GRID)
    assert worst < 0
    assert contact.holds is True and contact.rate_needed == 0.0 and contact.rate_needed_at_deg is None


# ---- a machine cam with a massive linkage behind it (the reflected inertia as a load table) ---------------------

def _heavy_arm(rpm: float) -> dict:
    """The automaton's arm cam alone, its four-bar given masses (lying flat, no [parts]), a light spring."""
    with (ROOT / "templates" / "automaton.toml").open("rb") as stream:
        raw = tomllib.load(stream)
    raw["cams"] = raw["cams"][2:3]
    raw["machine"].update(rpm=rpm, frame="none")
    bars = raw["linkages"][0]["template"]
    bars.pop("parts")
    bars["dynamics"] = {"incline": 0.0, "links": copy.deepcopy({
        "crank": {"mass": 0.05, "centre": [12.0, 3.0], "inertia": 8.0},
        "coupler": {"mass": 0.4, "centre": [40.0, 12.0], "inertia": 350.0},
        "rocker": {"mass": 0.25, "centre": [28.0, -4.0], "inertia": 90.0}})}
    raw["cams"][0]["template"]["follower"].update(preload=2.0, spring_rate=0.1)
    return raw


def test_the_machine_cam_at_240_rpm_reports_the_rate_its_rows_ask_for():
    """At 240 rpm the linkage's reflected inertia pulls the arm's roller off: the rate needed is the largest of
    (margin - F_rest) / s computed here from the cam's program and the load table's rows (interpolated
    periodically), 0.136 N/mm near 167 degrees (it was reported as 0 when sentinels broke the search), and the
    lift-off speed the least of sqrt(1000 F_still / (m -s'')) over the rows."""
    from camgen import api

    design = api.design(api.validate(_heavy_arm(240.0)))
    cam = design.cam("arm").design
    follower = cam.spec.follower
    contact = cam.speed.contact
    assert isinstance(contact, HeldContact) and contact.holds is False
    scale = follower.arm_length * math.pi / 180.0
    omega = 240.0 * math.pi / 30
    angles, loads = (np.array(c) for c in zip(*follower.load_table_rows, strict=True))

    def rows(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        m = cam.cam.program.evaluate(theta)
        still = follower.preload + follower.spring_rate * scale * m[0] \
            + np.interp(np.degrees(theta), angles, loads, period=360.0)
        return m[0] * scale, m[2] * scale, still

    def ratio(theta: np.ndarray) -> np.ndarray:
        s, a, still = rows(theta)
        short = -(still - follower.spring_rate * s + follower.mass * omega ** 2 * a / 1000.0)
        return np.where(s > 0, short / np.where(s > 0, s, 1.0), np.nan)

    def inverse(theta: np.ndarray) -> np.ndarray:
        _, a, still = rows(theta)
        return np.where(a < 0, follower.mass * -a / (1000.0 * still), 0.0)

    rate, at = _refined_max(ratio, GRID)
    assert rate == pytest.approx(0.13633, abs=5e-5) and at == pytest.approx(166.6, abs=0.1)
    assert contact.rate_needed == pytest.approx(rate, rel=1e-6)
    assert contact.rate_needed_at_deg == pytest.approx(at, abs=1e-3)
    top, _ = _refined_max(inverse, GRID)
    assert contact.liftoff_rpm == pytest.approx(math.sqrt(1.0 / top) * 30 / math.pi, rel=1e-6)
    assert contact.liftoff_rpm < 240.0
