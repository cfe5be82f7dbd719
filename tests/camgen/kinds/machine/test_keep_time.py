"""A cam that makes a linkage keep time (issue 36 item 6): the machine driven by the designed cam reaches each target
at its shaft angle to 1e-6 mm, evaluated independently (the built cam's program at the target's time, shifted by
its phase, fed into a circle intersection written here); a rocker's rise-dwell-return program reproduced to 1e-6
degrees at its points; the crank's motion continuous to the acceleration and monotone between targets; the
bundled example's cam passing its own checks; the bad inputs refused in one line naming the field."""
from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core.errors import SpecError
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-keep-time")

KEEP_TIME = ROOT / "templates" / "keep-time.toml"
#: the bundled example's four-bar: ground, crank, coupler, rocker (mm), the hand at 45 mm, 30 degrees off A -> B
LENGTHS = (80.0, 30.0, 90.0, 60.0)
HAND = (45.0, math.radians(30.0))


def _raw() -> dict:
    with KEEP_TIME.open("rb") as stream:
        return tomllib.load(stream)


def _design(raw: dict):
    from camgen import api

    return api.design(api.validate(raw))


def _pins(lengths, theta2: np.ndarray, side: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """The crank pin A and the rocker pin B at crank angles ``theta2``: B where the circle about A (radius coupler)
    meets the circle about O4 = (ground, 0) (radius rocker), on the left of A -> O4 (``side`` -1: on the right,
    the crossed assembly)."""
    ground, crank, coupler, rocker = lengths
    a = np.column_stack((crank * np.cos(theta2), crank * np.sin(theta2)))
    dx, dy = ground - a[:, 0], -a[:, 1]
    d = np.hypot(dx, dy)
    along = (coupler ** 2 - rocker ** 2 + d ** 2) / (2 * d)
    h = side * np.sqrt(coupler ** 2 - along ** 2)
    b = np.column_stack((a[:, 0] + along * dx / d - h * dy / d, a[:, 1] + along * dy / d + h * dx / d))
    return a, b


def _hand(lengths, hand, theta2: np.ndarray, side: float = 1.0) -> np.ndarray:
    """The coupler point (n, 2) (mm) at crank angles ``theta2`` (radians)."""
    a, b = _pins(lengths, theta2, side)
    angle = np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0]) + hand[1]
    return a + hand[0] * np.column_stack((np.cos(angle), np.sin(angle)))


def _rocker(lengths, theta2: np.ndarray) -> np.ndarray:
    """The rocker's angle (degrees) at crank angles ``theta2`` (radians), the open assembly."""
    _, b = _pins(lengths, theta2)
    return np.degrees(np.arctan2(b[:, 1], b[:, 0] - lengths[0]))


def _timed(lengths, hand, crank_deg, times, dwells=None, tolerance=1e-3) -> dict:
    """The bundled example with its linkage's lengths and hand replaced and targets on the hand's path at the
    ``crank_deg`` angles, reached at shaft angles ``times`` (holding for ``dwells``)."""
    raw = _raw()
    table = raw["linkages"][0]["template"]["linkage"]
    table.update(ground=lengths[0], crank=lengths[1], coupler=lengths[2], rocker=lengths[3],
                 point_distance=hand[0], point_angle=math.degrees(hand[1]))
    points = _hand(lengths, hand, np.radians(crank_deg))
    dwells = dwells or [0.0] * len(times)
    raw["couplings"][0]["keep_time"] = {
        "targets": [[float(p[0]), float(p[1]), float(t), float(d)] for p, t, d in zip(points, times, dwells,
                                                                                     strict=True)],
        "tolerance": tolerance}
    return raw


def _swing(design, phi_deg: np.ndarray) -> np.ndarray:
    """The follower's swing (degrees) at shaft angles ``phi_deg``: the built cam's program at phi - phase."""
    mount = design.spec.cams[0]
    program = design.cam(mount.name).design.cam.program
    return program.evaluate(np.radians(np.asarray(phi_deg) - mount.phase))[0]


def _crank(design, phi_deg) -> np.ndarray:
    """The crank's angle (radians) at shaft angles ``phi_deg``: the coupling's rest + the follower's swing."""
    return np.radians(design.spec.couplings[0].rest + _swing(design, phi_deg))


