"""A machine's gear pairs as real involute gears (issue 35): each pair is linkgen's own gear-pair design, its gears
clash bodies on their plane, written with the machine's files, listed in its kit and placed in its assembly.

Cross-checks: the gears' outlines in the machine's DXF equal a standalone linkgen gear-pair template's (written here
by hand) to 1e-9 mm; the driven gear turns teeth-ratio times as fast as the driver's, the other way, as its shaft
does; the two gears placed at 720 main shaft angles never overlap and stay within the normal backlash of each other
(shapely); the contact ratio equals the textbook formula worked out here; bad values are one line naming
``gears[i].<field>``.
"""
from __future__ import annotations

import csv
import math
import tomllib

import numpy as np
import pytest
import shapely

from tests.conftest import ROOT
from tests.support.refusals import assert_refused

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-machine-gears")

TOY = ROOT / "templates" / "walking-toy.toml"


@pytest.fixture(scope="module")
def toy():
    from camgen import api

    return api.design(api.load(TOY))


def _raw() -> dict:
    return tomllib.loads(TOY.read_text(encoding="utf-8"))


def _gear_bodies(design):
    return [b for b in design.bodies if b.name.startswith("gears.")]


def test_speed_ratio_is_the_teeth_ratio(toy):
    """Each gear turns with its shaft: the driven gear's angle moves -z1/z2 times the driver's, as the legs' shaft
    turns (its turns per main turn), to 1e-12 rad."""
    gear = toy.gears[0]
    phi = np.linspace(0.0, 2 * math.pi, 361)
    driver, driven = gear.angles(phi)
    assert np.allclose(driver - driver[0], phi, rtol=0, atol=1e-12)               # the main shaft is the driver's
    assert np.allclose(driven - driven[0], -36 / 18 * phi, rtol=0, atol=1e-12)
    assert toy.spec.turns["legs"] == -36 / 18
    legs = next(m for m in toy.cranked if m.name == "left")
    assert legs.turns == gear.turns[1]


def test_the_gears_never_overlap_at_720_angles(toy):
    """The two gears' outlines, placed where the machine places them at 720 main shaft angles, never overlap, and
    come within the normal backlash j cos a_w of each other at every angle (they mesh, with play)."""
    from camgen.kinds.machine.clash import outlines

    a, b = _gear_bodies(toy)
    phi = np.arange(720) * (2 * math.pi / 720)
    pa, pb = outlines(a, phi), outlines(b, phi)
    assert not shapely.intersects(pa, pb).any()
    gap = shapely.distance(pa, pb)
    normal_backlash = 0.1 * math.cos(math.radians(20.0))                          # a_w = a: no shifts
    assert gap.min() > 0.0 and gap.max() <= normal_backlash
    assert toy.clashes == ()


def _standalone_cut_outlines():
    """A linkgen gear-pair template written by hand with the toy's gears: 36 teeth driving 18, module 1.5, 20
    degrees, backlash 0.1 mm, 6 mm thick, an 8 mm hole (the toy's shafts: no cam gives a bore), no kerf."""
    from linkgen import api

    raw = {"name": "standalone", "linkage": {"type": "gear-pair", "module": 1.5, "pressure_angle": 20.0,
                                             "backlash": 0.1, "pinion": {"teeth": 36}, "gear": {"teeth": 18}},
           "parts": {"width": 12.0, "thickness": 6.0, "pin_diameter": 8.0, "clearance": 0.0, "kerf": 0.0}}
    design = api.design(api.validate(raw), parts=True)
    cut = {p.name: p for p in design.build.cut}
    return cut["pinion"], cut["gear"]


def _bundled(bundled_builds):
    """The folder ``camgen build templates/walking-toy.toml`` wrote (shared with the golden test)."""
    from tests.support.golden import runs

    return bundled_builds.folder(TOY, *runs(TOY)[0])


