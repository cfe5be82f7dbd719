"""Nesting by true outlines (camgen.core.nesting): the written sheets read back with ezdxf and rebuilt as shapely
polygons; no two parts overlap, every gap between parts and to the sheet's edge is at least kerf + margin, every
part is there once, congruent to the part as cut, turned only by an allowed rotation; utilisation is reported and
beats the shelf packing on the bundled jansen parts; parts that overflow a sheet go on more; a part larger than the
sheet is refused with one line naming the sheet field and the part's size, and nothing is written."""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from camgen.core.errors import DesignError
from camgen.core.nesting import SheetRules, nest, rotations_of, shelf
from camgen.core.parts import Part
from camgen.core.shapes import Circle, Contour, rounded_hull
from linkgen.cli import main as linkgen
from tests.conftest import ROOT

JANSEN = ROOT / "templates" / "jansen.toml"
FORMATS = 'output.formats=["dxf","json"]'


def _build(tmp_path: Path, *sets: str, template: Path = JANSEN) -> tuple[Path, CliRunner]:
    out = tmp_path / "out"
    args = ["build", str(template), "-o", str(out), "--set", FORMATS]
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke(linkgen, args)
    return out, result


def _read_sheet(path: Path) -> list[tuple[Contour, list]]:
    """Each part on a written sheet: its outline (exact, from the LWPOLYLINE's bulges) and its holes."""
    msp = ezdxf.readfile(path).modelspace()
    outlines = []
    for pl in msp.query('LWPOLYLINE[layer=="OUTLINE"]'):
        pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
        outlines.append(Contour(pts[:, :2], pts[:, 2]))
    holes = [shapely.Point(np.array(c.dxf.center)[:2]).buffer(c.dxf.radius, quad_segs=64)
             for c in msp.query('CIRCLE[layer=="HOLES"]')]
    return [(o, [h for h in holes if shapely.Polygon(o.flatten(1e-3)).contains(h)]) for o in outlines]


def _check_sheet(parts: list[tuple[Contour, list]], size: tuple[float, float], gap: float) -> None:
    """No overlap, gaps >= gap - 1e-6 between outlines (the chords' distance from the arcs taken off, at 1e-7 mm
    where 1e-3 mm chords leave too little room to tell) and to the edges (exact boxes)."""
    tol = 1e-3
    polys = [(shapely.Polygon(c.flatten(tol)), c.flatten_error(tol)) for c, _ in parts]
    for i, (a, ea) in enumerate(polys):
        assert a.is_valid
        x0, y0, x1, y1 = parts[i][0].bounds()
        assert min(x0, y0, size[0] - x1, size[1] - y1) >= gap - 1e-6
        for j, (b, eb) in enumerate(polys[i + 1:], start=i + 1):
            assert not a.intersects(b)
            if a.distance(b) - ea - eb < gap - 1e-6:                   # touching at the gap: measure finer
                fine = [(shapely.Polygon(parts[k][0].flatten(1e-7)), parts[k][0].flatten_error(1e-7)) for k in (i, j)]
                assert fine[0][0].distance(fine[1][0]) - fine[0][1] - fine[1][1] >= gap - 1e-6


#: the tests of the module's jansen build run on one worker, so it is made once a run
JANSEN_SHEET = pytest.mark.xdist_group("core-nesting-jansen")


@pytest.fixture(scope="module")
def jansen(tmp_path_factory):
    from camgen.core.spec import read_template
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import validate_spec

    out, result = _build(tmp_path_factory.mktemp("jansen"))
    assert result.exit_code == 0, result.output
    design = design_linkage(validate_spec(read_template(JANSEN)), parts=True)
    return out, json.loads((out / "jansen.json").read_text()), design.build