# ---- the machine reaches every target at its time


CASES = {
    # the bundled crank-rocker, a pick and a place held, the crank turning back twice
    "crank-rocker": (LENGTHS, HAND, [60.0, 72.0, 84.0, 88.0, 70.0], [0.0, 110.0, 160.0, 200.0, 300.0],
                     [50.0, 0.0, 0.0, 40.0, 0.0]),
    # its crank through 0 degrees: the arm's swing lies across the cut at 360
    "through-zero": (LENGTHS, HAND, [350.0, 5.0, 15.0, 0.0], [20.0, 90.0, 170.0, 280.0], None),
    # a triple rocker whose crank reaches -100.8 to 100.8 degrees (see tests/camgen/kinds/machine/test_machine.py)
    "triple-rocker": ((60.0, 50.0, 40.0, 45.0), (20.0, math.radians(-40.0)), [70.0, 85.0, 95.0, 80.0],
                      [0.0, 90.0, 150.0, 240.0], [30.0, 0.0, 20.0, 0.0]),
}


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request):
    lengths, hand, crank, times, dwells = CASES[request.param]
    raw = _timed(lengths, hand, crank, times, dwells)
    return lengths, hand, crank, raw, _design(raw)


def test_the_linkage_driven_by_the_cam_reaches_each_target_at_its_time(case):
    lengths, hand, _, raw, design = case
    targets = np.array(raw["couplings"][0]["keep_time"]["targets"])
    for x, y, at, dwell in targets:
        for t in (at, at + dwell):
            point = _hand(lengths, hand, _crank(design, [t]))[0]
            assert math.hypot(point[0] - x, point[1] - y) < 1e-6


def test_the_machines_own_tracer_is_there_at_the_targets_times(case):
    """The machine's composition (its tracer over the turn at 720 shaft angles) agrees at every target's time."""
    _, _, _, raw, design = case
    linkage = design.linkages[0]
    for x, y, at, _ in raw["couplings"][0]["keep_time"]["targets"]:
        i = round(at * len(design.phi) / 360.0)
        assert math.degrees(design.phi[i]) == pytest.approx(at)
        assert math.hypot(*(linkage.point[i] - (x, y))) < 1e-6


def test_the_crank_is_continuous_to_the_acceleration_and_monotone_between_targets(case):
    raw, design = case[3], case[4]
    program = design.cam(design.spec.cams[0].name).design.cam.program
    for i, seg in enumerate(program.segments):          # every boundary: both sides' s, s', s'' the same
        end = seg.start if i else 2 * math.pi
        left = program.segments[i - 1].evaluate(np.array([end]))[:3, 0]
        right = seg.evaluate(np.array([seg.start]))[:3, 0]
        assert np.abs(left - right).max() < 1e-9 * max(1.0, np.abs(left).max())
    jumps = program.jumps()
    assert {j.quantity for j in jumps} <= {"jerk"}
    targets = raw["couplings"][0]["keep_time"]["targets"]
    ends = [t[2] + t[3] for t in targets]
    arrivals = [t[2] for t in targets[1:]] + [targets[0][2] + 360.0]
    for leave, arrive in zip(ends, arrivals, strict=True):
        swing = _swing(design, np.linspace(leave, arrive, 400))
        steps = np.diff(swing)
        assert (steps >= -1e-12).all() or (steps <= 1e-12).all()
    for *_, at, dwell in targets:                      # held still over each dwell
        if dwell:
            swing = _swing(design, np.linspace(at, at + dwell, 50))
            assert np.ptp(swing) < 1e-12


def test_the_follower_rests_at_the_cranks_lowest_target():
    lengths, hand, crank, times, dwells = CASES["through-zero"]
    design = _design(_timed(lengths, hand, crank, times, dwells))
    assert design.spec.couplings[0].rest == pytest.approx(350.0, abs=1e-6)
    assert design.spec.cams[0].phase == pytest.approx(20.0)
    assert _swing(design, [20.0, 90.0, 170.0, 280.0]) == pytest.approx([0.0, 15.0, 25.0, 10.0], abs=1e-6)