def test_the_dxf_outlines_equal_the_standalone_gear_pair(bundled_builds):
    """Each gear's cut DXF (written by the machine, listed in its report's files) holds the standalone pair's
    outline, vertices and bulges, to 1e-9 mm, and its hole."""
    import json

    import ezdxf

    folder = _bundled(bundled_builds)
    files = json.loads((folder / "walking-toy.json").read_text())["files"]
    for stem, part in zip(("driver", "driven"), _standalone_cut_outlines(), strict=True):
        doc = ezdxf.readfile(folder / files[f"gears.crank-legs-{stem}_dxf"])
        lines = [e for e in doc.modelspace() if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == "OUTLINE"]
        assert len(lines) == 1
        got = np.array(lines[0].get_points("xyb"))
        want = np.column_stack([part.outline.vertices, part.outline.bulges])
        assert got.shape == want.shape
        assert np.abs(got - want).max() < 1e-9
        holes = [e for e in doc.modelspace() if e.dxftype() == "CIRCLE"]
        # each gear's hole is its shaft's: the hand crank's 8 mm (no part on it gives another), the legs' 3 mm
        # (the legs' cranks' pins, which their 8 mm width cannot bore larger)
        assert [round(h.dxf.radius, 12) for h in holes] == [{"driver": 4.0, "driven": 1.5}[stem]]


def test_the_report_gives_the_textbook_contact_ratio(bundled_builds):
    """The report's contact ratio equals (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - c sin a) / (pi m cos a), with
    ra = m (z/2 + 1) and rb = m z/2 cos a, to 1e-9; the speed ratio is -z1/z2; no warning."""
    import json

    folder = _bundled(bundled_builds)
    report = json.loads((folder / "walking-toy.json").read_text())
    entry = report["gears"][0]
    m, a, z1, z2 = 1.5, math.radians(20.0), 36, 18
    ra1, ra2 = m * (z1 / 2 + 1), m * (z2 / 2 + 1)
    rb1, rb2 = m * z1 / 2 * math.cos(a), m * z2 / 2 * math.cos(a)
    c = m * (z1 + z2) / 2
    ratio = (math.sqrt(ra1**2 - rb1**2) + math.sqrt(ra2**2 - rb2**2) - c * math.sin(a)) / (math.pi * m * math.cos(a))
    assert entry["contact_ratio"] == pytest.approx(ratio, abs=1e-9)
    assert entry["speed_ratio"] == pytest.approx(-z1 / z2, abs=1e-12)
    assert entry["name"] == "crank-legs" and entry["plane"] == 0 and entry["warnings"] == []
    assert not entry["driver_gear"]["undercut"] and not entry["driven_gear"]["undercut"]
    assert not [w for w in report["warnings"] if "gears" in w]
    with open(folder / "walking-toy-kit.csv", newline="", encoding="utf-8") as f:
        kit = {row["part"]: row for row in csv.DictReader(f)}
    assert kit["gear crank-legs-driver"]["size"].startswith("36 teeth, module 1.5 mm, 6 mm thick, 8 mm hole")
    assert kit["gear crank-legs-driven"]["size"].startswith("18 teeth, module 1.5 mm")


def test_the_assembly_and_the_figures_turn_the_gears(toy):
    """At the assembly angle (and at every figure angle) each gear's piece is its outline turned by the angle its
    shaft has then; in the assembly it stands on plane 0, on the frame plate, 6 mm thick."""
    from camgen.kinds.machine import assembly, poses

    gear = toy.gears[0]
    bodies = {b.name: b for b in _gear_bodies(toy)}
    pieces = {p.part.name: p for p in assembly.pieces(toy)}
    phi = math.radians(toy.spec.machine.assembly_angle)
    angles = gear.angles(np.array([phi]))
    for k, name in enumerate(("gears.crank-legs.driver", "gears.crank-legs.driven")):
        c, s = math.cos(angles[k][0]), math.sin(angles[k][0])
        want = bodies[name].outline @ np.array([[c, s], [-s, c]]) + gear.centres[k]
        piece = pieces[name]
        assert np.abs(piece.part.outline.vertices - want).max() < 1e-9
        assert piece.part.thickness == 6.0 and not piece.bought
        assert piece.z == pytest.approx(toy.frame.stack.bottom[0], abs=1e-12)
    figure_phi = np.radians(toy.spec.machine.figure_angles)
    placed = {p.name: p for p in poses.placed_parts(toy, figure_phi)}
    for k, member in enumerate(("driver", "driven")):
        turn = np.radians(placed[f"gears.crank-legs.{member}"].turn)
        assert np.abs(np.angle(np.exp(1j * (turn - gear.angles(figure_phi)[k])))).max() < 1e-9


