"""Mechanisms on a Geneva-indexed shaft (issue 35, :mod:`camgen.kinds.machine.shaft_motion`): one motion Q(phi) for
every shaft, and a gear pair, a shaft-driven four-bar and a cam coupled to a four-bar on a shaft that indexes.

Independent checks: Q, Q', Q'' against the Geneva's closed form written here (the wheel's slot through the pin) and
central differences of it; the shaft-driven four-bar's rocker against a circle intersection written here at crank
angle Q(phi), standing exactly still while the wheel is locked; the gear on the wheel's shaft turning by its ratio
times Q; the camshaft torque of the four-bar's [dynamics] against virtual work (dE/dt / omega, E from positions
alone); the cam's real-rate acceleration against s''(Q) Q'^2 + s'(Q) Q''."""
from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest

from tests.camgen.kinds.machine.test_general_inertia import _link_poses
from tests.camgen.kinds.machine.test_geneva_mount import MACHINE as GENEVA_MACHINE
from tests.conftest import ROOT
from tests.support.kinetic_energy import kinetic_energy

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-indexed-shaft")

#: the main shaft turns a driver 4 times a turn the other way (60:15), whose 4-slot Geneva turns the wheel's shaft
#: once a turn (+1, the other way from its driver) in 4 indexes; the wheel's shaft carries a cam (its follower
#: driving a four-bar), a shaft-driven four-bar (ground 80, crank 20, coupler and rocker sqrt(30^2 + 60^2): a
#: crank-rocker) and a 30-tooth gear turning the idle shaft's 50 (its shaft turns -30/50 of the wheel's)
FOUR_BAR = {"type": "four-bar", "ground": 80.0, "crank": 30.0, "coupler": 90.0, "rocker": 60.0}
ROCKER = {"linkage": {"type": "linkage", "ground": ["O", "D"], "input": {"link": "crank", "pivot": "O"},
                      "tracers": ["B"], "joints": {"O": [0.0, 0.0], "A": [20.0, 0.0], "B": [50.0, 60.0],
                                                   "D": [80.0, 0.0]},
                      "links": {"crank": ["O", "A"], "coupler": ["A", "B"], "rocker": ["D", "B"]}},
          "dynamics": {"incline": 0.0, "links": {
              "crank": {"mass": 0.05, "centre": [10.0, 2.0], "inertia": 6.0},
              "coupler": {"mass": 0.3, "centre": [30.0, 8.0], "inertia": 250.0},
              "rocker": {"mass": 0.2, "centre": [30.0, -3.0], "inertia": 120.0}}}}


def _machine() -> dict:
    """The Geneva mount's machine (``test_geneva_mount.MACHINE``) at 60 rpm with no frame, its idle shaft moved to
    80 mm from the wheel's at 150 degrees, a 30:50 gear pair from the wheel's shaft to it, the cam's follower coupled
    to a four-bar (rest 60 degrees, -0.2 N*m on its rocker) and the shaft-driven four-bar (phase 30 degrees)."""
    raw = tomllib.loads(GENEVA_MACHINE)
    raw["name"] = "indexed"
    raw["machine"].update(rpm=60.0, frame="none")
    next(s for s in raw["shafts"] if s["name"] == "idle")["at"] = [75.0 - 40.0 * math.sqrt(3.0), 120.0]
    raw["gears"].append({"driver": "wheel", "driven": "idle", "driver_teeth": 30, "driven_teeth": 50, "module": 2.0})
    raw["linkages"] = [{"name": "bars", "template": {"linkage": dict(FOUR_BAR)}},
                       {"name": "rocker", "shaft": "wheel", "phase": 30.0, "template": copy.deepcopy(ROCKER)}]
    raw["couplings"] = [{"cam": "lift", "linkage": "bars", "link": "crank", "rest": 60.0, "output_torque": -0.2}]
    return raw
SLOTS, DRIVER_TURNS, START, PHASE = 4, 4.0, math.radians(150.0), math.radians(20.0)
#: the wheel's shaft's mean turns (the other way from its driver) and the idle shaft's ratio to it
WHEEL_TURNS, IDLE_RATIO = 1.0, -30.0 / 50.0
CRANK, RIB = 20.0, math.hypot(30.0, 60.0)
PHI = np.arange(1440) * (2 * math.pi / 1440)


