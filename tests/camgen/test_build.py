"""``camgen build``: the files users take to the cutter and the printer, read back by the tools they use."""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.flat import build_cam
from camgen.cli import main
from camgen.core.shapes import Contour
from camgen.surface import surface_deviation
from tests.conftest import ROOT, template

TEMPLATE = ROOT / "templates" / "rdrd.toml"


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("rdrd")
    result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(out)])
    assert result.exit_code == 0, result.output
    return out, result


#: what a default build writes: every format but the figures
DEFAULT_FILES = ["rdrd.dxf", "rdrd-cut.svg", "rdrd.stl", "rdrd.3mf", "rdrd.json", "rdrd.html"]
#: what ``--figures`` (``output.figures = true``) adds
FIGURE_FILES = ["rdrd-svaj.png", "rdrd-svaj.svg", "rdrd-cam.png", "rdrd-cam.svg", "rdrd-checks.png",
                "rdrd-checks.svg"]


def test_all_files_are_written_and_no_temporaries_left(built):
    out, _ = built
    assert sorted(p.name for p in out.iterdir()) == sorted(DEFAULT_FILES)


@pytest.mark.parametrize("how", [["--figures"], ["--set", "output.figures=true"],
                                 ["--set", 'output.formats=["dxf","cut-svg","stl","3mf","json","html","png","svg"]'],
                                 ["--figures", "--set", 'output.formats=["json","png"]']])
def test_figures_are_written_when_asked(how, built, tmp_path):
    """The figures are on request, three ways alike: ``--figures``, ``output.figures = true``, or named in
    ``output.formats``; ``figures`` adds both figure formats to the formats given. The other files keep their bytes,
    but the report, which lists the files written."""
    result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(tmp_path), *how])
    assert result.exit_code == 0, result.output
    names = sorted(p.name for p in tmp_path.iterdir())
    formats = json.loads((tmp_path / "rdrd.json").read_text())["files"]
    if "json" in how[-1] and "--figures" in how:
        assert names == sorted(["rdrd.json", *FIGURE_FILES])
    else:
        assert names == sorted(DEFAULT_FILES + FIGURE_FILES)
    assert sorted(formats.values()) == names
    default, _ = built
    for name in set(names) & set(DEFAULT_FILES) - {"rdrd.json", "rdrd.html"}:
        assert (tmp_path / name).read_bytes() == (default / name).read_bytes(), name


def test_dxf_audit_units_layers_and_accuracy(built):
    import ezdxf

    out, _ = built
    doc = ezdxf.readfile(out / "rdrd.dxf")
    assert not doc.audit().has_errors
    assert doc.header["$INSUNITS"] == 4 and doc.header["$MEASUREMENT"] == 1
    polylines = doc.modelspace().query("LWPOLYLINE")
    circles = doc.modelspace().query("CIRCLE")
    assert len(polylines) == 1 and len(circles) == 1
    pl = polylines[0]
    assert pl.closed and pl.dxf.layer == "OUTLINE"
    assert circles[0].dxf.layer == "HOLES" and circles[0].dxf.radius == pytest.approx(5.0)
    assert tuple(circles[0].dxf.center)[:2] == (0.0, 0.0)
    # read back and compare with the exact surface (independent of the outline code)
    pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
    contour = Contour(pts[:, :2], pts[:, 2])
    v = contour.flatten(1e-6)
    w = np.roll(v, -1, axis=0)
    probes = (v[:, None, :] + (w - v)[:, None, :] * np.linspace(0, 1, 9)[None, :-1, None]).reshape(-1, 2)
    cam = build_cam(template())
    assert np.abs(surface_deviation(cam, probes)).max() <= 0.01
    report = json.loads((out / "rdrd.json").read_text())
    assert report["outline_vertices"] == len(pts)
    assert report["outline_arcs"] == int(np.count_nonzero(pts[:, 2]))


def test_stl_is_watertight_outward_with_the_expected_volume(built):
    import ezdxf
    import trimesh

    out, _ = built
    mesh = trimesh.load(out / "rdrd.stl")
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    pl = ezdxf.readfile(out / "rdrd.dxf").modelspace().query("LWPOLYLINE")[0]
    pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
    area = Contour(pts[:, :2], pts[:, 2]).area - np.pi * 5.0**2
    assert mesh.volume == pytest.approx(area * 8.0, rel=1e-3)
    assert mesh.bounds[0][2] == pytest.approx(0.0) and mesh.bounds[1][2] == pytest.approx(8.0)


