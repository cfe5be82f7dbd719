"""A translating follower's stem, roller and guide rails as parts of the machine's kit (issue 35 item 4,
:mod:`camgen.kinds.machine.stem_kit`), and a coupled four-bar's crank left out (the follower's arm is it).

The lifter (a disc cam lifting a roller stem that drives a slider-crank, ``tests/support/stem_slider_crank.py``) in a
one-plate frame, built through the installed command with every file a machine writes, checked against numbers found
here independently: the roller's centre at rest 48 mm over the camshaft (base 40 + roller 8); the lift the cycloidal
rise's closed form s = h (u - sin(2 pi u) / 2 pi) after the cam's phase; the stem 8 mm wide (the linkage's parts)
and 2 x 30 + 8 = 68 mm long; each rail 0.2 mm clear of it and 3 mm wide from 1 mm over the roller's top at the top
of the stroke (48 + 30 + 8 + 1 = 87 mm) to the stem's top at the bottom (48 + 68 = 116 mm), its lugs 7.4 mm square
(the M3 clearance hole 3.4 mm, 2 mm of wall each side) at its ends. The files are read back by ezdxf, admesh,
PrusaSlicer and FreeCAD.
"""
from __future__ import annotations

import csv
import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from tests.camgen.kinds.machine.test_slider_coupling import TEMPLATE
from tests.conftest import ROOT

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-stem-kit")

#: the assembly's angle (degrees of the main shaft): in the rise (the cam's phase is 30 degrees)
ANGLE = 100.0
FRAMED = TEMPLATE.replace('rpm = 30.0\n', f'rpm = 30.0\nframe = "one"\nassembly_angle = {ANGLE}\n', 1).replace(
    'formats = ["dxf", "stl", "json"]', 'formats = ["dxf", "stl", "3mf", "step", "json"]', 1)
REST_Y, WIDTH, LENGTH, THICK = 48.0, 8.0, 68.0, 6.0
M4_HOLE, M3_HOLE = 4.5, 3.4
#: the guide screws (mm, the machine's frame): x = +-(4 + 0.2 + 3 + 7.4 / 2), y = 87 + 3.7 and 116 - 3.7
SCREWS = sorted((k * 10.9, y) for k in (-1.0, 1.0) for y in (90.7, 112.3))
#: a 3MF's coordinates are 32-bit floats: half their spacing at 128 to 256 mm is 7.6e-6 mm
F32 = 2e-5


def _lift(phi_deg: float) -> float:
    """The follower's lift (mm) at main shaft angle ``phi_deg``, within the 120 degree cycloidal rise of 30 mm."""
    u = (phi_deg - 30.0) / 120.0
    assert 0.0 <= u <= 1.0
    return 30.0 * (u - math.sin(2 * math.pi * u) / (2 * math.pi))


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> tuple[Path, dict]:
    """The framed lifter built by ``camgen build`` with every file: (its folder, its report)."""
    folder = tmp_path_factory.mktemp("lifter")
    path = folder / "lifter.toml"
    path.write_text(FRAMED)
    result = CliRunner().invoke(camgen, ["build", str(path), "-o", str(folder / "out")])
    assert result.exit_code == 0, result.output
    out = folder / "out"
    return out, json.loads((out / "lifter.json").read_text())


@pytest.fixture(scope="module")
def design():
    from camgen import api

    return api.design(api.validate(tomllib.loads(FRAMED)))


def _dxf(path: Path):
    """A part's DXF read back by ezdxf (its audit clean): its outline (a Contour) and its holes (centre, diameter)."""
    import ezdxf

    from camgen.core.shapes import Contour

    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors, path.name
    msp = doc.modelspace()
    (outline,) = msp.query("LWPOLYLINE[layer=='OUTLINE']")
    points = np.array([(p[0], p[1], p[4]) for p in outline.get_points("xyseb")])
    holes = [((h.dxf.center.x, h.dxf.center.y), 2 * h.dxf.radius) for h in msp.query("CIRCLE")]
    return Contour(points[:, :2], points[:, 2]), holes


