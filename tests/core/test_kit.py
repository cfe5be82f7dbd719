"""Mechanism kits (issue 18, item 3): the parts round a cam or a linkage, read back from the files written, placed by
the design's own kinematics, measured against the catalogue and the design's distances."""
from __future__ import annotations

import itertools
import json
import math

import ezdxf
import numpy as np
import pytest
import shapely
import trimesh
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core.hardware import BEARINGS, BOLTS
from camgen.core.shapes import Contour
from camgen.api import design_cam
from camgen.spec import load_spec
from linkgen.cli import main as linkgen
from tests.conftest import ROOT

TEMPLATES = ROOT / "templates"
#: the module's builds (rdrd in both senses, oscillating, crank_rocker) are made once a run: its tests on one worker
pytestmark = pytest.mark.xdist_group("core-kit")
POSES = 720
#: the files the checks read (no figures or pages: they cost time and are checked elsewhere)
FILES = 'output.formats=["dxf", "stl", "3mf", "json"]'


def _build(main, template, out, *sets):
    args = ["build", str(template), "-o", str(out)]
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return json.loads((out / f"{out.name}.json").read_text()) if (out / f"{out.name}.json").exists() else None


@pytest.fixture(scope="module", params=[(), ("cam.rotation=cw", "follower.offset=-5")], ids=["ccw", "cw"])
def rdrd(tmp_path_factory, request):
    """kit-rdrd built as bundled, and turning clockwise with the follower offset to the left."""
    out = tmp_path_factory.mktemp("kit-rdrd") / "kit-rdrd"
    _build(camgen, TEMPLATES / "kit-rdrd.toml", out, FILES, *request.param)
    spec = load_spec(TEMPLATES / "kit-rdrd.toml", request.param)
    return out, json.loads((out / "kit-rdrd.json").read_text()), design_cam(spec)


@pytest.fixture(scope="module")
def oscillating(tmp_path_factory):
    out = tmp_path_factory.mktemp("kit-oscillating")
    _build(camgen, TEMPLATES / "kit-oscillating.toml", out, FILES)
    spec = load_spec(TEMPLATES / "kit-oscillating.toml")
    return out, json.loads((out / "kit-oscillating.json").read_text()), design_cam(spec)


def _read(path):
    """A DXF part read back: its plan (outline less holes, arcs as chords within 1e-4 mm) and its round holes
    (centre, diameter)."""
    msp = ezdxf.readfile(path).modelspace()
    rings = []
    for pl in msp.query("LWPOLYLINE"):
        pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
        rings.append((pl.dxf.layer, shapely.Polygon(Contour(pts[:, :2], pts[:, 2]).flatten(1e-4))))
    circles = [(np.array(c.dxf.center)[:2], 2 * c.dxf.radius) for c in msp.query("CIRCLE")]
    outline = next(poly for layer, poly in rings if layer == "OUTLINE")
    holes = [poly for layer, poly in rings if layer == "HOLES"]
    holes += [shapely.Point(c).buffer(d / 2, quad_segs=256) for c, d in circles]
    return outline.difference(shapely.union_all(holes)), circles


def _nominal(plan, kerf):
    """A cut part's plan as the laser leaves it: its drawn path moved in by half the kerf (holes open by it)."""
    return plan.buffer(-kerf / 2, quad_segs=64) if kerf else plan


def _stack(report):
    return {s["name"]: (s["z_mm"], s["top_mm"]) for s in report["kit"]["stack"]}


def _centres(design, theta):
    """The roller's centre in the fixed frame: the pitch point (cam frame) turned by the cam's angle."""
    cam = design.cam
    p = cam.pitch(theta).point
    turn = cam.follower.sense * theta
    return np.column_stack([np.cos(turn) * p[:, 0] - np.sin(turn) * p[:, 1],
                            np.sin(turn) * p[:, 0] + np.cos(turn) * p[:, 1]])


def _standoff_diameter(out, name):
    bounds = trimesh.load(out / f"{name}-standoff.stl").bounds
    return float(bounds[1, 0] - bounds[0, 0])


def _turned(plans, turn):
    return np.array([shapely.affinity.rotate(plans, t, origin=(0.0, 0.0), use_radians=True) for t in turn])


