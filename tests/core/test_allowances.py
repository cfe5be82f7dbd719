"""Process allowances (issue 18, item 4): the elephant-foot chamfer of printed solids and the tool-radius check of
outlines for CNC routing."""
from __future__ import annotations

import functools
import json
import math
from dataclasses import replace

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core.errors import DesignError
from camgen.core.parts import Allowances, Part
from camgen.core.routing import tool_check
from camgen.core.shapes import Circle, Contour, arc_steps
from camgen.core.solids import _rings, check_mesh, extrude, foot_volume, pin, spacer, trimesh_of
from linkgen.cli import main as linkgen
from tests.conftest import ROOT

RDRD = ROOT / "templates" / "rdrd.toml"


def disc(radius: float) -> Contour:
    """A counter-clockwise circle of ``radius`` (mm) about the origin, as two exact half-circle arcs."""
    return Contour(np.array([[radius, 0.0], [-radius, 0.0]]), np.array([1.0, 1.0]))


def section_area(part_or_mesh, z: float) -> float:
    """The area (mm^2) of a solid's section at height ``z``, sliced by trimesh."""
    solid = extrude(part_or_mesh) if isinstance(part_or_mesh, Part) else part_or_mesh
    mesh = solid if hasattr(solid, "section") else trimesh_of(solid)
    return sliced_area(mesh, z)


def sliced_area(mesh, z: float) -> float:
    """The area (mm^2) of a trimesh mesh's section at height ``z``: its rings (trimesh's slice) joined by their
    symmetric difference (an outline less the holes inside it), with shapely."""
    rings = mesh.section(plane_origin=[0, 0, z], plane_normal=[0, 0, 1]).discrete
    return float(functools.reduce(shapely.symmetric_difference,
                                  [shapely.Polygon(np.asarray(r)[:, :2]) for r in rings]).area)


def nominal(part: Part) -> shapely.Polygon:
    """The part's section as the solid has it: its outline and holes as chords within its tolerance."""
    rings = _rings(part)
    return shapely.Polygon(rings[0], rings[1:])


# --- the elephant foot ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("size", [0.3, 1e-3, 1.9])
def test_a_ring_gets_the_frustum_rings_volume_and_the_inset_bed_face(size):
    big, small, thickness, tol = 20.0, 5.0, 4.0, 1e-4
    part = Part("ring", disc(big), (Circle((0.0, 0.0), small),), thickness, tol, elephant_foot=size)
    mesh = extrude(part)
    check = check_mesh(mesh)
    assert check.ok and trimesh_of(mesh).is_watertight
    # the exact frustum rings: pi c^2 (R - c/3) off round the rim, pi c^2 (r + c/3) round the bore
    exact = math.pi * (big**2 - small**2) * thickness - math.pi * size**2 * (big - size / 3) \
        - math.pi * size**2 * (small + size / 3)
    assert check.volume_mm3 == pytest.approx(exact, rel=2e-5)        # the chords' area, within the tolerance
    # and the chords' own section, exactly: its area x thickness less the formula over its rings
    rings = _rings(part)
    polygon = nominal(part)
    assert check.volume_mm3 == pytest.approx(polygon.area * thickness - sum(foot_volume(r, size) for r in rings),
                                             rel=1e-7)            # the mesh is single precision
    # the bed face is the section inset by the chamfer; from z = c up the section is untouched
    assert section_area(mesh, 1e-9) == pytest.approx(polygon.buffer(-size, quad_segs=64).area, abs=1e-3)
    plain = extrude(replace(part, elephant_foot=0.0))
    for z in (size + 1e-6, (size + thickness) / 2, thickness - 1e-6):     # z in single precision too
        assert section_area(mesh, z) == pytest.approx(section_area(plain, z), rel=1e-10)
        assert section_area(mesh, z) == pytest.approx(polygon.area, abs=1e-5)      # to single precision
    # halfway up the chamfer the section is the section eroded by half of it
    assert section_area(mesh, size / 2) == pytest.approx(polygon.buffer(-size / 2, quad_segs=64).area, abs=1e-3)


