"""A figure-eight that a six-bar makes and no four-bar makes well (issue 36 item 3): templates/synth-figure-eight.toml's
twelve timed points are the tracer of a known Watt I, whose curve this test draws by its own circle intersections and
finds to cross itself once, its two loops turning opposite ways; the six-bar search meets them to the points' rounding
where the best four-bar on the same targets and budget stays some 20 mm^2 off, both errors re-evaluated here from the
candidates' joints."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from tests.support.six_bar_circles import four_bar_tracer, watt1_joints, watt1_tracer, watt1_worst_transmission

from tests.synthesis.conftest import FIGURE_EIGHT as TEMPLATE, FIGURE_EIGHT_GROUP
#: the known Watt I: the crank-rocker O2-A-B-O4 (crank 25 mm at 60 degrees), the ternary coupler A-B-E and rocker
#: O4-B-F, the dyad E-G-F, the tracer P on the output F-G (mm)
KNOWN = {"O2": (0.0, 0.0), "O4": (125.0, 0.0), "A": (12.5, 21.650635095), "B": (28.667, 87.921), "E": (79.504, 4.1),
         "F": (193.126, 47.582), "G": (146.195, 106.298), "P": (153.114, 25.41)}
#: the points' rounding in the template (mm): each coordinate to 1e-3
ROUNDING = 5e-4


def _task() -> dict:
    return tomllib.loads(TEMPLATE.read_text())["task"]


def _directions(degrees: list[float]) -> np.ndarray:
    """The crank's world directions (rad) at the crank angles ``degrees``: the ground line O2 -> O4 lies on +X."""
    return np.radians(np.array(degrees, dtype=float))


def _crossings(curve: np.ndarray) -> list[tuple[int, int]]:
    """The pairs (i, j), i < j, of edges of the closed polygon ``curve`` (m, 2) that cross, adjacent edges left out."""
    a, d = curve, np.roll(curve, -1, axis=0) - curve
    m = len(curve)
    out = []
    for i in range(m):
        den = d[i, 0] * d[:, 1] - d[i, 1] * d[:, 0]
        gap = a - a[i]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (gap[:, 0] * d[:, 1] - gap[:, 1] * d[:, 0]) / den
            u = (gap[:, 0] * d[i, 1] - gap[:, 1] * d[i, 0]) / den
        j = np.arange(m)
        hit = (t > 0) & (t < 1) & (u > 0) & (u < 1) & (j > i + 1) & ~((i == 0) & (j == m - 1))
        out += [(i, int(k)) for k in np.nonzero(hit)[0]]
    return out


def _area(loop: np.ndarray) -> float:
    """The signed area (mm^2, counter-clockwise positive) of the closed polygon ``loop``."""
    x, y = loop[:, 0], loop[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def test_the_templates_points_are_the_known_watt1s_figure_eight():
    """The template's points are the known Watt I's tracer at its crank angles, to their rounding; over a turn
    (3600 crank angles) its curve crosses itself once and the two loops turn opposite ways, each at least a fifth
    of the other's area (measured: 69 and 118 mm^2 about, in a curve 32 mm across); its transmission angles (at B
    between the coupler and the rocker, at G between the rod and the output) stay above 45 degrees."""
    task = _task()
    targets = np.array(task["points"])
    reached = watt1_tracer(KNOWN, _directions(task["input_angles"]))
    assert np.max(np.abs(reached - targets)) <= ROUNDING + 1e-9
    turn = math.radians(60.0) + np.linspace(0.0, 2 * math.pi, 3600, endpoint=False)
    curve = watt1_joints(KNOWN, turn)["P"]
    [(i, j)] = _crossings(curve)
    first, second = _area(curve[i + 1:j + 1]), _area(np.vstack([curve[j + 1:], curve[:i + 1]]))
    assert first * second < 0
    assert min(abs(first), abs(second)) > 0.2 * max(abs(first), abs(second))
    assert 25.0 < float(np.max(np.ptp(curve, axis=0))) < 40.0
    assert watt1_worst_transmission(KNOWN, turn) > 45.0
    # the known linkage meets the points to their rounding: the least error a search can reach, about
    assert float(np.sum((reached - targets) ** 2)) < len(targets) * 2 * ROUNDING**2


@pytest.fixture
def found(figure_eight_found):
    """The bundled task with one start, searched once a session (tests/synthesis/conftest.py)."""
    return figure_eight_found


@pytest.mark.slow
@pytest.mark.xdist_group(FIGURE_EIGHT_GROUP)                # one worker: the session's search runs once
def test_the_six_bar_beats_the_best_four_bar_on_the_figure_eight_by_a_large_factor(found):
    """The bundled task with one start (seed 1, 300 generations; about 5 s of CPU): the Watt I found meets the
    twelve points to their rounding (measured 4.98e-7 mm^2, as the task itself gives) where the best four-bar on
    the same targets, timing, seed and budget stays at 18.85 mm^2, a factor above 1e6 (3.8e7); both errors are the
    test's own, from each linkage's joints by circle intersections at the crank directions its row reports, and
    so is the Watt I's worst transmission angle over a turn (measured 49.3 degrees)."""
    task = _task()
    targets = np.array(task["points"])
    best = found.candidates[0].row
    four = found.search["four_bar"]
    six = float(np.sum((watt1_tracer(best["joints"], np.radians(best["input_directions"])) - targets) ** 2))
    fourbar = float(np.sum((four_bar_tracer(four["joints"], np.radians(four["input_directions"])) - targets) ** 2))
    assert six == pytest.approx(best["error_mm2"], rel=1e-6, abs=1e-9)
    assert fourbar == pytest.approx(four["error_mm2"], rel=1e-9)
    assert best["linkage"] == "watt1" and best["defects"] == [] and best["transmission_worst_deg"] >= 30.0
    drawn = math.radians(best["input_directions"][0])
    assert watt1_worst_transmission(best["joints"], drawn + np.linspace(0, 2 * math.pi, 36001)) == pytest.approx(
        best["transmission_worst_deg"], abs=2e-3)
    assert six < len(targets) * 2 * ROUNDING**2 and fourbar > 10.0
    assert fourbar / six > 1e6
    assert best["four_bar_error_mm2"] == four["error_mm2"]


@pytest.mark.slow
@pytest.mark.xdist_group(FIGURE_EIGHT_GROUP)                # one worker: the session's search runs once
def test_the_figure_eight_search_s_record_counts_its_designs(found):
    """One start of the bundled task: its record says how many generations it ran and why it stopped, and counts
    the designs it evaluated, 150 a generation (population 15 a number of the drawing's 10) and the first
    population's."""
    record = found.search
    assert record["starts_run"] == 1 and not record["starts_agreed"]
    assert len(record["generations_run"]) == len(record["stopped"]) == 1
    assert record["generations_run"][0] <= 300 and record["stopped"][0] in ("stall", "collapse", "budget")
    assert record["designs_evaluated"] == (record["generations_run"][0] + 1) * 150 == record["vectorised_calls"] * 150