def test_an_overshooting_piece_is_made_monotone_and_still_meets_its_targets():
    """Crank 6, 39, 21, 5 degrees at shaft 100, 195, 261, 346: at the first target the slope before (1 degree over
    114) is 40 times smaller than the one after (33 over 95), so the slopes' change (0.00324 degrees per degree
    squared) bends the piece that arrives there back on itself; its ends' rates and accelerations are halved until
    no piece turns back, and every target is still met exactly."""
    from camgen.kinds.machine import timing

    times, crank = [100.0, 195.0, 261.0, 346.0], [6.0, 39.0, 21.0, 5.0]
    before, after = (6.0 - 5.0) / 114.0, (39.0 - 6.0) / 95.0
    w1, w2 = 2 * 95.0 + 114.0, 95.0 + 2 * 114.0                 # Fritsch and Butland's weights
    rate, acceleration = (w1 + w2) / (w1 / before + w2 / after), (after - before) / ((95.0 + 114.0) / 2)
    unhalved = timing.Piece(346.0, 460.0, 5.0, 6.0, 0.0, 0.0, rate, acceleration)
    assert not unhalved.monotone()
    pieces = timing.through_targets(times, crank, [0.0] * 4)
    assert all(p.monotone() for p in pieces)
    assert [(float(p.t0), float(p.y0)) for p in pieces] == list(zip(times, crank, strict=True))
    halved = pieces[0].w0 / rate
    assert halved < 1 and math.log2(halved) == pytest.approx(round(math.log2(halved)))
    assert pieces[0].a0 / acceleration == pytest.approx(halved)
    grid = np.linspace(0, 1, 2001)
    for p in pieces:                                 # the quintic's own values: monotone from 0 to 1
        values = np.polynomial.Polynomial(p.quintic())(grid)
        assert values[0] == pytest.approx(0.0, abs=1e-12) and values[-1] == pytest.approx(1.0, abs=1e-12)
        assert (np.diff(values) >= -1e-12).all()


def test_targets_in_a_synthesis_frame_are_met_there():
    """The bundled targets given in a frame where the linkage's crank pivot sits at (120, -35) and its ground line
    points at 150 degrees (as a synthesis row places it): met there, and refused when the pivots lie 1 mm too far
    apart."""
    from camgen import api

    raw = _raw()
    keep = raw["couplings"][0]["keep_time"]
    turn, origin = math.radians(150.0), np.array([120.0, -35.0])
    c, s = math.cos(turn), math.sin(turn)
    world = [[c * x - s * y + origin[0], s * x + c * y + origin[1], *rest] for x, y, *rest in keep["targets"]]
    keep["targets"] = world
    keep["ground_pivots"] = [origin.tolist(), (origin + 80.0 * np.array([c, s])).tolist()]
    design = _design(raw)
    for x, y, at, *_ in world:
        local = _hand(LENGTHS, HAND, _crank(design, [at]))[0]
        placed = (c * local[0] - s * local[1] + origin[0], s * local[0] + c * local[1] + origin[1])
        assert math.hypot(placed[0] - x, placed[1] - y) < 1e-6
    from camgen.kinds.machine.report import machine_report

    rows = machine_report(design)["keep_time"]["couplings[0]"]["targets"]
    assert max(r["from_target_mm"] for r in rows) < 1e-6
    keep["ground_pivots"][1] = (origin + 81.0 * np.array([c, s])).tolist()
    with pytest.raises(SpecError, match=r"^couplings\[0\]\.keep_time\.ground_pivots: the pivots lie 81 mm apart; "
                                        r"this linkage's ground is 80 mm"):
        api.validate(raw)


# ---- an output program: the rocker's rise, dwell and return


def _cycloidal(u: np.ndarray) -> np.ndarray:
    return u - np.sin(2 * np.pi * u) / (2 * np.pi)


def _rocker_program(t: np.ndarray) -> np.ndarray:
    """The rocker program of :func:`_output_raw` (degrees above its start) at shaft angles ``t`` (degrees):
    cycloidal rise of 8 over 0-120, dwell to 180, cycloidal return over 180-300, dwell."""
    t = np.mod(t, 360.0)
    return np.where(t < 120, 8 * _cycloidal(t / 120), np.where(t < 180, 8.0, np.where(
        t < 300, 8 * (1 - _cycloidal((t - 180) / 120)), 0.0)))