def test_a_concave_corner_is_rounded_on_the_bed_as_the_erosion_has_it():
    # an L: six sharp corners, one of them concave (at (10, 10)), and a slotted hole (lines and exact arcs)
    outline = Contour(np.array([[0, 0], [30, 0], [30, 10], [10, 10], [10, 30], [0, 30]], dtype=float))
    slot = Contour(np.array([[18, 4], [24, 4], [24, 6], [18, 6]], dtype=float), np.array([0, 1, 0, 1.0]))
    part = Part("ell", outline, (slot,), 5.0, 1e-3, elephant_foot=0.8)
    mesh = extrude(part)
    check = check_mesh(mesh)
    assert check.ok
    polygon = nominal(part)
    # the concave corners' arcs (the L's, and round each of the slot's chords) are chords within the tolerance
    assert section_area(mesh, 1e-9) == pytest.approx(polygon.buffer(-0.8, quad_segs=64).area, rel=1e-5)
    assert section_area(mesh, 0.8 + 1e-6) == pytest.approx(section_area(replace(part, elephant_foot=0.0), 1), rel=1e-10)
    assert check.volume_mm3 == pytest.approx(polygon.area * 5 - sum(foot_volume(r, 0.8) for r in _rings(part)),
                                             rel=1e-6)


def test_every_printed_cam_gets_the_foot_and_default_files_stay_the_same(tmp_path):
    def build(folder, *sets):
        args = ["build", str(RDRD), "-o", str(tmp_path / folder), "--set", 'output.formats=["stl","json"]',
                "--set", "hub.keyway=true"]
        for s in sets:
            args += ["--set", s]
        result = CliRunner().invoke(camgen, args)
        assert result.exit_code == 0, result.output
        return tmp_path / folder / "rdrd.stl"

    plain, zero = build("plain"), build("zero", "output.elephant_foot=0")
    foot = build("foot", "output.elephant_foot=0.4")
    assert plain.read_bytes() == zero.read_bytes()
    import trimesh

    from camgen.api import design_cam
    from camgen.spec import load_spec

    printed = design_cam(load_spec(RDRD, ["hub.keyway=true", "output.elephant_foot=0.4"])).printed
    assert printed.elephant_foot == 0.4
    mesh = trimesh.load(foot)
    assert mesh.is_watertight and mesh.is_winding_consistent
    polygon = nominal(printed)
    bed = sliced_area(mesh, 1e-9)
    assert bed == pytest.approx(polygon.buffer(-0.4, quad_segs=64).area, abs=1e-2)
    above = sliced_area(mesh, 0.4 + 1e-6)
    assert above == pytest.approx(polygon.area, abs=1e-3)
    volume = mesh.volume
    expected = polygon.area * printed.thickness - sum(foot_volume(r, 0.4) for r in _rings(printed))
    assert volume == pytest.approx(expected, rel=1e-6)


def test_pins_spacers_and_linkage_parts(tmp_path):
    shank = pin(4.0, 12.0, 1e-3, foot=0.3)
    assert check_mesh(shank).ok
    bed = trimesh_of(shank).vertices
    bed = bed[bed[:, 2] == 0.0]
    # a convex ring's edges move in by the chamfer and meet: the corners of n chords at r - c / cos(pi / n)
    assert np.hypot(bed[:, 0], bed[:, 1]).max() == pytest.approx(2.0 - 0.3 / math.cos(math.pi / len(bed)), abs=1e-6)
    tube = spacer(4.2, 8.0, 6.0, 1e-3, foot=0.3)
    assert check_mesh(tube).ok
    bed = trimesh_of(tube).vertices[trimesh_of(tube).vertices[:, 2] == 0.0]
    r = np.hypot(bed[:, 0], bed[:, 1])
    outer = np.count_nonzero(r > 3.0)
    assert r.max() == pytest.approx(4.0 - 0.3 / math.cos(math.pi / outer), abs=1e-6)
    # the bore's chords move out by the chamfer, joined round each corner by an arc of its radius (one chord
    # here, as the corners turn so little): every corner at the same distance, within r + c
    n = arc_count(2.1, 1e-3)
    assert r.min() == pytest.approx(math.sqrt(2.1**2 + 0.3**2 + 2 * 2.1 * 0.3 * math.cos(math.pi / n)), abs=1e-6)
    assert r[r < 3.0].max() <= 2.4 + 1e-6
    result = CliRunner().invoke(linkgen, ["build", str(ROOT / "templates" / "crank-rocker.toml"), "-o",
                                          str(tmp_path), "--set", "output.elephant_foot=0.3", "--set",
                                          "parts.pins=true", "--set", 'output.formats=["stl","json"]'])
    assert result.exit_code == 0, result.output
    import trimesh

    for stl in sorted(tmp_path.glob("*.stl")):
        mesh = trimesh.load(stl)
        assert mesh.is_watertight and mesh.is_winding_consistent, stl.name


