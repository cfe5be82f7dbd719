"""Watt II and Stephenson I six-bar path synthesis, timed and untimed: a known Watt II's timed curve found again
below the best four-bar's error; each candidate's error re-evaluated by this test's own circle intersections
(timed: at its crank directions; untimed: to the nearest point of a dense curve); bad tasks refused in one line."""
from __future__ import annotations

import numpy as np
import pytest

from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.structure import Input, make_structure
from linkgen.synthesis import synthesize, validate_task
from linkgen.synthesis.sixbar_types import TOPOLOGIES
from tests.support.refusals import assert_refused_sets
from tests.support.six_bar_circles import circles, rigid, side

#: a known Watt II (the bundled watt2.toml's drawing, its tracer P moved onto the rod C-D) and a known Stephenson I
#: whose ternary crank turns fully (worst transmission 62.5 degrees), its tracer P on the rod E-G
KNOWN = {"watt2": {"O2": (0.0, 0.0), "O4": (120.0, 0.0), "O6": (200.0, 0.0), "A": (12.5, 21.650635095),
                   "B": (98.914459183, 71.974995439), "C": (132.815685308, 84.028317906),
                   "D": (249.565206829, 56.28756765), "P": (200.0, 110.0)},
         "stephenson1": {"O2": (0.0, 0.0), "O4": (100.0, 0.0), "A": (11.411356, 19.765048),
                         "B": (83.397415, 60.223124), "E": (-8.086376, 26.994672), "F": (144.55041, 2.09662),
                         "G": (103.777193, 75.563481), "P": (60.0, 95.0)}}


def curve_of(kind: str, degrees: np.ndarray) -> np.ndarray:
    """The known linkage's tracer (n, 2) at crank directions ``degrees``, by the general solver."""
    s = make_structure(KNOWN[kind], TOPOLOGIES[kind].links, TOPOLOGIES[kind].ground, (),
                       (Input("crank", "crank", "O2"),))
    return Linkage.of(s).solve(np.radians(degrees)[None, :], derivatives=False).points["P"]


def tracer(kind: str, joints: dict, directions: np.ndarray) -> np.ndarray:
    """P (n, 2) of a ``kind`` six-bar drawn at ``joints`` with its crank at world ``directions`` (rad), by hand:
    each dyad by the intersection of two circles on the side the drawing shows."""
    j = {k: np.array(v, dtype=float) for k, v in joints.items()}
    n = len(directions)
    o2, o4 = np.tile(j["O2"], (n, 1)), np.tile(j["O4"], (n, 1))
    a = o2 + np.linalg.norm(j["A"] - j["O2"]) * np.column_stack([np.cos(directions), np.sin(directions)])

    def dyad(p, q, pn, qn, x):
        return circles(p, np.linalg.norm(j[x] - j[pn]), q, np.linalg.norm(j[x] - j[qn]), side(j[pn], j[qn], j[x]))

    b = dyad(a, o4, "A", "O4", "B")
    if kind == "watt2":
        c = rigid(j["O4"], j["B"], j["C"], o4, b)
        d = dyad(c, np.tile(j["O6"], (n, 1)), "C", "O6", "D")
        return rigid(j["C"], j["D"], j["P"], c, d)
    e = rigid(j["O2"], j["A"], j["E"], o2, a)
    f = rigid(j["O4"], j["B"], j["F"], o4, b)
    g = dyad(e, f, "E", "F", "G")
    return rigid(j["E"], j["G"], j["P"], e, g)


def task_of(kind: str, n: int, timed: bool, generations: int, population: int) -> dict:
    first = float(np.degrees(np.arctan2(KNOWN[kind]["A"][1], KNOWN[kind]["A"][0])))
    angles = first + np.arange(n) * 360.0 / n
    task = {"kind": "path", "linkage": kind, "points": curve_of(kind, angles).tolist(), "seed": 1, "starts": 1,
            "generations": generations, "population": population, "candidates": 2}
    if timed:
        task["input_angles"] = angles.tolist()
    return {"name": kind, "task": task}


#: the four-bar of templates/stephenson3.toml (its coupler point C as P), drawn as the four-bar search draws a
#: candidate: O2, O4, A, B and P at the first target
FOUR = {"O2": (0.0, 0.0), "O4": (120.0, 0.0), "A": (12.5, 21.650635095), "B": (75.78826943, 78.392109807),
        "P": (104.570023599, -17.376416479)}


