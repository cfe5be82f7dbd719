"""The fit-test coupon (issue 18, item 4): its holes read back from the DXF and measured in the STL equal their
labels plus the stated allowance; the labels parse to the clearances; bad values are one line, exit 2, no file."""
from __future__ import annotations

import json
import math
import re

import ezdxf
import numpy as np
import pytest
import shapely
import trimesh
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core.coupon import MAX_HOLES, coupon, coupon_spec, design_coupon
from camgen.core.errors import SpecError

KERF, PRINT, FOOT = 0.12, 0.2, 0.3


def run(tmp_path, *sets: str):
    args = ["coupon", "-o", str(tmp_path)]
    for s in sets:
        args += ["--set", s]
    return CliRunner().invoke(camgen, args)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """A 5 mm coupon with a kerf and a print clearance, as the command writes it."""
    out = tmp_path_factory.mktemp("coupon")
    result = run(out, f"output.kerf={KERF}", f"output.clearance={PRINT}")
    assert result.exit_code == 0, result.output
    return out, json.loads((out / "coupon.json").read_text())


def single(coordinate: float) -> float:
    """How far (mm) single precision may round a coordinate of this size: half its spacing."""
    return float(np.spacing(np.float32(abs(coordinate)))) / 2


def corners(mesh: trimesh.Trimesh, z: float, centre: tuple[float, float]) -> np.ndarray:
    """The distances from ``centre`` (mm) of the corners of the hole round it in ``mesh`` sliced at height ``z``:
    the slice's points on the walls' vertical edges, whose x and y are a vertex's (the slice also crosses the walls'
    diagonals, between the corners, inside the circle)."""
    rings = [np.asarray(r)[:, :2] for r in mesh.section(plane_origin=[0, 0, z], plane_normal=[0, 0, 1]).discrete]
    ring = min(rings, key=lambda r: np.linalg.norm(r.mean(axis=0) - centre))
    vertices = {tuple(v) for v in np.round(mesh.vertices[:, :2], 9)}
    on_edges = np.array([tuple(p) in vertices for p in np.round(ring, 9)])
    return np.linalg.norm(ring[on_edges] - np.asarray(centre), axis=1)


def test_the_dxf_holes_are_their_labels_less_the_kerf(built):
    out, report = built
    msp = ezdxf.readfile(out / "coupon.dxf").modelspace()
    circles = msp.query('CIRCLE[layer=="HOLES"]')
    labels = [t for t in msp.query('TEXT[layer=="LABELS"]') if t.dxf.text[0] in "+-"]
    assert len(circles) == len(labels) == 13 == len(report["holes"])
    for text in labels:
        clearance = float(text.dxf.text)                      # the label parses to the clearance
        x = text.dxf.insert.x + 0.6 * text.dxf.height * len(text.dxf.text) / 2
        circle = min(circles, key=lambda c: abs(c.dxf.center.x - x))
        assert abs(circle.dxf.center.x - x) < 1e-9 and circle.dxf.center.y > text.dxf.insert.y + text.dxf.height
        assert 2 * circle.dxf.radius == pytest.approx(5.0 + clearance - KERF, abs=1e-9)
    clearances = sorted(float(t.dxf.text) for t in labels)
    assert clearances == pytest.approx(np.round(np.arange(-0.2, 0.4001, 0.05), 9), abs=1e-12)
    # the report lists each hole as drawn, in order from the left
    for hole, c in zip(report["holes"], clearances, strict=True):
        assert float(hole["label"]) == hole["clearance_mm"] == pytest.approx(c, abs=1e-12)
        assert hole["nominal_mm"] == 5.0
        assert hole["cut_diameter_mm"] == pytest.approx(5.0 + c - KERF, abs=1e-9)
        assert hole["printed_diameter_mm"] == pytest.approx(5.0 + c + PRINT, abs=1e-9)
    # the pin's disc grows by half the kerf: nominal + kerf across
    pins = [np.array(p.get_points("xy")) for p in msp.query('LWPOLYLINE[layer=="OUTLINE"]')
            if len(p) == 2]
    assert len(pins) == 1
    assert np.ptp(pins[0][:, 0]) == pytest.approx(5.0 + KERF, abs=1e-9)
    assert report["pin"]["cut_diameter_mm"] == pytest.approx(5.0 + KERF, abs=1e-12)
    # the plate's outline is the nominal one (its top-left corner cut off, at the smallest clearance's end) moved out
    # by half the kerf, exactly: each of its five corners an arc of radius kerf / 2, turning 2 pi in all
    plates = [p for p in msp.query('LWPOLYLINE[layer=="OUTLINE"]') if len(p) > 2]
    assert len(plates) == 1
    points = np.array(plates[0].get_points("xyb"))
    ahead = np.roll(points, -1, axis=0)
    arcs = np.flatnonzero(points[:, 2])
    turn = 4 * np.arctan(points[arcs, 2])
    chord = np.linalg.norm(ahead[arcs, :2] - points[arcs, :2], axis=1)
    assert len(points) == 10 and len(arcs) == 5 and turn.sum() == pytest.approx(2 * math.pi, abs=1e-12)
    assert chord / (2 * np.sin(turn / 2)) == pytest.approx(np.full(5, KERF / 2), abs=1e-12)
    width, height = report["plate_mm"]
    nominal = shapely.Polygon([(0, 0), (width, 0), (width, height), (3.0, height), (0, height - 3.0)])
    lines = [shapely.LineString([p[:2], q[:2]]) for p, q, b in zip(points, ahead, points[:, 2], strict=True) if not b]
    assert all(nominal.exterior.distance(shapely.Point(c)) == pytest.approx(KERF / 2, abs=1e-9)
               for line in lines for c in line.coords)
    assert min(report["holes"], key=lambda h: h["x_mm"])["label"] == "-0.20"


