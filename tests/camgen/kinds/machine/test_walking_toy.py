"""The walking toy (issue 35 item 6): a hand crank turns, through a gear pair, one shaft carrying two Jansen legs
in antiphase. Each foot over the turn is checked against ``linkgen analyze`` of the leg's own template at the
shaft's angle (its drawn angle + its phase + the gear ratio times the main shaft's angle); the two feet trace one
curve half a leg turn apart; the clash check finds nothing in the toy and, with both legs on one side of the frame,
names the shaft crossing the lower leg's rods at the angle the rods' own positions give; bad mounts are refused in
one line naming the field."""
from __future__ import annotations

import json
import math
import tomllib

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from camgen.core.errors import SpecError
from tests.conftest import ROOT
from tests.support.refusals import assert_refused
from tests.camgen.kinds.machine.conftest import DESIGNS
from tests.camgen.kinds.machine.test_machine import _design

TOY = ROOT / "templates" / "walking-toy.toml"
JANSEN = ROOT / "templates" / "jansen.toml"

#: one worker for the modules that read the bundled machines' shared designs (conftest.py)
pytestmark = pytest.mark.xdist_group(DESIGNS)


def _raw() -> dict:
    return tomllib.loads(TOY.read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def toy(bundled_design):
    return bundled_design("walking-toy")


@pytest.fixture(scope="module")
def leg():
    from linkgen import api

    return api.load(JANSEN)


def _analyzed_foot(leg, angle_deg: float) -> tuple[float, float]:
    """The foot G at crank angle ``angle_deg`` as ``linkgen analyze --angle`` reports it (mm)."""
    from linkgen import api

    joint = api.design(leg, angle=angle_deg).report["positions"]["joints"]["G"]
    return joint["x_mm"], joint["y_mm"]


def test_the_toys_legs_are_jansens_leg():
    """Each leg inlined in the toy is templates/jansen.toml's linkage (its speed aside: the machine sets it)."""
    with JANSEN.open("rb") as stream:
        jansen = tomllib.load(stream)["linkage"]
    jansen.pop("rpm")
    for mount in _raw()["linkages"]:
        assert mount["template"]["linkage"] == jansen


def test_each_foot_is_linkgen_analyze_at_the_shaft_angle(toy, leg):
    """At main shaft angle phi the legs' shaft has turned -36/18 phi (the gear pair: the other way, twice as fast),
    so a leg's crank stands at 90 (its drawing) + phase - 2 phi; its foot is linkgen's there, to 1e-9 mm."""
    ratio = -36 / 18
    assert toy.spec.turns["legs"] == ratio
    phi_deg = np.degrees(toy.phi)
    for m in toy.cranked:
        for k in range(0, len(toy.phi), 37):
            angle = (90.0 + m.phase_deg + ratio * phi_deg[k]) % 360.0
            assert m.points["G"][k] == pytest.approx(_analyzed_foot(leg, angle), abs=1e-9), (m.name, phi_deg[k])


def test_linkgen_analyze_on_the_command_line_agrees(toy, tmp_path):
    from linkgen.cli import main

    k = 100                                                     # 50 degrees of the main shaft
    angle = (90.0 + 180.0 - 2 * 50.0) % 360.0                   # the right leg's crank
    result = CliRunner().invoke(main, ["analyze", str(JANSEN), "--angle", f"{angle:g}", "-o", str(tmp_path)])
    assert result.exit_code == 0, result.output
    joint = json.loads((tmp_path / "jansen.json").read_text())["positions"]["joints"]["G"]
    right = next(m for m in toy.cranked if m.name == "right")
    assert right.points["G"][k] == pytest.approx((joint["x_mm"], joint["y_mm"]), abs=1e-9)


def test_the_feet_move_in_antiphase(toy):
    """The right foot is where the left one was a quarter of a main turn (half a turn of the legs' shaft) before:
    one curve, half a leg turn apart; and the two are never at one place at once."""
    left, right = (next(m for m in toy.cranked if m.name == n).points["G"] for n in ("left", "right"))
    n = len(toy.phi)
    assert np.allclose(right, np.roll(left, n // 4, axis=0), rtol=0, atol=1e-9)
    assert np.hypot(*(right - left).T).min() > 1.0
    # the feet's rates are the same curve's too, per radian of the main shaft
    rates = [next(m for m in toy.cranked if m.name == s).rates["G"] for s in ("left", "right")]
    assert np.allclose(rates[1], np.roll(rates[0], n // 4, axis=0), rtol=0, atol=1e-9)


def test_a_foot_rate_is_its_path_differentiated(toy):
    """The foot's rate (mm per radian of the main shaft) against a central difference of its path."""
    m = toy.cranked[0]
    step = float(toy.phi[1])
    numeric = (np.roll(m.points["G"], -1, axis=0) - np.roll(m.points["G"], 1, axis=0)) / (2 * step)
    scale = float(np.abs(m.rates["G"]).max())
    assert np.abs(numeric - m.rates["G"]).max() <= 2e-3 * scale


def test_a_leg_by_its_path_is_the_inline_leg(toy):
    raw = _raw()
    for mount in raw["linkages"]:
        mount["template"] = str(JANSEN)
    design = _design(raw)
    for a, b in zip(design.cranked, toy.cranked, strict=True):
        assert np.allclose(a.points["G"], b.points["G"], rtol=0, atol=1e-12)


def test_the_toy_has_no_clash_and_its_parts_meet_only_at_their_joints(toy):
    from camgen.kinds.machine import clash

    assert toy.clashes == () and toy.unchecked == ()
    bodies, joints, _ = clash.machine_parts(toy)
    names = {b.name for b in bodies}
    assert {f"linkages.{s}.{link}" for s in ("left", "right") for link in ("crank", "leg", "hip")} <= names
    assert "shafts.legs" in names
    phi = np.arange(720) * (2 * math.pi / 720)
    for joint in joints:
        a, b = (next(x for x in bodies if x.name == n) for n in (joint.a, joint.b))
        gap = shapely.distance(clash._shapes(a, phi), clash._shapes(b, phi))
        assert gap.max() <= 0.02, (joint.a, joint.b, gap.max())
        if a.low <= b.high and b.low <= a.high:
            assert not clash._overlap(a, b, joint, phi).any(), (joint.a, joint.b)
    # each leg's frame pin B is one pin through both legs, from the back leg's planes to the front one's
    pin = next(b for b in bodies if b.name.startswith("pins."))
    assert (pin.low, pin.high) == (-2, 2)


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distances (n,) from point p to the segments a[i]-b[i]."""
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.einsum("ij,ij->i", d, d), 0.0, 1.0)
    return np.hypot(*(a + t[:, None] * d - p).T)


def test_two_legs_on_one_side_meet_the_shaft_where_the_rods_cross_it(leg):
    """Both legs in front (the second two layers up): the shaft reaching the upper leg's crank passes through the
    lower leg's planes, where its rod A-C (j) sweeps over the shaft's centre O. The rod's outline is a bar of half
    its width (4 mm) round A-C and the shaft a 1.5 mm pin, so they first meet where O comes within 5.5 mm of the
    segment A-C, which linkgen's own positions of A and C give."""
    raw = _raw()
    raw["linkages"][1].update(side="front", layer=2)
    design = _design(raw)
    found = {frozenset((c.a, c.b)): c.angle_deg for c in design.clashes}
    key = frozenset(("linkages.left.rod_j", "shafts.legs"))
    assert key in found, design.clashes
    from linkgen import api

    a = api.design(leg).kinematics
    phi = np.radians(np.arange(0.0, 120.0, 0.01))
    sol = a.linkage.solve((math.radians(90.0) - 2 * phi)[None, :])
    gap = _segment_distance(np.zeros(2), sol.points["A"], sol.points["C"])
    first = float(np.degrees(phi[np.argmax(gap < 4.0 + 1.5)]))
    assert abs(found[key] - first) <= 0.1 + 0.05, (found[key], first)
    assert any(w.startswith("clash: linkages.left.rod_j and shafts.legs meet at") for w in design.warnings)


@pytest.mark.parametrize("change, message", [
    ({"linkages.0.shaft": "axle"}, "linkages[0].shaft: no shaft 'axle'; shafts: crank, legs"),
    ({"linkages.0.side": "left"}, "linkages[0].side: unknown value 'left'; one of front, back"),
    ({"linkages.0.phase": 360}, "linkages[0].phase: must be >= 0 and < 360 degrees (got 360)"),
    ({"machine.figure_angles": [0, 360]}, "machine.figure_angles[1]: must be < 360 degrees (got 360)"),
    ({"machine.figure_angles": list(range(13))}, "machine.figure_angles: give 1 to 12 angles (got 13)"),
])
def test_bad_mounts_are_refused_in_one_line(tmp_path, change, message):
    assert_refused(TOY, change, message, tmp_path)


def test_a_shaft_that_turns_part_of_a_main_turn_is_refused(tmp_path):
    assert_refused(TOY, {"gears.0.driver_teeth": 27, "shafts.0.at": [33.75, 0.0]},
                   "linkages[0].shaft: shaft legs turns 1.5 times a turn of the main shaft", tmp_path)


def _refused(raw: dict, message: str) -> None:
    with pytest.raises(SpecError) as caught:
        _design(raw)
    assert str(caught.value).startswith(message), str(caught.value)


def test_a_shaft_drives_only_a_general_linkage_with_one_crank():
    raw = _raw()
    raw["linkages"][0]["template"] = str(ROOT / "templates" / "crank-rocker.toml")
    _refused(raw, "linkages[0].template: a shaft drives a type = \"linkage\" template whose one input is a crank")


def test_a_crank_that_cannot_turn_round_is_refused():
    """A drawing whose crank is longer than the rest allows (the crank's pin beyond the reach of its rod's dyad)
    turns only part of a turn: a shaft cannot turn it."""
    raw = _raw()
    raw["linkages"][0]["template"]["linkage"]["joints"]["A"] = [0.0, 30.0]
    raw["linkages"][0]["template"]["linkage"]["lengths"].pop("O-A")
    for k in ("A-C", "A-D"):
        raw["linkages"][0]["template"]["linkage"]["lengths"].pop(k)
    _refused(raw, "linkages[0].template: its crank reaches only")


def test_a_coupling_to_a_shaft_driven_linkage_is_a_coupling_loop():
    """A cam's follower coupled to a leg its shaft already turns: the leg would be driven twice."""
    automaton = tomllib.loads((ROOT / "templates" / "automaton.toml").read_text())
    raw = _raw()
    raw["cams"] = [{**automaton["cams"][2], "shaft": "legs"}]
    raw["couplings"] = [{**automaton["couplings"][0], "linkage": "left"}]
    _refused(raw, "couplings[0].linkage: a coupling loop: linkages.left is driven by shaft legs already")


def test_a_phase_without_a_shaft_is_refused():
    raw = tomllib.loads((ROOT / "templates" / "automaton.toml").read_text())
    raw["linkages"][0]["phase"] = 90.0
    _refused(raw, "linkages[0].phase: a linkage driven by a coupling takes its phase and plane from its cam")


def test_a_machine_of_nothing_is_refused():
    raw = _raw()
    for mount in raw["linkages"]:
        mount.pop("shaft")
        mount.pop("phase")
        mount.pop("layer", None)
        mount.pop("side", None)
    _refused(raw, "cams: a machine has at least one cam, or a linkage driven by a shaft")


def test_the_report_and_the_timing_name_both_feet(toy, tmp_path):
    from camgen.cli import main

    result = CliRunner().invoke(main, ["build", str(TOY), "-o", str(tmp_path), "--set",
                                       'output.formats=["json", "dxf"]'])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "walking-toy.json").read_text())
    assert set(report["cranked"]) == {"left", "right"}
    for name, m in report["cranked"].items():
        assert m["turns_per_main_turn"] == -2.0 and m["shaft"] == "legs"
        ours = next(c for c in toy.cranked if c.name == name).points["G"]
        assert m["tracers"]["G"]["x_mm"] == pytest.approx([ours[:, 0].min(), ours[:, 0].max()], abs=1e-6)
    labels = [o["output"] for o in report["timing"]["outputs"]]
    assert labels == ["linkages.left.G.x", "linkages.left.G.y", "linkages.right.G.x", "linkages.right.G.y"]
    # one leg's own x and y move together by construction: never listed as an overlap
    assert all(o["outputs"][0].split(".")[1] != o["outputs"][1].split(".")[1] for o in report["timing"]["overlaps"])
    for leg_name in ("left", "right"):
        assert (tmp_path / f"walking-toy-{leg_name}-sheet.dxf").exists()
    assert "2 linkage(s)" in result.output


def test_every_file_of_the_toy_reads_back(bundled_builds):
    """The toy's files, read back: every DXF by ezdxf with no audit error, every STL closed by admesh and
    PrusaSlicer, the page and the figures; the report names exactly the files written. The build is the one with
    every format a machine writes that test_machine_files_read_back.py reads (made once a run, read only).
    PrusaSlicer reads all 17 STLs in one ``--info`` call, each file its own section, each asked to be manifold."""
    import ezdxf

    from tests.camgen.kinds.machine.test_machine_files_read_back import _built, _info
    from tests.project.test_programs import _admesh

    tmp_path = _built(bundled_builds, "walking-toy").folder
    report = json.loads((tmp_path / "walking-toy.json").read_text())
    assert set(report["files"].values()) == {p.name for p in tmp_path.iterdir()}
    dxf = sorted(tmp_path.glob("*.dxf"))
    assert [p.name for p in dxf] == ["walking-toy-crank-legs-driven.dxf", "walking-toy-crank-legs-driver.dxf",
                                     "walking-toy-frame.dxf", *(f"walking-toy-{leg}-{what}.dxf"
                                                                for leg in ("left", "right")
                                                                for what in ("assembly", "sheet"))]
    for path in dxf:
        doc = ezdxf.readfile(path)
        assert not doc.audit().has_errors and len(doc.modelspace()) > 0, path.name
    solids = sorted(tmp_path.glob("*.stl"))
    assert len(solids) == 17              # 7 parts a leg (its ground is the frame), the frame's plate, two gears
    read = _info(solids)                  # PrusaSlicer's --info of every STL, by file name
    assert sorted(read) == [p.name for p in solids]
    for path in solids:
        stats = _admesh(path)
        assert all(stats[k] == 0 for k in stats if k != "volume"), (path.name, stats)
        assert stats["volume"] > 0
        assert [found["manifold"] for found in read[path.name]] == [1.0], path.name
    assert (tmp_path / "walking-toy.html").read_text(encoding="utf-8").startswith("<!DOCTYPE html>")


def test_the_assembly_stacks_the_back_leg_below_the_frame_and_the_front_leg_above(toy):
    """The front leg's parts stand over the (virtual) frame plate's top face, the back leg's hang under its bottom
    face, each as thick as linkgen cut it; on each side a higher layer is further from the plate (parts on one plane
    at one height), and the legs' shaft reaches down to the back crank's face (its rods cross the axis under it)."""
    from camgen.kinds.machine import assembly

    pieces = {p.part.name: p for p in assembly.pieces(toy)}
    t = toy.spec.machine.frame_thickness
    for m in toy.cranked:
        away = {}                                                       # plane on its side -> distance from the plate
        for part in m.design.build.cut:
            if part.name == "ground":                                   # the frame carries the leg's pivots
                continue
            piece = pieces[f"linkages.{m.name}.{part.name}"]
            assert piece.part.thickness == pytest.approx(part.thickness, abs=1e-12)
            k = 2 * m.layer + m.design.build.layers[part.name]
            gap = piece.z - t if m.side > 0 else -(piece.z + part.thickness)
            assert gap >= 1.0 - 1e-9, part.name                       # clear of the plate by a plane's gap
            assert away.setdefault(k, gap) == pytest.approx(gap, abs=1e-12)
        order = [away[k] for k in sorted(away)]
        assert order == sorted(order) and len(set(order)) == len(order)
    shaft = pieces["shafts.legs"]
    assert shaft.z == pytest.approx(pieces["linkages.right.crank"].z, abs=1e-12)     # down to the back crank's face
    assert not any(math.isnan(p.z) for p in pieces.values())
