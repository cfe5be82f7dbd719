"""linkgen synthesize: each method against a textbook case computed independently here, every candidate re-analysed
as written, the defect checks, the path search recovering a known linkage, seeds, and bad tasks refused in one line."""
from __future__ import annotations

import json
import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.core.errors import SpecError
from linkgen.linkage_design import design_linkage
from linkgen.kinematics.fourbar import FourBar
from linkgen.kinematics.slidercrank import SliderCrank
from linkgen.spec import validate_spec
from linkgen.synthesis import synthesize, validate_task, write_synthesis
from linkgen.synthesis.defects import defects, sense
from tests.conftest import ROOT
from tests.support.six_bar_circles import watt1_worst_transmission
from tests.synthesis.conftest import FIGURE_EIGHT, FIGURE_EIGHT_GROUP

LINE6 = ROOT / "templates" / "synth-line6.toml"
#: a crank-rocker and coupler point the path and motion tests generate their targets from
KNOWN = FourBar(40.0, 12.0, 35.0, 30.0, 20.0, math.radians(30.0))
#: where the known linkage sits in the task's frame: crank pivot and ground line direction
PLACED = (np.array([10.0, 5.0]), math.radians(25.0))


def run(raw: dict, **kwargs):
    return synthesize(validate_task(raw), **kwargs)


def task(kind: str, **keys) -> dict:
    return {"name": f"t-{kind}", "task": {"kind": kind, **keys}}


def placed(points: np.ndarray) -> np.ndarray:
    """Points of the known linkage's frame in the task's frame."""
    o2, turn = PLACED
    c, s = math.cos(turn), math.sin(turn)
    return points @ np.array([[c, s], [-s, c]]) + o2


def reanalysed(candidate, angles_deg) -> np.ndarray:
    """The traced point (mm) of a candidate's template, analysed as `linkgen analyze --angle` does, at each input."""
    spec = validate_spec(tomllib.loads(tomllib_text(candidate.template)))
    out = []
    for angle in angles_deg:
        joints = design_linkage(spec, angle).report["positions"]["joints"]
        point = joints[spec.linkage.tracers[0]]
        out.append([point["x_mm"], point["y_mm"]])
    return np.array(out)


def sampled_transmission(lengths, theta2) -> float:
    """The worst transmission angle (degrees) of a four-bar at crank angles ``theta2`` (rad from the ground line),
    sampled: the rocker pin B where the circles about the crank pin A (radius coupler) and about O4 (radius rocker)
    meet, and the angle at B between B->A and B->O4 folded into [0, 90]. ``lengths`` is a row or table with ground,
    crank, coupler and rocker (mm)."""
    r1, r2, r3, r4 = (lengths[k] for k in ("ground", "crank", "coupler", "rocker"))
    a = r2 * np.exp(1j * np.asarray(theta2))
    d = r1 - a
    z = np.abs(d)
    along = (r3**2 - r4**2 + z**2) / (2 * z)
    b = a + (along + 1j * np.sqrt(r3**2 - along**2)) * d / z
    gamma = np.degrees(np.abs(np.angle((a - b) / (r1 - b))))
    assert np.all(np.isfinite(gamma)), "the loop does not close over the motion"
    return float(np.min(np.minimum(gamma, 180 - gamma)))


def template_transmission(c, task_keys: dict) -> float:
    """The worst transmission angle (degrees) of a candidate's template over the motion it makes, sampled (36 001
    crank angles): the whole turn for a crank, else the crank's travel from the first target to the last; a
    slider-crank's the angle between the rod and the normal to the slider line."""
    table = c.template["linkage"]
    if table["type"] == "slider-crank":
        r, rod, e = table["crank"], table["rod"], table["offset"]
        t = np.linspace(0, 2 * math.pi, 36001)
        lean = np.degrees(np.abs(np.arcsin((r * np.sin(t) - e) / rod)))       # the rod's angle to the slider line
        return float(np.min(90 - lean))
    if table["type"] == "linkage" and "G" in table["joints"]:     # a Watt I six-bar, its crank turning fully
        j = table["joints"]
        drawn = math.atan2(j["A"][1] - j["O2"][1], j["A"][0] - j["O2"][0])
        return watt1_worst_transmission(j, drawn + np.linspace(0, 2 * math.pi, 36001))
    if table["type"] == "linkage":                  # drawn in the task's frame: its lengths from its joints
        j = {k: np.array(v) for k, v in table["joints"].items()}
        table = {"ground": math.dist(j["O2"], j["O4"]), "crank": math.dist(j["O2"], j["A"]),
                 "coupler": math.dist(j["A"], j["B"]), "rocker": math.dist(j["O4"], j["B"])}
    if task_keys["kind"] == "function":
        turned = c.row["crank_turned_deg"]
        lo, hi = (a + turned for a in task_keys["input_angles"])
        return sampled_transmission(table, np.radians(np.linspace(lo, hi, 36001)))
    if task_keys.get("crank", True) or task_keys["kind"] == "crank-rocker":
        return sampled_transmission(table, np.linspace(0, 2 * math.pi, 36001))
    start, end = np.radians(c.row["input_angles"][0]), np.radians(c.row["input_angles"][-1])
    turn = 1 if sense(np.radians(c.row["input_angles"])) > 0 else -1
    end = start + turn * np.mod(turn * (end - start), 2 * math.pi)
    return sampled_transmission(table, np.linspace(start, end, 36001))


def tomllib_text(raw: dict) -> str:
    from camgen.core.toml_text import dumps

    return dumps(raw, "test")


# ---------------------------------------------------------------------- crank-rocker and slider-crank