def _output_raw(turn: str = "ccw", step: float = 5.0) -> tuple[dict, float]:
    raw = _raw()
    start = float(_rocker(LENGTHS, np.radians([60.0 if turn == "ccw" else 85.0]))[0])
    raw["couplings"][0]["keep_time"] = {
        "output": [{"type": "rise", "law": "cycloidal", "lift": 8.0, "angle": 120.0}, {"type": "dwell", "angle": 60.0},
                   {"type": "return", "law": "cycloidal", "lift": 8.0, "angle": 120.0},
                   {"type": "dwell", "angle": 60.0}],
        "start": start, "turn": turn, "step": step}
    return raw, start


@pytest.mark.parametrize("turn", ["ccw", "cw"])
def test_a_rockers_rise_dwell_return_is_reproduced_at_its_points(turn):
    raw, start = _output_raw(turn)
    design = _design(raw)
    sign = 1.0 if turn == "ccw" else -1.0
    points = np.r_[np.arange(0.0, 120.0, 5.0), 120.0, np.arange(180.0, 300.0, 5.0), 300.0]
    want = start + sign * _rocker_program(points)
    got = _rocker(LENGTHS, _crank(design, points))
    assert np.abs(got - want).max() < 1e-6
    fine = np.arange(0.0, 360.0, 0.1)                # between the points: the quintics' error, to the step^6
    between = np.abs(_rocker(LENGTHS, _crank(design, fine)) - (start + sign * _rocker_program(fine))).max()
    assert between < 1e-5
    timed = design.spec.couplings[0]
    from camgen.kinds.machine.report import machine_report

    entry = machine_report(design)["keep_time"]["couplings[0]"]
    assert entry["at_points_max_deg"] < 1e-9 and entry["between_points_max_deg"] == pytest.approx(between, rel=0.5)
    assert timed.keep_time.turn == turn


def test_a_finer_step_follows_the_program_more_closely():
    from camgen.kinds.machine.report import machine_report

    errors = [machine_report(_design(_output_raw(step=s)[0]))["keep_time"]["couplings[0]"]["between_points_max_deg"]
              for s in (10.0, 5.0)]
    assert errors[1] < errors[0] / 8                 # a quintic Hermite's error falls as the step^6 (64x)


# ---- the bundled example


def test_the_bundled_cam_passes_its_own_checks(tmp_path):
    result = CliRunner().invoke(camgen, ["build", str(KEEP_TIME), "-o", str(tmp_path)])
    assert result.exit_code == 0, result.output
    out, report = tmp_path, json.loads((tmp_path / "keep-time.json").read_text())
    cam = json.loads((out / "keep-time-lever.json").read_text())
    assert cam["pressure_angle_max_deg"] < cam["pressure_angle_limit_deg"]
    assert cam["undercut"] is False and cam["warnings"] == []
    assert cam["profile_rho_min_mm"] > 0
    assert {j["quantity"] for j in cam["continuity"]} == {"jerk"}           # C2: only finite jerk steps
    assert cam["speed"]["contact"]["holds"] is True
    assert report["warnings"] == []
    timed = report["keep_time"]["couplings[0]"]
    assert timed["worst_from_path_point_mm"] < 1e-6
    assert all(row["from_target_mm"] < 1e-6 for row in timed["targets"])
    assert len(timed["targets"]) == 7                # five targets, two of them held: their dwells' ends too


def test_the_bundled_targets_are_met_by_an_independent_evaluation():
    raw = _raw()
    design = _design(raw)
    for x, y, at, *dwell in raw["couplings"][0]["keep_time"]["targets"]:
        for t in (at, at + (dwell[0] if dwell else 0.0)):
            point = _hand(LENGTHS, HAND, _crank(design, [t]))[0]
            assert math.hypot(point[0] - x, point[1] - y) < 1e-6


def test_a_spec_validated_again_keeps_its_timing():
    """``with_changes`` dumps the expanded template (motion, phase and rest set) and validates it again: keep_time
    recognises its own values."""
    from camgen import api

    spec = api.validate(_raw())
    again = spec.with_changes({"output.formats": ["json"]})
    assert again.cams[0].template["motion"] == spec.cams[0].template["motion"]
    assert again.couplings[0].rest == spec.couplings[0].rest


