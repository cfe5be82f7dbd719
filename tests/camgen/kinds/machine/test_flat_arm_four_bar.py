"""A four-bar on an oscillating flat face's arm placed for the clash check and the assembly (issue 35 item 4,
:mod:`camgen.kinds.machine.flat_arm`): its coupler and rocker were left out (``clash_check.not_checked`` listed
``linkages.<name>``). The crank pin against the follower's swing worked here from the cam's program and the
four-bar's circle intersection (1e-9 mm, 720 angles); a crank on the camshaft sweeping into the resting rocker found
within 0.1 degree of the first angle at which the two bars' centre lines come their half widths apart (the distance
of two segments, worked here); and the machine meeting no part but at its joints over 720 angles."""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from tests.camgen.kinds.machine.test_face_guide_clash import _cam
from tests.support.machine_meetings import assert_meet_only_at_joints, spans

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-flat-arm-four-bar")

#: the face's cam (base radius 95 mm, its pivot 160 mm from the camshaft, at (sqrt(160^2 - 95^2), 95)): a swing of
#: 15 degrees (cycloidal over 120 degrees of its program), a hold, the return over 120 and a rest over the last 60;
#: the program starts at 160 degrees of the main shaft (the camshaft), so the arm rests over phi in [100, 160]
BASE, PIVOT, PHASE = 95.0, 160.0, 160.0
#: the four-bar (mm) on the arm, its crank 60 degrees from its ground line with the follower at rest; its bars 10 mm
#: wide; the sweeping crank on the camshaft (45 mm, 8 mm wide, drawn at -100 degrees)
GROUND, CRANK, COUPLER, ROCKER, REST, HALF = 80.0, 30.0, 90.0, 60.0, 60.0, 5.0
SWEEP, SWEEP_AT, SWEEP_HALF = 45.0, -100.0, 4.0
PHI = np.arange(720) * (2 * math.pi / 720)


def _raw(sweep_layer: int) -> dict:
    """The machine: the face's cam on the camshaft (layer 0: the cam on plane 0, its arm on planes 0 and 1), the
    four-bar driven by the arm (its rocker on plane 1, its coupler on plane 2), the crank on the camshaft at
    ``sweep_layer`` (0: plane 1, the rocker's; 1: plane 3, over every part)."""
    tip = [SWEEP * math.cos(math.radians(SWEEP_AT)), SWEEP * math.sin(math.radians(SWEEP_AT))]
    bars = {"name": "bars", "template": {
        "linkage": {"type": "four-bar", "ground": GROUND, "crank": CRANK, "coupler": COUPLER, "rocker": ROCKER},
        "parts": {"width": 2 * HALF, "thickness": 4.0, "pin_diameter": 4.0}}}
    sweep = {"name": "sweep", "shaft": "cam", "layer": sweep_layer, "template": {
        "linkage": {"type": "linkage", "ground": ["O"], "input": {"link": "crank", "pivot": "O"}, "tracers": ["A"],
                    "joints": {"O": [0.0, 0.0], "A": tip}, "links": {"crank": ["O", "A"]}},
        "parts": {"width": 2 * SWEEP_HALF, "thickness": 3.0, "pin_diameter": 3.0}}}
    face = {"type": "oscillating-flat", "base": BASE, "pivot_distance": PIVOT, "face_margin": 3.0}
    return {"name": "barred", "machine": {"main": "cam", "rpm": 30.0, "clash_samples": 180},
            "shafts": [{"name": "cam", "at": [0.0, 0.0]}], "output": {"formats": ["json"]},
            "cams": [_cam("lift", "cam", face, (("rise", 15.0, 120.0), ("dwell", 0, 60.0), ("return", 15.0, 120.0),
                                                ("dwell", 0, 60.0)), PHASE)],
            "linkages": [bars, sweep],
            "couplings": [{"cam": "lift", "linkage": "bars", "link": "crank", "rest": REST, "output_torque": -0.2}]}


