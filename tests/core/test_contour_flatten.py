"""`Contour.flatten` (all arcs' chords made at once): a contour of lines keeps its vertices; every arc's chord ends
lie on the arc's circle worked here from its bulge, in order from its start to its end, its chords' sagitta within
the tolerance, and each vertex of the contour stays where it was. `Contour.bounds` (all arcs' axis crossings at
once) holds every point of the arcs sampled densely, and no more than the sampling's sagitta beyond them."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.core.shapes import Contour


def test_a_contour_of_lines_flattens_to_its_vertices():
    square = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])
    assert np.array_equal(Contour(square).flatten(0.01), square)


def _circle(a: np.ndarray, b: np.ndarray, bulge: float) -> tuple[np.ndarray, float, float]:
    """The arc from ``a`` to ``b`` of ``bulge`` (tan of a quarter of its sweep, + counter-clockwise): its centre,
    radius and sweep (rad)."""
    sweep = 4 * math.atan(bulge)
    chord = b - a
    length = float(np.hypot(*chord))
    radius = length / (2 * abs(math.sin(sweep / 2)))
    middle = (a + b) / 2
    normal = np.array([-chord[1], chord[0]]) / length
    offset = (length / 2) / math.tan(sweep / 2)         # signed: the centre on the arc's inner side
    return middle + offset * normal, radius, sweep


@pytest.mark.parametrize("seed", range(4))
def test_each_arc_s_chords_lie_on_its_circle_within_the_tolerance(seed):
    rng = np.random.default_rng(seed)
    for _ in range(200):
        n = int(rng.integers(2, 10))
        vertices = rng.normal(size=(n, 2)) * 20
        bulges = rng.uniform(-1.5, 1.5, n) * (rng.random(n) < 0.6)
        bulges[np.abs(bulges) < 1e-3] = 0.0
        tolerance = float(10 ** rng.uniform(-3, -1))
        points = Contour(vertices, bulges).flatten(tolerance)
        at = [int(np.flatnonzero(np.all(points == v, axis=1))[0]) for v in vertices]
        assert at == sorted(at) and at[0] == 0                  # every vertex kept, in order
        ends = [*at[1:], len(points)]
        for k in range(n):
            run = points[at[k]:ends[k]]                         # vertex k and its arc's inner chord ends
            if bulges[k] == 0:
                assert len(run) == 1
                continue
            b = vertices[(k + 1) % n]
            centre, radius, sweep = _circle(vertices[k], b, float(bulges[k]))
            chain = np.vstack([run, b])
            assert np.allclose(np.hypot(*(chain - centre).T), radius, rtol=0, atol=1e-9 * max(radius, 1.0))
            turns = np.unwrap(np.arctan2(*(chain - centre).T[::-1]))
            steps = np.diff(turns)
            assert np.all(np.sign(steps) == np.sign(sweep))
            assert float(turns[-1] - turns[0]) == pytest.approx(sweep, abs=1e-9)
            assert float(np.max(radius * (1 - np.cos(np.abs(steps) / 2)))) <= tolerance * (1 + 1e-9)


@pytest.mark.parametrize("seed", range(2))
def test_bounds_are_the_arcs_and_vertices_extremes(seed):
    """`Contour.bounds` (every arc's axis crossings found at once) against each arc sampled at 20,001 angles from its
    circle worked here from the bulge: the box holds every sample (1e-9 mm), and each side is a sample's within the
    densest sampling's sagitta (radius x (1 - cos(half a step))), or a vertex's exactly; contours turned too."""
    rng = np.random.default_rng(100 + seed)
    for _ in range(100):
        n = int(rng.integers(2, 9))
        vertices = rng.normal(size=(n, 2)) * 20
        bulges = rng.uniform(-2.0, 2.0, n) * (rng.random(n) < 0.7)
        bulges[np.abs(bulges) < 1e-3] = 0.0
        contour = Contour(vertices, bulges).moved(float(rng.uniform(-4, 4)), np.zeros(2))
        samples, slack = [contour.vertices], 0.0
        for k in np.flatnonzero(contour.bulges):
            a, b = contour.vertices[k], contour.vertices[(k + 1) % n]
            centre, radius, sweep = _circle(a, b, float(contour.bulges[k]))
            start = math.atan2(a[1] - centre[1], a[0] - centre[0])
            turn = start + sweep * np.linspace(0.0, 1.0, 20001)
            samples.append(centre + radius * np.column_stack([np.cos(turn), np.sin(turn)]))
            slack = max(slack, radius * (1 - math.cos(abs(sweep) / 20000 / 2)))
        points = np.vstack(samples)
        x0, y0, x1, y1 = contour.bounds()
        low, high = points.min(axis=0), points.max(axis=0)
        assert np.all(np.array([x0, y0]) <= low + 1e-9) and np.all(np.array([x1, y1]) >= high - 1e-9)
        assert np.all(low - np.array([x0, y0]) <= slack + 1e-9) and np.all(np.array([x1, y1]) - high <= slack + 1e-9)