@JANSEN_SHEET
def test_jansen_sheet_read_back_no_overlap_gaps_every_part_once_congruent(jansen):
    out, report, build = jansen
    sheet = report["sheet"]
    table = build.table
    gap = table.kerf + table.margin
    assert sheet["sheets"] == 1 and sheet["gap_mm"] == gap
    parts = _read_sheet(out / "jansen-sheet.dxf")
    _check_sheet(parts, tuple(table.sheet), gap)
    cut = {p.name: p for p in build.cut}
    placed = sheet["parts"]
    assert sorted(p["name"] for p in placed) == sorted(cut)                 # every part, once
    assert len(parts) == len(cut)
    for (outline, holes), where in zip(parts, placed, strict=True):
        part = cut[where["name"]]
        assert where["rotation_deg"] in (0.0, 90.0, 180.0, 270.0)
        assert outline.area == pytest.approx(part.outline.area, rel=1e-9)   # area preserved
        # congruent: the part as cut, turned and moved as the report says, is the outline read back
        moved = part.outline.moved(math.radians(where["rotation_deg"]), np.array([where["x_mm"], where["y_mm"]]))
        assert np.abs(moved.vertices - outline.vertices).max() < 1e-5
        assert np.array_equal(moved.bulges, outline.bulges) or np.abs(moved.bulges - outline.bulges).max() < 1e-9
        assert len(holes) == len(part.holes)
        assert sum(h.area for h in holes) == pytest.approx(sum(abs(h.area) for h in part.holes), rel=1e-3)


@JANSEN_SHEET
def test_utilisation_reported_and_at_least_the_shelf_figure(jansen):
    _, report, build = jansen
    sheet = report["sheet"]
    area = sum(p.area for p in build.cut)
    assert 0 < sheet["shelf_utilisation"] <= sheet["utilisation"] <= 1
    # the figure is the parts' area over the rectangle the layout uses from the sheet's corner
    ends = np.max([p.outline.moved(math.radians(w["rotation_deg"]), np.array([w["x_mm"], w["y_mm"]])).bounds()[2:]
                   for w in sheet["parts"] for p in build.cut if p.name == w["name"]], axis=0)
    assert sheet["utilisation"] == pytest.approx(area / (ends[0] * ends[1]), abs=1e-4)
    shelves = _shelf_extent(build.cut, tuple(build.table.sheet), sheet["gap_mm"])
    assert sheet["shelf_utilisation"] == pytest.approx(area / sum(e[0] * e[1] for e in shelves), abs=1e-4)


def _shelf_extent(parts: tuple[Part, ...], size: tuple[float, float], gap: float) -> list[np.ndarray]:
    """Each sheet's farthest right and top extents (mm) in the shelf layout (camgen.core.nesting.shelf)."""
    placed = shelf(parts, size, gap)
    assert placed is not None
    ends = [np.zeros(2) for _ in range(max(p.sheet for p in placed) + 1)]
    for p in placed:
        ends[p.sheet] = np.maximum(ends[p.sheet], p.outline().bounds()[2:])
    return ends


def test_grain_and_rotation_steps_keep_to_the_allowed_set(tmp_path):
    out, result = _build(tmp_path, "parts.grain=true", "parts.kerf=0.2")
    assert result.exit_code == 0, result.output
    report = json.loads((out / "jansen.json").read_text())["sheet"]
    assert {p["rotation_deg"] for p in report["parts"]} <= {0.0, 180.0} and report["rotations_deg"] == [0.0, 180.0]
    _check_sheet(_read_sheet(out / "jansen-sheet.dxf"), (600.0, 400.0), 3.2)
    assert rotations_of(45, False) == (0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0)
    assert rotations_of(0, True) == (0.0,) and rotations_of(120, True) == (0.0,) and rotations_of(90, True) == (
        0.0, 180.0)


def test_several_sheets_when_one_is_full(tmp_path):
    out, result = _build(tmp_path, "parts.sheet=[100.0, 90.0]")
    assert result.exit_code == 0, result.output
    report = json.loads((out / "jansen.json").read_text())["sheet"]
    assert report["sheets"] >= 2
    assert not (out / "jansen-sheet.dxf").exists()
    seen = []
    for i in range(report["sheets"]):
        parts = _read_sheet(out / f"jansen-sheet-{i + 1}.dxf")
        assert parts
        _check_sheet(parts, (100.0, 90.0), 3.0)
        seen += [p["name"] for p in report["parts"] if p["sheet"] == i + 1]
        assert len(parts) == sum(p["sheet"] == i + 1 for p in report["parts"])
    assert sorted(seen) == sorted({p["name"] for p in report["parts"]}) and len(seen) == len(set(seen))


