"""Gears as joints of a general linkage (issue 34, item 2): gear pairs and racks as higher pairs.

* The geared five-bar's coupler point over a full turn against a solution written here: each crank turned by its own
  gear ratio, the couplers' joint by a circle intersection of its own, the tracer carried rigidly (1e-9 mm); its
  velocities and accelerations against central differences; its mobility 1 (Gruebler with the higher pair).
* Virtual work through the gears: the input torque holding a torque on the geared crank is -M w_out / w_in = 2 M,
  and with a force on the coupler point the effort equals the force's power by finite differences of positions.
* A rack on a slider in a linkage (a slider-crank's block, a four-bar's rocker driving a rack): the slider's travel
  equals r theta to 1e-12 mm, its speed r omega.
* A planetary train drawn as a linkage against Willis' formula (1 + z_sun / z_ring for the ring, 1 + z_sun / z_planet
  for the planet, the sun held).
* Bad input (a rack on no slider, centres off their distance, a fractional ratio on a crank that turns fully, a gear
  whose centres drift apart over the motion) refused in one line naming the field, exit code 2, nothing written.
* The parts and the assembly include the gears on their own layer, which never overlap as the linkage turns.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from camgen.core.errors import SpecError
from linkgen import api
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.statics import LinkTorque, PointForce, input_effort
from linkgen.kinematics.structure import Gear, Input, Rack, Slider, make_structure
from tests.support.refusals import assert_refused_sets
from tests.conftest import ROOT

FIVEBAR = ROOT / "templates" / "geared-fivebar.toml"


def _turn(v: np.ndarray, angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _fivebar():
    spec = api.load(FIVEBAR)
    return spec, api.design(spec).kinematics


def test_the_geared_fivebar_has_mobility_one_and_a_gear_step():
    spec, a = _fivebar()
    # five links (the ground too), five revolutes, one gear pair: 3 (5 - 1) - 2 * 5 - 1
    assert a.linkage.structure.mobility == 1 == a.linkage.plan.mobility
    report = api.design(spec).report
    assert [s["step"] for s in report["solve_order"]] == ["input", "gear", "RRR"]
    assert report["higher_pairs"][0]["ratio"] == -2.0


def test_the_coupler_point_against_an_independent_solution():
    spec, a = _fivebar()
    joints = {k: np.array(v) for k, v in spec.linkage.joints.items()}
    z_a, z_b = spec.linkage.gears["mesh"].a.teeth, spec.linkage.gears["mesh"].b.teeth
    drawn = math.atan2(*(joints["A"] - joints["O2"])[::-1])
    t = np.linspace(0.0, 2 * math.pi, 721)
    sol = a.linkage.solve(drawn + t)
    # each crank turns about its pivot: the first by t, the second by -z_a / z_b t (the frame is the carrier)
    A = joints["O2"] + _turn(joints["A"] - joints["O2"], t)
    B = joints["O5"] + _turn(joints["B"] - joints["O5"], -z_a / z_b * t)
    r1, r2 = np.linalg.norm(joints["C"] - joints["A"]), np.linalg.norm(joints["C"] - joints["B"])
    ab, ac = joints["B"] - joints["A"], joints["C"] - joints["A"]
    side = np.sign(ab[0] * ac[1] - ab[1] * ac[0])
    # C on the circles about A and B: the angle at A by the law of cosines, on the drawing's side of AB
    d = np.hypot(*(B - A).T)
    at_a = np.arccos((r1**2 + d**2 - r2**2) / (2 * r1 * d))
    heading = np.arctan2((B - A)[:, 1], (B - A)[:, 0]) + side * at_a
    C = A + r1 * np.column_stack([np.cos(heading), np.sin(heading)])
    drawn_ac = joints["C"] - joints["A"]
    turn = heading - math.atan2(drawn_ac[1], drawn_ac[0])
    P = A + _turn(joints["P"] - joints["A"], turn)
    assert np.max(np.hypot(*(sol.points["C"] - C).T)) < 1e-9
    assert np.max(np.hypot(*(sol.points["P"] - P).T)) < 1e-9
    # the second crank's turn is the gear ratio's, exactly: -2 turns a turn
    assert np.allclose(np.remainder(sol.angle("crank2") + 2 * t + math.pi, 2 * math.pi) - math.pi, 0.0, atol=1e-12)


def test_velocities_and_accelerations_against_central_differences():
    _, a = _fivebar()
    x = a.linkage.drawn_inputs[0] + np.linspace(0.0, 2 * math.pi, 97)[:-1]
    h = 1e-5
    sol, up, down = (a.linkage.solve(x + e) for e in (0.0, h, -h))
    for p in ("A", "B", "C", "P"):
        fd_v = (up.points[p] - down.points[p]) / (2 * h)
        fd_a = (up.velocities[p] - down.velocities[p]) / (2 * h)
        assert np.max(np.abs(fd_v - sol.velocities[p])) < 1e-6 * max(1.0, np.abs(sol.velocities[p]).max())
        assert np.max(np.abs(fd_a - sol.accelerations[p])) < 1e-6 * max(1.0, np.abs(sol.accelerations[p]).max())
    assert np.allclose(sol.omegas["crank2"], -2.0, rtol=0, atol=1e-12)
    assert np.allclose(sol.alphas["crank2"], 0.0, atol=1e-12)


def test_virtual_work_through_the_gear_pair():
    _, a = _fivebar()
    x = a.linkage.drawn_inputs[0] + np.linspace(0.0, 2 * math.pi, 73)
    sol = a.linkage.solve(x)
    # a torque M on the geared crank: T_in w_in + M w_out = 0 with w_out = -2 w_in
    effort = input_effort(sol, (), (LinkTorque("crank2", 1.5),), True)
    assert np.allclose(effort, 3.0, rtol=1e-12)
    # a force on the coupler point: the input's power balances the force's, its velocity by differences of positions
    force = np.array([12.0, -30.0])
    effort = input_effort(sol, (PointForce("P", (12.0, -30.0)),), (), True)
    h = 1e-6
    dp = (a.linkage.solve(x + h).points["P"] - a.linkage.solve(x - h).points["P"]) / (2 * h)
    assert np.allclose(effort * 1000.0 + dp @ force, 0.0, atol=1e-5)


def _slider_crank_with_rack(lead_side: float = 1.0) -> Linkage:
    """A slider-crank (crank 20, rod 60) whose block carries a rack meshing with a 20-tooth module-2 pinion (r = 20)
    on the frame above (or below) the block's line."""
    r = 20.0
    points = {"O2": (0.0, 0.0), "A": (20.0, 0.0), "B": (80.0, 0.0), "Q": (80.0, lead_side * r),
              "T": (95.0, lead_side * r)}
    links = {"crank": ("O2", "A"), "rod": ("A", "B"), "pinion": ("Q", "T")}
    s = make_structure(points, links, ("O2", "Q"), (Slider("ram", "B", "ground", 0.0),),
                       (Input("crank", "crank", "O2"),), (), (Rack("drive", "ram", "pinion", "Q", lead_side * r),))
    return Linkage.of(s)


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_a_rack_on_a_slider_crank_turns_its_pinion_by_its_travel(side):
    linkage = _slider_crank_with_rack(side)
    assert linkage.structure.mobility == 1
    theta = np.linspace(0.0, 2 * math.pi, 361)
    sol = linkage.solve(theta)
    travel = sol.points["B"][:, 0] - 80.0
    psi = sol.angle("pinion")
    # s = r theta, the pinion's turn counter-clockwise with the pinion above the rack (clockwise below it)
    assert np.max(np.abs(side * 20.0 * psi - travel)) < 1e-12
    assert np.max(np.abs(side * 20.0 * sol.omegas["pinion"] - sol.velocities["B"][:, 0])) < 1e-12
    assert np.max(np.abs(side * 20.0 * sol.alphas["pinion"] - sol.accelerations["B"][:, 0])) < 1e-9


