"""Barrel cams with an oscillating roller: the bundled template builds; the roller in its true 3D pose (on its arm,
its axis square to the cam's and passing it by the chordal error) touches both walls of the exported groove with
half the clearance and never cuts in; the walls against a brute-force envelope; z = L sin(psi) and the chordal
error against an independent computation; the 3D pressure angle against finite differences; bad values."""
from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.api import design_cam
from camgen.spec import validate_spec
from tests.camgen.kinds.barrel.sectors import Sectors
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

#: how a refusal names the follower's table
ARM_TABLE = "a barrel cam's oscillating-roller follower (driven both ways, no spring)"


TEMPLATE = ROOT / "templates" / "barrel-oscillating.toml"
RAW = tomllib.loads(TEMPLATE.read_text())
L, C, RR, CLEAR = 80.0, 79.4, 5.0, 0.2
RM, RI, RO, LENGTH = 40.0, 36.0, 44.0, 60.0
SWING = 20.0


def _pose(design, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The roller's centre by the arm's own geometry, not the code under test: the arm's angle psi = s - swing/2
    (square to the cam's axis at mid-swing), the pivot at mid-length, C from the cam's axis: (y, z) in the fixed
    frame, y = C - L cos(psi), z = length/2 + L sin(psi)."""
    psi = np.radians(design.cam.program.evaluate(theta)[0] - SWING / 2)
    return C - L * np.cos(psi), LENGTH / 2 + L * np.sin(psi)


def _axis(theta: float, y: float, z: float, sense: int) -> tuple[np.ndarray, np.ndarray]:
    """The roller's axis in the cam's frame at cam angle ``theta``: its point nearest the cam's axis and its
    direction (the fixed frame's +X and (0, y, z), turned back by the cam's rotation sense theta)."""
    a = -sense * theta
    d = np.array([math.cos(a), math.sin(a), 0.0])
    foot = np.array([-math.sin(a) * y, math.cos(a) * y, z])
    return foot, d


def _build(tmp_path, *overrides: str) -> tuple[dict, object]:
    args = ["build", str(TEMPLATE), "-o", str(tmp_path / "out")] + [a for o in overrides for a in ("--set", o)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return json.loads((tmp_path / "out" / "barrel-oscillating.json").read_text()), tmp_path / "out"


def _wall_samples(mesh, inner: float) -> np.ndarray:
    """Points on the mesh's triangles off the floor, a barycentric grid of 66 points each."""
    tri = mesh.vertices[mesh.faces]
    tri = tri[np.hypot(tri[..., 0], tri[..., 1]).min(axis=1) > inner + 1e-4]     # single precision: 36 to 4e-6
    i, j = np.meshgrid(np.arange(11), np.arange(11), indexing="ij")
    keep = i + j <= 10
    bary = np.stack([i[keep], j[keep], 10 - i[keep] - j[keep]], axis=1) / 10.0
    return np.einsum("kb,tbc->tkc", bary, tri).reshape(-1, 3)


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_the_roller_on_its_arm_runs_in_the_exported_groove(tmp_path, rotation):
    """The roller (a cylinder of radius Rr about its axis, from the floor's radius to the rim's) in its true pose at
    720 cam angles (cw: 240) against the exported STL: it touches both walls within the tolerance plus half the
    clearance and never cuts in."""
    import trimesh

    report, out = _build(tmp_path, f"cam.rotation='{rotation}'")
    sense = 1 if rotation == "ccw" else -1
    design = design_cam(validate_spec(RAW | {"cam": RAW["cam"] | {"rotation": rotation}}))
    samples = _wall_samples(trimesh.load(out / "barrel-oscillating.stl"), RI)
    sectors = Sectors(samples, np.arctan2(samples[:, 1], samples[:, 0]))
    theta = np.linspace(0, 2 * math.pi, 720 if rotation == "ccw" else 240, endpoint=False)
    ys, zs = _pose(design, theta)
    below, above = np.empty(len(theta)), np.empty(len(theta))
    for k, (t, y, z) in enumerate(zip(theta, ys, zs, strict=True)):
        foot, d = _axis(t, y, z, sense)
        near = sectors.near(-sense * t, 0.4, z, 8.0)
        p = samples[near] - foot
        along = np.clip(p @ d, math.sqrt(RI**2 - y**2), math.sqrt(RO**2 - y**2))
        gap = np.linalg.norm(p - along[:, None] * d, axis=1)
        below[k], above[k] = gap[p[:, 2] < 0].min(), gap[p[:, 2] > 0].min()
    tol = report["tolerance_mm"]
    for gap in (below - RR, above - RR):
        assert np.all(gap >= CLEAR / 2 - tol) and np.all(gap <= CLEAR / 2 + tol), (gap.min(), gap.max())
    assert min(below.min(), above.min()) > RR                        # never cuts into the roller
    assert report["mesh"]["watertight"] and report["wall_max_error_mm"] <= tol


def test_the_walls_against_a_brute_force_envelope():
    """Every wall point (floor, pitch and rim cylinders, both walls) is Rw from the nearest roller's axis over a grid
    of 2e5 cam angles, the axes placed by the arm's own geometry, and no axis is nearer."""
    design = design_cam(validate_spec(RAW))
    grid = np.linspace(0, 2 * math.pi, 200001)
    ys, zs = _pose(design, grid)
    a = -grid
    d = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=1)
    foot = np.stack([-np.sin(a) * ys, np.cos(a) * ys, zs], axis=1)
    theta = np.linspace(0, 2 * math.pi, 41)[:-1]
    for r in (RI, RM, RO):
        for side in (-1, 1):
            psi, z = design.walls.wall(theta, r, side)
            pts = np.stack([r * np.cos(psi), r * np.sin(psi), z], axis=1)
            for p in pts:
                q = p - foot
                along = np.einsum("ij,ij->i", q, d)
                dist = np.where(along > 0, np.linalg.norm(q - along[:, None] * d, axis=1), np.inf)
                gap = dist.min() - (RR + CLEAR / 2)
                assert -1e-12 < gap < 1e-8, gap
            assert np.all(side * (z - _pose(design, theta)[1]) > 0)


def test_axial_height_is_l_sin_psi_and_the_chordal_error():
    """The roller's height and its axis's offset from the cam's axis against the arm's geometry; the chordal error
    the report states against the largest |C - L cos(psi)| over a grid of 1e6 cam angles; the least error at the
    pivot distance L (1 + cos(swing/2)) / 2, where it is L (1 - cos(swing/2)) / 2."""
    from camgen.kinds.barrel.outputs import barrel_report

    design = design_cam(validate_spec(RAW))
    theta = np.linspace(0, 2 * math.pi, 1_000_000, endpoint=False)
    y, z = _pose(design, theta)
    pose = design.walls.pose(theta)
    assert np.abs(pose[0] - z).max() < 1e-12                              # z = z0 + L sin(psi)
    assert np.abs(pose[3] + y).max() < 1e-12                              # e = -y for a ccw cam
    arm = barrel_report(design)["follower"]
    assert arm["chordal_error_mm"] == pytest.approx(np.abs(y).max(), abs=1e-9)
    assert arm["axial_stroke_mm"] == pytest.approx(z.max() - z.min(), abs=1e-9)
    assert arm["pitch_cylinder_departure_mm"] == pytest.approx(np.hypot(RM, y).max() - RM, abs=1e-9)
    half = math.radians(SWING / 2)
    assert arm["pivot_distance_least_mm"] == pytest.approx(L * (1 + math.cos(half)) / 2, abs=1e-9)
    best = copy.deepcopy(RAW)
    best["follower"]["pivot_distance"] = arm["pivot_distance_least_mm"]
    y_best = _pose(design, theta)[0] - C + arm["pivot_distance_least_mm"]
    assert barrel_report(design_cam(validate_spec(best)))["follower"]["chordal_error_mm"] == pytest.approx(
        np.abs(y_best).max(), abs=1e-9) == pytest.approx(L * (1 - math.cos(half)) / 2, abs=1e-9)


def test_pressure_angle_in_3d_against_finite_differences():
    """At the pitch, floor and rim cylinders: the normal of the exact wall (the cross product of its finite
    differences along theta and along the radius) against the roller centre's path (a finite difference of the
    arm's geometry), in the fixed frame: the angle between them is the pressure angle the design reports (the larger
    of the two walls')."""
    design = design_cam(validate_spec(RAW))
    theta = np.linspace(0, 2 * math.pi, 361)[:-1] + 0.001
    h = 1e-5

    for name, r in (("floor", RI), ("pitch", RM), ("rim", RO)):
        angles = []
        for side in (-1, 1):
            pts = [design.walls.wall(theta + dt, r, side) for dt in (-h, h)]
            along_t = [np.stack([r * np.cos(psi), r * np.sin(psi), z], axis=-1) for psi, z in pts]
            along_r = [np.stack([rr * np.cos(psi), rr * np.sin(psi), z], axis=-1)
                       for rr in (r - h, r + h) for psi, z in [design.walls.wall(theta, rr, side)]]
            normal = np.cross(along_t[1] - along_t[0], along_r[1] - along_r[0])
            c, s = np.cos(theta), np.sin(theta)
            normal = np.stack([c * normal[:, 0] - s * normal[:, 1], s * normal[:, 0] + c * normal[:, 1],
                               normal[:, 2]], axis=1)
            y0, z0 = _pose(design, theta - h)
            y1, z1 = _pose(design, theta + h)
            path = np.stack([np.zeros_like(y0), y1 - y0, z1 - z0], axis=1)
            cos = np.abs(np.einsum("ij,ij->i", normal, path)) / np.linalg.norm(normal, axis=1) / np.maximum(
                np.linalg.norm(path, axis=1), 1e-300)
            angles.append(np.where(np.linalg.norm(path, axis=1) > 1e-12, np.arccos(np.minimum(cos, 1.0)), 0.0))
        fd = np.maximum(*angles)
        from camgen.kinds.barrel.design import _developed_cam

        developed = _developed_cam(design.cam, r, design.walls)
        exact = np.abs(developed.pitch(theta).pressure_angle)
        moving = np.abs(design.cam.program.evaluate(theta)[1]) > 1e-2       # finite differences of a path
        assert np.abs(exact - fd)[moving].max() < 1e-6, (name, np.abs(exact - fd)[moving].max())  # starting to move
        assert np.abs(exact - fd).max() < 1e-4 and np.all(exact[fd == 0] == 0)  # lose digits; standing: both 0
        assert design.pressure_deg[name] >= math.degrees(fd.max()) - 1e-6
        assert design.pressure_deg[name] < math.degrees(fd.max()) + 0.05       # the grid's 1 degree steps
    assert design.pressure_deg["pitch"] == pytest.approx(design.analysis.pressure_angle_max_deg, abs=1e-12)


@pytest.mark.parametrize("change, message", [
    ({"follower.pivot_distance": 40.0}, "follower.pivot_distance: must be over 49.1 and under 109.685 mm, so the "
                                        "roller's axis passes the cam's axis"),
    ({"follower.arm_length": 5000.0, "follower.pivot_distance": 5000.0, "cam.length": 2000.0},
     "follower.arm_length: must be < 4067.86 mm, so the arm's chordal error (half of arm_length (1 - cos(swing / 2)) "
     "at best) leaves the roller in the groove (got 5000)"),
    ({"cam.length": 30.0}, "cam.length: must be > 37.9837 mm, the roller's axial stroke"),
    ({"follower.offset": 2.0}, f"follower.offset: not a key of {ARM_TABLE}; it takes: "
                               "roller_radius, pivot_distance, arm_length, inertia, arm_mass, arm_com, roller_shape, "),
    ({"follower.mass": 2.0, "follower.orientation": 0.0}, "follower.orientation: not modelled for a barrel's arm"),
    ({"follower.spring_rate": 2.0}, f"follower.spring_rate: not a key of {ARM_TABLE}; "),
    ({"follower.roller_width": 8.0}, f"follower.roller_width: not a key of {ARM_TABLE} (did you mean "
                                     "'roller_shape'?); it takes: "),
    ({"cam.material": "steel"}, "cam.material: a barrel cam's contact pressure is at cam.rpm with follower.mass"),
    ({"follower.face_margin": 2.0}, f"follower.face_margin: not a key of {ARM_TABLE}; "),
])
def test_bad_values_are_one_line_exit_2_nothing_written(tmp_path, change, message):
    assert_refused(TEMPLATE, change, message, tmp_path)


def test_required_keys_and_a_swing_of_180_degrees_or_more():
    for key in ("arm_length", "pivot_distance"):
        raw = copy.deepcopy(RAW)
        del raw["follower"][key]
        with pytest.raises(ValueError, match=rf"^follower\.{key}: missing: give oscillating(?: roller)?: .* in mm$"):
            validate_spec(raw)
    raw = copy.deepcopy(RAW)
    raw["motion"] = [{"type": "rise", "law": "cycloidal", "lift": 70.0, "angle": 60.0}] * 3 + [
        {"type": "return", "law": "cycloidal", "lift": 70.0, "angle": 60.0}] * 3
    with pytest.raises(ValueError, match=r"^motion: an arm on a barrel cam swings less than 180 degrees in all "
                                         r"\(got 210\)$"):
        validate_spec(raw)


def test_an_oscillating_barrel_family(tmp_path):
    fam = tmp_path / "fam.toml"
    fam.write_text(f'base = "{TEMPLATE.as_posix()}"\nname = "ofam"\n[sweep]\n"cam.pitch_radius" = [40.0, 50.0]\n'
                   '"output.formats" = [["json"]]\n')
    result = CliRunner().invoke(main, ["family", str(fam), "-o", str(tmp_path / "f")])
    assert result.exit_code == 0, result.output
    rows = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert [r["status"] for r in rows] == ["ok", "ok"]
    assert rows[0]["pressure_angle_max_deg"] > rows[1]["pressure_angle_max_deg"]     # a larger cylinder is flatter
