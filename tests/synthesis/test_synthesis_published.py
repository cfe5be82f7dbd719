"""Published path problems and Fourier-descriptor path synthesis, checked independently here.

Every error is re-evaluated in this file from the drawn numbers alone (pivots, lengths, coupler point as distance
and angle from the coupler line, assembly): A on the crank circle, B where the circles about A and O4 meet, the
coupler point off A -> B, on a dense grid of crank angles refined by a bounded scalar minimisation per target.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.optimize import minimize_scalar

from linkgen.cli import main
from linkgen.synthesis import fourier
from linkgen.synthesis.published import PROBLEMS, score, solve_row

BY_KEY = {p.key: p for p in PROBLEMS}


def drawn_curve(o2, o4, crank, coupler, rocker, point, assembly, theta):
    """The coupler points (m, 2) at crank angles ``theta`` from the ground line: circle intersections."""
    o2, o4 = np.asarray(o2, float), np.asarray(o4, float)
    ground = math.atan2(o4[1] - o2[1], o4[0] - o2[0])
    theta = np.atleast_1d(np.asarray(theta, float))
    a = o2 + crank * np.column_stack([np.cos(ground + theta), np.sin(ground + theta)])
    gap = o4 - a
    d = np.hypot(gap[:, 0], gap[:, 1])
    along = (coupler**2 - rocker**2 + d**2) / (2 * d)
    across = np.sqrt(coupler**2 - along**2) * (1.0 if assembly == "open" else -1.0)
    u = gap / d[:, None]
    b = a + along[:, None] * u + across[:, None] * np.column_stack([-u[:, 1], u[:, 0]])
    angle = np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0]) + math.radians(point[1])
    return a + point[0] * np.column_stack([np.cos(angle), np.sin(angle)])


def drawn_error(targets, *drawn):
    """The sum of squared distances from the targets to the nearest points of the whole curve (mm^2)."""
    grid = np.linspace(0.0, 2 * math.pi, 20_001)
    pts = drawn_curve(*drawn, grid)
    assert np.all(np.isfinite(pts)), "the crank must turn fully"
    step = grid[1] - grid[0]
    total = 0.0
    for q in targets:
        k = int(np.argmin(np.sum((pts - q) ** 2, axis=1)))
        best = minimize_scalar(lambda t, q=q: float(np.sum((drawn_curve(*drawn, t)[0] - q) ** 2)),
                               bounds=(grid[k] - step, grid[k] + step), method="bounded",
                               options={"xatol": 1e-12})
        total += min(best.fun, float(np.sum((pts[k] - q) ** 2)))
    return total


def paper_drawn(problem):
    """The paper's linkage in the drawn numbers above, straight from its published parameters (mm)."""
    p1x, p1y, a, l1, l2, l3, l4, l5, g = problem.linkage
    k = problem.scale
    o2 = (k * p1x, k * p1y)
    o4 = (k * (p1x + l1 * math.cos(a)), k * (p1y + l1 * math.sin(a)))
    return o2, o4, k * l2, k * l3, k * l4, (k * l5, math.degrees(g)), "open" if problem.circuit == 1 else "crossed"


def row_drawn(row):
    """A candidate's row in the drawn numbers above."""
    return (*row["ground_pivots"], row["crank"], row["coupler"], row["rocker"], row["coupler_point"], row["assembly"])


@pytest.mark.parametrize("key", sorted(BY_KEY))
def test_each_papers_linkage_is_recomputed_and_scored_by_the_metric(key):
    """The paper's linkage's curve from its own parameters here: a full turn of the crank, the same points as the
    package's design of it, and its error by the metric agreeing with the independent one (to 1e-9 relative).
    Kunjur and Krishnamurty's 18 points against Bulatovic et al.'s linkage: 49.60 mm^2 at 100 mm a unit, as the
    issue measured it (0.00496 in the paper's units)."""
    from linkgen.synthesis.geometry import place

    problem = BY_KEY[key]
    drawn = paper_drawn(problem)
    v, branch = problem.design()
    theta = np.linspace(0.0, 2 * math.pi, 721)
    ours = place(*v, branch, theta)
    np.testing.assert_allclose(np.column_stack([ours.px, ours.py]), drawn_curve(*drawn, theta), atol=1e-9)
    assert np.all(ours.out_of_reach == 0.0)
    independent = drawn_error(problem.targets(), *drawn)
    assert score(v, branch, problem.targets()) == pytest.approx(independent, rel=1e-9)
    if key == "mkh1":
        assert independent == pytest.approx(49.60, abs=0.01)