def test_translating_kit_runs_a_full_turn_touching_the_cam_only_at_the_roller(rdrd):
    out, report, design = rdrd
    spec = design.spec
    kerf, cam_kerf = spec.kit.kerf, spec.output.kerf
    theta = 2 * np.pi * np.arange(POSES) / POSES
    centres = _centres(design, theta)
    # the design's kinematics in closed form: the roller rides the follower's axis at d0 + s
    rp, e = spec.cam.base_radius + spec.follower.roller_radius, spec.follower.offset
    s = design.cam.program.evaluate(theta)[0]
    assert np.allclose(centres, np.column_stack([np.full(POSES, e), math.sqrt(rp**2 - e**2) + s]), atol=1e-9)
    cam = _nominal(_read(out / "kit-rdrd.dxf")[0], cam_kerf)
    roller = _nominal(_read(out / "kit-rdrd-roller.dxf")[0], kerf)
    follower = _nominal(_read(out / "kit-rdrd-follower.dxf")[0], kerf)
    _, frame_holes = _read(out / "kit-rdrd-frame.dxf")
    cams = _turned(cam, design.cam.follower.sense * theta)
    rollers = np.array([shapely.affinity.translate(roller, *c) for c in centres])
    followers = np.array([shapely.affinity.translate(follower, *c) for c in centres])
    # the roller touches the cam all round the turn: its centre stays its radius off the cam's outline
    gap = shapely.distance(shapely.points(centres), shapely.boundary(cams)) - spec.follower.roller_radius
    assert np.abs(gap).max() <= 2 * spec.output.tolerance
    assert shapely.area(shapely.intersection(cams, rollers)).max() <= 0.05
    # the parts stand at heights where only the cam and the roller share a plane
    stack = _stack(report)
    for a, b in itertools.combinations(["frame", "kit-rdrd", "follower"], 2):
        assert min(stack[a][1], stack[b][1]) <= max(stack[a][0], stack[b][0]) + 1e-9
    assert stack["roller"] == stack["kit-rdrd"]
    # the guide bolts stand in the frame's guide holes and run in the follower's slot over the whole lift
    guides = [c for c, d in frame_holes if abs(c[0] - e) < 1e-6]
    assert len(guides) == 2
    bolt = BOLTS[spec.kit.bolt]
    for c in guides:
        shank = shapely.Point(c).buffer(bolt.diameter / 2, quad_segs=64)
        assert shapely.area(shapely.intersection(followers, shank)).max() == 0.0
        assert shapely.contains(shapely.convex_hull(followers), shank).all()
        # their standoffs share the cam's plane: clear of the cam and the roller all the way round
        post = shapely.Point(c).buffer(_standoff_diameter(out, "kit-rdrd") / 2, quad_segs=64)
        assert shapely.distance(cams, post).min() > 0 and shapely.distance(rollers, post).min() > 0
    assert stack["standoff-1"][0] == stack["frame"][1] and stack["standoff-1"][1] == stack["follower"][0]


def test_oscillating_kit_arm_follows_the_design_and_clears_the_cam(oscillating):
    out, report, design = oscillating
    spec = design.spec
    theta = 2 * np.pi * np.arange(POSES) / POSES
    centres = _centres(design, theta)
    pivot = design.cam.follower.pivot
    assert np.linalg.norm(pivot) == pytest.approx(spec.follower.pivot_distance, abs=1e-9)
    assert np.allclose(np.linalg.norm(centres - pivot, axis=1), spec.follower.arm_length, atol=1e-9)
    # the arm as printed: its two holes the arm length apart (STL section); the frame's pivot hole at the design's
    # pivot, checked in the report's as-made holes
    frame = report["kit"]["parts"][0]
    seat, post = frame["holes"][0], frame["holes"][1]
    assert (seat["x_mm"], seat["y_mm"]) == (0.0, 0.0)
    assert math.hypot(post["x_mm"], post["y_mm"]) == pytest.approx(spec.follower.pivot_distance, abs=1e-9)
    arm = _section(out / "kit-oscillating-follower.stl")
    holes = [np.array(ring.centroid.coords[0]) for ring in arm.interiors_polygons]
    assert float(np.linalg.norm(holes[0] - holes[1])) == pytest.approx(spec.follower.arm_length, abs=1e-6)
    cam = _read(out / "kit-oscillating.dxf")[0]
    cams = _turned(cam, design.cam.follower.sense * theta)
    gap = shapely.distance(shapely.points(centres), shapely.boundary(cams)) - spec.follower.roller_radius
    assert np.abs(gap).max() <= 2 * spec.output.tolerance
    standoff = shapely.Point(pivot).buffer(_standoff_diameter(out, "kit-oscillating") / 2, quad_segs=64)
    assert shapely.distance(cams, standoff).min() > 0


class _Section:
    """A printed part's section at mid-height (read from its STL): its outline and its holes as polygons."""

    def __init__(self, loops):
        loops = sorted(loops, key=lambda p: -p.area)
        self.poly, self.interiors_polygons = loops[0], loops[1:]


def _section(path):
    mesh = trimesh.load(path)
    mid = (mesh.bounds[0, 2] + mesh.bounds[1, 2]) / 2
    cut = mesh.section(plane_origin=[0, 0, mid], plane_normal=[0, 0, 1])
    return _Section([shapely.Polygon(loop[:, :2]) for loop in cut.discrete])


