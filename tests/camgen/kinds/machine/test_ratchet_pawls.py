"""A machine ratchet's pawls as placed parts (issue 35): each pawl's nose on a tooth's tip where it drives or holds,
its drawn gap off the teeth everywhere, its pin where the kinematics puts it (the arm's on the arm, the holding
pawl's in the frame plate's DXF and the kit), and a clash with a lever built on purpose found where a scan finds
it."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from camgen import api
from camgen.cli import main as camgen
from camgen.kinds.machine import clash
from camgen.kinds.machine.spec import MachineSpec
from linkgen.mechanisms.ratchet import NOSE_GAP_MM
from tests.conftest import ROOT

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-ratchet-pawls")

EXAMPLE = ROOT / "templates" / "ratchet-counter.toml"
PHI = np.arange(720) * (2 * math.pi / 720)


def _design(phase: float | None = None):
    raw = tomllib.loads(EXAMPLE.read_text())
    if phase is not None:
        raw["cams"][0]["phase"] = phase
    return api.design(MachineSpec.model_validate(raw))


def _placed(body, phi, points):
    m, t = body.place(phi)
    return np.einsum("nij,mj->nmi", m, np.asarray(points, float)) + np.asarray(t)[:, None, :]


@pytest.mark.parametrize("phase", [0.0, 260.0])
def test_each_pawl_bears_on_a_tooth_tip_where_it_drives_or_holds(phase):
    """Where the wheel turns (its rate > 0, and the one sample where the arm starts it from rest) the arm's pawl's
    contact C (linkgen's, at the tooth's tip) is a placed tooth's tip, to 1e-9 mm, and more than 0.1 mm off one
    elsewhere; where it is still, the holding pawl's is. At all 720 angles each pawl lies its drawn nose gap,
    0.05 mm, off the teeth (to 1e-8 mm): riding over them, never into them."""
    design = _design(phase)
    r = design.ratchets[0]
    bodies = {b.name: b for b in design.bodies}
    wheel = bodies["ratchets.index.wheel"]
    tips = _placed(wheel, PHI, wheel.outline[1::2])                        # each tooth's tip, after its face's root
    pawl = r.table.holding_pawl
    local = pawl.contact - pawl.pivot                                       # C in the pawl's frame (its pin at 0)
    turning = r.driving_at(PHI)                          # the arm's pawl drives: the wheel turns, but where it
    assert np.all(turning[r.rate > 0]) and np.count_nonzero(turning & (r.rate == 0)) <= 1   # starts at rest
    assert 100 < np.count_nonzero(turning) < 600
    for name, bears in (("lever-pawl", turning), ("pawl", ~turning)):
        body = bodies[f"ratchets.index.{name}"]
        c = _placed(body, PHI, [local])[:, 0]
        nearest = np.min(np.hypot(*(tips - c[:, None, :]).transpose(2, 0, 1)), axis=1)
        assert nearest[bears].max() <= 1e-9, name
        assert nearest[~bears].min() > 0.1, name                            # riding, or dropped in, elsewhere
        gap = shapely.distance(clash.outlines(body, PHI), clash.outlines(wheel, PHI))
        assert np.abs(gap - NOSE_GAP_MM).max() <= 1e-8, name


def test_the_arm_pawl_pin_rides_on_the_arm_and_the_holding_pawl_pin_stands_still():
    """The arm's pawl's pin is on the arm's line |P| out from its pivot at every angle (P linkgen's pivot: the
    contact (0, 30) plus 24 mm along the tangent, |P| = sqrt(24^2 + 30^2)), to 1e-9 mm; the holding pawl's pin is a
    frame pin of the clash check (a pins.* body) at one place over the turn, |P| from the wheel's axis."""
    design = _design()
    bodies = {b.name: b for b in design.bodies}
    arm = bodies["cams.rocker.arm"]
    m, pivot = arm.place(PHI)
    pin = bodies["ratchets.index.lever-pawl"].place(PHI)[1]
    along = np.einsum("nji,nj->ni", m, pin - pivot)
    reach = math.hypot(24.0, 30.0)
    assert np.abs(along - [reach, 0.0]).max() <= 1e-9
    assert any(abs(c[0] - reach) <= 1e-9 for c, _ in arm.holes)            # the arm's hole for it
    held = bodies["ratchets.index.pawl"].place(PHI)[1]
    assert np.ptp(held, axis=0).max() == 0.0
    assert abs(math.dist(held[0], pivot[0]) - reach) <= 1e-9
    frame_pins = [b for b in design.bodies if b.name.startswith("pins.")]
    assert sum(math.dist(b.place(PHI[:1])[1][0], held[0]) <= 1e-9 for b in frame_pins) == 1


