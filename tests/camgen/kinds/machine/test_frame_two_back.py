"""Two frame plates with a linkage behind the lower one (issue 35 item 4): the bundled automaton (three cams and a
four-bar in front, ``frame = "two"``) with a crank-rocker on the back of its camshaft (``side = "back"``). The
back linkage's crank rides the camshaft through the bottom plate and its rocker's pivot comes up through the bottom
plate from below; the spacers stand only round the pins that carry a front part, the top plate holds those and the
pins hanging from it. Read back: the plates' holes from their DXFs, every part at 720 angles meeting no other (both
plates among them, with their holes) but at its joints, heights from the assembly; FreeCAD reads the assembly's STEP
with the back parts under the lower plate, the front ones between the plates."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
import shapely

from tests.conftest import ROOT
from tests.support.machine_meetings import assert_meet_only_at_joints, freecad_boxes, spans

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-frame-two-back")

AUTOMATON = ROOT / "templates" / "automaton.toml"
#: the back crank-rocker (mm, its drawing = the machine's frame, O = PIVOT on the camshaft): crank O-A, rod A-B,
#: rocker B-C
PIVOT, A, C = np.array([0.0, 0.0]), np.array([12.0, 0.0]), np.array([0.0, -75.0])
ROD, ROCKER, PIN = 70.0, 55.0, 4.0
ANGLE = 30.0
#: main shaft angles of the meeting check
PHI = np.arange(720) * (2 * math.pi / 720)


def _rocker_pin() -> np.ndarray:
    """B: |B - A| = ROD, |B - C| = ROCKER, on the left of A -> C (a circle intersection)."""
    d = float(np.linalg.norm(C - A))
    a = (ROD**2 - ROCKER**2 + d * d) / (2 * d)
    u = (C - A) / d
    return A + a * u + math.sqrt(ROD**2 - a * a) * np.array([-u[1], u[0]])


def _raw() -> dict:
    raw = tomllib.loads(AUTOMATON.read_text(encoding="utf-8"))
    raw["machine"]["assembly_angle"] = ANGLE
    b = _rocker_pin()
    raw["linkages"].append({
        "name": "back", "shaft": "camshaft", "side": "back",
        "template": {"linkage": {"type": "linkage", "ground": ["O", "C"], "input": {"link": "crank", "pivot": "O"},
                                 "tracers": ["B"],
                                 "joints": {"O": PIVOT.tolist(), "A": A.tolist(), "B": [round(float(v), 9) for v in b],
                                            "C": C.tolist()},
                                 "links": {"crank": ["O", "A"], "rod": ["A", "B"], "rocker": ["B", "C"]}},
                     "parts": {"width": 8.0, "thickness": 3.0, "pin_diameter": PIN}}})
    return raw


@pytest.fixture(scope="module")
def machine():
    from camgen import api

    return api.design(api.validate(_raw()))


@pytest.fixture(scope="module")
def built(machine, tmp_path_factory):
    from camgen import api

    out = tmp_path_factory.mktemp("two-back")
    api.write(machine, out, formats=["dxf", "json", "3mf", "step"])
    return out


def test_two_plates_carry_a_back_linkage_without_a_clash(machine):
    """Two plates, no clash, nothing unchecked; the back linkage's parts on planes under the frame; its rocker's
    pivot a pin of the bottom plate alone (no spacer: it carries nothing in front), the camshaft in the bottom plate
    alone, reaching down to the back crank; a spacer round every pin that stands on the bottom plate and carries a
    front part, and none elsewhere."""
    f = machine.frame
    assert f is not None and f.top is not None
    assert machine.clashes == () and machine.unchecked == ()
    bodies = {b.name: b for b in machine.bodies}
    back = [n for n in bodies if n.startswith("linkages.back.")]
    assert sorted(back) == ["linkages.back.crank", "linkages.back.rocker", "linkages.back.rod"]
    assert all(bodies[n].high < 0 for n in back)
    pivot = next(s for s in f.seats if math.dist(s.centre, C) < 1e-9)
    assert pivot.bottom and not pivot.top and pivot.diameter == PIN
    assert pivot.name not in {sp.pin for sp in f.spacers}
    shaft = next(s for s in f.seats if s.name == "shafts.camshaft")
    assert shaft.bottom and not shaft.top
    assert bodies["shafts.camshaft"].low == bodies["linkages.back.crank"].low
    standing = {s.name for s in f.seats if s.name.startswith("pins.") and s.bottom and bodies[s.name].high > 0}
    assert standing and {sp.pin for sp in f.spacers} == standing


def _holes(path) -> list[tuple[tuple[float, float], float]]:
    import ezdxf

    doc = ezdxf.readfile(path)
    return [(tuple(e.dxf.center)[:2], e.dxf.radius) for e in doc.modelspace().query("CIRCLE[layer=='HOLES']")]


def test_the_plates_holes_read_back_from_their_dxfs(built, machine):
    """The bottom plate has the camshaft's plain hole (8 mm shaft + 0.2 mm) at (0, 0) and the back rocker's pivot's
    M4 clearance hole (4.5 mm) at C, to 1e-9 mm; the top plate has neither; each plate's holes are at the seats it
    holds."""
    bottom, top = _holes(built / "automaton-frame.dxf"), _holes(built / "automaton-frame-top.dxf")
    for centre, radius in ((tuple(PIVOT), 8.2 / 2), (tuple(C), 4.5 / 2)):
        near = [h for h in bottom if math.dist(h[0], centre) <= 1e-9]
        assert len(near) == 1 and near[0][1] == pytest.approx(radius, abs=1e-9), (centre, bottom)
        assert not [h for h in top if math.dist(h[0], centre) < 5.0], (centre, top)
    seats = machine.frame.seats
    for holes, held in ((bottom, [s for s in seats if s.bottom]), (top, [s for s in seats if s.top])):
        assert len(holes) == len(held)
        for s in held:
            assert any(math.dist(h[0], s.centre) <= 1e-9 and h[1] == pytest.approx(s.hole / 2, abs=1e-9)
                       for h in holes), s.name


def test_at_720_angles_every_part_meets_no_other_but_at_its_joints(machine):
    """Heights from the assembly, outlines from the kinematics at 720 angles: two parts whose heights overlap meet
    only inside a joint's disc; each plate (its outline with its holes) meets only the pins, shafts and spacers
    that cross its height, each in its hole, and every moving part lies wholly above, below or between them."""
    from camgen.kinds.machine import assembly, clash, frame

    bodies, joints = frame.with_top_plate(*clash.machine_parts(machine)[:2])
    span = spans(machine, bodies)
    checked = assert_meet_only_at_joints(bodies, joints, span, PHI)
    assert checked >= 15
    t = machine.spec.machine.frame_thickness
    crossing = {}
    plates = {p.part.name: p.z for p in assembly.pieces(machine)}
    for plate in machine.frame.plates:
        z = plates[plate.name]
        ring = shapely.Polygon(plate.outline.flatten(0.01),
                               [shapely.Point(c).buffer(d / 2, quad_segs=64).exterior.coords for c, d in plate.holes])
        crossing[plate.name] = []
        for body in bodies:
            z0, z1 = span[body.name]
            if z0 < z + t - 1e-9 and z1 > z + 1e-9:
                crossing[plate.name].append(body.name)
                assert body.name.startswith(("pins.", "shafts.")), (plate.name, body.name)
                area = shapely.area(shapely.intersection(clash.outlines(body, PHI), ring))
                assert area.max() < 1e-6, (plate.name, body.name)
    held = {s.name for s in machine.frame.seats if s.top}
    assert sorted(crossing["frame-top"]) == sorted(held)
    assert "shafts.camshaft" in crossing["frame"] and "shafts.camshaft" not in crossing["frame-top"]


def test_freecad_reads_the_assembly_with_the_back_parts_under_the_lower_plate(built, machine):
    """FreeCAD reads one valid solid a piece, of the pieces' volumes; the lower plate spans 0..t, the back linkage's
    parts lie wholly under it by a plane's gap (1 mm) at least, every front moving part between the plates' faces
    by that gap, the spacers from a part's top to the top plate's bottom face; the back pivot's pin and the camshaft
    cross the lower plate."""
    box = freecad_boxes(machine, built / "automaton-assembly.step")
    t = machine.spec.machine.frame_thickness
    assert box["frame"][2] == pytest.approx(0.0, abs=1e-6) and box["frame"][5] == pytest.approx(t, abs=1e-6)
    roof = box["frame-top"][2]
    assert box["frame-top"][5] == pytest.approx(roof + t, abs=1e-6)
    back = [n for n in box if n.startswith("linkages.back.")]
    front = [n for n in box if n.startswith(("cams.", "linkages.arm-bars."))]
    assert len(back) == 3 and len(front) == 11 + 3              # with the rollers' axles, between the plates too
    assert all(box[n][5] <= -1.0 + 1e-6 for n in back), {n: box[n][5] for n in back}
    assert all(box[n][2] >= t + 1.0 - 1e-6 and box[n][5] <= roof - 1.0 + 1e-6 for n in front)
    spacers = [n for n in box if n.startswith("spacers.")]
    assert spacers and all(box[n][5] == pytest.approx(roof, abs=1e-6) and box[n][2] > t for n in spacers)
    pivot = next(s.name for s in machine.frame.seats if math.dist(s.centre, C) < 1e-9)
    for name in (pivot, "shafts.camshaft"):
        assert box[name][2] < -1.0 and box[name][5] > t + 1.0, (name, box[name])
    assert box[pivot][5] < roof                                 # it stands in the lower plate only
