"""Machines (issue 35): a cam's follower driving a four-bar, checked against an independent composition (the cam's
program shifted by its phase, fed into a circle intersection written here); the camshaft torque against the
linkage's load power over the shaft speed (virtual work); the timing diagram's dwells against the programs shifted
by their phases; the bad inputs the issue lists, refused in one line; the bundled machine's files read back."""
from __future__ import annotations

import copy
import csv
import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely

from camgen.core.errors import SpecError
from tests.conftest import ROOT
from tests.camgen.kinds.machine.conftest import DESIGNS
from tests.support.refusals import assert_refused

AUTOMATON = ROOT / "templates" / "automaton.toml"

#: one worker for the modules that read the bundled machines' shared designs (conftest.py)
pytestmark = pytest.mark.xdist_group(DESIGNS)


def _raw() -> dict:
    with AUTOMATON.open("rb") as stream:
        return tomllib.load(stream)


def _design(raw: dict):
    from camgen import api

    return api.design(api.validate(raw))


@pytest.fixture(scope="module")
def automaton(bundled_design):
    return bundled_design("automaton")


# ---- an independent composition: the program shifted by its phase, a circle intersection for the four-bar


def _swing(design, cam: str, phi: np.ndarray) -> np.ndarray:
    """The follower's swing (degrees) at main shaft angles ``phi``: its program at phi - phase."""
    mount = next(c for c in design.spec.cams if c.name == cam)
    program = design.cam(cam).design.cam.program
    return program.evaluate(np.mod(phi - math.radians(mount.phase), 2 * math.pi))[0]


def _rocker(lengths: tuple[float, float, float, float], theta2: np.ndarray) -> np.ndarray:
    """The open four-bar's rocker angle at crank angles ``theta2``: B where the circle about the crank pin A (radius
    coupler) meets the circle about O4 = (ground, 0) (radius rocker), on the left of A -> O4."""
    ground, crank, coupler, rocker = lengths
    ax, ay = crank * np.cos(theta2), crank * np.sin(theta2)
    dx, dy = ground - ax, -ay
    d = np.hypot(dx, dy)
    along = (coupler ** 2 - rocker ** 2 + d ** 2) / (2 * d)
    h = np.sqrt(coupler ** 2 - along ** 2)
    bx = ax + along * dx / d - h * dy / d
    by = ay + along * dy / d + h * dx / d
    return np.arctan2(by, bx - ground)


def _independent_rocker(design, phi: np.ndarray) -> np.ndarray:
    coupling = design.spec.couplings[0]
    table = design.linkages[0].design.spec.linkage
    theta2 = np.radians(coupling.rest + _swing(design, coupling.cam, phi))
    return _rocker((table.ground, table.crank, table.coupler, table.rocker), theta2)


def test_the_rocker_over_the_turn_is_the_cam_fed_into_a_four_bar(automaton):
    linkage = automaton.linkages[0]
    expected = _independent_rocker(automaton, automaton.phi)
    gap = np.angle(np.exp(1j * (linkage.theta4 - expected)))
    assert np.abs(gap).max() < 1e-9
    assert np.ptp(expected) > math.radians(5)                     # it does move: 11.8 degrees


def test_the_rocker_rate_is_the_chain_rule_through_the_coupling(automaton):
    h = 1e-5
    phi = automaton.phi
    numeric = (_independent_rocker(automaton, phi + h) - _independent_rocker(automaton, phi - h)) / (2 * h)
    scale = np.abs(numeric).max()
    assert scale > 0.05
    assert np.abs(automaton.linkages[0].rocker_rate - numeric).max() < 1e-6 * scale