def test_a_rocker_drives_a_rack_by_its_swing():
    # a crank-rocker (crank 20, coupler 70, rocker 50, frame 80) whose rocker carries a 24-tooth module-1 pinion
    # (r = 12) about O4, meshing with a rack on a block that slides on the frame 12 mm below O4
    points = {"O2": (0.0, 0.0), "A": (10.0, 17.320508076), "O4": (80.0, 0.0), "B": (72.221149669, 49.391188359),
              "D": (80.0, -12.0)}
    links = {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("O4", "B")}
    s = make_structure(points, links, ("O2", "O4"), (Slider("ram", "D", "ground", 0.0),),
                       (Input("crank", "crank", "O2"),), (), (Rack("drive", "ram", "rocker", "O4", 12.0),))
    linkage = Linkage.of(s)
    assert linkage.plan.steps[-1].body == "ram" and linkage.plan.steps[-1].partner == "rocker"
    sol = linkage.solve(linkage.drawn_inputs[0] + np.linspace(0.0, 2 * math.pi, 361))
    travel = sol.points["D"][:, 0] - 80.0
    assert np.max(np.abs(12.0 * sol.angle("rocker") - travel)) < 1e-12
    assert np.max(np.abs(12.0 * sol.omegas["rocker"] - sol.velocities["D"][:, 0])) < 1e-12
    assert np.allclose(sol.points["D"][:, 1], -12.0, atol=1e-12)