def test_the_stl_holes_are_their_labels_plus_the_print_clearance(built):
    out, report = built
    mesh = trimesh.load(out / "coupon.stl")
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    for hole in report["holes"]:
        radius = (5.0 + float(hole["label"]) + PRINT) / 2
        centre = (hole["x_mm"], hole["y_mm"])
        distance = corners(mesh, 1.5, centre)
        rounding = 2 * single(max(centre) + radius)      # single precision's rounding of a corner's x and y
        assert len(distance) >= 30                       # every corner of the hole's chords (36 or so)
        assert np.all(np.abs(distance - radius) <= rounding)
        assert 2 * distance.mean() == pytest.approx(2 * radius, abs=1e-6 + rounding / 3)
    pin = trimesh.load(out / "coupon-pin.stl")
    assert pin.is_watertight and pin.bounds[1, 2] == pytest.approx(10.0)
    centre = tuple(pin.bounds[:, :2].mean(axis=0))
    assert np.abs(corners(pin, 5.0, centre) - 2.5).max() <= 2 * single(max(centre) + 2.5) + 1e-6


def test_the_elephant_foot_opens_the_holes_on_the_bed_only(tmp_path):
    report = coupon(tmp_path, None, [f"output.clearance={PRINT}", f"output.elephant_foot={FOOT}",
                                     'output.formats=["stl","json"]'])
    mesh = trimesh.load(tmp_path / "coupon.stl")
    assert mesh.is_watertight and mesh.is_winding_consistent
    bed = mesh.vertices[mesh.vertices[:, 2] == 0.0][:, :2]
    for hole in report["holes"]:
        radius, centre = hole["printed_diameter_mm"] / 2, (hole["x_mm"], hole["y_mm"])
        rounding = 2 * single(max(centre) + radius)
        for z in (1.5, FOOT + 1e-3):                    # above the chamfer the holes are as printed
            assert np.all(np.abs(corners(mesh, z, centre) - radius) <= rounding)
        # on the bed the hole is opened by the chamfer (its cones' chords within the tolerance, 0.01 mm)
        near = np.linalg.norm(bed - centre, axis=1)
        widest = near[near < radius + FOOT + 0.1].max()
        assert radius + FOOT - 0.01 <= widest <= radius + FOOT + rounding
    plate = report["mesh"]["plate"]
    assert abs(plate["volume_error_mm3"]) <= plate["volume_bound_mm3"]


