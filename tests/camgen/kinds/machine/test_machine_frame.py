"""The machine's frame (issue 35 item 4): its holes read back from the DXF at the shafts' and pivots' positions
(worked here from the template: a follower's pivot at pivot_distance from its shaft, its roller at rest where the
circle of the prime radius meets the arm's circle, the rocker's pivot a ground link from the arm's pivot at the
coupling's rest angle), their diameters the seats' with the kerf and the clearance, every seat inside the plate
by the margin, the spacers in the clash check, the bill of materials, the refusals."""
from __future__ import annotations

import copy
import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core.hardware import BOLTS, RUNNING_PLAY
from tests.support.refusals import assert_refused
from tests.camgen.kinds.machine.test_machine import AUTOMATON, _design, _raw, _write

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-machine-frame")

KERF, CLEARANCE = 0.2, 0.3


def _circles(p0, r0, p1, r1) -> list[np.ndarray]:
    """The two points where circle (p0, r0) meets circle (p1, r1)."""
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    d = float(np.linalg.norm(p1 - p0))
    a = (r0**2 - r1**2 + d**2) / (2 * d)
    h = math.sqrt(r0**2 - a**2)
    u = (p1 - p0) / d
    mid = p0 + a * u
    return [mid + h * np.array([-u[1], u[0]]), mid - h * np.array([-u[1], u[0]])]


def _expected_centres(raw: dict) -> dict[str, tuple[float, float]]:
    """The shaft's, the followers' pivot's and the rocker's pivot's centres (mm), worked from the template alone."""
    shaft = np.array(raw["shafts"][0]["at"], float)
    arm = next(c for c in raw["cams"] if c["name"] == "arm")["template"]
    follower, cam = arm["follower"], arm["cam"]
    # the pivot: pivot_distance from the shaft, arm_length from the roller at rest on the cam's +y axis (the cam's
    # angle zero), the roller at rest base radius + roller radius from the shaft; on the +x side
    prime = cam["base_radius"] + follower["roller_radius"]
    roller = shaft + np.array([0.0, prime])
    pivot = max(_circles(shaft, follower["pivot_distance"], roller, follower["arm_length"]), key=lambda p: p[0])
    bars = raw["linkages"][0]["template"]["linkage"]
    rest = math.radians(raw["couplings"][0]["rest"])
    towards = math.atan2(*(roller - pivot)[::-1])
    # the crank (the arm) makes the rest angle with the ground line; this follower swings clockwise (its swing
    # sign -1), so the four-bar is drawn mirrored and the ground line lies the rest angle counter-clockwise on
    ground = towards + rest
    rocker = pivot + bars["ground"] * np.array([math.cos(ground), math.sin(ground)])
    return {"shaft": tuple(shaft), "pivot": tuple(pivot), "rocker": tuple(rocker)}


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("frame")
    result = CliRunner().invoke(camgen, ["build", str(AUTOMATON), "-o", str(out), "--set", f"output.kerf={KERF}",
                                         "--set", f"output.clearance={CLEARANCE}", "--set",
                                         'output.formats=["dxf", "cut-svg", "stl", "3mf", "json"]'])
    assert result.exit_code == 0, result.output
    return out, json.loads((out / "automaton.json").read_text())


def _dxf_circles(path: Path) -> list[tuple[float, float, float]]:
    import ezdxf

    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    return [(c.dxf.center.x, c.dxf.center.y, c.dxf.radius) for c in doc.modelspace().query("CIRCLE")
            if c.dxf.layer == "HOLES"]


def test_the_pivots_worked_from_the_template_are_the_swing_sign_the_design_uses(automaton):
    follower = automaton.cam("arm").design.cam.follower
    assert follower._swing_sign == -1.0                     # the mirrored four-bar _expected_centres assumes
    assert np.linalg.norm(follower.pivot) == pytest.approx(110.0, abs=1e-12)


@pytest.fixture(scope="module")
def automaton():
    return _design(_raw())


