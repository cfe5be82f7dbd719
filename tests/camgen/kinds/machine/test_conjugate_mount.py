"""A conjugate cam mounted on a machine's shaft (issue 35): its bell crank as a four-bar's crank, the rocker over the
turn against an independent composition (the pair's program shifted by its phase, fed into a circle intersection
written here); both rollers on their plates at every angle (the clash bodies placed by the machine against each
roller's distance from its placed plate); the pair's two layers and the one-line refusal of a cam on its second;
the yoke's follower in the timing; both plates in the machine's files."""
from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from tests.conftest import ROOT
from tests.support.refusals import assert_refused
from tests.support.stem_slider_crank import stem_slider_crank

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-conjugate-mount")

PHASE_DEG, REST_DEG = 40.0, 60.0
#: the four-bar the bell crank drives: ground, crank, coupler, rocker (mm)
BARS = (80.0, 30.0, 90.0, 60.0)

ARM = f"""
name = "conjarm"

[machine]
main = "camshaft"
rpm = 20.0

[[shafts]]
name = "camshaft"
at = [10.0, -5.0]

[output]
formats = ["dxf", "json"]

[[cams]]
name = "lever"
shaft = "camshaft"
layer = 1
phase = {PHASE_DEG}
template = "{ROOT / 'templates' / 'conjugate-arm.toml'}"

[[linkages]]
name = "bars"

[linkages.template.linkage]
type = "four-bar"
ground = {BARS[0]}
crank = {BARS[1]}
coupler = {BARS[2]}
rocker = {BARS[3]}
point_distance = 45.0
point_angle = 30.0

[linkages.template.parts]
width = 10.0
thickness = 4.0
pin_diameter = 4.0

[[couplings]]
cam = "lever"
linkage = "bars"
rest = {REST_DEG}
output_torque = -0.2
"""

YOKE = f"""
name = "conjyoke"

[machine]
main = "camshaft"
rpm = 30.0

[[shafts]]
name = "camshaft"
at = [0.0, 0.0]

[[cams]]
name = "yoke"
shaft = "camshaft"
phase = 90.0
template = "{ROOT / 'templates' / 'conjugate.toml'}"
"""


def _design(text: str):
    from camgen import api

    return api.design(api.validate(tomllib.loads(text)))


@pytest.fixture(scope="module")
def lever():
    return _design(ARM)


@pytest.fixture(scope="module")
def yoke():
    return _design(YOKE)


def _swing_deg(design, name: str, phi: np.ndarray) -> np.ndarray:
    """The pair's follower swing (degrees) at main shaft angles ``phi``: its program at phi - phase."""
    mount = next(c for c in design.spec.cams if c.name == name)
    program = design.cam(name).design.cam.program
    return program.evaluate(np.mod(phi - math.radians(mount.phase), 2 * math.pi))[0]


def _rocker_angle(theta2: np.ndarray) -> np.ndarray:
    """The open four-bar's rocker angle at crank angles ``theta2`` (rad), by complex numbers: the crank pin A, the
    rocker's pivot O4 = ground on the real axis, B where |B - A| = coupler and |B - O4| = rocker, on the left of
    A -> O4."""
    ground, crank, coupler, rocker = BARS
    a = crank * np.exp(1j * theta2)
    u = ground - a
    d = np.abs(u)
    cos_b = (coupler ** 2 + d ** 2 - rocker ** 2) / (2 * coupler * d)           # at A, between A->O4 and A->B
    b = a + coupler * (u / d) * np.exp(1j * np.arccos(cos_b))
    return np.angle(b - ground)


def test_the_bell_cranks_rocker_is_the_pair_fed_into_a_four_bar(lever):
    m = lever.linkages[0]
    expected = _rocker_angle(np.radians(REST_DEG + _swing_deg(lever, "lever", lever.phi)))
    gap = np.angle(np.exp(1j * (m.theta4 - expected)))
    assert np.abs(gap).max() < 1e-9
    assert np.ptp(np.degrees(expected)) > 5.0                          # it moves: 9.26 degrees
    row = {o.label: o for o in lever.outputs}
    assert np.allclose(row["cams.lever"].values, _swing_deg(lever, "lever", lever.phi), atol=1e-12)
    assert np.allclose(row["linkages.bars"].values, np.degrees(expected), atol=1e-7)


def test_the_pair_needs_no_spring_with_the_linkage_attached(lever):
    from camgen.kinds.machine.report import machine_report

    spring = machine_report(lever)["linkages"]["bars"]["spring"]
    assert spring["positive_drive"] is True


def _bodies(design) -> dict:
    return {b.name: b for b in design.bodies}


def _roller_gaps(design, plate: str, roller: str, radius: float) -> np.ndarray:
    """Each angle's distance (mm) from the roller body's centre (its placement) to the placed plate's outline,
    less the roller's radius: 0 where the roller touches its plate."""
    from camgen.kinds.machine.clash import outlines

    bodies, phi = _bodies(design), design.phi[::6]
    rings = shapely.get_exterior_ring(outlines(bodies[plate], phi))
    centres = bodies[roller].place(phi)[1]
    return shapely.distance(rings, shapely.points(centres)) - radius


@pytest.mark.parametrize("which", ["lever", "yoke"])
def test_both_rollers_ride_on_their_plates_at_every_angle(which, request):
    design = request.getfixturevalue(which)
    pair = design.cam(which).design
    r1, r2 = pair.cam.follower.roller_radius, pair.second.follower.contact_radius
    for plate, roller, radius in ((f"cams.{which}", f"cams.{which}.roller", r1),
                                  (f"cams.{which}.second", f"cams.{which}.roller2", r2)):
        gaps = _roller_gaps(design, plate, roller, radius)
        assert np.abs(gaps).max() < 0.02, (plate, np.abs(gaps).max())     # the outlines' 0.01 mm and chords