def four_bar_task(kind: str):
    """FOUR and the six-bar ``kind`` path problem of its twelve timed points of P (every 30 degrees from 60)."""
    from linkgen.synthesis.sixbar import problem_of

    s = make_structure(FOUR, {"crank": ("O2", "A"), "coupler": ("A", "B", "P"), "rocker": ("O4", "B")},
                       ("O2", "O4"), (), (Input("crank", "crank", "O2"),))
    angles = np.arange(60.0, 420.0, 30.0)
    targets = Linkage.of(s).solve(np.radians(angles)[None, :], derivatives=False).points["P"]
    spec = validate_task({"name": kind, "task": {"kind": "path", "linkage": kind, "points": targets.tolist(),
                                                 "input_angles": angles.tolist(), "starts": 1, "generations": 10}})
    return FOUR, problem_of(spec.task)


def nearest_error(kind: str, joints: dict, targets: np.ndarray) -> float:
    """The sum of squared distances (mm^2) from the targets to the nearest point of the curve, by this test's own
    curve: 36,000 crank directions, then 2,001 within one step either side of each target's nearest."""
    turn = np.linspace(0.0, 2 * np.pi, 36_000, endpoint=False)
    curve = tracer(kind, joints, turn)
    at = turn[np.argmin(np.sum((curve[None] - targets[:, None]) ** 2, axis=2), axis=1)]
    total = 0.0
    for k, t in enumerate(at):
        local = tracer(kind, joints, t + np.linspace(-1, 1, 2001) * (turn[1] - turn[0]))
        total += float(np.min(np.sum((local - targets[k]) ** 2, axis=1)))
    return total


def test_a_known_watt2_is_found_again_by_the_polish_from_near_it():
    """The known Watt II normalised (O2 at 0, O4 at 1) meets its twelve timed targets to rounding, and the
    search's polish (least squares on the distances) started from designs up to 5 % of the ground length off it in
    every coordinate meets them again to rounding (measured 1e-23 to 2e-21 mm^2 from 12 such starts; the designs
    it ends at differ from the known one by up to 0.08: the targets do not fix every joint of a Watt II). Each
    polished design, placed in the targets' frame, is checked by this test's own circle intersections at its crank
    directions, not by the search's evaluation."""
    from linkgen.synthesis.sixbar import _polish, evaluate, placed, problem_of

    spec = task_of("watt2", 12, True, 100, 15)
    p = problem_of(validate_task(spec).task)
    targets = np.array(spec["task"]["points"])
    known = KNOWN["watt2"]
    x = np.array([v for name in TOPOLOGIES["watt2"].free for v in known[name]]) / known["O4"][0]
    e = evaluate(x, p)
    assert np.all(e.rows >= 0) and np.max(np.abs(e.residuals)) < 1e-9
    rng = np.random.default_rng(0)
    for _ in range(6):
        polished, error = _polish(x + rng.uniform(-0.05, 0.05, x.shape), p)
        assert error < 1e-12
        got = placed(polished, p)
        assert got is not None
        joints, e = got
        directions = p.timing + np.angle(complex(e.uzt[1]))
        assert np.sum((tracer("watt2", joints, directions) - targets) ** 2) < 1e-12


@pytest.mark.slow
def test_a_watt2_search_from_twelve_timed_points_gives_a_sound_candidate():
    """Seed 1, one search of 100 generations, population 15 a number: the best candidate is a timed Watt II with no
    defects and a worst transmission angle of at least 30 degrees, each candidate's own circle intersections at its
    crank directions give the error its row reports, and the best four-bar on the same targets stays above 0.5
    mm^2 (1.21). How close this budget comes to the known design follows the optimiser's random
    stream: 1.9 to 79 mm^2 over seeds 1 to 6 with scipy 1.17 (an earlier scipy's seed 1 met it to rounding); the
    exact recovery is the polish's, tested above."""
    spec = task_of("watt2", 12, True, 100, 15)
    result = synthesize(validate_task(spec))
    best = result.candidates[0].row
    four = result.search["four_bar"]["error_mm2"]
    assert best["linkage"] == "watt2" and best["timed"] and best["defects"] == []
    assert 0.0 <= best["error_mm2"] < 1e3 and four > 0.5
    assert best["four_bar_error_mm2"] == four
    assert best["transmission_worst_deg"] >= 30.0
    targets = np.array(spec["task"]["points"])
    for c in result.candidates:
        p = tracer("watt2", c.row["joints"], np.radians(c.row["input_directions"]))
        assert np.sum((p - targets) ** 2) == pytest.approx(c.row["error_mm2"], rel=1e-6, abs=1e-6)


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["watt2", "stephenson1"])
def test_an_untimed_candidate_s_error_is_its_nearest_point_error(kind):
    """Untimed, a short search (20 generations, the four-bar's search beside it): each
    candidate's error is the sum of squared distances from the targets to the nearest point of its curve, as this
    test's own dense curve gives it (to 1e-6 relative), and its crank directions there put its tracer on those
    nearest points."""
    spec = task_of(kind, 16, False, 20, 5)
    result = synthesize(validate_task(spec))
    targets = np.array(spec["task"]["points"])
    assert result.candidates
    for c in result.candidates:
        row = c.row
        assert row["linkage"] == kind and not row["timed"]
        assert nearest_error(kind, row["joints"], targets) == pytest.approx(row["error_mm2"], rel=1e-6, abs=1e-6)
        reached = tracer(kind, row["joints"], np.radians(row["input_directions"]))
        assert np.sum((reached - targets) ** 2) == pytest.approx(row["error_mm2"], rel=1e-9, abs=1e-9)
        assert row["transmission_worst_deg"] >= 30.0