def test_every_hole_is_at_its_shaft_or_pivot_read_back_from_the_dxf(built):
    out, report = built
    want = _expected_centres(_raw())
    bottom = _dxf_circles(out / "automaton-frame.dxf")
    top = _dxf_circles(out / "automaton-frame-top.dxf")
    # the bottom plate carries the camshaft and the followers' pivot pin; the top one the rocker's pivot (hanging)
    # and the followers' pivot pin again, through the spacer standing on it
    for circles, names in ((bottom, ("shaft", "pivot")), (top, ("rocker", "pivot"))):
        assert len(circles) == len(names)
        for (x, y, _), name in zip(sorted(circles), sorted(names, key=lambda n: want[n][0]), strict=True):
            assert (x, y) == pytest.approx(want[name], abs=1e-9), name
    assert report["frame"]["plates"] == ["frame", "frame-top"]


def test_hole_diameters_are_the_seats_with_the_allowances(built, automaton):
    out, report = built
    shaft = 8.0 + RUNNING_PLAY                             # cam.bore 8, a plain hole the shaft runs in
    pin = BOLTS["M4"].clearance_hole                       # ISO 273 medium for the 4 mm pins
    radii = sorted(r for _, _, r in _dxf_circles(out / "automaton-frame.dxf"))
    assert radii == pytest.approx(sorted([(shaft - KERF) / 2, (pin - KERF) / 2]), abs=1e-9)
    seats = {s["name"]: s for s in report["frame"]["seats"]}
    assert seats["shafts.camshaft"]["cut_mm"] == pytest.approx(shaft - KERF, abs=1e-9)
    assert seats["shafts.camshaft"]["printed_mm"] == pytest.approx(shaft + CLEARANCE, abs=1e-9)
    # the printed plate: its holes opened by the clearance, its volume the plan area x thickness
    import trimesh

    mesh = trimesh.load(out / "automaton-frame.stl")
    plate = automaton.frame.plate
    outline = shapely.Polygon(plate.outline.flatten(1e-4))
    area = outline.area - math.pi * ((shaft + CLEARANCE) ** 2 + (pin + CLEARANCE) ** 2) / 4
    assert mesh.volume == pytest.approx(area * plate.thickness, rel=2e-4)


def test_every_seat_is_inside_the_plate_by_the_margin(built, automaton):
    out, report = built
    import ezdxf
    from ezdxf import path as dxfpath

    doc = ezdxf.readfile(out / "automaton-frame.dxf")
    outline = next(e for e in doc.modelspace() if e.dxf.layer == "OUTLINE")
    ring = np.array([(v.x, v.y) for v in dxfpath.make_path(outline).flattening(1e-4)])
    plate = shapely.Polygon(ring)
    margin = automaton.spec.machine.frame_margin + KERF / 2    # the cut outline grows by half the kerf
    gaps = [plate.exterior.distance(shapely.Point(s["x_mm"], s["y_mm"])) for s in report["frame"]["seats"]]
    assert all(plate.contains(shapely.Point(s["x_mm"], s["y_mm"])) for s in report["frame"]["seats"])
    assert min(gaps) == pytest.approx(margin, abs=1e-3)       # a hull's corner: the margin exactly
    assert all(g >= margin - 1e-3 for g in gaps)


