"""One frame plate between a machine's two sides (issue 35 item 4): the bundled walking toy (a Jansen leg in front
of the plate, one behind it, ``frame = "one"``). Every hole of the plate is at its shaft or at a leg's frame pivot,
both worked here from the template's own numbers and read back from the plate's DXF; at 720 angles of the main shaft
every part meets no other (the plate among them, with its holes) except at its joints, heights taken from the
assembly and outlines from the kinematics; FreeCAD reads the assembly's STEP file with the back leg under the plate
and the front one over it; with two plates, the spacer at the legs' pivot is crossed by the front leg's rod, found
at the angle computed independently."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
import shapely

from tests.conftest import ROOT
from tests.support.machine_meetings import assert_meet_only_at_joints, freecad_boxes, spans

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-frame-back")

TOY = ROOT / "templates" / "walking-toy.toml"
ANGLE = 40.0
#: main shaft angles of the meeting check
PHI = np.arange(720) * (2 * math.pi / 720)


def _raw() -> dict:
    return tomllib.loads(TOY.read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def toy():
    from camgen import api

    raw = _raw()
    raw["machine"]["assembly_angle"] = ANGLE
    return api.design(api.validate(raw))


@pytest.fixture(scope="module")
def built(tmp_path_factory, toy):
    """The files of ``toy`` (its DXF, JSON, 3MF and STEP), written from the module's design: the bytes
    ``camgen build walking-toy.toml --set machine.assembly_angle=40 --set output.formats=[...]`` writes, without
    designing the toy a second time."""
    from camgen import api

    out = tmp_path_factory.mktemp("toy-frame")
    api.write(toy, out, formats=["dxf", "json", "3mf", "step"])
    return out


def test_the_toy_has_one_plate_and_builds_as_before(toy):
    """The toy asks for one plate; the frame adds no warning (the toy's are its legs' transmission angles) and no
    clash, and nothing goes unchecked."""
    raw = _raw()
    assert raw["machine"]["frame"] == "one" and toy.frame is not None and toy.frame.top is None
    assert toy.clashes == () and toy.unchecked == ()
    assert all("transmission angle" in w for w in toy.warnings), toy.warnings


def test_every_hole_of_the_plate_is_at_its_shaft_or_pivot_read_back_from_the_dxf(built):
    """The plate's holes (the DXF's HOLES layer): each shaft's at its ``at`` in a plain hole 0.2 mm over it (the
    legs' shaft as thick as its cranks' pin holes, ``parts.pin_diameter``; the hand crank's 8 mm, no cam or crank
    giving a bore) and the legs' frame pivot B (the leg's joint B relative to its crank's pivot O,
    on the legs' shaft: one M3 bolt through both legs, in its 3.4 mm clearance hole), to 1e-9 mm; nothing else."""
    import ezdxf

    raw = _raw()
    shafts = {s["name"]: s["at"] for s in raw["shafts"]}
    bore = {m["shaft"]: m["template"]["parts"]["pin_diameter"] for m in raw["linkages"]}
    assert bore == {"legs": 3.0}
    want = [(tuple(at), (bore.get(name, 8.0) + 0.2) / 2) for name, at in shafts.items()]
    pivots = set()
    for mount in raw["linkages"]:
        joints = mount["template"]["linkage"]["joints"]
        o, b = np.array(joints["O"]), np.array(joints["B"])
        pivots.add(tuple(np.array(shafts[mount["shaft"]]) + b - o))
    assert len(pivots) == 1                                     # both legs' B: one place
    want += [(p, 3.4 / 2) for p in pivots]
    doc = ezdxf.readfile(built / "walking-toy-frame.dxf")
    holes = [(tuple(e.dxf.center)[:2], e.dxf.radius) for e in doc.modelspace().query("CIRCLE[layer=='HOLES']")]
    assert len(holes) == len(want) == 3
    for centre, radius in want:
        near = [h for h in holes if math.dist(h[0], centre) <= 1e-9]
        assert len(near) == 1, (centre, holes)
        assert near[0][1] == pytest.approx(radius, abs=1e-9)


def test_at_720_angles_every_part_meets_no_other_but_at_its_joints(toy):
    """Heights from the assembly (each piece's z and thickness), outlines from the kinematics at 720 angles: two
    parts whose heights overlap meet only inside a joint's disc; the plate (its outline with its holes, at 0..t)
    meets only the pins and shafts, each in its hole (no area in common), and every leg's part lies wholly above or
    below it."""
    from camgen.kinds.machine import clash

    bodies, joints, _ = clash.machine_parts(toy, one_plate=True)
    span = spans(toy, bodies)
    checked = assert_meet_only_at_joints(bodies, joints, span, PHI)
    assert checked >= 20
    t = toy.spec.machine.frame_thickness
    plate = toy.frame.plate
    ring = shapely.Polygon(plate.outline.flatten(0.01),
                           [shapely.Point(c).buffer(d / 2, quad_segs=64).exterior.coords for c, d in plate.holes])
    through = []
    for body in bodies:
        z0, z1 = span[body.name]
        if z0 < t and z1 > 0:
            through.append(body.name)
            assert body.name.startswith(("pins.", "shafts.")), body.name
            area = shapely.area(shapely.intersection(clash.outlines(body, PHI), ring))
            assert area.max() < 1e-6, body.name
        else:
            assert z1 <= 0 or z0 >= t, body.name
    assert sorted(through) == ["pins.0", "shafts.crank", "shafts.legs"]       # the crank's shaft carries its gear


