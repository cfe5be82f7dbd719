"""File formats: DXF flavours and versions, the SVG cut file and 3MF, re-read and checked against the exact cam."""
from __future__ import annotations

import re
import shutil
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from camgen.api import write_cam
from camgen.flat import build_cam
from camgen.api import design_cam
from camgen.surface import surface_deviation
from tests.conftest import template, ROOT

TOL = 0.01


@pytest.fixture(scope="module")
def cam():
    return build_cam(template())


def build(tmp_path, **output):
    changes = {f"output.{k}": v for k, v in output.items()}
    design = design_cam(template(changes))
    write_cam(design, tmp_path)
    return design


def points_of(msp) -> tuple[np.ndarray, list]:
    """Points on every LWPOLYLINE, POLYLINE, LINE and ARC of the OUTLINE layer (exact on the written geometry)."""
    pts = []
    for e in msp.query('*[layer=="OUTLINE"]'):
        if e.dxftype() == "LINE":
            a, b = np.array(e.dxf.start)[:2], np.array(e.dxf.end)[:2]
            pts += [a, 0.5 * (a + b)]
        else:
            from ezdxf import path

            pts += [np.array(p)[:2] for p in path.make_path(e).flattening(0.001)]
    return np.array(pts), [e.dxftype() for e in msp.query('*[layer=="OUTLINE"]')]


@pytest.mark.parametrize("flavour, version, kinds", [
    ("polyline-bulge", "R2010", {"LWPOLYLINE"}),
    ("polyline-bulge", "R12", {"POLYLINE"}),
    ("lines-arcs", "R2010", {"LINE", "ARC"}),
    ("segments", "R2010", {"LINE"}),
    ("segments", "R12", {"LINE"}),
])
def test_dxf_flavours_read_back_within_tolerance(tmp_path, cam, flavour, version, kinds):
    import ezdxf

    build(tmp_path, dxf=flavour, dxf_version=version, formats=["dxf"])
    doc = ezdxf.readfile(tmp_path / "rdrd.dxf")
    assert doc.dxfversion == {"R2010": "AC1024", "R12": "AC1009"}[version]
    assert not doc.audit().has_errors
    pts, types = points_of(doc.modelspace())
    assert set(types) == kinds
    assert np.abs(surface_deviation(cam, pts)).max() <= TOL
    holes = doc.modelspace().query('*[layer=="HOLES"]')
    if flavour == "segments":
        assert {e.dxftype() for e in holes} == {"LINE"}
        ends = np.array([e.dxf.start for e in holes])[:, :2]
        assert np.linalg.norm(ends, axis=1) == pytest.approx(5.0, abs=1e-12)
    else:
        assert [e.dxftype() for e in holes] == ["CIRCLE"]


def test_lines_arcs_dxf_keeps_the_dwells_as_arcs_about_the_centre(tmp_path, cam):
    import ezdxf

    build(tmp_path, dxf="lines-arcs", formats=["dxf"])
    arcs = ezdxf.readfile(tmp_path / "rdrd.dxf").modelspace().query('ARC[layer=="OUTLINE"]')
    assert len(arcs) == 2
    for arc in arcs:
        assert np.linalg.norm(np.array(arc.dxf.center)[:2]) < 1e-9
        assert (arc.dxf.end_angle - arc.dxf.start_angle) % 360 == pytest.approx(60.0, abs=1e-9)
    assert sorted(a.dxf.radius for a in arcs) == pytest.approx(
        [np.hypot(5, cam.follower.d0) - 10, np.hypot(5, cam.follower.d0 + 20) - 10], abs=1e-9)


def _svg_points(path_d: str, top: float, left: float) -> tuple[np.ndarray, list[float]]:
    """The points and arc radii of an SVG path of M, L, A and Z commands, back in the drawing's millimetres."""
    pts, radii = [], []
    for cmd, args in re.findall(r"([MLAZ])([^MLAZ]*)", path_d):
        nums = [float(x) for x in re.split(r"[ ,]+", args.strip()) if x]
        if cmd in "ML":
            pts.append(nums[-2:])
        elif cmd == "A":
            radii.append(nums[0])
            pts.append(nums[-2:])
    p = np.array(pts)
    return np.column_stack([p[:, 0] + left, top - p[:, 1]]), radii