def test_the_files_and_the_python_call(tmp_path):
    report = coupon(tmp_path, {"coupon": {"diameter": 8, "clearance_min": 0, "clearance_max": 0.3,
                                          "clearance_step": 0.1}})
    assert sorted(report["files"].values()) == ["coupon-cut.svg", "coupon-pin.3mf", "coupon-pin.stl", "coupon.3mf",
                                                "coupon.dxf", "coupon.json", "coupon.stl"]
    assert [h["label"] for h in report["holes"]] == ["+0.00", "+0.10", "+0.20", "+0.30"]
    assert [h["cut_diameter_mm"] for h in report["holes"]] == pytest.approx([8.0, 8.1, 8.2, 8.3], abs=1e-12)
    assert json.loads((tmp_path / "coupon.json").read_text())["holes"] == report["holes"]
    # a step the range does not divide ends below clearance_max; finer steps get more decimals
    spec = coupon_spec(None, ["coupon.clearance_min=0", "coupon.clearance_max=0.1", "coupon.clearance_step=0.025"])
    assert design_coupon(spec).labels == ("+0.000", "+0.025", "+0.050", "+0.075", "+0.100")
    spec = coupon_spec(None, ["coupon.clearance_min=0", "coupon.clearance_max=0.1", "coupon.clearance_step=0.03"])
    assert design_coupon(spec).labels == ("+0.00", "+0.03", "+0.06", "+0.09")
    # the sheet as a figure when asked
    report = coupon(tmp_path / "some", None, ['output.formats=["dxf","json","png"]'])
    assert sorted(report["files"].values()) == ["coupon.dxf", "coupon.json", "coupon.png"]


def test_the_figures_show_the_sheet(tmp_path):
    """png and svg: the cut sheet drawn by matplotlib, a colour a layer (the outlines matplotlib's first, C0
    #1f77b4, the holes its second, C1 #ff7f0e); the PNG reads back as an image with both colours in it, the SVG as
    an SVG document naming both layers in its legend."""
    import xml.etree.ElementTree as ET

    import matplotlib.image

    report = coupon(tmp_path, None, ['output.formats=["png","svg"]'])
    assert sorted(report["files"].values()) == ["coupon.png", "coupon.svg"]
    pixels = (matplotlib.image.imread(tmp_path / "coupon.png")[:, :, :3] * 255).round().astype(int)
    seen = {tuple(p) for p in pixels.reshape(-1, 3)}
    assert len(pixels) > 100 and (31, 119, 180) in seen and (255, 127, 14) in seen
    root = ET.parse(tmp_path / "coupon.svg").getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert {"OUTLINE", "HOLES"} <= {c.text for c in root.iter("{http://www.w3.org/2000/svg}title")} | set(
        re.findall(r"<!-- (\w+) -->", (tmp_path / "coupon.svg").read_text()))


def test_step_holds_the_plate_and_the_pin_as_on_the_sheet(tmp_path):
    """step: the printed plate and pin as exact solids, named coupon and coupon-pin, re-read by Open CASCADE and by
    FreeCAD: each its exact area x thickness (the holes nominal + c_k + output.clearance, the pin pi d^2 / 4 x
    pin_length), the plate's box from the origin, the pin's round its centre beside the plate on the cut sheet."""
    pytest.importorskip("OCP")
    from tests.support.freecad import freecad_check
    from tests.core.test_step import _fc, assert_apart, assert_plate, expect_plate, measure, read_step

    report = coupon(tmp_path, None, [f"output.clearance={PRINT}", 'output.formats=["step","json","dxf"]'])
    assert report["files"]["step"] == "coupon.step"
    design = design_coupon(coupon_spec(None, [f"output.clearance={PRINT}"]))
    plate, pin = design.printed
    solids = read_step(tmp_path / "coupon.step")
    assert [name for name, _ in solids] == ["coupon", "coupon-pin"]
    for (_, shape), part in zip(solids, design.printed, strict=True):
        assert_plate(measure(shape), part)
    width, height = report["plate_mm"]
    holes = sum(math.pi * (h["printed_diameter_mm"] / 2) ** 2 for h in report["holes"])
    corner = design.spec.coupon.web ** 2 / 2
    assert measure(solids[0][1])["volume"] == pytest.approx((width * height - corner - holes) * 3.0, rel=1e-9)
    x, y = design.pin.centre
    assert measure(solids[1][1])["volume"] == pytest.approx(math.pi * 2.5**2 * 10.0, rel=1e-9)
    assert measure(solids[1][1])["box"] == pytest.approx([x - 2.5, y - 2.5, 0.0, x + 2.5, y + 2.5, 10.0], abs=1e-6)
    assert x - 2.5 > width                                  # beside the plate, not on it
    # where the cut sheet has the pin's disc (a closed polyline of two half-turn arcs), and the plate's outline
    discs = [np.array(pl.get_points("xy")) for pl in ezdxf.readfile(tmp_path / "coupon.dxf").modelspace().query(
        'LWPOLYLINE[layer=="OUTLINE"]')]
    [disc] = [d for d in discs if len(d) == 2]
    assert disc.mean(axis=0) == pytest.approx([x, y], abs=1e-9)
    box = measure(solids[0][1])["box"]
    assert box == pytest.approx([0.0, 0.0, 0.0, width, height, 3.0], abs=1e-6)
    assert_apart([box, measure(solids[1][1])["box"]])
    done = freecad_check("step", tmp_path / "coupon.step", [_fc(expect_plate(p)) for p in (plate, pin)])
    assert done.returncode == 0, done.stdout.strip().splitlines()[-1][:2000]