def test_a_part_larger_than_the_sheet_is_refused_in_one_line_and_nothing_written(tmp_path):
    out, result = _build(tmp_path, "parts.sheet=[100.0, 50.0]")
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: parts.sheet: the parts do not fit a 100 x 50 mm sheet")
    assert " x " in lines[0].split(":")[-1] and "mm" in lines[0] and "Traceback" not in result.output
    assert not out.exists() or not any(out.iterdir())


# ---- the library on any parts ------------------------------------------------------------------------------------

def _plate(name: str, w: float, h: float, hole: float = 0.0) -> Part:
    outline = Contour(np.array([[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]]))
    return Part(name, outline, (Circle((w / 2, h / 2), hole),) if hole else (), 3.0, 0.01)


def _ell(name: str) -> Part:
    """A concave part with arcs: an L whose outer corner is rounded and whose inner corner is a concave arc."""
    verts = np.array([[0.0, 0.0], [60.0, 0.0], [60.0, 15.0], [25.0, 15.0], [15.0, 25.0], [15.0, 60.0], [0.0, 60.0]])
    bulges = np.array([0.0, 0.0, 0.0, -math.tan(math.radians(90) / 4), 0.0, 0.0, 0.0])
    return Part(name, Contour(verts, bulges), (Circle((7.0, 7.0), 3.0),), 3.0, 0.01)


def _written(nested, tmp_path: Path) -> list[list[tuple[Contour, list]]]:
    from camgen.core.writers.dxf import write_dxf

    sheets = []
    for i, drawing in enumerate(nested.drawings(0.01)):
        path = tmp_path / f"s{i}.dxf"
        write_dxf(drawing, path)
        sheets.append(_read_sheet(path))
    return sheets


def test_any_parts_concave_and_round_exact_gaps_and_deterministic(tmp_path):
    parts = (*(_ell(f"ell{i}") for i in range(4)), *(_plate(f"plate{i}", 40 + 5 * i, 20, 6) for i in range(4)),
             Part("disc", rounded_hull(np.zeros((1, 2)), 25.0), (Circle((0.0, 0.0), 4.0),), 3.0, 0.01),
             Part("bar", rounded_hull(np.array([[0.0, 0.0], [90.0, 0.0]]), 6.0), (), 3.0, 0.01))
    rules = SheetRules((200.0, 150.0), 2.5, rotations_of(45, False), "sheet")
    nested = nest(parts, rules)
    assert nest(parts, rules) == nested                                   # no randomness, no clock
    sheets = _written(nested, tmp_path)
    assert sum(len(s) for s in sheets) == len(parts)
    for s in sheets:
        _check_sheet(s, rules.size, rules.gap)
    assert {p.rotation for p in nested.placed} <= set(rules.rotations)
    assert sorted(p.part.name for p in nested.placed) == sorted(p.name for p in parts)
    shelf = nested.shelf_utilisation
    assert shelf is not None and nested.utilisation >= shelf


def test_several_sheets_first_fit_and_labels_inside_parts(tmp_path):
    parts = tuple(_plate(f"p{i}", 50.0, 30.0) for i in range(9))
    rules = SheetRules((110.0, 70.0), 3.0, (0.0, 90.0), "sheet")
    nested = nest(parts, rules)
    # 2 x 2 plates of 50 x 30 fit a 110 x 70 sheet with 3 mm gaps (3 + 50 + 3 + 50 + 3 = 109, 3 + 30 + 3 + 30 + 3 =
    # 69): nine plates take three sheets
    assert nested.sheets == 3
    for s in _written(nested, tmp_path):
        _check_sheet(s, rules.size, rules.gap)
    for drawing in nested.drawings(0.01):
        bodies = [shapely.Polygon(s.flatten(1e-3)) for layer, s in drawing.items if layer == "OUTLINE"]
        labels = [s for layer, s in drawing.items if layer == "LABELS"]
        assert len(labels) == len(bodies)
        for text in labels:
            assert any(b.contains(shapely.Point(text.position)) for b in bodies)


@pytest.mark.parametrize("short", [0.0, 1e-12])
def test_a_part_that_fits_only_just(short):
    size = (50.0 + 6.0 - short, 30.0 + 6.0 - short)
    nested = nest((_plate("only", 50.0, 30.0),), SheetRules(size, 3.0, (0.0,), "parts.sheet"))
    (placed,) = nested.placed
    x0, y0, x1, y1 = placed.outline().bounds()
    assert min(x0, y0, size[0] - x1, size[1] - y1) >= 3.0 - 1e-6