def _design(sweep_layer: int):
    from camgen import api

    return api.design(api.validate(copy.deepcopy(_raw(sweep_layer))))


@pytest.fixture(scope="module")
def barred():
    """The sweeping crank over every part: nothing meets."""
    return _design(1)


@pytest.fixture(scope="module")
def swept():
    """The sweeping crank on the rocker's plane."""
    return _design(0)


def _swing(phi: np.ndarray) -> np.ndarray:
    """The follower's swing psi (degrees) at main shaft angles ``phi`` (rad): its program angle phi - 160 degrees,
    cycloidal rise and return of 15 degrees over 120 degrees each, a hold of 60 between and a rest of 60 after."""
    t = np.mod(np.degrees(phi) - PHASE, 360.0)

    def cycloid(u: np.ndarray) -> np.ndarray:
        return u - np.sin(2 * math.pi * u) / (2 * math.pi)

    return 15.0 * np.select([t < 120.0, t < 180.0, t < 300.0], [cycloid(t / 120.0), np.ones_like(t),
                                                                  1.0 - cycloid((t - 180.0) / 120.0)], 0.0)


def _to_machine(local: np.ndarray) -> np.ndarray:
    """(n, 2) points of the four-bar's frame (its crank's pivot at the origin, its ground line along +x) in the
    machine's: the crank lies along the face, which a rise turns clockwise about the pivot, so the frame is mirrored
    and a direction beta in it points at 180 + REST - beta degrees, from the pivot."""
    r = np.hypot(local[:, 0], local[:, 1])
    beta = np.arctan2(local[:, 1], local[:, 0])
    turn = math.pi + math.radians(REST) - beta
    pivot = np.array([math.sqrt(PIVOT**2 - BASE**2), BASE])
    return pivot + r[:, None] * np.column_stack([np.cos(turn), np.sin(turn)])


