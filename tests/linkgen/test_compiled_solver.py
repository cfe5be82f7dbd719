"""The optional compiled kernel (issue 38, item 1) against the numpy kernels it may replace for positions.

The two share the construction but not the arithmetic's order (one pose at a time, cosine and sine instead of the
tangent half-angle), so they are compared within tolerances: over 10^5 crank angles on every bundled linkage the
fused kernels solve and on seeded random Watt I and Stephenson III six-bars, positions to 1e-12 mm (loosened as
1 / margin within a margin of 0.1 of a toggle, as the fused solver's own tests), the same poses reached, and the
random six-bars' worst poses against a 50-digit solution. Each pose is computed alone, so the threads' runs and the
blocks join without a seam: the results are the same bits on 1, 2 or 3 threads. No test here times anything.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import linkgen
from camgen.core.errors import SpecError
from linkgen.bench_solver import reference
from linkgen.kinematics import compiled, fused
from linkgen.kinematics.linkage import FEASIBILITY_TOL, Linkage
from linkgen.kinematics.structure import Input, make_structure
from tests.conftest import ROOT
from tests.support.random_six_bars import random_six_bars

pytestmark = pytest.mark.skipif(not compiled.available(), reason="numba is not installed (pip install '.[fast]')")

#: the bundled templates made of a crank and RRR dyads only: the kernels solve them
FUSED = ("jansen", "klann", "watt1", "watt2", "stephenson1", "stephenson3", "pantograph", "single-dwell")
N = 100_000


def _linkage(name: str) -> Linkage:
    return linkgen.design_linkage(linkgen.load_spec(ROOT / "templates" / f"{name}.toml")).kinematics.linkage


def _inputs(linkage: Linkage, n: int = N) -> np.ndarray:
    return linkage.unwrap(linkage.revolution + 2 * math.pi / n * np.arange(n))


def _numpy(linkage: Linkage, x: np.ndarray, rates: bool = False) -> fused.Outputs:
    """The numpy kernels' positions (with ``rates`` velocities and accelerations), margins and reach at crank
    angles x on the linkage's branches."""
    prog = linkage.program
    assert prog is not None
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return fused.run(prog, x[None, :], np.ones(1), list(linkage.base_signs), rates, True, FEASIBILITY_TOL)


def _bound(out: fused.Outputs, tol: float) -> np.ndarray:
    """``tol`` (mm) at each pose, loosened as 1 / margin within a margin of 0.1 of a toggle (there a change of
    rounding moves a joint by about eps L / margin)."""
    least = np.min(out.margins, axis=0)
    return tol * np.maximum(1.0, 0.1 / np.maximum(least, 1e-300))


def _agree(linkage: Linkage, x: np.ndarray, tol: float) -> tuple[dict[str, np.ndarray], fused.Outputs]:
    theirs = _numpy(linkage, x)
    got = compiled.positions(linkage.compiled_program, x[None, :], list(linkage.base_signs))
    mine, ok = got.points, got.ok
    assert ok.dtype == bool and (ok == theirs.ok).all() and ok.any()
    assert set(mine) == {name for name, holder, _ in linkage.program.points if holder is not None}
    bound = _bound(theirs, tol)[ok]
    for name, z in mine.items():
        assert np.all(np.abs(z[ok] - theirs.points[name][ok]) <= bound), name
    return mine, theirs


@pytest.mark.parametrize("name", FUSED)
def test_the_compiled_kernel_equals_the_numpy_kernels_on_every_bundled_linkage(name):
    linkage = _linkage(name)
    _agree(linkage, _inputs(linkage), 1e-12)


def _rates_agree(linkage: Linkage, x: np.ndarray, tol: float = 1e-9) -> None:
    """Velocities and accelerations to ``tol`` relative, loosened near a toggle as 1 / margin^2 (the 2x2 solve's
    determinant and the rates themselves grow there), as the fused solver's own test."""
    theirs = _numpy(linkage, x, rates=True)
    got = compiled.positions(linkage.compiled_program, x[None, :], list(linkage.base_signs), speeds=np.ones(1))
    ok = theirs.ok
    near = _bound(theirs, 1.0)[ok] ** 2
    for table in ("velocities", "accelerations"):
        mine = getattr(got, table)
        assert set(mine) == set(getattr(theirs, table))
        for name, want in getattr(theirs, table).items():
            scale = tol * np.maximum(1.0, np.abs(want[ok])) * near
            assert np.all(np.abs(mine[name][ok] - want[ok]) <= scale), (table, name)


