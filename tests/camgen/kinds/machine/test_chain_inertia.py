"""Forces through a machine's chain (issue 35 item 3): a coupled four-bar's own masses carried back through the
follower onto the cam and the camshaft.

Two independent methods: the camshaft torque linkgen's inverse dynamics gives equals d(kinetic energy)/dt / omega
plus the output torque's power over omega, the kinetic energy computed here from the links' positions alone (a
circle intersection written here, the links' centres placed in their own frames, velocities by central
differences: sum 1/2 m v^2 + 1/2 I w^2). At zero masses the figures are those of the output torque alone, exactly.
The follower's contact force with the linkage attached is cross-checked with the spring, the follower's own inertia
and the reflected load row by row, and the preload the check asks for holds the follower at the margin.
"""
from __future__ import annotations

import copy
import math
import re
import tomllib

import numpy as np
import pytest

from camgen.kinds.machine import kinematics
from tests.conftest import ROOT

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-chain-inertia")

AUTOMATON = ROOT / "templates" / "automaton.toml"

#: each link's mass (kg), centre (mm, in its own frame: origin at its first joint, +x to its second) and inertia
#: about its centre (kg*mm^2)
LINKS = {"crank": {"mass": 0.05, "centre": [12.0, 3.0], "inertia": 8.0},
         "coupler": {"mass": 0.4, "centre": [40.0, 12.0], "inertia": 350.0},
         "rocker": {"mass": 0.25, "centre": [28.0, -4.0], "inertia": 90.0}}
#: each link's two frame joints, as [dynamics.links] places its centre
FRAMES = {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("O4", "B")}


def _raw(links: dict | None = LINKS, rpm: float = 150.0) -> dict:
    """The automaton's arm alone (its cam driving the four-bar), at ``rpm``; the four-bar's links given ``links``
    (none: no [dynamics]), lying flat (no gravity) and with no [parts] (its masses are only those given)."""
    with AUTOMATON.open("rb") as stream:
        raw = tomllib.load(stream)
    raw["cams"] = [raw["cams"][2]]
    raw["machine"].update(rpm=rpm, frame="none")
    template = raw["linkages"][0]["template"]
    del template["parts"]
    if links is not None:
        template["dynamics"] = {"incline": 0.0, "links": copy.deepcopy(links)}
    return raw


def _design(raw: dict):
    from camgen import api

    return api.design(api.validate(raw))


@pytest.fixture(scope="module")
def heavy():
    return _design(_raw())


# ---- the independent method: kinetic energy from positions -----------------------------------------------------


def _joints(design, phi: np.ndarray) -> dict[str, np.ndarray]:
    """O2, A, B, O4 (n, 2) mm at main shaft angles ``phi``: the cam's program at phi - phase, the crank at rest +
    swing, B where the circle about A (radius coupler) meets the circle about O4 (radius rocker), on the left of
    A -> O4 (the open assembly)."""
    mount, coupling = design.spec.cams[0], design.spec.couplings[0]
    table = design.linkages[0].design.spec.linkage
    program = design.cam(mount.name).design.cam.program
    swing = program.evaluate(np.mod(phi - math.radians(mount.phase), 2 * math.pi))[0]
    theta2 = np.radians(coupling.rest + swing)
    a = table.crank * np.column_stack((np.cos(theta2), np.sin(theta2)))
    o4 = np.array([table.ground, 0.0])
    d_vec = o4 - a
    d = np.hypot(*d_vec.T)
    along = (table.coupler ** 2 - table.rocker ** 2 + d ** 2) / (2 * d)
    h = np.sqrt(table.coupler ** 2 - along ** 2)
    u = d_vec / d[:, None]
    b = a + along[:, None] * u + h[:, None] * np.column_stack((-u[:, 1], u[:, 0]))
    n = len(phi)
    return {"O2": np.zeros((n, 2)), "A": a, "B": b, "O4": np.tile(o4, (n, 1))}