@pytest.fixture(scope="module")
def indexed():
    from camgen import api

    return api.design(api.validate(_machine()))


def _wheel(phi: np.ndarray) -> np.ndarray:
    """The wheel's turn W (rad, its own sense, 0 at the start) in closed form: the driver's pin at alpha = 4 phi +
    start, a in (-pi, pi] within its turn; while |a| < pi/2 - pi/n the slot through the pin stands at
    beta = atan2(l sin a, 1 - l cos a), l = sin(pi/n), else at -+pi/n (before entry, after exit); each driver turn
    adds an index of 2 pi / n."""
    alpha = DRIVER_TURNS * np.asarray(phi, dtype=float) + START
    k = np.ceil((alpha - math.pi) / (2 * math.pi))
    a = alpha - 2 * math.pi * k
    lam = math.sin(math.pi / SLOTS)
    inside = np.abs(a) < math.pi / 2 - math.pi / SLOTS
    beta = np.where(inside, np.arctan2(lam * np.sin(a), 1 - lam * np.cos(a)),
                    np.where(a < 0, -math.pi / SLOTS, math.pi / SLOTS))
    turned = k * 2 * math.pi / SLOTS + beta + math.pi / SLOTS
    a0 = START - 2 * math.pi * math.ceil((START - math.pi) / (2 * math.pi))
    return turned - (math.pi / SLOTS + (math.pi / SLOTS if a0 > 0 else -math.pi / SLOTS))


def _near_edges(phi: np.ndarray, h: float) -> np.ndarray:
    """Where a main shaft angle lies within ``h`` (of the driver's turn, times its speed) of the pin's entry or exit:
    there Q'' jumps."""
    alpha = DRIVER_TURNS * phi + START
    a = np.angle(np.exp(1j * alpha))
    edge = math.pi / 2 - math.pi / SLOTS
    return np.abs(np.abs(a) - edge) < DRIVER_TURNS * 3 * h


@pytest.mark.parametrize("shaft, ratio", [("wheel", WHEEL_TURNS), ("idle", WHEEL_TURNS * IDLE_RATIO)])
def test_q_and_its_rates_are_the_genevas_closed_form_and_its_differences(indexed, shaft, ratio):
    """Q = ratio W (the wheel's shaft turns +1 a turn, the idle shaft -30/50 of it), to 1e-12 rad; Q' against the
    central difference of the closed form (h = 1e-6) and Q'' against the central difference of Q' (both to 1e-7 of
    their peaks) and the closed form's second difference (h = 3e-5; to 1e-6: its truncation and rounding), the
    samples within 3 h of the pin's entry and exit (where Q'' jumps) left out."""
    from camgen.kinds.machine.shaft_motion import shaft_motions

    motion = shaft_motions(indexed.spec, indexed.indexed)[shaft]
    assert not motion.uniform and motion.turns == pytest.approx(ratio, abs=1e-15)
    q = motion.angles(PHI)
    assert np.abs(q[0] - ratio * _wheel(PHI)).max() < 1e-12
    assert q[0][-1] - q[0][0] == pytest.approx(ratio * 2 * math.pi * (1 - 1 / 1440), abs=1e-2)
    h1, h2 = 1e-6, 3e-5
    first = ratio * (_wheel(PHI + h1) - _wheel(PHI - h1)) / (2 * h1)
    second = ratio * (_wheel(PHI + h2) - 2 * _wheel(PHI) + _wheel(PHI - h2)) / h2 ** 2
    of_rate = (motion.angles(PHI + h1)[1] - motion.angles(PHI - h1)[1]) / (2 * h1)
    keep = ~_near_edges(PHI, h2)
    assert keep.mean() > 0.95
    assert np.abs(q[1] - first)[keep].max() < 1e-7 * np.abs(q[1]).max()
    assert np.abs(q[2] - of_rate)[keep].max() < 1e-7 * np.abs(q[2]).max()
    assert np.abs(q[2] - second)[keep].max() < 1e-6 * np.abs(q[2]).max()    # its truncation and rounding
    locked = ~indexed.indexed[0].indexing(PHI) & ~_near_edges(PHI, 1e-12)     # at an edge Q'' is entry's
    assert (q[1][locked] == 0.0).all() and (q[2][locked] == 0.0).all()        # exactly still while locked
    assert np.abs(q[1]).max() > 2.0 * abs(ratio)                              # indexing faster than its mean