def test_the_camshaft_torque_is_the_load_power_over_the_shaft_speed(automaton):
    """T_shaft omega = -T_out omega_out at every angle (the shaft works against the output torque), the output's
    speed from the independent composition by central differences."""
    linkage = automaton.linkages[0]
    torque_out = automaton.spec.couplings[0].output_torque
    h = 1e-5
    phi = automaton.phi
    omega = automaton.omega
    omega_out = (_independent_rocker(automaton, phi + h) - _independent_rocker(automaton, phi - h)) / (2 * h) * omega
    power = -torque_out * omega_out
    assert np.abs(power).max() > 1e-3
    assert np.abs(automaton.shaft_torque - power / omega).max() < 1e-6 * np.abs(power / omega).max()
    # the same through the follower: the reflected force times the roller's speed along its path
    arm = automaton.cam("arm").design.spec.follower.arm_length
    roller = np.radians(automaton.cam("arm").rate) * arm / 1000.0                    # m per radian of the shaft
    assert np.allclose(linkage.force * roller, linkage.torque, atol=1e-12)


def test_the_reflected_load_reaches_the_cam_as_its_load_table(automaton):
    """The cam is designed again with the reflected force as its follower's load table (its rows the force at
    each degree of the program), which its own contact check counts."""
    cam = automaton.cam("arm")
    rows = cam.design.spec.follower.load_table_rows
    assert rows is not None and len(rows) == 360
    mount = next(c for c in automaton.spec.cams if c.name == "arm")
    # the force at the shaft angles where the program is at a whole degree: phase + that degree
    for degree in (0, 50, 100, 170, 300):
        j = round(((degree + mount.phase) % 360) * 2)
        assert rows[degree][1] == pytest.approx(automaton.linkages[0].force[j], abs=1e-8)
    assert cam.design.speed.contact.load_table.rows == 360


def test_the_spring_is_sized_with_the_linkage_attached():
    """A torque pulling the arm's follower off its cam: camgen's contact check says the spring's preload loses
    contact and what preload would hold it; with that preload (and a little more) the follower stays on."""
    raw = _raw()
    raw["couplings"][0]["output_torque"] = 3.0                   # N*m: pulls the follower off its cam
    design = _design(raw)
    contact = design.cam("arm").design.speed.contact
    assert contact.holds is False and contact.preload_needed > 12.0
    assert any(w.startswith("cams.arm: the spring loses contact") for w in design.warnings)
    raw["cams"][2]["template"]["follower"]["preload"] = contact.preload_needed + 0.5
    held = _design(raw).cam("arm").design.speed.contact
    assert held.holds is True and held.force_min == pytest.approx(0.5, abs=0.05)


def _program_dwells(motion: list[dict], phase: float) -> list[tuple[float, float]]:
    """The dwells of a program (its segments' angles in degrees) shifted by ``phase``: (start in [0, 360), end), a
    dwell ending the turn and one starting it being one."""
    out, at = [], 0.0
    for seg in motion:
        if seg["type"] == "dwell":
            if out and out[-1][1] == at:
                out[-1] = (out[-1][0], at + seg["angle"])
            else:
                out.append((at, at + seg["angle"]))
        at += seg["angle"]
    if len(out) > 1 and out[0][0] == 0.0 and out[-1][1] == 360.0:
        out = [(out[-1][0], out[0][1] + 360.0), *out[1:-1]]
    return sorted(((a + phase) % 360, (a + phase) % 360 + (b - a)) for a, b in out)


def test_the_timing_dwells_are_the_programs_shifted_by_their_phases(automaton):
    from camgen.kinds.machine.report import timing

    rows = {row["output"]: row for row in timing(automaton)["outputs"]}
    raw = _raw()
    for mount in raw["cams"]:
        expected = _program_dwells(mount["template"]["motion"], mount["phase"])
        found = sorted((a % 360, a % 360 + (b - a)) for a, b in rows[f"cams.{mount['name']}"]["dwells_deg"])
        assert len(found) == len(expected), (mount["name"], found, expected)
        for (a, b), (c, d) in zip(found, expected, strict=True):
            assert a == pytest.approx(c, abs=1e-6) and b == pytest.approx(d, abs=1e-6), (mount["name"], found)
    # the four-bar dwells with the follower that drives it
    assert rows["linkages.arm-bars"]["dwells_deg"] == rows["cams.arm"]["dwells_deg"]


