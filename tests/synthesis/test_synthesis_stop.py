"""The path search's stop: it triggers on a target whose optimum is known (a known four-bar's coupler points, the
search's record showing fewer generations than the budget), the starts stop once two agree, the same seed gives the
same result on one process and on two, and the rules themselves on made-up histories."""
from __future__ import annotations

import math

import numpy as np
import pytest

from linkgen.synthesis import synthesize, validate_task
from linkgen.synthesis.stop import Rule, agreed, distinct, run_starts, why_stop

#: a Grashof crank-rocker: ground 40, crank 10, coupler 35, rocker 30 mm, crank pivot (5, -3), ground line at 0.3 rad,
#: coupler point (15, 10) mm in the coupler's frame, the open assembly (B left of A -> O4)
KNOWN = {"x0": 5.0, "y0": -3.0, "theta0": 0.3, "r1": 40.0, "r2": 10.0, "r3": 35.0, "r4": 30.0, "cx": 15.0,
         "cy": 10.0}
ANGLES = [0.0, 50.0, 100.0, 150.0, 200.0, 250.0]


def _coupler_points(d: dict, degrees: list[float]) -> np.ndarray:
    """The coupler points (n, 2) mm by this test's own circle intersection: A on the crank, B where the circles
    about A (coupler) and O4 (rocker) meet, left of A -> O4."""
    o2 = np.array([d["x0"], d["y0"]])
    o4 = o2 + d["r1"] * np.array([math.cos(d["theta0"]), math.sin(d["theta0"])])
    out = []
    for deg in degrees:
        t = d["theta0"] + math.radians(deg)
        a = o2 + d["r2"] * np.array([math.cos(t), math.sin(t)])
        gap = o4 - a
        dist = float(np.hypot(*gap))
        along = (d["r3"] ** 2 - d["r4"] ** 2 + dist**2) / (2 * dist)
        up = math.sqrt(d["r3"] ** 2 - along**2)
        u = gap / dist
        b = a + along * u + up * np.array([-u[1], u[0]])
        e = (b - a) / d["r3"]
        out.append(a + d["cx"] * e + d["cy"] * np.array([-e[1], e[0]]))
    return np.array(out)


def _task(**more) -> dict:
    points = _coupler_points(KNOWN, ANGLES)
    return {"name": "known", "task": {"kind": "path", "points": points.tolist(),
                                      "input_angles": ANGLES,
                                      "crank": True, "link_range": [5, 60], "generations": 1500, "starts": 4,
                                      "seed": 3, "candidates": 1, **more}}


def test_the_known_linkages_own_points_are_what_the_test_computes():
    """The targets: the known linkage's crank turns fully (Grashof, crank shortest) and its points are distinct."""
    lengths = sorted([KNOWN["r1"], KNOWN["r2"], KNOWN["r3"], KNOWN["r4"]])
    assert lengths[0] == KNOWN["r2"] and lengths[0] + lengths[3] < lengths[1] + lengths[2]
    gaps = np.linalg.norm(_coupler_points(KNOWN, ANGLES)[:, None] - _coupler_points(KNOWN, ANGLES)[None], axis=-1)
    assert gaps[np.triu_indices(len(ANGLES), 1)].min() > 1.0


def test_the_stop_triggers_at_the_known_optimum():
    """The known linkage's points are met to 1e-8 mm^2, and every search stopped on its own (stall or collapse)
    before the budget of 1500 generations; the starts stopped once two agreed."""
    result = synthesize(validate_task(_task()))
    record = result.search
    assert result.candidates[0].row["error_mm2"] < 1e-8
    assert all(g < 1500 for g in record["generations_run"]), record["generations_run"]
    assert set(record["stopped"]) <= {"stall", "collapse"}
    assert record["starts_agreed"] and record["starts_run"] == len(record["generations_run"]) < 4


def test_the_same_seed_gives_the_same_result_on_one_process_and_on_two():
    raw = _task(generations=300, seed=5)
    first, again = synthesize(validate_task(raw)), synthesize(validate_task(raw), jobs=2)
    assert first.candidates[0].row == again.candidates[0].row
    for key in ("generations_run", "stopped", "starts_run", "designs_evaluated"):
        assert first.search[key] == again.search[key]


RULE = Rule(generations=5, rtol=1e-6, spread=1e-9, atol=1e-12)


@pytest.mark.parametrize(("best", "energies", "expected"), [
    ([10.0, 9.0, 8.0, 7.0, 6.0, 5.0, 4.0], [4.0, 9.0], None),             # still improving by 1 a generation
    ([5.0] * 5, [5.0, 9.0], None),                                         # too few generations to judge
    ([5.0] * 6 + [5.0 - 1e-4], [5.0, 9.0], None),                          # 1e-4 over 5 generations: > 5e-6
    ([5.0] * 6 + [5.0 - 1e-7], [5.0, 9.0], "stall"),                       # 1e-7 over 5 generations: < 5e-6
    ([5.0] * 2, [5.0, 5.0 + 1e-12], "collapse"),
    ([5.0] * 2, [5.0, math.inf], None),
])
def test_why_stop_follows_its_two_rules(best, energies, expected):
    assert why_stop(best, np.array(energies), RULE) == expected


def test_starts_are_cut_at_the_first_that_agrees_with_an_earlier_one():
    assert agreed([1.0, 2.0, 3.0], 0.0) is None
    assert agreed([1.0, 2.0, 1.0 + 1e-7, 2.0], 0.0) == 3
    assert agreed([math.inf, math.inf], 0.0) is None
    assert agreed([2.0, 1.0, 1.0 + 1e-3], 0.0) is None


def test_starts_go_on_until_they_hold_the_candidates_asked_for_and_are_cut_alike_in_any_batch():
    """Runs whose best errors are 3, 1, 1 (agreeing at the third) holding errors {3}, {1, 2}, {1}, {4}: one candidate
    asked for stops at the third start, three at the third too (1, 2, 3), four only at the fourth; the same runs are
    kept whatever the batch size."""
    held = {10: [3.0], 11: [1.0, 2.0], 12: [1.0], 13: [4.0]}

    def run(batch):
        return [{"seed": s, "found": [(None, 1.0, None, e) for e in held[s]]} for s in batch]

    assert distinct([1.0, 1.0 + 1e-9, 2.0, math.inf], 0.0) == 2
    for batch in (1, 2, 4):
        for wanted, kept, agree in ((1, 3, True), (3, 3, True), (4, 4, True), (5, 4, False)):
            done, stopped = run_starts(run, [10, 11, 12, 13], batch, 0.0, wanted)
            assert [r["seed"] for r in done] == [10, 11, 12, 13][:kept] and stopped == agree