def test_report_has_the_figures(built):
    out, result = built
    r = json.loads((out / "rdrd.json").read_text())
    for key in ("pressure_angle_max_deg", "pressure_angle_max_at_deg", "pitch_rho_min_mm", "profile_rho_min_mm",
                "undercut", "outline_vertices", "outline_max_error_mm", "tolerance_mm", "continuity"):
        assert key in r
    assert r["undercut"] is False and r["envelope"] is False
    assert 0 < r["outline_max_error_mm"] <= r["tolerance_mm"] == 0.01
    assert r["profile_rho_min_mm"] == pytest.approx(r["pitch_rho_min_mm"] - 10.0)
    assert {(j["at_deg"], j["quantity"]) for j in r["continuity"]} == {
        (0.0, "jerk"), (120.0, "jerk"), (180.0, "acceleration"), (300.0, "acceleration")}
    assert r["mesh"]["watertight"] is True
    assert "pressure angle max 18.84 deg" in result.output


def test_set_overrides_a_field(tmp_path):
    result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(tmp_path), "--set", "motion.0.lift=25",
                                       "--set", "motion.2.lift=25", "--set", "output.formats=['json']"])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rdrd.json"]
    assert json.loads((tmp_path / "rdrd.json").read_text())["lift_max_mm"] == 25.0


@pytest.mark.parametrize("sets, field", [
    (["cam.base_radius=0"], 'cam.base_radius: must be > 0 and <= 10000 mm, or "auto" (got 0)'),
    (["cam.base_radius=-5"], "cam.base_radius: must be > 0 and <= 10000 mm"),
    (["cam.base_radius='big'"], 'cam.base_radius: must be a number of mm or "auto"'),
    (["follower.roller_radius=nan"], "follower.roller_radius: must be a finite number"),
    (["cam.thickness=inf"], "cam.thickness: must be a finite number"),
    (["motion.0.lift=-1"], "motion[0].lift: must be > 0 and <= 10000 mm"),
    (["motion.0.angle=0"], "motion[0].angle: must be > 0 and <= 360 degrees"),
    (["motion.1.angle=50"], "motion: segment angles add up to 350 degrees"),
    (["motion.0.law='cycloid'"], "motion[0].law: unknown value 'cycloid' (did you mean 'cycloidal'?); one of uniform"),
    (["follower.offset=50"], "follower.offset: |offset| must be < the prime radius 50 mm"),
    (["cam.colour='red'"], "cam.colour: not a key of a disc cam; it takes: base_radius, thickness, "),
    (["motion.0.ratio=2"], "motion[0].ratio: not a parameter of law 'cycloidal'"),
    (["cam.bore=90"], "cam.bore: 90 mm leaves no material"),
    (["cam.base_radius=10", "cam.bore=0", "follower.offset=0", "motion.0.angle=40", "motion.1.angle=140"],
     "undercut at 33.14 degrees"),
    (["motion.0.law='polynomial'", "motion.0.conditions=[[0,0,0],[1,0,1],[1,0,0]]"],
     "motion[0].conditions: the conditions contradict each other"),
    (["motion.0.law='modified-uniform'", "motion.0.form='drafted'", "motion.0.angle=30", "motion.1.angle=150"],
     "motion[0].form: the drafted form needs"),
    (["motion.9.lift=3"], "--set motion.9.lift: no item 9"),
])
def test_bad_input_is_one_line_exit_2_and_no_files(tmp_path, sets, field):
    out = tmp_path / "out"
    args = ["build", str(TEMPLATE), "-o", str(out)]
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ")
    assert field in lines[0]
    assert not out.exists() or not any(out.iterdir())


def test_missing_key_and_bad_toml(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(TEMPLATE.read_text().replace("base_radius = 40.0", ""))
    result = CliRunner().invoke(main, ["build", str(bad), "-o", str(tmp_path / "o")])
    assert result.exit_code == 2 and "cam.base_radius: missing" in result.stderr
    bad.write_text("name = [")
    result = CliRunner().invoke(main, ["build", str(bad), "-o", str(tmp_path / "o")])
    assert result.exit_code == 2 and "is not valid TOML" in result.stderr
    result = CliRunner().invoke(main, ["build", str(tmp_path / "none.toml")])
    assert result.exit_code == 2


def test_a_failing_writer_leaves_no_file(tmp_path, monkeypatch):
    import camgen.core.writers.stl as stl
    from camgen.core.errors import ExportError

    def broken(mesh):
        raise ExportError("disk full")

    monkeypatch.setattr(stl, "stl_bytes", broken)
    result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(tmp_path)])
    assert result.exit_code == 2 and "disk full" in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_laws_json_table():
    result = CliRunner().invoke(main, ["laws", "--json"])
    rows = {row["law"]: row for row in json.loads(result.output)}
    assert list(rows) == ["uniform", "modified-uniform", "parabolic", "harmonic", "cycloidal",
                          "polynomial-345", "polynomial-4567", "modified-trapezoid", "modified-sine",
                          "double-harmonic"]
    assert rows["cycloidal"]["cj"] == pytest.approx(4 * np.pi**2)
    text = CliRunner().invoke(main, ["laws"]).output
    assert "cycloidal" in text and "6.2832" in text


