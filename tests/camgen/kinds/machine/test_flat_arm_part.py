"""An oscillating flat face's arm is a made part (:mod:`camgen.kinds.machine.flat_arm_part`): a machine whose flat
face drives a four-bar wrote no file for the four-bar's crank (the arm is the crank, and the arm was no part). Its
exact outline (lines and arcs) against the union of its rectangle and its ears' discs made by shapely, grown either
way, either side, with ears apart and overlapping; the part the machine writes: its holes the clash body's, its
outline the body's within the chord tolerance, its DXF read back by ezdxf at the kerf's growth, its STL a closed
solid of its area times its thickness, listed in the report."""
from __future__ import annotations

import json

import numpy as np
import pytest
import shapely

from camgen.kinds.machine.flat_arm_part import FlatArmPart
from tests.camgen.kinds.machine.test_flat_arm_four_bar import CRANK, _raw

pytestmark = pytest.mark.xdist_group("machine-flat-arm-part")     # one worker designs and writes the machine once


def _union(part: FlatArmPart, grow: float) -> shapely.Polygon:
    """The rectangle grown by ``grow`` on every side and each ear's disc by ``grow`` in radius, by shapely (discs
    of 8,192 chords)."""
    lo, hi = (-grow, part.depth + grow) if part.side > 0 else (-part.depth - grow, grow)
    discs = [shapely.Point(c).buffer(e + grow, quad_segs=2048) for (c, _), e in zip(part.holes, part.ears,
                                                                                    strict=True)]
    return shapely.union_all([shapely.box(-grow, lo, part.far + grow, hi), *discs])


CASES = {"apart": ((((0.0, 0.0), 4.5), ((40.0, 0.0), 3.4)), (4.25, 3.7)),
         "overlapping": ((((0.0, 0.0), 4.5), ((7.0, 0.0), 3.4)), (4.25, 3.7)),
         "pivot only": ((((0.0, 0.0), 4.5),), (4.25,)),
         "past the end": ((((0.0, 0.0), 4.5), ((30.0, 0.0), 3.4), ((98.0, 0.0), 4.5)), (4.25, 3.7, 4.25))}


@pytest.mark.parametrize("side", [1.0, -1.0])
@pytest.mark.parametrize("grow", [0.0, 0.1, -0.1, 0.5])
@pytest.mark.parametrize("case", list(CASES))
def test_the_outline_is_the_union_of_its_rectangle_and_ears(case, grow, side):
    """Its area in closed form (arcs exact) within 1e-4 mm^2 of shapely's union (whose 8,192-chord discs lose
    about 3e-5 mm^2 each), the two shapes differing by less than 5e-3 mm^2 (the chords of both), counter-clockwise;
    an ear past the far end lengthens the arm to the ear's edge."""
    holes, ears = CASES[case]
    part = FlatArmPart("lift-arm", 100.0, side, 8.0, holes, ears, 6.0, 0.01)
    contour = part.contour(grow)
    exact = _union(part, grow)
    drawn = shapely.Polygon(contour.flatten(1e-4))
    assert contour.area == pytest.approx(exact.area, abs=1e-4)
    assert drawn.is_valid and drawn.exterior.is_ccw
    assert drawn.symmetric_difference(exact).area < 5e-3
    assert part.far == (102.25 if case == "past the end" else 100.0)


def test_an_ear_behind_the_pivot_is_refused():
    with pytest.raises(ValueError, match="behind"):
        FlatArmPart("a", 100.0, 1.0, 8.0, (((0.0, 0.0), 4.5), ((2.0, 0.0), 3.4)), (4.25, 3.7), 6.0, 0.01)