def test_the_clash_check_includes_the_spacers(automaton):
    """A second shaft geared 1:1 to the camshaft, carrying a cam on the spacer's plane whose disc covers the spacer
    round the followers' pivot pin: the clash check names the spacer and that cam."""
    raw = _raw()
    spacer = automaton.frame.spacers[0]
    assert automaton.bodies[-1].name == spacer.name == "spacers.0"
    centre = np.array(spacer.centre) - (0.0, 30.0)           # the cam's base circle (40 mm) covers the spacer
    distance = float(np.linalg.norm(centre))
    raw["shafts"].append({"name": "second", "at": [float(centre[0]), float(centre[1])]})
    raw["gears"] = [{"driver": "camshaft", "driven": "second", "driver_teeth": 20, "driven_teeth": 20,
                     "module": distance / 20}]
    tail = copy.deepcopy(next(c for c in raw["cams"] if c["name"] == "jaw"))
    tail.update(name="tail", shaft="second", layer=spacer.low // 2)
    tail["template"]["follower"] = {"type": "translating-roller", "roller_radius": 8.0}
    raw["cams"].append(tail)
    design = _design(raw)
    assert any({c.a, c.b} == {"cams.tail", "spacers.0"} for c in design.clashes), design.clashes


def test_the_bundled_automaton_meets_nothing_with_its_frame(automaton):
    assert automaton.clashes == ()
    assert [s.name for s in automaton.frame.spacers] == ["spacers.0"]


def test_the_bill_of_materials_lists_the_frame_and_its_hardware(built):
    out, report = built
    with (out / "automaton-kit.csv").open() as stream:
        rows = {r["part"]: r for r in csv.DictReader(stream)}
    assert {"frame", "frame-top", "spacer-0", "shaft camshaft"} <= set(rows)
    frame = report["frame"]
    top = frame["top_plate_mm"] + frame["thickness_mm"]
    # the followers' pivot pin runs from under the bottom plate through the spacer and the top plate: an M4 bolt
    # of the shortest ISO 4762 length over that grip, a washer, a nut and 1 mm of thread
    need = top + BOLTS["M4"].washer_thickness + BOLTS["M4"].nut_height + 1.0
    length = min(n for n in (6, 8, 10, 12, 16, 20, 25, 30, 35, 40, 45, 50, 55, 60, 65, 70, 80) if n >= need)
    assert f"M4 x {length} socket head cap screw, ISO 7089 washer, ISO 4032 nut" in rows
    spacer = frame["spacers"][0]
    assert spacer["z_mm"] + spacer["height_mm"] == pytest.approx(frame["top_plate_mm"], abs=1e-9)
    assert set(report["files"].values()) == {p.name for p in out.iterdir()}


def test_the_frames_solids_read_back_closed(built):
    from tests.project.test_programs import _admesh, _prusa

    out, _ = built
    for name in ("automaton-frame.stl", "automaton-frame-top.stl", "automaton-spacer-0.stl"):
        stats = _admesh(out / name)
        assert all(stats[k] == 0 for k in stats if k != "volume"), (name, stats)
        assert "manifold = yes" in _prusa(out / name), name


@pytest.mark.parametrize("change, message", [
    ({"machine.frame_margin": 3.0}, "machine.frame_margin: at least 6.1 mm (the largest seat's radius + 2 mm"),
    ({"machine.frame_margin": 500.0}, "machine.frame_margin: "),
    ({"machine.frame_thickness": 0.0}, "machine.frame_thickness: "),
    ({"machine.bearing": "625"}, "machine.bearing: a 625 bearing has a 5 mm bore; shaft camshaft is 8 mm"),
    ({"machine.frame": "three"}, "machine.frame: "),
])
def test_bad_frame_settings_are_refused(tmp_path, change, message):
    assert_refused(AUTOMATON, change, message, tmp_path)


@pytest.mark.parametrize("frame", ["none", "two"])
def test_a_mount_named_like_the_machines_own_files_is_refused(tmp_path, frame):
    raw = _raw()
    raw["machine"]["frame"] = frame
    raw["cams"][1]["name"] = "assembly"
    assert_refused(_write(tmp_path, raw), {}, "cams[1].name: 'assembly' names the machine's own files", tmp_path)


def test_one_plate_stands_every_pin_on_it():
    raw = _raw()
    raw["machine"]["frame"] = "one"
    design = _design(raw)
    assert design.frame.top is None and design.frame.spacers == ()
    assert all(s.bottom and not s.top for s in design.frame.seats)
    # the rocker's pivot pin now stands up through the cams' planes, where the cams sweep over it
    assert any("pins." in c.a + c.b for c in design.clashes)


def test_the_report_gives_the_sweep_outside_the_plate(automaton):
    """At the automaton's 12 mm margin the cams stand out of the plate: at least the disc the largest cam sweeps
    over a turn (its farthest point's radius) less the plate; at a 100 mm margin the plate covers every part."""
    from camgen.kinds.machine.framekit import swept_outside

    outside = swept_outside(automaton.frame, automaton)
    reach = max(float(np.linalg.norm(c.design.part.outline.flatten(c.design.tolerance), axis=1).max())
                for c in automaton.cams)
    plate = shapely.Polygon(automaton.frame.plate.outline.flatten(1e-4))
    disc = shapely.Point(0.0, 0.0).buffer(reach * math.cos(math.radians(2.5)), quad_segs=256)  # inside 5-degree steps
    assert outside >= disc.difference(plate).area > 1000.0
    raw = _raw()
    raw["machine"]["frame_margin"] = 100.0
    wide = _design(raw)
    assert swept_outside(wide.frame, wide) == 0.0