def test_a_part_1e_6_too_large_is_refused_naming_field_and_size():
    with pytest.raises(DesignError) as err:
        nest((_plate("only", 50.0, 30.0),), SheetRules((56.0 - 1e-6, 36.0), 3.0, (0.0,), "parts.sheet"))
    message = str(err.value)
    assert message.startswith("parts.sheet: the parts do not fit") and "only is 50 x 30 mm" in message
    assert "\n" not in message


# ---- a camgen family's sheet -------------------------------------------------------------------------------------

def _family(tmp_path: Path, sheet: str) -> tuple[Path, object]:
    from camgen.cli import main as camgen

    (tmp_path / "rdrd.toml").write_text((ROOT / "templates" / "rdrd.toml").read_text())
    (tmp_path / "fam.toml").write_text(f'base = "rdrd.toml"\nname = "fam"\n[output]\nformats = ["dxf", "json"]\n'
                                       f'kerf = 0.2\n[sheet]\n{sheet}\n[sweep.zip]\n"motion.0.lift" = [10, 20, 30]\n'
                                       '"motion.2.lift" = [10, 20, 30]\n')
    out = tmp_path / "out"
    return out, CliRunner().invoke(camgen, ["family", str(tmp_path / "fam.toml"), "-o", str(out)])


def test_a_family_of_cams_on_one_sheet_read_back(tmp_path):
    from camgen.core.family import read_cut_part

    out, result = _family(tmp_path, "size = [300.0, 200.0]\nmargin = 2.0")
    assert result.exit_code == 0, result.output
    report = json.loads((out / "fam-sheet.json").read_text())
    assert report["sheets"] == 1 and report["gap_mm"] == pytest.approx(2.2)
    parts = _read_sheet(out / "fam-sheet.dxf")
    _check_sheet(parts, (300.0, 200.0), 2.2)
    assert sorted(p["name"] for p in report["parts"]) == sorted(d.name for d in out.iterdir() if d.is_dir())
    for (outline, holes), where in zip(parts, report["parts"], strict=True):
        own = read_cut_part(out / where["name"] / f"{where['name']}.dxf", where["name"])   # the member's cut file
        moved = own.outline.moved(math.radians(where["rotation_deg"]), np.array([where["x_mm"], where["y_mm"]]))
        assert np.abs(moved.vertices - outline.vertices).max() < 1e-5 and outline.area == pytest.approx(
            own.outline.area, rel=1e-9)
        assert len(holes) == len(own.holes)
    assert report["utilisation"] >= report["shelf_utilisation"]


@pytest.mark.parametrize("sheet, words", [
    ("size = [100.0, 100.0]", r"sheet\.size: the parts do not fit a 100 x 100 mm sheet: fam-0lift\d+-2lift\d+ is "
                              r"[\d.]+ x [\d.]+ mm and needs gaps of 3\.2 mm"),
    ("rotations = 70", r"sheet\.rotations: must be 0 or divide 360 degrees"),
    ("colour = 1", r"sheet\.colour: unknown key"),
])
def test_a_family_sheet_refused_in_one_line(tmp_path, sheet, words):
    out, result = _family(tmp_path, sheet)
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and re.match(f"error: {words}", lines[0]), lines
    assert not list(out.glob("fam-sheet*")) if out.exists() else True


# ---- cams of several parts: a Geneva drive, a conjugate pair -------------------------------------------------------

