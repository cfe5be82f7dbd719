"""The Fourier path synthesis' nearest points of many designs at once (linkgen.synthesis.fourier_path.nearest_many)
are each design's own: the batch gives every design, its branch and its span the angles and points it gets alone,
to the bit, so scoring the atlas's guesses together ranks them as one at a time did."""
from __future__ import annotations

import math

import numpy as np
import pytest

from linkgen.synthesis import fourier_path as F
from linkgen.synthesis.published import PROBLEMS

BY_KEY = {p.key: p for p in PROBLEMS}


def _designs(key: str, count: int, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The paper's linkage of ``key`` and ``count`` random relatives (lengths scaled by 0.6-1.4 each, the coupler
    point and the frame moved): some turn fully, some lock up part of the turn (poses out of reach), on both
    branches; and the problem's targets."""
    problem = BY_KEY[key]
    v, branch = problem.design()
    rng = np.random.default_rng(seed)
    scale = np.ones((count, 9))
    scale[:, 3:] = rng.uniform(0.6, 1.4, (count, 6))
    vs = v * scale
    vs[:, :3] += rng.normal(0.0, [5.0, 5.0, 0.3], (count, 3))
    branches = np.where(rng.random(count) < 0.5, branch, -branch)
    return np.vstack([v, vs]), np.r_[branch, branches], problem.targets()


@pytest.mark.parametrize("key", ["mkh1", "yu1"])
def test_many_designs_at_once_are_each_designs_own_to_the_bit(key):
    vs, branches, targets = _designs(key, 40, seed=7)
    th, pts = F.nearest_many(vs, branches, targets)
    locked = 0
    for k in range(len(vs)):
        alone_th, alone_pts = F.nearest(vs[k], float(branches[k]), targets)
        assert np.array_equal(th[k], alone_th) and np.array_equal(pts[k], alone_pts), k
        locked += bool(F._placed(vs[k].reshape(9, 1), branches[k], np.linspace(0, 2 * math.pi, 360))[1].any())
    assert 0 < locked < len(vs)                   # designs that lock up part of the turn are among them, not all
    # the paper's own linkage: its nearest points are its error's (the bench's score), within 1e-9 mm^2
    assert float(np.sum((pts[0] - targets) ** 2)) == pytest.approx(
        float(np.sum(F.errors(vs[0], float(branches[0]), targets, True, F.GRID)[0])), rel=1e-12)


def test_a_span_of_the_turn_is_searched_as_each_design_alone():
    """Over part of the turn (a crank that does not turn fully: the nearest points only on its travel) the batch
    keeps each design's search inside the span, as the design alone does."""
    vs, branches, targets = _designs("mkh1", 12, seed=3)
    span = (0.4, 3.9)
    th, pts = F.nearest_many(vs, branches, targets, F.GRID, span)
    assert (th >= span[0]).all() and (th <= span[1]).all()
    for k in range(len(vs)):
        alone = F.nearest(vs[k], float(branches[k]), targets, F.GRID, span)
        assert np.array_equal(th[k], alone[0]) and np.array_equal(pts[k], alone[1])


def test_the_guesses_errors_are_each_guess_errors_alone():
    """The atlas guesses' errors worked in blocks (of 32, here of 5 over 23 guesses: a short last block) are the
    errors each gets alone, to the bit; so the guesses polished are the same ones in the same order."""
    vs, branches, targets = _designs("yu1", 22, seed=11)
    first = [(0.0, v, float(b)) for v, b in zip(vs, branches, strict=True)]
    alone = [float(np.sum(F.errors(v, b, targets, True, F.GRID)[0])) for _, v, b in first]
    assert F.guess_errors(first, targets, block=5).tolist() == alone
    assert F.guess_errors(first, targets).tolist() == alone