def test_a_uniform_shaft_is_its_turns_times_phi(indexed):
    from camgen.kinds.machine.shaft_motion import shaft_motions

    motion = shaft_motions(indexed.spec, indexed.indexed)["driver"]
    q = motion.angles(PHI)
    assert motion.uniform and motion.turns == -4.0
    assert (q[0] == -4.0 * PHI).all() and (q[1] == -4.0).all() and (q[2] == 0.0).all()


def _rocker_angle(theta2: np.ndarray) -> np.ndarray:
    """The rocker's angle at crank angles ``theta2`` (rad) by a circle intersection: B on the rib's circle about
    A = 20 (cos, sin) theta2 and about D = (80, 0), the branch above the chord A -> D (as drawn, B = (50, 60))."""
    a = CRANK * np.column_stack([np.cos(theta2), np.sin(theta2)])
    d = np.array([80.0, 0.0]) - a
    dist = np.hypot(d[:, 0], d[:, 1])
    along = dist / 2                                                           # equal sides: the chord's middle
    half = np.sqrt(RIB ** 2 - along ** 2)
    u = d / dist[:, None]
    b = a + along[:, None] * u + half[:, None] * np.column_stack([-u[:, 1], u[:, 0]])
    return np.arctan2(b[:, 1], b[:, 0] - 80.0)


def test_a_four_bar_on_the_indexed_shaft_follows_q_and_dwells(indexed):
    """Its rocker (D -> B) stands where the circle intersection puts it at crank angle Q(phi) + phase (the crank
    drawn along +X), to 1e-9 rad; its joints stand exactly still (rate 0) wherever the wheel is locked."""
    from camgen.kinds.machine.shaft_motion import shaft_motions

    m = next(x for x in indexed.cranked if x.name == "rocker")
    q = shaft_motions(indexed.spec, indexed.indexed)["wheel"].angles(indexed.phi)
    expected = _rocker_angle(q[0] + math.radians(30.0))
    b, d = m.points["B"], m.points["D"]
    got = np.arctan2(b[:, 1] - d[:, 1], b[:, 0] - d[:, 0])
    assert np.abs(np.angle(np.exp(1j * (got - expected)))).max() < 1e-9
    assert np.ptp(got) > 0.5
    locked = ~indexed.indexed[0].indexing(indexed.phi)
    assert locked.mean() > 0.7
    for joint in ("A", "B"):
        assert (m.rates[joint][locked] == 0.0).all()
        assert np.abs(m.rates[joint][~locked]).max() > 10.0
    # its rates are Q' times the rates per radian of the crank: central differences of the positions
    h = 1e-6
    ahead, behind = m.solve(indexed.phi + h).points["B"], m.solve(indexed.phi - h).points["B"]
    keep = ~_near_edges(indexed.phi, h)
    first = (ahead - behind) / (2 * h)
    assert np.abs(m.rates["B"] - first)[keep].max() < 1e-6 * np.abs(first).max()


def test_a_gear_on_the_indexed_shaft_turns_by_its_ratio_times_q(indexed):
    from camgen.kinds.machine.shaft_motion import shaft_motions

    gear = next(g for g in indexed.gears if g.shafts == ("wheel", "idle"))
    q = shaft_motions(indexed.spec, indexed.indexed)["wheel"].angles(PHI)[0]
    driver, driven = gear.angles(PHI)
    assert np.abs((driver - driver[0]) - q).max() < 1e-12
    assert np.abs((driven - driven[0]) - IDLE_RATIO * q).max() < 1e-12
    locked = ~indexed.indexed[0].indexing(PHI)
    both = locked[:-1] & locked[1:]                                  # two samples in a row while the wheel is locked
    assert both.sum() > 1000 and np.abs(np.diff(driven)[both]).max() < 1e-12
    assert np.ptp(driven) > 3.0


