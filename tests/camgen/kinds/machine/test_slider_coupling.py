"""A translating follower's stem as a linkage's slider input (issue 35 item 1): a cam lifting the slider of a
slider-crank run backwards (the slider drives, the crank is driven), checked against an independent composition
(the cam's program shifted by its phase, fed to a slider-crank closed form written here: a circle intersection);
the camshaft torque against the output's load power over the shaft speed (a numeric derivative); the reflected
load reaching the cam; the bad inputs refused in one line; the machine's files read back."""
from __future__ import annotations

import json
import math
import re
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from tests.camgen.kinds.machine.conftest import DESIGNS
from tests.support.refusals import assert_refused
from tests.support.stem_slider_crank import stem_slider_crank

#: one worker for the modules that read the bundled machines' shared designs (conftest.py)
pytestmark = pytest.mark.xdist_group(DESIGNS)

#: a disc cam (base 40 mm, roller 8 mm: the roller's centre 48 mm above the shaft at rest) lifting the slider C of
#: a slider-crank 30 mm: crank O-A turning about O, rod A-C, C sliding along +Y under the cam
TEMPLATE = """name = "lifter"

[machine]
main = "camshaft"
rpm = 30.0

[[shafts]]
name = "camshaft"
at = [0.0, 0.0]

[output]
formats = ["dxf", "stl", "json"]

[[cams]]
name = "lift"
shaft = "camshaft"
phase = 30.0

[cams.template.cam]
base_radius = 40.0
thickness = 6.0
bore = 8.0

[cams.template.follower]
type = "translating-roller"
roller_radius = 8.0
mass = 0.2
spring_rate = 1.0
preload = 20.0

[[cams.template.motion]]
type = "rise"
law = "cycloidal"
lift = 30.0
angle = 120.0

[[cams.template.motion]]
type = "dwell"
angle = 60.0

[[cams.template.motion]]
type = "return"
law = "modified-sine"
lift = 30.0
angle = 130.0

[[cams.template.motion]]
type = "dwell"
angle = 50.0

""" + stem_slider_crank("lift")
#: the drawing: the slider's point, the crank's pivot, the crank pin (mm)
C0, O0, A0 = np.array([0.0, 0.0]), np.array([50.0, 60.0]), np.array([24.684032711, 76.096639408])
#: the follower's rest point in the machine's frame: on its axis x = 0, the prime radius above the shaft
REST = np.array([0.0, 48.0])
PHASE, TORQUE = math.radians(30.0), 1.5


def _write(tmp_path: Path, old: str = "", new: str = "") -> Path:
    assert old in TEMPLATE
    path = tmp_path / "lifter.toml"
    path.write_text(TEMPLATE.replace(old, new, 1))
    return path


@pytest.fixture(scope="module")
def lifter():
    from camgen import api

    return api.design(api.validate(tomllib.loads(TEMPLATE)))


def _lift(design, phi: np.ndarray) -> np.ndarray:
    """The follower's lift (mm) at main shaft angles ``phi``: its program at phi - phase."""
    program = design.cam("lift").design.cam.program
    return program.evaluate(np.mod(phi - PHASE, 2 * math.pi))[0]


def _crank_pin(phi: np.ndarray, design) -> np.ndarray:
    """The slider-crank's crank pin A (mm, machine frame): where the circle about O (the crank) meets the circle
    about C = rest point + lift (the rod), on the drawing's side (left of C -> O)."""
    r, rod = np.linalg.norm(A0 - O0), np.linalg.norm(A0 - C0)
    o = O0 + REST - C0
    c = REST + np.column_stack([np.zeros_like(phi), _lift(design, phi)])
    u = o - c
    d = np.hypot(u[:, 0], u[:, 1])
    along = (rod ** 2 - r ** 2 + d ** 2) / (2 * d)
    h = np.sqrt(rod ** 2 - along ** 2)
    n = np.column_stack([-u[:, 1], u[:, 0]]) / d[:, None]
    return c + along[:, None] * u / d[:, None] + h[:, None] * n