def test_frame_holes_at_the_design_distances_and_catalogue_sizes(rdrd):
    out, report, design = rdrd
    spec = design.spec
    kit = spec.kit
    _, holes = _read(out / "kit-rdrd-frame.dxf")
    seat = [d for c, d in holes if np.all(c == 0.0)]
    assert seat == [pytest.approx(BEARINGS[kit.bearing].outside - kit.kerf, abs=1e-9)]
    guides = [c for c, _ in holes if c[0] == spec.follower.offset]
    assert len(guides) == 2 and all(abs(c[0] - spec.follower.offset) <= 1e-9 for c in guides)
    bolt = BOLTS[kit.bolt]
    assert sorted({round(d, 9) for c, d in holes if not np.all(c == 0.0)}) == [round(bolt.clearance_hole - kit.kerf, 9)]
    assert report["kit"]["seat"] == {"nominal_diameter_mm": 22.0, "as_made_diameter_mm": 21.85}
    _, roller_holes = _read(out / "kit-rdrd-roller.dxf")
    assert [round(d, 9) for _, d in roller_holes] == [round(bolt.clearance_hole - kit.kerf, 9)]


def test_printed_seat_is_the_catalogue_bearing_plus_the_clearance(oscillating):
    out, _, design = oscillating
    kit = design.spec.kit
    frame = _section(out / "kit-oscillating-frame.stl")
    seat = next(h for h in frame.interiors_polygons if h.contains(shapely.Point(0.0, 0.0)))
    diameter = 2 * math.sqrt(seat.area / math.pi)
    expected = BEARINGS[kit.bearing].outside + kit.clearance
    assert diameter == pytest.approx(expected, abs=2 * design.spec.output.tolerance)


def _no_overlaps(path, stack, report):
    """A kit 3MF holds every part the user makes and nothing bought (the report's stack says which are), each a
    closed solid standing at its stack height, and no two of them overlap: manifold3d's intersection of each pair
    is 0 within 1e-9 mm^3 (touching faces leave ~1e-13)."""
    import manifold3d

    scene = trimesh.load(path)
    bought = {s["name"] for s in report["kit"]["stack"] if s["bought"]}
    assert bought and set(scene.geometry) == set(stack) - bought
    solids = {}
    for name, mesh in scene.geometry.items():
        assert mesh.is_watertight
        assert mesh.bounds[:, 2] == pytest.approx(stack[name], abs=1e-4)
        solids[name] = manifold3d.Manifold(manifold3d.Mesh(vert_properties=np.asarray(mesh.vertices, np.float32),
                                                           tri_verts=np.asarray(mesh.faces, np.uint32)))
    for a, b in itertools.combinations(solids, 2):
        common = (solids[a] ^ solids[b]).volume()
        assert common <= 1e-9, (a, b, common)


def test_kit_3mf_has_every_part_in_place_without_overlaps(rdrd):
    out, report, _ = rdrd
    _no_overlaps(out / "kit-rdrd-kit.3mf", _stack(report), report)


def test_oscillating_kit_3mf_holds_the_made_parts_only(oscillating):
    """kit-oscillating (all printed, a 625 bearing in the frame's seat): its 3MF has the frame, arm, roller, spacer,
    standoff and the cam, none of the shaft, bearing, nuts (the bearing's press fit overlapped the frame by 0.35
    mm^3 there); PrusaSlicer reads it as those objects, each manifold, of the volumes trimesh finds (its --info
    rounds to 6 digits)."""
    import re
    import shutil
    import subprocess

    out, report, _ = oscillating
    path = out / "kit-oscillating-kit.3mf"
    _no_overlaps(path, _stack(report), report)
    scene = trimesh.load(path)
    assert set(scene.geometry) == {"frame", "follower", "roller", "spacer", "standoff-1", "kit-oscillating"}
    program = shutil.which("prusa-slicer")
    if program is None:
        pytest.skip("prusa-slicer is not installed (Debian package; .ci/run installs it)")
    info = subprocess.run([program, "--info", str(path)], capture_output=True, text=True, timeout=300).stdout
    volumes = sorted(float(v) for v in re.findall(r"^volume = ([\d.]+)$", info, re.M))
    assert info.count("manifold = yes") == len(volumes) == len(scene.geometry)
    assert volumes == pytest.approx(sorted(m.volume for m in scene.geometry.values()), rel=1e-5)


def test_a_hub_boss_lifts_the_follower_clear(tmp_path):
    out = tmp_path / "kit-rdrd"
    _build(camgen, TEMPLATES / "kit-rdrd.toml", out, "hub.boss_diameter=20", "hub.boss_height=6",
           'output.formats=["json", "3mf"]')
    report = json.loads((out / "kit-rdrd.json").read_text())
    stack = _stack(report)
    assert stack["kit-rdrd"][1] == pytest.approx(stack["kit-rdrd"][0] + 8.0 + 6.0)          # the boss on the cam
    assert stack["follower"][0] == pytest.approx(stack["kit-rdrd"][1] + BOLTS["M4"].washer_thickness)
    assert stack["shaft"][1] == pytest.approx(stack["kit-rdrd"][1])
    _no_overlaps(out / "kit-rdrd-kit.3mf", stack, report)


