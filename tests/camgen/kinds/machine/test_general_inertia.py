"""Forces through a machine's chain for a follower-driven general linkage (issue 35 item 3): the accelerations of a
linkage an arm drives as its crank (the bundled pick-and-place's bell crank) or a stem as its slider, and the
linkage's inertia carried back onto the follower, the cam and the camshaft.

Independent checks: the accelerations (and velocities) equal central differences of the positions linkgen's
position solver places; the camshaft torque equals dE/dt / omega less the output torque's power over omega, E the
kinetic energy written here from the links' positions alone (each link's centre placed in its own frame, velocities
by central differences: sum 1/2 m v^2 + 1/2 I w^2); the reflected force times the follower's own speed is the
shaft's power; at zero masses the figures are the output torque's alone, exactly; the spring check's least contact
force equals the force written here row by row.
"""
from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from tests.conftest import ROOT
from tests.support.kinetic_energy import kinetic_energy
from tests.support.lost_contact import assert_contact_lost

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-general-inertia")

PICK = ROOT / "templates" / "pick-and-place.toml"

#: each link's mass (kg), centre (mm, its own frame: origin at its first joint, +x to its second; a slider's block
#: along its guide) and inertia about its centre (kg*mm^2)
BELL_LINKS = {"bell": {"mass": 0.06, "centre": [25.0, 4.0], "inertia": 30.0},
              "rod": {"mass": 0.12, "centre": [50.0, -3.0], "inertia": 140.0},
              "carriage": {"mass": 0.5, "centre": [6.0, 2.0], "inertia": 200.0}}
LIFTER_LINKS = {"crank": {"mass": 0.1, "centre": [15.0, 2.0], "inertia": 15.0},
                "rod": {"mass": 0.3, "centre": [35.0, -2.0], "inertia": 180.0},
                "stem": {"mass": 0.4, "centre": [0.0, 3.0], "inertia": 20.0}}
ZERO = {"mass": 0.0, "centre": [0.0, 0.0], "inertia": 0.0}


def _bell(links: dict | None = BELL_LINKS, rpm: float = 120.0) -> dict:
    """The bundled pick-and-place at ``rpm``, its carriage's rod held by 0.8 N*m, its bell crank linkage given
    ``links`` lying flat (none: no [dynamics]); its clash check on 36 angles (its own tests check 720)."""
    with PICK.open("rb") as stream:
        raw = tomllib.load(stream)
    raw["machine"].update(rpm=rpm, clash_samples=36)
    raw["couplings"][0]["output_torque"] = 0.8
    if links is not None:
        raw["linkages"][0]["template"]["dynamics"] = {"incline": 0.0, "links": copy.deepcopy(links)}
    return raw


def _lifter(links: dict | None = LIFTER_LINKS, rpm: float = 120.0, preload: float = 15.0) -> dict:
    """A disc cam (base 35 mm, roller 7 mm, phase 40 degrees) lifting the slider C of a slider-crank run backwards
    25 mm: C drawn at the origin sliding along +Y, the crank O-A about O = (45, 50), the rod A-C; 0.2 N*m on the
    crank; its links given ``links`` lying flat (none: no [dynamics])."""
    linkage: dict = {"linkage": {"type": "linkage", "ground": ["O"], "input": {"slider": "stem"}, "tracers": ["A"],
                                 "joints": {"C": [0.0, 0.0], "O": [45.0, 50.0], "A": [20.0, 68.0]},
                                 "links": {"crank": ["O", "A"], "rod": ["A", "C"]},
                                 "sliders": {"stem": {"point": "C", "guide": "ground", "angle": 90.0}}}}
    if links is not None:
        linkage["dynamics"] = {"incline": 0.0, "links": copy.deepcopy(links)}
    motion = [{"type": "rise", "law": "cycloidal", "lift": 25.0, "angle": 100.0}, {"type": "dwell", "angle": 80.0},
              {"type": "return", "law": "cycloidal", "lift": 25.0, "angle": 110.0}, {"type": "dwell", "angle": 70.0}]
    cam = {"cam": {"base_radius": 35.0, "thickness": 6.0, "bore": 8.0},
           "follower": {"type": "translating-roller", "roller_radius": 7.0, "mass": 0.15, "spring_rate": 0.8,
                        "preload": preload}, "motion": motion}
    return {"name": "lifter", "machine": {"main": "camshaft", "rpm": rpm, "clash_samples": 36},
            "shafts": [{"name": "camshaft", "at": [0.0, 0.0]}], "output": {"formats": ["json"]},
            "cams": [{"name": "lift", "shaft": "camshaft", "phase": 40.0, "template": cam}],
            "linkages": [{"name": "rocker", "template": linkage}],
            "couplings": [{"cam": "lift", "linkage": "rocker", "link": "stem", "rest": 0.0, "output": "crank",
                           "output_torque": 0.2}]}