def test_a_planetary_train_against_willis():
    # the arm O-P turns; the sun (20 teeth) is held on the frame at O, the planet (10) turns on the arm at P, the
    # ring (40) about O: module 2 puts P 30 mm from O for both meshes
    zs, zp, zr = 20, 10, 40
    points = {"O": (0.0, 0.0), "P": (30.0, 0.0), "Q": (30.0, 10.0), "R": (0.0, 50.0)}
    links = {"arm": ("O", "P"), "planet": ("P", "Q"), "ring": ("O", "R")}
    gears = (Gear("sun", ("ground", "planet"), ("O", "P"), (zs, zp), False, 30.0),
             Gear("rim", ("planet", "ring"), ("P", "O"), (zp, zr), True, 30.0))
    s = make_structure(points, links, ("O",), (), (Input("crank", "arm", "O"),), gears)
    assert s.mobility == 1
    linkage = Linkage.of(s)
    t = np.linspace(0.0, 2 * math.pi, 181)[:-1]
    sol = linkage.solve(t)
    # Willis: (w_ring - w_arm) / (w_sun - w_arm) = -zs / zr, w_sun = 0; the planet's (w_p - w_arm) / -w_arm = -zs / zp
    assert np.allclose(sol.omegas["ring"], 1 + zs / zr, rtol=0, atol=1e-12)
    assert np.allclose(sol.omegas["planet"], 1 + zs / zp, rtol=0, atol=1e-12)
    ring = np.remainder(sol.angle("ring") - (1 + zs / zr) * t + math.pi, 2 * math.pi) - math.pi
    assert np.max(np.abs(ring)) < 1e-12


