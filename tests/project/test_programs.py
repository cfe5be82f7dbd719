"""Our files, checked by the programs users really use; every check also rejects a deliberately broken file.

.ci/run installs the programs (Debian packages, pymeshlab from PyPI). Where one is
missing, its tests are skipped with the reason printed (pytest -rs), never silently.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from camgen.api import write_cam
from camgen.api import design_cam
from tests.conftest import template
from tests.support.freecad import freecad_check
from tests.support.meshlab import meshlab

HUB = {"cam.bore": 20.0, "hub.keyway": True, "hub.bolt_circle": 50.0, "hub.bolt_holes": 4,
       "hub.bolt_hole_diameter": 4.0, "hub.boss_diameter": 34.0, "hub.boss_height": 10.0, "hub.set_screw": 4.0}


def need(program: str) -> str:
    path = shutil.which(program)
    if path is None:
        pytest.skip(f"{program} is not installed (Debian package; .ci/run installs it)")
    return path


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """The reference cam with hub features, every flavour of DXF, its STL; and deliberately broken files."""
    out = tmp_path_factory.mktemp("files")
    design = design_cam(template({**HUB, "output.formats": ["dxf", "stl"]}))
    write_cam(design, out)
    for flavour in ("lines-arcs", "segments"):
        d = design_cam(template({**HUB, "output.formats": ["dxf"], "output.dxf": flavour}))
        write_cam(d, out / flavour)
    write_cam(design_cam(template({**HUB, "output.formats": ["dxf"], "output.dxf_version": "R12"})), out / "R12")
    import ezdxf
    import trimesh

    for name, points, closed in (("open", [(0, 0), (30, 0), (30, 30), (0, 30)], False),
                                 ("eight", [(0, 0), (30, 30), (30, 0), (0, 30)], True)):
        doc = ezdxf.new("R2010")
        doc.units = ezdxf.units.MM
        doc.modelspace().add_lwpolyline(points, close=closed, dxfattribs={"layer": "OUTLINE"})
        doc.saveas(out / f"broken-{name}.dxf")
    mesh = trimesh.load(out / "rdrd.stl")
    holed = trimesh.Trimesh(mesh.vertices, mesh.faces[5:], process=False)       # five faces gone: a hole
    holed.export(out / "broken-hole.stl")
    return out, design


def _expect(design, chords: bool = False) -> dict:
    """Areas with their allowed differences: 1e-6 relative for exact geometry; for chords within the
    tolerance, up to perimeter x tolerance (the most a chord's sag can take off)."""
    part = design.cut
    tol = design.spec.output.tolerance
    ring = part.outline.flatten(1e-3)

    def allowed(shape) -> float:
        pts = shape.flatten(1e-3)
        perimeter = float(np.linalg.norm(np.diff(np.vstack([pts, pts[:1]]), axis=0), axis=1).sum())
        return perimeter * tol if chords else 1e-6 * abs(shape.area)

    shapes = [part.outline, *part.holes]
    return {"areas": [[abs(s.area), allowed(s)] for s in shapes],
            "box": [ring[:, 0].min(), ring[:, 1].min(), ring[:, 0].max(), ring[:, 1].max()], "box_tol": 0.01}


@pytest.mark.parametrize("flavour", ["polyline-bulge", "lines-arcs", "segments", "R12"])
def test_freecad_imports_every_dxf_as_closed_valid_faces(files, flavour):
    out, design = files
    path = out / "rdrd.dxf" if flavour == "polyline-bulge" else out / flavour / "rdrd.dxf"
    done = freecad_check("dxf", path, _expect(design, chords=flavour == "segments"))
    assert done.returncode == 0, done.stdout.strip().splitlines()[-1][:2000]


@pytest.mark.parametrize("name", ["open", "eight"])
def test_freecad_check_rejects_a_broken_dxf(files, name):
    out, _ = files
    done = freecad_check("dxf", out / f"broken-{name}.dxf",
                         {"areas": [[900.0, 1e-3]], "box": [0, 0, 30, 30], "box_tol": 0.01})
    assert done.returncode == 1
    assert json.loads(done.stdout.strip().splitlines()[-1])["problems"]


def test_pymeshlab_finds_a_closed_two_manifold_of_our_volume(files):
    out, _ = files
    m = meshlab(out / "rdrd.stl")
    assert m["manifold"] and m["boundary_edges"] == 0 and m["self_intersecting"] == 0
    import trimesh

    assert m["volume"] == pytest.approx(trimesh.load(out / "rdrd.stl").volume, rel=1e-6)
    assert m["volume"] > 0                                     # outward orientation


def test_pymeshlab_rejects_a_mesh_with_a_hole(files):
    out, _ = files
    assert meshlab(out / "broken-hole.stl")["boundary_edges"] > 0


def _admesh(path: Path) -> dict:
    text = subprocess.run([need("admesh"), "-e", str(path)], capture_output=True, text=True, timeout=120).stdout
    stats = {}
    for key in ("Total disconnected facets", "Degenerate facets", "Facets reversed", "Backwards edges",
                "Normals fixed"):
        stats[key] = int(re.search(rf"{key}\s*:\s*(\d+)", text).group(1))
    stats["volume"] = float(re.search(r"Volume\s*:\s*([-\d.]+)", text).group(1))
    return stats


def test_admesh_exact_check(files):
    out, _ = files
    stats = _admesh(out / "rdrd.stl")
    assert all(stats[k] == 0 for k in stats if k != "volume"), stats
    import trimesh

    assert stats["volume"] == pytest.approx(trimesh.load(out / "rdrd.stl").volume, rel=1e-5)


def test_admesh_rejects_a_mesh_with_a_hole(files):
    out, _ = files
    assert _admesh(out / "broken-hole.stl")["Total disconnected facets"] > 0


def _prusa(path: Path) -> str:
    return subprocess.run([need("prusa-slicer"), "--info", str(path)], capture_output=True, text=True,
                          timeout=300).stdout


def test_prusaslicer_info_says_manifold(files):
    out, _ = files
    info = _prusa(out / "rdrd.stl")
    assert "manifold = yes" in info
    assert "open_edges" not in info or re.search(r"open_edges = 0\b", info)


def test_prusaslicer_rejects_a_mesh_with_a_hole(files):
    out, _ = files
    assert "manifold = no" in _prusa(out / "broken-hole.stl")


def _openscad(tmp: Path, source: str) -> tuple[subprocess.CompletedProcess, Path]:
    scad, stl = tmp / "check.scad", tmp / "result.stl"
    scad.write_text(source)
    done = subprocess.run([need("openscad"), "--hardwarnings", "-o", str(stl), str(scad)], capture_output=True,
                          text=True, timeout=300)
    return done, stl


def test_openscad_uses_our_stl_in_a_boolean(files, tmp_path):
    import trimesh

    out, _ = files
    done, stl = _openscad(tmp_path, f'intersection() {{ import("{out / "rdrd.stl"}"); '
                                    "cube([1000, 1000, 1000], center = true); }\n")
    assert done.returncode == 0, done.stderr[-2000:]
    assert trimesh.load(stl).volume == pytest.approx(trimesh.load(out / "rdrd.stl").volume, rel=1e-4)


def _openscad_plate(tmp_path: Path, dxf: Path) -> float:
    import trimesh

    done, stl = _openscad(tmp_path, f'difference() {{ linear_extrude(height = 8) import("{dxf}", layer = "OUTLINE"); '
                                    f'translate([0, 0, -1]) linear_extrude(height = 10) import("{dxf}", '
                                    'layer = "HOLES"); }\n')
    assert done.returncode == 0, done.stderr[-2000:]
    return float(trimesh.load(stl).volume)


def test_openscad_extrudes_our_lines_arcs_dxf_to_our_volume(files, tmp_path):
    """OpenSCAD reads the lines-arcs flavour as drawn: the extruded plate has our volume."""
    out, design = files
    volume = _openscad_plate(tmp_path, out / "lines-arcs" / "rdrd.dxf")
    assert volume == pytest.approx(design.cut.area * 8.0, rel=2e-3)


def test_openscad_volume_check_fails_on_the_bulge_flavour(files, tmp_path):
    """OpenSCAD drops LWPOLYLINE bulges without a word: the same check on that flavour comes out wrong."""
    out, design = files
    assert _openscad_plate(tmp_path, out / "rdrd.dxf") != pytest.approx(design.cut.area * 8.0, rel=2e-3)


def test_openscad_rejects_a_mesh_with_a_hole(files, tmp_path):
    out, _ = files
    done, _ = _openscad(tmp_path, f'intersection() {{ import("{out / "broken-hole.stl"}"); '
                                  "cube([1000, 1000, 1000], center = true); }\n")
    assert done.returncode != 0


def _librecad_extent(dxf: Path, tmp: Path) -> tuple[float, float]:
    """Print with LibreCAD at scale 1 on a 300 mm page, rasterise at 50 dpi, measure the ink's extent in mm."""
    need("librecad")
    pdftoppm = need("pdftoppm")
    pdf = tmp / f"{dxf.stem}.pdf"
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}
    # wrapped in timeout: LibreCAD hangs on a file it cannot read; -t sets the folder of <name>.pdf
    subprocess.run(["timeout", "120", "librecad", "dxf2pdf", "-s", "1", "-c", "-p", "300x300", "-t", str(tmp),
                    str(dxf)], env=env, capture_output=True, text=True, timeout=150)
    assert pdf.exists(), "LibreCAD wrote no PDF"
    subprocess.run([pdftoppm, "-r", "50", "-gray", "-png", str(pdf), str(tmp / "page")], check=True, timeout=120)
    from PIL import Image

    page = np.asarray(Image.open(sorted(tmp.glob("page*.png"))[0]).convert("L"))
    ink = np.argwhere(page < 128)
    (y0, x0), (y1, x1) = ink.min(axis=0), ink.max(axis=0)
    return (x1 - x0) / 50 * 25.4, (y1 - y0) / 50 * 25.4


def _true_size(dxf: Path, ring: np.ndarray, tmp: Path) -> bool:
    width, height = _librecad_extent(dxf, tmp)
    # a pixel at 50 dpi is 0.5 mm
    return abs(width - np.ptp(ring[:, 0])) <= 1.5 and abs(height - np.ptp(ring[:, 1])) <= 1.5


def test_librecad_prints_the_drawing_at_its_true_size(files, tmp_path):
    out, design = files
    assert _true_size(out / "rdrd.dxf", design.cut.outline.flatten(1e-3), tmp_path)


def test_librecad_size_check_rejects_a_drawing_in_the_wrong_unit(files, tmp_path):
    """Our outline written in centimetres by mistake: LibreCAD prints it a tenth of the size, and the check says so."""
    import ezdxf

    _, design = files
    ring = design.cut.outline.flatten(1e-3)
    doc = ezdxf.new("R2010")
    doc.units = ezdxf.units.MM
    doc.modelspace().add_lwpolyline((ring / 10).tolist(), close=True)
    doc.saveas(tmp_path / "cm.dxf")
    assert not _true_size(tmp_path / "cm.dxf", ring, tmp_path)