def test_crank_rocker_equal_times_is_norton_example_3_1():
    """Norton, Design of Machinery, example 3-1: 45 degrees of rocker swing, equal times forward and back. The crank
    is half the chord between the rocker pin's limit positions, whatever the free choice."""
    result = run(task("crank-rocker", swing=45.0, rocker=50.0))
    assert len(result.candidates) == 5
    half_chord = 50.0 * math.sin(math.radians(22.5))
    for c in result.candidates:
        fb = FourBar(c.row["ground"], c.row["crank"], c.row["coupler"], c.row["rocker"])
        assert c.row["crank"] == pytest.approx(half_chord, rel=1e-12)
        assert fb.grashof.inversion == "crank-rocker"
        assert fb.time_ratio() == pytest.approx(1.0, abs=1e-9)
        assert c.report["rocker_swing_deg"] == pytest.approx(45.0, abs=1e-6)
    worst = [c.row["transmission_worst_deg"] for c in result.candidates]
    assert worst == sorted(worst, reverse=True)


def test_quick_return_crank_rocker_is_norton_example_3_9():
    """Norton example 3-9: 45 degrees of swing with a time ratio of 1.25; the crank pivot sees the rocker pin's limit
    positions 180 (Q - 1) / (Q + 1) = 20 degrees apart, read here from each linkage's own dead centres."""
    result = run(task("crank-rocker", swing=45.0, time_ratio=1.25, rocker=50.0))
    for c in result.candidates:
        fb = FourBar(c.row["ground"], c.row["crank"], c.row["coupler"], c.row["rocker"])
        ends = {d.kind: d.crank for d in fb.dead_centres("open") if d.kind in ("extended", "folded")}
        b1, b2 = fb.positions(np.array([ends["extended"], ends["folded"]]), "open").b
        seen = math.degrees(abs(math.remainder(math.atan2(*b1[::-1]) - math.atan2(*b2[::-1]), 2 * math.pi)))
        assert seen == pytest.approx(20.0, abs=1e-9)
        assert fb.time_ratio() == pytest.approx(1.25, rel=1e-9)
        assert c.report["time_ratio"] == pytest.approx(1.25, rel=1e-9)


def test_crank_rocker_with_its_ground_given_meets_it():
    """On a ground of 70 mm the construction gives two linkages (and their mirror images); one lets its transmission
    angle fall below the 30 degrees every candidate keeps by default, so only the other is offered, with a line naming
    the limit. 60 degrees of swing with a time ratio of 1.3 on that ground binds whatever the choice: the nearest
    offered (16.56 degrees, sampled here, as the note says) with a line naming the limit, and with no line once the
    task lowers it."""
    result = run(task("crank-rocker", swing=45.0, time_ratio=1.2, rocker=50.0, ground=70.0))
    assert result.candidates
    for c in result.candidates:
        assert c.row["ground"] == pytest.approx(70.0, rel=1e-12)
        assert c.report["rocker_swing_deg"] == pytest.approx(45.0, abs=1e-6)
        assert sampled_transmission(c.row, np.linspace(0, 2 * math.pi, 36001)) >= 30.0
    assert len(result.search["bound"]) == 1 and result.search["bound"][0].startswith("task.min_transmission: 2 of ")
    binding = task("crank-rocker", swing=60.0, time_ratio=1.3, rocker=40.0, ground=70.0)
    nearest = run(binding)
    assert [line.split(";")[0] for line in nearest.search["bound"]] == [
        "task.min_transmission: none of the 2 linkages found keeps its transmission angle at least 30 degrees over its "
        "turn"] and "the best reaches 16.56" in nearest.search["bound"][0]
    sampled = [sampled_transmission(c.row, np.linspace(0, 2 * math.pi, 36001)) for c in nearest.candidates]
    assert sampled[0] == pytest.approx(16.56, abs=0.01) and max(sampled) == sampled[0]
    binding["task"]["min_transmission"] = 0
    for c in run(binding).candidates:
        assert c.row["ground"] == pytest.approx(70.0, rel=1e-12)
        assert c.report["rocker_swing_deg"] == pytest.approx(60.0, abs=1e-6)
        assert sampled_transmission(c.row, np.linspace(0, 2 * math.pi, 36001)) == pytest.approx(
            c.row["transmission_worst_deg"], abs=1e-3)


def test_slider_crank_stroke_and_time_ratio():
    """The stroke and time ratio of each candidate, from the slider-crank's own dead centres; a time ratio of 1 is a
    centred slider with the crank half the stroke."""
    for c in run(task("slider-crank", stroke=100.0, time_ratio=1.4)).candidates:
        sc = SliderCrank(c.row["crank"], c.row["rod"], c.row["offset"])
        assert sc.stroke == pytest.approx(100.0, rel=1e-9) and sc.time_ratio == pytest.approx(1.4, rel=1e-9)
        assert c.report["stroke_mm"] == pytest.approx(100.0, rel=1e-9)
    for c in run(task("slider-crank", stroke=80.0)).candidates:
        assert c.row["offset"] == 0 and c.row["crank"] == pytest.approx(40.0, rel=1e-12)


# ---------------------------------------------------------------------- function generation