def test_a_cam_template_given_by_its_path(tmp_path):
    from camgen.core.starter import toml_value

    raw = _raw()
    cam = raw["cams"][0].pop("template")
    lines = ['name = "lever"']
    for table, keys in cam.items():
        lines += [f"[{table}]", *(f"{k} = {toml_value(v)}" for k, v in keys.items())]
    path = tmp_path / "lever.toml"
    path.write_text("\n".join(lines) + "\n")
    raw["cams"][0]["template"] = str(path)
    design = _design(raw)
    assert len(design.spec.cams[0].template["motion"]) == 7


# ---- bad input: one line naming the field, exit code 2, nothing written


def _path_point(crank_deg: float, side: float = 1.0) -> list[float]:
    return [float(v) for v in _hand(LENGTHS, HAND, np.radians([crank_deg]), side)[0]]


TARGETS = "couplings.0.keep_time.targets"


@pytest.mark.parametrize("change, message", [
    ({TARGETS: [[0.0, 0.0, 0.0], [*_path_point(70.0), 100.0]]},
     "couplings[0].keep_time.targets[0]: the tracer comes no nearer than"),
    ({TARGETS: [[*_path_point(60.0), 0.0], [*_path_point(70.0), 100.0], [*_path_point(80.0), 50.0]]},
     "couplings[0].keep_time.targets[2]: its angle 50 degrees must come after targets[1]'s (100)"),
    ({TARGETS: [[*_path_point(60.0), 0.0, 120.0], [*_path_point(70.0), 100.0]]},
     "couplings[0].keep_time.targets[0]: its dwell of 120 degrees runs to 120, not before the next target's angle "
     "100"),
    ({TARGETS: [[*_path_point(60.0), 0.0], [*_path_point(160.0), 180.0]]},
     "couplings[0].keep_time.targets: the crank must swing through 100 degrees (from 60 to 160)"),
    ({TARGETS: [[*_path_point(60.0), 0.0], [*_path_point(60.0), 180.0]]},
     "couplings[0].keep_time.targets: every target is the same point of the tracer's path"),
    ({TARGETS: [[1.0, 2.0], [3.0, 4.0, 5.0]]},
     "couplings[0].keep_time.targets[0]: a target is [x, y, angle] or [x, y, angle, dwell] (got 2 numbers)"),
    ({TARGETS: [[*_path_point(60.0), 0.0], [*_path_point(70.0), 360.0]]},
     "couplings[0].keep_time.targets[1]: its angle must be >= 0 and < 360 degrees (got 360)"),
    ({TARGETS: [[20000.0, 0.0, 0.0], [*_path_point(70.0), 100.0]]},
     "couplings[0].keep_time.targets[0]: x and y must lie within +-10000 mm (got 20000, 0)"),
    ({"couplings.0.keep_time.tolerance": 20.0}, "couplings[0].keep_time.tolerance: must be > 0 and <= 10 mm"),
    ({"couplings.0.keep_time.step": 0.1}, "couplings[0].keep_time.step: must be >= 0.5 and <= 30 degrees"),
    ({"couplings.0.keep_time.start": 30.0}, "couplings[0].keep_time.start: only with output"),
    ({"couplings.0.keep_time.output": [{"type": "dwell", "angle": 360.0}]},
     "couplings[0].keep_time.targets: give targets"),
    ({"couplings.0.rest": 10.0}, "couplings[0].rest: keep_time sets the crank's rest"),
    ({"cams.0.phase": 10.0}, "cams[0].phase: couplings[0].keep_time sets this cam's phase"),
    ({"cams.0.template.motion": [{"type": "dwell", "angle": 360.0}]},
     "cams[0].template.motion: couplings[0].keep_time makes this cam's motion; leave motion out"),
    ({"couplings.0.cam": "wheel"}, "couplings[0].cam: no cam 'wheel'; cams: lever"),
])
def test_bad_timing_is_refused_naming_the_field(tmp_path, change, message):
    from camgen.core.starter import toml_value

    assert_refused(KEEP_TIME, change, message, tmp_path, inline=toml_value)