def test_hard_cases_of_the_foot():
    part = Part("ring", disc(10.0), (Circle((0.0, 0.0), 3.0),), 2.0, 1e-3)
    # the least length a template may give, and a hair under the thickness
    for size in (1e-6, 2.0 - 1e-6):
        mesh = extrude(replace(part, elephant_foot=size))
        assert check_mesh(mesh).ok
        assert check_mesh(mesh).volume_mm3 == pytest.approx(
            nominal(part).area * 2.0 - sum(foot_volume(r, size) for r in _rings(part)), rel=1e-5)   # cones' chords
    with pytest.raises(DesignError, match=r"^output.elephant_foot: must be < the thickness of ring, 2 mm \(got 2\)"):
        extrude(replace(part, elephant_foot=2.0))
    # a web narrower than twice the chamfer would close up on the bed: refused, naming the field
    web = Part("web", disc(10.0), (Circle((0.0, 0.0), 9.5),), 5.0, 1e-3, elephant_foot=0.3)
    with pytest.raises(DesignError, match=r"^output.elephant_foot: a chamfer of 0.3 mm closes up the bed face of web"):
        extrude(web)
    # the allowance is carried to the printed part only
    assert Allowances(elephant_foot=0.2).elephant_foot == 0.2


def test_a_foot_too_thick_is_one_line_exit_2_and_nothing_written(tmp_path):
    for sets, message in ((["cam.thickness=4", "output.elephant_foot=4"],
                           "error: output.elephant_foot: must be < the thickness of rdrd, 4 mm (got 4)\n"),
                          (["output.elephant_foot=5.5"],
                           "error: output.elephant_foot: must be >= 0 and <= 5 mm (got 5.5)\n"),
                          (["output.elephant_foot=-0.1"],
                           "error: output.elephant_foot: must be >= 0 and <= 5 mm (got -0.1)\n")):
        args = ["build", str(RDRD), "-o", str(tmp_path / "o")]
        for one in sets:
            args += ["--set", one]
        result = CliRunner().invoke(camgen, args)
        assert result.exit_code == 2 and result.stderr == message
        assert not (tmp_path / "o").exists()


# --- the tool radius -----------------------------------------------------------------------------------------


def arc_count(radius: float, tolerance: float) -> int:
    """How many chords a circle of ``radius`` (mm) is drawn with (:meth:`Circle.flatten`)."""
    return max(arc_steps(radius, 2 * math.pi, tolerance), 8)


def notched(radius: float) -> Part:
    """A 40 x 20 plate with a half-round notch of ``radius`` (mm) down from the middle of its top edge (an exact
    concave arc), and a round hole of 2 mm radius."""
    outline = Contour(np.array([[0, 0], [40, 0], [40, 20], [20 + radius, 20], [20 - radius, 20], [0, 20]], dtype=float),
                      np.array([0, 0, 0, -1.0, 0, 0]))            # clockwise: the arc bends into the material
    return Part("notched", outline, (Circle((8.0, 8.0), 2.0),), 3.0, 0.01)


def test_a_concave_arc_of_radius_r_is_found_exactly():
    r = 3.7
    part = notched(r)
    failing = tool_check([part], r + 1e-9)
    assert failing["smallest_concave_radius_mm"] == {"notched": pytest.approx(2.0, abs=1e-12)}
    places = {f["what"]: f for f in failing["fails"]}
    assert set(places) == {"arc", "hole"}                       # the plate's four corners and the notch's are convex
    assert places["arc"]["radius_mm"] == pytest.approx(r, abs=1e-12)
    assert (places["arc"]["x_mm"], places["arc"]["y_mm"]) == pytest.approx((20.0, 20.0 - r), abs=1e-9)
    assert places["hole"]["radius_mm"] == 2.0 and (places["hole"]["x_mm"], places["hole"]["y_mm"]) == (8.0, 8.0)
    passing = tool_check([part], r - 1e-9)
    assert [f["what"] for f in passing["fails"]] == ["hole"]
    assert tool_check([part], 2.0 - 1e-9)["fails"] == []