def test_freudenstein_log10_three_chebyshev_points():
    """y = log10(x), 1 <= x <= 10, crank 30 to 120 degrees, rocker 90 to 180: the K's solved here from the three
    Chebyshev points; the linkage meets log10 exactly there and its reported structural error is the one measured
    here over the range."""
    result = run(task("function", function="log10(x)", x_range=[1, 10], input_angles=[30, 120],
                      output_angles=[90, 180], min_transmission=0))     # it binds: see the test below
    row = result.candidates[0].row
    x = 5.5 - 4.5 * np.cos(np.array([1, 3, 5]) * math.pi / 6)
    t2, t4 = np.radians(30 + (x - 1) / 9 * 90), np.radians(90 + np.log10(x) * 90)
    k = np.linalg.solve(np.column_stack([np.cos(t4), -np.cos(t2), np.ones(3)]), np.cos(t2 - t4))
    a, c = 100 / k[0], 100 / k[1]
    b = math.sqrt(a * a + c * c + 100**2 - 2 * a * c * k[2])
    assert (row["crank"], row["coupler"], row["rocker"]) == pytest.approx((abs(a), b, abs(c)), rel=1e-12)
    fb = FourBar(100.0, row["crank"], row["coupler"], row["rocker"])
    got = np.degrees(fb.positions(t2, row["assembly"]).theta4)
    assert got == pytest.approx(np.degrees(t4), abs=1e-9)
    fine = np.linspace(1, 10, 20001)
    theta4 = fb.sweep(np.radians(30 + (fine - 1) / 9 * 90), row["assembly"]).theta4
    y = np.remainder(np.degrees(theta4) - 90 + 180, 360) / 90 - 2        # the rocker's turn from 90 degrees, / 90
    assert row["structural_error_max"] == pytest.approx(np.max(np.abs(y - np.log10(fine))), rel=1e-3)
    assert row["structural_error_percent"] == pytest.approx(100 * row["structural_error_max"], rel=1e-12)


def test_freudenstein_least_squares_meets_the_normal_equations():
    row = run(task("function", function="log10(x)", x_range=[1, 10], input_angles=[30, 120], output_angles=[90, 180],
                   precision_points=9, min_transmission=0)).candidates[0].row
    x = np.array(row["precision_x"])
    t2, t4 = np.radians(30 + (x - 1) / 9 * 90), np.radians(90 + np.log10(x) * 90)
    m = np.column_stack([np.cos(t4), -np.cos(t2), np.ones(9)])
    assert np.abs(m.T @ (m @ np.array(row["freudenstein_k"]) - np.cos(t2 - t4))).max() < 1e-12


def test_a_function_generator_that_binds_is_offered_naming_the_limit():
    """The textbook log10 task's linkage (crank 30 to 120 degrees, rocker 90 to 180) lets its transmission angle fall to
    2.8 degrees over the input range (sampled here from its lengths): offered as the nearest by default, with a line
    naming the limit; the
    bundled task's rocker range (105 to 165 degrees) keeps it above 30."""
    keys = {"function": "log10(x)", "x_range": [1, 10], "input_angles": [30, 120]}
    row = run(task("function", **keys, output_angles=[90, 180], min_transmission=0)).candidates[0].row
    crank = np.radians(np.linspace(30, 120, 20001) + row["crank_turned_deg"])
    worst = sampled_transmission(row, crank)
    assert worst == pytest.approx(row["transmission_worst_deg"], abs=1e-6) and 2 < worst < 3
    nearest = run(task("function", **keys, output_angles=[90, 180]))
    assert nearest.candidates[0].row["transmission_worst_deg"] == pytest.approx(worst, abs=1e-6)
    assert len(nearest.search["bound"]) == 1 and nearest.search["bound"][0].startswith("task.min_transmission: ")
    assert f"fall to {worst:.3g} degrees over the input range" in nearest.search["bound"][0]
    row = run(task("function", **keys, output_angles=[105, 165])).candidates[0].row
    assert sampled_transmission(row, np.radians(np.linspace(30, 120, 20001) + row["crank_turned_deg"])) >= 30


def test_function_from_a_table():
    x = np.linspace(0, 1, 11)
    row = run(task("function", table=np.column_stack([x, x**2]).tolist(), input_angles=[0, 60],
                   output_angles=[60, 120])).candidates[0].row
    assert row["precision_y"] == pytest.approx(np.interp(row["precision_x"], x, x**2), rel=1e-12)


# ---------------------------------------------------------------------- motion generation and defects


def _poses(theta_deg, assemblies=("open",) * 3):
    """The known linkage's coupler poses [x, y, angle] in the task's frame, its pins at the first."""
    out, pins = [], None
    for t, asm in zip(theta_deg, assemblies, strict=True):
        p = KNOWN.positions([math.radians(t)], asm)
        xy = placed(p.point)[0]
        out.append([float(xy[0]), float(xy[1]), math.degrees(p.theta3[0] + PLACED[1])])
        pins = pins or [placed(p.a)[0].tolist(), placed(p.b)[0].tolist()]
    return out, pins


def _meets(c, positions):
    """The candidate's four-bar, re-solved at its crank angles, carries the coupler through every pose."""
    theta = np.radians(c.row["input_directions"])
    got = reanalysed(c, np.degrees(theta))
    assert got == pytest.approx(np.array([p[:2] for p in positions]), abs=1e-8)
    assert max(c.row["angle_errors_deg"]) < 1e-8


def test_two_positions_norton_example_3_3():
    """Norton example 3-3: move the coupler line CD from C1D1 to C2D2; each fixed pivot lies on the perpendicular
    bisector of its moving pivot's two positions (checked here by distances)."""
    positions = [[0.0, 0.0, 0.0], [30.0, 25.0, 40.0]]
    moving = [[-10.0, -20.0], [25.0, -15.0]]
    result = run(task("motion", positions=positions, moving_pivots=moving, crank=False))
    assert result.candidates
    for c in result.candidates:
        assert sorted(map(tuple, c.row["moving_pivots"])) == sorted(map(tuple, moving))
        for pivot, m in zip(c.row["ground_pivots"], c.row["moving_pivots"], strict=True):
            turned = complex(*positions[1][:2]) + (complex(*m) - complex(*positions[0][:2])) * np.exp(
                1j * math.radians(40))
            assert abs(complex(*pivot) - complex(*m)) == pytest.approx(abs(complex(*pivot) - turned), rel=1e-9)
        _meets(c, positions)