def test_the_stem_is_its_clash_body_with_the_axle_and_slider_joint_hole(built, design):
    """The stem's DXF: its outline, split into chords at the cam's tolerance, is the clash check's stem body to
    1e-9 mm (8 mm wide, 68 mm from the roller's centre up, a round foot of 4 mm about it); its one hole (the roller's
    axle, an M4 clearance hole, and the slider's pin, 3 mm: the larger kept) is at the roller's centre, which is the
    slider joint C of the linkage at every angle (the linkage's own solution, less the lift) to 1e-9 mm."""
    out, _ = built
    outline, holes = _dxf(out / "lifter-lift-stem.dxf")
    body = next(b for b in design.bodies if b.name == "cams.lift.stem")
    tol = float(design.cam("lift").design.tolerance)
    flat = outline.flatten(tol)
    assert flat.shape == body.outline.shape and np.abs(flat - body.outline).max() <= 1e-9
    x0, y0, x1, y1 = outline.bounds()
    assert (x0, y0, x1, y1) == pytest.approx((-WIDTH / 2, -WIDTH / 2, WIDTH / 2, LENGTH), abs=1e-9)
    ((centre, d),) = holes
    assert np.abs(centre).max() <= 1e-9 and d == pytest.approx(M4_HOLE, abs=1e-12)
    m = design.slid[0]
    lift = np.column_stack([np.zeros(len(design.phi)), m.lift[0]])
    assert np.abs(m.points["C"] - lift - (np.array(centre) + np.array([0.0, REST_Y]))).max() <= 1e-9


def test_a_knife_stem_has_the_slider_joint_hole_alone():
    """A knife edge (no roller, no axle): the stem's one hole is the slider's pin's (M3 clearance, 3.4 mm) at the
    knife's edge, its round foot about it."""
    from camgen import api
    from camgen.kinds.machine.stem_kit import stem_parts

    text = FRAMED.replace('type = "translating-roller"\nroller_radius = 8.0\n', 'type = "knife-edge"\n', 1)
    parts = {p.plate.name: p.plate for p in stem_parts(api.design(api.validate(tomllib.loads(text))))}
    assert sorted(parts) == ["lift-guide-left", "lift-guide-right", "lift-stem"]
    ((centre, d),) = parts["lift-stem"].holes
    assert np.abs(centre).max() <= 1e-9 and d == pytest.approx(M3_HOLE, abs=1e-12)
    assert parts["lift-stem"].outline.bounds()[1] == pytest.approx(-WIDTH / 2, abs=1e-12)


def test_the_rails_lugs_line_up_with_the_frames_holes(built):
    """Each rail's DXF has two M3 clearance holes, in its lugs, at the screws' places found here; the frame's DXF
    has a hole at each of them (to 1e-9 mm) of the same size; the rails as the rules place them: 3 mm wide,
    0.2 mm clear of the stem, from 87 to 116 mm, the lugs 7.4 mm out."""
    out, report = built
    found = []
    for side, k in (("left", -1.0), ("right", 1.0)):
        outline, holes = _dxf(out / f"lifter-lift-guide-{side}.dxf")
        x0, y0, x1, y1 = outline.bounds()
        inner, outer = 4.2, 4.2 + 3.0 + 7.4
        assert (x0, x1) == pytest.approx(tuple(sorted((k * inner, k * outer))), abs=1e-9)
        assert (y0, y1) == pytest.approx((87.0, 116.0), abs=1e-9)
        assert len(holes) == 2 and all(d == pytest.approx(M3_HOLE, abs=1e-12) for _, d in holes)
        found += [c for c, _ in holes]                     # the rail's frame: the stem's axis x = 0, the machine's y
    assert np.abs(np.array(sorted(found)) - np.array(SCREWS)).max() <= 1e-9
    _, frame_holes = _dxf(out / "lifter-frame.dxf")
    for screw in SCREWS:
        centre, d = min(frame_holes, key=lambda h: math.dist(h[0], screw))
        assert math.dist(centre, screw) <= 1e-9 and d == pytest.approx(M3_HOLE, abs=1e-12)
    seats = {s["name"]: s for s in report["frame"]["seats"]}
    assert sorted((s["x_mm"], s["y_mm"]) for s in seats.values() if s["carries_mm"] == 3.0
                  and (s["x_mm"], s["y_mm"]) != (50.0, 108.0)) == pytest.approx(SCREWS, abs=1e-9)