def _with_gears(toy, change: dict, at: float | None = None):
    """The toy's design with its gears designed again from ``change`` (its legs as they are): the gears alone
    depend on it."""
    from dataclasses import replace

    from camgen import api
    from camgen.kinds.machine.machine_gears import designed

    raw = _raw()
    raw["gears"][0].update(change)
    if at is not None:
        raw["shafts"][0]["at"] = [at, 0.0]
    spec = api.validate(raw)
    return replace(toy, spec=spec, gears=designed(spec, toy.tolerance))


def test_a_gear_is_a_clash_body(toy):
    """Put on the front leg's second plane (layer 1: plane 2) the legs' gear meets the leg's links there: the clash
    check names the gear and a link of the left leg."""
    from camgen.kinds.machine import clash

    bodies, joints, _ = clash.machine_parts(_with_gears(toy, {"layer": 1}), one_plate=True)
    assert [(b.low, b.high) for b in bodies if b.name.startswith("gears.")] == [(2, 2), (2, 2)]
    second = [b for b in bodies if b.low <= 2 <= b.high]                      # what shares plane 2
    met = [c for c in clash.clashes(second, joints, 720) if "gears.crank-legs.driven" in (c.a, c.b)]
    assert met and all(other.startswith(("linkages.left.", "shafts.")) for c in met for other in (c.a, c.b)
                       if not other.startswith("gears."))


def test_a_hub_is_printed_and_placed(toy):
    """A hub (12 mm across, 4 mm high) stands on each printed gear (its STL 6 + 4 mm high) and fills the plane over
    the gears (plane 1) in the clash check, meeting its shaft."""
    from camgen.core.solids import checked_mesh
    from camgen.kinds.machine import clash
    from camgen.kinds.machine.machine_gears import gear_parts

    design = _with_gears(toy, {"hub_diameter": 12.0, "hub_height": 4.0})
    bodies, joints, _ = clash.machine_parts(design, one_plate=True)
    hubs = [b for b in bodies if b.name.endswith(".hub")]
    assert [(b.name, b.low, b.high) for b in hubs] == [("gears.crank-legs.driver.hub", 1, 1),
                                                       ("gears.crank-legs.driven.hub", 1, 1)]
    assert {(j.a, j.b) for j in joints if j.a.endswith(".hub")} == {("gears.crank-legs.driver.hub", "shafts.crank"),
                                                                    ("gears.crank-legs.driven.hub", "shafts.legs")}
    for _, _, printed in gear_parts(design):
        mesh = checked_mesh(printed)[0]
        assert mesh.vertices[:, 2].max() - mesh.vertices[:, 2].min() == pytest.approx(10.0, abs=1e-9)


@pytest.mark.parametrize("change, message", [
    ({"gears.0.backlash": 1.0}, "gears[0].backlash: must be > 0 and <= 0.589049 mm"),
    ({"gears.0.hub_diameter": 12.0}, "gears[0].hub_height: give both boss_diameter and boss_height"),
    ({"gears.0.hub_diameter": 30.0, "gears.0.hub_height": 4.0}, "gears[0].hub_diameter: a hub wider than shaft"),
    ({"gears.0.driven_shift": 0.8}, "gears[0].module: the shafts crank and legs lie 40.5 mm apart; these gears "
                                    "need 41.5971 mm"),
    ({"gears.0.name": "left"}, "gears[0].name: 'left' names a mount already"),
])
def test_bad_gears_are_refused(tmp_path, change, message):
    assert_refused(TOY, change, message, tmp_path)