def test_three_positions_recover_the_known_fixed_pivots():
    positions, pins = _poses([20, 100, 200])
    for given in ({"moving_pivots": pins}, {"fixed_pivots": [placed(np.zeros((1, 2)))[0].tolist(),
                                                            placed(np.array([[40.0, 0.0]]))[0].tolist()]}):
        best = run(task("motion", positions=positions, **given)).candidates[0]
        assert np.array(best.row["ground_pivots"]) == pytest.approx(placed(np.array([[0.0, 0.0], [40.0, 0.0]])),
                                                                   abs=1e-9)
        assert (best.row["crank"], best.row["coupler"], best.row["rocker"]) == pytest.approx((12, 35, 30), rel=1e-9)
        _meets(best, positions)


def test_three_positions_free_choices_are_exposed_and_met():
    positions, _ = _poses([20, 100, 200])
    result = run(task("motion", positions=positions, link_range=[5, 150]))
    for c in result.candidates:
        assert len(c.row["free_choice"]["crank_turns_deg"]) == 2 and not c.row["defects"]
        assert FourBar(c.row["ground"], c.row["crank"], c.row["coupler"], c.row["rocker"]).grashof.input_turns_fully
        _meets(c, positions)


def test_a_branch_defect_is_refused():
    """Two poses of the open assembly and one of the crossed: the linkage through them (the known one) is found
    from its moving pivots, and refused for the branch defect; the check itself names it."""
    positions, pins = _poses([20, 100, 200], ("open", "open", "crossed"))
    with pytest.raises(SpecError, match="no defect-free four-bar"):
        run(task("motion", positions=positions, moving_pivots=pins))
    theta = np.radians([20, 100, 200])
    signs = [1, 1, -1]
    lengths = (KNOWN.ground, KNOWN.crank, KNOWN.coupler, KNOWN.rocker)
    assert defects(lengths, theta, signs, crank=True) == ["branch"]
    assert defects(lengths, theta, [1, 1, 1], crank=True) == []
    assert defects((40.0, 30.0, 35.0, 12.0), theta, [1, 1, 1], crank=True)[0] == "grashof"
    assert sense(np.radians([10, 50, 120])) == 1 and sense(np.radians([10, 300, 200])) == -1
    assert sense(np.radians([10, 120, 50, 200])) == 0                   # neither way meets them in order


# ---------------------------------------------------------------------- path generation


def _known_path(angles_deg):
    return placed(KNOWN.positions(np.radians(angles_deg), "open").point)


def test_path_search_recovers_a_known_linkage_and_every_candidate_reanalyses():
    angles = [20, 60, 100, 140, 180, 220]
    targets = _known_path(angles)
    result = run(task("path", points=targets.tolist(), input_angles=angles, link_range=[5, 80], starts=1,
                      generations=300, seed=3))
    # six timed points can have more than one exact four-bar: with this seed it finds 0.5803 times the known one
    # with coupler and rocker exchanged, through the same points at the same crank angles
    assert result.candidates[0].row["error_mm2"] < 1e-6
    for c in result.candidates:
        got = reanalysed(c, c.row["input_directions"])
        distances = np.hypot(*(got - targets).T)
        assert np.all(distances <= np.array(c.row["errors_mm"]) + 1e-6)
        assert np.sum(distances**2) <= c.row["error_mm2"] + 1e-6
        assert c.row["input_angles"] == pytest.approx(angles, abs=1e-9)


def test_path_without_timing_recovers_a_closed_curve():
    targets = _known_path(range(0, 360, 45))
    result = run(task("path", points=targets.tolist(), closed=True, link_range=[5, 80], starts=1, generations=700,
                      seed=2))
    assert result.candidates[0].row["error_mm2"] < 1e-6


def test_a_seed_gives_identical_candidates_on_one_or_two_processes():
    raw = task("path", points=[[0, 0], [10, 2], [20, 8], [28, 18], [32, 30]], link_range=[4, 60], starts=2,
               generations=60, seed=11, candidates=2)
    once = run(raw).summary()["candidates"]
    again = run(raw, jobs=2).summary()["candidates"]
    assert json.dumps(once) == json.dumps(again)
    raw["task"]["seed"] = 12
    assert json.dumps(run(raw).summary()["candidates"]) != json.dumps(once)


def test_line6_contract_through_the_command(tmp_path):
    """The issue's task as written: summary.json best first with the fields a user draws the linkage from; each
    template analyses as written (`linkgen analyze --angle` at the crank's direction) through its targets, and
    `linkgen build` takes it."""
    from linkgen.cli import main

    out = tmp_path / "line6"
    result = CliRunner().invoke(main, ["synthesize", str(LINE6), "-o", str(out), "--set", "task.starts=1",
                                       "--set", "task.generations=200", "--set", "task.candidates=2"])
    assert result.exit_code == 0, result.output
    summary = json.loads((out / "summary.json").read_text())
    rows = summary["candidates"]
    assert rows and [r["error_mm2"] for r in rows] == sorted(r["error_mm2"] for r in rows)
    targets = np.array(tomllib.loads(LINE6.read_text())["task"]["points"], dtype=float)
    for row in rows:
        assert {"template", "error_mm2", "ground_pivots", "crank", "coupler", "rocker", "coupler_point",
                "input_angles"} <= set(row)
        assert row["input_angles"] == pytest.approx([30, 45, 60, 75, 90, 105], abs=1e-9)
        (x2, y2), (x4, y4) = row["ground_pivots"]
        assert math.hypot(x4 - x2, y4 - y2) == pytest.approx(row["ground"], rel=1e-12)
        assert all(5 - 1e-9 <= row[k] <= 60 + 1e-9 for k in ("ground", "crank", "coupler", "rocker"))
        # the coupler point from the drawing: A, B, P at the first target, by hand
        turn = math.atan2(y4 - y2, x4 - x2) + math.radians(row["input_angles"][0])
        a = np.array([x2, y2]) + row["crank"] * np.array([math.cos(turn), math.sin(turn)])
        got = []
        for k, angle in enumerate(row["input_directions"]):
            report = json.loads(CliRunner().invoke(main, [
                "analyze", str(out / row["template"]), "--angle", repr(angle), "--json", "-o", str(tmp_path / "a"),
                "--set", "output.formats=['json']"]).stdout)
            p = report["positions"]["joints"]["P"]
            got.append([p["x_mm"], p["y_mm"]])
            if k == 0:
                assert [report["positions"]["joints"]["A"][key] for key in ("x_mm", "y_mm")] == pytest.approx(a)
        assert np.sum((np.array(got) - targets) ** 2) == pytest.approx(row["error_mm2"], rel=1e-6, abs=1e-9)
    built = CliRunner().invoke(main, ["build", str(out / rows[0]["template"]), "-o", str(tmp_path / "b"),
                                      "--set", "output.formats=['json', 'dxf']"])
    assert built.exit_code == 0, built.output
    assert (tmp_path / "b" / rows[0]["template"].replace(".toml", "-sheet.dxf")).exists()