def test_svg_cut_file_is_in_millimetres_with_exact_geometry(tmp_path, cam):
    design = build(tmp_path, formats=["cut-svg"])
    root = ET.parse(tmp_path / "rdrd-cut.svg").getroot()
    ns = {"s": "http://www.w3.org/2000/svg"}
    w, h = root.get("width"), root.get("height")
    assert w.endswith("mm") and h.endswith("mm")
    vb = [float(x) for x in root.get("viewBox").split()]
    assert vb[2] == pytest.approx(float(w[:-2])) and vb[3] == pytest.approx(float(h[:-2]))   # 1 unit = 1 mm
    groups = {g.get("id"): g for g in root.findall("s:g", ns)}
    assert set(groups) == {"OUTLINE", "HOLES"}
    assert groups["OUTLINE"].get("stroke") != groups["HOLES"].get("stroke")
    assert all(float(g.get("stroke-width")) <= 0.0254 and g.get("fill") == "none" for g in groups.values())
    ring = design.cut.outline.flatten(TOL)
    left, top = ring[:, 0].min() - 2.0, ring[:, 1].max() + 2.0
    pts, radii = _svg_points(groups["OUTLINE"].find("s:path", ns).get("d"), top, left)
    assert np.abs(surface_deviation(cam, pts)).max() < 1e-5            # 6 decimals written
    assert sorted(radii) == pytest.approx(sorted(design.outline.contour.arcs()[2]), abs=1e-5)
    circle = groups["HOLES"].find("s:circle", ns)
    assert float(circle.get("r")) == pytest.approx(5.0)
    assert (float(circle.get("cx")) + left, top - float(circle.get("cy"))) == pytest.approx((0.0, 0.0), abs=1e-5)


@pytest.mark.skipif(shutil.which("rsvg-convert") is None, reason="rsvg-convert (Debian librsvg2-bin) not installed")
def test_svg_renders_at_its_true_size(tmp_path):
    """A real renderer (librsvg) draws it at 96 dpi: pixels = mm / 25.4 * 96."""
    from PIL import Image

    build(tmp_path, formats=["cut-svg"])
    out = tmp_path / "cut.png"
    subprocess.run(["rsvg-convert", "-d", "96", "-p", "96", str(tmp_path / "rdrd-cut.svg"), "-o", str(out)],
                   check=True, timeout=60)
    root = ET.parse(tmp_path / "rdrd-cut.svg").getroot()
    expected = (float(root.get("width")[:-2]) / 25.4 * 96, float(root.get("height")[:-2]) / 25.4 * 96)
    assert Image.open(out).size == (pytest.approx(expected[0], abs=1), pytest.approx(expected[1], abs=1))


def test_3mf_is_a_watertight_solid_of_the_right_volume(tmp_path):
    import trimesh

    design = build(tmp_path, formats=["3mf"])
    mesh = trimesh.load(tmp_path / "rdrd.3mf", force="mesh")
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.volume == pytest.approx(design.printed.area * 8.0, rel=1e-3)


@pytest.mark.parametrize("program, template, extra, count", [
    ("camgen", "rdrd.toml", ["--figures"], 12), ("linkgen", "jansen.toml", [], 22)])
def test_every_file_is_reproducible_across_processes(tmp_path, program, template, extra, count):
    """The same template gives the same bytes in two processes with different string-hash seeds and time zones
    (no dates, GUIDs or set orders leak into DXF, SVG, STL, 3MF, PNG, HTML or JSON)."""
    import os
    import sys

    from tests.conftest import ROOT

    outs = []
    for seed, zone in (("1", "UTC"), ("2", "Asia/Kathmandu")):
        out = tmp_path / seed
        env = {**os.environ, "PYTHONHASHSEED": seed, "TZ": zone}
        subprocess.run([sys.executable, "-m", program, "build", str(ROOT / "templates" / template), "-o", str(out),
                        *extra], env=env, check=True, capture_output=True, timeout=300)
        outs.append(out)
    names = sorted(p.name for p in outs[0].iterdir())
    assert names == sorted(p.name for p in outs[1].iterdir()) and len(names) == count
    for name in names:
        assert (outs[0] / name).read_bytes() == (outs[1] / name).read_bytes(), name


def test_no_negative_zero_in_reports_or_on_the_console(tmp_path):
    """The toggle press's ram runs on x = 0: rounding leaves -0.0 and -1e-13; the JSON says 0.0 and the console
    0.000 (a sign on nothing reads as a direction)."""

    from click.testing import CliRunner

    from camgen.core.cli import fixed
    from camgen.core.writers.report import report_json
    from linkgen.cli import main as linkgen

    assert report_json({"a": [-0.0, (1.5, -0.0)], "b": {"c": -0.0, "d": -2.0}}) == report_json(
        {"a": [0.0, [1.5, 0.0]], "b": {"c": 0.0, "d": -2.0}})
    assert (fixed(-1e-13), fixed(-0.0004), fixed(-0.0006), fixed(2.5, 1)) == ("0.000", "0.000", "-0.001", "2.5")
    template = ROOT / "templates" / "toggle-press.toml"
    result = CliRunner().invoke(linkgen, ["analyze", str(template), "-o", str(tmp_path)])
    assert result.exit_code == 0 and "tracer R: x 0.000 to 0.000 mm (0.000 wide)" in result.output
    assert "-0.0," not in (tmp_path / "toggle-press.json").read_text() and "-0.0\n" not in (
        tmp_path / "toggle-press.json").read_text()