def test_the_camshaft_torque_of_the_indexed_four_bar_is_virtual_work(indexed):
    """T = dE/dt / omega (no gravity, no load): E = sum 1/2 m v^2 + 1/2 I w^2 from the links' positions alone at
    phi +- h (velocities by central differences), its rate by a central difference over +- h; to 1e-6 of the
    torque's peak, the samples near the pin's entry and exit (where Q'' and so the torque jump) left out; 0 exactly
    while the wheel is locked."""
    m = next(x for x in indexed.cranked if x.name == "rocker")
    links = {k: {"mass": v.mass, "centre": list(v.centre), "inertia": v.inertia}
             for k, v in m.design.spec.dynamics.links.items()}
    phi, omega, h = indexed.phi, indexed.omega, 1e-5

    def energy(at: np.ndarray) -> np.ndarray:
        return kinetic_energy(_link_poses(m, links, at + h), _link_poses(m, links, at - h), links, h, omega)

    expected = (energy(phi + h) - energy(phi - h)) / (2 * h)                 # dE/dt / omega = dE/dphi
    keep = ~_near_edges(phi, 3 * h)
    assert m.torque is not None
    assert np.abs(m.torque - expected)[keep].max() < 1e-6 * np.abs(m.torque).max()
    assert np.abs(m.torque).max() > 1e-3
    locked = ~indexed.indexed[0].indexing(phi)
    assert (m.torque[locked] == 0.0).all()


def test_a_cam_on_the_indexed_shaft_moves_its_four_bar_at_the_real_rates(indexed):
    """The follower's acceleration per radian^2 of the main shaft is s''(Q) Q'^2 + s'(Q) Q'' (the program at
    Q - phase, Q from the closed form), to 1e-9 of its peak; the coupled four-bar's crank is rest + s, its rates
    s' Q' and that acceleration (in radians)."""
    cam = indexed.cam("lift")
    program = cam.design.cam.program
    q = _wheel(indexed.phi)                                                   # the wheel's own sense
    h = 1e-6
    q1 = (_wheel(indexed.phi + h) - _wheel(indexed.phi - h)) / (2 * h)
    from camgen.kinds.machine.shaft_motion import shaft_motions

    exact = shaft_motions(indexed.spec, indexed.indexed)["wheel"].own(indexed.phi)
    assert np.abs(exact[1] - q1).max() < 1e-7 * np.abs(q1).max()
    s = program.evaluate(np.mod(q - PHASE, 2 * math.pi))[:3]
    expected = s[2] * exact[1] ** 2 + s[1] * exact[2]
    assert np.abs(cam.rates[2] - expected).max() < 1e-9 * np.abs(expected).max()
    assert np.abs(cam.rates[1] - s[1] * exact[1]).max() < 1e-9 * np.abs(cam.rates[1]).max()
    m = next(x for x in indexed.linkages if x.name == "bars")
    assert np.abs(m.chain.theta2 - np.radians(60.0 + s[0])).max() < 1e-12
    assert np.abs(m.chain.d2 - np.radians(expected)).max() < 1e-9 * np.abs(np.radians(expected)).max()
    locked = ~indexed.indexed[0].indexing(indexed.phi)
    assert (m.rocker_rate[locked] == 0.0).all() and np.abs(m.rocker_rate).max() > 0.1


def test_a_geneva_driven_by_a_shaft_geared_to_a_wheel_is_refused(tmp_path):
    """A Geneva drive's driver turns steadily: one on the idle shaft (geared to the wheel's, so indexing) is one line
    naming ``genevas[1].driver``, exit code 2, nothing written."""
    from tests.support.refusals import assert_refused

    more = GENEVA_MACHINE + f"""
[[gears]]
driver = "wheel"
driven = "idle"
driver_teeth = 40
driven_teeth = 40
module = 2.0

[[shafts]]
name = "second"
at = [155.0, 160.0]

[[genevas]]
name = "again"
driver = "idle"
wheel = "second"
template = "{ROOT / 'templates' / 'geneva4.toml'}"
"""
    template = tmp_path / "again.toml"
    template.write_text(more)
    assert_refused(template, {}, "genevas[1].driver: shaft idle indexes (geared to a Geneva drive's wheel)", tmp_path)


# ---- a cam on the indexing shaft at its real rates --------------------------------------------------------------