@pytest.mark.parametrize("name", FUSED)
def test_the_compiled_rates_equal_the_numpy_kernels_on_every_bundled_linkage(name):
    linkage = _linkage(name)
    _rates_agree(linkage, _inputs(linkage, N // 10))


@pytest.mark.parametrize("kind", ["watt", "stephenson"])
def test_the_compiled_kernel_equals_the_numpy_kernels_on_random_six_bars(kind):
    for linkage in random_six_bars(kind):
        x = _inputs(linkage)
        tol = 2e-12 * max(1.0, linkage.structure.size / 100.0)   # as the fused solver's test: ~40 ulp a 100 mm
        mine, theirs = _agree(linkage, x, tol)
        apart = np.max([np.abs(z - theirs.points[k]) for k, z in mine.items()], axis=0)
        worst = np.argsort(np.where(theirs.ok, apart, -1.0))[-4:]
        ref = reference(linkage, x[worst])
        bound = _bound(theirs, tol)[worst]
        for name, xy in ref.items():
            z = mine[name][worst]
            assert np.all(np.hypot(z.real - xy[:, 0], z.imag - xy[:, 1]) <= bound), name
        _rates_agree(linkage, x[::10])


@pytest.mark.parametrize("n", [1, compiled.BLOCK - 1, compiled.BLOCK, compiled.BLOCK + 1, 3 * compiled.BLOCK + 7])
def test_threads_and_blocks_join_without_a_seam(n):
    linkage = _linkage("jansen")
    x = _inputs(linkage, n)[None, :]
    runs = [compiled.positions(linkage.compiled_program, x, list(linkage.base_signs), threads=k, speeds=np.ones(1))
            for k in (1, 2, 3)]
    for got in runs[1:]:
        assert (got.ok == runs[0].ok).all()
        for table in ("points", "velocities", "accelerations"):
            for name, z in getattr(got, table).items():
                assert np.array_equal(z, getattr(runs[0], table)[name]), (table, name)
    _agree(linkage, x[0], 1e-12)


def test_branches_given_pose_by_pose_are_taken_pose_by_pose():
    """Signs one a pose (as a linkage past a change point has) flip each joint where they say, as numpy's do."""
    linkage = _linkage("klann")
    prog = linkage.program
    x = _inputs(linkage, 4000)[None, :]
    rng = np.random.default_rng(5)
    signs = [np.where(rng.random(x.shape[1]) < 0.5, -1.0, 1.0) * g for g in linkage.base_signs]
    with np.errstate(invalid="ignore"):
        theirs = fused.run(prog, x, np.ones(1), signs, False, False, FEASIBILITY_TOL)
    got = compiled.positions(linkage.compiled_program, x, signs)
    mine, ok = got.points, got.ok
    assert (ok == theirs.ok).all() and not ok.all() and ok.any()     # some flipped poses cannot close
    for name, z in mine.items():
        assert np.all(np.abs(z[ok] - theirs.points[name][ok]) <= 1e-11), name


def test_positions_by_the_compiled_engine_are_the_numpy_engines_and_refuse_alike():
    linkage = _linkage("watt1")
    t = _inputs(linkage, 720)
    a, b = linkage.positions(t), linkage.positions(t, engine="numba")
    assert set(a.points) == set(b.points) and b.ok.all()
    for name, xy in a.points.items():
        assert np.abs(b.points[name] - xy).max() <= 1e-12, name
    with pytest.raises(SpecError, match="engine: one of numpy, numba"):
        linkage.positions(t, engine="fortran")
    with pytest.raises(SpecError, match="finite"):
        linkage.positions([float("nan")], engine="numba")
    values = np.array([t[3], float("nan"), t[300]])
    loose = linkage.positions(values, strict=False, engine="numba")
    assert loose.ok.tolist() == [True, False, True]
    lean, fast = (linkage.positions(values, derivatives=True, strict=False, engine=e) for e in ("numba", "numpy"))
    for name, v in lean.velocities.items():        # past reach the rates are infinite, never NaN, as numpy's
        if name in linkage.structure.bodies["ground"]:
            continue
        assert not np.isnan(v).any() and np.isinf(v[1]).all(), name
        assert not np.isnan(lean.accelerations[name]).any(), name
        assert np.allclose(v[[0, 2]], fast.velocities[name][[0, 2]], rtol=1e-9, atol=1e-9), name


def test_an_unreachable_input_is_refused_alike_by_both_engines():
    linkage = Linkage.of(make_structure({"O2": (0.0, 0.0), "O4": (100.0, 0.0), "A": (0.0, 70.0),
                                         "B": (20.0, 80.0)},
                                        {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("O4", "B")},
                                        ("O2", "O4"), (), (Input("crank", "crank", "O2"),)))
    bad = np.radians([90.0, 0.0])               # the crank cannot reach 0 degrees: the rocker's pin is too far
    with pytest.raises(SpecError) as by_numpy:
        linkage.positions(bad)
    with pytest.raises(SpecError) as by_numba:
        linkage.positions(bad, engine="numba")
    assert str(by_numba.value) == str(by_numpy.value)
    assert linkage.positions(bad, strict=False, engine="numba").ok.tolist() == [True, False]


def test_a_deltoid_whose_pins_meet_is_left_to_the_general_path():
    """A deltoid (ground = crank = 50 mm, coupler = rocker = 40 mm): at crank angle 0 its crank pin meets the
    rocker's pivot, where only the motion places the joint; the kernel says so and the general path answers."""
    linkage = Linkage.of(make_structure({"O2": (0.0, 0.0), "O4": (50.0, 0.0), "A": (0.0, 50.0),
                                         "B": (25.0 + 18.7083 / math.sqrt(2), 25.0 + 18.7083 / math.sqrt(2))},
                                        {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("O4", "B")},
                                        ("O2", "O4"), (), (Input("crank", "crank", "O2"),)))
    assert linkage.program is not None
    t = np.radians(np.arange(-100.0, 100.5, 1.0))       # it reaches |crank| <= 2 asin(0.8) = 106.26 degrees
    with pytest.raises(fused.Folded):
        compiled.positions(linkage.compiled_program, t[None, :], linkage.signs(t[None, :]))
    a, b = linkage.positions(t), linkage.positions(t, engine="numba")
    for name, xy in a.points.items():
        assert np.array_equal(b.points[name], xy), name