def test_a_target_only_the_other_assembly_passes_would_need_a_toggle(tmp_path):
    crossed = _path_point(70.0, side=-1.0)
    assert_refused(KEEP_TIME, {TARGETS: [[*_path_point(60.0), 0.0], [*crossed, 100.0]]},
                   "couplings[0].keep_time.targets[1]: the tracer comes no nearer than", tmp_path)
    result = CliRunner().invoke(camgen, ["build", str(KEEP_TIME), "-o", str(tmp_path / "out"), "--set",
                                         f"{TARGETS}={json.dumps([[*_path_point(60.0), 0.0], [*crossed, 100.0]])}"])
    assert "only the crossed assembly passes it (crank at 70 degrees): reaching it would need the crank to reverse " \
           "through a toggle" in result.output


def test_targets_on_the_cranks_two_ranges_would_need_a_toggle(tmp_path):
    """ground 60, crank 40, coupler 20, rocker 70: Z = |A O4| must lie within [50, 90], so the crank reaches
    cos theta2 <= (60^2 + 40^2 - 50^2) / 4800 = 0.5625 and >= (5200 - 8100) / 4800 = -0.604: two ranges, above and
    below the ground line."""
    lengths, hand = (60.0, 40.0, 20.0, 70.0), (10.0, 0.0)
    raw = _timed(lengths, hand, [70.0, 80.0], [0.0, 180.0])
    below = [float(v) for v in _hand(lengths, hand, np.radians([-70.0]))[0]]
    raw["couplings"][0]["keep_time"]["targets"][1][:2] = below
    from camgen import api

    with pytest.raises(SpecError, match=r"^couplings\[0\]\.keep_time\.targets\[1\]: the tracer passes it at crank "
                                        r"angle 290 degrees, in another range of the crank than targets\[0\] \(70 "
                                        r"degrees\): getting there would need the crank to reverse through a toggle"):
        api.validate(raw)
    assert math.degrees(math.acos(0.5625)) == pytest.approx(55.77, abs=0.01)


def test_an_output_program_beyond_the_rockers_reach(tmp_path):
    raw = _output_raw()[0]
    raw["couplings"][0]["keep_time"]["start"] = 125.0
    from camgen import api

    with pytest.raises(SpecError, match=r"^couplings\[0\]\.keep_time\.start: the rocker's program \(start 125 \+ its "
                                        r"lifts\) cannot be followed: rocker angle 131.897 degrees is out of "
                                        r"reach; this linkage reaches rocker angles \[-131.81, -62.7204\] or "
                                        r"\[62.7204, 131.81\] degrees"):
        api.validate(raw)


@pytest.mark.parametrize("change, message", [
    ({"angle": 100.0}, r"^couplings\[0\]\.keep_time\.output: segment angles add up to 340 degrees; they must add up "
                       r"to 360"),
    ({"law": "modified-uniform", "form": "drafted"}, r"^couplings\[0\]\.keep_time\.output\[0\]\.form: the drafted "
                                                     r"form needs a cam's prime radius"),
])
def test_a_bad_output_program(change, message):
    raw = _output_raw()[0]
    raw["couplings"][0]["keep_time"]["output"][0].update(change)
    from camgen import api

    with pytest.raises(SpecError, match=message):
        api.validate(raw)


def test_a_linkage_that_is_not_a_four_bar(tmp_path):
    raw = _raw()
    raw["linkages"][0]["template"]["linkage"] = {"type": "slider-crank", "crank": 30.0, "rod": 90.0}
    raw["linkages"][0]["template"].pop("parts")
    from camgen import api

    with pytest.raises(SpecError, match=r"^couplings\[0\]\.keep_time: keep_time drives a four-bar by its crank"):
        api.validate(copy.deepcopy(raw))


def test_targets_too_quick_for_the_cam_are_refused_by_its_own_check(tmp_path):
    """Three targets a degree of shaft apart swing the arm 16 degrees in 2: the cam's own curvature check finds the
    pitch curve far sharper than the roller (an undercut) and refuses, before anything is written."""
    from camgen.core.starter import toml_value

    quick = [[*_path_point(60.0), 0.0], [*_path_point(72.0), 1.0], [*_path_point(76.0), 2.0]]
    assert_refused(KEEP_TIME, {TARGETS: quick}, "undercut at", tmp_path, inline=toml_value)