def _real_force(indexed, rows: np.ndarray) -> np.ndarray:
    """The oscillating roller's contact force (N) written here from its loading: preload 5 N + rate 0.5 N/mm times
    the roller's travel L psi + the load table (the four-bar's output torque reflected, linear and periodic over its
    rows) + the roller's 0.2 kg times its acceleration along its path, L (pi/180) s'' omega^2 / 1000 (m/s^2),
    L = 90 mm; ``rows`` the follower's (s, ds/dphi, d^2s/dphi^2) per radian of the main shaft, omega its speed."""
    cam = indexed.cam("lift")
    table = np.asarray(cam.design.spec.follower.load_table, dtype=float)
    theta = np.degrees(cam.theta)
    loads = np.interp(theta, np.concatenate([table[:, 0], [360.0]]), np.concatenate([table[:, 1], table[:1, 1]]))
    lever = 90.0 * math.pi / 180.0
    return 5.0 + 0.5 * lever * rows[0] + loads + 0.2 * lever * rows[2] * indexed.omega ** 2 / 1000.0


def test_the_cams_real_rate_figures_are_reported_against_its_mean_speed(indexed, tmp_path):
    """``cams.lift.indexed``: the peak acceleration omega^2 |s''(Q) Q'^2 + s'(Q) Q''| (1e-9 of it, and where) against
    the cam's own figure at its shaft's mean speed; the least contact force at the real rates as written here (1e-9 N)
    below 0 (the follower leaves while the wheel indexes) where the mean-speed check holds (its least force the same
    loading at the rates |n| s', n^2 s'', to 1e-6 N); the machine warns of it."""
    from camgen import api
    from camgen.kinds.machine.indexed_cam import speed_of

    cam = indexed.cam("lift")
    exact = cam.shaft_rates(indexed.phi)
    s = cam.design.cam.program.evaluate(cam.theta)[:3]
    acc = np.abs(s[2] * exact[1] ** 2 + s[1] * exact[2]) * indexed.omega ** 2
    api.write(indexed, tmp_path / "out", formats=["json"])
    report = json.loads((tmp_path / "out" / "indexed.json").read_text())
    real = report["cams"]["lift"]["indexed"]
    assert real["acceleration_max"] == pytest.approx(acc.max(), rel=1e-9)
    assert real["acceleration_max_at_deg"] == pytest.approx(math.degrees(indexed.phi[np.argmax(acc)]), abs=1e-9)
    speed = speed_of(cam.design)
    assert real["mean_speed_acceleration_max"] == pytest.approx(speed.acceleration_max, rel=1e-9)
    assert real["acceleration_max"] > 50 * real["mean_speed_acceleration_max"]      # Q' up to 9.7 while indexing
    force = _real_force(indexed, cam.rates)
    contact = real["contact"]
    assert contact["least_contact_force_n"] == pytest.approx(force.min(), abs=1e-9)
    assert contact["at_deg"] == pytest.approx(math.degrees(indexed.phi[np.argmin(force)]), abs=1e-9)
    assert contact["least_contact_force_n"] < 0 and contact["holds"] is False
    mean = _real_force(indexed, np.stack([s[0], s[1], s[2]]))                         # |n| = 1
    assert contact["mean_speed_least_contact_force_n"] == pytest.approx(mean.min(), abs=1e-6)
    assert contact["mean_speed_holds"] is True
    assert any(w.startswith("cams.lift: at its indexing shaft's real rates the follower leaves its cam")
               for w in indexed.warnings)


def test_a_cam_held_at_its_real_rates_is_reported_holding():
    """With 120 N of preload the follower stays on its cam at the real rates too: no warning, ``holds`` true, its
    least force 115 N more than at 5 N (the preload adds to the force everywhere)."""
    from camgen import api
    from camgen.kinds.machine.report import _cam_entry

    raw = _machine()
    with (ROOT / "templates" / "oscillating.toml").open("rb") as stream:
        cam = tomllib.load(stream)
    cam["follower"]["preload"] = 120.0
    raw["cams"][0]["template"] = cam
    held = api.design(api.validate(raw))
    real = _cam_entry(held, 0)["indexed"]["contact"]
    assert real["holds"] is True and real["least_contact_force_n"] > 0
    assert not any("real rates" in w for w in held.warnings)