def test_installed_command_runs_as_a_process(tmp_path):
    """The console script as users run it: exit codes and the default output folder."""
    ok = subprocess.run([sys.executable, "-m", "camgen", "build", str(TEMPLATE), "--set", "output.formats=['json']"],
                        cwd=tmp_path, capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    assert (tmp_path / "out" / "rdrd" / "rdrd.json").exists()
    bad = subprocess.run([sys.executable, "-m", "camgen", "build", str(TEMPLATE), "--set", "cam.bore=-1"],
                         cwd=tmp_path, capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.startswith("error: cam.bore: must be >= 0 and <= 10000 mm")
    assert "Traceback" not in bad.stderr


def test_kerf_and_clearance_move_the_edges_by_the_stated_amount(tmp_path):
    """Kerf 0.2: the cut outline lies 0.1 mm outside the cam surface and the cut bore is 0.1 mm smaller in radius;
    clearance 0.3: the printed bore is 0.15 mm larger in radius. Measured on the files as re-read."""
    import ezdxf
    import trimesh

    out = tmp_path / "o"
    result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(out), "--set", "output.kerf=0.2",
                                       "--set", "output.clearance=0.3", "--set", "output.formats=['dxf','stl','json']"])
    assert result.exit_code == 0, result.output
    msp = ezdxf.readfile(out / "rdrd.dxf").modelspace()
    pl = msp.query("LWPOLYLINE")[0]
    pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
    contour = Contour(pts[:, :2], pts[:, 2])
    on = contour.flatten(1e-4)
    deviation = surface_deviation(build_cam(template()), on)          # negative: outside the nominal surface
    assert deviation.min() >= -0.1 - 1e-9 and deviation.max() <= -0.1 + 0.01 + 1e-9
    assert msp.query("CIRCLE")[0].dxf.radius == pytest.approx(5.0 - 0.1, abs=1e-12)
    mesh = trimesh.load(out / "rdrd.stl")
    radial = np.linalg.norm(mesh.vertices[:, :2], axis=1)
    assert radial.min() == pytest.approx(5.0 + 0.15, abs=1e-5)         # on the bore circle, to float32 (STL)
    report = json.loads((out / "rdrd.json").read_text())
    assert (report["kerf_mm"], report["clearance_mm"], report["bore_cut_mm"], report["bore_printed_mm"]) == \
        (0.2, 0.3, pytest.approx(9.8), pytest.approx(10.3))
    assert report["outline_max_error_mm"] <= 0.01


def test_a_flat_face_console_states_its_pressure_angle_and_no_pitch_radius(tmp_path):
    """A translating flat face is pushed square to its face: the console says its pressure angle is 0 by
    definition instead of printing a 'max 0.00 deg' peak, and gives the cam's radius only (a flat face's pitch curve
    is its profile); the radius printed is the report's."""
    flat = TEMPLATE.parent / "flat-face.toml"
    result = CliRunner().invoke(main, ["build", str(flat), "-o", str(tmp_path), "--set", "output.formats=['json']"])
    assert result.exit_code == 0, result.output
    first = result.output.splitlines()[0]
    report = json.loads((tmp_path / "flat-face.json").read_text())
    assert "pressure angle 0 by definition" in first and "pressure angle max" not in first
    assert "(pitch)" not in first
    assert f"min convex radius {report['profile_rho_min_mm']:.3f} mm (cam)" in first


def test_a_union_field_is_named_without_pydantics_member_tag(tmp_path):
    """``follower.load_table`` takes a file name or rows: a number there is refused naming the field itself, not
    pydantic's ``follower.load_table.str``."""
    result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(tmp_path / "out"), "--set",
                                       "follower.load_table=0"])
    assert result.exit_code == 2
    assert result.output.startswith("error: follower.load_table: ") and ".str" not in result.output
    assert not (tmp_path / "out").exists()


def test_set_takes_list_items_as_errors_name_them(tmp_path):
    """``--set motion[0].lift=25`` (the way errors name a list item) is ``motion.0.lift=25``: the same report."""
    reports = []
    for style in ("motion[0].lift", "motion.0.lift"):
        other = style.replace("0", "2")
        result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(tmp_path / style), "--set",
                                           f"{style}=25", "--set", f"{other}=25", "--set", "output.formats=['json']"])
        assert result.exit_code == 0, result.output
        reports.append(json.loads((tmp_path / style / "rdrd.json").read_text()))
    assert reports[0] == reports[1] and reports[0]["segments"][0]["lift_mm"] == 25 == reports[0]["lift_max_mm"]


def test_a_top_level_key_that_looks_like_a_list_item_is_refused_by_name(tmp_path):
    """A template key written ``"motion[0]"`` is an unknown key named as written, in one line (it was taken for
    pydantic's tag of a union member and dropped, leaving no key to name: a traceback)."""
    template = tmp_path / "odd.toml"
    template.write_text('"motion[0]" = 1\n' + TEMPLATE.read_text())
    result = CliRunner().invoke(main, ["build", str(template), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert result.output.startswith("error: motion[0]: unknown key") and len(result.output.splitlines()) == 1
    assert not (tmp_path / "out").exists()