def _crank_turn(phi: np.ndarray, design) -> np.ndarray:
    """The crank's turn from the drawing (radians), independently."""
    a = _crank_pin(phi, design) - (O0 + REST - C0)
    drawn = math.atan2(*(A0 - O0)[::-1])
    return np.angle(np.exp(1j * (np.arctan2(a[:, 1], a[:, 0]) - drawn)))


def test_the_driven_linkage_over_the_turn_is_the_cam_fed_into_a_slider_crank(lifter):
    m = lifter.slid[0]
    assert np.ptp(m.inputs) == pytest.approx(30.0, abs=1e-9)          # the stroke is the slider's travel
    assert np.abs(m.points["C"] - (REST + np.column_stack([0 * lifter.phi, _lift(lifter, lifter.phi)]))).max() < 1e-9
    assert np.abs(m.points["A"] - _crank_pin(lifter.phi, lifter)).max() < 1e-9
    assert np.abs(m.output_angle - _crank_turn(lifter.phi, lifter)).max() < 1e-9
    assert np.degrees(np.ptp(m.output_angle)) > 60.0                   # it does turn the crank
    outputs = {o.label: o for o in lifter.outputs}
    assert np.allclose(outputs["linkages.rocker"].values, np.degrees(m.output_angle), atol=1e-12)


def test_the_camshaft_torque_is_the_load_power_over_the_shaft_speed(lifter):
    """Virtual work: the main shaft works against the torque on the crank, -T omega_out / omega; the stem's force
    times its speed is the same power."""
    m, phi, h = lifter.slid[0], lifter.phi, 1e-6
    rate = (_crank_turn(phi + h, lifter) - _crank_turn(phi - h, lifter)) / (2 * h)      # rad per rad of the shaft
    expected = -TORQUE * rate
    assert np.abs(expected).max() > 0.5
    assert np.abs(lifter.shaft_torque - expected).max() < 1e-6 * np.abs(expected).max()
    assert np.abs(m.output_rate - rate).max() < 1e-6
    stem_speed = m.lift[1] / 1000.0                                     # m per radian of the shaft
    assert np.allclose(m.force * stem_speed, m.torque, atol=1e-12)


def test_the_reflected_load_reaches_the_cam_as_its_load_table(lifter):
    """The cam is designed again with the stem's force as its follower's load table, at each degree of its
    program: the force where the main shaft stands at phase + that degree."""
    cam = lifter.cam("lift")
    rows = cam.design.spec.follower.load_table_rows
    assert rows is not None and len(rows) == 360
    for degree in (0, 45, 100, 150, 250):
        j = round(((degree + 30.0) % 360) * 2)
        assert rows[degree][1] == pytest.approx(lifter.slid[0].force[j], abs=1e-8)
    assert cam.design.speed.contact.load_table.rows == 360


def test_the_spring_check_counts_the_linkage_load(lifter):
    """A torque that pulls the stem up (negative on this crank) lifts the follower off the cam: the spring check
    says so and what preload would hold it."""
    from camgen import api

    raw = tomllib.loads(TEMPLATE)
    raw["couplings"][0]["output_torque"] = -6.0
    contact = api.design(api.validate(raw)).cam("lift").design.speed.contact
    assert contact.holds is False and contact.preload_needed > 20.0
    assert lifter.cam("lift").design.speed.contact.holds is True


def test_the_driven_parts_are_in_the_clash_check(lifter):
    names = {b.name for b in lifter.bodies}
    assert {"linkages.rocker.crank", "linkages.rocker.rod", "cams.lift.stem", "cams.lift.roller"} <= names
    assert not lifter.clashes and lifter.unchecked == ()