def test_bill_of_materials_names_the_hardware(rdrd):
    _, report, _ = rdrd
    bom = {line["item"]: line for line in report["kit"]["bom"]}
    assert bom["bearing 608"]["quantity"] == 1 and bom["bearing 608"]["size"] == "8 x 22 x 7 mm"
    bolts = [line for line in report["kit"]["bom"] if line["item"].startswith("M4 x ")]
    assert sum(line["quantity"] for line in bolts) == 5                      # 2 guides, the axle, 2 mounting
    assert bom["standoff"]["quantity"] == 2 and bom["frame"]["source"] == "laser"


def _spring(line: dict) -> list[float]:
    """The numbers of a spring's BOM size, in order."""
    import re

    return [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", line["size"])]


def test_bill_of_materials_lists_the_return_spring(oscillating, tmp_path):
    """A spring-loaded follower's spring is bought: kit-oscillating's (k = 0.5 N/mm, F0 = 5 N at the roller, arm
    L = 90 mm, swing 20 degrees) as a torsion spring at the pivot of k L^2 pi / 180 = 70.69 N*mm a degree, F0 L = 450
    N*mm at psi = 0, F0 L + k L^2 (20 pi / 180) = 1864 N*mm at the full swing, free 180 F0 / (pi k L) = 6.366 degrees
    back; kit-rdrd given k = 2 N/mm and F0 = 10 N as a compression spring of 10 N at s = 0 and F0 + k h = 50 N at
    the full lift of 20 mm, free length 5 mm more than at s = 0; the CSV has the same line; no spring, no line."""
    out, report, _ = oscillating
    [line] = [row for row in report["kit"]["bom"] if row["item"] == "return spring"]
    k, f0, arm, swing = 0.5, 5.0, 90.0, 20.0
    expected = [k * arm**2 * math.pi / 180, k, arm, f0 * arm, 0.0, f0 * arm + k * arm**2 * math.radians(swing), swing,
                math.degrees(f0 / (k * arm)), 0.0]
    assert line["source"] == "buy" and line["standard"] == "EN 13906-3" and line["quantity"] == 1
    assert "torsion spring" in line["size"]
    assert _spring(line) == pytest.approx(expected, rel=5e-4)              # 4 significant digits
    assert any(row["part"] == "return spring" for row in _bom_csv(out, report, "kit-oscillating"))
    rdrd = _build(camgen, TEMPLATES / "kit-rdrd.toml", tmp_path / "kit-rdrd", 'output.formats=["json"]',
                  "follower.spring_rate=2", "follower.preload=10")
    [line] = [row for row in rdrd["kit"]["bom"] if row["item"] == "return spring"]
    assert line["standard"] == "EN 13906-1" and "compression spring" in line["size"]
    assert _spring(line) == pytest.approx([2.0, 10.0, 0.0, 10.0 + 2.0 * 20.0, 20.0, 0.0, 10.0 / 2.0])
    plain = _build(camgen, TEMPLATES / "kit-rdrd.toml", tmp_path / "plain" / "kit-rdrd", 'output.formats=["json"]')
    assert not [row for row in plain["kit"]["bom"] if "spring" in row["item"]]


def _bom_csv(out, report, name):
    """The kit's CSV read back, checked to be the report's bom line for line (its item and source as part and
    process, the columns part, quantity, standard, size, process); its rows."""
    import csv

    assert report["files"]["kit_csv"] == f"{name}-kit.csv"
    with (out / f"{name}-kit.csv").open(encoding="utf-8", newline="") as stream:
        rows = list(csv.DictReader(stream))
    assert list(rows[0]) == ["part", "quantity", "standard", "size", "process"]
    want = [{"part": line["item"], "quantity": str(line["quantity"]), "standard": line["standard"],
             "size": line["size"], "process": line["source"]} for line in report["kit"]["bom"]]
    assert rows == want
    return rows


def test_bill_of_materials_csv_is_the_reports(rdrd):
    """<name>-kit.csv beside the JSON: the report's kit bom line for line, its columns part, quantity, standard, size
    and process; the bought items name their standards."""
    out, report, _ = rdrd
    _bom_csv(out, report, "kit-rdrd")
    bought = [line for line in report["kit"]["bom"] if line["source"] == "buy"]
    assert bought and all(line["standard"] for line in bought)
    assert {line["standard"] for line in report["kit"]["bom"] if line["source"] != "buy"} == {""}
    assert "ISO 4762; ISO 7089; ISO 4032" in {line["standard"] for line in bought}


def _panels(path, degrees):
    """The assembly drawing read back, a panel a cam angle: {degrees: {part: (circles [(centre, diameter)],
    outlines [polygons])}} from layers KIT-<degrees>-<part>, each moved so that its frame's seat (the largest hole
    of the frame, round the shaft) is at the origin."""
    msp = ezdxf.readfile(path).modelspace()
    out = {}
    for deg in degrees:
        prefix = f"KIT-{deg}-"
        parts: dict = {}
        for c in msp.query("CIRCLE"):
            if c.dxf.layer.startswith(prefix):
                parts.setdefault(c.dxf.layer[len(prefix):], ([], []))[0].append((np.array(c.dxf.center)[:2],
                                                                                  2 * c.dxf.radius))
        for pl in msp.query("LWPOLYLINE"):
            if pl.dxf.layer.startswith(prefix):
                pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
                parts.setdefault(pl.dxf.layer[len(prefix):], ([], []))[1].append(
                    shapely.Polygon(Contour(pts[:, :2], pts[:, 2]).flatten(1e-4)))
        origin = max(parts["frame"][0], key=lambda cd: cd[1])[0]
        out[deg] = {name: ([(c - origin, d) for c, d in circles], [shapely.affinity.translate(p, *-origin)
                                                                   for p in polys])
                    for name, (circles, polys) in parts.items()}
    return out


def test_assembly_drawing_a_panel_at_each_quarter_turn(rdrd):
    """kit-rdrd-kit-assembly.dxf holds the kit at 0, 90, 180 and 270 degrees, a panel each: in each, the roller's
    axle hole and the follower's are at the design's roller centre for that cam angle (the follower's axis at the
    offset, d0 + s(theta) up it: the design's lift), the roller touches the cam's outline drawn turned by that angle,
    and the fixed parts stand where they do at 0 degrees."""
    out, _, design = rdrd
    spec = design.spec
    hole = BOLTS[spec.kit.bolt].clearance_hole
    degrees = (0, 90, 180, 270)
    panels = _panels(out / "kit-rdrd-kit-assembly.dxf", degrees)
    rp, e = spec.cam.base_radius + spec.follower.roller_radius, spec.follower.offset
    theta = np.radians(np.array(degrees, dtype=float))
    lift = design.cam.program.evaluate(theta)[0]
    assert np.ptp(lift) > 10.0                                     # the panels show the follower at different lifts
    for deg, t, s in zip(degrees, theta, lift, strict=True):
        panel = panels[deg]
        [centre] = _centres(design, np.array([t]))
        assert np.abs(centre - [e, math.sqrt(rp**2 - e**2) + s]).max() <= 1e-9
        for name in ("roller", "follower"):
            axle = [c for c, d in panel[name][0] if abs(d - hole) < 1e-9]
            assert len(axle) == 1 and np.abs(axle[0] - centre).max() <= 1e-6, (deg, name)
        [cam] = [p for p in panel["kit-rdrd"][1]]
        gap = cam.exterior.distance(shapely.Point(centre)) - spec.follower.roller_radius
        assert abs(gap) <= 2 * spec.output.tolerance, (deg, gap)
        assert [np.round(c, 6).tolist() for c, _ in panel["frame"][0]] == \
            [np.round(c, 6).tolist() for c, _ in panels[0]["frame"][0]]
    assert "KIT-LABELS" in {e.dxf.layer for e in ezdxf.readfile(out / "kit-rdrd-kit-assembly.dxf").modelspace()}


@pytest.mark.parametrize("sets, field, words", [
    (["kit.bearing=609"], "kit.bearing", "unknown value '609' (did you mean '608'?); one of 623, 624, 625, 608, none"),
    (["kit.bearing=625"], "kit.bearing", "for that shaft: 608, none"),
    (["kit.shaft=6"], "kit.shaft", "must be one of 3, 4, 5, 8 mm"),
    (["kit.shaft=8", "cam.bore=7.999999999999"], "kit.shaft", "bore of 7.999999999999 mm (cam.bore); allowed: 3, 4, 5"),
    (["kit.bolt=M6"], "kit.bolt", "unknown value 'M6'; one of M3, M4, M5"),
    (["kit.process=cnc"], "kit.process", "unknown value 'cnc'; one of laser, fdm"),
    (["kit.thickness=-1"], "kit.thickness", "must be > 0"),
    (["kit.wall=0"], "kit.wall", "must be > 0"),
])
def test_bad_kit_values_give_one_line_and_write_nothing(tmp_path, sets, field, words):
    args = ["build", str(TEMPLATES / "kit-rdrd.toml"), "-o", str(tmp_path / "o")]
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke(camgen, args)
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}: ") and words in lines[0], lines
    assert not (tmp_path / "o").exists()