def _joints(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The crank pin A, the rocker pin B (the open four-bar: B to the left of the line A -> O4) and the rocker's
    pivot O4 (n, 2) mm in the machine's frame at main shaft angles ``phi``: the crank at REST + psi, B on the circle
    of the coupler's length about A and the rocker's about O4 (the chord's midpoint on A -> O4, the half chord
    square to it)."""
    theta2 = np.radians(REST + _swing(phi))
    a = CRANK * np.column_stack([np.cos(theta2), np.sin(theta2)])
    o4 = np.tile([GROUND, 0.0], (len(phi), 1))
    d = o4 - a
    dist = np.hypot(d[:, 0], d[:, 1])
    along = (COUPLER**2 - ROCKER**2 + dist**2) / (2 * dist)
    half = np.sqrt(COUPLER**2 - along**2)
    u = d / dist[:, None]
    b = a + along[:, None] * u + half[:, None] * np.column_stack([-u[:, 1], u[:, 0]])
    return _to_machine(a), _to_machine(b), _to_machine(o4)


def _placed(body, phi: np.ndarray, local) -> np.ndarray:
    """Point ``local`` (mm, the body's own frame) placed at ``phi``: (n, 2) mm."""
    m, t = body.place(phi)
    return np.einsum("nij,j->ni", np.asarray(m), np.asarray(local, float)) + np.asarray(t)


def test_the_four_bar_on_the_face_is_checked_and_assembled(barred):
    """``clash_check.not_checked`` is empty (it listed ``linkages.bars``); the coupler and rocker are clash bodies,
    pieces of the assembly and posed parts; the arm carries the crank pin's hole 30 mm out along its face (the
    pin's ISO 273 medium clearance hole), which the assembly puts where the coupler's crank pin is; the poses name
    the arm's pivot."""
    from camgen.kinds.machine import assembly, poses
    from camgen.kinds.machine.frame import pin_hole
    from camgen.kinds.machine.report import machine_report

    assert barred.unchecked == () and barred.clashes == ()
    assert machine_report(barred)["clash_check"]["not_checked"] == []
    names = {b.name for b in barred.bodies}
    assert {"linkages.bars.coupler", "linkages.bars.rocker", "cams.lift.arm"} <= names
    arm = next(b for b in barred.bodies if b.name == "cams.lift.arm")
    assert ((CRANK, 0.0), pin_hole(4.0) / 2) in arm.holes
    pieces = {p.part.name: p.part for p in assembly.pieces(barred)}
    assert {"linkages.bars.coupler", "linkages.bars.rocker"} <= set(pieces)
    a = _joints(np.zeros(1))[0][0]                                 # the assembly's angle: 0
    assert min(math.dist(h.centre, a) for h in pieces["cams.lift.arm"].holes) < 1e-9
    assert min(math.dist(h.centre, a) for h in pieces["linkages.bars.coupler"].holes) < 1e-9
    posed = {p.name for p in poses.placed_parts(barred, PHI[:2])}
    assert {"linkages.bars.coupler", "linkages.bars.rocker"} <= posed
    pivot = poses.points(barred, PHI[:2])["cams.lift.pivot"]
    assert pivot == pytest.approx(np.tile([math.sqrt(PIVOT**2 - BASE**2), BASE], (2, 1)), abs=1e-9)


def test_the_coupler_rides_the_arms_crank_pin_at_the_followers_swing(barred):
    """At 720 angles (1e-9 mm): the coupler's crank-pin end (its frame's origin), the arm's crank-pin hole and the
    joint between them all lie on A worked here from the program; the coupler's far end, the rocker's and their
    joint on B; the rocker's pivot on O4; the other branch of the four-bar lies well apart (the pick is no tie)."""
    from camgen.kinds.machine import clash

    bodies, joints, _ = clash.machine_parts(barred)
    named = {b.name: b for b in bodies}
    arm, coupler, rocker = (named[n] for n in ("cams.lift.arm", "linkages.bars.coupler", "linkages.bars.rocker"))
    a, b, o4 = _joints(PHI)
    assert np.ptp(_swing(PHI)) == pytest.approx(15.0)
    pin = next(j for j in joints if {j.a, j.b} == {arm.name, coupler.name})
    knee = next(j for j in joints if {j.a, j.b} == {coupler.name, rocker.name})
    for found, want in ((_placed(coupler, PHI, (0.0, 0.0)), a), (_placed(arm, PHI, (CRANK, 0.0)), a),
                        (pin.centre(PHI), a), (_placed(coupler, PHI, (COUPLER, 0.0)), b),
                        (_placed(rocker, PHI, (ROCKER, 0.0)), b), (knee.centre(PHI), b),
                        (_placed(rocker, PHI, (0.0, 0.0)), o4)):
        assert np.abs(found - want).max() < 1e-9
    crossed = 2 * (a + (o4 - a) * np.sum((b - a) * (o4 - a), 1)[:, None] / np.sum((o4 - a) ** 2, 1)[:, None]) - b
    assert np.hypot(*(crossed - b).T).min() > 10.0                  # B mirrored in A -> O4: the crossed branch


def _segment_gap(p0: np.ndarray, p1: np.ndarray, q0: np.ndarray, q1: np.ndarray) -> np.ndarray:
    """The distance (n,) mm between segments p0 p1 and q0 q1 (each (n, 2) mm) that do not cross: the least of the
    four distances of an end of one to the other."""
    def point(x: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        ab = b - a
        t = np.clip(np.sum((x - a) * ab, 1) / np.sum(ab * ab, 1), 0.0, 1.0)
        return np.hypot(*(a + t[:, None] * ab - x).T)

    return np.min([point(p0, q0, q1), point(p1, q0, q1), point(q0, p0, p1), point(q1, p0, p1)], axis=0)


def _sweep_gap(phi: np.ndarray) -> np.ndarray:
    """How far (mm) the sweeping crank's bar (round ends of 4 mm about the camshaft and its tip, which turns
    counter-clockwise with the main shaft from -100 degrees) is from the rocker's (5 mm about O4 and B): the
    distance of their centre lines less 9 mm."""
    phi = np.atleast_1d(np.asarray(phi, float))
    _, b, o4 = _joints(phi)
    turn = np.radians(SWEEP_AT) + phi
    tip = SWEEP * np.column_stack([np.cos(turn), np.sin(turn)])
    return _segment_gap(np.zeros_like(tip), tip, o4, b) - (SWEEP_HALF + HALF)


def test_a_crank_sweeping_into_the_resting_rocker_is_found_at_its_angle(swept):
    """The crank on the rocker's plane first comes within 9 mm (its half width and the rocker's) of the rocker at
    the root of the centre lines' gap found here (a 0.01 degree grid over the turn, then brentq to 1e-12), while the
    arm rests (phi in [100, 160]); the clash check names that pair at that angle within 0.1 degree, and no other."""
    grid = np.radians(np.arange(0.0, 360.0, 0.01))
    gap = _sweep_gap(grid)
    assert gap[0] > 0
    k = int(np.argmax(gap <= 0))
    expected = math.degrees(brentq(lambda x: float(_sweep_gap(x)[0]), grid[k - 1], grid[k], xtol=1e-12))
    assert 100.0 < expected < 160.0
    met = {frozenset((c.a, c.b)): c.angle_deg for c in swept.clashes}
    assert set(met) == {frozenset(("linkages.bars.rocker", "linkages.sweep.crank"))}, met
    assert abs(met[frozenset(("linkages.bars.rocker", "linkages.sweep.crank"))] - expected) <= 0.1, (met, expected)


def test_the_machine_meets_no_part_but_at_its_joints_over_the_turn(barred):
    """Every pair of parts standing at common heights (the assembly's) at 720 angles meets only inside a joint's
    disc: the rocker and the arm (a plane in common, no joint) never, the coupler and the arm at the crank pin."""
    from camgen.kinds.machine import clash

    bodies, joints, _ = clash.machine_parts(barred)
    span = spans(barred, bodies)
    (a0, a1), (r0, r1) = span["cams.lift.arm"], span["linkages.bars.rocker"]
    assert a0 < r1 and r0 < a1                                     # the rocker stands beside the arm's top
    assert assert_meet_only_at_joints(bodies, joints, span, PHI) >= 5


def test_a_general_linkage_on_the_face_is_one_bell_crank_with_its_arm():
    """The same four-bar drawn as a general linkage (``type = "linkage"``, at rest: O the pivot, A 30 mm out at 60
    degrees, D 80 mm along +X, B the open intersection), its crank and the face's arm one rigid bell crank: they
    meet in a joint at the pivot (the clash check named them meeting at 0 degrees), nothing clashes or is left
    unchecked."""
    from camgen import api
    from camgen.kinds.machine import clash

    raw = _raw(1)
    a = CRANK * np.array([math.cos(math.radians(REST)), math.sin(math.radians(REST))])
    d = np.array([GROUND, 0.0]) - a
    along = (COUPLER**2 - ROCKER**2 + d @ d) / (2 * math.hypot(*d))
    u = d / math.hypot(*d)
    b = a + along * u + math.sqrt(COUPLER**2 - along**2) * np.array([-u[1], u[0]])
    raw["linkages"][0]["template"]["linkage"] = {
        "type": "linkage", "ground": ["O", "D"], "input": {"link": "crank", "pivot": "O"}, "tracers": ["B"],
        "joints": {"O": [0.0, 0.0], "A": a.tolist(), "B": b.tolist(), "D": [GROUND, 0.0]},
        "links": {"crank": ["O", "A"], "coupler": ["A", "B"], "rocker": ["D", "B"]}}
    raw["couplings"][0]["output"] = "rocker"
    made = api.design(api.validate(raw))
    assert made.unchecked == () and made.clashes == ()
    bell = next(j for j in clash.machine_parts(made)[1] if {j.a, j.b} == {"cams.lift.arm", "linkages.bars.crank"})
    pivot = (math.sqrt(PIVOT**2 - BASE**2), BASE)
    assert np.abs(bell.centre(PHI[:4]) - pivot).max() < 1e-9
