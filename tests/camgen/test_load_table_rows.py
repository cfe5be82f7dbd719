"""A long ``follower.load_table`` costs work in proportion to its rows (issue 30: a 10 000-row table took time about
quadratic in its rows, the torque's means evaluating the whole table once a row).

The work is counted, not timed: how many times the table is interpolated and over how many cam angles in all. A
table of n rows splits the turn into about n stretches of 64 Gauss-Legendre nodes each, so the angles grow as n;
the calls must not. The figures are checked against a quadrature of the same torque made here, and against the
same table given with its rows at 360 degrees repeated (which splits nothing more).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.api import design_cam
from camgen.dynamics import LoadTable
from camgen.spec import load_spec
from tests.conftest import ROOT

RDRD = ROOT / "templates" / "rdrd.toml"
LOADED = ("cam.rpm=300", "follower.mass=0.2", "follower.spring_rate=0.5", "follower.preload=5")


def _table(rows: int) -> list[list[float]]:
    """A load of 10 sin(3 theta) N sampled at ``rows`` cam angles evenly spaced over the turn."""
    angles = np.linspace(0.0, 360.0, rows, endpoint=False)
    return [[float(a), float(10.0 * math.sin(3 * math.radians(a)))] for a in angles]


def _counted(monkeypatch: pytest.MonkeyPatch, rows: int) -> tuple[object, int, int]:
    """The design of rdrd with a table of ``rows`` rows, the table's interpolations counted: (design, calls, angles
    interpolated in all)."""
    calls, angles = [0], [0]
    original = LoadTable.__call__

    def counting(self: LoadTable, theta: np.ndarray) -> np.ndarray:
        calls[0] += 1
        angles[0] += np.size(theta)
        return original(self, theta)

    monkeypatch.setattr(LoadTable, "__call__", counting)
    table = "[" + ", ".join(f"[{a!r}, {v!r}]" for a, v in _table(rows)) + "]"
    design = design_cam(load_spec(RDRD, (*LOADED, f"follower.load_table={table}")))
    monkeypatch.setattr(LoadTable, "__call__", original)
    return design, calls[0], angles[0]


def test_the_tables_interpolations_do_not_grow_with_its_rows(monkeypatch):
    """The peak searches and the means interpolate the table a bounded number of times (about 50 to 75 here,
    fewer with more rows as the searches' refinement settles sooner; it was about one a row more: 274 at 200 rows,
    4055 at 4000), and the angles interpolated grow as the rows: once a node of each row's stretch in each mean."""
    counts = {rows: _counted(monkeypatch, rows)[1:] for rows in (200, 4000)}
    (calls_small, angles_small), (calls_large, angles_large) = counts[200], counts[4000]
    assert calls_large <= calls_small <= 100
    # the nodes a mean gains, 64 a stretch and a stretch a row, less what the searches' own angles vary by
    nodes = 64 * (4000 - 200)
    assert nodes / 2 <= angles_large - angles_small <= 8 * nodes


def test_a_long_tables_torque_figures_against_a_quadrature():
    """The torque T = F s' / 1000 with F = preload + rate s + mass a + table(theta) (the table interpolated here
    with numpy's periodic interp, independently of the cam's Loading): its RMS by a 400 001-point trapezoid, and its
    mean (the spring and inertia do no net work over a turn, only the table does)."""
    rows = _table(3000)
    table = "[" + ", ".join(f"[{a!r}, {v!r}]" for a, v in rows) + "]"
    design = design_cam(load_spec(RDRD, (*LOADED, f"follower.load_table={table}")))
    forces = design.speed.forces
    theta = np.linspace(0.0, 2 * math.pi, 400001)
    m = design.cam.program.evaluate(theta)
    omega = 300 * 2 * math.pi / 60
    load = np.interp(theta, np.radians([a for a, _ in rows]), [v for _, v in rows], period=2 * math.pi)
    force = 5.0 + 0.5 * m[0] + 0.2 * omega ** 2 * m[2] / 1000.0 + load
    t = force * m[1] / 1000.0
    rms = math.sqrt(np.trapezoid(t ** 2, theta) / (2 * math.pi))
    assert forces.torque_rms == pytest.approx(rms, rel=1e-6)
    assert forces.torque_max == pytest.approx(t.max(), abs=1e-6)
    assert forces.torque_min == pytest.approx(t.min(), abs=1e-6)
