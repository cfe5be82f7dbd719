"""The fused solver's outputs made as one block of each kind (issue 38, item 1: a long run's first writes fault once
a huge page): every output its own row of its block, no two sharing memory and no row left over, for every kind of
run (positions, with rates, the whole solve); and a kept result unchanged by later runs. No test here times
anything.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import linkgen
from linkgen.kinematics import fused
from linkgen.kinematics.linkage import FEASIBILITY_TOL, Linkage
from tests.conftest import ROOT

#: bundled linkages the fused kernels solve: legs, six-bars, a pantograph
FUSED = ("jansen", "klann", "watt1", "watt2", "stephenson3", "pantograph")


def _linkage(name: str) -> Linkage:
    linkage = linkgen.design_linkage(linkgen.load_spec(ROOT / "templates" / f"{name}.toml")).kinematics.linkage
    assert linkage.program is not None, name
    return linkage


def _arrays(out: fused.Outputs) -> list[np.ndarray]:
    """Every output array of a run but ``ok``."""
    found: list[np.ndarray] = []
    for field in ("points", "velocities", "accelerations", "rotations", "omegas", "alphas"):
        found += getattr(out, field).values()
    for field in ("margins", "transmissions", "slacks", "spreads"):
        found += getattr(out, field)
    return found


@pytest.mark.parametrize("name", FUSED)
@pytest.mark.parametrize(("derivatives", "extras"), [(False, False), (True, False), (False, True), (True, True)])
def test_each_output_is_a_row_of_its_block_none_shared_none_left(name, derivatives, extras):
    linkage = _linkage(name)
    n = 1000
    t = linkage.revolution + 2 * math.pi / n * np.arange(n)
    x = np.atleast_2d(linkage.unwrap(t))
    out = fused.run(linkage.program, x, np.ones(1), list(linkage.signs(x)), derivatives, extras, FEASIBILITY_TOL)
    arrays = _arrays(out)
    moving = sum(holder is not None for _, holder, _ in linkage.program.points)
    dyads = sum(isinstance(op, fused.RRROp) for op in linkage.program.ops)
    bodies = len(linkage.program.bodies)
    complexes = moving * (3 if derivatives else 1) + (bodies if extras else 0)
    reals = (2 * bodies if derivatives and extras else 0) + (dyads * (4 if derivatives else 3) if extras else 0)
    assert len(arrays) == complexes + reals
    blocks = {id(a.base): a.base for a in arrays}
    assert sorted(b.shape for b in blocks.values()) == sorted(
        s for s, count in (((complexes, n), complexes), ((reals, n), reals)) if count)
    for a in arrays:
        assert a.shape == (n,) and a.flags.c_contiguous
    for i, a in enumerate(arrays):                  # no two outputs overlap (a row handed out twice would)
        for b in arrays[i + 1:]:
            assert not np.shares_memory(a, b)


@pytest.mark.parametrize("name", FUSED)
def test_a_kept_result_is_unchanged_by_later_runs(name):
    linkage = _linkage(name)
    t = linkage.revolution + np.linspace(0.0, 2 * math.pi, 20_000, endpoint=False)
    first = linkage.positions(t, derivatives=True)
    kept = {k: v.copy() for k, v in first.points.items()}
    for shift in (0.3, 1.1):                        # other runs, of the same and another size, reuse freed memory
        linkage.positions(t + shift, derivatives=True)
        linkage.solve(t[:5000] + shift)
    for k, v in kept.items():
        assert np.array_equal(first.points[k], v), k