def test_freecad_reads_the_assembly_with_the_back_leg_under_the_plate(built, toy):
    """FreeCAD reads the STEP file's solids, one a piece, valid, of the pieces' volumes; the plate's solid spans
    0..t, the back leg's parts lie wholly under its bottom face and the front leg's over its top face, by a
    plane's gap (1 mm) at least; the pivot pin and the legs' shaft cross it."""
    box = freecad_boxes(toy, built / "walking-toy-assembly.step")
    t = toy.spec.machine.frame_thickness
    assert box["frame"][2] == pytest.approx(0.0, abs=1e-6) and box["frame"][5] == pytest.approx(t, abs=1e-6)
    back = [name for name in box if name.startswith("linkages.right.")]
    front = [name for name in box if name.startswith("linkages.left.")]
    assert len(back) == len(front) == 7
    assert all(box[n][5] <= -1.0 + 1e-6 for n in back), {n: box[n][5] for n in back}
    assert all(box[n][2] >= t + 1.0 - 1e-6 for n in front), {n: box[n][2] for n in front}
    for name in ("pins.0", "shafts.legs"):
        assert box[name][2] < -1.0 and box[name][5] > t + 1.0, (name, box[name])


def test_the_bill_of_materials_gives_the_shaft_and_pin_through_both_sides(toy):
    """The legs' shaft runs from the back crank's bottom face (no stub there: the back leg's rods cross its axis
    under it) to the front crank's top (its length in the bill that long), the pivot bolt through the links at B
    on both sides, long enough for its grip."""
    from camgen.kinds.machine import assembly
    from camgen.kinds.machine.framekit import bom

    pieces = {p.part.name: p for p in assembly.pieces(toy)}
    lines = {line.item: line for line in bom(toy.frame, toy)}
    shaft = pieces["shafts.legs"]
    assert f"{math.ceil(shaft.part.thickness):g} mm long" in lines["shaft legs"].size
    back, front = pieces["linkages.right.crank"], pieces["linkages.left.crank"]
    assert shaft.z == pytest.approx(back.z, abs=1e-9)
    assert shaft.z + shaft.part.thickness == pytest.approx(front.z + front.part.thickness, abs=1e-9)
    # the pin through both legs' links at B (from the template's links), from the lowest back one to the top front
    links = _raw()["linkages"][0]["template"]["linkage"]["links"]
    at_b = [name for name, joints in links.items() if "B" in joints]
    pin = pieces["pins.0"]
    assert pin.z == pytest.approx(min(pieces[f"linkages.right.{n}"].z for n in at_b), abs=1e-9)
    top = max(pieces[f"linkages.left.{n}"].z + pieces[f"linkages.left.{n}"].part.thickness for n in at_b)
    assert pin.z + pin.part.thickness == pytest.approx(top, abs=1e-9)
    bolt = [line for line in lines.values() if "pins.0" in line.size]
    length = int(bolt[0].item.split(" x ")[1].split()[0])
    assert len(bolt) == 1 and bolt[0].item.startswith("M3 x ") and length >= pin.part.thickness


def _rod_k_gap(deg: float) -> float:
    """The front leg's rod A-D (8 mm wide, round ends) less its reach to a spacer's edge (9.2 mm across: the 3 mm
    pin + 0.2 mm play + two 3 mm walls) at the frame pivot B, at main shaft angle ``deg`` (mm; negative: they
    overlap). The legs' shaft turns twice the other way (36 teeth to 18); A from its drawing angle of 90 degrees,
    D by the circle intersection |D - A| = 61.9, |D - B| = 39.3 on the drawing's side of A -> B."""
    b, d0 = np.array([-38.0, -7.8]), np.array([-20.995300643, -43.23063928])
    t = math.pi / 2 - 2 * math.radians(deg)
    a = 15.0 * np.array([math.cos(t), math.sin(t)])
    dist = float(np.linalg.norm(b - a))
    along = (61.9**2 - 39.3**2 + dist * dist) / (2 * dist)
    u = (b - a) / dist
    normal = np.array([-u[1], u[0]])
    (ux, uy), (vx, vy) = b - np.array([0.0, 15.0]), d0 - np.array([0.0, 15.0])
    side = math.copysign(1.0, float(ux * vy - uy * vx))
    d = a + along * u + side * math.sqrt(61.9**2 - along**2) * normal
    w = d - a
    x = min(max(float((b - a) @ w / (w @ w)), 0.0), 1.0)
    return float(np.linalg.norm(a + x * w - b)) - (4.0 + 9.2 / 2)


def test_two_plates_put_a_spacer_at_the_legs_pivot_which_the_front_rod_crosses():
    """With two plates the pin at B (both legs' pivot) carries front links, so a spacer stands on it from the front
    leg's B links up to the top plate; the front leg's rod A-D, on the plane over them, sweeps across B: the check
    names that clash (and no other) within 0.1 degree of the angle found here independently."""
    from scipy.optimize import brentq

    from camgen import api

    raw = _raw()
    raw["machine"]["frame"] = "two"
    made = api.design(api.validate(raw))
    assert [sp.pin for sp in made.frame.spacers] == ["pins.0"]
    grid = np.arange(0.0, 360.0, 0.5)
    gaps = np.array([_rod_k_gap(x) for x in grid])
    k = int(np.argmax((gaps < 0) & (np.roll(gaps, 1) >= 0)))
    expected = brentq(_rod_k_gap, grid[k - 1], grid[k], xtol=1e-10)
    assert len(made.clashes) == 1
    met = made.clashes[0]
    assert {met.a, met.b} == {"linkages.left.rod_k", "spacers.0"}
    assert abs(met.angle_deg - expected) <= 0.1, (met.angle_deg, expected)
