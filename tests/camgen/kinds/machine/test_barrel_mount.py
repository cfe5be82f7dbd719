"""A barrel cam mounted on a machine's shaft (issue 35): its follower's motion in the outputs (mm along the shaft, or
degrees of an arm's swing) equal to its program shifted by its phase; its drum a disc of its rim's radius in the
clash check, its follower placed there (see test_barrel_follower_clash); a coupling from it refused in one line; its
files among the machine's, the drum as long as it is in the assembly."""
from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from camgen.kinds.machine.clash import outlines

from tests.conftest import ROOT
from tests.support.refusals import assert_refused


def _machine(template: str, phase: float, extra: str = "") -> str:
    return f"""
name = "drums"

[machine]
main = "camshaft"
rpm = 30.0
frame = "one"

[[shafts]]
name = "camshaft"
at = [5.0, 15.0]

[output]
formats = ["stl", "json", "3mf"]

[[cams]]
name = "drum"
shaft = "camshaft"
layer = 1
phase = {phase}
template = "{ROOT / 'templates' / template}"
{extra}"""


def _design(text: str):
    from camgen import api

    return api.design(api.validate(tomllib.loads(text)))


@pytest.mark.parametrize(("template", "unit"), [("barrel.toml", "mm"), ("barrel-oscillating.toml", "deg")])
def test_the_followers_motion_is_its_program_shifted_by_the_phase(template, unit):
    design = _design(_machine(template, 75.0))
    program = design.cam("drum").design.cam.program
    expected = program.evaluate(np.mod(design.phi - math.radians(75.0), 2 * math.pi))
    row = {o.label: o for o in design.outputs}["cams.drum"]
    assert row.unit == unit
    assert np.allclose(row.values, expected[0], atol=1e-12)
    assert np.allclose(row.rate, expected[1], atol=1e-12)
    assert np.ptp(row.values) == pytest.approx(20.0 if unit == "mm" else np.ptp(expected[0]), abs=1e-9)


def test_the_drum_is_a_disc_of_its_rim_and_its_follower_is_placed():
    design = _design(_machine("barrel.toml", 0.0))
    drum = next(b for b in design.bodies if b.name == "cams.drum")
    assert (drum.low, drum.high) == (2, 2)
    placed = shapely.get_exterior_ring(outlines(drum, design.phi[:3]))
    radii = np.hypot(*(np.asarray(placed[1].coords) - (5.0, 15.0)).T)
    assert radii.max() == pytest.approx(33.0, abs=1e-9)           # the rim: pitch 30 + half the 6 mm groove
    assert radii.min() > 33.0 - 0.011                              # within the chords' 0.01 mm
    assert design.unchecked == ()                                  # its follower too (test_barrel_follower_clash)
    assert design.clashes == ()


def test_a_coupling_from_a_barrel_is_refused_in_one_line(tmp_path):
    extra = """
[[linkages]]
name = "bars"

[linkages.template.linkage]
type = "four-bar"
ground = 80.0
crank = 30.0
coupler = 90.0
rocker = 60.0

[[couplings]]
cam = "drum"
linkage = "bars"
rest = 60.0
"""
    path = tmp_path / "m.toml"
    path.write_text(_machine("barrel-oscillating.toml", 0.0, extra))
    assert_refused(path, {}, "couplings[0].cam: cams.drum is a barrel cam: its follower moves along the shaft (or "
                   "swings across it), out of the frame's plane, so it drives no planar linkage", tmp_path)


def test_the_barrels_files_are_the_machines_and_the_drum_stands_as_long_as_it_is(tmp_path: Path):
    from camgen.cli import main

    path = tmp_path / "m.toml"
    path.write_text(_machine("barrel.toml", 0.0))
    result = CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "out" / "drums.json").read_text())
    assert "drums-drum.stl" in report["files"].values()
    piece = next(p for p in report["assembly"]["pieces"] if p["name"] == "cams.drum")
    assert piece["thickness_mm"] == pytest.approx(50.0)
    assert piece["bounds_mm"] == pytest.approx([5 - 33.0, 15 - 33.0, 5 + 33.0, 15 + 33.0], abs=1e-6)