def test_a_phase_moves_every_dwell_by_itself():
    from camgen.kinds.machine.report import timing

    raw = _raw()
    before = {r["output"]: r for r in timing(_design(raw))["outputs"]}
    raw["cams"][0]["phase"] = 37.5
    after = {r["output"]: r for r in timing(_design(raw))["outputs"]}
    shift = [((a + 37.5) % 360, (b - a)) for a, b in before["cams.head"]["dwells_deg"]]
    moved = [(a % 360, b - a) for a, b in after["cams.head"]["dwells_deg"]]
    assert sorted(moved) == pytest.approx(sorted(shift), abs=1e-6)
    assert after["cams.jaw"] == before["cams.jaw"]


def test_overlaps_are_where_two_outputs_move_together(automaton):
    from camgen.kinds.machine.report import timing

    pairs = {tuple(o["outputs"]): o["deg"] for o in timing(automaton)["overlaps"]}
    assert ("cams.head", "cams.jaw") not in pairs                 # the jaw moves in the head's dwell
    # the head returns over 180-270 while the arm rises from 200: they move together over (200, 270)
    assert [200.5, 269.5] in pairs[("cams.head", "cams.arm")]


# ---- bad input: one line naming the field, exit 2, nothing written


def _write(tmp_path: Path, raw: dict) -> Path:
    """``raw`` written as a TOML template (each mount's template an inline table)."""
    from camgen.core.starter import toml_value

    lines = [f"{k} = {toml_value(v)}" for k, v in raw.items() if not isinstance(v, (dict, list))]
    for key, value in raw.items():
        for table in [value] if isinstance(value, dict) else value if isinstance(value, list) else []:
            lines += [f"[[{key}]]" if isinstance(value, list) else f"[{key}]",
                      *(f"{k} = {toml_value(v)}" for k, v in table.items())]
    path = tmp_path / "machine.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def _refused(tmp_path, raw: dict, message: str) -> None:
    assert_refused(_write(tmp_path, raw), {}, message, tmp_path)


@pytest.mark.parametrize("key, value, message", [
    ("link", "lever", "couplings[0].link: linkages.arm-bars has no link 'lever'; its links: ground, crank"),
    ("linkage", "leg", "couplings[0].linkage: no linkage 'leg'; linkages: arm-bars"),
    ("link", "rocker", "couplings[0].link: the follower's arm is a four-bar's input link, its crank"),
    ("cam", "tail", "couplings[0].cam: no cam 'tail'; cams: head, jaw, arm"),
])
def test_a_follower_coupled_to_what_does_not_exist(tmp_path, key, value, message):
    raw = _raw()
    raw["couplings"][0][key] = value
    _refused(tmp_path, raw, message)


def test_two_cams_on_one_shaft_at_one_layer(tmp_path):
    raw = _raw()
    raw["cams"][1]["layer"] = 0
    _refused(tmp_path, raw, "cams[1].layer: cams.head already sits on shaft camshaft at layer 0")


def test_a_linkage_the_followers_stroke_cannot_drive(tmp_path):
    """A triple rocker (s + l = 100 > p + q = 95) whose crank reaches -100.81 to 100.81 degrees (cos = -0.1875):
    rest 80 + a swing of 25 runs past its toggle."""
    raw = _raw()
    raw["linkages"][0]["template"]["linkage"].update(ground=60.0, crank=50.0, coupler=40.0, rocker=45.0)
    raw["couplings"][0]["rest"] = 80.0
    _refused(tmp_path, raw, "couplings[0]: cams.arm's follower swings the crank of linkages.arm-bars through "
                            "[80, 105] degrees (rest 80 + its swing), past a toggle: this four-bar's crank reaches "
                            "[-100.8, 100.8] degrees")


def test_the_same_linkage_within_its_reach_is_driven():
    raw = _raw()
    raw["linkages"][0]["template"]["linkage"].update(ground=60.0, crank=50.0, coupler=40.0, rocker=45.0)
    raw["couplings"][0]["rest"] = 70.0
    design = _design(raw)
    chain = design.linkages[0].chain
    assert (np.degrees(chain.theta2.min()), np.degrees(chain.theta2.max())) == pytest.approx((70.0, 95.0))
    assert math.degrees(math.acos(-0.1875)) == pytest.approx(100.807, abs=1e-3)