def test_a_lever_crossing_the_holding_pawl_is_found_where_a_scan_finds_it():
    """A lever 25 mm long, 2 mm wide, turning with the main shaft about a point 25 mm from the holding pawl's pin
    (off the pawl's bar, away from the wheel), pointing at the pin at 250 degrees: the clash check (720 samples)
    finds it first meeting the pawl within 0.1 degree of the first angle of a 0.01-degree scan at which shapely
    finds their outlines overlapping by more than the check's area tolerance. The wheel is held there (from 150 to
    415 degrees with phase 0), so the pawl stands still over the scan."""
    design = _design(0.0)
    pawl = next(b for b in design.bodies if b.name == "ratchets.index.pawl")
    m, pin = pawl.place(np.array([0.0]))
    pin = pin[0]
    bar_dir = m[0] @ (design.ratchets[0].table.holding_pawl.contact - design.ratchets[0].table.holding_pawl.pivot)
    normal = np.array([-bar_dir[1], bar_dir[0]]) / np.hypot(*bar_dir)
    wheel_axis = next(b for b in design.bodies if b.name == "ratchets.index.wheel").place(np.zeros(1))[1][0]
    if normal @ (pin - wheel_axis) < 0:
        normal = -normal                                                    # away from the wheel
    centre = pin + 25.0 * normal
    at = math.atan2(-normal[1], -normal[0])                                 # the lever's angle pointing at the pin
    offset = at - math.radians(250.0)
    outline = clash.bar(25.0, 1.0)

    def place(phi):
        return clash.rotation(np.asarray(phi) + offset), np.broadcast_to(centre, (len(phi), 2))

    lever = clash.Body("lever", pawl.low, pawl.high, outline, place)
    found = clash.clashes([pawl, lever], [], 720)
    assert len(found) == 1 and {found[0].a, found[0].b} == {"lever", "ratchets.index.pawl"}
    scan = np.radians(np.arange(150.0, 250.0, 0.01))
    still = pawl.place(scan)
    assert np.abs(still[0] - m[0]).max() <= 1e-9 and np.abs(still[1] - pin).max() <= 1e-9
    fixed = shapely.Polygon(_placed(pawl, np.array([0.0]), pawl.outline)[0])
    c, s = np.cos(scan + offset), np.sin(scan + offset)
    levers = shapely.polygons(np.einsum("nij,mj->nmi", np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2),
                                        outline) + centre)
    hit = shapely.area(shapely.intersection(levers, fixed)) > clash.AREA_TOL_MM2
    assert not hit[0] and hit.any()
    first = math.degrees(scan[int(np.argmax(hit))])
    assert 150.0 < first < 250.0
    assert abs(found[0].angle_deg - first) <= 0.1


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("pawls")
    result = CliRunner().invoke(camgen, ["build", str(EXAMPLE), "-o", str(out), "--set",
                                         'output.formats=["dxf", "json"]'])
    assert result.exit_code == 0, result.output
    return out


def test_the_frame_dxf_has_the_holding_pawls_pin_hole_and_the_kit_its_bolts(built):
    """The frame plate's DXF has a hole centred on the holding pawl's pin (to 1e-9 mm), of the M4's ISO 273 medium
    clearance hole (4.5 mm, the kerf taken off); the kit lists a bolt for it and one for the arm's pawl's pin; the
    assembly has both pawls, on the wheel's plane, and that pin among its bought parts."""
    import json

    import ezdxf

    design = _design()
    pin = next(b for b in design.bodies if b.name == "ratchets.index.pawl").place(np.zeros(1))[1][0]
    doc = ezdxf.readfile(built / "ratchet-counter-frame.dxf")
    holes = [(c.dxf.center.x, c.dxf.center.y, c.dxf.radius) for c in doc.modelspace().query("CIRCLE")
             if c.dxf.layer == "HOLES"]
    at = [h for h in holes if math.hypot(h[0] - pin[0], h[1] - pin[1]) <= 1e-9]
    assert len(at) == 1
    report = json.loads((built / "ratchet-counter.json").read_text())
    kerf = report.get("frame", {}).get("allowances", {}).get("kerf_mm")
    seat = next(s for s in report["frame"]["seats"] if math.hypot(s["x_mm"] - pin[0], s["y_mm"] - pin[1]) <= 1e-6)
    assert seat["nominal_mm"] == 4.5 and abs(2 * at[0][2] - seat["cut_mm"]) <= 1e-9 and kerf is not None
    bom = report["frame"]["bom"]
    text = json.dumps(bom)
    assert f"pivot pin {seat['name']} at ({pin[0]:.4g}, {pin[1]:.4g}) mm" in text
    assert "arm's pawl pin ratchets.index.pin at (" in text
    pieces = {p["name"]: p for p in report["assembly"]["pieces"]}
    assert {"ratchets.index.pawl", "ratchets.index.lever-pawl", "ratchets.index.wheel"} <= set(pieces)
    assert pieces["ratchets.index.pin"]["bought"] and not pieces["ratchets.index.pawl"]["bought"]
    assert pieces["ratchets.index.pawl"]["z_mm"] == pieces["ratchets.index.wheel"]["z_mm"]