TEMPLATE = """name = "bad"
[task]
kind = "path"
linkage = "watt2"
starts = 1
generations = 100
points = {points}
"""


@pytest.mark.parametrize("sets, message", [
    (["task.linkage='stephenson4'"], "task.linkage"),
    (["task.points=[[0, 0], [10, 5], [20, 0], [10, -5]]", "task.input_angles=[0, 90, 180, 270]"],
     "task.points: linkage 'watt2' timed needs at least 8 targets"),
    (["task.linkage='stephenson1'"],
     "task.points: linkage 'stephenson1' untimed (no input_angles) needs at least 16 targets"),
])
def test_bad_six_bar_type_tasks_are_one_line_exit_2_and_nothing_written(tmp_path, sets, message):
    from linkgen.cli import main

    points = [[round(100 * float(np.cos(t)), 6), round(50 * float(np.sin(2 * t)), 6)]
              for t in np.linspace(0.0, 6.0, 10)]
    template = tmp_path / "bad.toml"
    template.write_text(TEMPLATE.format(points=points))
    assert_refused_sets(template, sets, message, tmp_path, main, "synthesize")


def test_the_best_four_bar_embedded_as_a_stephenson3_meets_its_targets_as_the_four_bar_does():
    """The four-bar of templates/stephenson3.toml (its coupler point C) drawn as the four-bar search draws a
    candidate (O2, O4, A, B and P at the first target): embedded as a Stephenson III with a dyad that keeps the
    search's constraints, the six-bar's tracer (fitted by least squares) meets the four-bar's twelve timed points of
    C to rounding, so the search that starts from it starts at the four-bar's error."""
    from linkgen.synthesis.sixbar import SHAPE_BOX, evaluate
    from linkgen.synthesis.sixbar_seed import embedded

    four, p = four_bar_task("stephenson3")
    x = embedded(four, "stephenson3", SHAPE_BOX, lambda v: bool(np.all(evaluate(v, p).rows >= 0)))
    assert x is not None
    # A, B and C of the drawing are the four-bar's, normalised to O2 at 0 and O4 at 1
    assert x[:6] == pytest.approx(np.array([v for k in ("A", "B", "P") for v in four[k]]) / 120.0, abs=1e-12)
    e = evaluate(x, p)
    assert np.max(np.abs(e.residuals)) < 1e-9
    assert embedded(four, "watt1", SHAPE_BOX, lambda v: True) is None


@pytest.mark.slow
def test_stephenson3_on_its_test_curve_is_no_worse_than_the_four_bar():
    """Twelve timed points of a tracer on the rod of templates/stephenson3.toml (drawn at (160, 10) mm), seed 1, one
    search of 100 generations: started from the best four-bar (0.448 mm^2), the Stephenson III found meets them to
    rounding (measured 1.6e-24 mm^2, as 50 and 150 generations do: 1.5e-24 and 2.1e-24; before the start from the
    four-bar 300 generations stopped at 18.9 mm^2)."""
    known = {"O2": (0.0, 0.0), "O4": (120.0, 0.0), "O6": (70.0, 100.0), "A": (12.5, 21.650635095),
             "B": (75.78826943, 78.392109807), "C": (104.570023599, -17.376416479),
             "D": (172.143781842, 75.676187982), "P": (160.0, 10.0)}
    s = make_structure(known, TOPOLOGIES["stephenson3"].links, TOPOLOGIES["stephenson3"].ground, (),
                       (Input("crank", "crank", "O2"),))
    angles = np.arange(60.0, 420.0, 30.0)
    points = Linkage.of(s).solve(np.radians(angles)[None, :], derivatives=False).points["P"]
    result = synthesize(validate_task({"name": "s3", "task": {
        "kind": "path", "linkage": "stephenson3", "points": points.tolist(), "input_angles": angles.tolist(),
        "seed": 1, "starts": 1, "generations": 100, "population": 15, "candidates": 2}}))
    four = result.search["four_bar"]["error_mm2"]
    best = result.candidates[0].row
    assert result.search["seeded_from_four_bar"]
    assert 0.4 < four < 0.5
    assert best["error_mm2"] <= four and best["error_mm2"] < 1e-6
    assert best["transmission_worst_deg"] >= 30.0