@pytest.mark.parametrize("gears, message", [
    ([{"driver": "second", "driven": "camshaft", "driver_teeth": 20, "driven_teeth": 20, "module": 2.0}],
     "gears[0].driven: a coupling loop: shaft camshaft is the main shaft"),
    ([{"driver": "camshaft", "driven": "second", "driver_teeth": 20, "driven_teeth": 20, "module": 2.0},
      {"driver": "third", "driven": "second", "driver_teeth": 20, "driven_teeth": 20, "module": 2.0}],
     "gears[1].driven: a coupling loop: shaft second is driven by gears[0] already"),
    ([{"driver": "third", "driven": "second", "driver_teeth": 20, "driven_teeth": 20, "module": 2.0},
      {"driver": "second", "driven": "third", "driver_teeth": 20, "driven_teeth": 20, "module": 2.0}],
     "gears[0]: a coupling loop: second -> third -> second"),
])
def test_a_coupling_loop(tmp_path, gears, message):
    raw = _raw()
    raw["shafts"] += [{"name": "second", "at": [40.0, 0.0]}, {"name": "third", "at": [40.0, 40.0]}]
    raw["gears"] = gears
    _refused(tmp_path, raw, message)


def test_a_linkage_driven_twice_is_a_coupling_loop(tmp_path):
    raw = _raw()
    raw["couplings"].append({**raw["couplings"][0], "cam": "head"})
    _refused(tmp_path, raw, "couplings[1].linkage: a coupling loop: linkages.arm-bars is driven by couplings[0]")


def test_a_gear_pair_at_the_wrong_distance(tmp_path):
    raw = _raw()
    raw["shafts"].append({"name": "second", "at": [41.0, 0.0]})
    raw["gears"] = [{"driver": "camshaft", "driven": "second", "driver_teeth": 20, "driven_teeth": 20,
                     "module": 2.0}]
    _refused(tmp_path, raw, "gears[0].module: the shafts camshaft and second lie 41 mm apart; these gears need 40 mm")


def test_a_bad_key_inside_a_cam_is_named_under_its_mount(tmp_path):
    raw = _raw()
    raw["cams"][2]["template"]["motion"][0]["lift"] = -5.0
    _refused(tmp_path, raw, "cams[2].template.motion[0].lift: must be > 0")


def test_a_translating_follower_cannot_drive_a_four_bar(tmp_path):
    raw = _raw()
    follower = raw["cams"][2]["template"]["follower"]
    for key in ("pivot_distance", "arm_length"):
        del follower[key]
    follower["type"] = "translating-roller"
    for seg in raw["cams"][2]["template"]["motion"]:
        if "lift" in seg:
            seg["lift"] = 10.0
    _refused(tmp_path, raw, "couplings[0].linkage: cams.arm's translating follower drives a type = \"linkage\" "
             "template whose one input is a slider (input = { slider = NAME }); linkages.arm-bars is a four-bar")


def test_a_gear_pair_turns_a_cam_at_its_ratio():
    raw = _raw()
    raw["shafts"].append({"name": "second", "at": [0.0, 60.0]})
    raw["gears"] = [{"driver": "camshaft", "driven": "second", "driver_teeth": 40, "driven_teeth": 20,
                     "module": 2.0}]
    raw["cams"][0]["shaft"] = "second"
    design = _design(raw)
    assert design.spec.turns["second"] == -2.0
    assert design.cam("head").design.spec.cam.rpm == pytest.approx(40.0)
    # the head's program runs twice over one main turn: four dwells
    from camgen.kinds.machine.report import timing

    head = next(r for r in timing(design)["outputs"] if r["output"] == "cams.head")
    assert len(head["dwells_deg"]) == 4


def test_the_library_raises_rather_than_exits():
    from camgen import api

    raw = copy.deepcopy(_raw())
    raw["cams"][1]["shaft"] = "nowhere"
    with pytest.raises(SpecError, match=r"^cams\[1\]\.shaft: no shaft 'nowhere'; shafts: camshaft"):
        api.validate(raw)


# ---- the bundled machine's files, read back