def test_a_shifted_pair_meshes_at_its_working_distance(toy):
    """Shifts whose sum is not 0 mesh the pair at the working centre distance c = m (z1 + z2) / 2 cos a / cos a_w,
    inv a_w = inv a + 2 tan a (x1 + x2) / (z1 + z2) (a_w solved here by bisection): the shafts placed there are
    accepted, and the teeth still never overlap over 720 angles."""
    from camgen.kinds.machine.clash import outlines

    m, a, z1, z2, x1, x2 = 1.5, math.radians(20.0), 36, 18, 0.2, 0.3
    target = math.tan(a) - a + 2 * math.tan(a) * (x1 + x2) / (z1 + z2)
    lo, hi = a, 1.2
    for _ in range(200):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if math.tan(mid) - mid < target else (lo, mid)
    c = m * (z1 + z2) / 2 * math.cos(a) / math.cos(lo)
    design = _with_gears(toy, {"driver_shift": x1, "driven_shift": x2}, at=c)
    gear = design.gears[0]
    assert gear.pair.centre_distance == pytest.approx(c, abs=1e-9)
    from camgen.kinds.machine import clash

    bodies = [b for b in clash.machine_parts(design)[0] if b.name.startswith("gears.")]
    phi = np.arange(720) * (2 * math.pi / 720)
    pa, pb = outlines(bodies[0], phi), outlines(bodies[1], phi)
    assert not shapely.intersects(pa, pb).any()
    assert shapely.distance(pa, pb).max() <= 0.1 * math.cos(lo)


def _gears_of(change: dict, at: float):
    from camgen import api
    from camgen.kinds.machine.machine_gears import designed, warnings_of

    raw = _raw()
    raw["shafts"][0]["at"] = [at, 0.0]
    raw["gears"][0].update(change)
    return next(warnings_of(g) for g in designed(api.validate(raw), 0.01))


def test_an_undercut_gear_is_warned_of_naming_its_shift():
    """14 teeth at 20 degrees are undercut (fewer than 2 / sin^2 a = 17.1): a warning naming gears[0].driven_shift
    and the least shift 1 - z sin^2 a / 2 that avoids it; shifted by +0.2 (and the driver by -0.2, the same
    distance) it is cut whole."""
    a = math.radians(20.0)
    least = 1 - 14 * math.sin(a) ** 2 / 2
    found = _gears_of({"driver_teeth": 42, "driven_teeth": 14}, 42.0)
    assert found == [f"gears[0].driven_shift: the driven gear is undercut: 14 teeth at shift 0, fewer than the "
                     f"{2 / math.sin(a) ** 2:.4g} that shift cuts whole; a shift of {least:.4g} or more avoids it"]
    assert _gears_of({"driver_teeth": 42, "driven_teeth": 14, "driven_shift": 0.2, "driver_shift": -0.2}, 42.0) == []


def test_pointed_teeth_are_refused_naming_the_shift(tmp_path):
    assert_refused(TOY, {"gears.0.driven_teeth": 8, "gears.0.driven_shift": 0.8},
                   "gears[0].driven_shift: the teeth come to a point inside the tip circle", tmp_path)


def test_a_second_pair_on_one_shaft_takes_the_next_free_plane(toy):
    """A second pair on the crank's shaft (36 teeth driving 18 on a shaft 40.5 mm beyond it) cannot stand on plane 0,
    where the first pair's 36 teeth turn, nor on planes 1 to 3, where the front leg's links sweep into its tip
    circle: it takes plane 4, and its driven shaft turns -2 times a main turn."""
    from dataclasses import replace

    from camgen import api
    from camgen.kinds.machine import clash
    from camgen.kinds.machine.machine_gears import designed

    raw = _raw()
    raw["shafts"].append({"name": "idle", "at": [81.0, 0.0]})
    raw["gears"].append({"driver": "crank", "driven": "idle", "driver_teeth": 36, "driven_teeth": 18, "module": 1.5})
    spec = api.validate(raw)
    bodies = clash.machine_parts(replace(toy, spec=spec, gears=designed(spec, toy.tolerance)), one_plate=True)[0]
    assert [(b.name, b.low) for b in bodies if b.name.startswith("gears.")] == [
        ("gears.crank-legs.driver", 0), ("gears.crank-legs.driven", 0),
        ("gears.crank-idle.driver", 4), ("gears.crank-idle.driven", 4)]
    assert spec.turns["idle"] == -2.0
