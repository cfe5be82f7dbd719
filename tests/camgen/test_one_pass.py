"""A program's one-pass evaluation gives every point its own numbers to the bit.

:meth:`camgen.cam.Cam.pitch_of` evaluates many points on many segments in one pass (one gather of each segment's
numbers, one call of each law, a dwell's rows set after). Each point must still get the same bits as its own
segment's evaluation, signed zeros included (compared as integers).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.laws import make_law
from camgen.program import build_program

H = 20.0


def bits(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=float).view(np.int64)


def same(a: np.ndarray, b: np.ndarray) -> bool:
    return a.shape == b.shape and np.array_equal(bits(a), bits(b))


PROGRAMS = {
    "one law and dwells": [("rise", 120, H, "cycloidal"), ("dwell", 60, 0, None), ("return", 120, H, "cycloidal"),
                           ("dwell", 60, 0, None)],
    "two laws": [("rise", 100, H, "harmonic"), ("dwell", 50, 0, None), ("return", 150, H, "cycloidal"),
                 ("dwell", 60, 0, None)],
    "three laws, no dwell": [("rise", 90, H, "polynomial-345"), ("return", 90, H / 2, "modified-sine"),
                             ("return", 180, H / 2, "harmonic")],
    "laws with pieces": [("dwell", 30, 0, None), ("rise", 150, H, "modified-trapezoid"),
                         ("return", 150, H, "parabolic"), ("dwell", 30, 0, None)],
}


@pytest.fixture(params=list(PROGRAMS), ids=list(PROGRAMS))
def program(request):
    return build_program([(kind, angle, lift, make_law(law) if law else None)
                          for kind, angle, lift, law in PROGRAMS[request.param]])


def _points(program, rng, n=400):
    """Segments (n,) and, on each, a law variable and a cam angle: ends, -0.0, and angles outside the segment."""
    m = len(program.segments)
    index = rng.integers(0, m, n)
    v = rng.random(n)
    v[:m] = 0.0
    v[m:2 * m] = 1.0
    v[2 * m:3 * m] = -0.0
    index[:3 * m] = np.tile(np.arange(m), 3)
    start = np.array([program.segments[i].start for i in index])
    beta = np.array([program.segments[i].beta for i in index])
    theta = start + beta * rng.uniform(-0.1, 1.1, n)
    theta[:m], theta[m:2 * m] = start[:m], (start + beta)[m:2 * m]
    return index, v, theta


def test_every_point_gets_its_own_segments_numbers(program):
    rng = np.random.default_rng(5)
    index, v, theta = _points(program, rng)
    table = program._table
    motion = program.evaluate_on(index, theta)
    at_law = table.at_law(index, v)
    angle = table.angle(index, v)
    for k, seg in enumerate(program.segments):
        mine = index == k
        assert same(motion[:, mine], seg.evaluate(theta[mine])), k
        own_theta, own_motion = seg.at_law(v[mine])
        assert same(at_law[:, mine], own_motion), k
        assert same(angle[mine], own_theta), k
    cut = 150                                   # law variables, then cam angles, in one pass
    got_theta, got = table.on(index, np.concatenate([v[:cut], theta[cut:]]), cut)
    assert same(got_theta, np.concatenate([angle[:cut], theta[cut:]]))
    assert same(got, np.concatenate([at_law[:, :cut], motion[:, cut:]], axis=1))


def test_the_variable_of_a_cam_angle_is_what_a_segment_evaluates_at(program):
    rng = np.random.default_rng(6)
    index, _, theta = _points(program, rng)
    u = program._table.variable(index, theta)
    for k, seg in enumerate(program.segments):
        mine = index == k
        own = np.minimum(np.maximum((theta[mine] - seg.start) / seg.beta, 0.0), 1.0)
        backwards = seg.kind == "return" and seg.law is not None
        assert same(u[mine], np.where(backwards, 1.0 - own, own)), k
        assert not np.signbit(u[mine]).any()


@pytest.mark.parametrize("law", ["cycloidal", "harmonic"])
def test_laws_filled_in_place_keep_their_formulas(law):
    """The trigonometric laws fill their rows in place: the bits of their formulas, term by term; a scalar's rows are
    0-d."""
    u = np.concatenate([np.linspace(0.0, 1.0, 1001), [-0.0, 0.5]])
    pi = np.pi
    if law == "cycloidal":
        x = 2 * pi * u
        expected = [u - np.sin(x) / (2 * pi), 1 - np.cos(x), 2 * pi * np.sin(x), 4 * pi**2 * np.cos(x)]
    else:
        x = pi * u
        expected = [(1 - np.cos(x)) / 2, pi / 2 * np.sin(x), pi**2 / 2 * np.cos(x), -(pi**3) / 2 * np.sin(x)]
    got = make_law(law).derivatives(u)
    assert same(got, np.array(expected))
    one = make_law(law).derivatives(0.25)
    assert one.shape == (4,) and same(one, make_law(law).derivatives(np.array([0.25]))[:, 0])


def test_jumps_keep_their_numbers_with_the_scales_made_at_once(program):
    """The program's jumps compare against every segment's scales made in one pass: Segment.scale's numbers."""
    assert program._table.scales == [seg.scale().tolist() for seg in program.segments]
    for jump in program.jumps():
        assert type(jump.jump) is float and type(jump.at_deg) is float and jump.order in (1, 2, 3)


def test_a_part_is_a_view_of_its_whole():
    """PitchGeometry.part slices every field: the same bits as slicing each array, sharing the whole's memory, a
    part of a part likewise; dataclasses.replace makes a geometry holding every field."""
    import dataclasses

    from camgen.flat import build_cam
    from camgen.followers.base import PitchGeometry
    from tests.conftest import template

    cam = build_cam(template({}))
    whole = cam.pitch(np.linspace(0.0, 2 * math.pi, 50))
    part = whole.part(7, 31)
    inner = part.part(3, 9)
    for f in dataclasses.fields(PitchGeometry):
        value, expected = getattr(part, f.name), getattr(whole, f.name)
        if expected is None:
            assert value is None
            continue
        assert same(value, expected[7:31]) and np.shares_memory(value, expected), f.name
        assert same(getattr(inner, f.name), expected[10:16]), f.name
    moved = dataclasses.replace(whole.part(2, 4), point=np.zeros((2, 2)))
    assert same(moved.point, np.zeros((2, 2))) and same(moved.d1, whole.d1[2:4])


def test_a_part_pickles_as_its_own_samples_not_its_whole():
    """A pickled (or deep-copied) part holds its own samples only (numpy pickles a view's own elements): a design's
    cached boundary parts carry no whole round of evaluation. It comes back as a geometry of the same bits."""
    import copy
    import dataclasses
    import pickle

    from camgen.flat import build_cam
    from camgen.followers.base import PitchGeometry
    from tests.conftest import template

    whole = build_cam(template({})).pitch(np.linspace(0.0, 2 * math.pi, 2000))
    part = whole.part(10, 14)
    for back in (pickle.loads(pickle.dumps(part)), copy.deepcopy(part)):
        assert type(back) is PitchGeometry
        for f in dataclasses.fields(PitchGeometry):
            expected = getattr(whole, f.name)
            assert (getattr(back, f.name) is None) if expected is None else same(getattr(back, f.name),
                                                                                   expected[10:14]), f.name
    assert len(pickle.dumps(part)) < len(pickle.dumps(whole)) / 50
