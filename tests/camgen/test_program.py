"""Motion programs: coverage of 360 degrees, continuity findings, mirrored returns."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.core.errors import SpecError
from camgen.laws import Law, make_law
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


def _law_classes(cls: type) -> list[type]:
    """Every subclass of ``cls``, at any depth."""
    return [sub for direct in cls.__subclasses__() for sub in (direct, *_law_classes(direct))]


def test_only_laws_without_parameters_say_so_and_a_subclass_does_not_inherit_it():
    import dataclasses

    flagged = {cls.name for cls in _law_classes(Law) if cls.PARAMETERLESS}
    assert flagged == {"uniform", "harmonic", "cycloidal", "double-harmonic"}
    for cls in _law_classes(Law):
        if cls.PARAMETERLESS:
            assert not [f for f in dataclasses.fields(cls) if f.init]
            assert cls() == cls() and hash(cls()) == hash(cls())

    @dataclasses.dataclass(frozen=True)
    class Steeper(type(make_law("cycloidal"))):       # a parameter on a law without any
        k: float = 1.0

    assert not Steeper.PARAMETERLESS


class _Scaled(Law):
    """A law that is no dataclass of its own, its parameter kept outside the dataclass fields: f = u + k u (1 - u)
    (f(0) = 0, f(1) = 1)."""

    name = "scaled"

    def __init__(self, k: float) -> None:
        object.__setattr__(self, "k", k)

    def derivatives(self, u):
        u, k = np.asarray(u, dtype=float), self.k
        return np.stack([u + k * u * (1 - u), 1 + k * (1 - 2 * u), np.full_like(u, -2 * k), np.zeros_like(u)])


@pytest.mark.parametrize("make", [lambda k: _Scaled(k), lambda k: make_law("parabolic", ratio=1.0 + k)],
                         ids=["outside dataclass fields", "a dataclass field"])
def test_laws_with_parameters_are_never_evaluated_as_one(make):
    """Two segments of one law class with other parameters keep their own numbers in the one-pass evaluation (a
    class without fields of its own, or not a dataclass, is not thereby without parameters)."""
    p = build_program([("rise", 120, H, make(0.5)), ("dwell", 60, 0, None), ("return", 120, H, make(0.25)),
                       ("dwell", 60, 0, None)])
    theta = np.radians(np.linspace(0.0, 359.0, 719))
    index = p.segment_index(theta)
    assert len(p._table.laws) == 3                      # the dwells', and each law its own
    assert np.array_equal(p.evaluate_on(index, theta), p.evaluate(theta))


def test_a_cycloidal_rise_and_return_are_evaluated_as_one_law():
    p = build_program([("rise", 120, H, make_law("cycloidal")), ("dwell", 60, 0, None),
                       ("return", 90, H, make_law("cycloidal")), ("dwell", 90, 0, None)])
    theta = np.radians(np.linspace(0.0, 359.0, 719))
    assert len(p._table.laws) == 2 and np.array_equal(p.evaluate_on(p.segment_index(theta), theta), p.evaluate(theta))


def test_a_jumps_angle_is_its_boundary_rounded_to_9_places_in_degrees():
    """A jump's at_deg is round(degrees(theta), 9) % 360 of its boundary theta, to the bit, whether the boundary
    lies at a whole number of degrees or within 1e-10 of one (taken as that number: its own rounding) or not
    (119.99999999999999 -> 120.0, 120.00000000004 -> 120.0 within 1e-10, 120.0000000006 -> 120.000000001)."""
    for angles in ((120, 60, 120, 60), (100.5, 79.25, 120.125, 60.125), (33.3, 90, 200.7, 36), (90, 90, 90, 90),
                   (120.00000000004, 59.99999999996, 120, 60), (120.0000000006, 59.9999999994, 120, 60),
                   (119.99999999996, 60.0000000004, 119.99999999994, 60.00000000000)):
        steps = [("rise", angles[0], H, make_law("cycloidal")), ("dwell", angles[1], 0, None),
                 ("return", angles[2], H, make_law("harmonic")), ("dwell", angles[3], 0, None)]
        p = build_program(steps)
        ends = [seg.start + seg.beta for seg in p.segments]
        expected = {round(math.degrees(t), 9) % 360.0 for t in ends}
        found = {j.at_deg for j in p.jumps()}
        assert found == expected and len(found) == 4, angles
        assert all(math.copysign(1.0, a) > 0 for a in found)
    assert math.degrees(math.radians(120)) != 120.0      # a boundary that is not a whole number, rounded to one


def _segments(steps):
    """The segments build_program lays end to end, made by Segment's own constructor."""
    from camgen.program import Segment

    out, start, level = [], 0.0, 0.0
    for kind, angle, lift, law in steps:
        seg = Segment(kind, start, math.radians(angle), 0.0 if kind == "dwell" else lift, level,
                      None if kind == "dwell" else law)
        out.append(seg)
        start, level = seg.end, seg.end_level
    return tuple(out)


@pytest.mark.parametrize("steps", [
    [("rise", 120, H, make_law("cycloidal")), ("dwell", 60, 0, None), ("return", 180, H, make_law("harmonic"))],
    [("rise", 120, H, make_law("cycloidal")), ("return", 120, H, make_law("cycloidal"))],
    [("rise", 180, H, make_law("cycloidal")), ("return", 180, H / 2, make_law("cycloidal"))],
    [("return", 180, H, make_law("cycloidal")), ("rise", 180, H, make_law("cycloidal"))],
    [("dwell", 360, 0, None)],
    [],
])
def test_build_program_checks_as_program_checks_itself(steps):
    """build_program's checks (from the angles and levels it lays out) accept and refuse what Program's own do,
    with the same message and field."""
    from camgen.program import Program

    try:
        made = build_program(steps)
    except SpecError as error:
        with pytest.raises(SpecError) as own:
            Program(_segments(steps))
        assert (str(own.value), own.value.field) == (str(error), error.field)
    else:
        assert made == Program(_segments(steps))


def test_a_program_of_thousands_of_segments_evaluates_as_each_segment_does():
    """The one-pass table's scales and evaluation equal each segment's own to the bit at any size: 5 000 rises and
    returns of random angles and lifts (numpy's power in another layout differed in the last bits of ~1 in 20 from
    about 2 700 segments on)."""
    m, law = 5000, make_law("cycloidal")
    rng = np.random.default_rng(5000)
    w = rng.uniform(0.5, 1.5, m)
    angles = (w / w.sum() * 360).tolist()
    angles[-1] = 360 - sum(angles[:-1])
    lifts = [1.0 + (i // 2 % 7) * 0.1 for i in range(m)]
    program = build_program([("rise" if i % 2 == 0 else "return", a, h, law)
                             for i, (a, h) in enumerate(zip(angles, lifts, strict=True))])
    assert program._table.scales == [list(map(float, s.scale())) for s in program.segments]
    theta = np.array([s.start + 0.37 * s.beta for s in program.segments])
    own = np.column_stack([s.evaluate(theta[i:i + 1]) for i, s in enumerate(program.segments)])
    assert np.array_equal(program.evaluate_on(np.arange(m), theta), own)


def test_a_nan_angle_is_refused_by_the_program():
    """A NaN among the segment angles makes their sum NaN, which is not one turn: refused, naming the motion."""
    law = make_law("cycloidal")
    with pytest.raises(SpecError, match="add up to nan degrees") as err:
        build_program([("rise", 120.0, 10.0, law), ("dwell", math.nan, 0.0, None), ("return", 120.0, 10.0, law)])
    assert err.value.field == "motion"