def _design(raw: dict):
    from camgen import api

    return api.design(api.validate(raw))


@pytest.fixture(scope="module")
def bell():
    return _design(_bell())


@pytest.fixture(scope="module")
def lifter():
    return _design(_lifter())


@pytest.fixture(params=["bell", "lifter"])
def driven(request, bell, lifter):
    return {"bell": bell, "lifter": lifter}[request.param]


# ---- the accelerations --------------------------------------------------------------------------------------------


def _breaks(design) -> np.ndarray:
    """The main shaft angles (radians) where the cam's program changes segment: there its jerk jumps, and a
    second central difference over +-h is off by h times the jump over 6."""
    return np.mod(_program(design).starts + math.radians(design.cams[0].phase_deg), 2 * math.pi)


def _program(design):
    cam = design.cams[0].design
    return (cam.cam if hasattr(cam, "cam") else cam.profile.cam).program


def test_the_accelerations_are_central_differences_of_the_positions(driven):
    """d P / d phi and d^2 P / d phi^2 of every joint and the output link's angle equal the first and second central
    differences (h = 3e-4 rad) of the positions linkgen's solver places at phi +- h, to 1e-6 of their peaks; the
    samples within 2 h of a segment's start (where the program's jerk jumps) are left out."""
    m, phi, h = driven.slid[0], driven.phi, 3e-4
    gap = np.abs(np.angle(np.exp(1j * (phi[:, None] - _breaks(driven)[None, :])))).min(axis=1)
    keep = gap > 2 * h
    assert keep.sum() > 0.95 * len(phi)
    ahead, here, behind = m.solve(phi + h), m.solve(phi), m.solve(phi - h)
    moving = [p for p in m.points if np.ptp(m.points[p], axis=0).max() > 1.0]
    assert moving
    for p in moving:
        first = (ahead.points[p] - behind.points[p]) / (2 * h)
        second = (ahead.points[p] - 2 * here.points[p] + behind.points[p]) / h ** 2
        assert np.abs(m.rates[p] - first)[keep].max() < 1e-6 * np.abs(first).max(), p
        assert np.abs(m.accelerations[p] - second)[keep].max() < 1e-6 * np.abs(second).max(), p
    body = m.coupling.output
    turn = [np.unwrap(s.angle(body)) for s in (ahead, here, behind)]
    second = (turn[0] - 2 * turn[1] + turn[2]) / h ** 2
    assert np.abs(second).max() > 1e-3
    assert np.abs(m.output_acc - second)[keep].max() < 1e-6 * np.abs(second).max()


# ---- the inertia on the camshaft: energy -----------------------------------------------------------------------


