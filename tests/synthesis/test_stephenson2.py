"""Stephenson II path synthesis (``task.linkage = "stephenson2"``): the vectorised triad solver against the general
solver over a turn; its transmission angle against the four-bar's where the triad is one; a known Stephenson II's
twelve timed points met far below the best four-bar's error, the candidate re-evaluated by this test's own Newton
continuation of the triad and built by ``linkgen build``; bad tasks refused in one line."""
from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner

from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.structure import Input, make_structure
from linkgen.synthesis import synthesize, validate_task, write_synthesis
from linkgen.synthesis.sixbar_triad import Triad, solve, transmission
from linkgen.synthesis.sixbar_types import STEPHENSON2
from tests.support.refusals import assert_refused_sets

#: a known Stephenson II (ground 100 mm): the ternary crank O2-A-E, the plate C-D-F held by the rods A-C, E-D and the
#: rocker O4-F, the tracer P on the plate; its crank turns fully, its triad's worst transmission angle 63.4 degrees
KNOWN = {"O2": (0.0, 0.0), "O4": (100.0, 0.0), "A": (149.007533, 124.992142), "E": (-198.567461, -189.709634),
         "C": (-196.226274, 195.338795), "D": (-178.521183, 73.801314), "F": (-128.356821, -14.56487),
         "P": (-167.701426, 84.858413)}


def general(joints: dict) -> Linkage:
    s = make_structure(joints, STEPHENSON2.links, STEPHENSON2.ground, (), (Input("crank", "crank", "O2"),))
    return Linkage.of(s)


def triad_of(joints: dict) -> Triad:
    return Triad(*(np.array([complex(*joints[k])]) for k in ("A", "E", "C", "D", "F", "O4")))


def first_direction(joints: dict) -> float:
    return math.atan2(joints["A"][1] - joints["O2"][1], joints["A"][0] - joints["O2"][0])


def test_the_triad_solver_matches_the_general_solver_over_a_turn():
    """The known Stephenson II at 3,600 crank angles (every 0.1 degree from the drawing): the plate's pins C, D, F by
    the triad solver within 1e-9 mm of the general solver's (its Newton continuation of the class-III group)."""
    turns = np.linspace(0.0, 2 * np.pi, 3600, endpoint=False)
    sol = solve(triad_of(KNOWN), turns)
    placed = general(KNOWN).solve((first_direction(KNOWN) + turns)[None, :], derivatives=False).points
    assert sol.clean[0]
    for name in "CDF":
        got = getattr(sol, name.lower())[0]
        assert np.max(np.abs(got - (placed[name][:, 0] + 1j * placed[name][:, 1]))) < 1e-9
    assert np.degrees(sol.transmission.min()) == pytest.approx(63.4, abs=0.05)


def test_a_triad_that_cannot_follow_the_crank_s_turn_is_refused_as_the_general_solver_finds():
    """The known drawing with its rocker's pivot O4 moved to (150, 0) or (-100, 0) mm: the general solver finds the
    crank stops (a range); the triad solver refuses both designs (not clean), the known one beside them in the same
    call kept (as it is with O4 moved to (20, 0), which the general solver finds turns fully)."""
    moved = [{**KNOWN, "O4": o4} for o4 in ((150.0, 0.0), (-100.0, 0.0), (20.0, 0.0))]
    assert [general(m).ranges is not None for m in moved] == [True, True, False]
    every = [triad_of(j) for j in (*moved, KNOWN)]
    t = Triad(*(np.concatenate([getattr(b, k) for b in every]) for k in ("a", "e", "c", "d", "f", "o4")))
    assert solve(t, np.linspace(0.0, 2 * np.pi, 72, endpoint=False)).clean.tolist() == [False, False, True, True]


def test_the_triad_s_transmission_angle_is_the_four_bar_s_where_two_binaries_meet():
    """Two binaries meeting at the plate's pin Q (the lines of the rods E-D and O4-F through it): the third binary's
    angle is the four-bar's, between the rod A-C and the plate's side C-Q (here 60 degrees; the other two 90); where
    the three lines meet in one point (the rod A-C turned onto C-Q, the rocker onto 45 degrees) the triad toggles
    (0)."""
    q = 50 + 50j
    c = q + 40                                          # the plate's side Q-C along +X
    a = c + 30 * np.exp(1j * np.radians(60.0))          # the rod A-C at 60 degrees to it
    mu = transmission(np.array([a]), np.array([q + 20j]), np.array([q - 30]), np.array([c]), np.array([q]),
                      np.array([q]))
    assert np.degrees(mu[0]) == pytest.approx(60.0, abs=1e-9)
    toggled = transmission(np.array([c + 10]), np.array([q + 20j]), np.array([q - 30 - 30j]), np.array([c]),
                           np.array([q]), np.array([q]))
    assert toggled[0] == pytest.approx(0.0, abs=1e-9)