def test_the_kit_makes_the_stem_roller_and_rails_and_buys_the_axle_and_screws(built):
    """The kit: the stem, its roller and both rails made (their own files); the roller's M4 axle and the four M3
    guide screws bought, each long enough for what it passes (the rails stand on the plate's top, 6 mm, up to the
    stem's plane's top) with a washer and a nut; every bought line a bought piece of the assembly."""
    from camgen.core.hardware import BOLTS

    out, report = built
    rows = list(csv.DictReader((out / "lifter-kit.csv").open()))
    made = {r["part"] for r in rows if r["process"] != "buy"}
    assert {"lift-stem", "lift-roller", "lift-guide-left", "lift-guide-right"} <= made
    for name in ("lift-stem", "lift-roller", "lift-guide-left", "lift-guide-right"):
        assert (out / f"lifter-{name}.dxf").exists() and (out / f"lifter-{name}.stl").exists()
    pieces = {p["name"]: p for p in report["assembly"]["pieces"]}
    screws = [r for r in rows if "guide screw" in r["size"]]
    assert len(screws) == 4 and all(r["part"].startswith("M3 x ") for r in screws)
    m3 = BOLTS["M3"]
    for row in screws:
        pin = row["size"].split()[2]
        assert pieces[pin]["bought"]
        assert float(row["part"].split(" x ")[1].split()[0]) >= pieces[pin]["thickness_mm"] + m3.washer_thickness \
            + m3.nut_height
    rail = pieces["cams.lift.guide.left"]
    assert rail["z_mm"] == pytest.approx(THICK, abs=1e-12)              # on the plate's top face
    stem = pieces["cams.lift.stem"]
    assert rail["z_mm"] + rail["thickness_mm"] == pytest.approx(stem["z_mm"] + stem["thickness_mm"], abs=1e-12)
    (axle,) = [r for r in rows if "roller axle" in r["size"]]
    assert axle["part"].startswith("M4 x ") and pieces["cams.lift.axle"]["bought"]
    roller = pieces["cams.lift.roller"]
    assert pieces["cams.lift.axle"]["z_mm"] == pytest.approx(roller["z_mm"], abs=1e-12)
    assert pieces["cams.lift.axle"]["z_mm"] + pieces["cams.lift.axle"]["thickness_mm"] == pytest.approx(
        stem["z_mm"] + stem["thickness_mm"], abs=1e-12)
    assert report["clashes"] == [] and report["clash_check"]["not_checked"] == []