def test_a_gear_whose_centres_drift_apart_is_refused():
    # a wheel pinned at a crank-rocker's B with a gear meshing one held at O2: no link holds both centres, and B's
    # distance from O2 changes as the crank turns
    points = {"O2": (0.0, 0.0), "A": (10.0, 17.320508076), "O4": (80.0, 0.0), "B": (72.221149669, 49.391188359),
              "W": (80.0, 60.0)}
    far = math.dist(points["O2"], points["B"])
    raw = {"name": "drift", "linkage": {
        "type": "linkage", "ground": ["O2", "O4"], "input": {"link": "crank", "pivot": "O2"},
        "joints": {k: list(v) for k, v in points.items()},
        "links": {"crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"], "wheel": ["B", "W"]},
        "gears": {"mesh": {"a": {"link": "ground", "centre": "O2", "teeth": 40},
                           "b": {"link": "wheel", "centre": "B", "teeth": 20}, "module": far / 30}}}}
    with pytest.raises(SpecError, match=r"^linkage\.gears\.mesh: no one link holds both centres O2 and B"):
        api.design(api.validate(raw))
    # the same wheel meshing a gear held at O4, which the rocker carries with B: kept
    raw["linkage"]["gears"]["mesh"] = {"a": {"link": "ground", "centre": "O4", "teeth": 30},
                                       "b": {"link": "wheel", "centre": "B", "teeth": 20}, "module": 2.0}
    a = api.design(api.validate(raw)).kinematics
    sol = a.sweep
    # the wheel turns with the rocker plus (-30 / 20) times the frame's turn relative to the rocker
    assert np.allclose(sol.omegas["wheel"], sol.omegas["rocker"] * (1 + 30 / 20), rtol=0, atol=1e-12)


RACK_TEMPLATE = """name = "rack"
[linkage]
type = "linkage"
ground = ["O2", "Q"]
input = {{ link = "crank", pivot = "O2" }}
[linkage.joints]
O2 = [0, 0]
A = [20, 0]
B = [80, 0]
Q = [80, 20]
T = [95, 20]
[linkage.links]
crank = ["O2", "A"]
rod = ["A", "B"]
pinion = ["Q", "T"]
[linkage.sliders.ram]
point = "B"
angle = 0
[linkage.racks.drive]
slider = "{slider}"
pinion = {{ link = "pinion", centre = "Q", teeth = 20 }}
module = 2.0
[parts]
width = 8.0
thickness = 3.0
pin_diameter = 3.0
"""


@pytest.mark.parametrize(("template", "sets", "message"), [
    ("rack", [], "linkage.racks.drive.slider: a rack rides on a slider: no slider 'nope' (sliders: ram)"),
    ("ram", ["linkage.racks.drive.module=2.1"], "linkage.racks.drive: the pinion's centre Q is drawn 20 mm from "
                                                 "the rack's pitch line, not its pitch radius m z / 2 = 21 mm"),
    ("fivebar", ["linkage.gears.mesh.module=1.6"], "linkage.gears.mesh: the drawing puts the centres O2 and O5 45 mm "
                                                   "apart, but teeth 40 and 20 mesh at 48 mm"),
    ("fivebar", ["linkage.gears.mesh.a.teeth=30", "linkage.gears.mesh.module=1.8"],
     "linkage.gears.mesh: with the crank input, link crank2 turns -3/2 times a turn of the input"),
    ("fivebar", ["linkage.gears.mesh.a.teeth=3"], "linkage.gears.mesh.a.teeth: must be >= 4"),
    ("fivebar", ["linkage.gears.mesh.b.link=\"left\""], "linkage.gears.mesh.b.centre: link 'left' does not hold 'O5'"),
    ("fivebar", ["linkage.gears.mesh.backlash=2"], "linkage.gears.mesh.backlash: must be > 0 and <= 0.589049 mm"),
])
@pytest.mark.parametrize("command", ["analyze", "build"])
def test_bad_input_is_one_line_naming_the_field(tmp_path, template, sets, message, command):
    from linkgen.cli import main

    if template != "fivebar":
        path = tmp_path / "rack.toml"
        path.write_text(RACK_TEMPLATE.format(slider="nope" if template == "rack" else template))
    else:
        path = FIVEBAR
    assert_refused_sets(path, sets, message, tmp_path, main, command)