def test_sharp_concave_corners_have_radius_0():
    outline = Contour(np.array([[0, 0], [30, 0], [30, 10], [10, 10], [10, 30], [0, 30]], dtype=float))
    part = Part("ell", outline, (), 3.0, 0.01)
    fails = tool_check([part], 1e-9)["fails"]
    assert fails == [{"part": "ell", "x_mm": 10.0, "y_mm": 10.0, "radius_mm": 0.0, "what": "corner"}]
    # the same corner drawn clockwise is read the same way (the material is on the left once turned)
    assert tool_check([replace(part, outline=outline.reversed())], 1e-9)["fails"] == fails
    # a hole's corners: a square hole's four corners are all concave to the material round it
    square = Contour(np.array([[12, 12], [12, 16], [16, 16], [16, 12]], dtype=float))      # clockwise
    holed = Part("holed", Contour(np.array([[0, 0], [30, 0], [30, 30], [0, 30]], dtype=float)), (square,), 3.0, 0.01)
    corners = tool_check([holed], 0.5)["fails"]
    assert sorted((f["x_mm"], f["y_mm"]) for f in corners) == [(12, 12), (12, 16), (16, 12), (16, 16)]
    assert all(f["radius_mm"] == 0.0 and f["what"] == "corner" for f in corners)


def test_chords_of_a_concave_curve_read_as_its_radius_and_a_sharp_turn_as_a_corner():
    big, tol = 25.0, 0.01
    # a bay of radius 25 mm cut into a plate's top edge, as chords within the tolerance (as an outline's samples)
    step = 2 * math.acos(1 - tol / big)
    n = math.ceil(math.pi / 3 / step)
    angle = -math.pi / 2 + math.pi / 6 * np.linspace(1, -1, n + 1)
    bay = np.column_stack([50 + big * np.cos(angle), 40 + big * np.sin(angle)])[::-1]
    outline = Contour(np.vstack([[0, 0], [100, 0], [100, 30], bay[::-1], [0, 30]]))
    found = tool_check([Part("bay", outline, (), 3.0, tol)], 30.0)["fails"]
    chords = [f for f in found if f["what"] == "chords"]
    assert len(chords) == n - 1
    assert [f["radius_mm"] for f in chords] == pytest.approx([big] * (n - 1), rel=1e-3)
    # the same bay drawn with chords four times too long for the tolerance turns too sharply: corners
    coarse = np.vstack([[0, 0], [100, 0], [100, 30], bay[::-1][::4], [0, 30]])
    found = tool_check([Part("bay", Contour(coarse), (), 3.0, tol)], 30.0)["fails"]
    assert found and all(f["what"] == "corner" and f["radius_mm"] == 0.0 for f in found if f["x_mm"] != 0)


def test_the_build_reports_and_warns_where_the_tool_fails(tmp_path):
    args = ["build", str(RDRD), "-o", str(tmp_path / "k"), "--set", "hub.keyway=true", "--set",
            'output.formats=["json"]']
    result = CliRunner().invoke(camgen, [*args, "--set", "output.tool_radius=1"])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "k" / "rdrd.json").read_text())
    routing = report["routing"]
    assert routing["tool_radius_mm"] == 1 and routing["smallest_concave_radius_mm"] == {"rdrd": 0.0}
    # DIN 6885 for the 10 mm bore: a key 3 mm wide, the keyway's floor 1.4 mm above the bore: two sharp corners
    assert sorted((f["x_mm"], f["y_mm"], f["what"]) for f in routing["fails"]) == [(-1.5, 6.4, "corner"),
                                                                                  (1.5, 6.4, "corner")]
    warnings = [line for line in result.output.splitlines() if line.startswith("warning: output.tool_radius")]
    assert len(warnings) == 1 and "2 concave place(s)" in warnings[0] and warnings[0] in [
        f"warning: {w}" for w in report["warnings"]]
    # without a tool radius there is no check; the bore's 5 mm radius passes a 5 mm tool without the keyway
    result = CliRunner().invoke(camgen, args)
    assert "routing" not in json.loads((tmp_path / "k" / "rdrd.json").read_text())
    result = CliRunner().invoke(camgen, ["build", str(RDRD), "-o", str(tmp_path / "b"), "--set",
                                         'output.formats=["json"]', "--set", "output.tool_radius=5"])
    routing = json.loads((tmp_path / "b" / "rdrd.json").read_text())["routing"]
    assert routing["fails"] == [] and routing["smallest_concave_radius_mm"]["rdrd"] == pytest.approx(5.0)


def test_linkage_parts_are_checked_too(tmp_path):
    result = CliRunner().invoke(linkgen, ["build", str(ROOT / "templates" / "crank-rocker.toml"), "-o",
                                          str(tmp_path), "--set", "output.tool_radius=3", "--set",
                                          'output.formats=["json"]'])
    assert result.exit_code == 0, result.output
    report = json.loads(next(tmp_path.glob("*.json")).read_text())
    routing = report["routing"]
    assert routing["fails"] and {f["what"] for f in routing["fails"]} == {"hole"}
    assert "warning: output.tool_radius" in result.output
