"""An oscillating flat-faced follower's arm as a four-bar's crank (issue 35): the coupling of
``templates/automaton.toml`` with its follower a flat face. Its arm's lever is the distance from its pivot to the
crank pin (the four-bar's crank), not a roller's arm length (which a face has none of: this raised AttributeError
'arm_length'). The rocker against an independent circle intersection fed by the follower's swing to 1e-9 rad, the
crank pin on the face's line through the contact, the reflected force by virtual work at the crank pin, and the
machine built and posed."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from tests.conftest import ROOT

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-flat-face-coupling")

AUTOMATON = ROOT / "templates" / "automaton.toml"


def _flat_automaton() -> dict:
    """The automaton's arm and its four-bar, the follower a flat face (base radius 95 mm, its pivot 160 mm from the
    cam's centre: a swing of 15 degrees over 120 of the program, cycloidal, keeps the profile convex)."""
    with AUTOMATON.open("rb") as stream:
        raw = tomllib.load(stream)
    arm = next(c for c in raw["cams"] if c["name"] == "arm")
    template = arm["template"]
    template["cam"]["base_radius"] = 95.0
    template["follower"] = {"type": "oscillating-flat", "pivot_distance": 160.0, "mass": 0.1, "spring_rate": 0.5,
                            "preload": 12.0}
    template["motion"] = [{"type": t, "law": "cycloidal", "lift": 15.0, "angle": 120.0} if t != "dwell"
                          else {"type": t, "angle": 60.0} for t in ("rise", "dwell", "return", "dwell")]
    raw.update(name="flat-automaton", cams=[arm])
    return raw


GROUND, CRANK, COUPLER, ROCKER, REST, TORQUE = 80.0, 30.0, 90.0, 60.0, 60.0, -0.2


@pytest.fixture(scope="module")
def flat():
    from camgen import api

    return api.design(api.validate(_flat_automaton()))


