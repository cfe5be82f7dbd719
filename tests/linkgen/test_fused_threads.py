"""The fused solver's chunks shared among threads (issue 38, item 1): the result is the single-threaded one whatever
the thread count and the chunk size (chunk boundaries, a run not a multiple of the chunk, one angle, none), a
thread's :class:`~linkgen.kinematics.fused.Folded` reaches the caller (which then takes the general path), the
caller's floating-point error state holds inside the threads (no raw numpy warning), and 10^6 angles solved on two
threads are within 1e-12 mm of a 50-digit solution. No test here times anything.
"""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import linkgen
from linkgen.bench_solver import reference
from linkgen.kinematics import fused
from linkgen.kinematics import linkage as solver
from linkgen.kinematics.linkage import FEASIBILITY_TOL, Linkage
from linkgen.kinematics.structure import Input, make_structure
from tests.conftest import ROOT

#: the bench's three linkages: Jansen's leg, Klann's, a Watt I six-bar
BENCH = ("jansen", "klann", "watt1")


def _linkage(name: str) -> Linkage:
    return linkgen.design_linkage(linkgen.load_spec(ROOT / "templates" / f"{name}.toml")).kinematics.linkage


def _run(linkage: Linkage, t: np.ndarray, derivatives: bool, extras: bool, **how: int) -> fused.Outputs:
    prog = linkage.program
    assert prog is not None
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        x = np.atleast_2d(linkage.unwrap(t))
        return fused.run(prog, x, np.ones(1), list(linkage.signs(x)), derivatives, extras, FEASIBILITY_TOL, **how)


def _same(a: fused.Outputs, b: fused.Outputs) -> None:
    """Every output of two runs within 1e-12 (mm, rad, per unit input speed), the reached poses identical."""
    assert a.ok.tolist() == b.ok.tolist()
    for field in ("points", "velocities", "accelerations", "rotations", "omegas", "alphas"):
        one, two = getattr(a, field), getattr(b, field)
        assert set(one) == set(two), field
        for name in one:
            assert one[name].shape == two[name].shape
            assert np.abs(one[name] - two[name]).max(initial=0.0) <= 1e-12, (field, name)
    for field in ("margins", "transmissions", "slacks", "spreads"):
        for one, two in zip(getattr(a, field), getattr(b, field), strict=True):
            assert np.abs(one - two).max(initial=0.0) <= 1e-12, field


@pytest.mark.parametrize("name", BENCH)
@pytest.mark.parametrize(("n", "chunk"), [(3 * 8192 + 7, None), (1000, 7), (1000, 250), (1, None), (2, 1)])
def test_threads_and_chunk_sizes_give_the_single_threaded_result(name, n, chunk):
    linkage = _linkage(name)
    t = linkage.revolution + 2 * math.pi / max(n, 2) * np.arange(n)
    for derivatives, extras in ((False, False), (True, True)):
        alone = _run(linkage, t, derivatives, extras, workers=1)
        for workers in (2, 3):
            _same(_run(linkage, t, derivatives, extras, workers=workers, chunk=chunk or fused.CHUNK), alone)


def test_no_angles_give_empty_results_on_any_thread_count():
    linkage = _linkage("jansen")
    for workers in (1, 2):
        out = _run(linkage, np.empty(0), True, True, workers=workers)
        assert out.ok.shape == (0,) and all(v.shape == (0,) for v in out.points.values())
    assert all(v.shape == (0, 2) for v in linkage.positions(np.empty(0)).points.values())


def test_one_angle_equals_the_general_solve():
    linkage = _linkage("klann")
    x = np.atleast_2d(linkage.unwrap(np.array([1.234])))
    signs = list(linkage.signs(x))
    general = solver._solve(linkage, x, np.ones(1), signs, False, True, None, lambda i, r: None)
    pos = linkage.positions(x[0], derivatives=True)
    for name, xy in general.points.items():
        assert np.abs(pos.points[name] - xy).max() <= 1e-12, name
        assert np.abs(pos.velocities[name] - general.velocities[name]).max() <= 1e-9, name


def _deltoid() -> Linkage:
    """A four-bar whose rocker's pins meet: ground O2-O4 = crank O2-A = 50 mm, coupler A-B = rocker O4-B, so at
    crank angle 0 the crank pin A lies on the rocker's pivot O4."""
    return Linkage.of(make_structure({"O2": (0.0, 0.0), "O4": (50.0, 0.0), "A": (0.0, 50.0), "B": (65.0, 65.0)},
                                     {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("O4", "B")},
                                     ("O2", "O4"), (), (Input("crank", "crank", "O2"),)))


def test_a_fold_in_another_thread_reaches_the_caller_and_the_general_path_takes_over():
    linkage = _deltoid()
    prog = linkage.program
    assert prog is not None and any(isinstance(op, fused.RRROp) and op.deltoid for op in prog.ops)
    n = 4 * 100
    t = 2 * math.pi / n * (np.arange(n) + 0.5)
    t[-1] = 0.0                        # crank angle 0 (the fold) in the last run of chunks, the other thread's
    x = np.atleast_2d(t)
    with pytest.raises(fused.Folded):
        fused.run(prog, x, np.ones(1), [1.0, 1.0], False, False, FEASIBILITY_TOL, workers=2, chunk=100)
    far = t[: n // 2]
    fused.run(prog, np.atleast_2d(far), np.ones(1), [1.0, 1.0], False, False, FEASIBILITY_TOL, workers=2, chunk=100)
    pos = linkage.positions(t, strict=False)
    sol = linkage.solve(t, strict=False, derivatives=False)
    for name, xy in sol.points.items():
        assert np.array_equal(np.isnan(pos.points[name]), np.isnan(xy)), name
        assert np.nanmax(np.abs(pos.points[name] - xy)) <= 1e-12, name


def test_the_callers_error_state_holds_in_the_threads():
    """An infinite angle in the other thread's chunks (its tangent is invalid): no raw numpy warning from any
    thread under the caller's ``np.errstate``, the pose not reached and its rates infinite, not NaN."""
    linkage = _linkage("watt1")
    t = linkage.revolution + 2 * math.pi / 40_000 * np.arange(40_000)
    t[-3] = float("inf")
    prog = linkage.program
    assert prog is not None
    with warnings.catch_warnings(), np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        warnings.simplefilter("error")       # the angles as they are (unwrapping would make the infinity a NaN)
        out = fused.run(prog, np.atleast_2d(t), np.ones(1), list(linkage.base_signs), True, False, FEASIBILITY_TOL,
                        workers=2)
    assert not out.ok[-3] and out.ok[:-3].all()
    assert out.velocities and all(np.isinf(v[-3]) for v in out.velocities.values())


@pytest.mark.parametrize("name", BENCH)
def test_a_million_angles_on_two_threads_equal_a_50_digit_solution(name):
    linkage = _linkage(name)
    n = 1_000_000
    t = linkage.revolution + 2 * math.pi / n * np.arange(n)
    pos = linkage.positions(t)
    probe = np.array([0, 1, 8191, 8192, 499_999, 777_777, n - 1])         # chunk seams, the far end
    ref = reference(linkage, t[probe])
    for point, xy in ref.items():
        assert np.abs(pos.points[point][probe] - xy).max() <= 1e-12, point
