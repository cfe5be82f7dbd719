"""Issue 30, item 9: no outline of a linkage's parts has a piece of (almost) no length.

The Watt I and II output links hold three nearly collinear holes (the tracer P lies 1e-10 mm off the line F-G); their
rounded hulls had a corner arc 1e-11 mm long that FreeCAD read as a full circle across the bar and Open CASCADE
could not make an edge of. Every bundled linkage template (family members too; those without a ``[parts]`` table
given one) is built here: every piece of every contour of its parts, cut sheets and assembly is at least
:data:`~camgen.core.shapes.MIN_PIECE_MM` long, and FreeCAD reads each cut sheet's DXF as closed wires, as many as the
sheet has contours and circles, of their exact areas (1e-6 relative).
"""
from __future__ import annotations

import json
import math
import os
import shutil
import subprocess

import numpy as np
import pytest

from camgen.core.family import members, split_family
from camgen.core.parts import Drawing
from camgen.core.shapes import MIN_PIECE_MM, Circle, Contour, Polyline, Text, merged_pieces, rounded_hull
from camgen.core.spec import read_template
from camgen.core.writers.dxf import write_dxf
from linkgen.linkage_design import design_linkage
from linkgen.spec import validate_spec
from tests.conftest import ROOT
from tests.support.freecad import PROGRAMS, freecad_check

#: the [parts] table a bundled linkage template without one is built with
PARTS = {"width": 12.0, "thickness": 4.0, "pin_diameter": 4.0}


def _linkages() -> list[tuple[str, dict]]:
    """(name, raw template) of every bundled linkage template and family member, each with a [parts] table."""
    import tomllib

    out = []
    for path in sorted((ROOT / "templates").glob("*.toml")):
        text = tomllib.loads(path.read_text())
        if "task" in text:
            continue
        raw, sweep, _ = split_family(read_template(path))
        if "linkage" not in raw:
            continue
        for name, member in ([(m.name, m.raw) for m in members(raw, sweep)] if sweep else [(raw["name"], raw)]):
            out.append((name, {**member, "parts": member.get("parts", PARTS)}))
    return out


LINKAGES = _linkages()


def test_every_bundled_linkage_is_here():
    """13 templates with parts, two without (hoekens, slider-crank), 5 crank-rockers and 4 straight-line linkages."""
    names = [n for n, _ in LINKAGES]
    assert len(names) >= 24 and {"watt1", "watt2", "hoekens", "slider-crank", "jansen"} <= set(names)


class _Builds(dict):
    """Each linkage's parts built when a test first asks for it, then kept: a worker of a parallel run builds only
    the linkages of the tests it is given, not all of them."""

    def __missing__(self, name: str):
        self[name] = design_linkage(validate_spec(dict(LINKAGES)[name]), parts=True).build
        return self[name]


@pytest.fixture(scope="module")
def builds():
    return _Builds()


#: the tests that share the builds (and FreeCAD's reading of every sheet) run on one worker, so each is made once
SHARED = pytest.mark.xdist_group("outline-pieces")


def _pieces(shape) -> np.ndarray:
    """The distance between the two vertices of each piece of a contour (mm)."""
    v = shape.vertices
    return np.linalg.norm(np.roll(v, -1, axis=0) - v, axis=1)


def _contours(build):
    for part in (*build.cut, *build.printed):
        yield part.name, part.outline
        yield from ((part.name, h) for h in part.holes if isinstance(h, Contour))
    for drawing in (*build.sheets, build.assembly):
        yield from ((layer, s) for layer, s in drawing.items if isinstance(s, Contour))


@SHARED
@pytest.mark.parametrize("name", [n for n, _ in LINKAGES])
def test_no_piece_shorter_than_the_bound(builds, name):
    build = builds[name]
    shortest = min(_pieces(shape).min() for _, shape in _contours(build))
    assert shortest >= MIN_PIECE_MM, name


@SHARED
def test_watt_output_links_are_plain_bars(builds):
    """The output link F-G-P: its third hole 1e-10 to 1e-9 mm off the line of the other two, so its outline is the
    bar round F and P (two lines, two half-turn arcs) with the corner at G merged into one vertex. Its area is
    Steiner's for the triangle's hull grown by w = 4 mm: A + w (FG + GP + PF) + pi w^2 (to 1e-9 mm^2; about
    2 w FP + pi w^2 with FP = 130 and 115 mm), and its pieces are at least 4 mm long."""
    for name, length in (("watt1", 130.0), ("watt2", 115.0)):
        build = builds[name]
        [output] = [p for p in build.parts if p.name == "output"]
        f, g, p = output.centres
        triangle = abs(float((g - f)[0] * (p - f)[1] - (g - f)[1] * (p - f)[0])) / 2
        perimeter = math.dist(f, g) + math.dist(g, p) + math.dist(p, f)
        outline = output.outline()
        assert outline.area == pytest.approx(triangle + 4.0 * perimeter + math.pi * 4.0**2, abs=1e-9)
        assert math.dist(f, p) == pytest.approx(length, abs=1e-8)
        assert outline.n_arcs == 2 and _pieces(outline).min() > 4.0