def test_the_pair_takes_two_layers_and_its_linkage_stands_over_both(lever):
    planes = {name: (b.low, b.high) for name, b in _bodies(lever).items()}
    assert planes["cams.lever"] == (2, 2) and planes["cams.lever.second"] == (4, 4)
    assert planes["cams.lever.arm"] == (3, 3)
    assert planes["cams.lever.roller"] == (2, 3) and planes["cams.lever.roller2"] == (3, 4)
    assert min(planes["linkages.bars.rocker"][0], planes["linkages.bars.coupler"][0]) > 4
    assert planes["shafts.camshaft"] == (0, 4)
    assert lever.clashes == () and lever.unchecked == ()


def test_the_bell_crank_turns_about_its_pivot_with_the_swing(lever):
    """The arm's placement turns by the swing (its sign the follower's) about the pivot, which stays put."""
    arm = _bodies(lever)["cams.lever.arm"]
    f = lever.cam("lever").design.cam.follower
    turn, shift = arm.place(lever.phi)
    angle = np.arctan2(turn[:, 1, 0], turn[:, 0, 0])
    swing = np.radians(_swing_deg(lever, "lever", lever.phi))
    moved = np.angle(np.exp(1j * (angle - angle[np.argmin(swing)])))
    assert np.allclose(np.abs(moved), swing - swing.min(), atol=1e-12)
    assert np.allclose(shift, np.array([10.0, -5.0]) + f.pivot, atol=1e-12)


def test_the_yokes_lift_is_in_the_timing_shifted_by_its_phase(yoke):
    row = {o.label: o for o in yoke.outputs}["cams.yoke"]
    assert row.unit == "mm"
    assert np.allclose(row.values, _swing_deg(yoke, "yoke", yoke.phi), atol=1e-12)
    from camgen.kinds.machine.report import timing

    out = timing(yoke)["outputs"][0]
    # the program's dwells (90-180 and 300-360 degrees of the cam) shifted by the phase of 90 degrees
    assert sorted(out["dwells_deg"]) == [pytest.approx([30.0, 90.0]), pytest.approx([180.0, 270.0])]
    assert yoke.clashes == ()
    names = set(_bodies(yoke))
    assert {"cams.yoke", "cams.yoke.second", "cams.yoke.yoke", "cams.yoke.roller2", "cams.yoke.stem"} <= names


def _path(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "machine.toml"
    path.write_text(text)
    return path


def test_a_cam_on_the_pairs_second_layer_is_refused_in_one_line(tmp_path):
    other = f"""
[[cams]]
name = "nod"
shaft = "camshaft"
layer = 2
template = "{ROOT / 'templates' / 'oscillating.toml'}"
"""
    assert_refused(_path(tmp_path, ARM + other), {}, "cams[1].layer: cams.lever already sits on shaft camshaft at "
                   "layer 2 (cams.lever is a conjugate pair: its two plates take layers 1 and 2)", tmp_path)


def test_both_plates_are_in_the_machines_files(tmp_path):
    from camgen.cli import main

    result = CliRunner().invoke(main, ["build", str(_path(tmp_path, ARM)), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "out" / "conjarm.json").read_text())
    files = set(report["files"].values())
    assert {"conjarm-lever-1.dxf", "conjarm-lever-2.dxf"} <= files
    assert all((tmp_path / "out" / f).is_file() for f in files)
    assert report["clashes"] == []


#: the yoke's first roller (the conjugate template's: base 40 mm, roller 8 mm, 48 mm above the shaft at rest) lifts
#: the slider C of a slider-crank: crank O-A about O, rod A-C, C sliding along +Y
O_DRAWN, A_DRAWN = np.array([50.0, 60.0]), np.array([24.684032711, 76.096639408])
LIFTER = YOKE.replace('name = "conjyoke"', 'name = "conjlift"') + "\n" + stem_slider_crank("yoke")


def _crank_pin(c: np.ndarray, o: np.ndarray) -> np.ndarray:
    """A where the circle about O (radius |OA| drawn) meets the circle about C (radius |AC| drawn), on the drawn
    A's side of the line C -> O (mm)."""
    crank, rod = np.hypot(*(A_DRAWN - O_DRAWN)), np.hypot(*A_DRAWN)
    u = o - c
    d = np.hypot(u[:, 0], u[:, 1])[:, None]
    along = (rod ** 2 - crank ** 2 + d ** 2) / (2 * d)
    h = np.sqrt(rod ** 2 - along ** 2)
    left = np.column_stack([-u[:, 1], u[:, 0]]) / d
    side = np.sign(O_DRAWN[0] * A_DRAWN[1] - O_DRAWN[1] * A_DRAWN[0])     # the drawing's C is the origin
    return c + along * u / d + side * h * left


def test_the_yokes_stem_drives_a_slider_crank_as_a_single_cams_does():
    design = _design(LIFTER)
    m = design.slid[0]
    lift = _swing_deg(design, "yoke", design.phi)
    roller = next(b for b in design.bodies if b.name == "cams.yoke.roller").place(design.phi)[1]
    assert np.allclose(roller, np.column_stack([np.zeros_like(lift), 48.0 + lift]), atol=1e-12)
    expected = _crank_pin(np.asarray(roller, float), np.broadcast_to(O_DRAWN + np.array([0.0, 48.0]), roller.shape))
    assert np.abs(m.points["A"] - expected).max() < 1e-9
    assert np.ptp(m.points["A"][:, 1]) > 5.0
    assert design.clashes == ()                                    # the block rides the stem and the yoke
