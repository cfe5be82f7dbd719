"""The fused solver (issue 38, item 1) against the general path it replaces for a crank and RRR dyads.

The general path is the step-by-step solve that every other dyad kind still takes; a solve given a chooser
(here one that chooses nothing) always goes that way, so the two are compared on the same linkage, inputs and
branches: over 10^5 crank angles on every bundled linkage template and on seeded random Watt I and Stephenson III
six-bars, positions to 1e-12 mm, the same poses reached, every joint on the same side of its pins (the branch),
and the rates to 1e-9 relative. Jansen's foot is also checked against a 50-digit solution, and the bench's leg
against the bundled template. No test here times anything.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import linkgen
from camgen.core.errors import SpecError
from linkgen.bench_solver import reference
from linkgen.kinematics import fused
from linkgen.kinematics import linkage as solver
from linkgen.kinematics.dyads import cross
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.structure import Input, make_structure
from tests.conftest import ROOT
from tests.support.random_six_bars import random_six_bars

TEMPLATES = ("jansen", "klann", "watt1", "watt2", "stephenson1", "stephenson3", "shaper", "pendulum-pump",
             "toggle-press", "pantograph", "single-dwell")
#: the templates made of a crank and RRR dyads only: the fused kernels solve them
FUSED = {"jansen", "klann", "watt1", "watt2", "stephenson1", "stephenson3", "pantograph", "single-dwell"}
N = 100_000


def _linkage(name: str) -> Linkage:
    return linkgen.design_linkage(linkgen.load_spec(ROOT / "templates" / f"{name}.toml")).kinematics.linkage


def _both(linkage: Linkage, x: np.ndarray, derivatives: bool) -> tuple[solver.Solution, solver.Solution]:
    """The fused solve and the general one of the same inputs on the same branches."""
    x = np.atleast_2d(x)
    signs = linkage.signs(x)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):     # as Linkage.solve: +-inf marked
        fast = solver._solve(linkage, x, np.ones(1), list(signs), False, derivatives, None, None)
        general = solver._solve(linkage, x, np.ones(1), list(signs), False, derivatives, None, lambda i, r: None)
    return fast, general


def _inputs(linkage: Linkage, n: int = N) -> np.ndarray:
    """n crank angles over a turn from the revolution's start, unwrapped as solve does."""
    return linkage.unwrap(linkage.revolution + 2 * math.pi / n * np.arange(n))


def _sides(linkage: Linkage, sol: solver.Solution) -> list[np.ndarray]:
    """Each RRR's branch at each pose: the side of pin 1 -> pin 2 its joint lies on (0 where in line)."""
    out = []
    prog = linkage.program
    assert prog is not None
    for op in prog.ops:
        if isinstance(op, fused.RRROp):
            p1, p2 = solver.body_point(linkage.structure, sol, op.bodies[0], op.pins[0]), \
                solver.body_point(linkage.structure, sol, op.bodies[1], op.pins[1])
            c = cross(p2 - p1, sol.points[op.joint] - p1)
            out.append(np.where(np.abs(c) > 1e-9, np.sign(c), 0.0))
    return out


def _bound(sol: solver.Solution, tol: float = 1e-12) -> np.ndarray:
    """The tolerance (mm) of a position at each pose: ``tol``, loosened as 1 / margin where a dyad comes within a
    margin of 0.1 of its toggle (there any change of rounding moves the joint by about eps L / margin: the general
    solve is no closer to a 50-digit solution than that either, see the random six-bars)."""
    least = np.min([d.margin for d in sol.dyads], axis=0)
    return tol * np.maximum(1.0, 0.1 / np.maximum(least, 1e-300))


