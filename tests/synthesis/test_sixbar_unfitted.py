"""A six-bar design that a dyad's margin or transmission angle already breaks is left unfitted where only the
constraint-keeping designs' errors are asked for (linkgen.synthesis.sixbar.errors, the Stephenson I seed grid's
scorer): the errors are those of fitting every design, to the bit, and the fit is skipped for the broken ones."""
from __future__ import annotations

import math

import numpy as np

from linkgen.synthesis import sixbar
from linkgen.synthesis.task import validate_task
from tests.synthesis.test_sixbar_types import KNOWN, task_of


def _designs(count: int, seed: int) -> np.ndarray:
    """The known Stephenson I normalised and ``count`` relatives of it, each joint moved by up to 0.15 ground
    lengths: some keep every constraint, some break a dyad's margin or transmission, some its links' lengths."""
    known = KNOWN["stephenson1"]
    x = np.array([v for name in sixbar.TOPOLOGIES["stephenson1"].free for v in known[name]]) / known["O4"][0]
    rng = np.random.default_rng(seed)
    return np.column_stack([x, x[:, None] + rng.uniform(-0.15, 0.15, (len(x), count))])


def test_errors_leave_the_broken_designs_unfitted_and_the_rest_as_fitted():
    p = sixbar.problem_of(validate_task(task_of("stephenson1", 16, False, 20, 5)).task)
    x = _designs(120, seed=5)
    fitted = sixbar.objective(x, p)                                  # every design fitted, as the search does
    assert np.array_equal(sixbar.errors(x, p), np.where(fitted < sixbar.BIG, fitted, math.inf))
    whole, skipped = sixbar.evaluate_many(x, p), sixbar.evaluate_many(x, p, fit_broken=False)
    dyads = np.all(skipped.rows[:, :-2 * len(sixbar.pairs(p.topology))] >= 0, axis=1)
    left = np.isnan(skipped.residuals).all(axis=1) & np.isfinite(whole.residuals).all(axis=1)
    assert np.array_equal(left, whole.linkage & ~dyads & np.isfinite(whole.residuals).all(axis=1))
    assert left.sum() > 5 and (dyads & whole.linkage).sum() > 5     # both kinds are among them
    keep = ~left
    assert np.array_equal(skipped.residuals[keep], whole.residuals[keep], equal_nan=True)