def test_shaft_equal_to_the_bore_fits(tmp_path):
    _build(camgen, TEMPLATES / "kit-rdrd.toml", tmp_path / "kit-rdrd", "kit.shaft=8", "cam.bore=8",
           'output.formats=["json"]')


@pytest.mark.parametrize("template, sets, field", [
    ("flat-face.toml", ["kit.shaft=3"], "kit"),
    ("kit-crank-rocker.toml", ["kit.bolt=M3"], "kit.bolt"),
    ("crank-rocker.toml", ["kit.bolt=M4", "parts.pin_diameter=5"], "kit.bolt"),
])
def test_kits_refused_where_they_cannot_mount(tmp_path, template, sets, field):
    main = linkgen if "crank" in template else camgen
    args = ["build", str(TEMPLATES / template), "-o", str(tmp_path / "o")]
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 2 and result.stderr.startswith(f"error: {field}: ")
    assert len(result.stderr.strip().splitlines()) == 1 and not (tmp_path / "o").exists()


def test_a_roller_too_small_for_its_axle_is_refused(tmp_path):
    result = CliRunner().invoke(camgen, ["build", str(TEMPLATES / "kit-rdrd.toml"), "-o", str(tmp_path / "o"),
                                         "--set", "follower.roller_radius=3.7", "--set", "kit.bolt=M5"])
    assert result.exit_code == 2
    assert result.stderr.strip() == ("error: kit.bolt: the roller's M5 axle hole (5.5 mm) leaves less than 1 mm of "
                                     "material in a roller of follower.roller_radius 3.7 mm; use a smaller bolt or a "
                                     "roller of at least 3.75 mm radius")
    assert not (tmp_path / "o").exists()
    # at the limit it builds
    _build(camgen, TEMPLATES / "kit-rdrd.toml", tmp_path / "kit-rdrd", "follower.roller_radius=3.75", "kit.bolt=M5",
           'output.formats=["json"]')