def test_the_known_stephenson1_is_a_design_of_error_zero_inside_the_search_s_box():
    """The known Stephenson I normalised (O2 at 0, O4 at 1) lies inside the search's box, keeps every hard
    constraint and meets its own twelve timed points to rounding: the search's design vector holds it."""
    from linkgen.synthesis.sixbar import SHAPE_BOX, evaluate, problem_of

    p = problem_of(validate_task(task_of("stephenson1", 12, True, 10, 5)).task)
    known = KNOWN["stephenson1"]
    x = np.array([v for name in TOPOLOGIES["stephenson1"].free for v in known[name]]) / known["O4"][0]
    assert np.all(np.abs(x) <= SHAPE_BOX)
    e = evaluate(x, p)
    assert np.all(e.rows >= 0)
    assert np.max(np.abs(e.residuals)) < 1e-9
    # the tracer's place fitted: P relative to the drawing, scaled back by the ground's 100 mm
    assert abs(e.uzt[1] - 100.0) < 1e-9


def test_the_best_four_bar_embedded_as_a_stephenson1_keeps_the_constraints_near_the_four_bar_s_error():
    """A four-bar drawn at its first target (O2, O4, A, B, P) embedded as a Stephenson I (its loop O2-E-G-F with
    F a short offset from O4 on a rocker a short crank barely swings): the design keeps every hard constraint and
    its error is within 1 mm^2 of the four-bar's own on its twelve timed points of P (the six-bar's tracer nearly
    the coupler curve); where every embedding breaks a constraint there is none."""
    from linkgen.synthesis.sixbar import SHAPE_BOX, errors, evaluate
    from linkgen.synthesis.sixbar_seed import embedded_stephenson1

    four, p = four_bar_task("stephenson1")
    x = embedded_stephenson1(four, SHAPE_BOX, p.lengths[0] / 120.0, lambda v: errors(v, p))
    assert x is not None
    e = evaluate(x, p)
    assert np.all(e.rows >= 0)
    assert float(np.sum(np.abs(e.residuals) ** 2)) < 1.0
    # E and G are the four-bar's crank and rocker pins, normalised
    assert x[4:6] == pytest.approx(np.array(four["A"]) / 120.0, abs=1e-12)
    assert x[8:10] == pytest.approx(np.array(four["B"]) / 120.0, abs=1e-12)
    assert embedded_stephenson1(four, SHAPE_BOX, p.lengths[0] / 120.0,
                                lambda v: np.full(v.shape[1], np.inf)) is None


@pytest.mark.slow
def test_a_known_stephenson1_s_timed_points_are_met_no_worse_than_by_the_four_bar():
    """Seed 1, one search of 200 generations, population 15, on twelve timed points of the known Stephenson I:
    started from the best four-bar embedded (35.4 mm^2; the embedding itself 31.0 mm^2), the best Stephenson I is
    no worse than the four-bar (measured 31.03 mm^2; before the embedded start the same budget stopped at 1614
    mm^2). The known linkage itself (error 0) is not found again in this budget: the differential evolution does
    not leave the embedding's basin. The candidate's own circle intersections give the error its row reports."""
    spec = task_of("stephenson1", 12, True, 200, 15)
    result = synthesize(validate_task(spec))
    best = result.candidates[0].row
    four = result.search["four_bar"]["error_mm2"]
    assert result.search["seeded_from_four_bar"]
    assert best["linkage"] == "stephenson1" and best["timed"] and best["defects"] == []
    assert 30.0 < four < 40.0
    assert best["error_mm2"] <= four
    assert best["transmission_worst_deg"] >= 30.0
    targets = np.array(spec["task"]["points"])
    for c in result.candidates:
        p = tracer("stephenson1", c.row["joints"], np.radians(c.row["input_directions"]))
        assert np.sum((p - targets) ** 2) == pytest.approx(c.row["error_mm2"], rel=1e-6, abs=1e-6)