def _link_poses(design, phi: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each link's centre of mass (n, 2) mm and angle (n,) rad at main shaft angles ``phi``."""
    at = _joints(design, phi)
    out = {}
    for link, (first, second) in FRAMES.items():
        axis = at[second] - at[first]
        angle = np.arctan2(axis[:, 1], axis[:, 0])
        cx, cy = LINKS[link]["centre"]
        centre = at[first] + np.column_stack((cx * np.cos(angle) - cy * np.sin(angle),
                                              cx * np.sin(angle) + cy * np.cos(angle)))
        out[link] = (centre, angle)
    return out


def _kinetic_energy(design, phi: np.ndarray, h: float = 1e-4) -> np.ndarray:
    """sum 1/2 m v^2 + 1/2 I w^2 (J) at main shaft angles ``phi``, each velocity by central differences of the
    positions over +-h radians of the shaft at its speed."""
    omega = design.omega
    ahead, behind = _link_poses(design, phi + h), _link_poses(design, phi - h)
    energy = np.zeros_like(phi)
    for link, values in LINKS.items():
        v = (ahead[link][0] - behind[link][0]) / (2 * h) * omega / 1000.0                        # m/s
        w = np.angle(np.exp(1j * (ahead[link][1] - behind[link][1]))) / (2 * h) * omega          # rad/s
        energy += 0.5 * values["mass"] * np.sum(v ** 2, axis=1) + 0.5 * values["inertia"] * 1e-6 * w ** 2
    return energy


def _rocker_angle(design, phi: np.ndarray) -> np.ndarray:
    at = _joints(design, phi)
    return np.arctan2(*(at["B"] - at["O4"]).T[::-1])


def test_the_camshaft_torque_is_the_rate_of_kinetic_energy_plus_the_load_power(heavy):
    """T_shaft = (dE/dt + P_load) / omega at every shaft angle: E from the positions alone, P_load the power
    against the output torque (-T omega_4); to 1e-6 of the torque's peak (the nested central differences at 1e-4
    rad give 5e-8; finer steps lose it to rounding)."""
    phi, omega = heavy.phi, heavy.omega
    h = 1e-4
    d_energy = (_kinetic_energy(heavy, phi + h) - _kinetic_energy(heavy, phi - h)) / (2 * h) * omega    # W
    out = heavy.spec.couplings[0].output_torque
    omega4 = np.angle(np.exp(1j * (_rocker_angle(heavy, phi + h) - _rocker_angle(heavy, phi - h)))) / (2 * h) * omega
    expected = (d_energy - out * omega4) / omega
    torque = heavy.linkages[0].torque
    assert np.abs(d_energy).max() / omega > 0.5 * np.abs(out * omega4).max() / omega   # the inertia's share counts
    assert np.abs(torque - expected).max() < 1e-6 * np.abs(expected).max()
    assert np.abs(heavy.shaft_torque - expected).max() < 1e-6 * np.abs(expected).max()


def test_the_inertia_share_does_no_net_work_over_the_turn(heavy):
    """Over a whole turn the kinetic energy returns: the inverse dynamics' share of the shaft torque averages to 0
    (the sum over uniform samples is the turn's integral), while its peak is not small."""
    m = heavy.linkages[0]
    share = m.effort * m.chain.d1
    assert np.abs(share).max() > 1e-3
    assert abs(share.mean()) < 1e-9 * np.abs(share).max()


def test_the_reflected_force_times_the_rollers_speed_is_the_shaft_torque(heavy):
    m = heavy.linkages[0]
    arm = heavy.cam("arm").design.spec.follower.arm_length
    roller = np.radians(heavy.cam("arm").rate) * arm / 1000.0                      # m per radian of the shaft
    assert np.allclose(m.force * roller, m.torque, rtol=0, atol=1e-12 * np.abs(m.torque).max())


def test_the_cams_load_table_is_the_reflected_force_with_the_inertia(heavy):
    """The cam is designed again with the whole reflected force (inertia and output torque): its rows at whole
    degrees of the program are the force at the shaft angles phase + that degree."""
    rows = heavy.cam("arm").design.spec.follower.load_table_rows
    phase = heavy.spec.cams[0].phase
    force = heavy.linkages[0].force
    plain = _design(_raw(links=None))
    for degree in range(0, 360, 7):
        j = round(((degree + phase) % 360) * 2)                       # 720 samples: half a degree apart
        assert rows[degree][1] == pytest.approx(force[j], abs=1e-8)
    assert np.abs(force - plain.linkages[0].force).max() > 0.1       # N: the masses change it


def test_at_zero_masses_the_figures_are_the_output_torques_exactly():
    zero = {link: {"mass": 0.0, "centre": [0.0, 0.0], "inertia": 0.0} for link in LINKS}
    massless, plain = _design(_raw(links=zero)), _design(_raw(links=None))
    a, b = massless.linkages[0], plain.linkages[0]
    assert a.effort is not None and b.effort is None and np.all(a.effort == 0.0)
    arm = plain.cam("arm").design.spec.follower.arm_length
    out = plain.spec.couplings[0].output_torque
    assert np.array_equal(b.force, kinematics.reflected_force(out, b.k4, arm))         # the present figures
    assert np.array_equal(b.torque, kinematics.shaft_torque(out, b.k4, b.chain.d1))
    assert np.array_equal(a.force, b.force) and np.array_equal(a.torque, b.torque)
    assert np.array_equal(massless.shaft_torque, plain.shaft_torque)
    assert massless.cam("arm").design.spec.follower.load_table_rows == \
        plain.cam("arm").design.spec.follower.load_table_rows


# ---- the follower's spring with the linkage attached -------------------------------------------------------------


def _contact_rows(design) -> np.ndarray:
    """The contact force (N) at each whole degree of the arm's program, computed here: preload + rate x the
    roller's travel along its path + the reflected load's row + the follower's own mass x its acceleration along
    the path (no weight: the follower's orientation is not given)."""
    cam = design.cam("arm").design
    follower = cam.spec.follower
    theta = np.radians(np.arange(360))
    s = cam.cam.program.evaluate(theta)
    scale = follower.arm_length * math.pi / 180.0                               # mm of the roller's path per degree
    omega = cam.spec.cam.rpm * math.pi / 30.0
    rows = np.array([f for _, f in follower.load_table_rows])
    return follower.preload + follower.spring_rate * scale * s[0] + rows + follower.mass * omega ** 2 * scale * s[2] \
        / 1000.0


def _light_spring(raw: dict) -> dict:
    raw["cams"][0]["template"]["follower"].update(preload=2.0, spring_rate=0.1)
    return raw


def test_the_linkages_inertia_pulls_the_follower_off_and_the_check_says_where():
    """At 240 rpm, with a light spring (2 N of preload, 0.1 N/mm), the four-bar's inertia reflected onto the
    follower overcomes it (without the masses the spring holds): the least contact force (the cam's own check)
    matches the force computed row by row here, the warning names the cam and the angle, and the report gives the
    preload that would hold it; with that preload (and 0.5 N more) the least force is 0.5 N."""
    from camgen.kinds.machine.report import machine_report

    raw = _light_spring(_raw(rpm=240.0))
    design = _design(raw)
    contact = design.cam("arm").design.speed.contact
    rows = _contact_rows(design)
    assert rows.min() < 0 and contact.holds is False
    assert contact.force_min == pytest.approx(rows.min(), abs=0.02 * np.ptp(rows))
    assert abs((contact.force_min_at_deg - float(np.argmin(rows)) + 180) % 360 - 180) <= 2.0
    lost = [w for w in design.warnings if w.startswith("cams.arm: the spring loses contact near")]
    assert len(lost) == 1 and f"{contact.force_min_at_deg:.1f} degrees" in lost[0]
    spring = machine_report(design)["linkages"]["arm-bars"]["spring"]
    assert spring["holds"] is False and spring["least_contact_force_n"] == pytest.approx(contact.force_min)
    assert spring["preload_needed_n"] == pytest.approx(contact.preload_needed) and contact.preload_needed > 2.0
    shaft = (spring["at_cam_deg"] + design.spec.cams[0].phase) % 360
    assert spring["at_shaft_deg"] == pytest.approx(shaft)
    # without the linkage's masses the same follower stays on its cam
    assert _design(_light_spring(_raw(links=None, rpm=240.0))).cam("arm").design.speed.contact.holds is True
    raw["cams"][0]["template"]["follower"]["preload"] = contact.preload_needed + 0.5
    held = _design(raw)
    again = held.cam("arm").design.speed.contact
    assert again.holds is True and again.force_min == pytest.approx(0.5, abs=0.05)
    assert _contact_rows(held).min() == pytest.approx(0.5, abs=0.05)
    assert not any(w.startswith("cams.arm: the spring") for w in held.warnings)


def test_a_grooved_cam_needs_no_spring_and_the_report_says_so():
    raw = _raw(rpm=240.0)
    cam = raw["cams"][0]["template"]
    cam["cam"].update(kind="grooved", groove_depth=3.0, running_clearance=0.2, rim=5.0)
    for key in ("mass", "spring_rate", "preload"):
        del cam["follower"][key]
    from camgen.kinds.machine.report import machine_report

    design = _design(raw)
    spring = machine_report(design)["linkages"]["arm-bars"]["spring"]
    assert spring["positive_drive"] is True and re.search(r"no spring", spring["note"])
    assert not any("loses contact" in w for w in design.warnings)
    sprung = _design(_raw(rpm=240.0))
    assert np.abs(design.linkages[0].torque - sprung.linkages[0].torque).max() < 1e-12


# ---- a shaft-driven linkage's inertia on the main shaft ------------------------------------------------------------


def _toy(rpm: float = 60.0) -> dict:
    """The walking toy, its left leg given masses (each link's half-way along its first two joints), lying flat."""
    with (ROOT / "templates" / "walking-toy.toml").open("rb") as stream:
        raw = tomllib.load(stream)
    raw["machine"].update(rpm=rpm, clash_samples=36)
    leg = raw["linkages"][0]["template"]
    lengths = leg["linkage"]["lengths"]
    links = {}
    for k, (name, joints) in enumerate(leg["linkage"]["links"].items()):
        length = lengths.get(f"{joints[0]}-{joints[1]}", lengths.get(f"{joints[1]}-{joints[0]}"))
        links[name] = {"mass": 0.01 * (k + 1), "centre": [length / 2, 1.0 + k], "inertia": 2.0 * (k + 1)}
    leg["dynamics"] = {"incline": 0.0, "links": links}
    return raw


def test_a_shaft_driven_legs_torque_is_its_kinetic_energys_rate():
    """The left leg's share of the main shaft's torque is dE/dt / omega (no gravity, no loads), E from its joints'
    positions over the turn (the machine's own placing of them, tested against linkgen's analysis elsewhere) by
    central differences; the right leg has no masses and adds nothing."""
    design = _design(_toy())
    left, right = design.cranked
    assert right.torque is None and left.torque is not None
    table = left.design.spec.linkage
    given = left.design.spec.dynamics.links
    omega, phi, h = design.omega, design.phi, 1e-4

    def energy(at: np.ndarray) -> np.ndarray:
        ahead, behind = left.solve(at + h).points, left.solve(at - h).points
        total = np.zeros_like(at)
        for name, joints in table.links.items():
            first, second = joints[0], joints[1]
            poses = []
            for points in (ahead, behind):
                axis = np.asarray(points[second]) - np.asarray(points[first])
                angle = np.arctan2(axis[:, 1], axis[:, 0])
                cx, cy = given[name].centre
                poses.append((np.asarray(points[first]) + np.column_stack(
                    (cx * np.cos(angle) - cy * np.sin(angle), cx * np.sin(angle) + cy * np.cos(angle))), angle))
            v = (poses[0][0] - poses[1][0]) / (2 * h) * omega / 1000.0
            w = np.angle(np.exp(1j * (poses[0][1] - poses[1][1]))) / (2 * h) * omega
            total += 0.5 * given[name].mass * np.sum(v ** 2, axis=1) + 0.5 * given[name].inertia * 1e-6 * w ** 2
        return total

    expected = (energy(phi + h) - energy(phi - h)) / (2 * h)          # dE/dphi = (dE/dt) / omega
    assert np.abs(expected).max() > 1e-3
    assert np.abs(left.torque - expected).max() < 1e-6 * np.abs(expected).max()
    assert np.array_equal(design.shaft_torque, left.torque)
    plain = _design({**_toy(), "linkages": _raw_toy_linkages()})
    assert not np.any(plain.shaft_torque)


def _raw_toy_linkages() -> list:
    with (ROOT / "templates" / "walking-toy.toml").open("rb") as stream:
        return tomllib.load(stream)["linkages"]