def test_a_page_is_refused_in_one_line(tmp_path):
    result = run(tmp_path / "o", 'output.formats=["dxf","html"]')
    assert result.exit_code == 2 and result.stderr.count("\n") == 1
    assert result.stderr.startswith("error: output.formats: a coupon is written as dxf, cut-svg, stl, 3mf, json, "
                                    "png, svg, step (html does not apply")
    assert not (tmp_path / "o").exists()
    # the default (no output.formats) is the coupon's own, without the page
    assert run(tmp_path / "d").exit_code == 0 and not list((tmp_path / "d").glob("*.html"))


def test_hard_cases_at_the_limits():
    # exactly MAX_HOLES holes is allowed, one step finer is not
    step = 0.6 / MAX_HOLES
    assert len(design_coupon(coupon_spec(None, [f"coupon.clearance_step={step * (1 + 1e-9)!r}"])).labels) == MAX_HOLES
    with pytest.raises(SpecError, match=r"^coupon.clearance_step: must be > 0.012 mm, .* \(got 0.012: 51 holes\)"):
        coupon_spec(None, [f"coupon.clearance_step={step!r}"])
    # one hole when the range is a point
    assert design_coupon(coupon_spec(None, ["coupon.clearance_max=-0.2"])).labels == ("-0.20",)
    # the kerf just below the smallest hole is allowed, at it refused
    spec = coupon_spec(None, ["coupon.diameter=3", "coupon.clearance_min=-0.5", f"output.kerf={2.5 - 1e-9!r}"])
    assert design_coupon(spec).cut[0].holes[0].radius == pytest.approx(0.5e-9, abs=1e-15)
    with pytest.raises(SpecError, match=r"^output.kerf: must be < 2.5 mm"):
        coupon_spec(None, ["coupon.diameter=3", "coupon.clearance_min=-0.5", "output.kerf=2.5"])
    with pytest.raises(SpecError, match=r"^coupon.clearance_min: must be > -diameter = -1 mm"):
        coupon_spec(None, ["coupon.diameter=1", "coupon.clearance_min=-1"])


@pytest.mark.parametrize("setting, message", [
    ("coupon.diameter=-3", "error: coupon.diameter: must be > 0 and <= 50 mm (got -3)"),
    ("coupon.diameter=51", "error: coupon.diameter: must be > 0 and <= 50 mm (got 51)"),
    ("coupon.clearance_min=-6", "error: coupon.clearance_min: must be >= -2 and <= 5 mm (got -6)"),
    ("coupon.clearance_max=-0.5", "error: coupon.clearance_max: must be >= clearance_min -0.2 mm (got -0.5)"),
    ("coupon.clearance_step=0", "error: coupon.clearance_step: must be > 0 and <= 5 mm (got 0)"),
    ("output.kerf=6", "error: output.kerf: must be >= 0 and <= 5 mm (got 6)"),
    ("output.elephant_foot=3", "error: output.elephant_foot: must be < the thickness of coupon, 3 mm (got 3)"),
    ("coupon.pitch=3", "error: coupon.pitch: unknown key"),
])
def test_bad_values_are_one_line_exit_2_and_nothing_written(tmp_path, setting, message):
    result = run(tmp_path / "o", setting)
    assert result.exit_code == 2
    assert result.stderr.startswith(message) and result.stderr.count("\n") == 1
    assert not (tmp_path / "o").exists()