@pytest.fixture(scope="module")
def atlas_folder(shared_cache):
    """The run's one closed atlas for this module's syntheses (:func:`tests.conftest.shared_cache`)."""
    return str(shared_cache / "linkgen")


def _beats_the_paper(key, atlas_folder):
    problem = BY_KEY[key]
    row = solve_row(problem, atlas_folder)
    best = row["candidate"]
    independent = drawn_error(problem.targets(), *row_drawn(best))
    assert independent == pytest.approx(best["error_mm2"], rel=1e-6, abs=1e-9)
    paper = drawn_error(problem.targets(), *paper_drawn(problem))
    assert independent <= paper
    assert best["transmission_worst_deg"] >= row["min_transmission_deg"] - 1e-9
    return row


def test_ours_beats_kunjur_and_krishnamurty_18_points(atlas_folder):
    """Untimed, closed, 18 points: our best candidate, re-evaluated from its row, no worse than Bulatovic et al.'s
    linkage by the same metric (30.7 against 49.6 mm^2 when this was written); that linkage's transmission falls to
    24.6 degrees, so ours is held to 24."""
    row = _beats_the_paper("mkh1", atlas_folder)
    assert row["min_transmission_deg"] == 24


def test_ours_beats_yu_et_al_first_curve(atlas_folder):
    """Untimed, closed, 20 points: no worse than Yu et al.'s linkage (3.4 against 13.7 mm^2 when written)."""
    _beats_the_paper("yu1", atlas_folder)


@pytest.mark.slow
def test_ours_beats_bulatovic_25_points(atlas_folder):
    """Untimed, closed, 25 points: no worse than Bulatovic et al.'s linkage, whose transmission falls to 5.8 degrees
    (so ours may go to 5): the issue's curve where the evolution was 10.5 times worse."""
    _beats_the_paper("mkh3", atlas_folder)


# --- the Fourier descriptors ------------------------------------------------------------------------------------

def _shape(count=41):
    t = np.linspace(0.0, 2 * math.pi, count, endpoint=False)
    return np.column_stack([3 * np.cos(t) + 0.5 * np.cos(2 * t) + 0.3 * np.sin(3 * t),
                            np.sin(t) + 0.4 * np.sin(2 * t) - 0.2 * np.cos(3 * t)])


def _normalised(points, harmonics=10):
    centre, coeffs = fourier.coefficients(points, harmonics)
    return fourier.normalise(centre, coeffs)


@pytest.mark.parametrize("shift, turn, size, start", [((10.0, -4.0), 0.9, 2.5, 7), ((-300.0, 55.0), -2.6, 0.01, 23),
                                                       ((0.0, 0.0), math.pi, 40.0, 1)])
def test_normalised_descriptors_ignore_position_rotation_size_and_start(shift, turn, size, start):
    """The same curve moved, turned, scaled and started elsewhere has the same normalised coefficients (to 1e-9, in
    one of its two forms), and the similarity recovered in closed form is the one applied."""
    base = _shape()
    rot = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])
    moved = np.roll(base, start, axis=0) @ rot.T * size + np.array(shift)
    a, b = _normalised(base), _normalised(moved)
    forms = fourier.forms(b.coefficients)
    gaps = [float(np.max(np.abs(f - a.coefficients))) for f in forms]
    assert min(gaps) < 1e-9
    scale, angle, offset = fourier.similarity(b, a, bool(np.argmin(gaps)))
    assert float(scale) == pytest.approx(size, rel=1e-9)
    assert math.remainder(float(angle) - turn, 2 * math.pi) == pytest.approx(0.0, abs=1e-9)
    # the similarity takes the base curve's mean point onto the moved one's
    np.testing.assert_allclose(float(scale) * rot @ a.centre + offset, b.centre, atol=1e-9 * size)
    # traversed backwards, still the same coefficients
    back = _normalised(moved[::-1])
    assert min(float(np.max(np.abs(f - a.coefficients))) for f in fourier.forms(back.coefficients)) < 1e-9