@pytest.mark.parametrize("figures", [False, True])
def test_python_api_writes_what_the_command_writes(tmp_path, figures):
    """The files written, figures only when asked; the command writes the same (``--figures`` or not)."""
    from linkgen.cli import main

    result = run(task("crank-rocker", swing=30.0, rocker=40.0, candidates=2))
    names = write_synthesis(result, tmp_path / "api", figures=figures)
    ends = (".toml", ".json") + (("-curve.png", "-curve.svg") if figures else ())
    assert sorted(names) == sorted(["summary.json", "summary.csv"] + [
        f"t-crank-rocker-{k}{end}" for k in (1, 2) for end in ends])
    assert sorted(p.name for p in (tmp_path / "api").iterdir()) == sorted(names)
    report = json.loads((tmp_path / "api" / "t-crank-rocker-1.json").read_text())
    assert report["synthesis"]["rank"] == 1 and report["inversion"] == "crank-rocker"
    template = tmp_path / "t.toml"
    template.write_text(tomllib_text(task("crank-rocker", swing=30.0, rocker=40.0, candidates=2)))
    flag = "--figures" if figures else "--no-figures"
    ran = CliRunner().invoke(main, ["synthesize", str(template), "-o", str(tmp_path / "cli"), flag])
    assert ran.exit_code == 0, ran.output
    assert sorted(p.name for p in (tmp_path / "cli").iterdir()) == sorted(names)


# ---------------------------------------------------------------------- bad tasks