def _agree(linkage: Linkage, fast: solver.Solution, general: solver.Solution, rates: bool,
           tol: float = 1e-12) -> None:
    assert (fast.ok == general.ok).all()
    ok = general.ok
    assert ok.any()
    assert set(fast.points) == set(general.points)
    bound = _bound(general, tol)[ok]
    for name, xy in general.points.items():
        assert np.all(np.abs(fast.points[name][ok] - xy[ok]).max(axis=1) <= bound), name
    for body, (c, s) in general.rotations.items():
        fc, fs = fast.rotations[body]
        assert np.all(np.abs(fc[ok] - c[ok]) <= bound) and np.all(np.abs(fs[ok] - s[ok]) <= bound), body
    for a, b in zip(fast.dyads, general.dyads, strict=True):
        assert (a.kind, a.bodies, a.joint) == (b.kind, b.bodies, b.joint)
        for field in ("margin", "transmission", "slack"):
            assert np.all(np.abs(getattr(a, field)[ok] - getattr(b, field)[ok]) <= bound), field
    for sa, sb in zip(_sides(linkage, fast), _sides(linkage, general), strict=True):
        assert (sa[ok] == sb[ok]).all()                    # the same branch at every pose
    if not rates:
        return
    # rates to 1e-9 relative, loosened near a toggle as 1 / margin^2 (the 2x2 solve's determinant and the rates
    # themselves grow there)
    near = (_bound(general, 1.0)[ok] ** 2)
    for table in ("velocities", "accelerations", "omegas", "alphas"):
        for name, values in getattr(general, table).items():
            mine, want = getattr(fast, table)[name][ok], values[ok]
            scale = 1e-9 * np.maximum(1.0, np.abs(want)) * (near if want.ndim == 1 else near[:, None])
            assert np.all(np.abs(mine - want) <= scale), (table, name)
    for a, b in zip(fast.dyads, general.dyads, strict=True):
        assert b.spread is not None and a.spread is not None
        assert np.all(np.abs(a.spread[ok] - b.spread[ok]) <= 1e-9 * np.maximum(1.0, np.abs(b.spread[ok])) * near)


@pytest.mark.parametrize("name", TEMPLATES)
def test_the_fused_solver_equals_the_general_one_on_every_bundled_linkage(name):
    linkage = _linkage(name)
    assert (linkage.program is not None) == (name in FUSED)
    if linkage.program is None:
        return                                      # a slider or an RRP/RPR dyad: the general path solves it
    x = _inputs(linkage)
    _agree(linkage, *_both(linkage, x, False), rates=False)
    _agree(linkage, *_both(linkage, x[::10], True), rates=True)


@pytest.mark.parametrize("kind", ["watt", "stephenson"])
def test_the_fused_solver_equals_the_general_one_on_random_six_bars(kind):
    for linkage in random_six_bars(kind):
        assert linkage.program is not None
        x = _inputs(linkage)
        fast, general = _both(linkage, x, False)
        # random drawings reach 100-220 mm with links to 280 mm: 2e-12 mm a 100 mm of the drawing (about 40 ulp)
        tol = 2e-12 * max(1.0, linkage.structure.size / 100.0)
        _agree(linkage, fast, general, rates=False, tol=tol)
        # where the two differ most, both lie as close to a 50-digit solution as the bound allows
        apart = np.max([np.abs(fast.points[k] - v).max(axis=1) for k, v in general.points.items()], axis=0)
        worst = np.argsort(np.where(general.ok, apart, -1.0))[-4:]
        ref = reference(linkage, x[worst])
        for sol in (fast, general):
            for name, xy in ref.items():
                assert np.all(np.abs(sol.points[name][worst] - xy).max(axis=1) <= _bound(general, tol)[worst]), name
        _agree(linkage, *_both(linkage, x[::10], True), rates=True, tol=tol)


def test_positions_are_the_solves_points_and_ground_points_are_constants():
    linkage = _linkage("klann")
    t = np.radians(np.arange(0.0, 360.0, 0.7))
    pos, sol = linkage.positions(t), linkage.solve(t, derivatives=False)
    assert set(pos.points) == set(sol.points) and pos.ok.all()
    for name, xy in sol.points.items():
        assert np.array_equal(pos.points[name], xy)
    assert np.array_equal(pos.points["U"], np.broadcast_to(linkage.structure.points["U"], (len(t), 2)))
    assert not pos.points["U"].flags.writeable                 # one drawn row, not a copy per pose