def _bulged_area(xyb: np.ndarray) -> float:
    """A closed LWPOLYLINE's area (mm^2) from its vertices and bulges: the polygon's shoelace plus each arc's
    segment, r^2 (theta - sin theta) / 2 for an arc of included angle theta = 4 atan(bulge) on its chord."""
    x, y, b = xyb.T
    polygon = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    chord = np.hypot(np.roll(x, -1) - x, np.roll(y, -1) - y)
    theta = 4 * np.arctan(b)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(b != 0, chord / (2 * np.sin(np.abs(theta) / 2)), 0.0)
    return polygon + float(np.sum(np.sign(theta) * r**2 * (np.abs(theta) - np.sin(np.abs(theta))) / 2))


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """The flat face driving a four-bar, written with DXF, STL and the kit."""
    from camgen import api

    raw = _raw(1)
    raw["output"] = {"formats": ["dxf", "stl", "json"], "kerf": 0.2}
    design = api.design(api.validate(raw))
    folder = tmp_path_factory.mktemp("flat-arm")
    api.write(design, folder)
    return design, folder


def test_the_machine_writes_the_arm_with_the_body_s_holes_and_outline(written):
    """The arm's part carries the clash body's holes (its pivot pin's at the origin, the crank pin's ``crank`` mm
    out on the face's line); the body's outline is the part's split into chords within the cam's tolerance."""
    from camgen.kinds.machine.follower_parts import follower_parts

    design, _ = written
    [arm] = [p for p in follower_parts(design) if p.body == "cams.lift.arm"]
    body = next(b for b in design.bodies if b.name == "cams.lift.arm")
    assert [c for c, _ in arm.plate.holes] == [(0.0, 0.0), (CRANK, 0.0)]
    assert [d for _, d in arm.plate.holes] == pytest.approx([2 * r for _, r in body.holes], abs=1e-12)
    exact = shapely.Polygon(arm.plate.outline.flatten(1e-5))
    chords = shapely.Polygon(body.outline)
    assert chords.symmetric_difference(exact).area < 0.01 * exact.length         # within a band of the tolerance
    assert shapely.hausdorff_distance(exact.exterior, chords.exterior) < 0.01 + 1e-9


def test_the_arm_s_files_read_back(written):
    """The DXF's outline (ezdxf's vertices and bulges, its area worked here from them) encloses the part grown by
    half the kerf (0.1 mm) to 1e-6 mm^2; its holes are the nominal ones less the kerf; the STL is a closed solid
    whose volume is the outline's area less its holes times the arm's thickness (0.5 %: the printer's clearance and
    the bed face's chamfer); the report's ``followers`` lists it with its two holes."""
    import ezdxf
    import trimesh

    design, folder = written
    from camgen.kinds.machine.follower_parts import follower_parts

    [arm] = [p for p in follower_parts(design) if p.body == "cams.lift.arm"]
    [dxf] = list(folder.rglob("barred-lift-arm.dxf"))
    polylines = list(ezdxf.readfile(dxf).modelspace().query("LWPOLYLINE"))
    areas = sorted((_bulged_area(np.array(list(p.get_points("xyb")))) for p in polylines), reverse=True)
    assert areas[0] == pytest.approx(arm.plate.contour(0.1).area, abs=1e-6)
    circles = sorted(2 * c.dxf.radius for c in ezdxf.readfile(dxf).modelspace().query("CIRCLE"))
    assert circles == pytest.approx(sorted(d - 0.2 for _, d in arm.plate.holes), abs=1e-9)
    [stl] = list(folder.rglob("barred-lift-arm.stl"))
    mesh = trimesh.load(stl)
    assert mesh.is_watertight
    solid = arm.plate.contour(0.0).area - sum(np.pi * d**2 / 4 for _, d in arm.plate.holes)
    assert mesh.volume == pytest.approx(solid * arm.plate.thickness, rel=5e-3)    # the clearance, the foot's chamfer
    report = json.loads((folder / "barred.json").read_text())
    [listed] = [f for f in report["followers"] if f["name"] == "lift-arm"]
    assert listed["body"] == "cams.lift.arm" and len(listed["holes"]) == 2