@pytest.mark.parametrize("template, names", [("geneva4", ("wheel", "lock", "crank")), ("conjugate", ("1", "2"))])
def test_a_product_of_several_cut_parts_on_one_sheet(tmp_path, template, names):
    from camgen.cli import main as camgen
    from camgen.core.family import read_cut_part

    out = tmp_path / "o"
    result = CliRunner().invoke(camgen, ["build", str(ROOT / "templates" / f"{template}.toml"), "-o", str(out),
                                         "--set", 'output.formats=["dxf","json"]', "--set", "output.kerf=0.1",
                                         "--set", "output.grain=true"])
    assert result.exit_code == 0, result.output
    report = json.loads((out / f"{template}.json").read_text())["sheet"]
    assert report["gap_mm"] == pytest.approx(3.1) and report["rotations_deg"] == [0.0, 180.0]
    assert 0 < report["shelf_utilisation"] <= report["utilisation"] <= 1
    parts = _read_sheet(out / f"{template}-sheet.dxf")
    _check_sheet(parts, (600.0, 400.0), 3.1)
    assert sorted(p["name"] for p in report["parts"]) == sorted(f"{template}-{n}" for n in names)
    for (outline, _), where in zip(parts, report["parts"], strict=True):
        own = read_cut_part(out / f"{where['name']}.dxf", where["name"])      # the part's own cut file
        moved = own.outline.moved(math.radians(where["rotation_deg"]), np.array([where["x_mm"], where["y_mm"]]))
        assert np.abs(moved.vertices - outline.vertices).max() < 1e-5


def test_a_geneva_drive_larger_than_its_sheet_is_refused(tmp_path):
    from camgen.cli import main as camgen

    out = tmp_path / "o"
    result = CliRunner().invoke(camgen, ["build", str(ROOT / "templates" / "geneva4.toml"), "-o", str(out),
                                         "--set", "output.sheet=[60.0, 400.0]"])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and re.match(r"error: output\.sheet: the parts do not fit a 60 x 400 mm sheet: "
                                        r"geneva4-\w+ is [\d.]+ x [\d.]+ mm", lines[0]), lines
    assert not out.exists() or not any(out.iterdir())
    bad = CliRunner().invoke(camgen, ["build", str(ROOT / "templates" / "geneva4.toml"), "-o", str(out),
                                      "--set", "output.sheet_rotations=70"])
    assert bad.exit_code == 2 and "output.sheet_rotations: must be 0 or divide 360 degrees" in bad.stderr


def test_the_fft_lengths_are_scipys_without_importing_it():
    """The nesting's FFT lengths are the least 5-smooth lengths, as scipy's ``next_fast_len(n, real=True)`` (numpy's
    FFT does the work, so a build never imports scipy for it)."""
    from scipy.fft import next_fast_len

    from camgen.core.nesting import _fast_length

    assert [_fast_length(n) for n in range(1, 3000)] == [next_fast_len(n, real=True) for n in range(1, 3000)]


def test_free_positions_are_those_a_cell_by_cell_check_finds():
    """Where a footprint may lie (camgen.core.nesting._Overlap: an FFT correlation, or on an empty sheet the free
    rectangle) is exactly where it covers no occupied cell, tried position by position: random sheets, empty
    sheets (their borders only), footprints from one cell to the whole window, some with no cell."""
    from numpy.lib.stride_tricks import sliding_window_view

    from camgen.core.nesting import _Grid, _Overlap

    rng = np.random.default_rng(16)
    for trial in range(60):
        grid = _Grid(SheetRules((60.0, 40.0), float(rng.choice([0.0, 3.0, 7.5]))), float(rng.choice([0.5, 1.0])))
        if trial % 4:
            grid.occupied |= rng.random(grid.shape) < rng.uniform(0.0, 0.3)
            grid.outlines.append(shapely.box(0, 0, 1, 1))           # a part is there: not an empty sheet
        window = (int(rng.integers(1, grid.shape[0] + 1)), int(rng.integers(1, grid.shape[1] + 1)))
        mask = rng.random((int(rng.integers(1, window[0] + 1)), int(rng.integers(1, window[1] + 1)))) < \
            rng.choice([0.0, 0.3, 1.0])
        free = _Overlap(grid, window).free(mask)
        under = sliding_window_view(grid.occupied[:window[0], :window[1]], mask.shape)
        assert np.array_equal(free, ~(under & mask).any(axis=(2, 3))), trial


