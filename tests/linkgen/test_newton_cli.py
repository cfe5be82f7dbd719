"""``linkgen analyze T.toml --angle 60 --newton 30,100 --tolerance 1e-5`` (issue 30, "also asked"): Newton-Raphson
as the course teaches it, from the user's start to the user's tolerance on the residual norm (mm), its table
against :meth:`FourBar.newton` and the closed form; every bad use one line naming the option, exit 2, no file."""
from __future__ import annotations

import functools
import json
import math
import re

import numpy as np
import pytest
from click.testing import CliRunner

from linkgen.cli import main
from linkgen.kinematics.fourbar import FourBar
from tests.conftest import ROOT

EXERCISE = (100.0, 125.0, 75.0, 163.0)          # the course's Exercise 3.1, rocker 163: crank 60 is in reach


def template(tmp_path, lengths=EXERCISE, **extra: str):
    path = tmp_path / "t.toml"
    body = "\n".join(f"{k} = {v}" for k, v in zip(("ground", "crank", "coupler", "rocker"), lengths, strict=True))
    more = "".join(f'{k} = "{v}"\n' for k, v in extra.items())
    path.write_text(f'name = "t"\n[linkage]\ntype = "four-bar"\n{body}\n{more}')
    return path


def analyze(path, *args, out):
    return CliRunner().invoke(main, ["analyze", str(path), "-o", str(out), *map(str, args)])


def test_the_table_is_newtons_from_the_given_start_to_the_given_tolerance(tmp_path):
    result = analyze(template(tmp_path), "--angle", 60, "--newton", "30,100", "--tolerance", "1e-5", "--json",
                     out=tmp_path / "out")
    assert result.exit_code == 0, result.output
    n = json.loads(result.output)["newton"]
    fb = FourBar(*EXERCISE)
    theta2 = math.radians(60)
    ref = fb.newton(theta2, (math.radians(30), math.radians(100)), tolerance_mm=1e-5)
    assert [(s["iteration"], s["coupler_deg"], s["rocker_deg"], s["residual_mm"]) for s in n["iterations"]] == [
        (s.iteration, math.degrees(s.theta3), math.degrees(s.theta4), s.residual) for s in ref.steps]
    rows = n["iterations"]
    assert (rows[0]["coupler_deg"], rows[0]["rocker_deg"]) == (pytest.approx(30, abs=1e-13), pytest.approx(100))
    # the course's iteration, written here: x <- x - J^-1 f on the loop closure (no step needed halving here)
    l1, l2, l3, l4 = EXERCISE
    x = np.radians([30.0, 100.0])
    for s in rows:
        assert (s["coupler_deg"], s["rocker_deg"]) == (pytest.approx(math.degrees(x[0]), abs=1e-11),
                                                        pytest.approx(math.degrees(x[1]), abs=1e-11))
        f = [l2 * math.cos(theta2) + l3 * math.cos(x[0]) - l4 * math.cos(x[1]) - l1,
             l2 * math.sin(theta2) + l3 * math.sin(x[0]) - l4 * math.sin(x[1])]
        jac = [[-l3 * math.sin(x[0]), l4 * math.sin(x[1])], [l3 * math.cos(x[0]), -l4 * math.cos(x[1])]]
        x = x - np.linalg.solve(jac, f)
    # the course's test: it stops at the first estimate whose residual norm is at most the tolerance
    assert rows[-1]["residual_mm"] <= 1e-5 < rows[-2]["residual_mm"]
    for s in rows:                                    # each row's residual is the loop closure's at its angles
        f = fb.residual(theta2, math.radians(s["coupler_deg"]), math.radians(s["rocker_deg"]))
        assert s["residual_mm"] == pytest.approx(math.hypot(*f), rel=1e-12)
    # the closed form, within what the last residual allows: |error| <= |f| / (smallest singular value of J)
    exact = fb.positions([theta2], n["assembly"])
    t3, t4 = exact.theta3[0], exact.theta4[0]
    jac = np.array([[-fb.coupler * math.sin(t3), fb.rocker * math.sin(t4)],
                    [fb.coupler * math.cos(t3), -fb.rocker * math.cos(t4)]])
    bound = 2 * rows[-1]["residual_mm"] / np.linalg.svd(jac, compute_uv=False).min()
    off = max(abs(math.remainder(math.radians(rows[-1]["coupler_deg"]) - t3, 2 * math.pi)),
              abs(math.remainder(math.radians(rows[-1]["rocker_deg"]) - t4, 2 * math.pi)))
    assert off <= bound and n["agrees_with_closed_form_deg"] == pytest.approx(math.degrees(off), rel=1e-9, abs=1e-15)
    assert n["assembly"] == "open" and n["tolerance_mm"] == 1e-5 and n["start_deg"] == [30.0, 100.0]


def test_the_printed_table_has_a_row_an_iteration_to_the_tolerances_digits(tmp_path):
    result = analyze(template(tmp_path), "--angle", 60, "--newton", "30,100", "--tolerance", "1e-5",
                     out=tmp_path / "out")
    assert result.exit_code == 0, result.output
    fb = FourBar(*EXERCISE)
    ref = fb.newton(math.radians(60), (math.radians(30), math.radians(100)), tolerance_mm=1e-5)
    lines = result.output.splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith("Newton-Raphson (given: coupler 30 degrees"))
    assert "stopping at a residual of 1e-05 mm" in lines[head] and "theta3 (deg)" in lines[head + 1]
    # 1e-5 mm turns the 163 mm rocker by 3.5e-6 degrees: 7 decimals
    for step, line in zip(ref.steps, lines[head + 2:], strict=False):
        assert line.split() == [str(step.iteration), f"{math.degrees(step.theta3):.7f}",
                                f"{math.degrees(step.theta4):.7f}", f"{step.residual:.3e}"]
    assert re.match(r"residual below the tolerance: the open assembly, \S+ degrees from its closed form",
                    lines[head + 2 + len(ref.steps)])