@pytest.mark.parametrize("old, new", [
    ('type = "translating-roller"\nroller_radius = 8.0\n', 'type = "knife-edge"\n'),
    ('type = "translating-roller"\nroller_radius = 8.0\n', 'type = "translating-flat"\n'),
])
def test_a_knife_or_flat_stem_is_checked_too(old, new):
    """The stem as wide as the linkage's parts (8 mm), rising from the knife's edge or the face at the base circle
    (40 mm over the shaft), twice the stroke plus its width long, with a round foot of half its width (4 mm) about
    the slider's joint there (its lowest chord within the cam's tolerance of the arc); no roller; no clash."""
    from camgen import api
    from camgen.kinds.machine.clash import outlines

    assert old in TEMPLATE
    design = api.design(api.validate(tomllib.loads(TEMPLATE.replace(old, new, 1))))
    stem = next(b for b in design.bodies if b.name == "cams.lift.stem")
    assert "cams.lift.roller" not in {b.name for b in design.bodies}
    assert design.unchecked == () and design.clashes == ()
    x0, y0, x1, y1 = outlines(stem, np.array([PHASE]))[0].bounds       # the program's start: lift 0
    assert (x0, x1, y1) == pytest.approx((-4.0, 4.0, 40.0 + 2 * 30.0 + 8.0), abs=1e-9)
    tol = float(design.cam("lift").design.tolerance)
    assert 40.0 - 4.0 <= y0 <= 40.0 - 4.0 + tol


@pytest.mark.parametrize("old, new, message", [
    ('link = "stem"', 'link = "crank"',
     "couplings[0].link: a translating follower's stem is its linkage's input slider: 'stem', not 'crank'"),
    ("O = [50.0, 60.0]", "O = [20.0, 40.0]",                  # the rod 80, the crank 36.4: |OC| >= 43.6 mm
     "couplings[0]: cams.lift's follower drives the slider of linkages.rocker through [0, 30] mm (rest 0 + its "
     "lift), past a toggle from the main shaft's "),
    ("rest = 0.0", "rest = -100.0",
     "couplings[0].rest: the slider of linkages.rocker at rest (-100 mm) is out of its reach; its slider reaches "),
    ("angle = 90.0\n", "angle = 0.0\n", "couplings[0].link: slider stem of linkages.rocker is drawn at 0 degrees; "
                                        "draw its guide along +Y"),
    ('output = "crank"', 'output = "lever"', "couplings[0].output: linkages.rocker has no link 'lever'"),
])
def test_bad_slider_couplings_are_refused_in_one_line(tmp_path, old, new, message):
    assert_refused(_write(tmp_path, old, new), {}, message, tmp_path)


def test_a_translating_follower_cannot_drive_a_four_bar(tmp_path):
    four_bar = ('[linkages.template.linkage]\ntype = "four-bar"\nground = 100.0\ncrank = 30.0\ncoupler = 90.0\n'
                'rocker = 80.0\n\n[[couplings]]')
    text = TEMPLATE[:TEMPLATE.index("[linkages.template.linkage]")] + four_bar + TEMPLATE.split("[[couplings]]")[1]
    path = tmp_path / "lifter.toml"
    path.write_text(text)
    assert_refused(path, {}, "couplings[0].linkage: cams.lift's translating follower drives a type = \"linkage\" "
                   "template whose one input is a slider (input = { slider = NAME }); linkages.rocker is a "
                   "four-bar", tmp_path)


