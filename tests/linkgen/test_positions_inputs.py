"""What positions() does with its inputs before the kernels run, on either engine: the encoded program cached on a
linkage (two linkages never share one, a changed linkage gets its own), and a value that is not finite anywhere in
the inputs refused by name (found from the inputs' least and largest value, no temporary array). No test times
anything.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import linkgen
from camgen.core.errors import SpecError
from linkgen.kinematics import compiled
from tests.linkgen.test_compiled_solver import GROUP
from linkgen.kinematics.linkage import Linkage
from tests.conftest import ROOT

def needs_numba(test):
    """A check of the compiled kernel: skipped without numba, and run by the worker that runs the kernel's own checks
    (tests/linkgen/test_compiled_solver.py's :data:`GROUP`), so that numba compiles the kernels once a run."""
    skip = pytest.mark.skipif(not compiled.available(), reason="numba is not installed (pip install '.[fast]')")
    return pytest.mark.xdist_group(GROUP)(skip(test))


def _linkage(name: str) -> Linkage:
    return linkgen.design_linkage(linkgen.load_spec(ROOT / "templates" / f"{name}.toml")).kinematics.linkage


def _angles(linkage: Linkage, n: int, offset: float = 0.0) -> np.ndarray:
    return linkage.revolution + offset + 2 * math.pi / n * np.arange(n)


@needs_numba
def test_two_linkages_share_neither_program_nor_results():
    jansen, klann = _linkage("jansen"), _linkage("klann")
    assert jansen.compiled_program is jansen.compiled_program          # encoded once a linkage
    assert jansen.compiled_program is not klann.compiled_program
    assert jansen.compiled_program.names != klann.compiled_program.names
    a = jansen.positions(_angles(jansen, 3000), engine="numba")
    b = klann.positions(_angles(klann, 3000), engine="numba")
    for name, xy in a.points.items():
        assert not any(np.shares_memory(xy, other) for other in b.points.values()), name
        assert np.abs(xy - jansen.positions(_angles(jansen, 3000)).points[name]).max() <= 1e-12, name
    for name, xy in b.points.items():
        assert np.abs(xy - klann.positions(_angles(klann, 3000)).points[name]).max() <= 1e-12, name


@needs_numba
def test_a_changed_linkage_gets_its_own_program():
    linkage = _linkage("jansen")
    before = linkage.compiled_program
    moved = replace(linkage, structure=replace(linkage.structure, points={
        **linkage.structure.points, "E": tuple(v + 1.0 for v in linkage.structure.points["E"])}))
    assert moved.compiled_program is not before
    assert not np.array_equal(moved.compiled_program.nums, before.nums)
    t = _angles(moved, 720)
    got = moved.positions(t, engine="numba", strict=False)
    want = moved.positions(t, strict=False)
    assert (got.ok == want.ok).all()
    for name, xy in want.points.items():
        assert np.abs(got.points[name][got.ok] - xy[want.ok]).max() <= 1e-12, name


@pytest.mark.parametrize("engine", ["numpy", pytest.param("numba", marks=pytest.mark.xdist_group(GROUP))])
@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan])
def test_a_value_that_is_not_finite_anywhere_is_refused_by_either_engine(engine, bad):
    if engine == "numba" and not compiled.available():
        pytest.skip("numba is not installed")
    linkage = _linkage("klann")
    t = _angles(linkage, 50)
    t[37] = bad
    with pytest.raises(SpecError, match=r"input: input (-?inf|nan) degrees is not a finite number"):
        linkage.positions(t, engine=engine)
    loose = linkage.positions(t, strict=False, engine=engine)
    assert not loose.ok[37] and loose.ok[:37].all() and loose.ok[38:].all()


@pytest.mark.parametrize("turns", [0.0, 3.9, 4.1, -7.0, 1e6])
def test_inputs_turns_away_from_the_drawing_give_the_same_poses(turns):
    """Inputs a whole number of turns from the drawn revolution, within the range positions() takes as near (4
    turns) and past it (unwrapped): the same poses as at the drawing's turn, to the rounding of the angles (an ulp
    of the shifted angle, times the leg's reach of under 200 mm, a few times over)."""
    linkage = _linkage("jansen")
    t = _angles(linkage, 360)
    shift = 2 * math.pi * round(turns)
    base, moved = linkage.positions(t), linkage.positions(t + shift)
    for name, xy in base.points.items():
        assert np.abs(moved.points[name] - xy).max() <= 1e-12 + 8 * np.spacing(abs(shift) + 10.0) * 200.0, name