def newton_tracer(joints: dict, directions: np.ndarray) -> np.ndarray:
    """P (n, 2) of a Stephenson II drawn at ``joints`` with its crank at world ``directions`` (rad, in the order the
    crank turns from the drawing), by this test's own continuation: the plate's pose (turn, F) by Newton's method on
    the three binaries' lengths, in steps of at most half a degree of the crank from the drawing."""
    j = {k: complex(*v) for k, v in joints.items()}
    l1, l2, l3 = abs(j["C"] - j["A"]), abs(j["D"] - j["E"]), abs(j["F"] - j["O4"])
    c, d, p = j["C"] - j["F"], j["D"] - j["F"], j["P"] - j["F"]
    start = first_direction(joints)

    def closure(q: np.ndarray, turn: float) -> np.ndarray:
        spin, rot, f = np.exp(1j * turn), np.exp(1j * q[0]), q[1] + 1j * q[2]
        a, e = (j["A"] - j["O2"]) * spin + j["O2"], (j["E"] - j["O2"]) * spin + j["O2"]
        return np.array([abs(f + rot * c - a) - l1, abs(f + rot * d - e) - l2, abs(f - j["O4"]) - l3])

    q, at, out = np.array([0.0, j["F"].real, j["F"].imag]), 0.0, []
    for target in np.mod(np.asarray(directions) - start, 2 * np.pi):
        for turn in np.linspace(at, target, max(2, int(np.degrees(target - at) / 0.5) + 2))[1:]:
            for _ in range(30):
                r = closure(q, turn)
                jac = np.column_stack([(closure(q + 1e-7 * e, turn) - r) / 1e-7 for e in np.eye(3)])
                q = q - np.linalg.solve(jac, r)
                if np.max(np.abs(r)) < 1e-11:
                    break
        at = target
        w = q[1] + 1j * q[2] + np.exp(1j * q[0]) * p
        out.append((w.real, w.imag))
    return np.array(out)


def known_task(generations: int) -> dict:
    first = math.degrees(first_direction(KNOWN))
    angles = first + np.arange(12) * 30.0
    points = general(KNOWN).solve(np.radians(angles)[None, :], derivatives=False).points["P"]
    return {"name": "s2", "task": {"kind": "path", "linkage": "stephenson2", "points": points.tolist(),
                                   "input_angles": angles.tolist(), "seed": 1, "starts": 1,
                                   "generations": generations, "population": 15, "candidates": 2}}


@pytest.mark.slow
def test_a_known_stephenson2_s_timed_points_are_met_far_below_the_best_four_bar(tmp_path):
    """Seed 1, one search of 60 generations, population 15 a number, from the box (no start given; about 8 s of
    CPU): the best Stephenson II meets the known one's twelve timed points to 1.377 mm^2 (measured; 100 and 250
    generations stop there too) where the best four-bar on the same targets and budget stays at 8144 mm^2. The known
    linkage itself (error 0) is not found from this seed: the search's best designs all polish into the basin of
    1.377 mm^2 (from other seeds the polish of some reaches 1e-24). Each candidate's error is what this test's own
    continuation of its triad gives at its crank directions; the first is written and `linkgen build` builds it."""
    from linkgen.cli import main

    spec = known_task(60)
    result = synthesize(validate_task(spec))
    best = result.candidates[0].row
    four = result.search["four_bar"]["error_mm2"]
    assert best["linkage"] == "stephenson2" and best["timed"] and best["defects"] == []
    assert best["four_bar_error_mm2"] == four
    assert best["error_mm2"] < 1.5 and four > 5000.0
    assert best["transmission_worst_deg"] >= 30.0
    targets = np.array(spec["task"]["points"])
    for c in result.candidates:
        reached = newton_tracer(c.row["joints"], np.radians(c.row["input_directions"]))
        assert np.sum((reached - targets) ** 2) == pytest.approx(c.row["error_mm2"], rel=1e-6, abs=1e-6)
    write_synthesis(result, tmp_path / "out")
    name = result.candidates[0].name
    built = CliRunner().invoke(main, ["build", str(tmp_path / "out" / f"{name}.toml"), "-o", str(tmp_path / "b"),
                                      "--set", "output.formats=['json', 'dxf']"])
    assert built.exit_code == 0, built.output
    assert (tmp_path / "b" / f"{name}-sheet.dxf").exists()


#: ten targets on a figure-eight (mm), and a Stephenson II task on them with too few generations to matter
POINTS = [[round(100 * math.cos(t), 6), round(50 * math.sin(2 * t), 6)] for t in np.linspace(0.0, 6.0, 10)]
TEMPLATE = f"""name = "bad"
[task]
kind = "path"
linkage = "stephenson2"
starts = 1
generations = 10
points = {POINTS}
"""


@pytest.mark.parametrize("sets, message", [
    ([], "task.input_angles: linkage 'stephenson2' is searched timed only"),
    (["task.points=[[0, 0], [10, 5], [20, 0], [10, -5]]", "task.input_angles=[0, 90, 180, 270]"],
     "task.points: linkage 'stephenson2' timed needs at least 8 targets"),
    (["task.input_angles=[0, 30, 60, 90, 120, 150, 180, 210, 240, 270]", "task.crank=false"], "task.crank: linkage"),
])
def test_bad_stephenson2_tasks_are_one_line_exit_2_and_nothing_written(tmp_path, sets, message):
    from linkgen.cli import main

    (tmp_path / "bad.toml").write_text(TEMPLATE)
    assert_refused_sets(tmp_path / "bad.toml", sets, message, tmp_path, main, "synthesize")