def test_a_start_near_the_crossed_assembly_converges_to_it(tmp_path):
    fb = FourBar(*EXERCISE)
    crossed = fb.positions([math.radians(60)], "crossed")
    start = f"{math.degrees(crossed.theta3[0]) + 5:.3f},{math.degrees(crossed.theta4[0]) - 5:.3f}"
    result = analyze(template(tmp_path), "--angle", 60, "--newton", start, "--tolerance", "1e-8", "--json",
                     out=tmp_path / "out")
    n = json.loads(result.output)["newton"]
    assert n["assembly"] == "crossed" and n["agrees_with_closed_form_deg"] < 1e-6


def test_method_newton_takes_a_tolerance_and_still_starts_off_the_closed_form(tmp_path):
    result = analyze(template(tmp_path), "--angle", 60, "--method", "newton", "--tolerance", "1e-3", "--json",
                     out=tmp_path / "out")
    n = json.loads(result.output)["newton"]
    assert n["start"].startswith("closed-form answer moved by +10 degrees")
    assert n["iterations"][-1]["residual_mm"] <= 1e-3 < n["iterations"][-2]["residual_mm"]


def _refused(result, option: str, text: str, out) -> None:
    lines = result.stderr.strip().splitlines()
    assert result.exit_code == 2 and len(lines) == 1, result.output
    assert lines[0].startswith(f"error: {option}: ") and text in lines[0], lines[0]
    assert not out.exists() or not any(out.iterdir())


@pytest.mark.parametrize("args, option, text", [
    (["--newton", "30,100"], "--newton", "needs an input angle: add --angle"),
    (["--tolerance", "1e-5", "--method", "newton"], "--method", "needs an input angle"),
    (["--angle", "60", "--newton", "30"], "--newton", "must be two finite angles in degrees"),
    (["--angle", "60", "--newton", "30,100,5"], "--newton", "THETA3,THETA4 (e.g. 30,100; got '30,100,5')"),
    (["--angle", "60", "--newton", "a,b"], "--newton", "must be two finite angles"),
    (["--angle", "60", "--newton", "nan,100"], "--newton", "must be two finite angles"),
    (["--angle", "60", "--newton", "30,inf"], "--newton", "must be two finite angles"),
    (["--angle", "60", "--newton", ""], "--newton", "must be two finite angles"),
    (["--angle", "60", "--newton", "30,100", "--tolerance", "0"], "--tolerance", "finite number of mm > 0 (got 0)"),
    (["--angle", "60", "--newton", "30,100", "--tolerance", "-1e-5"], "--tolerance", "> 0 (got -1e-05)"),
    (["--angle", "60", "--newton", "30,100", "--tolerance", "nan"], "--tolerance", "> 0 (got nan)"),
    (["--angle", "60", "--newton", "30,100", "--tolerance", "inf"], "--tolerance", "> 0 (got inf)"),
    (["--angle", "60", "--newton", "30,100", "--tolerance", "1e-20"], "--tolerance", "must be at least 1.63e-10 mm"),
    (["--angle", "60", "--tolerance", "1e-5"], "--tolerance", "add --newton THETA3,THETA4 (or --method newton)"),
    # coupler and rocker in line in the start: the Jacobian is singular at iteration 0
    (["--angle", "60", "--newton", "30,30"], "--newton", "singular Jacobian at iteration 0"),
    (["--angle", "60", "--newton", "30,210"], "--newton", "singular Jacobian at iteration 0"),
    (["--angle", "10", "--newton", "30,100"], "--angle", "out of reach"),
])
def test_bad_newton_input_is_one_line_naming_the_option(tmp_path, args, option, text):
    _refused(analyze(template(tmp_path), *args, out=tmp_path / "out"), option, text, tmp_path / "out")


def test_no_convergence_within_the_iteration_limit_is_one_line(tmp_path, monkeypatch):
    monkeypatch.setattr(FourBar, "newton", functools.partialmethod(FourBar.newton, max_iter=2))
    result = analyze(template(tmp_path), "--angle", 60, "--newton", "30,100", "--tolerance", "1e-5",
                     out=tmp_path / "out")
    _refused(result, "--newton", "Newton-Raphson did not converge in 2 iterations at crank angle 60 degrees",
             tmp_path / "out")


@pytest.mark.parametrize("path, args, text", [
    (ROOT / "templates" / "slider-crank.toml", ["--angle", "30", "--newton", "30,100"],
     "the Newton-Raphson table is for linkage.type 'four-bar' (this is 'slider-crank')"),
    (ROOT / "templates" / "hoekens.toml", ["--angle", "30", "--newton", "30,100"], "(this is 'hoekens')"),
    (ROOT / "templates" / "jansen.toml", ["--angle", "30", "--newton", "30,100"], "(this is 'linkage')"),
    (None, ["--angle", "100", "--newton", "30,100"], "for a four-bar driven by its crank"),
])
def test_newton_is_refused_where_there_is_no_crank_driven_four_bar(tmp_path, path, args, text):
    if path is None:
        path = template(tmp_path, (180.0, 80.0, 200.0, 150.0), input="rocker")
    _refused(analyze(path, *args, out=tmp_path / "out"), "--newton", text, tmp_path / "out")