def _rockers(theta2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The rocker's angle on both branches at crank angles ``theta2`` (rad): B on the circle of the coupler's
    length about the crank pin A = crank (cos, sin) theta2 and on the circle of the rocker's about O4 = (ground, 0),
    the two circles' intersections (the chord's midpoint along A -> O4, then the half chord either side)."""
    a = CRANK * np.column_stack([np.cos(theta2), np.sin(theta2)])
    o4 = np.array([GROUND, 0.0])
    d = o4 - a
    dist = np.hypot(d[:, 0], d[:, 1])
    along = (COUPLER**2 - ROCKER**2 + dist**2) / (2 * dist)
    half = np.sqrt(COUPLER**2 - along**2)
    u = d / dist[:, None]
    n = np.column_stack([-u[:, 1], u[:, 0]])
    mid = a + along[:, None] * u
    out = []
    for sign in (1.0, -1.0):
        b = mid + sign * half[:, None] * n
        out.append(np.arctan2(b[:, 1] - o4[1], b[:, 0] - o4[0]))
    return out[0], out[1]


def _wrapped(x: np.ndarray) -> np.ndarray:
    return (x + math.pi) % (2 * math.pi) - math.pi


def test_the_rocker_is_the_circles_intersection_at_the_followers_swing(flat):
    cam = flat.cam("arm")
    m = next(x for x in flat.linkages if x.name == "arm-bars")
    psi = cam.follower[0]                                         # the face's swing (degrees), its own program
    assert np.ptp(psi) == pytest.approx(15.0, abs=1e-9)
    theta2 = np.radians(REST + psi)
    first, second = _rockers(theta2)
    branch = first if abs(_wrapped(first[0] - m.theta4[0])) < abs(_wrapped(second[0] - m.theta4[0])) else second
    assert np.abs(_wrapped(m.theta4 - branch)).max() < 1e-9
    other = second if branch is first else first
    assert np.abs(_wrapped(other - branch)).min() > 0.1           # the branches lie apart: the pick is no tie


def test_the_reflected_force_acts_at_the_crank_pin(flat):
    """Virtual work at the crank pin, 30 mm from the pivot: F = -T (d theta4 / d theta2) 1000 / 30 N, the rate by
    central differences of the circle intersection; the camshaft's torque -T theta4' (the rocker's rate per radian
    of the main shaft)."""
    cam = flat.cam("arm")
    m = next(x for x in flat.linkages if x.name == "arm-bars")
    theta2 = np.radians(REST + cam.follower[0])
    h = 1e-6
    pick = 0 if abs(_wrapped(_rockers(theta2[:1])[0][0] - m.theta4[0])) < 1e-6 else 1
    k4 = _wrapped(_rockers(theta2 + h)[pick] - _rockers(theta2 - h)[pick]) / (2 * h)
    force = -TORQUE * k4 * 1000.0 / CRANK
    assert np.abs(m.force - force).max() < 1e-6 * np.abs(force).max()
    assert np.abs(force).max() > 1.0
    assert np.abs(m.torque + TORQUE * m.rocker_rate).max() < 1e-12


def test_the_crank_pin_rides_the_faces_line(flat):
    """The crank lies along the arm: its pin 30 mm from the pivot on the face's line through the cam's contact (the
    follower's envelope), on the contact's side, at every sample."""
    from camgen.kinds.machine import poses
    from camgen.kinds.machine.design import _cam_of

    cam = flat.cam("arm")
    kin = _cam_of(cam.design)
    f = kin.follower
    pin = poses.points(flat, flat.phi)["linkages.arm-bars.A"]
    pivot = np.asarray(f.pivot)
    theta = cam.program_angles(flat.phi)
    contact = f.fixed(theta, f.pitch(theta, kin.program.evaluate(theta)))   # the cam's frame turned back
    # f.fixed gives the contact in the fixed frame (the cam's centre at the origin: the camshaft's at (0, 0))
    arm, face = pin - pivot, contact - pivot
    assert np.abs(np.hypot(arm[:, 0], arm[:, 1]) - CRANK).max() < 1e-9
    cross = (arm[:, 0] * face[:, 1] - arm[:, 1] * face[:, 0]) / np.hypot(face[:, 0], face[:, 1])
    assert np.abs(cross).max() < 1e-9 * CRANK
    assert ((arm * face).sum(axis=1) > 0).all()


def test_the_machine_builds_with_the_face_driving_the_four_bar(flat, tmp_path):
    from camgen import api

    api.write(flat, tmp_path / "out")
    report = (tmp_path / "out" / "flat-automaton.json").read_text()
    assert "linkages.arm-bars" in report


def test_a_general_linkage_on_the_face_takes_the_crank_pin_as_its_lever():
    """The same four-bar drawn as a general linkage (``type = "linkage"``, its crank O-A of 30 mm at 60 degrees) on
    the face's arm: its lever is the crank's 30 mm (per degree of swing, pi/6 mm), and the force on the follower holds
    the rocker's torque by virtual work at the crank pin: F = -T (d theta4 / d psi) 1000 / lever, the rate by central
    differences of the circle intersection at the crank's angle k psi (k = -1, the face's sense of swing)."""
    from camgen import api

    raw = _flat_automaton()
    a = CRANK * np.array([math.cos(math.radians(REST)), math.sin(math.radians(REST))])
    first, _ = _rockers(np.array([math.radians(REST)]))
    b = np.array([GROUND, 0.0]) + ROCKER * np.array([math.cos(first[0]), math.sin(first[0])])
    raw["linkages"][0]["template"] = {"linkage": {
        "type": "linkage", "ground": ["O", "D"], "input": {"link": "crank", "pivot": "O"}, "tracers": ["B"],
        "joints": {"O": [0.0, 0.0], "A": a.tolist(), "B": b.tolist(), "D": [GROUND, 0.0]},
        "links": {"crank": ["O", "A"], "coupler": ["A", "B"], "rocker": ["D", "B"]}}}
    raw["couplings"][0].update(rest=REST, output="rocker")
    made = api.design(api.validate(raw))
    slid = made.slid[0]
    assert slid.lever == pytest.approx(CRANK * math.pi / 180.0, rel=1e-15)
    psi = np.radians(made.cam("arm").follower[0])
    h = 1e-6
    rate = _wrapped(_rockers(math.radians(REST) - (psi + h))[0] - _rockers(math.radians(REST) - (psi - h))[0]) / (2 * h)
    force = -TORQUE * rate * (math.pi / 180.0) * 1000.0 / slid.lever
    assert np.abs(slid.force - force).max() < 1e-6 * np.abs(force).max()
    assert np.abs(force).max() > 1.0
