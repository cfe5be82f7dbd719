"""``linkgen analyze``: the report the issue names, every linkage type, the Newton table, bad input."""
from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest
from click.testing import CliRunner

from linkgen.cli import main
from tests.conftest import ROOT

CRANK_ROCKER = ROOT / "templates" / "crank-rocker.toml"


def run(*args, tmp):
    result = CliRunner().invoke(main, ["analyze", *map(str, args), "-o", str(tmp)])
    return result


def test_crank_rocker_report(tmp_path):
    result = run(CRANK_ROCKER, "--angle", "30", "--json", "--figures", tmp=tmp_path)
    assert result.exit_code == 0, result.output
    r = json.loads(result.output)
    assert (r["grashof_class"], r["inversion"], r["input_range_deg"]) == ("I", "crank-rocker", None)
    assert r["transmission_min_deg"] == pytest.approx(math.degrees(math.acos(0.875)), abs=1e-9)
    assert r["transmission_max_deg"] == pytest.approx(math.degrees(math.acos(-0.085)), abs=1e-9)
    assert [d["kind"] for d in r["dead_centres"]] == ["extended", "folded"]
    assert all(set(d) >= {"kind", "crank_deg", "rocker_deg"} for d in r["dead_centres"])
    assert r["time_ratio"] == pytest.approx(1.3519225939837, rel=1e-12)
    for assembly in ("open", "crossed"):
        p = r["positions"][assembly]
        assert set(p) >= {"coupler_deg", "rocker_deg", "transmission_deg"}
        assert p["crank_deg"] == pytest.approx(30.0)
    assert r["positions"]["open"]["transmission_deg"] == pytest.approx(r["positions"]["crossed"]["transmission_deg"])
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([
        "crank-rocker.json", "crank-rocker-transmission.png", "crank-rocker-transmission.svg",
        "crank-rocker-dead-centres.png", "crank-rocker-dead-centres.svg",
        "crank-rocker-pose.png", "crank-rocker-pose.svg", "crank-rocker.html"])   # --angle draws the pose too
    assert r["warnings"] and "outside the usual 40-140" in r["warnings"][0]


def test_newton_table_is_printed(tmp_path):
    result = run(CRANK_ROCKER, "--angle", "30", "--method", "newton", "--set", "output.formats=['json']",
                 tmp=tmp_path)
    assert result.exit_code == 0, result.output
    assert "Newton-Raphson" in result.output
    report = json.loads((tmp_path / "crank-rocker.json").read_text())
    rows = report["newton"]["iterations"]
    assert rows[-1]["residual_mm"] <= 1e-12 * 200
    assert report["newton"]["agrees_with_closed_form_deg"] < 1e-10


@pytest.mark.parametrize("table, keys", [
    ({"type": "slider-crank", "crank": 50.0, "rod": 200.0, "offset": 20.0}, {"stroke_mm", "time_ratio"}),
    ({"type": "slider-crank", "crank": 50.0, "rod": 200.0}, {"approximation_error_max_mm"}),
    ({"type": "scotch-yoke", "crank": 40.0}, {"stroke_mm"}),
    ({"type": "whitworth", "crank": 100.0, "ground": 40.0, "arm": 60.0, "rod": 200.0}, {"time_ratio"}),
    ({"type": "crank-shaper", "crank": 50.0, "ground": 150.0, "lever": 300.0}, {"lever_swing_deg"}),
    ({"type": "chebyshev", "size": 20.0}, {"straightness"}),
    ({"type": "hoekens", "size": 20.0}, {"straightness"}),
    ({"type": "roberts", "size": 20.0}, {"straightness"}),
    ({"type": "watt", "size": 20.0}, {"straightness"}),
    ({"type": "four-bar", "ground": 100.0, "crank": 70.0, "coupler": 60.0, "rocker": 80.0}, {"input_range_deg"}),
    ({"type": "four-bar", "ground": 180.0, "crank": 80.0, "coupler": 200.0, "rocker": 150.0, "input": "rocker"},
     {"dead_centres"}),
])
def test_every_linkage_type(tmp_path, table, keys):
    body = "\n".join(f"{k} = {json.dumps(v)}" for k, v in table.items())
    path = tmp_path / "t.toml"
    path.write_text(f'name = "t"\n[linkage]\n{body}\n')
    angle = {"rocker": "100"}.get(table.get("input"), "60")     # inside every input range here
    result = run(path, "--angle", angle, "--json", "--figures", tmp=tmp_path / "out")
    assert result.exit_code == 0, result.output
    r = json.loads(result.output)
    assert keys <= set(r) and "positions" in r
    if "slider_mm" in r["positions"]:
        assert r["positions"]["crank_deg"] == pytest.approx(60.0)
    assert any(name.endswith(".png") for name in r["files"].values())