@pytest.fixture(scope="module")
def built(bundled_builds):
    """``camgen build automaton.toml``'s folder and report: the build tests/project/test_golden.py compares, run
    once a run (:mod:`tests.support.builds`; read only)."""
    from tests.support.golden import runs

    program, args = runs(AUTOMATON)[0]
    out = bundled_builds.folder(AUTOMATON, program, args)
    return out, json.loads((out / "automaton.json").read_text())


def test_the_report_names_every_file_written(built):
    out, report = built
    names = set(report["files"].values())
    assert names == {p.name for p in out.iterdir()}
    assert {"automaton-timing.png", "automaton-timing.svg", "automaton-timing.csv", "automaton-head.dxf",
            "automaton-arm-bars-sheet.dxf"} <= names
    cam = json.loads((out / "automaton-head.json").read_text())
    assert set(cam["files"].values()) == {"automaton-head.dxf", "automaton-head.stl", "automaton-head.json"}


def test_the_timing_csv_holds_every_output_over_the_turn(built, automaton):
    out, _ = built
    with (out / "automaton-timing.csv").open() as stream:
        rows = list(csv.DictReader(stream))
    assert len(rows) == automaton.spec.machine.samples
    swing = [float(r["linkages.arm-bars_deg"]) for r in rows]
    assert swing == pytest.approx(list(np.degrees(_independent_rocker(automaton, automaton.phi))), abs=1e-6)
    normalised = [float(r["cams.jaw_normalised"]) for r in rows]
    assert min(normalised) == 0.0 and max(normalised) == 1.0


def test_the_figures_read_back(built):
    out, _ = built
    import xml.etree.ElementTree as ET

    import matplotlib.image

    image = matplotlib.image.imread(out / "automaton-timing.png")
    assert image.shape[0] > 300 and image.shape[1] > 600
    assert ET.parse(out / "automaton-timing.svg").getroot().tag.endswith("svg")


def test_the_cams_dxf_read_back_in_freecad(built, automaton):
    from tests.support.freecad import freecad_check
    from tests.project.test_programs import _expect

    out, _ = built
    for cam in automaton.cams:
        done = freecad_check("dxf", out / f"automaton-{cam.name}.dxf", _expect(cam.design))
        assert done.returncode == 0, (cam.name, done.stdout.strip().splitlines()[-1][:2000])


def test_the_linkage_sheet_reads_back_in_ezdxf(built):
    import ezdxf

    out, _ = built
    for name in ("automaton-arm-bars-sheet.dxf", "automaton-arm-bars-assembly.dxf"):
        doc = ezdxf.readfile(out / name)
        assert not doc.audit().has_errors
        assert len(doc.modelspace()) > 0


def test_every_solid_reads_back_closed(built):
    from tests.project.test_programs import _admesh, _prusa

    out, report = built
    solids = [n for n in report["files"].values() if n.endswith(".stl")]
    assert len(solids) == 14       # 3 cams, 2 links (the crank is the arm, the ground the frame), 2 frame plates, a
    #                               spacer, 3 arms, 3 rollers
    for name in solids:
        stats = _admesh(out / name)
        assert all(stats[k] == 0 for k in stats if k != "volume"), (name, stats)
        assert stats["volume"] > 0
        assert "manifold = yes" in _prusa(out / name), name


def test_a_grooved_cam_drives_a_four_bar_as_a_disc_does():
    """The arm's cam made a grooved cam (its inner flank is the disc cam's profile): the same program gives the
    same rocker, the composition being the follower's, whatever carries it; a positive drive has no spring to size,
    so the reflected load is carried into its report without a contact check."""
    raw = _raw()
    cam = raw["cams"][2]["template"]
    cam["cam"].update(kind="grooved", groove_depth=3.0, running_clearance=0.2, rim=5.0)
    for key in ("mass", "spring_rate", "preload"):
        del cam["follower"][key]
    design = _design(raw)
    assert type(design.cam("arm").design).__name__ == "GroovedDesign"
    expected = _independent_rocker(design, design.phi)
    assert np.abs(np.angle(np.exp(1j * (design.linkages[0].theta4 - expected)))).max() < 1e-9
    plain = _design(_raw())
    assert np.abs(design.linkages[0].torque - plain.linkages[0].torque).max() < 1e-12