def test_pivot_too_close_for_its_standoff_is_refused(tmp_path):
    result = CliRunner().invoke(camgen, ["build", str(TEMPLATES / "kit-oscillating.toml"), "-o", str(tmp_path / "o"),
                                         "--set", "follower.pivot_distance=60", "--set", "follower.arm_length=50"])
    assert result.exit_code == 2 and result.stderr.startswith("error: follower.pivot_distance: ")
    assert not (tmp_path / "o").exists()


@pytest.fixture(scope="module")
def crank_rocker(tmp_path_factory):
    out = tmp_path_factory.mktemp("kit-crank-rocker")
    _build(linkgen, TEMPLATES / "kit-crank-rocker.toml", out, FILES)
    return out, json.loads((out / "kit-crank-rocker.json").read_text())


def test_linkage_bill_of_materials_csv(crank_rocker):
    """A linkage kit's CSV is its report's bom too: the pins and mounting bolts with their standards."""
    out, report = crank_rocker
    rows = _bom_csv(out, report, "kit-crank-rocker")
    bolts = [r for r in rows if r["process"] == "buy" and " x " in r["part"]]
    assert bolts and all(r["standard"] == "ISO 4762; ISO 7089; ISO 4032" for r in bolts)


def test_linkage_base_plate_pivots_and_mounting_holes(crank_rocker):
    out, report = crank_rocker
    msp = ezdxf.readfile(out / "kit-crank-rocker-sheet.dxf").modelspace()
    outlines = []
    for pl in msp.query('LWPOLYLINE[layer=="OUTLINE"]'):
        pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
        outlines.append(shapely.Polygon(Contour(pts[:, :2], pts[:, 2]).flatten(1e-3)))
    circles = [(np.array(c.dxf.center)[:2], 2 * c.dxf.radius) for c in msp.query('CIRCLE[layer=="HOLES"]')]
    base = max(outlines, key=lambda p: p.area)
    inside = [(c, d) for c, d in circles if base.contains(shapely.Point(c))]
    kerf, hole = 0.15, 4.0 + 0.2
    pivots = [c for c, d in inside if abs(d - (hole - kerf)) < 1e-9]
    mounts = [c for c, d in inside if abs(d - (BOLTS["M4"].clearance_hole - kerf)) < 1e-9]
    assert len(pivots) == 2 and len(mounts) == 4
    assert float(np.linalg.norm(pivots[0] - pivots[1])) == pytest.approx(180.0, abs=1e-9)
    # the corners make a rectangle about the pivots' box, square to the ground line
    pivots, mounts = np.array(pivots), np.array(mounts)
    assert np.ptp(mounts[:, 0]) - np.ptp(pivots[:, 0]) == pytest.approx(np.ptp(mounts[:, 1]) - np.ptp(pivots[:, 1]),
                                                                         abs=1e-9)
    kit = report["kit"]
    assert len(kit["pins"]) == 4 and all(p["bolt_length_mm"] == 16.0 for p in kit["pins"])
    assert [h["cut_diameter_mm"] for h in kit["mounting_holes"]] == [pytest.approx(4.35, abs=1e-12)] * 4


