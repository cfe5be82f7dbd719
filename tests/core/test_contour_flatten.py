"""`Contour.flatten` (all arcs' chords made at once): a contour of lines keeps its vertices; every arc's chord ends
lie on the arc's circle worked here from its bulge, in order from its start to its end, its chords' sagitta within
the tolerance, and each vertex of the contour stays where it was."""
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
