"""Cams over a range of speeds and loads per motion segment: the inertia's share of the torque against single-speed
builds, the contact's minimum crossing zero at the lift-off speed, a segment's load by hand."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from camgen.design import design_cam
from camgen.dynamics import spec_loading
from camgen.forces import cycle_mean, torque
from camgen.spec import load_spec
from tests.refusals import assert_refused

ROOT = Path(__file__).resolve().parent.parent
RDRD = ROOT / "templates" / "rdrd.toml"
LOADED = ("cam.rpm=300", "follower.mass=0.2", "follower.spring_rate=0.5", "follower.preload=5",
          "follower.load=3", 'cam.material="pla"')


def _design(template: Path = RDRD, sets: tuple[str, ...] = LOADED):
    return design_cam(load_spec(template, sets))


def _with_loads(folder: Path, loads: dict[int, float]) -> Path:
    """rdrd.toml with ``load = value`` in the motion tables named by index (--set takes no list indices)."""
    parts = RDRD.read_text().split("[[motion]]")
    for i, value in loads.items():
        parts[i + 1] = parts[i + 1].replace("\n", f"\nload = {value!r}\n", 1)
    path = folder / "loaded.toml"
    path.write_text("[[motion]]".join(parts))
    return path


def test_a_load_per_segment_by_hand(tmp_path):
    """8 N over the rise (0-120 degrees), -2 N over the return (180-300), none on the dwells. At 60 degrees (mid-rise
    of the cycloid: s = 10 mm, s' = 2 h / beta = 60 / pi mm/rad, s'' = 0) the torque is (preload 5 + rate 0.5 * 10 +
    load 3 + 8) * 60 / pi / 1000 N*m; on the dwell at 150 degrees (s = 20 mm, at rest) the contact force is 5 + 10 + 3
    = 18 N. Over a turn only the segments' loads do net work: 8 N over the 20 mm rise and -2 N back down the 20 mm
    return, 160 + 40 = 200 N*mm, so the mean torque is 200 / 2 pi / 1000 N*m."""
    design = _design(_with_loads(tmp_path, {0: 8.0, 2: -2.0}))
    ld = spec_loading(design.spec.follower, design.cam.follower, motion=design.spec.motion,
                      program=design.cam.program)
    omega = 300 * 2 * math.pi / 60
    at = np.radians([60.0, 150.0, 240.0, 330.0])
    m = design.cam.program.evaluate(at)
    assert ld.segments(at) == pytest.approx([8.0, 0.0, -2.0, 0.0], abs=0)
    assert torque(ld, omega, m, at)[0] == pytest.approx((5 + 0.5 * 10 + 3 + 8) * 60 / math.pi / 1000, rel=1e-12)
    assert ld.force(m, omega, at)[1] == pytest.approx(18.0, rel=1e-12)
    mean = cycle_mean(design.cam, lambda t, mm: torque(ld, omega, mm, t))
    assert mean == pytest.approx(200 / (2 * math.pi) / 1000, rel=1e-9)
    theta = np.linspace(0.0, 2 * math.pi, 400001)
    t = torque(ld, omega, design.cam.program.evaluate(theta), theta)
    forces, contact = design.speed["forces"], design.speed["contact"]
    assert forces["torque_max_N_m"] == pytest.approx(t.max(), rel=1e-9)
    assert forces["torque_rms_N_m"] == pytest.approx(math.sqrt(np.mean(t[:-1] ** 2)), rel=1e-6)
    assert contact["segment_loads_n"] == [{"segment": 0, "load_n": 8.0}, {"segment": 1, "load_n": 0.0},
                                          {"segment": 2, "load_n": -2.0}, {"segment": 3, "load_n": 0.0}]


def test_a_segments_load_at_its_bounds_and_with_a_table_refused(tmp_path):
    """-1e6 N (the bound) on the first dwell pulls the follower off there; 1e-12 beyond is refused by name, and so is
    a load per segment beside a load table."""
    design = _design(_with_loads(tmp_path, {1: -1e6}))
    assert design.speed["contact"]["holds"] is False
    assert 120.0 - 1e-9 <= design.speed["contact"]["force_min_at_deg"] <= 180.0 + 1e-9
    assert_refused(_with_loads(tmp_path, {0: 1e6 * (1 + 1e-12)}), {}, "motion[0].load: must be", tmp_path)
    assert_refused(_with_loads(tmp_path, {1: 2.0}), {"follower.load_table": [[0, 1], [180, 2]]},
                   "motion[1].load: give loads per segment or follower.load_table, not both", tmp_path)
