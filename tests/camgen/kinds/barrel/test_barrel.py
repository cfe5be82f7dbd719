"""Barrel (cylindrical) cams: the issue's contract template builds as written; the roller placed along the exported
solid touches both walls with half the clearance and never cuts in; the exact walls against a brute-force envelope;
pressure angle against atan(s'/Rm); undercut at the floor's radius; the developed drawing; bad values."""
from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.kinds.barrel.kinematics import GrooveWalls
from camgen.cli import main
from camgen.core.errors import DesignError
from camgen.api import design_cam
from camgen.spec import validate_spec
from tests.camgen.kinds.barrel.sectors import Sectors
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

#: the issue's contract, word for word
CONTRACT = '''name = "barrel"
[cam]
kind = "barrel"
pitch_radius = 30.0
length = 50.0
groove_depth = 6.0
bore = 10.0
[follower]
type = "translating-roller"
roller_radius = 5.0
[[motion]]
type = "rise"
law = "cycloidal"
lift = 20.0
angle = 150.0
[[motion]]
type = "dwell"
angle = 30.0
[[motion]]
type = "return"
law = "harmonic"
lift = 20.0
angle = 150.0
[[motion]]
type = "dwell"
angle = 30.0
'''
RAW = tomllib.loads(CONTRACT)