def _link_poses(m, links: dict, phi: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each link's centre of mass (n, 2) mm and angle (n,) rad at main shaft angles ``phi``: placed from its joints
    (linkgen's position solver), its centre in its own frame (a slider's block: along its guide, not turning)."""
    table = m.design.spec.linkage
    at = m.solve(phi).points
    out = {}
    for name in links:
        if name in table.links:
            first, second = table.links[name][:2]
            axis = np.asarray(at[second]) - np.asarray(at[first])
            angle = np.arctan2(axis[:, 1], axis[:, 0])
        else:
            first = table.sliders[name].point
            angle = np.full(len(phi), math.radians(table.sliders[name].angle))
        cx, cy = links[name]["centre"]
        centre = np.asarray(at[first]) + np.column_stack((cx * np.cos(angle) - cy * np.sin(angle),
                                                          cx * np.sin(angle) + cy * np.cos(angle)))
        out[name] = (centre, angle)
    return out


def _kinetic_energy(design, links: dict, phi: np.ndarray, h: float = 1e-4) -> np.ndarray:
    """sum 1/2 m v^2 + 1/2 I w^2 (J) at main shaft angles ``phi``, each velocity by central differences of the
    positions over +-h radians of the shaft at its speed."""
    m = design.slid[0]
    return kinetic_energy(_link_poses(m, links, phi + h), _link_poses(m, links, phi - h), links, h, design.omega)


@pytest.mark.parametrize("which", ["bell", "lifter"])
def test_the_camshaft_torque_is_the_rate_of_kinetic_energy_less_the_load_power(which, bell, lifter):
    """T_shaft = dE/dt / omega - T omega_out / omega at every shaft angle: E from the positions alone, T the output
    torque on its link turning at omega_out; to 1e-6 of the torque's peak. The inertia's share is not small."""
    design, links = {"bell": (bell, BELL_LINKS), "lifter": (lifter, LIFTER_LINKS)}[which]
    m, phi, omega, h = design.slid[0], design.phi, design.omega, 1e-4
    d_energy = (_kinetic_energy(design, links, phi + h) - _kinetic_energy(design, links, phi - h)) / (2 * h) * omega
    turn = [np.unwrap(m.solve(at).angle(m.coupling.output)) for at in (phi + h, phi - h)]
    omega_out = (turn[0] - turn[1]) / (2 * h) * omega
    power = m.coupling.output_torque * omega_out
    expected = (d_energy - power) / omega
    assert np.abs(d_energy).max() > 0.5 * np.abs(power).max()
    assert np.abs(m.torque - expected).max() < 1e-6 * np.abs(expected).max()
    assert np.abs(design.shaft_torque - expected).max() < 1e-6 * np.abs(expected).max()
    share = m.effort * (m.scale * m.lift[1]) * (1.0 if m.analysis.crank else 1e-3)
    assert abs(share.mean()) < 1e-9 * np.abs(share).max()                  # the kinetic energy returns over a turn


def test_upright_the_torque_also_lifts_the_links_weight():
    """With the slider-crank upright (gravity 9.80665 m/s^2 down the drawing's -y, the machine's too: the drawing is
    moved, not turned), T_shaft = d(E + V)/dt / omega - T omega_out / omega, V = sum m g y_G from the positions."""
    raw = _lifter()
    raw["linkages"][0]["template"]["dynamics"]["incline"] = 90.0
    design = _design(raw)
    m, phi, omega, h = design.slid[0], design.phi, design.omega, 1e-4

    def potential(at: np.ndarray) -> np.ndarray:
        return sum(LIFTER_LINKS[k]["mass"] * 9.80665 * centre[:, 1] / 1000.0
                   for k, (centre, _) in _link_poses(m, LIFTER_LINKS, at).items())

    d_energy = (_kinetic_energy(design, LIFTER_LINKS, phi + h) + potential(phi + h)
                - _kinetic_energy(design, LIFTER_LINKS, phi - h) - potential(phi - h)) / (2 * h) * omega
    turn = [np.unwrap(m.solve(at).angle(m.coupling.output)) for at in (phi + h, phi - h)]
    expected = (d_energy - m.coupling.output_torque * (turn[0] - turn[1]) / (2 * h) * omega) / omega
    flat = _design(_lifter())
    assert np.abs(m.torque - flat.slid[0].torque).max() > 0.05 * np.abs(expected).max()      # the weight counts
    assert np.abs(m.torque - expected).max() < 1e-6 * np.abs(expected).max()


def test_the_reflected_force_times_the_followers_speed_is_the_shaft_torque(driven):
    """Virtual work through the follower: its force along its path (N) times its path's speed (m per radian of the
    shaft: the stem's lift rate, or the roller's arc, arm length times the swing's rate) is the shaft torque."""
    m = driven.slid[0]
    cam = driven.cam(m.cam)
    if cam.unit == "deg":
        speed = np.radians(cam.rate) * cam.design.spec.follower.arm_length / 1000.0
    else:
        speed = cam.rate / 1000.0
    assert np.abs(m.force * speed - m.torque).max() < 1e-12 * np.abs(m.torque).max()


def test_the_cams_load_table_is_the_reflected_force_with_the_inertia(lifter):
    """The cam is designed again with the whole reflected force: its rows at whole degrees of its program are the
    force at the shaft's sample phase + that degree (720 samples, half a degree apart)."""
    rows = lifter.cam("lift").design.spec.follower.load_table_rows
    force = lifter.slid[0].force
    for degree in range(0, 360, 7):
        assert rows[degree][1] == pytest.approx(force[round(((degree + 40.0) % 360) * 2)], abs=1e-8)
    plain = _design(_lifter(links=None))
    assert np.abs(force - plain.slid[0].force).max() > 1.0                  # N: the masses change it


@pytest.mark.parametrize("make", [_bell, _lifter])
def test_at_zero_masses_the_figures_are_the_output_torques_exactly(make):
    from camgen.kinds.machine import kinematics

    zero = {name: dict(ZERO) for name in (BELL_LINKS if make is _bell else LIFTER_LINKS)}
    massless, plain = _design(make(links=zero)), _design(make(links=None))
    a, b = massless.slid[0], plain.slid[0]
    assert b.effort is None and a.effort is not None and np.all(a.effort == 0.0)
    out = plain.spec.couplings[0].output_torque
    assert np.array_equal(a.force, b.force) and np.array_equal(a.torque, b.torque)
    assert np.array_equal(massless.shaft_torque, plain.shaft_torque)
    assert massless.cam(a.cam).design.spec.follower.load_table_rows == \
        plain.cam(b.cam).design.spec.follower.load_table_rows
    sol = b.analysis.linkage.solve(b.inputs[None, :])
    k = b.scale * np.asarray(sol.omegas[b.coupling.output])
    assert np.array_equal(b.force, kinematics.reflected_force(out, k, b.lever))        # the present figures
    assert np.array_equal(b.torque, kinematics.shaft_torque(out, k, b.lift[1]))


# ---- the follower's spring with the linkage attached ---------------------------------------------------------------


def _contact_rows(design) -> np.ndarray:
    """The contact force (N) at each whole degree of the stem's program, computed here: preload + rate x lift + the
    reflected load's row + the follower's own mass x its acceleration (no weight: its orientation is not given)."""
    cam = design.cam("lift").design
    follower = cam.spec.follower
    s = cam.cam.program.evaluate(np.radians(np.arange(360)))
    omega = cam.spec.cam.rpm * math.pi / 30.0
    rows = np.array([f for _, f in follower.load_table_rows])
    return follower.preload + follower.spring_rate * s[0] + rows + follower.mass * omega ** 2 * s[2] / 1000.0


def test_the_linkages_inertia_pulls_the_stem_off_and_the_check_says_where():
    """At 240 rpm with 2 N of preload the linkage's inertia lifts the stem off its cam (without the masses the
    spring holds it): the cam's own least contact force equals the one computed row by row here, a warning names
    the cam and the angle, the report's ``slid.rocker.spring`` gives where and the preload that holds it, and with
    that preload (and 0.5 N more) the least force is 0.5 N and no warning is left."""
    from camgen.kinds.machine.report import machine_report

    design = _design(_lifter(rpm=240.0, preload=2.0))
    spring = machine_report(design)["slid"]["rocker"]["spring"]
    contact = assert_contact_lost(design, "lift", _contact_rows(design), spring, 40.0)
    assert _design(_lifter(links=None, rpm=240.0, preload=2.0)).cam("lift").design.speed.contact.holds is True
    held = _design(_lifter(rpm=240.0, preload=contact.preload_needed + 0.5))
    again = held.cam("lift").design.speed.contact
    assert again.holds is True and again.force_min == pytest.approx(0.5, abs=0.05)
    assert _contact_rows(held).min() == pytest.approx(0.5, abs=0.05)
    assert not any(w.startswith("cams.lift: the spring") for w in held.warnings)


# ---- the report and the bundled pick-and-place with [dynamics] -------------------------------------------------


def test_the_report_gives_the_accelerations_and_the_inertia(bell):
    from camgen.kinds.machine.report import machine_report

    entry = machine_report(bell)["slid"]["carriage"]
    m, omega = bell.slid[0], bell.omega
    assert entry["inertia_effort_n_m"] == pytest.approx([m.effort.min(), m.effort.max()], abs=1e-6)
    assert entry["output_alpha_max_rad_s2"] == pytest.approx(np.abs(m.output_acc).max() * omega ** 2, abs=1e-6)
    assert entry["tracers"]["C"]["acceleration_max_mm_s2"] == pytest.approx(
        np.hypot(*m.accelerations["C"].T).max() * omega ** 2, abs=1e-6)
    assert entry["spring"]["positive_drive"] is True                        # a grooved cam: no spring
    assert "[dynamics]" in machine_report(bell)["shaft_torque_n_m"]["note"]


def test_the_pick_and_place_with_dynamics_builds(tmp_path):
    from camgen.cli import main as camgen
    from camgen.core.toml_text import dumps

    raw = _bell()
    raw["output"]["formats"] = ["json", "dxf"]
    path = tmp_path / "pick.toml"
    path.write_text(dumps(raw))
    result = CliRunner().invoke(camgen, ["build", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "out" / "pick-and-place.json").read_text())
    assert report["warnings"] == []
    entry = report["slid"]["carriage"]
    assert entry["inertia_effort_n_m"][0] < 0 < entry["inertia_effort_n_m"][1]
    assert sorted((tmp_path / "out").glob("pick-and-place-carriage*.dxf"))