@pytest.mark.parametrize("lean", ["left", "down"])
def test_each_row_s_first_free_position_is_the_best_of_all(lean):
    """The best position by the nesting's order (the layout's rectangle, the corner, then the lean's extents, then
    the first in row-major order) among every free position, as the order was applied before, is among each row's
    first free ones (camgen.core.nesting._first_free), and chosen the same from them."""
    from camgen.core.nesting import _first_free

    def best(free: np.ndarray, cell: float, size: tuple[float, float], ends: np.ndarray) -> tuple[int, int]:
        right = free[:, 1] * cell + size[0]
        top = free[:, 0] * cell + size[1]
        used = np.round(np.maximum(right, ends[0]) * np.maximum(top, ends[1]), 6)
        first, second = (right, top) if lean == "left" else (top, right)
        j = int(np.lexsort((second, first, np.round(right + top, 6), used))[0])
        return int(free[j, 0]), int(free[j, 1])

    rng = np.random.default_rng(6)
    for _ in range(200):
        grid = rng.random((int(rng.integers(1, 60)), int(rng.integers(1, 60)))) < rng.uniform(0.05, 1.0)
        if not grid.any():
            continue
        cell, size = float(rng.choice([0.25, 0.98, 2.0])), tuple(rng.uniform(1, 80, 2))
        ends = rng.choice([0.0, 20.0, 150.0], 2) * rng.random(2)
        assert best(_first_free(grid), cell, size, ends) == best(np.argwhere(grid), cell, size, ends)


# ---- the nesting's memory: footprints kept packed, up to a limit ---------------------------------------------------

def _mixed(n: int) -> tuple[Part, ...]:
    """n parts of three shapes (a concave L with an arc, plates with a hole, round-ended bars), 30-60 mm."""
    return tuple((_ell(f"ell{i}"), _plate(f"plate{i}", 30.0 + 4 * i, 12.0, 4.0),
                  Part(f"bar{i}", rounded_hull(np.array([[0.0, 0.0], [40.0 + 3 * i, 0.0]]), 5.0), (), 3.0, 0.01))[i % 3]
                 for i in range(n))


def _kept_bound(parts: tuple[Part, ...], rules: SheetRules) -> int:
    """What keeping every footprint costs at most (bytes): a bit a cell, ENTRY_BYTES an entry, for every part at
    every rotation (its cells' count from camgen.core.nesting._Flat.frame)."""
    from camgen.core import nesting

    cell = max(nesting.MIN_CELL_MM, math.sqrt(rules.size[0] * rules.size[1] / nesting.MAX_CELLS))
    total = 0
    for part in parts:
        flat = nesting._Flat.of(part, rules)
        shapes = [flat.frame(k, cell)[1] for k in range(len(flat.angles))]
        total += sum(math.ceil(rows * cols / 8) + nesting.ENTRY_BYTES for rows, cols in shapes)
    return total


@pytest.mark.slow
def test_nest_memory_is_the_packed_footprints_at_most_linear_in_parts_and_capped(monkeypatch):
    """tracemalloc's peak of nest() (6 parts, 6-degree steps: 60 rotations each) with the footprints kept for the
    later layouts exceeds the peak with none kept by at most a bit a footprint cell and ENTRY_BYTES a footprint
    (the stated per-part constant: under 0.11 MB a part here; a byte a cell, as kept before, is 8 times the cells) and,
    with the limit lowered, by at most the limit; the layout is the same to the last bit, kept or not.

    The size: 360 footprints keep about 0.31 MB, three times the lowered limit (so the limit bites) and far above
    tracemalloc's noise; 3-degree steps only doubled the footprints (and the three traced runs' time)."""
    import tracemalloc

    from camgen.core import nesting

    parts = _mixed(6)
    rules = SheetRules((600.0, 400.0), 2.0, rotations_of(6, False), "sheet")
    bound = _kept_bound(parts, rules)
    default = nesting.FOOTPRINT_CACHE_BYTES

    def peak(limit: int):
        monkeypatch.setattr(nesting, "FOOTPRINT_CACHE_BYTES", limit)
        tracemalloc.start()
        try:
            nested = nest(parts, rules)
            return nested, tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()

    none, bare = peak(0)
    kept, full = peak(default)
    capped, low = peak(100_000)
    assert kept == none and capped == none
    assert bound < 6 * 0.11e6 and bound < default                 # all kept at the default limit
    assert bound > 3 * 100_000                                    # the lowered limit keeps a third at most
    assert full - bare <= bound
    assert low - bare <= 100_000


