"""Motion from a table (law = "table"): a known law reproduced from its samples within the fit's stated error, the
stated continuity inside and at the ends, a return's table, the CSV read beside its template, bad tables refused."""
from __future__ import annotations

import shutil

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core.errors import SpecError
from camgen.api import design_cam
from camgen.laws import make_law
from camgen.laws.fitted import table_law
from camgen.numeric import left_of
from camgen.spec import load_spec, validate_spec
from tests.conftest import ROOT

TEMPLATE = ROOT / "templates" / "table-law.toml"
CYCLOIDAL = make_law("cycloidal")


def _rows(law, beta: float, lift: float, step: float = 2.5) -> np.ndarray:
    angle = np.arange(0.0, beta + 1e-9, step)
    return np.column_stack([angle, lift * law.derivatives(angle / beta)[0]])


@pytest.mark.parametrize("continuity", [2, 3, 4])
def test_a_known_law_comes_back_from_its_samples(continuity):
    """Cycloidal sampled every 2.5 degrees over 120 (20 mm): every row within the stated residual, which is within
    the asked tolerance, and the displacement between the rows, velocity and acceleration close to the law's."""
    law = table_law(_rows(CYCLOIDAL, 120.0, 20.0), 120.0, 20.0, continuity=continuity, fit_tolerance=0.002)
    rows = _rows(CYCLOIDAL, 120.0, 20.0)
    fitted = 20.0 * law.derivatives(rows[:, 0] / 120.0)[0]
    assert np.max(np.abs(fitted - rows[:, 1])) == pytest.approx(law.residual * 20.0, rel=1e-12)
    assert law.residual * 20.0 <= 0.002
    u = np.linspace(0.0, 1.0, 20001)
    error = np.abs(law.derivatives(u) - CYCLOIDAL.derivatives(u)).max(axis=1) * 20.0
    assert error[0] <= 2 * 0.002                            # between the rows as close as at them
    peaks = 20.0 * CYCLOIDAL.peaks()                        # 40 mm, 126 mm per unit u and u^2
    assert error[1] < 1e-3 * peaks[0] and error[2] < 2e-2 * peaks[1]


@pytest.mark.parametrize("continuity", [2, 3, 4])
def test_the_stated_continuity_holds_at_every_knot_and_the_ends_meet_dwells(continuity):
    law = table_law(_rows(CYCLOIDAL, 120.0, 20.0, 10.0), 120.0, 20.0, continuity=continuity, fit_tolerance=0.05)
    assert len(law.knots) >= 2
    for knot in law.knots:
        left, right = law.derivatives(left_of(float(knot))), law.derivatives(float(knot))
        for order in range(4):
            step = abs(float(right[order] - left[order]))
            if order <= continuity:
                assert step < 1e-6, (knot, order, step)
            else:
                assert step > 1e-3, (knot, order, step)      # a cubic's jerk steps at its knots
    ends = law.derivatives(np.array([0.0, 1.0]))
    assert ends[0].tolist() == pytest.approx([0.0, 1.0], abs=1e-12)
    assert np.abs(ends[1:3]).max() < 1e-10
    assert [k for _, k, _ in law.jumps() if k < 3] == []    # no velocity or acceleration jump against dwells
    inside = [u for u, k, _ in law.jumps() if k == 3 and 0 < u < 1]
    assert bool(inside) == (continuity == 2)               # a jerk step at a knot only for a cubic


def test_a_return_reads_its_table_from_the_lift_down():
    rise = table_law(_rows(CYCLOIDAL, 90.0, 10.0), 90.0, 10.0, fit_tolerance=0.001)
    down = _rows(CYCLOIDAL, 90.0, 10.0)
    down[:, 1] = down[::-1, 1]
    back = table_law(down, 90.0, 10.0, falling=True, fit_tolerance=0.001)
    u = np.linspace(0, 1, 101)
    assert np.abs(rise.derivatives(u) - back.derivatives(u)).max() < 1e-9


def test_the_template_reads_its_csv_beside_it_from_any_folder(tmp_path, monkeypatch):
    folder = tmp_path / "elsewhere"
    folder.mkdir()
    shutil.copy(TEMPLATE, folder)
    shutil.copy(ROOT / "templates" / "table-law.csv", folder)
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(camgen, ["build", str(folder / "table-law.toml"), "-o", "o", "--set",
                                         'output.formats=["json"]'])
    assert result.exit_code == 0, result.output
    assert "motion[0]: 31 rows fitted by a C3 spline" in result.output
    design = design_cam(load_spec(folder / "table-law.toml"))
    law, rows = design.cam.program.segments[0].law, np.loadtxt(ROOT / "templates" / "table-law.csv", delimiter=",",
                                                               skiprows=2)
    s = design.cam.program.evaluate(np.radians(rows[:, 0]))[0]
    assert np.max(np.abs(s - rows[:, 1])) == pytest.approx(law.residual * 15.0, rel=1e-9)
    assert law.residual * 15.0 <= 0.005


def _refused(tmp_path, change: str, words: str) -> None:
    result = CliRunner().invoke(camgen, ["build", str(TEMPLATE), "-o", str(tmp_path / "o"), "--set", change])
    assert result.exit_code == 2, result.output
    assert result.output.startswith(f"error: {words}") and result.output.count("\n") == 1, result.output
    assert not (tmp_path / "o").exists()


def test_bad_tables_are_refused_by_name(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("angle,lift\n0,0\n10,1\nten,2\n20,3\n")
    _refused(tmp_path, f'motion.0.file="{bad}"', "motion[0].file: line 4: expected two numbers, angle and value")
    few = tmp_path / "few.csv"
    few.write_text("0,0\n150,15\n")
    _refused(tmp_path, f'motion.0.file="{few}"', f"motion[0].file: '{few}' holds 2 rows of angle, value")
    _refused(tmp_path, 'motion.0.file="no-such.csv"', "motion[0].file: cannot read")
    _refused(tmp_path, 'motion.2.file="table-law.csv"', "motion[2].file: only for law 'table' (got law 'cycloidal')")
    _refused(tmp_path, "motion.0.continuity=5", "motion[0].continuity: must be >= 2 and <= 4 (got 5)")
    huge = tmp_path / "huge.csv"
    huge.write_bytes(b"0,0\n" * 600_000)
    _refused(tmp_path, f'motion.0.file="{huge}"', f"motion[0].file: '{huge}' is larger than 2 MB")


def test_noise_beyond_the_tolerance_is_refused_with_its_row():
    rows = _rows(CYCLOIDAL, 120.0, 20.0)
    rows[17, 1] += 0.5                                      # a misread row, at 42.5 degrees
    spec = validate_spec({"name": "t", "cam": {"base_radius": 40.0, "thickness": 5.0},
                          "follower": {"type": "translating-roller", "roller_radius": 5.0},
                          "motion": [{"type": "rise", "law": "table", "data": rows.tolist(), "lift": 20.0,
                                      "angle": 120.0, "fit_tolerance": 0.01},
                                     {"type": "return", "law": "cycloidal", "lift": 20.0, "angle": 240.0}]})
    with pytest.raises(SpecError) as caught:
        design_cam(spec)
    assert str(caught.value).startswith("motion[0].data: a spline of continuity C3 with 44 knots comes no closer "
                                        "than"), str(caught.value)
    at = float(str(caught.value).split("to the row at ")[1].split(" degrees")[0])
    # the misread row or one beside it
    assert abs(at - 42.5) <= 2.5 and "degrees (fit_tolerance 0.01)" in str(caught.value)