def test_a_crank_that_turns_a_rack_away_is_refused_unless_its_range_is_one_turn(tmp_path):
    from linkgen.cli import main

    path = tmp_path / "pinion.toml"
    path.write_text(RACK_TEMPLATE.format(slider="ram").replace('link = "crank", pivot = "O2"',
                                                               'link = "pinion", pivot = "Q"'))
    text = path.read_text().replace('crank = ["O2", "A"]\nrod = ["A", "B"]\n', "").replace('A = [20, 0]\n', "")
    text = text.replace('ground = ["O2", "Q"]', 'ground = ["Q"]').replace("O2 = [0, 0]\n", "")
    path.write_text(text)
    assert_refused_sets(path, [], "linkage.racks.drive: the crank turns pinion pinion fully, so the rack would run "
                        "away", tmp_path, main, "analyze")
    spec = api.load(path, ["linkage.input.range=[0, 90]"])
    sol = api.design(spec).kinematics.sweep
    assert np.max(np.abs(sol.points["B"][:, 0] - 80.0 - 20.0 * sol.inputs[0])) < 1e-12


def _worst_overlap(layout, first: str, second: str) -> float:
    parts = {p.name: p for p in layout.parts}
    worst = 0.0
    for k in range(0, len(layout.sweep.angles[first]), 4):
        shapes = [shapely.Polygon(parts[n].outline().moved(layout.sweep.angles[n][k], layout.sweep.origins[n][k])
                                  .flatten(0.002)) for n in (first, second)]
        worst = max(worst, shapes[0].intersection(shapes[1]).area)
    return worst


def test_a_rack_and_its_pinion_are_parts_on_one_layer_that_never_overlap(tmp_path):
    path = tmp_path / "rack.toml"
    path.write_text(RACK_TEMPLATE.format(slider="ram"))
    design = api.design(api.load(path), parts=True)
    layers = design.build.layers
    assert layers["drive-rack"] == layers["pinion-gear"] and list(layers.values()).count(layers["drive-rack"]) == 2
    from linkgen.mechanisms.general import general_layout

    layout = general_layout(design.kinematics, design.spec.parts)
    assert _worst_overlap(layout, "drive-rack", "pinion-gear") < 1e-6
    # the pinion swings by the stroke over its pitch radius: 40 / 20 rad
    assert design.report["outputs"]["pinion"]["swing_deg"] == pytest.approx(math.degrees(2.0), abs=1e-9)


def test_the_parts_and_assembly_hold_the_gears_on_one_layer_that_never_overlap():
    design = api.design(api.load(FIVEBAR), parts=True)
    build = design.build
    names = [p.name for p in build.parts]
    assert {"crank-gear", "crank2-gear"} <= set(names)
    layers = build.layers
    assert layers["crank-gear"] == layers["crank2-gear"]
    assert sum(1 for v in layers.values() if v == layers["crank-gear"]) == 2       # alone on their layer
    # the gears' outlines in the assembly at every pose of the sweep: they mesh, never overlapping
    a = design.kinematics
    from linkgen.mechanisms.general import general_layout

    layout = general_layout(a, design.spec.parts)
    assert _worst_overlap(layout, "crank-gear", "crank2-gear") < 1e-6
    # and their centres stay on the pivots
    assert np.allclose(layout.sweep.origins["crank-gear"], [0.0, 0.0], atol=1e-9)
    assert np.allclose(layout.sweep.origins["crank2-gear"], [45.0, 0.0], atol=1e-9)
    # the assembly drawing carries both gears' outlines (the teeth: far more pieces than a bar's)
    outlines = [item for _, item in build.assembly.items if hasattr(item, "vertices") and len(item.vertices) > 100]
    assert len(outlines) >= 2 * len(layout.positions)


@pytest.mark.parametrize("key", ["slack", "dynamics"])
def test_slack_and_dynamics_are_refused_with_gears(tmp_path, key):
    from linkgen.cli import main

    path = tmp_path / "g.toml"
    path.write_text(FIVEBAR.read_text() + f"\n[{key}]\n")
    assert_refused_sets(path, [], f"{key}: a linkage with gears or racks takes no [{key}] yet", tmp_path, main,
                        "analyze")
