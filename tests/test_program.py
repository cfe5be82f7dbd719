"""Motion programs: coverage of 360 degrees, continuity findings, mirrored returns."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.core.errors import SpecError
from camgen.laws import make_law
from camgen.program import build_program

H = 20.0
BETA = 2 * math.pi / 3


def rdrd(ret="harmonic", **params):
    return build_program([("rise", 120, H, make_law("cycloidal")), ("dwell", 60, 0, None),
                          ("return", 120, H, make_law(ret, **params)), ("dwell", 60, 0, None)])


def test_segment_scaling_and_levels():
    p = rdrd()
    s = p.evaluate(np.radians([0, 60, 120, 150, 240, 300, 330]))
    assert s[0] == pytest.approx([0, 10, 20, 20, 10, 0, 0], abs=1e-12)
    assert s[1, 1] == pytest.approx(2 * H / BETA, rel=1e-13)         # cycloidal cv = 2 h / beta
    assert s[1, 4] == pytest.approx(-PI_2 * H / BETA, rel=1e-13)     # harmonic mid-return velocity


PI_2 = math.pi / 2


def test_jumps_of_rdrd_are_found_with_their_sizes():
    jumps = {(j.at_deg, j.order): j for j in rdrd().jumps()}
    assert set(jumps) == {(0.0, 3), (120.0, 3), (180.0, 2), (300.0, 2)}
    a0 = math.pi**2 / 2 * H / BETA**2                                # harmonic s'' at the ends
    assert jumps[(180.0, 2)].jump == pytest.approx(-a0, rel=1e-12)
    assert jumps[(300.0, 2)].jump == pytest.approx(-a0, rel=1e-12)
    assert jumps[(180.0, 2)].consequence == "infinite jerk"
    assert jumps[(0.0, 3)].jump == pytest.approx(4 * math.pi**2 * H / BETA**3, rel=1e-12)


def test_uniform_law_velocity_jumps_mean_infinite_acceleration():
    p = build_program([("rise", 180, H, make_law("uniform")), ("return", 180, H, make_law("uniform"))])
    vel = [j for j in p.jumps() if j.order == 1]
    assert [j.at_deg for j in vel] == [0.0, 180.0]
    assert vel[1].jump == pytest.approx(-2 * H / math.pi, rel=1e-12)
    assert vel[0].consequence == "infinite acceleration"


def test_inner_breakpoint_of_a_mirrored_asymmetric_return():
    """A return mirrors its rise: a K = 2 parabolic return switches at 2/3 of the way, not 1/3."""
    p = rdrd("parabolic", ratio=2.0)
    inside = [j for j in p.jumps() if j.inside]
    assert [j.at_deg for j in inside] == [pytest.approx(180 + 120 * 2 / 3)]
    x = np.linspace(0, BETA, 61)[:-1]
    mirrored = H * make_law("parabolic", ratio=2.0).derivatives(1 - x / BETA)[0]
    assert np.abs(p.evaluate(np.radians(180) + x)[0] - mirrored).max() < 1e-12


@pytest.mark.parametrize("steps, words", [
    ([("rise", 120, H, make_law("cycloidal")), ("return", 120, H, make_law("cycloidal"))], "add up to 240"),
    ([("rise", 180, H, make_law("cycloidal")), ("dwell", 180, 0, None)], "rises and returns must balance"),
    ([("return", 180, H, make_law("cycloidal")), ("rise", 180, H, make_law("cycloidal"))], "below its lowest"),
])
def test_program_errors(steps, words):
    with pytest.raises(SpecError, match=words):
        build_program(steps)


def test_evaluate_wraps_and_boundaries_take_the_later_segment():
    p = rdrd()
    assert p.evaluate([2 * math.pi])[0, 0] == pytest.approx(0.0)
    assert p.segment_index(np.radians([0, 120, 180, 300, 359.9])).tolist() == [0, 1, 2, 3, 3]