def test_merging_by_hand():
    """A square of side 10 with a corner arc 1e-9 long and a line 1e-8 long: both merged, the vertices at the
    midpoints of their ends; a piece at the bound is kept; a hull of two points 1e-9 apart is a circle."""
    v = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 1e-9], [10.0, 10.0], [1e-8, 10.0], [0.0, 10.0]])
    b = np.array([0.0, 1e-10, 0.0, 0.0, 0.0, 0.0])
    mv, mb = merged_pieces(v, b)
    assert mv.tolist() == [[0.0, 0.0], [10.0, 0.5e-9], [10.0, 10.0], [0.5e-8, 10.0]] and mb.tolist() == [0.0] * 4
    kept = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, MIN_PIECE_MM], [0.0, 10.0]])
    assert len(merged_pieces(kept, np.zeros(4))[0]) == 4
    circle = rounded_hull(np.array([[0.0, 0.0], [1e-9, 0.0]]), 5.0)
    assert len(circle.vertices) == 2 and circle.area == pytest.approx(math.pi * 25.0, rel=1e-12)


def _expect(drawing: Drawing) -> dict:
    """Each contour's and circle's exact area (with 1e-6 of it allowed) and the drawing's box (mm)."""
    shapes = [s for _, s in drawing.items if not isinstance(s, (Text, Polyline))]
    boxes = np.array([s.bounds() if isinstance(s, Contour) else (s.centre[0] - s.radius, s.centre[1] - s.radius,
                                                                 s.centre[0] + s.radius, s.centre[1] + s.radius)
                      for s in shapes])
    return {"areas": [[abs(s.area), 1e-6 * abs(s.area)] for s in shapes],
            "box": [*boxes[:, :2].min(axis=0), *boxes[:, 2:].max(axis=0)], "box_tol": 1e-6}


@pytest.fixture(scope="module")
def freecad_read(builds, tmp_path_factory) -> dict[str, list[dict]]:
    """What FreeCAD finds in each cut sheet's DXF of every linkage: {name: [{"code", "found"}, ...] a sheet}, all
    the sheets read by one ``freecadcmd`` (tests/programs/freecad_dxf_check.py with CAMGEN_DXFS: its start is most
    of a sheet's check), each against its own expected areas and box as :func:`_expect` gives them."""
    program = shutil.which("freecadcmd")
    if program is None:
        pytest.skip("freecadcmd is not installed (Debian package freecad; .ci/run installs it)")
    folder = tmp_path_factory.mktemp("sheets")
    jobs, names = [], []
    for name, _ in LINKAGES:
        for k, sheet in enumerate(builds[name].sheets):
            path = folder / f"{name}-{k}.dxf"
            write_dxf(sheet, path)
            jobs.append([str(path), _expect(sheet)])
            names.append(name)
    done = subprocess.run([program, str(PROGRAMS / "freecad_dxf_check.py")], capture_output=True, text=True,
                          env={**os.environ, "CAMGEN_DXFS": json.dumps(jobs)}, timeout=600)
    lines = done.stdout.strip().splitlines()
    assert lines and lines[-1].startswith("["), done.stdout[-2000:] + done.stderr[-2000:]
    found: dict[str, list[dict]] = {name: [] for name, _ in LINKAGES}
    for name, result in zip(names, json.loads(lines[-1]), strict=True):
        found[name].append(result)
    return found


@SHARED
@pytest.mark.parametrize("name", [n for n, _ in LINKAGES])
def test_freecad_reads_each_sheet_as_its_closed_wires(builds, freecad_read, name):
    sheets = builds[name].sheets
    assert len(freecad_read[name]) == len(sheets)
    for sheet, result in zip(sheets, freecad_read[name], strict=True):
        assert result["code"] == 0, (name, json.dumps(result["found"])[:2000])
        assert len(result["found"]["wires"]) == len(_expect(sheet)["areas"])


def test_freecad_check_sees_a_zero_length_arc(tmp_path):
    """The check fails on what the Watt output links were: a bar with a corner arc of 1e-11 mm (FreeCAD reads a
    full circle there and the wire's area grows by pi w^2)."""
    w = 4.0
    bar = Contour(np.array([[0.0, -w], [100.0, -w], [100.0 + 1e-11, -w], [100.0, w], [0.0, w]]),
                  np.array([0.0, 1e-13, 1.0, 0.0, 1.0]))
    drawing = Drawing((("OUTLINE", bar), ("HOLES", Circle((0.0, 0.0), 1.5))), 0.01)
    write_dxf(drawing, tmp_path / "bar.dxf")
    done = freecad_check("dxf", tmp_path / "bar.dxf", _expect(drawing))
    assert done.returncode == 1


@pytest.mark.parametrize("name", ["watt1", "watt2"])
def test_watt_step_builds_every_part(name, tmp_path):
    """`linkgen build` with step, which raised on the output link's zero-length arc: one valid solid a part, each of
    its exact volume (area x 3 mm), the output link's the bar's."""
    pytest.importorskip("OCP")
    from click.testing import CliRunner

    from linkgen.cli import main
    from tests.core.test_step import measure, read_step

    result = CliRunner().invoke(main, ["build", str(ROOT / "templates" / f"{name}.toml"), "-o", str(tmp_path),
                                       "--set", 'output.formats=["step"]'])
    assert result.exit_code == 0, result.output
    build = design_linkage(validate_spec(dict(LINKAGES)[name]), parts=True).build
    solids = dict(read_step(tmp_path / f"{name}.step"))
    assert list(solids) == [p.name for p in build.printed]
    for part in build.printed:
        found = measure(solids[part.name])
        assert found["solids"] == 1 and found["valid"]
        assert found["volume"] == pytest.approx(part.area * 3.0, rel=1e-9)