def test_footprints_kept_are_the_cells_made_and_the_limit_holds_at_one_entry():
    """A kept footprint (packed bits) unpacks to the cells _Flat.footprint makes, corner and all; a limit of exactly
    one footprint's bytes keeps that one and no more, 1 byte less keeps none (each is then made anew, the same);
    each rotation's box, from the turned vertices, is shapely's box of that rotation's polygon to the last bit."""
    from camgen.core.nesting import ENTRY_BYTES, _Flat, _Footprints, _Grid

    rules = SheetRules((200.0, 150.0), 2.5, rotations_of(30, False), "sheet")
    flat = _Flat.of(_ell("ell"), rules)
    grid = _Grid(rules, 0.5)
    made = [flat.footprint(k, grid) for k in range(len(flat.angles))]
    assert np.array_equal(flat.bounds, [flat.polygon(k).bounds for k in range(len(flat.angles))])   # to the bit
    one = int(np.ceil(made[0][1].size / 8)) + ENTRY_BYTES
    for limit, count in ((10**9, len(made)), (one, 1), (one - 1, 0)):
        cache = _Footprints(limit)
        for _ in range(2):                                  # made, then (where kept) unpacked
            for k, (lo, mask) in enumerate(made):
                got_lo, got = cache.get(0, flat, k, grid)
                assert np.array_equal(got_lo, lo) and got.dtype == bool and np.array_equal(got, mask)
        assert len(cache.kept) == count and cache.used <= limit


# ---- every part within the sheet, at any margin (issue 30) ---------------------------------------------------------

def _exact_extent(vertices: np.ndarray, bulges: np.ndarray) -> tuple[float, float, float, float]:
    """A closed outline's (xmin, ymin, xmax, ymax) in mm, its arcs exact: each bulged segment's centre and radius
    from its chord and included angle 4 atan(bulge), and the points where it crosses an axis direction from its
    centre (independently of Contour.bounds, which the nesting uses)."""
    points = [vertices]
    n = len(vertices)
    for i in range(n):
        if bulges[i] == 0:
            continue
        p0, p1 = vertices[i], vertices[(i + 1) % n]
        theta = 4 * math.atan(bulges[i])
        chord = p1 - p0
        length = math.hypot(*chord)
        radius = length / (2 * abs(math.sin(theta / 2)))
        centre = (p0 + p1) / 2 + np.array([-chord[1], chord[0]]) / length * (length / 2) / math.tan(theta / 2)
        start = math.atan2(p0[1] - centre[1], p0[0] - centre[0])
        for k in range(4):
            direction = k * math.pi / 2
            # the direction lies on the arc: its turn from the start, the arc's way round, is within the sweep
            if abs(math.remainder((direction - start) * math.copysign(1.0, theta) - abs(theta) / 2, 2 * math.pi)) \
                    <= abs(theta) / 2:
                points.append(centre + radius * np.array([[math.cos(direction), math.sin(direction)]]))
    allp = np.vstack(points)
    return float(allp[:, 0].min()), float(allp[:, 1].min()), float(allp[:, 0].max()), float(allp[:, 1].max())


def test_the_exact_extent_of_arcs_against_dense_sampling():
    """The measure itself: a half-disc, a three-quarter arc either way round and a small bulge, against 200 001
    points on each arc."""
    for vertices, bulges in [
        (np.array([[0.0, 0.0], [10.0, 0.0]]), np.array([1.0, 0.0])),                          # half-disc below
        (np.array([[3.0, 1.0], [1.0, 3.0]]), np.array([math.tan(3 * math.pi / 8), 0.0])),     # 270 degrees ccw
        (np.array([[3.0, 1.0], [1.0, 3.0]]), np.array([-math.tan(3 * math.pi / 8), 0.0])),    # 270 degrees cw
        (np.array([[0.0, 0.0], [5.0, 2.0], [1.0, 4.0]]), np.array([0.1, -0.3, 0.0])),
    ]:
        dense = [vertices]
        for i, b in enumerate(bulges):
            if b:
                p0, p1 = vertices[i], vertices[(i + 1) % len(vertices)]
                theta = 4 * math.atan(b)
                chord = p1 - p0
                length = math.hypot(*chord)
                centre = (p0 + p1) / 2 + np.array([-chord[1], chord[0]]) / length * (length / 2) / math.tan(theta / 2)
                radius = math.dist(p0, centre)
                t = math.atan2(*(p0 - centre)[::-1]) + np.linspace(0.0, theta, 200001)
                arc = centre + radius * np.column_stack([np.cos(t), np.sin(t)])
                assert np.abs(arc[-1] - p1).max() < 1e-9
                dense.append(arc)
        d = np.vstack(dense)
        want = (d[:, 0].min(), d[:, 1].min(), d[:, 0].max(), d[:, 1].max())
        assert _exact_extent(vertices, bulges) == pytest.approx(want, abs=1e-8)


