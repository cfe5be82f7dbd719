"""The formats' registry (camgen.core.writers.REGISTRY) and the bundles built from it: a new format is its writer
module and one Format line; a bundle keeps the formats asked for, knows what it offers and refuses the rest, naming
output.formats; synthesis writes through a bundle, all or nothing."""
from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from typing import get_args

import pytest

from camgen.core.bundle import (
    Bundle, figure_files, mesh_files, part_files, report_file, rows_file, sheet_files, write_bundle)
from camgen.core.errors import ExportError, SpecError
from camgen.core.spec import OutputTable
from camgen.core.writers import (
    DEFAULT_FORMATS, EXTRAS, FIGURE_FORMATS, FORMATS, OPTIONAL_FORMATS, REGISTRY, Format)
from tests.conftest import ROOT, template

#: a toy writer, as a plugin would ship it: the drawing's outline as WKT, flattened at the drawing's tolerance
TOY_WRITER = '''
from camgen.core.parts import LAYER_OUTLINE


def write_wkt(drawing, path, options=None):
    ring = next(shape for layer, shape in drawing.items if layer == LAYER_OUTLINE).flatten(drawing.tolerance)
    points = [*ring, ring[0]]                      # a WKT ring repeats its first point
    path.write_text("POLYGON ((" + ", ".join(f"{float(x)!r} {float(y)!r}" for x, y in points) + "))\\n",
                    encoding="utf-8")


WRITERS = {"wkt": write_wkt}
'''
#: the one registry line the toy format needs
TOY = Format("wkt", "toyformats.wkt", {"part": (".wkt", "wkt"), "sheet": (".wkt", "wkt")})


@pytest.fixture
def toy(tmp_path, monkeypatch):
    """The toy format registered for the test only (its writer module on sys.path)."""
    _plugin(tmp_path)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setitem(REGISTRY, "wkt", TOY)
    return TOY


def _plugin(folder):
    """The toy format's package ``toyformats`` (its writer module ``toyformats.wkt``) written into ``folder``."""
    (folder / "toyformats").mkdir()
    (folder / "toyformats" / "__init__.py").write_text("", encoding="utf-8")
    (folder / "toyformats" / "wkt.py").write_text(TOY_WRITER, encoding="utf-8")


def _design():
    from camgen.api import design_cam

    return design_cam(template())


def test_the_tuples_and_the_output_formats_type_come_from_the_registry():
    chosen = tuple(f.name for f in REGISTRY.values() if f.extra is None and f.follows is None)
    assert FORMATS == chosen == ("dxf", "cut-svg", "stl", "3mf", "json", "png", "svg", "html", "gif")
    assert FIGURE_FORMATS == ("png", "svg") and DEFAULT_FORMATS == ("dxf", "cut-svg", "stl", "3mf", "json", "html")
    assert OPTIONAL_FORMATS == tuple(EXTRAS) == ("step",)
    assert get_args(get_args(OutputTable.model_fields["formats"].annotation)[0]) == FORMATS + OPTIONAL_FORMATS
    assert {f.name for f in REGISTRY.values() if f.follows == "json"} == {"csv", "toml"}


@pytest.mark.parametrize("name", [f for f in REGISTRY if f != "step"])
def test_every_line_names_a_module_holding_its_writer(name):
    assert callable(REGISTRY[name].writer())


def test_constructors_name_files_and_keys_from_the_registry():
    drawing = object()
    assert [(e.format, e.key, e.name) for e in part_files(drawing, "cam-1", "cam1").entries] == [
        ("dxf", "cam1_dxf", "cam-1.dxf"), ("cut-svg", "cam1_cut_svg", "cam-1-cut.svg")]
    assert [(e.key, e.name) for e in sheet_files(drawing, "x-sheet", "sheet").entries] == [
        ("sheet_dxf", "x-sheet.dxf"), ("sheet_svg", "x-sheet.svg")]
    assert [(e.key, e.name) for e in mesh_files(drawing, "x").entries] == [("stl", "x.stl"), ("3mf", "x.3mf")]
    assert [(e.key, e.name) for e in figure_files(drawing, "x-a", "a", only=("png",)).entries] == [
        ("a_png", "x-a.png")]
    assert mesh_files(None, "x") is None and rows_file((), "x", "kit") is None


def test_a_bundle_keeps_what_is_asked_offers_the_rest_and_refuses_what_it_has_not(tmp_path):
    items = [part_files("drawing", "p"), report_file({"a": 1.5}, "p"), rows_file([{"n": 1}], "p-kit", "kit")]
    bundle = Bundle.of(items, formats=("json",))
    assert bundle.files == {"json": "p.json", "kit_csv": "p-kit.csv"}      # the CSV goes with the report
    assert bundle.offers == {"dxf", "cut-svg", "json", "csv"}
    bundle.require(("json", "dxf"))
    with pytest.raises(SpecError) as refused:
        bundle.require(("json", "stl"))
    assert str(refused.value) == ("output.formats: 'stl': this design has no stl file to write; give formats of "
                                  "dxf, cut-svg, json")
    assert write_bundle(bundle, tmp_path) == {"json": "p.json", "kit_csv": "p-kit.csv"}
    assert json.loads((tmp_path / "p.json").read_text()) == {"a": 1.5, "files": bundle.files}
    assert (tmp_path / "p-kit.csv").read_text() == "n\n1\n"
    with pytest.raises(SpecError):
        write_bundle(bundle, tmp_path / "none", formats=("stl",))
    assert not (tmp_path / "none").exists()