def _build(tmp_path, *overrides: str, text: str = CONTRACT) -> tuple[dict, object]:
    path = tmp_path / "barrel.toml"
    path.write_text(text)
    args = ["build", str(path), "-o", str(tmp_path / "out")] + [a for o in overrides for a in ("--set", o)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return json.loads((tmp_path / "out" / "barrel.json").read_text()), tmp_path / "out"


def test_the_contract_template_builds_as_written(tmp_path):
    report, out = _build(tmp_path)
    assert sorted(p.name for p in out.iterdir()) == sorted(
        ["barrel-developed.dxf", "barrel-developed.svg", "barrel.stl", "barrel.3mf", "barrel.json", "barrel.html"])
    assert report["cam"]["floor_radius_mm"] == 27.0 and report["cam"]["rim_radius_mm"] == 33.0
    assert report["cam"]["rest_height_mm"] == 15.0                  # the 20 mm travel in the middle of 50
    assert report["mesh"]["watertight"] and report["outline_max_error_mm"] <= report["tolerance_mm"]
    bundled = tomllib.loads((ROOT / "templates" / "barrel.toml").read_text())
    assert bundled == RAW                                            # the bundled template is the contract


def _roller_gaps(mesh, walls: GrooveWalls, theta: np.ndarray, inner: float, outer: float,
                 sense: int) -> tuple[np.ndarray, np.ndarray]:
    """For each cam angle: the least distance from the roller's axis (radial, at the polar angle -sense theta and
    the height zc, from the floor's radius to the rim's) to the exported walls below and above it. The walls are
    the mesh's triangles off the floor, each sampled on a barycentric grid of 66 points."""
    tri = mesh.vertices[mesh.faces]
    radius = np.hypot(tri[..., 0], tri[..., 1])
    off_floor = radius.min(axis=1) > inner + 1e-6
    tri = tri[off_floor]
    i, j = np.meshgrid(np.arange(11), np.arange(11), indexing="ij")
    keep = i + j <= 10
    bary = np.stack([i[keep], j[keep], 10 - i[keep] - j[keep]], axis=1) / 10.0
    samples = np.einsum("kb,tbc->tkc", bary, tri).reshape(-1, 3)
    sectors = Sectors(samples, np.arctan2(samples[:, 1], samples[:, 0]))
    below, above = np.empty(len(theta)), np.empty(len(theta))
    zc = walls.centre(theta)[0]
    for k, (t, z) in enumerate(zip(theta, zc, strict=True)):
        psi = -sense * t
        axis = np.array([math.cos(psi), math.sin(psi), 0.0])
        near = sectors.near(psi, 0.4, z, 8.0)
        p = samples[near]
        along = np.clip(p @ axis, inner, outer)
        gap = np.linalg.norm(p - along[:, None] * axis - np.array([0.0, 0.0, z]), axis=1)
        below[k], above[k] = gap[p[:, 2] < z].min(), gap[p[:, 2] > z].min()
    return below, above


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_the_roller_runs_in_the_exported_groove(tmp_path, rotation):
    """The issue's test: the roller (a cylinder of radius Rr about its radial axis) placed along the exported STL
    at 720 cam angles (cw: 240) touches both walls within the tolerance plus the clearance, and never cuts in."""
    import trimesh

    report, out = _build(tmp_path, f"cam.rotation='{rotation}'")
    design = design_cam(validate_spec(RAW | {"cam": RAW["cam"] | {"rotation": rotation}}))
    mesh = trimesh.load(out / "barrel.stl")
    rr, c, tol = 5.0, 0.2, report["tolerance_mm"]
    theta = np.linspace(0, 2 * math.pi, 720 if rotation == "ccw" else 240, endpoint=False)
    below, above = _roller_gaps(mesh, design.walls, theta, 27.0, 33.0, 1 if rotation == "ccw" else -1)
    for gap in (below - rr, above - rr):
        assert np.all(gap >= c / 2 - tol) and np.all(gap <= c / 2 + tol), (gap.min(), gap.max())
    assert min(below.min(), above.min()) > rr                        # never cuts into the roller


def test_the_exact_walls_against_a_brute_force_envelope():
    """The closed-form wall against the roller family searched on a grid of 4e5 angles: every wall point is Rw from
    the nearest roller axis, on the floor's, the pitch's and the rim's cylinders, for both walls."""
    walls = design_cam(validate_spec(RAW)).walls
    grid = np.linspace(0, 2 * math.pi, 400001)
    zc = walls.centre(grid)[0]
    for r in (27.0, 30.0, 33.0):
        for side in (-1, 1):
            theta = np.linspace(0, 2 * math.pi, 61)[:-1]
            phi, z = walls.developed(theta, r, side)
            d = np.hypot(r * np.sin(phi[:, None] - grid[None, :]), z[:, None] - zc[None, :])
            d = np.where(np.cos(phi[:, None] - grid[None, :]) > 0, d, np.inf)
            gap = d.min(axis=1) - 5.1               # no roller reaches past the wall; one touches it (to the grid)
            assert gap.min() > -1e-12 and gap.max() < 1e-8
            # and the wall point lies on the side it claims
            assert np.all(side * (z - walls.centre(theta)[0]) > 0)


def test_the_solid_walls_are_within_the_tolerance_of_the_exact_ones(tmp_path):
    """Points on the STL's wall triangles (a barycentric grid of 21 points each, off the floor and the rim) measured
    against the exact walls by a brute-force nearest roller axis (a grid of 4000 angles, then 400 round the best),
    not by the code that built them: within the tolerance (the grid's own step adds under 1e-4 mm)."""
    import trimesh

    report, out = _build(tmp_path)
    walls = design_cam(validate_spec(RAW)).walls
    mesh = trimesh.load(out / "barrel.stl")
    tri = mesh.vertices[mesh.faces]
    i, j = np.meshgrid(np.arange(6), np.arange(6), indexing="ij")
    keep = i + j <= 5
    bary = np.stack([i[keep], j[keep], 5 - i[keep] - j[keep]], axis=1) / 5.0
    v = np.einsum("kb,tbc->tkc", bary, tri).reshape(-1, 3)
    r = np.hypot(v[:, 0], v[:, 1])
    # the walls: off the floor, the rim and the ends (the files hold single precision: 27 mm is good to 2e-6; the
    # rim's facets lie up to the tolerance inside its circle, and the groove's edges on them)
    on_wall = (r > 27.0 + 1e-3) & (r < 33.0 - 2 * report["tolerance_mm"]) & (v[:, 2] > 1e-3) & (v[:, 2] < 50 - 1e-3)
    v, r = v[on_wall][::4], r[on_wall][::4]                           # a quarter of them: 15 000 points
    assert len(v) > 10000
    phi = -np.arctan2(v[:, 1], v[:, 0])

    def nearest(points: slice, grid: np.ndarray, zc: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The least distance to the rollers' axes at ``grid`` (heights ``zc``; one grid, or one a point), and where."""
        u = phi[points, None] - grid
        d = np.where(np.cos(u) > 0, np.hypot(r[points, None] * np.sin(u), v[points, 2, None] - zc), np.inf)
        k = np.argmin(d, axis=1)
        return d[np.arange(len(k)), k], np.broadcast_to(grid, d.shape)[np.arange(len(k)), k]

    coarse = np.linspace(0, 2 * math.pi, 4001)
    zc_coarse, step = walls.centre(coarse)[0], coarse[1]
    best = np.empty(len(v))
    for lo in range(0, len(v), 2000):
        part = slice(lo, lo + 2000)
        _, at = nearest(part, coarse, zc_coarse)
        fine = np.mod(at[:, None] + np.linspace(-step, step, 401)[None, :], 2 * math.pi)     # then 1/200 of a step
        best[part] = nearest(part, fine, walls.centre(fine.ravel())[0].reshape(fine.shape))[0]
    assert np.abs(best - 5.1).max() <= report["tolerance_mm"] + 1e-4
    assert report["wall_max_error_mm"] <= report["tolerance_mm"]
    assert report["floor_max_error_mm"] <= report["tolerance_mm"]


def test_pressure_angle_is_atan_of_the_slope_over_the_pitch_radius():
    design = design_cam(validate_spec(RAW))
    theta = np.linspace(0, 2 * math.pi, 720, endpoint=False)
    s1 = design.cam.program.evaluate(theta)[1]
    assert np.abs(design.cam.pitch(theta).pressure_angle - np.arctan(s1 / 30.0)).max() < 1e-14
    # the cycloidal rise's steepest slope, 2 h / beta at its middle, decides: atan(2 x 20 / (150 deg) / 30)
    beta = math.radians(150)
    assert design.analysis.pressure_angle_max_deg == pytest.approx(math.degrees(math.atan(2 * 20 / beta / 30)),
                                                                   abs=1e-9)
    assert design.pressure_deg["floor"] == pytest.approx(math.degrees(math.atan(2 * 20 / beta / 27)), abs=1e-9)


def test_the_developed_drawing(tmp_path):
    """The DXF read back: the unrolled pitch cylinder 2 pi Rm by the length; the pitch curve within the tolerance of
    (Rm theta, z0 + s); each wall Rw from it within the tolerance and the reported gap from the plane offset."""
    import ezdxf
    import shapely

    report, out = _build(tmp_path)
    doc = ezdxf.readfile(out / "barrel-developed.dxf")
    assert not doc.audit().has_errors
    frame = next(e for e in doc.modelspace() if e.dxf.layer == "OUTLINE")
    xs, ys = zip(*[(p[0], p[1]) for p in frame.get_points()], strict=True)
    assert max(xs) == pytest.approx(2 * math.pi * 30, abs=1e-12) and max(ys) == 50.0 and min(xs) == min(ys) == 0
    lines = {layer: [np.array([(p[0], p[1]) for p in e.get_points()]) for e in doc.modelspace()
                     if e.dxf.layer == layer] for layer in ("GROOVE", "PITCH")}
    design = design_cam(validate_spec(RAW))
    theta = np.linspace(0, 2 * math.pi, 20001)
    exact = shapely.LineString(np.column_stack([30 * theta, design.walls.centre(theta)[0]]))
    pitch = lines["PITCH"][0]
    assert pitch[:, 0].min() == 0.0 and pitch[:, 0].max() == pytest.approx(2 * math.pi * 30, abs=1e-9)
    assert shapely.distance(exact, shapely.points(pitch)).max() <= report["tolerance_mm"]
    gap = report["walls"]["plane_offset_gap_mm"]
    for wall in lines["GROOVE"]:
        inside = wall[(wall[:, 0] > 10) & (wall[:, 0] < 178)]               # off the ends, where the curve wraps
        d = shapely.distance(exact, shapely.points(inside))
        assert np.abs(d - 5.1).max() <= gap + report["tolerance_mm"]


def _with(clearance: float, **cam) -> dict:
    raw = copy.deepcopy(RAW)
    raw["cam"].update(running_clearance=clearance, **cam)
    return raw


def test_undercut_at_the_floor_at_and_within_1e_12_of_the_limit():
    """A steep short rise bends the developed curve most sharply on the floor's cylinder: with the base program
    fixed the walls' radius there does not move with the clearance, so Rw = that radius is the change point; 1e-12
    relative inside builds, outside is refused naming the wall, the angle and the floor's radius."""
    raw = copy.deepcopy(RAW)
    raw["motion"][0].update(angle=60.0, lift=20.0)
    raw["motion"][1]["angle"] = 120.0
    base = design_cam(validate_spec(_with(0.0) | {"motion": raw["motion"]}))
    lower, upper = base.checks
    worst = min((lower, upper), key=lambda c: c.flank.pitch_rho_min_mm)
    assert worst.at_radius_mm == 27.0                                     # the floor decides
    rho = worst.flank.pitch_rho_min_mm
    limit = 2 * (rho - 5.0)
    assert 0 < limit < 100
    fine = design_cam(validate_spec(_with(limit * (1 - 1e-12)) | {"motion": raw["motion"]}))
    assert 0 < min(c.flank.rho_min_mm for c in fine.checks) < 1e-10 * rho
    with pytest.raises(DesignError) as err:
        design_cam(validate_spec(_with(limit * (1 + 1e-12)) | {"motion": raw["motion"]}))
    assert str(err.value).startswith(f"undercut of the groove's {worst.flank.side} at {worst.flank.at_deg:.2f} "
                                     "degrees, on the cylinder of radius 27 mm: the developed pitch curve bends")
    # on the pitch cylinder alone the same roller would pass: the floor is what undercuts
    import dataclasses

    from camgen.followers.plate import PlateRoller
    from camgen.groove import flank_checks

    rw = 5.0 + limit / 2
    pitch = dataclasses.replace(base.cam, follower=PlateRoller(15.0 - rw, rw, 2 * math.pi * 30.0))
    assert min(f.pitch_rho_min_mm for f in flank_checks(pitch, rw)) > 1.1 * rw


@pytest.mark.parametrize("change, message", [
    ({"cam.base_radius": 20.0}, 'cam.base_radius: not a key of a barrel cam (a key of cam.kind = "disc", "plate", '
                                '"grooved" or "conjugate"); it takes: pitch_radius, groove_depth, running_clearance, '
                                'bore, max_pressure_angle, barrel_form, rib_width, rotation, length, rpm, material, '
                                'rpm_range, rpm_steps\n'),
    ({"cam.groove_depth": 50.0}, "cam.groove_depth: must be < 49.8 mm, so the groove's floor (cam.pitch_radius - "
                                 "groove_depth / 2 from the axis) stays wider than the roller there, 5.1 mm (got 50); "
                                 "or cam.pitch_radius > 30.1 mm"),
    ({"cam.length": 28.0}, "cam.length: must be > 30.2 mm, the follower's travel and the groove's width (got 28)"),
    ({"cam.allow_undercut": True}, 'cam.allow_undercut: not a key of a barrel cam (a key of cam.kind = "disc", '),
    ({"follower.offset": 2.0}, "follower.offset: not a key of a barrel cam's translating-roller follower (driven "
                               "both ways, no spring); it takes: roller_radius, roller_shape, mass, "),
    ({"output.kerf": 0.2}, "output.kerf: a barrel cam is printed; its drawing is a developed template"),
    ({"hub.engrave": True}, "hub.engrave: not used by a barrel cam (it takes cam.bore and hub.keyway)"),
    ({"cam.kind": "disc"}, 'cam.pitch_radius: not a key of a disc cam (a key of cam.kind = "barrel"); it takes: '),
])
def test_bad_values_are_one_line_exit_2_nothing_written(tmp_path, change, message):
    path = tmp_path / "barrel.toml"
    path.write_text(CONTRACT)
    assert_refused(path, change, message, tmp_path)


#: the floor's radius 30 - 6/2 = 27 mm; the cutter's radius Rw = 5 + 0.2/2 = 5.1 mm; no printing clearance by default
@pytest.mark.parametrize("change, message", [
    # the bore alone past the floor: named, with the largest bore (2 x 27), not the groove's depth (< 0 mm)
    ({"cam.bore": 60.0}, "cam.bore: must be < 54 mm, so the bore (its radius grown by output.clearance / 2: 30 mm from "
                         "the axis) stays inside the groove's floor, cam.pitch_radius - groove_depth / 2 = 27 mm from "
                         "the axis (got 60)\n"),
    ({"cam.bore": 54.0}, "cam.bore: must be < 54 mm, so the bore (its radius grown by output.clearance / 2: 27 mm from "
                         "the axis) stays inside the groove's floor, cam.pitch_radius - groove_depth / 2 = 27 mm from "
                         "the axis (got 54); or cam.groove_depth < 6 mm\n"),
    # as printed: 53 + 3 = 56 mm across, so 54 - 3 = 51 mm; a shallower groove, floor > 28 mm: depth < 4 mm
    ({"cam.bore": 53.0, "output.clearance": 3.0}, "cam.bore: must be < 51 mm, so the bore (its radius grown by "
                                                  "output.clearance / 2: 28 mm from the axis) stays inside the "
                                                  "groove's floor, cam.pitch_radius - groove_depth / 2 = 27 mm from "
                                                  "the axis (got 53); or cam.groove_depth < 4 mm\n"),
    # a 50 mm bore's key (44 < d <= 50: b 14, t2 3.8) reaches 25 + 3.8 = 28.8 mm; 2 (27 - 3.8) = 46.4 mm
    ({"cam.bore": 50.0, "hub.keyway": True}, "cam.bore: must be < 46.4 mm, so the bore (its radius grown by "
                                             "output.clearance / 2, and its keyway's seat: 28.8 mm from the axis) "
                                             "stays inside the groove's floor"),
    # the floor at 25.5 mm: a 44 mm bore's key (38 < d <= 44: t2 3.3) reaches 25.3, any larger one's 22 + 3.8 > 25.5
    ({"cam.bore": 45.0, "hub.keyway": True, "cam.groove_depth": 9.0}, "cam.bore: must be at most 44 mm, so the bore "
                                                                      "(its radius grown by output.clearance / 2, and "
                                                                      "its keyway's seat: 26.3 mm from the axis)"),
    # the roller wider than the pitch cylinder: no depth will do, the roller is named (27 - 0.1)
    ({"follower.roller_radius": 30.0}, "follower.roller_radius: must be < 26.9 mm, so the roller fits on the groove's "
                                       "floor, cam.pitch_radius - groove_depth / 2 = 27 mm from the axis (got 30)\n"),
    ({"cam.groove_depth": 60.0}, "cam.groove_depth: must be < 49.8 mm, so the groove's floor (cam.pitch_radius - "
                                 "groove_depth / 2 from the axis) stays wider than the roller there, 5.1 mm (got 60); "
                                 "or cam.pitch_radius > 35.1 mm\n"),
    # the pitch radius made too small: the depth (the more specific size) is named, the pitch radius offered
    ({"cam.pitch_radius": 6.0}, "cam.groove_depth: must be < 1.8 mm, so the groove's floor (cam.pitch_radius - "
                                "groove_depth / 2 from the axis) stays wider than the roller there, 5.1 mm (got 6); or "
                                "cam.pitch_radius > 8.1 mm\n"),
    # no depth and no roller will do (the floor at 0.05 mm): the pitch radius, 9.9 / 2 + 5.1 mm at least
    ({"cam.pitch_radius": 5.0, "cam.groove_depth": 9.9, "cam.bore": 0.0},
     "cam.pitch_radius: must be > 10.05 mm, so the groove's floor (cam.pitch_radius - groove_depth / 2 from the axis) "
     "holds the roller, 5.1 mm there (got 5)\n"),
    # the floor at 3.9 mm: the smallest keyed bore, over 6 mm with a 1 mm seat, reaches past it; a plain one < 7.8
    ({"cam.bore": 7.0, "hub.keyway": True, "cam.groove_depth": 52.2, "follower.roller_radius": 1.0},
     "hub.keyway: no keyed bore (DIN 6885-1: over 6 mm) fits inside the groove's floor, cam.pitch_radius - "
     "groove_depth / 2 = 3.9 mm from the axis; leave the keyway out (a plain bore must be < 7.8 mm)\n"),
    # the floor at 2.5 mm: a clearance of 5 mm alone opens the bore past it
    ({"cam.bore": 1.0, "output.clearance": 5.0, "cam.groove_depth": 55.0, "follower.roller_radius": 0.5},
     "output.clearance: must be < 4 mm, so the bore as printed (its diameter grown by the clearance) stays inside "
     "the groove's floor, cam.pitch_radius - groove_depth / 2 = 2.5 mm from the axis (got 5)\n"),
])
def test_each_size_relation_names_the_field_that_alone_is_wrong(tmp_path, change, message):
    """Each refusal names a field whose allowed range, given the others, is not empty (so the one a single change put
    wrong is among those it could name) and states that range in mm; a trailing newline in ``message`` means the
    whole line."""
    path = tmp_path / "barrel.toml"
    path.write_text(CONTRACT)
    assert_refused(path, change, message.rstrip("\n"), tmp_path)
    if message.endswith("\n"):
        args = ["build", str(path), "-o", str(tmp_path / "out")]
        for key, value in change.items():
            args += ["--set", f"{key}={json.dumps(value)}"]
        assert CliRunner().invoke(main, args).output == f"error: {message.rstrip(chr(10))}\n"


def test_a_bore_that_leaves_a_thin_wall_is_built_with_a_warning(tmp_path):
    """A 44 mm keyed bore (seat 3.3 mm) under a floor at 25.5 mm leaves 25.5 - 22 - 3.3 = 0.2 mm: built, warned."""
    report, _ = _build(tmp_path, "cam.bore=44", "hub.keyway=true", "cam.groove_depth=9",
                       "output.formats=['json']")
    assert "only 0.2 mm of material between the bore and the groove's floor" in report["warnings"]
    (tmp_path / "plain").mkdir()
    plain, _ = _build(tmp_path / "plain", "output.formats=['json']")
    assert not any("material between the bore" in w for w in plain["warnings"])


def test_required_keys():
    for key in ("pitch_radius", "length", "groove_depth"):
        raw = copy.deepcopy(RAW)
        del raw["cam"][key]
        with pytest.raises(ValueError, match=rf"^cam\.{key}: missing: give the .+ in mm$"):
            validate_spec(raw)
    disc = copy.deepcopy(RAW)
    disc["cam"] = {"base_radius": 30.0, "thickness": 8.0, "length": 10.0}
    with pytest.raises(ValueError, match=r'^cam\.length: not a key of a disc cam \(a key of cam\.kind = "barrel"\); '
                                         r'it takes: base_radius, thickness, allow_undercut, bore, rotation, '
                                         r'max_pressure_angle, min_rho_margin, rpm, material, rpm_range, rpm_steps$'):
        validate_spec(disc)
    del disc["cam"]["length"], disc["cam"]["thickness"]
    with pytest.raises(ValueError, match=r"^cam\.thickness: missing: give plate thickness \(STL extrusion\) in mm$"):
        validate_spec(disc)


def test_a_keyed_bore_and_the_printing_clearance(tmp_path):
    import trimesh

    _, out = _build(tmp_path, "hub.keyway=true", "output.clearance=0.3", "output.formats=['stl','json']")
    mesh = trimesh.load(out / "barrel.stl")
    assert mesh.is_watertight
    # the bore's wall: the smallest radius of the mesh's vertices at mid-length is the opened bore's, 5.15 mm
    v = mesh.vertices
    r = np.hypot(v[:, 0], v[:, 1])
    assert r.min() == pytest.approx(5.15, abs=1e-6)


def test_size_refuses_a_barrel_in_one_line(tmp_path):
    path = tmp_path / "barrel.toml"
    path.write_text(CONTRACT)
    result = CliRunner().invoke(main, ["size", str(path)])
    assert result.exit_code == 2 and result.output.startswith("error: template: a barrel cam has no base radius")


def test_a_barrel_family(tmp_path):
    path = tmp_path / "barrel.toml"
    path.write_text(CONTRACT)
    fam = tmp_path / "fam.toml"
    fam.write_text(f'base = "{path.as_posix()}"\nname = "bfam"\n[sweep]\n"cam.pitch_radius" = [30.0, 40.0]\n'
                   '"output.formats" = [["json"]]\n')
    result = CliRunner().invoke(main, ["family", str(fam), "-o", str(tmp_path / "f")])
    assert result.exit_code == 0, result.output
    rows = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert [r["status"] for r in rows] == ["ok", "ok"]
    beta = math.radians(150)
    assert [r["pressure_angle_max_deg"] for r in rows] == pytest.approx(
        [math.degrees(math.atan(2 * 20 / beta / rm)) for rm in (30.0, 40.0)], abs=1e-6)