def test_linkage_mounting_heads_clear_the_moving_parts_over_the_turn(crank_rocker):
    """The bolt heads on the base plate's corners never meet the crank, coupler or rocker (placed from the report's
    joints over the turn by the four-bar's closed form)."""
    _, report = crank_rocker
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import load_spec as load_linkage

    spec = load_linkage(TEMPLATES / "kit-crank-rocker.toml")
    fb = design_linkage(spec).kinematics
    theta = np.radians(np.arange(0.0, 360.0, 0.5))
    a = np.column_stack([fb.crank * np.cos(theta), fb.crank * np.sin(theta)])
    o4 = np.array([fb.ground, 0.0])
    d = np.linalg.norm(a - o4, axis=1)
    # B: on the circle of the coupler about A and the rocker about O4 (closed form, the template's branch)
    along = (fb.coupler**2 - fb.rocker**2 + d**2) / (2 * d)
    up = np.sqrt(fb.coupler**2 - along**2)
    u = (o4 - a) / d[:, None]
    b = a + along[:, None] * u + up[:, None] * np.column_stack([-u[:, 1], u[:, 0]])
    half = 7.0
    bars = shapely.union_all([shapely.LineString([p, q]).buffer(half) for p, q in itertools.chain(
        zip(np.zeros_like(a), a, strict=True), zip(a, b, strict=True),
        zip(b, np.tile(o4, (len(b), 1)), strict=True))])
    heads = [shapely.Point(h["x_mm"], h["y_mm"]).buffer(BOLTS["M4"].head_diameter / 2) for h in
             report["kit"]["mounting_holes"]]
    assert all(bars.distance(h) > 0 for h in heads)


def test_linkage_kit_3mf_has_every_part(crank_rocker):
    out, report = crank_rocker
    stack = _stack(report)
    parts = {p["name"] for p in report["parts"]}
    assert parts <= set(stack) and set(stack) - parts == {"pin-O2", "pin-A", "pin-B", "pin-O4", *(
        f"mount-head-{k}" for k in range(1, 5))}
    for name in parts:
        assert stack[name][0] == pytest.approx(report["layers"][name] * 4.0, abs=1e-12)
    _no_overlaps(out / "kit-crank-rocker-kit.3mf", stack, report)


def test_spacers_fill_the_layers_a_pin_crosses_and_nothing_meets(tmp_path):
    """single-dwell (a six-bar) needs spacers: one a layer a pin crosses between its parts, in the kit 3MF at the
    first dead centre with no two solids overlapping (manifold3d)."""
    out = tmp_path / "single-dwell"
    _build(linkgen, TEMPLATES / "single-dwell.toml", out, "kit.bolt=M4", "parts.pin_diameter=4.0",
           'output.formats=["json", "3mf"]')
    report = json.loads((out / "single-dwell.json").read_text())
    stack = _stack(report)
    t = report["parts"][0]["thickness_mm"]
    spacers = [name for name in stack if name.startswith("spacer-")]
    assert len(spacers) == round(sum(s["height_mm"] for s in report["spacers"]) / t) == 4
    assert all(stack[name][1] - stack[name][0] == pytest.approx(t) for name in spacers)
    _no_overlaps(out / "single-dwell-kit.3mf", stack, report)


def test_jansen_kit_one_pin_a_pivot_point(tmp_path):
    out = tmp_path / "jansen"
    _build(linkgen, TEMPLATES / "jansen.toml", out, "kit.bolt=M3", 'output.formats=["json", "3mf"]')
    report = json.loads((out / "jansen.json").read_text())
    pins = report["kit"]["pins"]
    assert len(pins) == 7                                         # O, A, B, C, D, E, F
    assert len({(p["x_mm"], p["y_mm"]) for p in pins}) == 7
    made = {s["name"] for s in report["kit"]["stack"] if not s["bought"]}
    assert set(trimesh.load(out / "jansen-kit.3mf").geometry) == made
    assert {p["name"] for p in report["parts"]} <= set(_stack(report))


def test_default_builds_carry_no_kit(tmp_path):
    _build(camgen, TEMPLATES / "rdrd.toml", tmp_path / "rdrd", 'output.formats=["json"]')
    assert "kit" not in json.loads((tmp_path / "rdrd" / "rdrd.json").read_text())