@pytest.mark.parametrize("keys, message", [
    ({"kind": "path", "points": [[0, 0], [10, 0]]}, "task.points: a path needs 3 to 200 target points (got 2)"),
    ({"kind": "path", "points": [[0, 0], [10, 0], [20, 5]], "input_angles": [30, 30, 60]},
     "task.input_angles: items 0 and 1 give the same crank angle for two different points"),
    ({"kind": "path", "points": [[0, 0], [10, 0], [20, 5]], "input_angles": [30, 390, 60]},
     "task.input_angles: items 0 and 1 give the same crank angle"),
    ({"kind": "path", "points": [[0, 0], [10, 0], [20, 5]], "input_angles": [30, 60]},
     "task.input_angles: give one angle a point (3 points, got 2 angles)"),
    ({"kind": "path", "points": [[0, 0], [10, 0], [20, 5]], "input_angles": [30, 90, 60]},
     "task.input_angles: the crank must meet the points in order"),
    ({"kind": "crank-rocker", "swing": 40, "rocker": 50, "time_ratio": 0.5}, "task.time_ratio: must be >= 1"),
    ({"kind": "crank-rocker", "swing": 40, "rocker": 50, "time_ratio": 1.3, "ground": 2},
     "task.ground: no Grashof crank-rocker swings its rocker 40 degrees with time ratio 1.3 on a ground of 2 mm"),
    ({"kind": "slider-crank", "stroke": 50, "time_ratio": 1.5, "offset": 0}, "task.offset: a centred slider-crank"),
    ({"kind": "function", "function": "log10(x)", "x_range": [1, 10], "input_angles": [30, 30],
      "output_angles": [90, 180]}, "task.input_angles: the two angles are the same (30)"),
    ({"kind": "function", "function": "import os", "x_range": [1, 10], "input_angles": [30, 120],
      "output_angles": [90, 180]}, "task.function: cannot read"),
    ({"kind": "motion", "positions": [[0, 0, 0]]}, "task.positions: needs 2 or 3 positions"),
    ({"kind": "motion", "positions": [[0, 0, 0], [0, 0, 360]], "moving_pivots": [[1, 1], [5, 1]]},
     "task.positions: items 0 and 1 give the same pose"),
    ({"kind": "spiral"}, "task.kind: unknown value 'spiral'"),
    # issue 30: coordinates a template cannot hold (1e300 raised OverflowError in the search's penalty)
    ({"kind": "path", "points": [[1e300, 0], [0, 1e300], [1e300, 1e300]]},
     "task.points: item 0, [1e+300, 0], must lie within 10000 mm of the origin"),
    ({"kind": "path", "points": [[0, 0], [10, 2], [20, 8]], "ground_region": [[-1e300, -1], [1e300, 1]]},
     "task.ground_region: item 0, [-1e+300, -1], must lie within 10000 mm"),
    ({"kind": "motion", "positions": [[0, 0, 0], [40, 20, 30], [70, 55, 75]], "fixed_pivots": [[1e300, 0], [0, 5]]},
     "task.fixed_pivots: item 0, [1e+300, 0], must lie within 10000 mm"),
    ({"kind": "motion", "positions": [[0, 0, 0], [2e4, 20, 30], [70, 55, 75]]}, "task.positions: item 1, [20000, 20]"),
    ({"kind": "function", "table": [[0, 0], [1, 1e300], [2, 3]], "input_angles": [30, 120], "output_angles": [90, 180]},
     "task.table: every x and y must lie within +-1e+12"),
    ({"kind": "function", "function": "exp(x)", "x_range": [1, 700], "input_angles": [30, 120],
      "output_angles": [105, 165]}, "task.function: y must stay within +-1e+12 over the range (it reaches 3.78e+12)"),
    # the coupler range that made scipy's least squares warn
    ({"kind": "path", "points": [[0, 0], [10, 2], [20, 8]], "coupler_range": 1e300},
     "task.coupler_range: must be > 0 and <= 10000 mm (got 1e+300)"),
    # budgets: each bounded, the bound in the message (samples = 720 tried to allocate 1.96 TiB)
    ({"kind": "motion", "positions": [[0, 0, 0], [40, 20, 30], [70, 55, 75]], "samples": 720},
     "task.samples: must be >= 4 and <= 60 (got 720)"),
    ({"kind": "crank-rocker", "swing": 45, "rocker": 50, "samples": 100_000},
     "task.samples: must be >= 3 and <= 3600 (got 100000)"),
    ({"kind": "slider-crank", "stroke": 50, "samples": 100_000}, "task.samples: must be >= 3 and <= 3600"),
    ({"kind": "path", "points": [[0, 0], [10, 2], [20, 8]], "generations": 1_000_000},
     "task.generations: must be >= 1 and <= 10000 (got 1000000)"),
    ({"kind": "path", "points": [[0, 0], [10, 2], [20, 8]], "population": 1000},
     "task.population: must be >= 5 and <= 100 (got 1000)"),
    ({"kind": "path", "points": [[0, 0], [10, 2], [20, 8]], "starts": 1000}, "task.starts: must be >= 1 and <= 64"),
    ({"kind": "path", "points": [[0, 0], [10, 2], [20, 8]], "starts": 64, "generations": 10_000},
     "task.generations: starts x generations is 640000, at most 100000"),
    ({"kind": "path", "points": [[k, k * k % 7] for k in range(100)], "closed": True, "generations": 10_000,
      "starts": 1}, "task.generations: the search would make about 2.33e+09 design-target evaluations (starts x "
                    "(generations x population x 108 unknowns + 600 x 109^2 for the polish) x 100 points), at most "
                    "1.5e+08"),
    ({"kind": "path", "points": [[math.cos(k), math.sin(k)] for k in range(60)], "closed": True, "starts": 1,
      "generations": 10}, "task.generations: the search would make about 1.72e+08"),
    ({"kind": "path", "points": [[k, k * k % 7] for k in range(201)]}, "task.points: a path needs 3 to 200"),
    ({"kind": "function", "function": "x", "x_range": [1, 10], "input_angles": [30, 120], "output_angles": [90, 180],
      "precision_points": 1001}, "task.precision_points: must be >= 3 and <= 1000"),
    ({"kind": "crank-rocker", "swing": 45, "rocker": 50, "min_transmission": 90},
     "task.min_transmission: must be >= 0 and < 90 degrees (got 90)"),
    # refusals that named the candidate's keys (linkage.ground, linkage.rod, linkage.crank) name the task's
    ({"kind": "crank-rocker", "swing": 45, "rocker": 10_000},
     "task.rocker: none of the 722 linkages found has its ground, crank, coupler, rocker within [1e-06, 10000] mm"),
    ({"kind": "function", "function": "log10(x)", "x_range": [1, 10], "input_angles": [30, 120],
      "output_angles": [105, 165], "ground": 10_000}, "task.ground: the linkage through the precision points has"),
    # found by fuzzing after the issue: an OverflowError from a huge offset, a ZeroDivisionError from a tiny swing
    ({"kind": "slider-crank", "stroke": 100, "time_ratio": 1.3, "offset": -1e300},
     "task.offset: must be at most 10000 mm in size (got -1e+300)"),
    ({"kind": "crank-rocker", "swing": 1e-300, "rocker": 50}, "task.swing: must be >= 0.01 and < 180 degrees"),
])
def test_bad_tasks_are_one_line_exit_2_and_nothing_written(tmp_path, keys, message):
    refused_in_one_line(tmp_path, keys, message)


def refused_in_one_line(tmp_path, keys: dict, message: str) -> None:
    """``linkgen synthesize`` on the task ``keys``: exit 2, one line on stderr holding ``message``, nothing written."""
    from linkgen.cli import main

    template = tmp_path / "bad.toml"
    template.write_text(tomllib_text({"name": "bad", "task": keys}))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["synthesize", str(template), "-o", str(out)])
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and message in lines[0], lines
    assert not out.exists()


def test_a_path_ranks_its_error_weighed_against_its_transmission():
    """Each row's rank_score is its error times max(1, sin 40 degrees / sin of its worst transmission angle), worked
    out here, and the rows come in that order: both the error and the transmission angle are in every row."""
    result = run(task("path", points=[[20, 20], [20, 25], [20, 30], [20, 35], [20, 40], [20, 45]],
                      input_angles=[30, 45, 60, 75, 90, 105], link_range=[5, 60], starts=4, generations=200,
                      candidates=4, min_transmission=10))
    rows = [c.row for c in result.candidates]
    assert len(rows) >= 2
    for row in rows:
        weight = max(1.0, math.sin(math.radians(40)) / math.sin(math.radians(row["transmission_worst_deg"])))
        assert row["rank_score"] == pytest.approx(row["error_mm2"] * weight, rel=1e-12)
        assert row["transmission_worst_deg"] >= 10 - 1e-6
    assert [r["rank_score"] for r in rows] == sorted(r["rank_score"] for r in rows)


