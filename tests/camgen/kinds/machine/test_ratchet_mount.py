"""A ratchet on a machine (issue 35): the wheel's angle against a step-by-step pawl simulation written here from the
arm's angle and the pitch, the load's force on the roller and torque on the main shaft against virtual work, the
bundled example's one tooth a turn, and the bad inputs refused in one line."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from camgen import api
from camgen.kinds.machine.spec import MachineSpec
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

EXAMPLE = ROOT / "templates" / "ratchet-counter.toml"


def _raw() -> dict:
    return tomllib.loads(EXAMPLE.read_text())


def _design(change=None) -> object:
    raw = _raw()
    if change is not None:
        change(raw)
    return api.design(MachineSpec.model_validate(raw))


def _simulated(psi: np.ndarray, pitch: float, turns: int = 3) -> np.ndarray:
    """The wheel's angle (rad) over the last of ``turns`` repeats of the arm's angles ``psi`` (rad, one turn),
    stepped sample by sample: the arm's pawl, at lever angle L on a wheel at W, bears on the first face at or ahead
    of it (faces every pitch, one at L - W = 0 at the start); moving forward past it, it pushes the wheel so that
    the face stays at the pawl; moving back it slides over the faces. The wheel never turns back (the holding pawl
    drops behind a tooth at the top of each stroke), so the last turn is the steady one."""
    wheel, out = 0.0, []
    ahead = 0.0                                     # the face the pawl bears on next, in L - W
    for _ in range(turns):
        out = []
        for lever in psi:
            if lever - wheel > ahead:               # the pawl meets its face and drives the wheel
                wheel = lever - ahead
            else:                                    # behind its face: the face ahead of it is the next one it meets
                ahead = math.ceil((lever - wheel) / pitch - 1e-9) * pitch
            out.append(wheel)
    angles = np.array(out)
    return angles - angles[0]


@pytest.mark.parametrize("teeth, lift, phase", [(20, 24.0, 0.0), (24, 40.0, 47.5), (30, 12.5, 300.0)])
def test_the_wheel_follows_a_step_by_step_pawl_simulation(teeth, lift, phase):
    """Over 720 main shaft angles the wheel's angle is the simulation's to 1e-9 rad: 1, 2 and 1 whole teeth a
    stroke (24 / 18, 40 / 15, 12.5 / 12 degrees), at any phase of the cam."""
    def change(raw):
        raw["ratchets"][0]["teeth"] = teeth
        raw["cams"][0]["phase"] = phase
        for seg in raw["cams"][0]["template"]["motion"]:
            if "lift" in seg:
                seg["lift"] = lift

    design = _design(change)
    r = design.ratchets[0]
    psi = np.radians(design.cam("rocker").follower[0])
    pitch = 2 * math.pi / teeth
    assert len(psi) == 720
    simulated = _simulated(psi, pitch)
    assert np.max(np.abs(r.angle - simulated)) <= 1e-9
    n = math.floor(math.radians(lift) / pitch)
    assert r.teeth_per_stroke == n >= 1
    # over a turn from the start the wheel goes on by n teeth, never back
    assert r.angle.min() == 0.0 and r.angle.max() <= n * pitch + 1e-9 and np.all(np.diff(r.angle) >= -1e-12)


def test_the_example_advances_one_tooth_a_turn_and_reports_it():
    design = _design()
    r = design.ratchets[0]
    assert r.teeth_per_stroke == 1 and r.teeth_per_turn == 1.0
    from camgen.kinds.machine.report import machine_report

    report = machine_report(design)
    entry = report["ratchets"]["index"]
    # the cam's program starts at the shaft's 260 degrees: the turn starts mid-stroke (program angle 100 degrees)
    assert entry["wheel_deg"][0] == 0.0 and 17.0 < entry["wheel_deg"][1] < 18.0
    assert entry["teeth_per_turn"] == 1.0 and entry["lost_motion_deg"] == 6.0
    # the arm's pawl drives only after the 6 degrees of lost motion on the rise (cycloidal, 24 degrees over 150):
    # s(u) = 24 (u - sin(2 pi u) / (2 pi)) reaches 6 where u = 0.3700..., 55.5 degrees after the rise starts
    u = np.linspace(0, 1, 2_000_001)
    first = 150.0 * u[np.argmax(24.0 * (u - np.sin(2 * np.pi * u) / (2 * np.pi)) > 6.0)]
    start, end = entry["driving_deg"][0]
    assert abs(start - 260.0 - first) <= 0.5 and end == 149.5 + 260.0
    labels = [o["output"] for o in report["timing"]["outputs"]]
    assert "ratchets.index" in labels


def test_the_load_on_the_roller_and_the_main_shaft_is_virtual_work():
    """T dW/dphi = F (arm / 1000) dpsi/dphi = main shaft torque, to 1e-9 relative, where the pawl drives; 0 where
    the holding pawl holds."""
    design = _design()
    r = design.ratchets[0]
    cam = design.cam("rocker")
    arm_m = 80.0 / 1000.0
    follower_rate = np.radians(cam.follower[1]) * arm_m            # m per rad of the main shaft (one turn a turn)
    torque = 0.2
    power = torque * r.rate
    assert np.count_nonzero(power) > 100
    assert np.allclose(r.force * follower_rate, power, rtol=1e-9, atol=1e-15)
    assert np.allclose(r.torque, power, rtol=1e-9, atol=1e-15)
    assert np.allclose(design.shaft_torque, power, rtol=1e-9, atol=1e-15)
    driving = r.rate > 0                        # (at the stroke's top the pawl may bear with the arm at rest)
    assert np.allclose(r.force[driving], torque * 1000.0 / 80.0, rtol=1e-12)
    assert np.allclose(r.force[r.force != 0], torque * 1000.0 / 80.0, rtol=1e-12)
    assert np.count_nonzero(r.force) - np.count_nonzero(driving) <= 2
    # the cam is designed again with that load: its load table is the force at its program angles
    table = np.array(cam.design.spec.follower.load_table)
    assert table[:, 1].max() == pytest.approx(2.5, rel=1e-9) and table[:, 1].min() == 0.0


def test_no_load_leaves_the_cam_as_it_was():
    design = _design(lambda raw: raw["ratchets"][0].update(load_torque=0.0))
    assert design.cam("rocker").design.spec.follower.load_table is None
    assert np.all(design.ratchets[0].torque == 0.0)


@pytest.mark.parametrize("change, message", [
    ({"ratchets.0.cam": "nothing"}, "ratchets[0].cam: no cam 'nothing'; cams: rocker"),
    ({"ratchets.0.teeth": 2}, "ratchets[0].teeth: must be >= 6 and <= 360 (got 2)"),
    ({"ratchets.0.face_angle": -20.0}, "ratchets[0].face_angle: the pawl does not hold"),
    ({"cams.0.template.motion.0.lift": 10.0, "cams.0.template.motion.2.lift": 10.0},
     "ratchets[0].cam: cams.rocker's arm swings 10 degrees, under a tooth's pitch: the wheel would never advance; "
     "give a swing of at least 18 degrees (360 / 20 teeth)"),
])
def test_bad_ratchets_are_refused_in_one_line(change, message, tmp_path):
    assert_refused(EXAMPLE, change, message, tmp_path)


def test_a_ratchet_on_a_translating_follower_is_refused(tmp_path):
    text = EXAMPLE.read_text()
    follower = text[text.index('type = "oscillating-roller"'):text.index("mass = 0.05")]
    template = tmp_path / "translating.toml"
    template.write_text(text.replace(follower, 'type = "translating-roller"\nroller_radius = 6.0\n'))
    assert_refused(template, {}, "ratchets[0].cam: cams.rocker has a translating-roller follower; a ratchet's "
                   "lever is an arm of fixed length: give an oscillating-roller follower", tmp_path)


SECOND = """
[[ratchets]]
name = "second"
cam = "rocker"
teeth = 20
tip_diameter = 60.0
depth = 4.0
pawl = { length = 24.0 }
"""


def test_two_ratchets_on_one_arm_are_refused(tmp_path):
    text = EXAMPLE.read_text()
    template = tmp_path / "two.toml"
    template.write_text(text[:text.index("[output]")] + SECOND)
    assert_refused(template, {}, "ratchets[1].cam: cams.rocker's arm drives ratchets[0] already; one arm carries "
                   "one ratchet's pawl", tmp_path)


def test_a_swing_that_goes_forward_twice_a_turn_is_refused(tmp_path):
    """A rise and a return twice a turn: two strokes a cam turn, which the ratchet's one stroke a turn is not."""
    text = EXAMPLE.read_text()
    template = tmp_path / "twice.toml"
    template.write_text(text.replace("angle = 150.0", "angle = 75.0").replace("angle = 30.0", "angle = 15.0")
                        .replace("[[ratchets]]", (text[text.index("[[cams.template.motion]]"):
                                                        text.index("[[ratchets]]")].replace("150.0", "75.0")
                                                  .replace("30.0", "15.0")) + "[[ratchets]]", 1))
    assert_refused(template, {}, "ratchets[0].cam: its follower swings forward more than once a cam turn", tmp_path)


