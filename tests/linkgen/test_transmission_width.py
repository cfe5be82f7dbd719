"""A transmission extreme is refined by sections (linkgen.kinematics.motion._sections: 17 inputs a round, until
the bracket is EXTREME_WIDTH narrow): the extremes are those golden sections to rounding find (the search they
replace, an independent method), their values to the last few bits and their places where the angle is flat, with
a fraction of the solves; a corner (a toggle's 0 degrees) is found within the width."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from linkgen import api
from linkgen.kinematics import motion
from tests.conftest import ROOT

#: linkages of dyads of every kind the bundled templates give, over their inputs' ranges
NAMES = ("jansen", "klann", "watt1", "stephenson3", "eightbar-triad", "toggle-press", "shaper", "pantograph")


def _linkage_and_range(name: str):
    raw = tomllib.loads((ROOT / "templates" / f"{name}.toml").read_text(encoding="utf-8"))
    linkage = api.design(api.validate(raw)).kinematics.linkage
    ranges = motion.input_ranges(linkage)
    lo, hi = (0.0, 2.0 * math.pi) if ranges is None else ranges[0]
    return linkage, lo, hi


def _solves(monkeypatch, linkage) -> list[int]:
    """Counts the linkage's solves."""
    asked: list[int] = []
    solve = type(linkage).solve

    def counting(self, *args, **kwargs):
        asked.append(1)
        return solve(self, *args, **kwargs)

    monkeypatch.setattr(type(linkage), "solve", counting)
    return asked


@pytest.mark.parametrize("name", NAMES)
def test_the_sections_find_the_extremes_golden_sections_find_to_rounding(monkeypatch, name):
    linkage, lo, hi = _linkage_and_range(name)
    asked = _solves(monkeypatch, linkage)
    ours = motion.transmission_extremes(linkage, lo, hi)
    solves = len(asked)
    asked.clear()
    monkeypatch.setattr(motion, "_sections", lambda f, a, b, width: motion._golden(f, a, b))
    golden = motion.transmission_extremes(linkage, lo, hi)
    assert len(ours) == len(golden) and ours
    scale = max(1.0, abs(lo), abs(hi))
    for dyad, ((gmin, at_min, gmax, at_max), theirs) in enumerate(zip(ours, golden, strict=True)):
        assert gmin == pytest.approx(theirs[0], rel=1e-14, abs=1e-12)
        assert gmax == pytest.approx(theirs[2], rel=1e-14, abs=1e-12)
        # both places lie where the angle is flat: within about the square root of the rounding of each other, or
        # both at the extreme's value to the last bits (toggle-press' slider is square to its guide twice, 1.2e-5
        # rad apart: two maxima of 90 degrees)
        for value, at, there in ((gmin, at_min, theirs[1]), (gmax, at_max, theirs[3])):
            if abs(at - there) > 1e-7 * scale:
                s = linkage.solve(np.array([[at, there]]), strict=False, derivatives=False)
                assert s.dyads[dyad].transmission == pytest.approx(value, rel=1e-13)
    assert solves < 0.5 * len(asked)


def test_a_corner_is_found_within_the_width():
    """|x - x0| + 0.3 has its least at a corner: the sections find it within the width, and its value within the
    width of the golden sections' to rounding."""
    x0 = np.array([0.1234567890123, 2.5, -1.75])

    def f(x: np.ndarray) -> np.ndarray:
        return np.abs(x - np.tile(x0, len(x) // len(x0))) + 0.3

    a, b = x0 - 1e-3 * np.array([1.0, 0.7, 1.3]), x0 + 1e-3 * np.array([0.8, 1.1, 0.9])
    x, value = motion._sections(f, a, b, motion.EXTREME_WIDTH)
    tight = motion.EXTREME_WIDTH * np.maximum(1.0, np.abs(x0))
    assert np.all(np.abs(x - x0) <= tight) and np.all(value - 0.3 <= tight)
    _, value_golden = motion._golden(f, a, b)
    assert np.all(np.abs(value - value_golden) <= tight)


def test_sections_to_rounding_stop_and_keep_a_bracket_of_one_point():
    """Width 0: the rounds stop once no bracket narrows (at rounding), well within the bound; a bracket of one
    point (a = b) gives that point."""
    calls: list[int] = []

    def f(x: np.ndarray) -> np.ndarray:
        calls.append(1)
        return (x - 1.0 / 3.0) ** 2

    x, value = motion._sections(f, np.array([0.0, 0.5]), np.array([1.0, 0.5]), 0.0)
    assert abs(x[0] - 1.0 / 3.0) <= 1e-7 and value[0] <= 1e-14 and x[1] == 0.5
    assert len(calls) < motion.ROUNDS