def _outlines(path: Path) -> list[tuple[np.ndarray, np.ndarray]]:
    msp = ezdxf.readfile(path).modelspace()
    return [(pts[:, :2], pts[:, 2]) for pl in msp.query('LWPOLYLINE[layer=="OUTLINE"]')
            for pts in [np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])]]


@pytest.mark.parametrize("template", ["jansen", "klann"])
@pytest.mark.parametrize("margin, kerf, step", [(0.0, 0.0, 90), (0.0, 0.0, 15), (0.0, 0.1, 90), (1e-6, 0.2, 45)])
def test_every_nested_part_lies_within_the_sheet_at_any_margin(tmp_path, template, margin, kerf, step):
    """Every part's outline on the written sheet, its arcs measured exactly (:func:`_exact_extent`), lies at least
    kerf + margin inside each of the sheet's four edges, to 1e-9 mm, margin 0 included. (Measured through ezdxf's
    bounding box or path, which make each arc of up to 90 degrees a cubic Bezier that bulges out by about 2.7e-4
    times its radius, a part of a 16 mm bar seems to reach 2 um past the edge; the arcs themselves do not.)"""
    sheet = (300.0, 200.0)
    out, result = _build(tmp_path, f"parts.margin={margin}", f"parts.kerf={kerf}", f"parts.sheet_rotations={step}",
                         f"parts.sheet=[{sheet[0]}, {sheet[1]}]", template=ROOT / "templates" / f"{template}.toml")
    assert result.exit_code == 0, result.output
    gap = kerf + margin
    report = json.loads((out / f"{template}.json").read_text())["sheet"]
    assert report["gap_mm"] == pytest.approx(gap, abs=1e-15)
    paths = sorted(out.glob(f"{template}-sheet*.dxf"))
    assert len(paths) == report["sheets"]
    placed = [o for path in paths for o in _outlines(path)]
    assert len(placed) == len(report["parts"])
    for vertices, bulges in placed:
        x0, y0, x1, y1 = _exact_extent(vertices, bulges)
        assert min(x0, y0, sheet[0] - x1, sheet[1] - y1) >= gap - 1e-9


@pytest.mark.parametrize("seed", range(6))
def test_any_parts_lie_within_the_sheet_with_no_gap(seed):
    """nest() with gap 0 (margin 0, no kerf): random rounded hulls of 1 to 4 centres at 15-degree steps, on a sheet
    each fits, measured with the exact extent of each placed outline; and a part exactly the sheet's size, placed
    at its corner."""
    rng = np.random.default_rng(seed)
    parts = tuple(Part(f"p{i}", rounded_hull(rng.uniform(-30, 30, (int(rng.integers(1, 5)), 2)),
                                             float(rng.uniform(1, 12))), (), 3.0, 0.01) for i in range(6))
    size = (float(rng.uniform(120, 200)), float(rng.uniform(120, 200)))
    nested = nest(parts, SheetRules(size, 0.0, rotations_of(15, False), "sheet"))
    assert sorted(p.part.name for p in nested.placed) == sorted(p.name for p in parts)
    for p in nested.placed:
        outline = p.outline()
        x0, y0, x1, y1 = _exact_extent(outline.vertices, outline.bulges)
        assert min(x0, y0, size[0] - x1, size[1] - y1) >= -1e-9
    (only,) = nest((_plate("only", 50.0, 30.0),), SheetRules((50.0, 30.0), 0.0, (0.0,), "sheet")).placed
    x0, y0, x1, y1 = _exact_extent(only.outline().vertices, only.outline().bulges)
    assert min(x0, y0, 50.0 - x1, 30.0 - y1) >= -1e-9