@pytest.mark.parametrize("n", [1, fused.CHUNK - 1, fused.CHUNK, fused.CHUNK + 1, 3 * fused.CHUNK + 7])
def test_chunks_join_without_a_seam(n):
    linkage = _linkage("jansen")
    x = _inputs(linkage, n)
    fast, general = _both(linkage, x, True)
    _agree(linkage, fast, general, rates=True)


def test_an_unreachable_input_is_refused_alike_by_positions_and_solve():
    linkage = Linkage.of(make_structure({"O2": (0.0, 0.0), "O4": (100.0, 0.0), "A": (0.0, 70.0),
                                         "B": (20.0, 80.0)},
                                        {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("O4", "B")},
                                        ("O2", "O4"), (), (Input("crank", "crank", "O2"),)))
    assert linkage.program is not None
    bad = np.radians([90.0, 0.0])               # the crank cannot reach 0 degrees: the rocker's pin is too far
    with pytest.raises(SpecError) as by_solve:
        linkage.solve(bad, derivatives=False)
    with pytest.raises(SpecError) as by_positions:
        linkage.positions(bad)
    assert str(by_positions.value) == str(by_solve.value)
    pos = linkage.positions(bad, strict=False)
    assert pos.ok.tolist() == linkage.solve(bad, strict=False).ok.tolist()
    with pytest.raises(SpecError, match="finite"):
        linkage.positions([float("nan")])


def test_jansens_foot_equals_a_50_digit_solution():
    linkage = _linkage("jansen")
    t = _inputs(linkage, 360)[::3]
    ref = reference(linkage, t)
    pos = linkage.positions(t)
    for name, xy in ref.items():
        assert np.abs(pos.points[name] - xy).max() <= 1e-12, name      # Jansen's leg stays clear of toggles


def test_the_benchs_leg_is_the_bundled_template():
    """The bench's own Jansen leg (its holy numbers, drawn at 90 degrees) has the bundled template's joints and
    bar lengths: the foot lifts 22.457 mm, not the 47.7 mm of a leg with two bars swapped."""
    from linkgen import bench

    table = linkgen.load_spec(ROOT / "templates" / "jansen.toml")
    drawn = bench.jansen_points(math.pi / 2)
    template = _linkage("jansen").structure.points
    for name, xy in template.items():
        assert math.dist(drawn[name], xy) <= 1e-6, name
    foot = bench.jansen(math.pi / 2)
    leg = Linkage.of(foot).positions(np.radians(np.arange(0.0, 360.0, 0.1)) + math.pi / 2).points["G"]
    assert leg[:, 1].max() - leg[:, 1].min() == pytest.approx(22.457, abs=1e-3)
    assert leg[:, 0].max() - leg[:, 0].min() == pytest.approx(67.908, abs=1e-3)
    assert table is not None


def test_positions_far_from_the_drawn_turn_and_non_finite_rates_follow_the_general_rule():
    """Angles many turns away are the same poses; a pose the linkage cannot take (non-strict) has infinite rates,
    never NaN, as the general solve gives."""
    linkage = _linkage("watt1")
    t = np.radians(np.arange(0.0, 360.0, 1.0))
    near = linkage.positions(t)
    for turns in (3, 1000):                  # read on the drawn turn as they are, and unwrapped onto it
        far = linkage.positions(t + 2 * math.pi * turns)
        for name, xy in near.points.items():
            assert np.abs(far.points[name] - xy).max() <= 1e-9, name
    values = np.array([0.3, float("nan"), 1.2])
    fast = linkage.solve(values, strict=False)
    for name, v in fast.velocities.items():
        if name in linkage.structure.bodies["ground"]:
            continue
        assert not np.isnan(v).any() and np.isinf(v[1]).all(), name
        assert not np.isnan(fast.accelerations[name]).any(), name
    lean = linkage.positions(values, derivatives=True, strict=False)
    for name, v in lean.velocities.items():
        assert np.array_equal(v, fast.velocities[name]), name