def test_the_machine_builds_and_its_files_read_back(tmp_path, lifter):
    import ezdxf

    result = CliRunner().invoke(camgen, ["build", str(_write(tmp_path)), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    out = tmp_path / "out"
    dxfs = sorted(out.glob("lifter-rocker*.dxf"))
    assert dxfs
    for path in dxfs:
        assert len(ezdxf.readfile(path).modelspace()) > 0
    stls = sorted(out.glob("lifter-rocker*.stl"))
    assert stls
    for path in stls:
        text = subprocess.run(["admesh", "-e", str(path)], capture_output=True, text=True, timeout=120).stdout
        for key in ("Degenerate facets", "Facets reversed", "Backwards edges"):
            assert int(re.search(rf"{key}\s*:\s*(\d+)", text).group(1)) == 0, (path, key)
        assert float(re.search(r"Volume\s*:\s*([-\d.]+)", text).group(1)) > 0
    report = json.loads((out / "lifter.json").read_text())
    entry = report["slid"]["rocker"]
    assert entry["travel_mm"] == pytest.approx([0.0, 30.0], abs=1e-6)
    turn = np.degrees(_crank_turn(np.linspace(0, 2 * math.pi, 720, endpoint=False), lifter))
    assert entry["output_deg"] == pytest.approx([turn.min(), turn.max()], abs=1e-6)


# ---- the bundled pick-and-place: a grooved cam's arm as a bell crank driving a carriage (a slider-crank)

PICK = Path(__file__).resolve().parents[4] / "templates" / "pick-and-place.toml"


@pytest.fixture(scope="module")
def pick(bundled_design):
    return bundled_design("pick-and-place")


def _carriage_x(design, phi: np.ndarray) -> np.ndarray:
    """The carriage C's x (mm, machine frame) independently: the bell crank's second arm at rest + the arm's
    turn (its swing, clockwise for this arm: the roller sits left of the pivot), the crank pin A on it, C on the
    guide's line (the drawn C's height) at the rod's length from A, on the drawing's side (right of A)."""
    raw = tomllib.loads(PICK.read_text())
    joints = raw["linkages"][0]["template"]["linkage"]["joints"]
    o, a0, c0 = (np.array(joints[k], dtype=float) for k in ("O", "A", "C"))
    follower = design.cam("shuttle").design.profile.cam.follower
    pivot = np.asarray(follower.pivot, dtype=float)                   # the shaft is at the origin
    program = design.cam("shuttle").design.profile.cam.program
    psi = np.radians(program.evaluate(np.mod(phi, 2 * math.pi))[0])
    angle = math.radians(raw["couplings"][0]["rest"]) - psi             # the arm swings clockwise (k = -1)
    r, rod = np.linalg.norm(a0 - o), np.linalg.norm(c0 - a0)
    a = pivot + r * np.column_stack([np.cos(angle), np.sin(angle)])
    height = pivot[1] + (c0 - o)[1]
    return a[:, 0] + np.sqrt(rod ** 2 - (height - a[:, 1]) ** 2)


def test_the_pick_and_place_carriage_is_the_cam_fed_into_a_slider_crank(pick):
    m = pick.slid[0]
    assert pick.cam("shuttle").design.profile.cam.follower._swing_sign == -1.0
    expected = _carriage_x(pick, pick.phi)
    assert np.abs(m.points["C"][:, 0] - expected).max() < 1e-9
    assert np.ptp(m.points["C"][:, 1]) < 1e-9                          # on its guide
    assert np.ptp(expected) > 20.0
    # the carriage stands still while the cam dwells (120-180 and 300-360 degrees of its program)
    dwell = (np.degrees(pick.phi) > 121) & (np.degrees(pick.phi) < 179)
    assert np.ptp(m.points["C"][dwell, 0]) < 1e-9
    outputs = {o.label: o for o in pick.outputs}                        # the timing diagram's carriage travel
    assert np.abs(outputs["linkages.carriage.C.x"].values - expected).max() < 1e-9
    assert pick.together("cams.shuttle", "linkages.carriage.C.x") and not pick.together("cams.shuttle", "cams.x")


def test_the_pick_and_place_is_clean(pick):
    """Its pressure angles within the cam's limit, no warnings, no clash, every moving part checked (the bell
    crank's arms share one pin)."""
    assert pick.warnings == ()
    assert pick.clashes == () and pick.unchecked == ()
    names = {b.name for b in pick.bodies}
    assert {"cams.shuttle.arm", "linkages.carriage.bell", "linkages.carriage.rod",
            "linkages.carriage.carriage"} <= names
    assert sum(n.startswith("pins.") for n in names) == 1
    profile = pick.cam("shuttle").design.profile
    assert 5.0 < profile.analysis.pressure_angle_max_deg <= profile.pressure_limit_deg


def test_the_pick_and_place_builds_and_its_files_read_back(tmp_path):
    import ezdxf

    result = CliRunner().invoke(camgen, ["build", str(PICK), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert "warning" not in result.output
    out = tmp_path / "out"
    dxfs = sorted(out.glob("*.dxf"))
    assert any(p.name.startswith("pick-and-place-carriage") for p in dxfs)
    for path in dxfs:
        assert len(ezdxf.readfile(path).modelspace()) > 0
    for path in sorted(out.glob("*.stl")):
        text = subprocess.run(["admesh", "-e", str(path)], capture_output=True, text=True, timeout=120).stdout
        for key in ("Degenerate facets", "Facets reversed", "Backwards edges"):
            assert int(re.search(rf"{key}\s*:\s*(\d+)", text).group(1)) == 0, (path, key)
    report = json.loads((out / "pick-and-place.json").read_text())
    assert report["slid"]["carriage"]["cam"] == "shuttle" and report["warnings"] == []


# ---- the sliders' guides (drawn still, over the slider's travel)


def test_the_stems_guide_spans_its_travel(lifter):
    """The stem's guide: on the follower's line x = 0, from its rest point to the top of its 30 mm stroke, in
    every pose of the report, on the stem's plane."""
    from camgen.kinds.machine.guides import guides
    from camgen.kinds.machine.poses import poses_report

    expected = np.stack([REST, REST + np.array([0.0, 30.0])])
    for pose in poses_report(lifter):
        assert set(pose["guides"]) == {"linkages.rocker.stem.guide"}
        assert np.abs(np.array(pose["guides"]["linkages.rocker.stem.guide"]) - expected).max() < 1e-9
    assert [g.plane for g in guides(lifter)] == [1]


def test_the_carriages_guide_spans_its_travel(pick):
    """The carriage's guide: along +X at the carriage's height, from the least to the largest x of the carriage's
    slider-crank (the independent closed form, on a grid of 0.01 degree: its ends fall in the cam's dwells), in the
    report's poses and as the figure's line."""
    from camgen.kinds.machine.plots import machine_figure
    from camgen.kinds.machine.poses import poses_report

    raw = tomllib.loads(PICK.read_text())
    joints = raw["linkages"][0]["template"]["linkage"]["joints"]
    follower = pick.cam("shuttle").design.profile.cam.follower
    height = float(follower.pivot[1]) + joints["C"][1] - joints["O"][1]
    x = _carriage_x(pick, np.radians(np.arange(36000) / 100.0))
    expected = np.array([[x.min(), height], [x.max(), height]])
    assert x.max() - x.min() > 20.0
    name = "linkages.carriage.carriage.guide"
    for pose in poses_report(pick):
        assert np.abs(np.array(pose["guides"][name]) - expected).max() < 1e-9
    fig = machine_figure(pick)
    lines = [line for ax in fig.axes for line in ax.get_lines() if line.get_gid() == name]
    assert len(lines) == len(pick.spec.machine.figure_angles)
    for line in lines:
        assert np.abs(np.column_stack([line.get_xdata(), line.get_ydata()]) - expected).max() < 1e-9
    import matplotlib.pyplot as plt

    plt.close(fig)


def _heights(path: Path) -> dict[str, float]:
    """Each object of a 3MF by its name: its height (mm, the z extent of its vertices)."""
    import zipfile
    from xml.etree import ElementTree

    core = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"
    with zipfile.ZipFile(path) as package:
        root = ElementTree.fromstring(package.read("3D/3dmodel.model"))
    return {o.get("name"): float(np.ptp([float(v.get("z")) for v in o.iter(f"{core}vertex")]))
            for o in root.iter(f"{core}object")}


def test_the_slider_driven_parts_stand_in_the_assembly_at_their_thickness(tmp_path):
    """The assembly 3MF of the pick-and-place and of the lifter: each linkage part as thick as its [parts] table
    (4 and 3 mm: a follower-driven linkage's planes used to be 0 high, and no solid could be built), the lifter's
    stem as thick as its cam (6 mm)."""
    for path, name, linkage, thick in ((PICK, "pick-and-place", "carriage", 4.0),
                                       (_write(tmp_path), "lifter", "rocker", 3.0)):
        out = tmp_path / name
        result = CliRunner().invoke(camgen, ["build", str(path), "-o", str(out), "--set", 'output.formats=["3mf"]'])
        assert result.exit_code == 0, result.output
        heights = _heights(out / f"{name}-assembly.3mf")
        parts = {k: v for k, v in heights.items() if k.startswith(f"linkages.{linkage}.")}
        assert len(parts) == 3
        assert all(abs(v - thick) < 1e-5 for v in parts.values()), parts
    assert heights["cams.lift.stem"] == pytest.approx(6.0, abs=1e-5)
