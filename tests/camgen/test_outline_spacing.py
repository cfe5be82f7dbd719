"""The outline's vertex spacing made for all stretches in one pass: each stretch's angles are those np.interp and
np.linspace give it alone, to the last bit, and a dwell's arcs are those drawn from its own angle."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.core.errors import DesignError
from camgen.bench import BASE
from camgen.outline import MAX_SEGMENT_VERTICES, _ranks, _spaced_all, exact_outline
from camgen.flat import build_cam
from camgen.spec import validate_spec


def _alone(aux: np.ndarray, cum: np.ndarray, factor: float) -> np.ndarray:
    """One stretch's angles, as the outline spaced them one stretch at a time: np.linspace over the counts, placed
    by np.interp (evenly spaced where it counts none)."""
    total = cum[-1]
    n = max(1, math.ceil(total * factor))
    if total <= 0:
        return np.linspace(aux[0], aux[-1], n + 1)
    return np.interp(np.linspace(0.0, total, n + 1), cum, aux)


@pytest.mark.parametrize("seed", range(6))
def test_all_stretches_at_once_are_each_spaced_alone(seed):
    rng = np.random.default_rng(seed)
    for _ in range(40):
        m, k = int(rng.integers(1, 9)), 65
        aux = np.sort(rng.uniform(-1.0, 4.0, (m, k)), axis=1)
        # densities with stretches of none (plateaus of the count), a stretch of no count at all, and large counts
        steps = rng.exponential(1.0, (m, k - 1)) * rng.integers(0, 2, (m, k - 1)) * rng.uniform(0, 80, (m, 1))
        steps[rng.integers(m)] = 0.0
        cum = np.zeros((m, k))
        cum[:, 1:] = np.cumsum(steps, axis=1)
        factor = rng.uniform(1.0, 3.0, m)
        theta, sizes = _spaced_all(list(range(m)), aux, cum, 0.01, factor)
        parts = np.split(theta, np.cumsum(sizes)[:-1])
        for j in range(m):
            expected = _alone(aux[j], cum[j], factor[j])
            assert parts[j].shape == expected.shape
            # the same numbers as np.interp's in the stretch alone (the outline is each stretch made alone)
            np.testing.assert_array_equal(parts[j], expected)


def test_the_first_stretch_past_the_vertex_bound_is_named():
    aux = np.tile(np.linspace(0.0, 1.0, 65), (3, 1))
    cum = np.tile(np.linspace(0.0, 1.0, 65), (3, 1)) * np.array([[10.0], [2.0 * MAX_SEGMENT_VERTICES], [1.0]])
    cum[2, 1:] = np.inf                                 # a curvature without bound, past the bound too
    with pytest.raises(DesignError, match=r"motion\[7\] would need 4e\+05 vertices .* \(at most 200000\)"):
        _spaced_all([3, 7, 9], aux, cum, 0.01, np.ones(3))


def test_ranks_are_each_items_group_and_place():
    group, place = _ranks(np.array([2, 0, 3, 1]))
    assert group.tolist() == [0, 0, 2, 2, 2, 3]
    assert place.tolist() == [0, 1, 0, 1, 2, 0]


def test_a_dwells_arcs_lie_on_its_circle_a_quarter_turn_at_most():
    """A dwell of 200 degrees at a lift of 10 mm: three arcs (ceil(200 / 90)), each bulge tan(angle / 4) of a third
    of 200 degrees, their vertices at the roller centre's distance from the cam centre, sqrt(e^2 + (d0 + 10)^2) with
    d0 = sqrt(Rp^2 - e^2) and Rp = 40 + 10 mm, less the roller's 10 mm; and the dwell of 60 degrees at the base
    radius is one arc at 40 mm."""
    spec = validate_spec({**BASE, "motion": [
        {"type": "rise", "law": "cycloidal", "lift": 10.0, "angle": 80.0}, {"type": "dwell", "angle": 200.0},
        {"type": "return", "law": "cycloidal", "lift": 10.0, "angle": 20.0}, {"type": "dwell", "angle": 60.0}]})
    outline = exact_outline(build_cam(spec), spec.output.tolerance)
    verts, bulges = outline.contour.vertices, np.abs(outline.contour.bulges)
    radius = np.hypot(verts[:, 0], verts[:, 1])
    top = math.hypot(5.0, math.sqrt(50.0**2 - 5.0**2) + 10.0) - 10.0
    high = np.abs(bulges - math.tan(math.radians(200.0 / 3) / 4)) < 1e-12
    low = np.abs(bulges - math.tan(math.radians(60.0) / 4)) < 1e-12
    assert high.sum() == 3 and low.sum() == 1
    np.testing.assert_allclose(radius[high], top, rtol=0, atol=1e-9)
    np.testing.assert_allclose(radius[low], 40.0, rtol=0, atol=1e-9)
    assert outline.max_error_mm <= spec.output.tolerance
