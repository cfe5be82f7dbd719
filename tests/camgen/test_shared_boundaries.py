"""A cam's segment boundaries are evaluated once, with the first round of a design's asks, and kept explicitly (no
cache filled behind a cached_property): what the design reads equals the boundaries' own evaluation."""
from __future__ import annotations

import dataclasses
import numpy as np

from camgen.analysis import analyze
from camgen.flat import build_cam
from camgen.followers.base import PitchGeometry
from tests.conftest import template
from tests.camgen.test_speed_outline import _Counting


def _fields(g: PitchGeometry) -> list[np.ndarray]:
    return [g.point, g.d1, g.d2, g.normal, g.kappa, g.pressure_angle]


def test_served_boundaries_are_their_own_evaluation():
    """An analysis evaluates the boundaries in its first round (no call of their own after it), and they are the
    numbers a fresh cam's own evaluation of them makes, as are the jumps read from them."""
    fresh = build_cam(template({"motion.0.law": "uniform"}))        # velocity jumps: corners and jumps to find
    counting = _Counting(fresh.follower)
    cam = dataclasses.replace(fresh, follower=counting)
    analyze(cam)
    rounds = len(counting.calls)
    served = cam.boundaries()
    ends, starts = cam.boundary_geometry()
    corners, jumps = cam.corners(), cam.jumps()
    assert len(counting.calls) == rounds                     # nothing evaluated after the analysis's rounds
    n = len(cam.program.segments)
    assert counting.calls[0] > 2 * n                         # the boundaries rode with the first round's points
    assert 2 * n not in counting.calls                       # never evaluated alone
    own = fresh.boundaries()                                 # a cam never served: its own evaluation
    assert np.array_equal(served.motion, own.motion)
    assert np.array_equal(served.motion, cam.program.boundaries[1])
    for a, b in ((ends, own.ends), (starts, own.starts)):
        for x, y in zip(_fields(a), _fields(b), strict=True):
            assert np.allclose(x, y, rtol=1e-14, atol=1e-12)
    assert [j.as_dict() for j in jumps] == [j.as_dict() for j in cam.program.jumps()]
    assert {j.order for j in jumps} >= {1} and len(corners) == 2   # the uniform rise's two velocity jumps


def test_a_replaced_cam_evaluates_its_own_boundaries():
    """dataclasses.replace with another follower starts afresh: its boundaries are its follower's, not the first
    cam's kept ones."""
    cam = build_cam(template({}))
    before = cam.boundaries()
    other = dataclasses.replace(cam, follower=dataclasses.replace(cam.follower, offset=cam.follower.offset + 2.0))
    after = other.boundaries()
    assert other.boundaries() is after and cam.boundaries() is before
    assert np.array_equal(after.motion, before.motion)       # the same program
    assert not np.allclose(after.ends.point, before.ends.point)


def test_served_boundaries_hold_their_own_samples_not_the_round():
    """The boundaries a design's first round made are kept in arrays of their own, not as views of the whole round
    (some 20 000 points at 1 024 segments), so that a round's geometry is let go once its makers have read it, and
    a design keeps only its boundaries' 2 n points."""
    cam = build_cam(template({}))
    analyze(cam)
    served = cam.boundaries()
    n = len(cam.program.segments)
    assert served.motion.shape == (4, 2 * n) and served.motion.base is None
    for g in (served.ends, served.starts):
        for a in (g.theta, *_fields(g)):
            assert a.shape[0] == n and a.base is None
