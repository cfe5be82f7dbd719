"""The six-bar path search's stop and count (issue 36 item 3, issue 38 item 4): the stall asks the population's
median to stand still as well as its best, the search's own record (generations run, why it stopped) follows the
rule on made-up objectives, and ``designs_evaluated`` counts designs, as a counting objective in the search's place
counts them (scipy's ``nfev`` counts a vectorised call, a whole population, as one)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from linkgen.synthesis import sixbar, validate_task
from linkgen.synthesis.sixbar_stop import why_stop_six
from linkgen.synthesis.stop import STALL_GENERATIONS, Rule

RULE = Rule(generations=5, rtol=1e-6, spread=1e-9, atol=1e-12)


@pytest.mark.parametrize(("best", "median", "energies", "expected"), [
    ([5.0] * 7, [9.0, 8.0, 7.0, 6.0, 5.5, 5.2, 5.1], [5.0, 5.1], None),     # the best stands, the median falls
    ([5.0] * 7, [6.0] * 7, [5.0, 6.0], "stall"),                            # both stand: a population at rest
    ([5.0] * 6 + [4.0], [6.0] * 7, [4.0, 6.0], None),                       # the best still falls
    ([5.0] * 2, [5.0] * 2, [5.0, 5.0 + 1e-12], "collapse"),                 # collapse needs no history
    ([5.0] * 7, [6.0] * 7, [5.0, math.inf], "stall"),
])
def test_a_six_bar_search_stalls_only_once_its_best_and_its_median_stand(best, median, energies, expected):
    assert why_stop_six(best, median, np.array(energies), RULE) == expected


def _problem(generations: int, population: int) -> sixbar.Problem:
    points = [[math.cos(t) * 40, math.sin(t) * 20] for t in np.radians(np.arange(0, 360, 30))]
    spec = validate_task({"name": "p", "task": {"kind": "path", "linkage": "watt1", "points": points,
                                                "input_angles": list(range(0, 360, 30)), "seed": 1, "starts": 1,
                                                "generations": generations, "population": population}})
    return sixbar.problem_of(spec.task)


def _run(monkeypatch, energy, generations: int, population: int, start: np.ndarray | None = None
         ) -> tuple[dict, list[int]]:
    """One search with ``energy`` (designs (10, N) -> (N,)) as its objective, counted (designs per call), its polish
    left out (each picked design kept as it is), ``start`` (10,) in its first population where given."""
    calls: list[int] = []

    def counting(x, p):
        calls.append(x.shape[1])
        return energy(x)

    monkeypatch.setattr(sixbar, "objective", counting)
    monkeypatch.setattr(sixbar, "_polish", lambda x, p: (x, float(energy(x[:, None])[0])))
    return sixbar.search((_problem(generations, population), 7, start)), calls


def test_designs_evaluated_counts_designs_not_vectorised_calls(monkeypatch):
    """A bowl objective over 20 generations, population 5 a number (50 designs a generation): the search's count is
    the designs the counting objective was given, its calls the calls (the first population and one a
    generation)."""
    run, calls = _run(monkeypatch, lambda x: np.sum(x**2, axis=0) + 1.0, 20, 5)
    assert run["evaluations"] == sum(calls) == 50 * len(calls)
    assert run["calls"] == len(calls) == run["generations"] + 1 == 21
    assert run["stopped"] == "budget"


def test_a_search_whose_population_collapses_stops_at_once(monkeypatch):
    run, calls = _run(monkeypatch, lambda x: np.full(x.shape[1], 3.0), 200, 5)
    assert run["stopped"] == "collapse" and run["generations"] == 1 and len(calls) == 2


def test_a_search_goes_on_while_its_median_falls_and_stops_when_it_stands(monkeypatch):
    """One design of the first population (the ``start``, as the best four-bar embedded is) scores 1, every other
    2 + |x|^2 / 10: the best stands at 1 from the first generation, where the four-bar's rule alone would stop 50
    generations later; the search goes on while the rest of the population descends the bowl, and stops on a stall
    (no collapse: the others stay at 2 or more) within the budget (measured: at generation 428 of 600)."""
    start = np.full(10, 2.5)

    def energy(x):
        return np.where(np.all(np.abs(x - start[:, None]) < 1e-12, axis=0), 1.0, 2.0 + np.sum(x**2, axis=0) / 10.0)

    run, calls = _run(monkeypatch, energy, 600, 5, start)
    assert calls[0] == 50 and run["best_energy"] == 1.0
    assert STALL_GENERATIONS + 1 < run["generations"] < 600
    assert run["stopped"] == "stall"