def test_a_binding_transmission_costs_a_path_candidate_its_rank():
    """Error 1.0 mm^2 at a worst transmission angle of 25 degrees weighs 1.0 x sin 40 / sin 25 = 1.521: a candidate
    of error 1.2 at 45 degrees (weight 1) ranks above it, one of error 1.6 does not."""
    from linkgen.synthesis.candidates import Candidate, ranked, weighed

    def made(error, gamma, k):
        return weighed(Candidate({}, {"error_mm2": error, "transmission_worst_deg": gamma}, error, (float(k),)))

    low = made(1.0, 25.0, 1)
    assert low.row["rank_score"] == pytest.approx(math.sin(math.radians(40)) / math.sin(math.radians(25)), rel=1e-12)
    assert low.row["rank_score"] == pytest.approx(1.521, abs=1e-3)
    assert [c.row["error_mm2"] for c in ranked([low, made(1.2, 45.0, 2)], 2)] == [1.2, 1.0]
    assert [c.row["error_mm2"] for c in ranked([low, made(1.6, 45.0, 2)], 2)] == [1.0, 1.6]


@pytest.mark.parametrize(("keys", "note"), [
    ({"kind": "slider-crank", "stroke": 100, "time_ratio": 1.5},
     "task.min_transmission: none of the 217 linkages found keeps its transmission angle at least 30 degrees"),
    ({"kind": "crank-rocker", "swing": 45, "rocker": 50, "min_transmission": 89},
     "task.min_transmission: none of the 722 linkages found keeps its transmission angle at least 89 degrees"),
    ({"kind": "motion", "positions": [[0, 0, 0], [40, 20, 30], [70, 55, 75]], "link_range": [15, 200],
      "min_transmission": 60}, "task.min_transmission: no defect-free four-bar through these positions keeps its "
                               "transmission angle at least 60 degrees"),
])
def test_the_impossible_gets_the_nearest_candidates_and_a_line_naming_the_limit(tmp_path, keys, note):
    """A requirement no linkage meets: exit 0, the candidates whose worst transmission angle comes nearest (the best
    first, the best the same task reaches with no limit; each as sampled here), and a note naming the limit."""
    from linkgen.cli import main

    template = tmp_path / "far.toml"
    template.write_text(tomllib_text({"name": "far", "task": keys}))
    result = CliRunner().invoke(main, ["synthesize", str(template), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    notes = [line for line in result.stdout.splitlines() if line.startswith("note: ")]
    assert len(notes) == 1 and notes[0].startswith(f"note: {note}"), notes
    rows = json.loads((tmp_path / "out" / "summary.json").read_text())["candidates"]
    worst = [row["transmission_worst_deg"] for row in rows]
    unlimited = run({"name": "free", "task": {**keys, "min_transmission": 0}}).candidates[0].row
    assert worst == sorted(worst, reverse=True) and worst[0] == pytest.approx(unlimited["transmission_worst_deg"],
                                                                              abs=1e-9)
    assert f"the best reaches {worst[0]:.4g}" in notes[0]
    for row in rows:
        if keys["kind"] != "slider-crank":
            assert sampled_transmission(row, np.linspace(0, 2 * math.pi, 36001)) == pytest.approx(
                row["transmission_worst_deg"], abs=1e-3)


def _bundled(path):
    """A bundled synthesis template as a parameter: a six-bar's search marked slow, the figure-eight's in the xdist
    group of the session's one search of it."""
    marks = [pytest.mark.slow] if tomllib.loads(path.read_text())["task"].get("linkage", "four-bar") != "four-bar" \
        else []
    return pytest.param(path, marks=marks + ([pytest.mark.xdist_group(FIGURE_EIGHT_GROUP)] if path == FIGURE_EIGHT
                                             else []))


@pytest.mark.parametrize("path", [_bundled(p) for p in sorted((ROOT / "templates").glob("synth-*.toml"))],
                         ids=lambda p: p.name)
def test_every_bundled_synthesis_template_gives_candidates(path, request):
    """Each bundled task as written (a four-bar path search on a small budget, 100 generations; the figure-eight's
    six-bar search at its own 300, the session's one search that tests/synthesis/test_figure_eight.py checks too)
    gives candidates whose reports are their own, and none binds: each keeps its transmission angle at least 30
    degrees over the motion it makes, as measured here from its template by sampling, and reports that worst
    angle."""
    from linkgen.synthesis import load_task

    keys = tomllib.loads(path.read_text())["task"]
    if path == FIGURE_EIGHT:
        result = request.getfixturevalue("figure_eight_found")
    else:
        result = synthesize(load_task(path, ["task.starts=1", "task.generations=100"] if keys["kind"] == "path"
                                      else []))
    assert result.candidates
    for c in result.candidates:
        assert c.report["name"] == c.name and c.row["template"] == f"{c.name}.toml"
        worst = template_transmission(c, keys)
        assert worst >= 30 - 1e-6, (c.name, worst)
        assert c.row["transmission_worst_deg"] >= 30 - 1e-9
        assert c.row["transmission_worst_deg"] == pytest.approx(worst, abs=2e-3)


# ---------------------------------------------------------------------- issue 30: limits, memory, warnings


def test_worst_transmission_over_an_arc_is_the_sampled_one():
    """The closed form over an arc (ends, and theta2 = 0 or 180 degrees where the arc holds them) against 20 001
    samples of the angle at B, for random four-bars and arcs either way round, some longer than a turn."""
    from linkgen.synthesis.geometry import worst_transmission

    rng = np.random.default_rng(30)
    for _ in range(300):
        lengths = dict(zip(("ground", "crank", "coupler", "rocker"), rng.uniform(5, 100, 4), strict=True))
        r1, r2, r3, r4 = lengths.values()
        if not abs(r3 - r4) + 1e-6 < min(abs(r1 - r2), r1 + r2) or max(abs(r1 - r2), r1 + r2) > r3 + r4 - 1e-6:
            continue                                    # only linkages that close over the whole turn
        start = rng.uniform(-10, 10)
        end = start + rng.uniform(-8, 8)
        got = math.degrees(float(worst_transmission(r1, r2, r3, r4, start, end)))
        assert got == pytest.approx(sampled_transmission(lengths, np.linspace(start, end, 20001)), abs=1e-4)


def test_a_path_search_keeps_the_transmission_limit_and_says_it_binds():
    """line6 on a small budget: the best candidate keeps 30 degrees over the whole turn (sampled here from its
    template), the limit binds and a line says so; a task asking more gets it, and one asking nothing may go lower."""
    keys = tomllib.loads(LINE6.read_text())["task"]
    for limit in (30, 50):
        result = run({"name": "l6", "task": {**keys, "starts": 1, "generations": 150, "candidates": 1,
                                             "min_transmission": limit}})
        c = result.candidates[0]
        assert template_transmission(c, keys) >= limit - 1e-6
        assert c.row["transmission_worst_deg"] == pytest.approx(template_transmission(c, keys), abs=2e-3)
        assert any(f"task.min_transmission (its transmission angle falls to the {limit} degrees allowed)" in line
                   for line in result.search["bound"]), result.search["bound"]
    free = run({"name": "l6", "task": {**keys, "starts": 1, "generations": 150, "candidates": 1,
                                       "min_transmission": 0}}).candidates[0]
    assert free.row["error_mm2"] < c.row["error_mm2"] and free.row["transmission_worst_deg"] < 30


def test_a_rocking_input_keeps_the_limit_over_its_travel():
    """Without a crank that turns fully the transmission angle is kept over the crank's travel from the first target
    (or position) to the last, the way it meets them: sampled here from each template."""
    targets = _known_path([20, 50, 80, 110, 140])
    keys = {"kind": "path", "points": targets.tolist(), "crank": False, "link_range": [5, 80]}
    for c in run({"name": "p", "task": {**keys, "starts": 1, "generations": 100, "candidates": 2}}).candidates:
        assert template_transmission(c, keys) >= 30 - 1e-6
        assert c.row["transmission_worst_deg"] == pytest.approx(template_transmission(c, keys), abs=2e-3)
    positions, _ = _poses([20, 100, 200])
    keys = {"kind": "motion", "positions": positions, "crank": False, "link_range": [5, 150], "samples": 12}
    result = run({"name": "m", "task": keys})
    assert result.candidates
    for c in result.candidates:
        assert template_transmission(c, keys) >= 30 - 1e-6
        assert c.row["transmission_worst_deg"] == pytest.approx(template_transmission(c, keys), abs=2e-3)


def test_motion_screen_memory_does_not_grow_with_the_pairs():
    """Three free positions screen about samples^4 / 2 pairs of dyads: block by block, so the peak memory (numpy's
    allocations, as tracemalloc sees them) stays about the same from 16 to 32 samples (16 times the pairs; a screen
    of all the pairs at once grew as samples^4: 3.5 GB at 60)."""
    import tracemalloc

    positions, _ = _poses([20, 100, 200])
    peaks = []
    for samples in (16, 32):
        spec = validate_task(task("motion", positions=positions, link_range=[5, 150], samples=samples))
        tracemalloc.start()
        try:
            from linkgen.synthesis import motion

            motion.solve(spec.task)
            peaks.append(tracemalloc.get_traced_memory()[1])
        finally:
            tracemalloc.stop()
    assert peaks[1] < 2 * peaks[0] and peaks[1] < 200 * 2**20, peaks


def _cli(tmp_path, keys: dict):
    """`linkgen synthesize` on a task, with every warning recorded; (result, warnings, output folder)."""
    import warnings

    from linkgen.cli import main

    template = tmp_path / "t.toml"
    template.write_text(tomllib_text({"name": "t", "task": keys}))
    out = tmp_path / "out"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = CliRunner().invoke(main, ["synthesize", str(template), "-o", str(out)])
    return result, [f"{w.category.__name__}: {w.message} ({w.filename})" for w in caught], out


@pytest.mark.parametrize("keys", [
    # matplotlib's "constrained_layout not applied" on a legend of 1,000 poses: the figure draws five
    {"kind": "function", "function": "log10(x)", "x_range": [1, 10], "input_angles": [30, 120],
     "output_angles": [105, 165], "precision_points": 1000},
    # scipy's overflow warnings from the polish with a huge coupler range: the largest allowed now
    {"kind": "path", "points": [[0, 0], [10, 2], [20, 8], [28, 18]], "coupler_range": 10_000, "starts": 1,
     "generations": 30, "candidates": 2},
    # candidates near the edge of what a template holds were refused as `linkage.joints.O2` / `O4`: now each is
    # kept within it
    {"kind": "motion", "positions": [[0, 0, 0], [9000, 2000, 30], [9999, 5500, 75]], "candidates": 2},
    {"kind": "path", "points": [[9000, 9000], [9990, 9000], [9999, 9999]], "starts": 1, "generations": 30},
], ids=["1000-precision-points", "coupler-range", "motion-at-the-edge", "path-at-the-edge"])
def test_no_raw_warning_and_templates_that_read_back(tmp_path, keys):
    result, warned, out = _cli(tmp_path, keys)
    assert result.exit_code == 0, result.output
    assert not warned and result.stderr == "", (warned, result.stderr)
    for template in out.glob("t-*.toml"):
        spec = validate_spec(tomllib.loads(template.read_text()))       # raises if a template cannot hold it
        assert spec.name == template.stem


def test_a_path_search_that_finds_nothing_names_a_field_of_the_task(tmp_path):
    """Ground pivots asked for far from the targets: no linkage reaches them; the refusal names a field of the task
    (was a DesignError naming none) and writes nothing."""
    keys = {**tomllib.loads(LINE6.read_text())["task"], "ground_region": [[500, 500], [501, 501]], "starts": 1,
            "generations": 40}
    result, warned, out = _cli(tmp_path, keys)
    assert result.exit_code == 2 and not warned
    line = result.stderr.strip()
    assert "\n" not in line and line.startswith(("error: task.coupler_range: no linkage found",
                                                 "error: task.ground_region: no linkage found")), line
    assert not out.exists()