def test_the_assembly_reads_back_with_the_stem_at_its_lift(built):
    """The assembly at 100 degrees: in its 3MF (PrusaSlicer reads it, every object closed) and its STEP (FreeCAD:
    one valid solid a piece) the stem stands 8 mm wide on x = 0, its top at 48 + s + 68 mm (s the cycloid's closed
    form at 100 degrees), from 14 to 20 mm high (the plate 6, a 1 mm gap, the cam 6, a 1 mm gap); the rails from the
    plate's top; the stem's STL closed for admesh, its volume the stem's area (the foot's half disc, less the
    axle hole) times 6 mm to 0.1 %."""
    from tests.camgen.kinds.machine.test_machine_files_read_back import _admesh, _info, _objects
    from tests.support.freecad import freecad_solids

    out, report = built
    top = REST_Y + _lift(ANGLE) + LENGTH
    meshes, _ = _objects(out / "lifter-assembly.3mf")
    v = meshes["cams.lift.stem"][0]
    assert v[:, 1].max() == pytest.approx(top, abs=F32)
    assert (v[:, 0].min(), v[:, 0].max()) == pytest.approx((-WIDTH / 2, WIDTH / 2), abs=F32)
    assert (v[:, 2].min(), v[:, 2].max()) == pytest.approx((14.0, 20.0), abs=F32)
    rail = meshes["cams.lift.guide.right"][0]
    assert (rail[:, 2].min(), rail[:, 2].max()) == pytest.approx((THICK, 20.0), abs=F32)
    info = _info([out / "lifter-assembly.3mf"])["lifter-assembly.3mf"]
    assert len(info) == len(meshes) and all(f["manifold"] == 1.0 for f in info)
    pieces = report["assembly"]["pieces"]
    solids = freecad_solids([out / "lifter-assembly.step"])[str(out / "lifter-assembly.step")]
    assert len(solids) == len(pieces) and all(s["valid"] for s in solids)
    (stem,) = [s for s, p in zip(solids, pieces, strict=True) if p["name"] == "cams.lift.stem"]
    assert stem["box"] == pytest.approx([-WIDTH / 2, top - LENGTH - WIDTH / 2, 14.0, WIDTH / 2, top, 20.0],
                                        abs=0.01)
    found = _admesh(out / "lifter-lift-stem.stl")
    area = WIDTH * LENGTH + math.pi * (WIDTH / 2) ** 2 / 2 - math.pi * (M4_HOLE / 2) ** 2
    assert found["volume"] == pytest.approx(area * THICK, rel=1e-3)


def test_a_coupled_four_bars_crank_and_ground_are_not_in_the_machines_files(tmp_path):
    """The automaton's four-bar "arm-bars" is driven by the arm of cams.arm, which carries its crank pin, and its
    fixed pivots stand in the frame's plates: the machine writes its coupler and rocker but no crank and no ground
    (no file, not on its cut sheet, which ezdxf reads back with the two others' labels), and the arm carries the
    crank pin's hole."""
    import ezdxf

    from camgen import api
    from camgen.core.writers.dxf import write_dxf
    from camgen.kinds.machine.outputs import machine_bundle

    design = api.design(api.load(ROOT / "templates" / "automaton.toml", ['output.formats=["dxf", "stl"]']))
    bundle, _ = machine_bundle(design)
    names = {e.name for it in bundle.items for e in it.entries}
    assert {"automaton-arm-bars-coupler.stl", "automaton-arm-bars-rocker.stl"} <= names
    assert not [n for n in names if "crank" in n or "ground" in n]
    (sheet,) = [it for it in bundle.items for e in it.entries if e.name == "automaton-arm-bars-sheet.dxf"]
    write_dxf(sheet.payload, tmp_path / "sheet.dxf")
    msp = ezdxf.readfile(tmp_path / "sheet.dxf").modelspace()
    labels = sorted(t.dxf.text for t in msp.query("TEXT"))
    outlines = msp.query("LWPOLYLINE[layer=='OUTLINE']")
    assert labels == ["coupler", "rocker"] and len(outlines) == 2
    assert {"crank", "ground"} <= {p.name for p in design.linkages[0].design.build.cut}   # the design knows them


def test_the_stem_carries_the_slider_block_and_the_frame_the_ground(built, design):
    """The framed lifter's slider-crank: its slider "stem" slides on the ground and the follower's stem carries its
    joint, and its fixed pivot O stands in the frame's plate, so the machine writes its crank and rod only (the
    linkage's own written report, and no file named for the block or the ground); the design still knows both."""
    out, report = built
    own = json.loads((out / report["files"]["rocker.json"]).read_text())
    assert [p["name"] for p in own["parts"]] == ["crank", "rod"]
    assert not [n for n in report["files"].values() if n.startswith("lifter-rocker-") and
                ("stem" in n or "ground" in n)]
    [rocker] = design.slid
    assert rocker.ground_slider.name == "stem"
    assert {"stem", "ground"} <= {p.name for p in rocker.design.build.cut}
    from camgen.kinds.machine.framekit import bom

    made = {line.item for line in bom(design.frame, design) if line.source != "buy"}
    assert {"rocker-crank", "rocker-rod"} <= made and not {"rocker-stem", "rocker-ground"} & made