def test_rocker_input_reports_dead_points(tmp_path):
    path = tmp_path / "t.toml"
    path.write_text(CRANK_ROCKER.read_text().replace('rocker = 150.0', 'rocker = 150.0\ninput = "rocker"'))
    r = json.loads(run(path, "--json", tmp=tmp_path / "o").output)
    assert r["inversion"] == "rocker-crank"
    assert all(d["meaning"].startswith("dead point") for d in r["dead_centres"])
    # one swing range for each assembly, each as wide as the rocker's swing: the angles at O4 in triangle
    # O2-B-O4 with O2B = 280 (extended) and 120 (folded), by the law of cosines
    at_o4 = [math.degrees(math.acos((180**2 + 150**2 - d**2) / (2 * 180 * 150))) for d in (280, 120)]
    swing = at_o4[0] - at_o4[1]
    assert [hi - lo for lo, hi in r["input_range_deg"]] == [pytest.approx(swing, abs=1e-8)] * 2


@pytest.mark.parametrize("sets, message", [
    (["linkage.crank=-5"], "linkage.crank: must be > 0 mm (got -5)"),
    (["linkage.crank=nan"], "linkage.crank: must be a finite number"),
    (["linkage.rocker=1000"], "linkage.rocker: 1000 mm is not shorter than the other three links together"),
    (["linkage.type='five-bar'"], "linkage.type: unknown value 'five-bar' (did you mean 'four-bar'?); one of "
                                  "four-bar, slider-crank, scotch-yoke, whitworth, crank-shaper, chebyshev, hoekens, "
                                  "roberts, watt"),
    (["linkage.colour=1"], "linkage.colour: unknown key"),
    (["linkage.coupler=60", "linkage.crank=70", "linkage.ground=100", "linkage.rocker=80"],
     "angle: crank angle 200 degrees is out of reach; this linkage reaches crank angles [-109.616, 109.616]"),
])
def test_bad_input_is_one_line_exit_2_and_no_files(tmp_path, sets, message):
    args = [CRANK_ROCKER, "--angle", "200"]
    for s in sets:
        args += ["--set", s]
    result = run(*args, tmp=tmp_path / "out")
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and message in lines[0]
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_newton_needs_an_angle(tmp_path):
    result = run(CRANK_ROCKER, "--method", "newton", tmp=tmp_path)
    assert result.exit_code == 2 and "--method: the Newton-Raphson table needs an input angle" in result.stderr


def test_console_script_as_a_process(tmp_path):
    done = subprocess.run([sys.executable, "-m", "linkgen", "analyze", str(CRANK_ROCKER), "--json",
                           "--set", "output.formats=['json']"], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["inversion"] == "crank-rocker"
    assert (tmp_path / "out" / "crank-rocker" / "crank-rocker.json").exists()


@pytest.mark.parametrize("template, formats, named", [
    ("slider-crank.toml", '["json", "dxf"]', "'dxf' writes"),                # no [parts] table
    ("slider-crank.toml", '["json", "stl", "3mf"]', "'stl', '3mf' write"),
    ("crank-rocker.toml", '["cut-svg", "json"]', "'cut-svg' writes"),         # analyze makes no parts
])
def test_parts_formats_named_without_parts_are_refused(tmp_path, template, formats, named):
    """A parts' format named in ``output.formats`` of a design made without parts is one line, not files quietly
    left out; the default list (which has them) still writes what it can."""
    result = CliRunner().invoke(main, ["analyze", str(ROOT / "templates" / template), "-o", str(tmp_path / "out"),
                                       "--set", f"output.formats={formats}"])
    assert result.exit_code == 2, result.output
    assert result.output.startswith(f"error: output.formats: {named} the linkage's parts, which `linkgen build`")
    assert result.output.count("\n") == 1 and not (tmp_path / "out").exists()
    default = CliRunner().invoke(main, ["analyze", str(ROOT / "templates" / template), "-o", str(tmp_path / "d")])
    assert default.exit_code == 0 and sorted(p.suffix for p in (tmp_path / "d").iterdir()) == [".html", ".json"]
