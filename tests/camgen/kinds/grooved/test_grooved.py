"""Grooved face (track) cams: both flanks as exact offsets of the pitch curve, checked for undercut, the groove as a
pocket in the solid and as its own layer in the cut files."""
from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.core.errors import DesignError
from camgen.api import design_cam
from camgen.groove import flank_checks
from camgen.kinds.grooved.design import largest_roller, pitch_rig
from camgen.spec import validate_spec
from camgen.surface import pitch_distance
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

#: how a refusal names the follower's table
DRIVEN = "a positive-drive translating-roller follower (driven both ways, no spring)"


TEMPLATE = ROOT / "templates" / "grooved.toml"
RAW = tomllib.loads(TEMPLATE.read_text())


def _raw(**cam) -> dict:
    raw = copy.deepcopy(RAW)
    raw["cam"].update(cam)
    return raw


def _flanks_from_dxf(path, flatten: float = 1e-4) -> list[np.ndarray]:
    """The GROOVE layer's closed contours read back with ezdxf (bulges flattened within ``flatten`` mm)."""
    import ezdxf
    from ezdxf import path as dxfpath

    doc = ezdxf.readfile(path)
    rings = [np.array([(v.x, v.y) for v in dxfpath.make_path(e).flattening(flatten)])
             for e in doc.modelspace() if e.dxf.layer == "GROOVE"]
    assert len(rings) == 2
    return sorted(rings, key=lambda r: np.abs(r).max())          # inner, outer


