"""Drawings that read: part names engraved on the cut sheet, assemblies drawn with strokes a viewer shows and each
pose in its own colour, cut files kept at hairlines, and the four-bar's figure naming the paths it draws."""
from __future__ import annotations

import re
from pathlib import Path

import ezdxf
import pytest
from click.testing import CliRunner

from camgen.core.parts import ACI_RGB, LAYER_LABELS, POSE_COLOURS, layer_colour
from linkgen.cli import main as linkgen
from tests.conftest import ROOT


@pytest.fixture(scope="module")
def jansen(tmp_path_factory):
    folder = tmp_path_factory.mktemp("jansen")
    result = CliRunner().invoke(linkgen, ["build", str(ROOT / "templates" / "jansen.toml"), "-o", str(folder)])
    assert result.exit_code == 0, result.output
    return folder


def test_every_part_is_labelled_inside_its_outline_on_the_sheet(jansen):
    import shapely

    doc = ezdxf.readfile(jansen / "jansen-sheet.dxf")
    msp = doc.modelspace()
    labels = {t.dxf.text: t for t in msp.query(f"TEXT[layer=='{LAYER_LABELS}']")}
    outlines = [shapely.Polygon([p[:2] for p in e.get_points("xy")]) for e in msp.query("LWPOLYLINE[layer=='OUTLINE']")]
    parts = [p.name.removeprefix("jansen-").removesuffix(".stl") for p in jansen.glob("jansen-*.stl")
             if not re.search(r"-(pin|spacer-\d+)\.stl$", p.name)]
    assert sorted(labels) == sorted(parts)
    for name, text in labels.items():
        anchor = shapely.Point(text.dxf.insert[0], text.dxf.insert[1])
        box = [o.envelope for o in outlines if o.envelope.contains(anchor)]
        assert box, name                                     # the label lies within its part's box
        assert 1.0 <= text.dxf.height <= 5.0
    assert doc.layers.get(LAYER_LABELS).color == 30


def test_assembly_strokes_show_and_cut_files_stay_hairlines(jansen):
    def widths(name: str) -> set[float]:
        return {float(w) for w in re.findall(r'stroke-width="([0-9.]+)"', (jansen / name).read_text())}

    assert widths("jansen-sheet.svg") == {0.01}
    assembly = widths("jansen-assembly.svg")
    assert len(assembly) == 1 and 0.2 <= assembly.pop() <= 2.0


def test_each_pose_has_its_own_colour(jansen):
    doc = ezdxf.readfile(jansen / "jansen-assembly.dxf")
    poses = sorted(layer.dxf.name for layer in doc.layers if layer.dxf.name.startswith("DC"))
    assert len(poses) >= 2
    colours = [doc.layers.get(p).color for p in poses]
    assert colours == [POSE_COLOURS[i % len(POSE_COLOURS)][0] for i in range(len(poses))]
    assert len(set(colours[:len(POSE_COLOURS)])) == min(len(poses), len(POSE_COLOURS))
    assert layer_colour("DC12-x") == POSE_COLOURS[11 % len(POSE_COLOURS)] and layer_colour("DCX") == (7, "#000000")


@pytest.mark.parametrize("distance, words", [(0.0, "dashed: rocker pin's arc"),
                                              (40.0, "dotted: coupler-point path; dashed: rocker pin")])
def test_the_four_bar_figure_names_the_paths_it_draws(distance, words):
    import math

    from linkgen.kinematics.fourbar import FourBar
    from linkgen.plots import dead_centre_figure

    fig = dead_centre_figure("fb", FourBar(100.0, 30.0, 90.0, 70.0, point_distance=distance,
                                           point_angle=math.radians(30)), "open")
    ax = fig.axes[0]
    assert ax.get_title().endswith(words)
    dotted = [line for line in ax.get_lines() if line.get_linestyle() == ":"]
    assert bool(dotted) == (distance > 0)                  # no crank circle drawn as a coupler path


def _svg_colours(path: Path) -> dict[str, str]:
    """Each layer group's stroke colour in an SVG written by the project."""
    import xml.etree.ElementTree as ET

    root = ET.parse(path).getroot()
    return {g.get("id"): g.get("stroke") for g in root.iter("{http://www.w3.org/2000/svg}g")}


def _dxf_colours(path: Path) -> dict[str, str]:
    """Each layer's colour in a DXF as the RGB a reader shows for its ACI number (ezdxf's standard palette; ACI 7,
    the foreground colour, as black on paper)."""
    from ezdxf.colors import aci2rgb

    out = {}
    for layer in ezdxf.readfile(path).layers:
        if layer.dxf.name in ("0", "Defpoints"):
            continue
        rgb = (0, 0, 0) if layer.color == 7 else tuple(aci2rgb(layer.color))
        out[layer.dxf.name] = "#{:02x}{:02x}{:02x}".format(*rgb)
    return out


def test_each_layer_is_one_colour_in_dxf_and_svg(jansen, tmp_path):
    """The labels, outlines, holes and each assembly pose: the SVG's stroke is the RGB of the DXF's colour number in
    the ACI palette (the labels orange, #ff7f00, ACI 30, in both), for the sheet, the assembly, and a cam's engraved
    and grooved layers."""
    from camgen.cli import main as camgen

    sheet_dxf, sheet_svg = _dxf_colours(jansen / "jansen-sheet.dxf"), _svg_colours(jansen / "jansen-sheet.svg")
    assert sheet_dxf[LAYER_LABELS] == sheet_svg[LAYER_LABELS] == "#ff7f00"
    assert {"OUTLINE", "HOLES", LAYER_LABELS} <= set(sheet_svg)
    assert {k: sheet_dxf[k] for k in sheet_svg} == sheet_svg
    assembly_dxf, assembly_svg = (_dxf_colours(jansen / "jansen-assembly.dxf"),
                                  _svg_colours(jansen / "jansen-assembly.svg"))
    assert len([k for k in assembly_svg if k.startswith("DC")]) >= 2
    assert {k: assembly_dxf[k] for k in assembly_svg} == assembly_svg
    result = CliRunner().invoke(camgen, ["build", str(ROOT / "templates" / "grooved.toml"), "-o", str(tmp_path),
                                         "--set", 'output.formats=["dxf","cut-svg"]'])
    assert result.exit_code == 0, result.output
    [dxf] = [p for p in tmp_path.glob("*.dxf") if "sheet" not in p.name]
    cam_dxf, cam_svg = _dxf_colours(dxf), _svg_colours(dxf.with_name(dxf.stem + "-cut.svg"))
    assert "GROOVE" in cam_svg and {k: cam_dxf[k] for k in cam_svg} == cam_svg
    from ezdxf.colors import aci2rgb

    assert all(n == 7 or "#{:02x}{:02x}{:02x}".format(*aci2rgb(n)) == rgb for n, rgb in ACI_RGB.items())
