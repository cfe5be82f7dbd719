"""The scripting API: importable from camgen and linkgen, cheap to import, objects that render in Jupyter."""
from __future__ import annotations

import subprocess
import sys
import xml.etree.ElementTree as ET

import camgen
import linkgen
from tests.conftest import ROOT, template


def test_public_names_resolve():
    for name in camgen.__all__:
        assert getattr(camgen, name) is not None
    for name in linkgen.__all__:
        assert getattr(linkgen, name) is not None


def test_import_stays_light():
    code = "import sys, camgen, linkgen; print(sorted(m for m in ('ezdxf', 'trimesh', 'matplotlib', 'scipy') " \
           "if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_objects_render_themselves_as_svg():
    design = camgen.design_cam(template())
    linkages = [linkgen.design_linkage(linkgen.validate_spec({"name": "fb", "linkage": {"type": "four-bar", **table}}))
                for table in ({"ground": 180, "crank": 80, "coupler": 200, "rocker": 150, "point_distance": 100,
                               "point_angle": 28.6479}, {"ground": 100, "crank": 70, "coupler": 60, "rocker": 80})]
    for obj in (design, design.part, camgen.Drawing.of_part(design.part), *linkages):
        root = ET.fromstring(obj._repr_svg_())
        assert root.tag.endswith("svg") and root.get("width").endswith("mm")
        assert root.findall(".//{http://www.w3.org/2000/svg}path")


def test_a_family_in_ten_lines(tmp_path):
    """docs/tutorials/scripting.md: a family made in a few lines of Python."""
    rows = []
    for lift in (10, 20, 30):
        spec = camgen.load_spec(ROOT / "templates" / "rdrd.toml", [f"motion.0.lift={lift}", f"motion.2.lift={lift}",
                                                            f"name='cam-{lift}'", "output.formats=['dxf']"])
        design = camgen.design_cam(spec)
        camgen.write_cam(design, tmp_path / spec.name)
        rows.append((lift, design.analysis.pressure_angle_max_deg))
    assert [r[0] for r in rows] == [10, 20, 30] and rows[0][1] < rows[2][1]
    assert all((tmp_path / f"cam-{lift}" / f"cam-{lift}.dxf").exists() for lift in (10, 20, 30))
