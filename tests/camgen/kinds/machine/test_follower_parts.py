"""A machine's cam followers' arms and rollers as parts of their own (issue 35 item 4): each oscillating follower's
arm and roller written as cut files (read back by ezdxf) whose outline is the assembly's piece and whose holes are
at the pivot, the roller's centre and a coupled crank's pin, found here independently; the kit listing each arm
and roller made and each axle bought.

The pivot is the circle intersection the follower's definition gives (``pivot_distance`` C from the cam's centre,
``arm_length`` L from the roller at rest at (0, R_p), R_p = base radius + roller radius, on the +X side); the
roller's centre is the cam's own pitch point turned by the cam's angle (:func:`camgen.kit.roller_centres`, the
single cam's kit), not the machine's swing of the arm.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from camgen import api
from tests.conftest import ROOT

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-follower-parts")

#: the bundled machines with oscillating roller followers: three arms on one pivot and a coupled four-bar's crank
#: pin (automaton), a four-bar's crank pin 30 mm out (keep-time), a bell crank (pick-and-place)
MACHINES = ("automaton", "keep-time", "pick-and-place")
#: ISO 273 medium clearance hole of an M4 bolt (mm): the axle's and the 4 mm pivot pins' holes
M4_HOLE = 4.5


@pytest.fixture(scope="module")
def designs():
    """Each of :data:`MACHINES` designed once (about 1 s each), with no kerf so that the cut outline is the
    nominal one."""
    return {name: api.design(api.load(ROOT / "templates" / f"{name}.toml", ["output.kerf=0"]))
            for name in MACHINES}


def _oscillating(design):
    from camgen.followers.oscillating_roller import OscillatingRoller
    from camgen.kinds.machine.design import _cam_of

    return [(cam, mount) for cam, mount in zip(design.cams, design.spec.cams, strict=True)
            if isinstance(_cam_of(cam.design).follower, OscillatingRoller)]


def _pivot_and_roller(design, cam, mount):
    """The follower's pivot and roller centre (mm, the machine's frame) at ``machine.assembly_angle``, found
    independently of the machine's arm (see the module's docstring)."""
    from camgen.kinds.machine.kinematics import program_angles
    from camgen.kit import roller_centres

    spec = cam.design.spec
    c, arm = spec.follower.pivot_distance, spec.follower.arm_length
    rp = spec.cam.base_radius + spec.follower.roller_radius
    y = (c**2 - arm**2 + rp**2) / (2 * rp)
    shaft = np.asarray(next(s.at for s in design.spec.shafts if s.name == mount.shaft), float)
    pivot = shaft + np.array([math.sqrt(c**2 - y**2), y])
    theta = program_angles(np.array([math.radians(design.spec.machine.assembly_angle)]), cam.turns,
                           math.radians(mount.phase))
    return pivot, shaft + roller_centres(cam.design, theta)[0]


def _dxf(item, folder: Path):
    """The item's DXF written and read back by ezdxf: its outline's vertices and bulges, its holes' centres and
    diameters (mm, the part's own frame)."""
    import ezdxf

    from camgen.core.writers.dxf import write_dxf

    (entry,) = [e for e in item.entries if e.format == "dxf"]
    path = folder / entry.name
    write_dxf(item.payload, path)
    msp = ezdxf.readfile(path).modelspace()
    (outline,) = msp.query("LWPOLYLINE[layer=='OUTLINE']")
    points = np.array([(p[0], p[1], p[4]) for p in outline.get_points("xyseb")])
    holes = [(np.array([h.dxf.center.x, h.dxf.center.y]), 2 * h.dxf.radius) for h in msp.query("CIRCLE")]
    return entry.name, points[:, :2], points[:, 2], holes


def _frame_of(pivot: np.ndarray, roller: np.ndarray):
    """Part frame -> machine frame: the arm's origin at the pivot, its +X towards the roller's centre."""
    u = (roller - pivot) / np.linalg.norm(roller - pivot)
    m = np.array([[u[0], -u[1]], [u[1], u[0]]])
    return lambda p: np.asarray(p) @ m.T + pivot


@pytest.mark.parametrize("name", MACHINES)
def test_each_arm_is_the_assembly_arm_with_holes_at_its_pivot_roller_and_crank_pin(designs, name, tmp_path):
    """Each arm's DXF: its outline, placed at the pivot towards the roller, has its round ends about the pivot and
    the roller's centre, of half the roller's radius (a grooved cam's follower's: grown by half its running
    clearance), and is the assembly's arm piece (its chords at the cam's tolerance) to 1e-6 mm; its holes are at
    the pivot and the roller's centre (and a coupled four-bar's crank pin, ``crank`` mm out along the arm) to 1e-9
    mm, each an M4 clearance hole; the roller's DXF is a circle of the roller's radius about its axle hole, the
    assembly's roller piece on that circle."""
    from camgen.core.shapes import Contour
    from camgen.kinds.machine import assembly
    from camgen.kinds.machine.follower_parts import follower_items

    design = designs[name]
    pieces = {p.part.name: p.part for p in assembly.pieces(design)}
    items = [i for i in follower_items(design, ("dxf",)) if i is not None]
    by_name = {i.entries[0].name.removesuffix(".dxf"): i for i in items}
    cams = _oscillating(design)
    assert cams and len(items) == 2 * len(cams)
    for cam, mount in cams:
        pivot, roller = _pivot_and_roller(design, cam, mount)
        spec, tol = cam.design.spec, float(cam.design.tolerance)
        assert math.dist(pivot, roller) == pytest.approx(spec.follower.arm_length, abs=1e-9)
        to_machine = _frame_of(pivot, roller)
        file, vertices, bulges, holes = _dxf(by_name[f"{name}-{cam.name}-arm"], tmp_path)
        outline = Contour(vertices, bulges)
        _, centres, radii, _ = outline.arcs()                # its two round ends: about the pivot and the roller
        ends = to_machine(np.asarray(centres))
        assert len(ends) == 2 and min(math.dist(ends[0], pivot) + math.dist(ends[1], roller),
                                      math.dist(ends[1], pivot) + math.dist(ends[0], roller)) <= 1e-9, file
        grown = getattr(spec.cam, "running_clearance", 0.0) / 2       # a grooved cam's follower
        assert np.asarray(radii) == pytest.approx((spec.follower.roller_radius + grown) / 2, abs=1e-12), file
        placed = to_machine(outline.flatten(tol))
        piece = pieces[f"cams.{cam.name}.arm"].outline
        assert piece.n_arcs == 0 and placed.shape == piece.vertices.shape, file
        assert np.abs(placed - piece.vertices).max() <= 1e-6, file
        expected = [pivot, roller]
        coupled = [m for m in design.linkages if m.cam == cam.name]
        for m in coupled:
            expected.append(pivot + m.fourbar.crank * (roller - pivot) / np.linalg.norm(roller - pivot))
        found = sorted((to_machine(c).tolist(), d) for c, d in holes)
        assert len(found) == len(expected), file
        for centre in expected:
            nearest = min(found, key=lambda h: math.dist(h[0], centre))
            assert math.dist(nearest[0], centre) <= 1e-9, (file, centre)
            assert nearest[1] == pytest.approx(M4_HOLE, abs=1e-12), file
        file, vertices, bulges, holes = _dxf(by_name[f"{name}-{cam.name}-roller"], tmp_path)
        r = spec.follower.roller_radius
        assert np.abs(np.hypot(*vertices.T) - r).max() <= 1e-12 and np.abs(bulges).tolist() == [1.0, 1.0], file
        ((centre, d),) = holes
        assert np.abs(centre).max() <= 1e-12 and d == pytest.approx(M4_HOLE, abs=1e-12), file
        ring = pieces[f"cams.{cam.name}.roller"]
        assert np.abs(np.hypot(*(ring.outline.vertices - roller).T) - r).max() <= 1e-6, file
        (hole,) = ring.holes
        assert math.dist(hole.centre, roller) <= 1e-9 and 2 * hole.radius == pytest.approx(M4_HOLE, abs=1e-12)


def test_the_kit_lists_each_arm_and_roller_made_and_each_axle_bought(designs):
    """The automaton's kit (a frame of two plates): besides the frame's, the cams' and the four-bar's
    coupler and rocker lines, one line per arm and per roller
    (made, its own files, as thick as the assembly's piece) and one bought M4 bolt per roller's axle, long enough
    for the roller, the gap and the arm it goes through with a washer, a nut and a thread proud of it; the
    assembly holds each axle as a bought piece at its roller's centre."""
    from camgen.core.hardware import BOLTS
    from camgen.kinds.machine import assembly
    from camgen.kinds.machine.framekit import bom

    design = designs["automaton"]
    lines = bom(design.frame, design)
    cams = [cam.name for cam, _ in _oscillating(design)]
    assert cams == ["head", "jaw", "arm"]
    pieces = {p.part.name: p for p in assembly.pieces(design)}
    made = {line.item: line for line in lines if line.source != "buy"}
    assert set(made) == ({"frame", "frame-top", "spacer-0", *cams, "arm-bars-coupler", "arm-bars-rocker"}
                         | {f"{c}-{p}" for c in cams for p in ("arm", "roller")})   # the cams, the four-bar's two
    for c in cams:
        for part in ("arm", "roller"):
            thick = pieces[f"cams.{c}.{part}"].part.thickness
            assert made[f"{c}-{part}"].size.startswith(f"{'follower arm' if part == 'arm' else 'roller'} of "
                                                        f"cams.{c}, {thick:g} mm,")
    axles = [line for line in lines if line.source == "buy" and "roller axle" in line.size]
    assert len(axles) == len(cams)
    m4 = BOLTS["M4"]
    for c, line in zip(cams, axles, strict=True):
        axle = pieces[f"cams.{c}.axle"]
        assert axle.bought and f"cams.{c}.axle" in line.size
        roller, arm = pieces[f"cams.{c}.roller"], pieces[f"cams.{c}.arm"]
        assert axle.z == pytest.approx(roller.z, abs=1e-12)
        assert axle.z + axle.part.thickness == pytest.approx(arm.z + arm.part.thickness, abs=1e-12)
        length = float(line.item.split(" x ")[1].split()[0])
        assert line.item.startswith("M4 x ")
        assert length >= axle.part.thickness + m4.washer_thickness + m4.nut_height + 1.0
        x0, y0, x1, y1 = axle.part.outline.bounds()
        centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
        _, roller_centre = _pivot_and_roller(design, *next((k, m) for k, m in _oscillating(design) if k.name == c))
        assert math.dist(centre, roller_centre) <= 1e-9 and x1 - x0 == pytest.approx(4.0, abs=1e-9)
    bought = [line for line in lines if line.source == "buy"]
    assert len(bought) == 1 + 2 + len(cams)               # the camshaft, two pivot pins, the axles
