"""How linkgen.kinematics.motion refines extremes. A transmission extreme by sections (``_sections``: 17 inputs a
round, until the bracket is EXTREME_WIDTH narrow): the extremes golden sections to rounding find (the search they
replace, an independent method), their values to the last few bits and their places where the angle is flat, with a
fraction of the solves; a corner (a toggle's 0 degrees) within the width. An output that does not move is left out
of the limit search, and the search stops at its fixed point, with the same limits."""
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
    """Records the linkage's solves: the poses each asks for."""
    asked: list[int] = []
    solve = type(linkage).solve

    def counting(self, x, *args, **kwargs):
        asked.append(np.shape(x)[-1])
        return solve(self, x, *args, **kwargs)

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


def test_an_output_that_does_not_move_is_not_refined_and_the_extents_stay(monkeypatch):
    """toggle-press' ram slides on a vertical guide: its x does not move, and the signs of its rate over the grid
    are rounding's (a bracket at some 700 grid steps, each refined with the rest to no purpose). Left unrefined,
    the extents are the same within 1e-12 mm, with a fraction of the poses solved; the check itself
    (:func:`motion._still`) holds for a constant with rounding noise, not for a motion of 1e-9 of its size, nor for
    no finite value."""
    linkage, lo, hi = _linkage_and_range("toggle-press")
    points = list(linkage.structure.points)
    asked = _solves(monkeypatch, linkage)
    ours = motion.extents(linkage, points, lo, hi)
    poses = sum(asked)
    asked.clear()
    monkeypatch.setattr(motion, "STILL", -1.0)                             # every output refined
    every = motion.extents(linkage, points, lo, hi)
    for point in points:
        assert np.allclose(np.array(ours[point]), np.array(every[point]), rtol=0.0, atol=1e-12), point
    assert poses < 0.5 * sum(asked)
    monkeypatch.undo()
    noisy = 250.0 + np.random.default_rng(1).normal(0.0, 1e-14, 4097)
    assert motion._still(noisy) and not motion._still(noisy + 2.5e-7 * np.sin(np.linspace(0.0, 6.0, 4097)))
    assert not motion._still(np.full(9, np.nan)) and motion._still(np.array([np.nan, 0.0, 1e-13]))


@pytest.mark.parametrize("name", ["toggle-press", "jansen", "shaper"])
def test_newton_stops_at_its_fixed_point_with_the_limits_of_all_sixty_rounds(monkeypatch, name):
    """Once a round leaves every column as it was, the limit search stops: the limit positions are those of all
    60 rounds to the bit (the rounds compare nothing, here, so that none stops early), in fewer rounds where a
    column sits on a flat zero (toggle-press)."""
    linkage, lo, hi = _linkage_and_range(name)
    outputs = [(p, axis) for p in linkage.structure.points for axis in (0, 1)]
    rounds: list[int] = []
    pick = motion._pick

    def counted(*args):
        rounds.append(1)
        return pick(*args)

    monkeypatch.setattr(motion, "_pick", counted)
    ours = motion.limits(linkage, outputs, lo, hi)
    fewer = len(rounds)
    rounds.clear()
    monkeypatch.setattr(motion.np, "array_equal", lambda *args, **kwargs: False)
    every = motion.limits(linkage, outputs, lo, hi)
    monkeypatch.undo()
    assert ours == every
    assert fewer <= len(rounds)
    if name == "toggle-press":
        assert fewer < len(rounds)