def test_a_cam_shaft_turning_part_of_a_main_turn_is_refused(tmp_path):
    """Over one main turn such a cam runs part of its program: the machine's cycle would be several main turns."""
    raw = _raw()
    raw["shafts"].append({"name": "second", "at": [0.0, 60.0]})
    raw["gears"] = [{"driver": "camshaft", "driven": "second", "driver_teeth": 20, "driven_teeth": 40,
                     "module": 2.0}]
    raw["cams"][0]["shaft"] = "second"
    _refused(tmp_path, raw, "cams[0].shaft: shaft second turns 0.5 times a turn of the main shaft")


def test_a_cam_template_by_its_path(tmp_path):
    """A mount's template may be a cam template file; the machine renames it and sets its speed."""
    raw = _raw()
    raw["cams"][0]["template"] = str(ROOT / "templates" / "oscillating.toml")
    design = _design(raw)
    head = design.cam("head").design.spec
    assert head.name == "automaton-head" and head.cam.rpm == 20.0
    assert head.motion[0].lift == 20.0                            # oscillating.toml's own program
    missing = _raw()
    missing["cams"][0]["template"] = str(tmp_path / "nowhere.toml")
    _refused(tmp_path, missing, "cams[0].template: ")


def test_a_linkage_template_that_is_a_cam_is_refused(tmp_path):
    raw = _raw()
    raw["linkages"][0]["template"] = str(ROOT / "templates" / "rdrd.toml")
    _refused(tmp_path, raw, "linkages[0].template: this is a camgen template")


# ---- the clash check (item 4): a clash built on purpose, found at its closed-form angle; none in the automaton


def test_two_levers_on_one_layer_clash_at_the_angle_worked_in_closed_form():
    from camgen.kinds.machine import clash

    # lever a (length L, half width h) turns clockwise from straight up about the origin; lever b stands upright
    # at x = D. They first touch when a's tip comes within 2 h of b's axis: L sin(phi) + 2 h = D.
    length, reach, h = 100.0, 80.0, 5.0

    def turning(phi):
        return clash.rotation(math.pi / 2 - phi), np.zeros((len(phi), 2))

    def upright(phi):
        return clash.rotation(np.full(len(phi), math.pi / 2)), np.tile([reach, 0.0], (len(phi), 1))

    levers = [clash.Body("a", 0, 0, clash.bar(length, h), turning), clash.Body("b", 0, 0, clash.bar(150.0, h),
                                                                             upright)]
    expected = math.degrees(math.asin((reach - 2 * h) / length))                 # 44.427 degrees
    (found,) = clash.clashes(levers, [], 720)
    assert {found.a, found.b} == {"a", "b"}
    assert abs(found.angle_deg - expected) <= 0.1
    # on neighbouring planes they pass each other
    assert clash.clashes([levers[0], clash.Body("b", 1, 1, levers[1].outline, upright)], [], 720) == ()


def _meets_only_at_its_joints(design, phi: np.ndarray) -> tuple:
    """Assert that ``design`` has no clash and nothing unchecked, that every joint is a real one (its two parts
    meet: overlap, or a roller touches its cam, to 0.02 mm, a ratchet's pawl lies its drawn nose gap off its
    wheel's teeth, to 1e-8 mm, at every one of the angles ``phi``) and that on a common
    plane they overlap only in its disc; then that, heights from the assembly, every part meets no other but inside
    a joint's disc. The bodies and joints (with a top plate's spacers)."""
    from camgen.kinds.machine import clash, frame
    from linkgen.mechanisms.ratchet import NOSE_GAP_MM
    from tests.support.machine_meetings import assert_meet_only_at_joints, spans

    assert design.clashes == () and design.unchecked == ()
    bodies, joints, _ = clash.machine_parts(design, one_plate=design.spec.machine.frame == "one")
    if design.spec.machine.frame == "two":
        bodies, joints = frame.with_top_plate(bodies, joints)
    for joint in joints:
        a, b = (next(x for x in bodies if x.name == n) for n in (joint.a, joint.b))
        gap = shapely.distance(clash._shapes(a, phi), clash._shapes(b, phi))
        if joint.a.endswith("pawl") and joint.b.endswith(".wheel"):     # a ratchet's pawl: its drawn nose gap
            assert np.abs(gap - NOSE_GAP_MM).max() <= 1e-8, (joint.a, joint.b, gap.min(), gap.max())
            continue
        assert gap.max() <= 0.02, (joint.a, joint.b, gap.max())
        if a.low <= b.high and b.low <= a.high:                               # on a common plane
            assert not clash._overlap(a, b, joint, phi).any(), (joint.a, joint.b)
    assert assert_meet_only_at_joints(bodies, joints, spans(design, bodies), phi) >= 3
    return bodies, joints