def test_kit_step_holds_every_kit_part_exactly(tmp_path):
    """With "step" asked for, <name>-kit.step holds each kit part as made and the cam (its biarc STEP part) as exact
    solids named after them, as assembled at theta = 0 (re-read with Open CASCADE): each its volume, faces and
    circular edges, its box its outline moved where the kit places it, at the report's stack height; the frame's seat
    round the shaft (0, 0), the roller's and the follower's axle holes at the roller's centre by the closed form
    (e, d0 + s(0)) = (5, sqrt(50^2 - 5^2)) mm; no two boxes coincide, and nothing bought is there."""
    pytest.importorskip("OCP")
    from camgen.profile import step_part
    from camgen.kit import cam_kit
    from tests.core.test_step import assert_apart, assert_placed, holes_at, measure, read_step

    out = tmp_path / "kit-rdrd"
    report = _build(camgen, TEMPLATES / "kit-rdrd.toml", out, 'output.formats=["step", "json"]')
    design = design_cam(load_spec(TEMPLATES / "kit-rdrd.toml"))
    kit = cam_kit(design)
    made = {part.name: part for part, _ in kit.made}
    solids = read_step(out / "kit-rdrd-kit.step")
    assert [n for n, _ in solids] == ["frame", "spacer", "standoff-1", "standoff-2", "kit-rdrd", "roller", "follower"]
    stack = _stack(report)
    for name, shape in solids:
        part = step_part(design)[0] if name == "kit-rdrd" else made[name.partition("-")[0]]
        solid = next(s for s in kit.solids if s.name == name)
        angle, (x, y) = solid.pose(0)
        assert_placed(measure(shape), part, angle, (x, y, stack[name][0]))
    shapes = dict(solids)
    axle = made["roller"].holes[0].radius
    centre = np.array([[5.0, math.sqrt(50.0**2 - 5.0**2)]])
    assert holes_at(shapes["roller"], axle) == pytest.approx(centre, abs=1e-9)
    # the follower's axle hole there (its slot's two ends are arcs of that radius too)
    assert np.abs(holes_at(shapes["follower"], made["follower"].holes[0].radius) - centre).max(axis=1).min() <= 1e-9
    assert holes_at(shapes["frame"], made["frame"].holes[0].radius) == pytest.approx(np.zeros((1, 2)), abs=1e-9)
    assert_apart(measure(shape)["box"] for _, shape in solids)


def test_a_linkage_kits_printed_parts_keep_the_elephant_foot():
    """The kit's build of a linkage (its ground made the base plate) chamfers its printed parts' bed faces by
    output.elephant_foot as the plain build does: the moving links' meshes are those of the mechanism's layout built
    without the base plate, vertex for vertex, and their bed faces are inset (the lowest vertices' ring is smaller
    than the next one up)."""
    from camgen.core.solids import extrude
    from linkgen.linkage_design import design_linkage
    from linkgen.parts import build_parts
    from linkgen.spec import load_spec as load_linkage

    design = design_linkage(load_linkage(ROOT / "templates" / "kit-crank-rocker.toml",
                                         ["output.elephant_foot=0.3"]), parts=True)
    spec = design.spec
    kit = design.kit
    assert kit.build is design.build and kit.build.allowances.elephant_foot == 0.3
    layout = design.mechanism.layout(spec.linkage, design.kinematics, spec.parts)
    plain = {p.name: p for p in build_parts(layout, spec.parts, 0.3).printed}
    for part in kit.build.printed:
        if part.name == "ground":                 # the base plate: the ground grown to carry the mounting holes
            continue
        mesh, reference = extrude(part), extrude(plain[part.name])
        assert np.array_equal(mesh.vertices, reference.vertices)
        bed = mesh.vertices[:, 2] == 0.0
        assert np.ptp(mesh.vertices[bed, 0]) == pytest.approx(np.ptp(mesh.vertices[~bed, 0]) - 0.6,
                                                            abs=spec.parts.tolerance)


def test_a_linkage_kit_is_built_once_and_routed_with_its_mounting_holes(tmp_path, monkeypatch):
    """kit-crank-rocker with a 2.2 mm router: the parts are laid out, nested and built once for the whole command
    (layout, nest and build_parts each called once), and the report's routing block is of the parts as made: the
    base plate's four mounting holes (ISO 273 medium, 4.5 mm less the 0.15 mm kerf: radius 2.175 mm) fail beside its
    two pivot holes (4.2 - 0.15 mm: radius 2.025 mm), at the report's mounting-hole centres."""
    from linkgen import linkage_design
    from linkgen import parts as linkage_parts
    from linkgen.mechanisms.fourbar import FourBarMechanism

    calls: dict[str, int] = {}

    def counted(owner, name):
        real = getattr(owner, name)

        def call(*args, **kwargs):
            calls[name] = calls.get(name, 0) + 1
            return real(*args, **kwargs)

        monkeypatch.setattr(owner, name, call)

    counted(linkage_design, "build_parts")
    counted(linkage_parts, "nest")
    counted(FourBarMechanism, "layout")
    out = tmp_path / "kit-crank-rocker"
    report = _build(linkgen, TEMPLATES / "kit-crank-rocker.toml", out, 'output.formats=["json", "3mf"]',
                    "output.tool_radius=2.2")
    assert calls == {"build_parts": 1, "nest": 1, "layout": 1}
    routing = report["routing"]
    assert routing["smallest_concave_radius_mm"]["ground"] == pytest.approx((4.2 - 0.15) / 2, abs=1e-9)
    holes = [(f["x_mm"], f["y_mm"], f["radius_mm"]) for f in routing["fails"]
             if f["part"] == "ground" and f["what"] == "hole"]
    mounts = [(m["x_mm"], m["y_mm"]) for m in report["kit"]["mounting_holes"]]
    assert len(mounts) == 4
    expected = [(0.0, 0.0, 2.025), (180.0, 0.0, 2.025)] + [(x, y, 2.175) for x, y in mounts]
    assert np.array(sorted(holes)) == pytest.approx(np.array(sorted(expected)), abs=1e-6)    # report: 6 decimals
