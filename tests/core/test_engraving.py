"""Engraved text as outlines for laser software that drops TEXT (issue 19): output.text = "outline"."""
from __future__ import annotations

import json

import ezdxf
import numpy as np
import shapely
from click.testing import CliRunner

from camgen.cli import main as camgen
from tests.conftest import ROOT

RDRD = ROOT / "templates" / "rdrd.toml"


def build(tmp_path, *sets: str):
    args = ["build", str(RDRD), "-o", str(tmp_path), "--set", "hub.engrave=true",
            "--set", 'output.formats=["dxf","cut-svg","json"]']
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke(camgen, args)
    assert result.exit_code == 0, result.output
    return ezdxf.readfile(tmp_path / "rdrd.dxf").modelspace(), (tmp_path / "rdrd-cut.svg").read_text()


def test_text_by_default_and_outlines_when_asked(tmp_path):
    msp, svg = build(tmp_path / "text")
    texts = msp.query("TEXT")
    assert [t.dxf.text for t in texts] == ["rdrd"] and svg.count("<text") == 1
    x, y = texts[0].dxf.insert.x, texts[0].dxf.insert.y
    height = texts[0].dxf.height
    msp, svg = build(tmp_path / "outline", 'output.text="outline"')
    assert not msp.query("TEXT") and "<text" not in svg
    engraved = [np.array(p.get_points("xy")) for p in msp.query('LWPOLYLINE[layer=="ENGRAVE"]')]
    # the arrow's shaft and head and the theta = 0 tick are open lines; the glyphs are closed rings: r, d (two), r, d
    rings = [p for p in engraved if len(p) > 3 and np.allclose(p[0], p[-1])]
    assert len(rings) == 6
    box = shapely.box(x - 1e-9, y - 1e-9, x + 0.6 * height * 4 + 1e-9, y + height + 1e-9)
    glyphs = shapely.union_all([shapely.Polygon(r) for r in rings])
    assert box.contains(glyphs)
    lo_x, lo_y, hi_x, hi_y = glyphs.bounds
    # scaled to fill the box one way: the text's width or its height
    assert np.isclose(hi_x - lo_x, 0.6 * height * 4) or np.isclose(hi_y - lo_y, height)
    # the counters of the d's are holes: the inked area is well under the rings' hull
    assert 0.2 * box.area < glyphs.area < 0.8 * box.area
    report = json.loads((tmp_path / "outline" / "rdrd.json").read_text())
    assert report["name"] == "rdrd"


def test_a_bad_text_mode_is_refused(tmp_path):
    result = CliRunner().invoke(camgen, ["build", str(RDRD), "-o", str(tmp_path / "o"), "--set",
                                         'output.text="paths"'])
    assert result.exit_code == 2 and result.stderr.startswith("error: output.text:")
    assert not (tmp_path / "o").exists()