def test_the_automaton_has_no_clash_and_its_parts_meet_only_at_their_joints(automaton):
    phi = np.arange(720) * (2 * math.pi / 720)
    bodies, joints = _meets_only_at_its_joints(automaton, phi)
    names = {b.name for b in bodies}
    assert {"cams.arm.arm", "linkages.arm-bars.coupler", "linkages.arm-bars.rocker", "shafts.camshaft"} <= names
    # the crank pin where the coupler meets the arm is crank mm from the follower's pivot, on the arm
    coupler = next(j for j in joints if {j.a, j.b} == {"cams.arm.arm", "linkages.arm-bars.coupler"})
    arm = next(b for b in bodies if b.name == "cams.arm.arm")
    m, pivot = arm.place(phi)
    pin = coupler.centre(phi)
    along = np.einsum("nji,nj->ni", m, pin - pivot)                       # the pin in the arm's own frame
    assert np.allclose(along, [30.0, 0.0], atol=1e-9)


#: every bundled machine: each template with [[shafts]]
BUNDLED = [p.stem for p in sorted((ROOT / "templates").glob("*.toml")) if "shafts" in tomllib.loads(p.read_text())]


def test_the_bundled_machines_are_found():
    assert {"automaton", "keep-time", "pick-and-place", "walking-toy"} <= set(BUNDLED)


@pytest.mark.slow
@pytest.mark.parametrize("name", BUNDLED)
def test_every_bundled_machine_meets_no_part_but_at_its_joints(name, bundled_design):
    """Each bundled machine (the automaton's check above, for all of them): every part placed by the kinematics at
    720 angles meets no other except at its joints, every joint a real one, nothing unchecked."""
    _meets_only_at_its_joints(bundled_design(name), np.arange(720) * (2 * math.pi / 720))


def test_a_clash_is_an_error_by_machine_clash_naming_both_parts(tmp_path):
    raw = _raw()
    raw["machine"]["clash"] = "error"
    raw["shafts"].append({"name": "second", "at": [0.0, -100.0]})
    raw["gears"] = [{"driver": "camshaft", "driven": "second", "driver_teeth": 50, "driven_teeth": 50, "module": 2.0}]
    twin = copy.deepcopy(raw["cams"][1])
    twin.update(name="twin", shaft="second", layer=0)
    raw["cams"].append(twin)
    assert_refused(_write(tmp_path, raw), {}, "machine.clash: cams.", tmp_path)
    raw["machine"]["clash"] = "warn"
    design = _design(raw)
    assert design.clashes and any(w.startswith("clash: ") for w in design.warnings)
    assert any({c.a, c.b} == {"cams.head", "cams.twin"} for c in design.clashes)


@pytest.mark.parametrize("change, message", [
    ({"machine.clash_samples": 99999}, "machine.clash_samples: must be >= 36 and <= 3600 (got 99999)"),
    ({"machine.clash": "never"}, "machine.clash: unknown value 'never'; one of error, warn"),
])
def test_the_clash_checks_settings_are_bounded(tmp_path, change, message):
    assert_refused(AUTOMATON, change, message, tmp_path)


def test_a_linkage_without_parts_is_named_as_not_checked_for_clashes():
    """A linkage drawn without a [parts] table has no outlines to place: the clash check says it did not check it,
    and still checks the rest (the cams, arms and rollers)."""
    raw = _raw()
    for linkage in raw["linkages"]:
        linkage["template"].pop("parts", None)
    design = _design(raw)
    assert set(design.unchecked) == {f"linkages.{m['name']}" for m in raw["linkages"]}
    assert design.clashes == ()
