"""An impossible path task gets its nearest candidates, not a refusal: the command exits 0 with a ``note:`` line
naming the requirement that binds; each row says by how much it breaks it, has no defect, and its transmission
angle, recomputed here by the cosine rule from its lengths, is the row's and falls short by the row's violation."""
from __future__ import annotations

import json
import math

import numpy as np
from click.testing import CliRunner

from linkgen.cli import main

#: the six-point line (templates/synth-line6.toml) asking a transmission angle of 85 degrees: a Grashof crank
#: within these lengths cannot keep it over a whole turn (the best such linkages reach about 77 degrees)
TASK = """name = "line6-85"

[task]
kind = "path"
points = [[20, 20], [20, 25], [20, 30], [20, 35], [20, 40], [20, 45]]
input_angles = [30, 45, 60, 75, 90, 105]
crank = true
link_range = [5, 60]
min_transmission = 85
starts = 2
generations = 300
candidates = 3
seed = 1
"""


def _worst_transmission_deg(ground: float, crank: float, coupler: float, rocker: float) -> float:
    """The least of gamma and 180 - gamma (degrees) over a whole turn of the crank, gamma the angle between coupler
    and rocker: cos gamma = (coupler^2 + rocker^2 - z^2) / (2 coupler rocker), z^2 = ground^2 + crank^2 - 2 ground
    crank cos theta, on 200,001 crank angles and at the two where z is extreme (theta 0 and pi)."""
    theta = np.r_[np.linspace(0.0, 2.0 * math.pi, 200_001), 0.0, math.pi]
    z2 = ground**2 + crank**2 - 2.0 * ground * crank * np.cos(theta)
    gamma = np.degrees(np.arccos(np.clip((coupler**2 + rocker**2 - z2) / (2.0 * coupler * rocker), -1.0, 1.0)))
    return float(np.min(np.minimum(gamma, 180.0 - gamma)))


def test_an_impossible_transmission_gets_the_nearest_candidates(tmp_path):
    template = tmp_path / "line6-85.toml"
    template.write_text(TASK)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["synthesize", str(template), "-o", str(out)])
    assert result.exit_code == 0, result.output
    notes = [line for line in result.output.splitlines() if line.startswith("note: ")]
    assert len(notes) == 1 and notes[0].startswith("note: task.min_transmission: ") and "nearest" in notes[0]
    rows = json.loads((out / "summary.json").read_text())["candidates"]
    assert rows
    assert [r["violation"] for r in rows] == sorted(r["violation"] for r in rows)
    for row in rows:
        assert row["defects"] == [] and row["bound_by"] == "task.min_transmission"
        assert row["violation_unit"] == "degrees"
        worst = _worst_transmission_deg(row["ground"], row["crank"], row["coupler"], row["rocker"])
        assert abs(worst - row["transmission_worst_deg"]) < 1e-6
        assert worst < 85.0 and abs((85.0 - worst) - row["violation"]) < 1e-6
        assert row["violations"]["task.min_transmission"] == row["violation"]
        assert (out / row["template"]).is_file()


def test_a_task_that_can_be_met_has_no_violation_in_its_rows(tmp_path):
    """The same task at 30 degrees: candidates keep the limit (by the cosine rule here), no row has a violation."""
    template = tmp_path / "line6.toml"
    template.write_text(TASK.replace("min_transmission = 85", "min_transmission = 30"))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["synthesize", str(template), "-o", str(out)])
    assert result.exit_code == 0, result.output
    for row in json.loads((out / "summary.json").read_text())["candidates"]:
        assert "violation" not in row
        assert _worst_transmission_deg(row["ground"], row["crank"], row["coupler"], row["rocker"]) >= 30.0 - 1e-6
