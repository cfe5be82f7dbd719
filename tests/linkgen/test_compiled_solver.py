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

#: one worker runs every check of the compiled kernels, so that numba compiles them once a run (about 9 CPU s; the
#: other worker then loads them from numba's cache on disk, or never needs them)
GROUP = "compiled-kernels"
pytestmark = [pytest.mark.skipif(not compiled.available(), reason="numba is not installed (pip install '.[fast]')"),
              pytest.mark.xdist_group(GROUP)]

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


@pytest.mark.parametrize("n", [1, compiled.BLOCK - 1, compiled.BLOCK, compiled.BLOCK + 1, 3 * compiled.BLOCK + 7,
                               compiled.SPLIT - 1, compiled.SPLIT, 10_000, 2 * compiled.CHUNK - 1,
                               2 * compiled.CHUNK, 3 * compiled.CHUNK + 5, 4 * compiled.CHUNK + 1])
def test_threads_and_blocks_join_without_a_seam(n):
    """On the calling thread or numba's (from SPLIT poses on: equal shares, then chunks of CHUNK), with the
    blocks' edges anywhere: the same bits."""
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


@pytest.mark.parametrize("threads", [1, 2, 3, 8])
@pytest.mark.parametrize("n", [0, 1, compiled.SPLIT - 1, compiled.SPLIT, 5_000, 10_000, 2 * 8 * compiled.CHUNK - 1,
                               2 * 8 * compiled.CHUNK, 10**6])
def test_a_run_is_shared_in_whole_blocks_nearly_equally_or_in_chunks(n, threads):
    """The chunk size covers the run: one chunk (the calling thread) for one thread or a short run; else whole
    blocks, every thread one chunk (the last at most a block a thread short), or chunks of CHUNK once a thread's
    share is longer."""
    size = compiled.chunk_size(n, threads)
    chunks = -(-n // size)
    if threads == 1 or n < compiled.SPLIT:
        assert size >= n and chunks <= 1
        return
    assert size % compiled.BLOCK == 0 and size <= compiled.CHUNK
    if n > threads * compiled.CHUNK:
        assert size == compiled.CHUNK and chunks > threads
    else:
        assert chunks <= threads and n - (chunks - 1) * size > size - threads * compiled.BLOCK


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


def test_the_kernels_cosine_and_sine_are_within_an_ulp_of_50_digits():
    """The kernel's own cosine and sine (vectorised; the C library's are not) against mpmath at 50 digits: random
    angles on every scale up to the reduction's reach, exact multiples of pi / 4 (the quadrants' edges, where the
    reduction cancels) and their neighbours; NaN for NaN and +-inf, as the C library's."""
    import mpmath

    from linkgen.kinematics.compiled_kernels import sincos

    rng = np.random.default_rng(38)
    edges = np.arange(-64, 65) * (math.pi / 4)
    x = np.concatenate([rng.uniform(-r, r, 400) for r in (1.0, 10.0, 1e3, 1e6, compiled.TRIG_REACH)]
                       + [edges, np.nextafter(edges, np.inf), np.nextafter(edges, -np.inf), [0.0, -0.0, 5e-324]])
    with mpmath.workdps(50):
        for v in x:
            c, s = sincos(float(v))
            assert abs(c - float(mpmath.cos(mpmath.mpf(float(v))))) <= 1.2e-16, v
            assert abs(s - float(mpmath.sin(mpmath.mpf(float(v))))) <= 1.2e-16, v
    for v in (math.nan, math.inf, -math.inf):
        assert all(math.isnan(z) for z in sincos(v))


def test_angles_past_the_reductions_reach_take_the_c_librarys_cosine():
    """|crank angle - drawn| beyond TRIG_REACH (never on a crank's few turns, but given): the kernel falls back to
    the C library, so the positions still equal the numpy kernels' (its tangent half-angle reduces exactly)."""
    linkage = _linkage("jansen")
    drawn = float(linkage.drawn_inputs[0])
    x = drawn + np.array([1.0, compiled.TRIG_REACH * 0.999, compiled.TRIG_REACH * 1.5, -3e9, 1e12])
    theirs = _numpy(linkage, x)
    got = compiled.positions(linkage.compiled_program, x[None, :], list(linkage.base_signs))
    assert (got.ok == theirs.ok).all()
    for name, z in got.points.items():
        ok = theirs.ok
        assert np.all(np.abs(z[ok] - theirs.points[name][ok]) <= 1e-12), name


def _limited_four_bar() -> tuple[Linkage, list[float]]:
    """A four-bar whose crank cannot turn (O2 O4 = 100, crank 70, coupler sqrt(500), rocker sqrt(12800) mm): its
    dyad folds (toggles) where |A - O4| = coupler +- rocker, and the crank angles there (rad) to 50 digits."""
    import mpmath

    linkage = Linkage.of(make_structure({"O2": (0.0, 0.0), "O4": (100.0, 0.0), "A": (0.0, 70.0),
                                         "B": (20.0, 80.0)},
                                        {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("O4", "B")},
                                        ("O2", "O4"), (), (Input("crank", "crank", "O2"),)))
    with mpmath.workdps(50):
        c, r = mpmath.sqrt(500), mpmath.sqrt(12800)
        # |A - O4|^2 = 70^2 + 100^2 - 2 70 100 cos(theta), theta the crank's angle from +x
        toggles = [float(mpmath.acos((4900 + 10000 - d * d) / 14000)) for d in (c + r, r - c)]
    return linkage, toggles


def test_at_and_within_1e_12_of_a_toggle_both_engines_agree_with_50_digits():
    """Crank angles at a toggle (rounded to a double) and 1e-13 to 1e-12 rad either side: every pose in reach
    (within the margin's allowance; the inner toggle's are just past it), no NaN, both engines' joints where 50
    digits put them within the toggle's own conditioning (a rounding delta of the squared area, at most about
    32 eps (r1 + r2)^2 dd, moves the joint by sqrt(delta) / (2 |d|): sqrt(32 eps) (r1 + r2) / 2, 5.7e-6 mm; they
    are off by about 6e-7) and from each other (their rounding differs: up to about 1e-8 apart); well past it
    (0.01 rad) out of reach on one side only, on both engines."""
    linkage, toggles = _limited_four_bar()
    signs = list(linkage.base_signs)
    bound = math.sqrt(32 * np.finfo(float).eps) * (math.sqrt(500) + math.sqrt(12800)) / 2
    for toggle in toggles:
        t = toggle + np.concatenate([np.arange(-10, 11) * 1e-13, [-1e-12, 1e-12]])
        theirs = _numpy(linkage, t)
        got = compiled.positions(linkage.compiled_program, t[None, :], signs)
        assert got.ok.all() and theirs.ok.all()
        ref = reference(linkage, t)["B"]
        for z in (got.points["B"], theirs.points["B"]):
            assert not np.isnan(z).any()
            assert np.all(np.hypot(z.real - ref[:, 0], z.imag - ref[:, 1]) <= bound)
        assert np.all(np.abs(got.points["B"] - theirs.points["B"]) <= bound)
        far = np.array([toggle - 0.01, toggle + 0.01])
        reach = compiled.positions(linkage.compiled_program, far[None, :], signs).ok
        assert reach.tolist() == _numpy(linkage, far).ok.tolist() and reach.sum() == 1