def test_a_wheel_set_on_its_cams_plane_clashes_where_shapely_finds_it():
    """The wheel put on the cam's plane (layer 0), 80 mm over its tips, on the pivot 100 mm from the cam's centre:
    the clash check's first angle is the first of a 0.01-degree scan in which shapely finds the cam's outline
    (its phase set to 0: turned by the main shaft's angle, counter-clockwise) and the wheel's (turned by its angle
    about the pivot, and its teeth's phase to the arm's pawl, mirrored for its clockwise drive) overlapping by more
    than the check's area tolerance, within 0.1 degree."""
    import shapely

    from camgen.kinds.machine.clash import AREA_TOL_MM2

    def change(raw):
        raw["ratchets"][0].update(layer=0, tip_diameter=80.0)
        raw["cams"][0]["phase"] = 0.0

    design = _design(change)
    found = [c for c in design.clashes if "ratchets.index.wheel" in (c.a, c.b)]
    assert found and {found[0].a, found[0].b} == {"cams.rocker", "ratchets.index.wheel"}
    r = design.ratchets[0]
    cam = next(b.outline for b in design.bodies if b.name == "cams.rocker")
    wheel = r.table.wheel.outline()[0]
    pivot = design.cam("rocker").design.cam.follower.pivot
    assert r.sense == -1 and abs(math.hypot(*pivot) - 100.0) <= 1e-9

    def turned(points, angle):
        c, s = math.cos(angle), math.sin(angle)
        return points @ np.array([[c, s], [-s, c]])

    # the wheel's teeth phased to the arm's pawl: at the stroke's top (program angle 180 degrees, the shaft's 180
    # with phase 0) the pawl's contact, |P| out on the arm less P's angle (mirrored frame), is a tooth's tip
    arm = next(b for b in design.bodies if b.name == "cams.rocker.arm")
    top = math.radians(180.0)
    m = arm.place(np.array([top]))[0][0]
    along = math.atan2(m[1, 0], -m[0, 0])                                  # the arm's direction, mirrored
    p = r.table.holding_pawl.pivot
    w0 = (along - math.atan2(p[1], p[0]) - float(r.wheel_angle(np.array([top]))[0])) % r.pitch
    first = None
    for deg in np.arange(0.0, 360.0, 0.01):
        phi = math.radians(deg)
        w = float(r.wheel_angle(np.array([phi]))[0]) + w0
        placed = turned(wheel * np.array([-1.0, 1.0]), -w) + pivot
        if shapely.Polygon(turned(cam, phi)).intersection(shapely.Polygon(placed)).area > AREA_TOL_MM2:
            first = deg
            break
    assert first is not None and first > 1.0
    assert abs(found[0].angle_deg - first) <= 0.1
