"""The six-bar search's population solved at once (:mod:`linkgen.synthesis.sixbar_batch`) against the general
solver's step-by-step path (not its fused kernels), design by design: the same poses reached, the same least margin
and transmission angle, the same turn of the tracer's link and the same reference joint; drawings the general solver
refuses are the ones marked not a linkage; and a population's energies are each design's own."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.core.errors import CamgenError
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.structure import plan
from linkgen.synthesis import sixbar, validate_task
from linkgen.synthesis.sixbar_types import TOPOLOGIES

#: random designs a type, in the search's box, and crank angles over a turn (rad)
DESIGNS, ANGLES = 60, np.linspace(0.0, 2 * math.pi, 48, endpoint=False)


def _problem(kind: str, timed: bool) -> sixbar.Problem:
    t = np.radians(np.arange(0.0, 360.0, 22.5))
    task = {"kind": "path", "linkage": kind, "points": np.column_stack([40 * np.cos(t), 20 * np.sin(2 * t) + 3 * t])
            .tolist(), "seed": 1, "starts": 1, "generations": 10, "population": 5}
    if timed:
        task["input_angles"] = np.degrees(t).tolist()
    return sixbar.problem_of(validate_task({"name": "b", "task": task}).task)


@pytest.mark.parametrize("kind", list(TOPOLOGIES))
def test_a_population_solved_at_once_is_each_design_by_the_general_solver(kind):
    from linkgen.synthesis.sixbar_batch import solve_many

    topo = TOPOLOGIES[kind]
    rng = np.random.default_rng(3)
    x = rng.uniform(-sixbar.SHAPE_BOX, sixbar.SHAPE_BOX, (10, DESIGNS))
    x[:2, 0] = x[2:4, 0]                                # A drawn on B (or E, C): not a linkage
    z = x[0::2] + 1j * x[1::2]
    joints = {"O2": np.zeros(DESIGNS, complex), "O4": np.ones(DESIGNS, complex)} | {
        name: z[i] for i, name in enumerate(topo.free)}
    links = {k: tuple(j for j in v if j != "P") for k, v in topo.links.items()}
    got = solve_many(sixbar._program(kind), joints, links, topo.ground, ANGLES, topo.tracer_link, topo.reference)
    assert not got.drawn[0]
    reached = 0
    for j in range(DESIGNS):
        try:
            s = sixbar.structure_of(sixbar.drawing(x[:, j], topo), topo)
        except CamgenError:
            assert not got.drawn[j]
            continue
        assert got.drawn[j]
        linkage = Linkage(s, plan(s))
        # ``upto`` all the steps: the general step-by-step placement, not the fused kernels
        sol = linkage.solve(ANGLES[None, :], strict=False, derivatives=False, upto=len(linkage.plan.steps))
        assert np.array_equal(got.ok[j], sol.ok)
        ok = sol.ok
        reached += int(ok.sum())
        margin = np.min([d.margin for d in sol.dyads], axis=0)
        gamma = np.min([np.minimum(d.transmission, math.pi - d.transmission) for d in sol.dyads], axis=0)
        assert got.margin[j][ok] == pytest.approx(margin[ok], abs=1e-12)
        assert got.gamma[j][ok] == pytest.approx(gamma[ok], abs=1e-9)
        c, sn = sol.rotations[topo.tracer_link]
        assert got.rot[j][ok] == pytest.approx((c + 1j * sn)[ok], abs=1e-12)
        ref = sol.points[topo.reference]
        assert got.ref[j][ok] == pytest.approx((ref[:, 0] + 1j * ref[:, 1])[ok], abs=1e-12)
    assert reached > 0.1 * DESIGNS * len(ANGLES)       # the comparison saw poses reached, not only refusals


@pytest.mark.parametrize("timed", [True, False])
def test_a_population_s_energies_are_each_design_s_own(timed):
    """A population of 40 watt1 designs in one call, and each design alone: the same energies to rounding (the
    feasible among them too)."""
    p = _problem("watt1", timed)
    x = np.random.default_rng(5).uniform(-sixbar.SHAPE_BOX, sixbar.SHAPE_BOX, (10, 40))
    together = sixbar.objective(x, p)
    alone = np.array([sixbar.objective(x[:, j:j + 1], p)[0] for j in range(x.shape[1])])
    assert together == pytest.approx(alone, rel=1e-12)


def test_a_design_left_to_the_general_solver_has_the_energy_the_batch_gives_it(monkeypatch):
    """Every design of a population of 200 handed to the general solver (as one whose deltoid's pins meet is):
    the same energies as solved at once, to rounding."""
    import dataclasses

    p = _problem("watt1", True)
    x = np.random.default_rng(5).uniform(-sixbar.SHAPE_BOX, sixbar.SHAPE_BOX, (10, 200))
    batch = sixbar.objective(x, p)
    solve_many = sixbar.solve_many

    def every_one_general(*args):
        got = solve_many(*args)
        return dataclasses.replace(got, general=np.ones_like(got.general))

    monkeypatch.setattr(sixbar, "solve_many", every_one_general)
    assert np.sum(batch < sixbar.BIG) > 0
    assert sixbar.objective(x, p) == pytest.approx(batch, rel=1e-10)