def test_descriptors_of_a_circle_are_its_radius_and_centre():
    """A circle of radius 5 about (7, -3) as a 400-gon: the first harmonic normalised is (1, 0, 0, 1) (a circle run
    counter-clockwise), the others nearly 0, the scale its radius (the polygon's, to 1e-4), the centre its centre."""
    t = np.linspace(0.0, 2 * math.pi, 400, endpoint=False)
    n = _normalised(np.column_stack([7 + 5 * np.cos(t), -3 + 5 * np.sin(t)])[::-1], 4)
    np.testing.assert_allclose(n.coefficients[0], [1, 0, 0, 1], atol=1e-9)
    assert np.max(np.abs(n.coefficients[1:])) < 1e-9 and bool(n.reversed)
    assert float(n.scale) == pytest.approx(5.0, rel=1e-4)
    np.testing.assert_allclose(n.centre, [7, -3], atol=1e-9)


def test_fourier_synthesis_recovers_a_known_linkages_curve(atlas_folder):
    """Forty points of a known crank-rocker's coupler curve (not an atlas entry): the Fourier method's best candidate
    passes every one within 1e-8 of the curve's size, re-evaluated from its row."""
    from linkgen.synthesis import synthesize, validate_task

    drawn = ((10.0, 5.0), (10.0 + 72.0 * math.cos(0.3), 5.0 + 72.0 * math.sin(0.3)), 25.0, 66.0, 58.0, (48.0, 27.0),
             "open")
    targets = drawn_curve(*drawn, np.linspace(0.0, 2 * math.pi, 40, endpoint=False) + 0.2)
    size = float(np.max(np.ptp(targets, axis=0)))
    raw = {"name": "known", "task": {"kind": "path", "closed": True, "method": "fourier", "points": targets.tolist(),
                                     "atlas_folder": atlas_folder, "candidates": 1, "guesses": 4}}
    best = synthesize(validate_task(raw)).candidates[0].row
    assert math.sqrt(drawn_error(targets, *row_drawn(best))) <= 1e-8 * size


# --- bad input ----------------------------------------------------------------------------------------------------

def _refused(tmp_path, points, extra=""):
    template = tmp_path / "bad.toml"
    template.write_text(f'name = "bad"\n[task]\nkind = "path"\nmethod = "fourier"\nclosed = true\n'
                        f"points = {points}\n{extra}")
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["synthesize", str(template), "-o", str(out)])
    assert result.exit_code == 2, result.output
    lines = [x for x in result.output.splitlines() if x.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: ")
    assert not out.exists()
    return lines[0]


def test_fourier_method_refuses_too_few_points(tmp_path):
    line = _refused(tmp_path, "[[0, 0], [10, 0], [10, 10], [0, 10]]")
    assert line.startswith("error: task.points:") and "5 to 2000" in line


def test_fourier_method_refuses_duplicate_points(tmp_path):
    line = _refused(tmp_path, "[[0, 0], [10, 0], [10, 10], [5, 15], [0, 10], [10, 0]]")
    assert line.startswith("error: task.points:")


def test_fourier_method_refuses_a_self_crossing_curve(tmp_path):
    """A figure-eight's polygon crosses itself: the atlas holds no such curve."""
    line = _refused(tmp_path, "[[0, 0], [10, 10], [20, 0], [30, 10], [30, 0], [20, 10], [10, 0], [0, 10]]")
    assert line.startswith("error: task.points:") and "crosses itself" in line


def test_fourier_method_refuses_an_atlas_folder_it_cannot_write(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    line = _refused(tmp_path, "[[0, 0], [10, 0], [14, 8], [10, 16], [0, 16], [-4, 8]]",
                    f'atlas_folder = "{blocker / "atlas"}"\n')
    assert line.startswith("error: task.atlas_folder:") and str(blocker / "atlas") in line
    assert blocker.read_text() == "not a folder"


def test_the_default_atlas_folder_is_the_users_cache_and_refused_in_one_line(tmp_path, monkeypatch):
    """Without atlas_folder the atlas goes to $XDG_CACHE_HOME/linkgen; one that cannot be made is named, with how to
    choose another, and nothing is written."""
    from linkgen.synthesis.atlas import cache_folder

    blocker = tmp_path / "cache-file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker))
    assert cache_folder() == blocker / "linkgen"
    line = _refused(tmp_path, "[[0, 0], [10, 0], [14, 8], [10, 16], [0, 16], [-4, 8]]")
    assert line.startswith("error: task.atlas_folder:") and str(blocker / "linkgen") in line
    assert "XDG_CACHE_HOME" in line and blocker.read_text() == "not a folder"