def _build(tmp_path, *overrides: str) -> tuple[dict, object]:
    out = tmp_path / "out"
    args = ["build", str(TEMPLATE), "-o", str(out)] + [a for o in overrides for a in ("--set", o)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return json.loads((out / "grooved.json").read_text()), out


def test_roller_along_the_pitch_curve_clears_both_flanks_by_half_the_clearance(tmp_path):
    """The issue's test: the roller placed along the pitch curve at 720 cam angles clears the exported inner and
    outer flanks (the DXF read back) by c/2, within the tolerance, and never touches either."""
    import shapely

    report, out = _build(tmp_path)
    design = design_cam(validate_spec(RAW))
    rr, c, tol = RAW["follower"]["roller_radius"], RAW["cam"]["running_clearance"], report["tolerance_mm"]
    centres = design.cam.pitch(np.radians(np.arange(720) / 2)).point
    points = shapely.points(centres)
    for ring in _flanks_from_dxf(out / "grooved.dxf"):
        gap = shapely.distance(shapely.LinearRing(ring), points) - rr
        assert np.all(np.abs(gap - c / 2) <= tol), (gap.min(), gap.max())
        assert gap.min() > 0
    # the other way round: every exported flank point is d = Rr + c/2 from the exact pitch curve (Newton projection)
    for ring in _flanks_from_dxf(out / "grooved.dxf", flatten=1e-3):
        assert np.abs(pitch_distance(design.cam, ring[::3]) - (rr + c / 2)).max() <= tol
    assert report["flanks"]["inner"]["max_error_mm"] <= tol and report["flanks"]["outer"]["max_error_mm"] <= tol


def test_kerf_moves_both_flanks_into_the_groove_by_half_of_it(tmp_path):
    import shapely

    report, out = _build(tmp_path, "output.kerf=0.3")
    design = design_cam(validate_spec(RAW))
    d = RAW["follower"]["roller_radius"] + RAW["cam"]["running_clearance"] / 2
    points = shapely.points(design.cam.pitch(np.radians(np.arange(360.0))).point)
    for ring in _flanks_from_dxf(out / "grooved.dxf"):
        gap = shapely.distance(shapely.LinearRing(ring), points)
        assert np.abs(gap - (d - 0.15)).max() <= report["tolerance_mm"]
    assert "moved into the groove by half the kerf (0.15 mm)" in report["outline_note"]


def _section_area(mesh, z: float) -> float:
    """The area of the mesh's section by the plane at height ``z`` (mm^2): its loops merged by shapely, even-odd."""
    import functools

    import shapely
    import trimesh

    segments = trimesh.intersections.mesh_plane(mesh, [0, 0, 1], [0, 0, z])[:, :, :2].round(9)   # shared ends meet
    loops = shapely.get_parts(shapely.line_merge(shapely.MultiLineString(list(segments))))
    assert all(loop.is_closed for loop in loops)
    return functools.reduce(shapely.symmetric_difference, [shapely.Polygon(loop.coords) for loop in loops]).area


def test_the_groove_is_a_pocket_of_the_given_depth(tmp_path):
    """The STL read back: watertight and outward, its volume the plate's area x thickness less the groove's area x
    depth within the bound the report states, and sliced above and below the groove's floor: the slice through the
    groove lacks exactly the groove's area, the one below it is the whole plate."""
    import trimesh

    report, out = _build(tmp_path)
    mesh = trimesh.load(out / "grooved.stl")
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    t, depth = RAW["cam"]["thickness"], RAW["cam"]["groove_depth"]
    plate, groove = report["area_mm2"], report["groove_area_mm2"]
    expected = plate * t - groove * depth
    assert report["mesh"]["volume_expected_mm3"] == pytest.approx(expected, abs=1e-5)
    assert abs(mesh.volume - expected) <= report["mesh"]["volume_bound_mm3"]
    # the chords lose area to the arcs only: a few tens of mm^3 of 1.2e5, well inside the bound
    assert abs(mesh.volume - expected) < 0.5 * report["mesh"]["volume_bound_mm3"]
    d = RAW["follower"]["roller_radius"] + RAW["cam"]["running_clearance"] / 2
    perimeter = 2 * math.pi * report["cam"]["plate_diameter_mm"] / 2
    for z, area in ((t - depth / 2, plate - groove), ((t - depth) / 2, plate)):
        assert _section_area(mesh, z) == pytest.approx(area, abs=report["tolerance_mm"] * 3 * perimeter)
    # the exact groove, 2 d wide, has the area of its centre line's length x 2 d (Steiner: the offsets' curvature
    # terms cancel); the exported flanks' chords stay within the tolerance of it, over both flanks' length
    pitch = design_cam(validate_spec(RAW)).cam.pitch(np.linspace(0, 2 * math.pi, 200001)).point
    length = np.linalg.norm(np.diff(pitch, axis=0), axis=1).sum()
    assert abs(groove - length * 2 * d) <= report["tolerance_mm"] * 2 * length


def test_the_cut_files_carry_the_groove_on_its_own_layer(tmp_path):
    import ezdxf

    report, out = _build(tmp_path)
    doc = ezdxf.readfile(out / "grooved.dxf")
    assert not doc.audit().has_errors
    layers = [e.dxf.layer for e in doc.modelspace()]
    assert layers.count("OUTLINE") == 1 and layers.count("GROOVE") == 2 and layers.count("HOLES") == 1
    assert doc.layers.get("GROOVE").dxf.color == 6
    plate = next(e for e in doc.modelspace() if e.dxf.layer == "OUTLINE")
    radius = max(math.hypot(x, y) for x, y, *_ in plate.get_points())
    assert 2 * radius == pytest.approx(report["cam"]["plate_diameter_mm"], abs=1e-9)
    svg = (out / "grooved-cut.svg").read_text()
    assert '<g id="GROOVE" fill="none" stroke="#ff00ff"' in svg
    # the plate is rim mm outside the outer flank's farthest point: Rp + max lift + d + rim
    d = RAW["follower"]["roller_radius"] + RAW["cam"]["running_clearance"] / 2
    far = RAW["cam"]["base_radius"] + RAW["follower"]["roller_radius"] + 20.0 + d + RAW["cam"]["rim"]
    assert radius == pytest.approx(far, abs=1e-9)


def _polar_radii(design) -> tuple[float, float]:
    """Smallest convex and concave radius of curvature of a centred translating roller's pitch curve from the polar
    formula rho = (r^2 + r'^2)^(3/2) / (r^2 + 2 r'^2 - r r''), r = Rp + s: independent of the pitch geometry code."""
    theta = np.linspace(0, 2 * math.pi, 400001)
    s, s1, s2 = design.cam.program.evaluate(theta)[:3]
    r = design.cam.base_radius + design.cam.contact_radius + s
    denominator = r**2 + 2 * s1**2 - r * s2
    rho = (r**2 + s1**2) ** 1.5 / denominator
    return rho[rho > 0].min(), (-rho[rho < 0]).min() if (rho < 0).any() else math.inf


#: a fast harmonic rise from a dwell: a concave start (s'' > Rp there) smaller than the convex top
STEEP = {"name": "steep", "cam": {"kind": "grooved", "base_radius": 15.0, "thickness": 8.0, "groove_depth": 4.0},
         "follower": {"type": "translating-roller", "roller_radius": 3.0},
         "motion": [{"type": "rise", "law": "harmonic", "lift": 40.0, "angle": 90.0}, {"type": "dwell", "angle": 90.0},
                    {"type": "return", "law": "cycloidal", "lift": 40.0, "angle": 150.0},
                    {"type": "dwell", "angle": 30.0}]}


def test_flank_checks_against_the_polar_formula():
    for raw in (RAW, STEEP):
        design = design_cam(validate_spec(raw))
        convex, concave = _polar_radii(design)
        assert design.inner.pitch_rho_min_mm == pytest.approx(convex, rel=1e-6)
        assert design.outer.pitch_rho_min_mm == pytest.approx(concave, rel=1e-6)
    # the harmonic rise starts concave with r''/r = s''(0)/Rp > 1: |rho| = Rp^2 / (s''(0) - Rp) exactly there
    rp, s2 = 18.0, math.pi**2 * 40.0 / (2 * (math.pi / 2) ** 2)
    design = design_cam(validate_spec(STEEP))
    assert design.outer.at_deg == pytest.approx(0.0, abs=1e-9)
    assert design.outer.pitch_rho_min_mm == pytest.approx(rp**2 / (s2 - rp), rel=1e-12)


def _with(raw: dict, clearance: float) -> dict:
    raw = copy.deepcopy(raw)
    raw["cam"]["running_clearance"] = clearance
    return raw


@pytest.mark.parametrize("raw, side", [(RAW, "inner"), (STEEP, "outer")], ids=["inner", "outer"])
def test_undercut_at_and_within_1e_12_of_the_limit(raw, side):
    """Each flank undercuts where its pitch radius falls below d = Rr + c/2: with the base radius fixed the pitch
    curve does not move with c, so c = 2 (rho - Rr) is the change point; 1e-12 relative inside it builds, outside
    it is refused naming the flank, the angle and both radii."""
    cam = design_cam(validate_spec(_with(raw, 0.0))).cam
    inner, outer = flank_checks(cam, 0.0)
    rho = (inner if side == "inner" else outer).pitch_rho_min_mm
    other = (outer if side == "inner" else inner).pitch_rho_min_mm
    assert rho < other                                   # this flank is the one that decides
    rr = raw["follower"]["roller_radius"]
    limit = 2 * (rho - rr)
    fine = design_cam(validate_spec(_with(raw, limit * (1 - 1e-12))))
    flank = fine.inner if side == "inner" else fine.outer
    assert not flank.undercut and 0 < flank.rho_min_mm < 1e-10 * rho
    at = design_cam(validate_spec(_with(raw, limit)))      # at the limit: a flank radius of 0 (within rounding)
    assert abs((at.inner if side == "inner" else at.outer).rho_min_mm) < 1e-12 * rho
    with pytest.raises(DesignError) as err:
        design_cam(validate_spec(_with(raw, limit * (1 + 1e-12))))
    sense = "convex" if side == "inner" else "concave"
    assert str(err.value).startswith(f"undercut of the {side} flank at {flank.at_deg:.2f} degrees: the pitch curve's "
                                     f"{sense} radius of curvature is {rho:.4g} mm, smaller than "
                                     "follower.roller_radius + cam.running_clearance / 2")
    assert "\n" not in str(err.value)


def test_the_largest_roller_that_fits_both_flanks():
    """The refusal names the largest roller: there the deciding flank's radius is 0 (to the bisection's 1e-9)."""
    raw = copy.deepcopy(STEEP)
    raw["cam"]["base_radius"] = 5.0
    raw["follower"]["roller_radius"] = 6.0
    spec = validate_spec(raw)
    best = largest_roller(pitch_rig(spec), spec.cam.base_radius, spec.cam.running_clearance)
    assert best is not None and best < 6.0
    # the outer flank at the harmonic rise's concave start decides, in closed form: (Rb + r)^2 / (s''(0) - Rb - r)
    # = r + c/2 with s''(0) = 80 mm/rad^2, Rb = 5, c/2 = 0.1: 2 r^2 - 64.9 r + 17.5 = 0, the smaller root
    assert best == pytest.approx((64.9 - math.sqrt(64.9**2 - 8 * 17.5)) / 4, rel=1e-8)
    with pytest.raises(DesignError, match=f"the largest roller that fits is {best:.4g} mm"):
        design_cam(spec)
    raw["follower"]["roller_radius"] = best
    design = design_cam(validate_spec(raw))
    assert 0 <= min(design.inner.rho_min_mm, design.outer.rho_min_mm) < 1e-6


def test_an_allowed_outer_undercut_is_the_cutters_envelope():
    """With allow_undercut the outer flank is the envelope a cutter of the groove's width leaves: no point of it
    comes nearer the pitch curve than d, and the groove still builds as a watertight pocket."""
    raw = _with(STEEP, 6.0)                           # d = 6 mm, over the 5.23 mm concave radius at the rise's start
    raw["cam"]["allow_undercut"] = True
    design = design_cam(validate_spec(raw))
    assert design.outer.undercut and not design.inner.undercut and design.outer_outline.envelope
    d = design.offset_mm
    ring = design.outer_outline.contour.flatten(1e-3)
    assert pitch_distance(design.cam, ring).min() >= d - design.tolerance
    assert any("outer flank is the cutter's envelope" in w for w in design.warnings)
    from camgen.core.solids import check_mesh, extrude

    assert check_mesh(extrude(design.printed)).ok


def test_an_oscillating_roller_in_a_groove():
    raw = copy.deepcopy(RAW)
    raw["follower"] = {"type": "oscillating-roller", "roller_radius": 5.0, "pivot_distance": 90.0, "arm_length": 70.0}
    for seg in raw["motion"]:
        if "lift" in seg:
            seg["lift"] = 15.0                               # degrees of swing
    design = design_cam(validate_spec(raw))
    ring = design.outer_outline.contour.flatten(1e-4)
    assert np.abs(pitch_distance(design.cam, ring[::5]) - design.offset_mm).max() <= design.tolerance


@pytest.mark.parametrize("change, message", [
    ({"cam.groove_depth": 8.0}, "cam.groove_depth: must be < cam.thickness 8 mm (got 8)"),
    ({"cam.groove_depth": -1.0}, "cam.groove_depth: must be > 0 and <= 10000 mm (got -1.0)"),
    ({"cam.running_clearance": -0.1}, "cam.running_clearance: must be >= 0 and <= 100 mm (got -0.1)"),
    ({"cam.rim": 0.0}, "cam.rim: must be > 0 and <= 10000 mm (got 0.0)"),
    ({"follower.spring_rate": 2.0}, f"follower.spring_rate: not a key of {DRIVEN}; it "
                                    "takes: roller_radius, offset, roller_width, mass, "),
    ({"hub.boss_diameter": 20.0, "hub.boss_height": 5.0}, "hub.boss_diameter: a boss would stand on the grooved face"),
    ({"cam.kind": "disc"}, 'cam.groove_depth: not a key of a disc cam (a key of cam.kind = "grooved" or "barrel"); it '
                          'takes: base_radius, thickness, '),
    ({"output.kerf": 5.0, "follower.roller_radius": 2.0},
     "output.kerf: a kerf of 5 mm closes the groove (4.2 mm wide)"),
])
def test_bad_values_are_one_line_exit_2_nothing_written(change, message, tmp_path):
    assert_refused(TEMPLATE, change, message, tmp_path)


def test_groove_depth_is_required_and_refused_on_a_plate():
    raw = copy.deepcopy(RAW)
    raw["follower"] = {"type": "knife-edge"}
    with pytest.raises(ValueError, match=r"^follower\.type: a grooved cam takes translating-roller or "
                                         r"oscillating-roller \(got 'knife-edge'\)$"):
        validate_spec(raw)
    raw = copy.deepcopy(RAW)
    del raw["cam"]["groove_depth"]
    with pytest.raises(ValueError,
                       match=r"^cam\.groove_depth: missing: give the depth of the groove the roller runs in \(< "
                             r"thickness\) in mm$"):
        validate_spec(raw)
    plate = {"name": "p", "cam": {"kind": "plate", "travel": 200.0, "base_radius": 20.0, "thickness": 6.0, "rim": 3.0},
             "follower": {"type": "knife-edge"}, "motion": [{"type": "dwell", "angle": 360.0}]}
    with pytest.raises(ValueError, match=r'^cam\.rim: not a key of a plate cam \(a key of cam\.kind = "grooved"\); '
                                          r'it takes: base_radius, thickness, allow_undercut, max_pressure_angle, '
                                          r'min_rho_margin, rpm, material, rpm_range, rpm_steps, travel$'):
        validate_spec(plate)


def test_auto_base_radius_sizes_the_inner_flank():
    """``base_radius = "auto"``: the smallest base radius keeping the pressure angle within its limit and the
    inner flank's convex radius above cam.min_rho_margin; reported in the grooved cam's own terms."""
    raw = _raw(base_radius="auto", min_rho_margin=2.0)
    design = design_cam(validate_spec(raw))
    sizing = design.profile.sizing
    assert design.spec.cam.base_radius == "auto"                    # the template as given: never validated again
    assert design.base_radius_mm == sizing.base_radius_mm
    assert design.profile.cam.base_radius == pytest.approx(sizing.base_radius_mm - 0.1, rel=1e-15)   # c/2 less
    decided = min(design.inner.rho_min_mm - 2.0, 30.0 - design.analysis.pressure_angle_max_deg)
    assert abs(decided) < 1e-6                        # one of the two limits is met with equality
    assert design.inner.rho_min_mm >= 2.0 - 1e-6 and design.analysis.pressure_angle_max_deg <= 30 + 1e-6


def test_grooved_family_builds(tmp_path):
    path = tmp_path / "fam.toml"
    path.write_text(f'base = "{TEMPLATE.as_posix()}"\nname = "gfam"\n[sweep]\n"cam.running_clearance" = [0.1, 0.3]\n')
    result = CliRunner().invoke(main, ["family", str(path), "-o", str(tmp_path / "f")])
    assert result.exit_code == 0, result.output
    rows = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert [r["status"] for r in rows] == ["ok", "ok"]


def test_size_sizes_the_inner_flank():
    """``camgen size`` of a grooved template: the island's smallest base radius plus c/2, the one ``"auto"`` builds."""
    result = CliRunner().invoke(main, ["size", str(TEMPLATE), "--json"])
    assert result.exit_code == 0, result.output
    sized = json.loads(result.output)
    design = design_cam(validate_spec(_raw(base_radius="auto")))
    assert sized["base_radius_mm"] == pytest.approx(design.base_radius_mm, rel=1e-8)   # bisection to 1e-9
    assert design.analysis.pressure_angle_max_deg == pytest.approx(30.0, abs=1e-6)


def test_the_island_keeps_the_follower_and_takes_the_rates_alone():
    """The island (the disc whose surface is the inner flank) is the template's rig with a roller c/2 larger on a
    base circle c/2 smaller: the same pitch curve, the template's follower as it is (its mass, load, speed range
    kept); its speed is the rates alone (no disc's contact check, lift-off or spring); the forces and speeds table
    are the groove's, a positive drive's (no lift-off, no margin), the same as camgen.forces.drive_speed gives on
    the island's cam."""
    from camgen.forces import drive_speed
    from camgen.kinds.grooved.design import island_base, island_rig
    from camgen.spec import load_spec

    spec = load_spec(ROOT / "templates" / "grooved.toml", ("cam.rpm=300", "follower.mass=0.2", "follower.load=-5",
                                                          "cam.rpm_range=[100, 1000]", "cam.rpm_steps=4"))
    rig, half = pitch_rig(spec), spec.cam.running_clearance / 2
    island = island_rig(rig, spec.cam.running_clearance)
    assert island.mount.table is spec.follower and island.roller_radius == spec.follower.roller_radius + half
    base = island_base(spec.cam.base_radius, spec.cam.running_clearance)
    assert base == spec.cam.base_radius - half
    theta = np.linspace(0.0, 2 * math.pi, 97)
    assert np.abs(island.cam(base).pitch(theta).point - rig.cam(spec.cam.base_radius).pitch(theta).point).max() < 1e-12
    design = design_cam(spec)
    speed = design.profile.speed
    assert speed.contact is None
    drive = speed.forces.drive
    assert (drive.force_positive, drive.force_negative) == ("inner flank", "outer flank")
    assert speed.speeds.liftoff_rpm is None and speed.speeds.margin is None
    assert all(row.holds is None for row in speed.speeds.rows)
    same = drive_speed(spec, design.profile.cam, ("inner flank", "outer flank"))
    assert same == (speed.forces, speed.speeds)
