"""When a path search stops: a differential evolution's stall or collapse, and the starts' agreement.

scipy's own test (the standard deviation of the population's energies at most ``tol`` times their
mean) never triggers on a constrained path task: the designs breaking a hard constraint sit at
BIG (1 + violation) (:mod:`linkgen.synthesis.path`), so the spread stays huge to the last
generation. Two tests that do trigger replace it, checked after every generation:

* **stall**: the population's best energy E (mm^2) has improved by no more than
  ``STALL_RTOL * E + atol`` over the last ``STALL_GENERATIONS`` generations;
* **collapse**: the whole population's energies lie within ``SPREAD_RTOL * E + atol`` of the best
  (every member feasible, all at one optimum).

``atol`` is ``ATOL_RELATIVE * scale^2`` (scale the lengths' scale, mm), so that a target a
linkage meets exactly (E -> 0) stops too. The polish that follows each search (least squares on
the distances) finishes the optimum, so the search needs only to have found its basin.

The **starts** (independent seeded searches) stop once two of them agree (their best polished
errors within ``AGREE_RTOL`` relative, plus ``atol``, of each other) and the starts run hold as
many designs of distinct errors as the candidates asked for. They are run in batches of the
processes at hand and cut at the first start where both hold, so the result is the same on one
process, several or a cluster.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

#: generations K over which the best must improve, and by how much relative to itself
STALL_GENERATIONS, STALL_RTOL = 50, 1e-5
#: the population's energies within this (relative to the best) of the best: collapsed
SPREAD_RTOL = 1e-9
#: the absolute tolerance of both, times the lengths' scale squared (mm^2)
ATOL_RELATIVE = 1e-14
#: two starts whose best polished errors agree to this (relative) stop the starts
AGREE_RTOL = 1e-6


@dataclass(frozen=True)
class Rule:
    """The stop of one search: stall over ``generations`` by ``rtol``, collapse by ``spread``, absolute ``atol``
    (mm^2)."""

    generations: int
    rtol: float
    spread: float
    atol: float


def rule_for(scale: float) -> Rule:
    """The stop for a task whose lengths' scale is ``scale`` (mm)."""
    return Rule(STALL_GENERATIONS, STALL_RTOL, SPREAD_RTOL, ATOL_RELATIVE * scale**2)


def why_stop(best: Sequence[float], energies: np.ndarray, rule: Rule) -> str | None:
    """Why a search should stop after the generations whose best energies are ``best`` (one a generation, oldest
    first; mm^2) with its population's energies now ``energies``: "stall", "collapse" or None (go on)."""
    now = best[-1]
    if len(best) > rule.generations and best[-1 - rule.generations] - now <= rule.rtol * abs(now) + rule.atol:
        return "stall"
    if np.all(np.isfinite(energies)) and float(np.max(energies)) - now <= rule.spread * abs(now) + rule.atol:
        return "collapse"
    return None


def agreed(errors: Sequence[float], atol: float) -> int | None:
    """The count of starts to keep, given each start's best polished error in order (mm^2; inf where it found
    nothing): the first k whose k-th agrees with an earlier one to AGREE_RTOL, or None where none does yet."""
    for k in range(1, len(errors)):
        e = errors[k]
        if math.isfinite(e) and any(math.isfinite(f) and abs(e - f) <= AGREE_RTOL * max(abs(e), abs(f)) + atol
                                    for f in errors[:k]):
            return k + 1
    return None


def distinct(errors: Sequence[float], atol: float) -> int:
    """How many of the polished ``errors`` (mm^2) differ from each other by more than AGREE_RTOL (plus ``atol``)."""
    out: list[float] = []
    for e in sorted(e for e in errors if math.isfinite(e)):
        if not out or e - out[-1] > AGREE_RTOL * abs(e) + atol:
            out.append(e)
    return len(out)


def run_starts(run: Callable[[list[int]], list[dict]], seeds: list[int], batch: int, atol: float, wanted: int = 1
               ) -> tuple[list[dict], bool]:
    """The starts' runs, ``batch`` seeds at a time through ``run`` (seeds -> their runs, in order), until two agree
    (:func:`agreed`; each run's ``found`` lists its polished designs, each a tuple whose last item is its
    error: the four-bar's (base, branch, angles, error), the six-bar's (design, error)) and the runs kept hold at least
    ``wanted`` designs of distinct errors (the candidates asked for); and whether they stopped so. The runs kept
    are the shortest such prefix of the seeds, whatever the batch."""
    done: list[dict] = []
    for i in range(0, len(seeds), max(1, batch)):
        done += run(seeds[i:i + max(1, batch)])
        keep = agreed([min((f[-1] for f in r["found"]), default=math.inf) for r in done], atol)
        for m in range(keep or len(done) + 1, len(done) + 1):
            if distinct([f[-1] for r in done[:m] for f in r["found"]], atol) >= wanted:
                return done[:m], True
    return done, False