def test_a_new_format_is_a_writer_module_and_one_line(toy, tmp_path):
    from shapely import wkt

    from camgen.core.parts import Drawing
    from camgen.kinds import spec_kind

    design = _design()
    bundle, _ = spec_kind(design.spec).bundle(design)
    assert "wkt" in bundle.offers and "wkt" not in bundle.files   # offered by every cam bundle, written when asked
    drawing = Drawing.of_part(design.cut)
    written = write_bundle(Bundle.of([part_files(drawing, "rdrd")], formats=("dxf", "wkt")), tmp_path)
    assert written == {"dxf": "rdrd.dxf", "wkt": "rdrd.wkt"}
    ring = wkt.loads((tmp_path / "rdrd.wkt").read_text())
    exact = design.cut.outline
    # chords inside an outline bulging outwards: the area lost is at most the perimeter times the chord tolerance
    assert 0 <= exact.area - ring.area <= ring.length * drawing.tolerance
    assert ring.area == pytest.approx(exact.area, rel=1e-4)


def test_a_registered_format_is_chosen_in_output_formats_and_written_by_the_command(tmp_path):
    """A plugin registering its format before the specs load: ``camgen build`` writes it, nothing else edited."""
    _plugin(tmp_path)
    script = textwrap.dedent(f"""
        import sys
        sys.path.insert(0, {str(tmp_path)!r})
        from camgen.core.writers import Format, register
        register(Format("wkt", "toyformats.wkt", {{"part": (".wkt", "wkt")}}))
        from camgen.cli import main
        main(["build", {str(ROOT / "templates" / "rdrd.toml")!r}, "-o", {str(tmp_path / "out")!r},
              "--set", "output.formats=['wkt', 'json']"])
    """)
    run = subprocess.run([sys.executable, "-c", script], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["rdrd.json", "rdrd.wkt"]
    report = json.loads((tmp_path / "out" / "rdrd.json").read_text())
    assert report["files"] == {"wkt": "rdrd.wkt", "json": "rdrd.json"}
    assert (tmp_path / "out" / "rdrd.wkt").read_text().startswith("POLYGON ((")


def test_a_linkage_without_parts_refuses_a_parts_format_by_name(tmp_path):
    import linkgen

    design = linkgen.design(linkgen.load(ROOT / "templates" / "crank-rocker.toml"))
    with pytest.raises(SpecError) as refused:
        linkgen.write(design, tmp_path / "out", formats=["json", "dxf"])
    assert refused.value.field == "output.formats" and "'dxf'" in str(refused.value)
    assert not (tmp_path / "out").exists()


def test_a_kit_part_s_cut_svg_has_the_regular_key():
    from camgen.core.kit import kit_items
    from camgen.core.parts import Drawing

    design = _design()
    part = design.cut.name
    items = kit_items("k", ((design.cut, "laser"),), Drawing.of_part(design.cut), None, ("dxf", "cut-svg"), "t")
    assert Bundle.of(items, formats=("dxf", "cut-svg")).files == {
        f"{part}_dxf": f"k-{part}.dxf", f"{part}_cut_svg": f"k-{part}-cut.svg",
        "kit_assembly_dxf": "k-kit-assembly.dxf", "kit_assembly_svg": "k-kit-assembly.svg"}
    assert Bundle.of(items).offers == {"dxf", "cut-svg", "png", "step"}     # no meshes made, no bill of materials


def test_synthesis_writes_through_a_bundle_all_or_nothing(tmp_path, monkeypatch):
    from linkgen.synthesis import synthesize, validate_task, write_synthesis
    from linkgen.synthesis.outputs import synthesis_bundle

    result = synthesize(validate_task({"name": "t", "task": {"kind": "crank-rocker", "swing": 30.0, "rocker": 40.0,
                                                              "candidates": 1}}))
    bundle = synthesis_bundle(result, figures=True)
    assert list(bundle.files.values()) == ["t-1.toml", "t-1.json", "t-1-curve.png", "t-1-curve.svg", "summary.json",
                                           "summary.csv"]
    assert bundle.offers == {"toml", "json", "png", "svg", "csv"}
    assert list(synthesis_bundle(result).files.values()) == ["t-1.toml", "t-1.json", "summary.json", "summary.csv"]

    def failing(rows, path, options=None):
        raise ExportError("the csv writer failed")

    monkeypatch.setattr("camgen.core.writers.report.WRITERS", {"json": REGISTRY["json"].writer(), "csv": failing})
    with pytest.raises(ExportError, match="the csv writer failed"):
        write_synthesis(result, tmp_path / "out")
    assert not (tmp_path / "out").exists()
