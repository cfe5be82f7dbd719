"""Barrel cams cut for a conical roller (follower.roller_shape = "conical", its apex on the cam's axis): the bundled
template builds; the cone in its true pose touches both walls of the exported groove with half the clearance and
never cuts in; where the follower dwells the walls are radial lines and the cone rolls without slip, a cylinder
slipping by |r - Rm| / r; the rolling slip over the cycle against finite differences of the contact's motion; an
oscillating roller's cone; bad values."""
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

TEMPLATE = ROOT / "templates" / "barrel-conical.toml"
RAW = tomllib.loads(TEMPLATE.read_text())
RR, RM, RI, RO, CLEAR = 5.0, 30.0, 27.0, 33.0, 0.2
T = RR / RM                                     # the cone's radius grows by T a mm along its axis


def _with(**follower) -> dict:
    raw = copy.deepcopy(RAW)
    raw["follower"].update(follower)
    return raw


def test_the_bundled_template_and_its_report(tmp_path):
    result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "out" / "barrel-conical.json").read_text())
    f = report["follower"]
    assert f["roller_shape"] == "conical"
    assert f["cone_half_angle_deg"] == pytest.approx(math.degrees(math.atan(T)), abs=1e-9)
    grown = CLEAR / 2 * math.hypot(1, T)          # the cone grown by c/2 square to its surface
    assert f["groove_width_floor_mm"] == pytest.approx(2 * (T * RI + grown), abs=1e-9)
    assert f["groove_width_rim_mm"] == pytest.approx(2 * (T * RO + grown), abs=1e-9)
    assert report["mesh"]["watertight"] and report["wall_max_error_mm"] <= report["tolerance_mm"]
    assert 0 < report["rolling_slip"]["floor_percent"] < 3.0                 # a cylinder: 3/27 = 11.1 %
    assert "rolling slip (conical roller)" in result.output


def test_the_cone_runs_in_the_exported_groove(tmp_path):
    """The cone (apex on the cam's axis at the roller's height, radius T a at a mm along its axis) at 720 cam angles
    against the exported STL's walls: the least distance from its surface to the walls below and above it is half
    the clearance within the tolerance, never less."""
    import trimesh

    result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(tmp_path / "out"), "--set",
                                       "output.formats=['stl','json']"])
    assert result.exit_code == 0, result.output
    tol = json.loads((tmp_path / "out" / "barrel-conical.json").read_text())["tolerance_mm"]
    mesh = trimesh.load(tmp_path / "out" / "barrel-conical.stl")
    tri = mesh.vertices[mesh.faces]
    r = np.hypot(tri[..., 0], tri[..., 1])
    tri = tri[r.min(axis=1) > RI + 1e-4]                    # off the floor (single precision: 27 to 2e-6)
    i, j = np.meshgrid(np.arange(11), np.arange(11), indexing="ij")
    keep = i + j <= 10
    bary = np.stack([i[keep], j[keep], 10 - i[keep] - j[keep]], axis=1) / 10.0
    samples = np.einsum("kb,tbc->tkc", bary, tri).reshape(-1, 3)
    sectors = Sectors(samples, np.arctan2(samples[:, 1], samples[:, 0]))
    design = design_cam(validate_spec(RAW))
    theta = np.linspace(0, 2 * math.pi, 720, endpoint=False)
    zc = 15.0 + design.cam.program.evaluate(theta)[0]                        # z0 + s, the travel mid-length
    below, above = np.empty(len(theta)), np.empty(len(theta))
    for k, (t, z) in enumerate(zip(theta, zc, strict=True)):
        d = np.array([math.cos(-t), math.sin(-t), 0.0])
        near = sectors.near(-t, 0.4, z, 9.0)
        q = samples[near] - np.array([0.0, 0.0, z])
        a = q @ d
        rho = np.linalg.norm(q - a[:, None] * d, axis=1)
        assert np.all((rho > T * a) | (a < RI) | (a > RO))                   # none inside the roller
        g = np.array([1.0, T]) / math.hypot(1, T)                            # the cone's generator from its apex
        along = np.clip(a * g[0] + rho * g[1], RI * math.hypot(1, T), RO * math.hypot(1, T))
        gap = np.hypot(a - along * g[0], rho - along * g[1])                 # from the roller, floor to rim
        below[k], above[k] = gap[q[:, 2] < 0].min(), gap[q[:, 2] > 0].min()
    for gap in (below, above):
        assert np.all(gap >= CLEAR / 2 - tol) and np.all(gap <= CLEAR / 2 + tol), (gap.min(), gap.max())


def test_where_the_follower_dwells_the_walls_are_radial_lines():
    """In the dwells, the walls on the cylinders from the floor to the rim lie on one radial line each: the same
    polar angle, and z = zc +- (T r + c/2 / cos(half-angle)), through the cone's apex when the clearance is 0."""
    for clearance in (CLEAR, 0.0):
        raw = copy.deepcopy(RAW)
        raw["cam"]["running_clearance"] = clearance
        walls = design_cam(validate_spec(raw)).walls
        theta = np.radians(np.r_[np.linspace(151, 179, 8), np.linspace(331, 359, 8)])
        radii = np.linspace(RI, RO + 1.0, 9)
        zc = walls.centre(theta)[0]
        assert np.all(walls.centre(theta)[1] == 0)                           # a dwell
        for side in (-1, 1):
            psi, z = walls.wall(theta[:, None], radii[None, :], side)
            assert np.abs(psi + theta[:, None]).max() < 1e-12                # the roller's own radial plane
            offset = T * radii + clearance / 2 * math.hypot(1, T)
            assert np.abs(z - zc[:, None] - side * offset[None, :]).max() < 1e-12


def _slip_by_differences(design, theta: np.ndarray, radius: float, side: int, h: float = 1e-6) -> np.ndarray:
    """The roller's rolling slip at its contact on the cylinder of ``radius``, from the motion of the contact's cam
    point in the roller's frame by central differences (the roller's pose by its own geometry), the spin making it 0
    on the pitch cylinder; the contact from the walls of a groove without clearance (the roller itself)."""
    out = {}
    for r in (RM, radius):
        psi, z = design.walls.wall(theta, r, side)
        p = np.stack([r * np.cos(psi), r * np.sin(psi), z], axis=1)         # fixed on the cam

        def local(t: np.ndarray, p: np.ndarray = p) -> np.ndarray:
            zc = 15.0 + design.cam.program.evaluate(t)[0]
            c, s = np.cos(-t), np.sin(-t)
            q = p - np.stack([0 * t, 0 * t, zc], axis=1)
            return np.stack([q[:, 0] * c + q[:, 1] * s, -q[:, 0] * s + q[:, 1] * c, q[:, 2]], axis=1)

        q = local(theta)
        vel = (local(theta + h) - local(theta - h)) / (2 * h)
        rho = np.hypot(q[:, 1], q[:, 2])
        roll = np.stack([0 * rho, -q[:, 2], q[:, 1]], axis=1) / rho[:, None]
        out[r] = (np.einsum("ij,ij->i", vel, roll), rho, q[:, 0])
    drift, rho, _ = out[RM]
    spin = drift / rho
    drift, rho, a = out[radius]
    return (drift - spin * rho) / a


@pytest.mark.parametrize("shape", ["conical", "cylindrical"])
def test_rolling_slip_against_finite_differences(shape):
    """Over 720 cam angles, both walls, at the floor and the rim: the slip from finite differences of the contact's
    motion. In the dwells a cone's is 0 and a cylinder's |r - Rm| / r; the largest over the cycle is the reported
    one (which a cone keeps a quarter of a cylinder's)."""
    raw = _with(roller_shape=shape)
    raw["cam"]["running_clearance"] = 0.0
    design = design_cam(validate_spec(raw))
    reported = design_cam(validate_spec(_with(roller_shape=shape))).slip      # the same roller, with clearance
    theta = np.linspace(0, 2 * math.pi, 720, endpoint=False) + 1e-4
    dwell = design.walls.centre(theta)[1] == 0
    for name, r in (("floor", RI), ("rim", RO)):
        slips = np.array([_slip_by_differences(design, theta, r, side) for side in (-1, 1)])
        if shape == "conical":
            assert np.abs(slips[:, dwell]).max() < 1e-8
        else:
            assert np.abs(np.abs(slips[:, dwell]) - abs(r - RM) / r).max() < 1e-8
        assert 100 * np.abs(slips).max() <= reported[name] + 1e-6
        assert 100 * np.abs(slips).max() >= reported[name] - 0.01                 # the grid's half-degree steps
    if shape == "conical":
        assert reported["floor"] < 0.25 * 100 * (RM - RI) / RI


def test_an_oscillating_roller_may_be_conical(tmp_path):
    """A cone on an arm (apex where its axis passes nearest the cam's axis): the walls are the exact envelope (every
    wall point half the clearance from the nearest cone of a 1e5 grid), and it slips far less than a cylinder."""
    path = ROOT / "templates" / "barrel-oscillating.toml"
    raw = tomllib.loads(path.read_text())
    raw["follower"]["roller_shape"] = "conical"
    design = design_cam(validate_spec(raw))
    cylinder = design_cam(validate_spec(tomllib.loads(path.read_text())))
    assert design.slip["floor"] < 0.4 * cylinder.slip["floor"]
    taper, rm = 5.0 / 40.0, 40.0
    grid = np.linspace(0, 2 * math.pi, 100001)
    psi = np.radians(design.cam.program.evaluate(grid)[0] - 10.0)
    y, zc = 79.4 - 80.0 * np.cos(psi), 30.0 + 80.0 * np.sin(psi)
    d = np.stack([np.cos(-grid), np.sin(-grid), 0 * grid], axis=1)
    apex = np.stack([-np.sin(-grid) * y, np.cos(-grid) * y, zc], axis=1)
    theta = np.linspace(0, 2 * math.pi, 31)[:-1]
    for r in (36.0, rm, 44.0):
        for side in (-1, 1):
            ang, z = design.walls.wall(theta, r, side)
            for p in np.stack([r * np.cos(ang), r * np.sin(ang), z], axis=1):
                q = p - apex
                a = np.einsum("ij,ij->i", q, d)
                gap = (np.linalg.norm(q - a[:, None] * d, axis=1) - taper * a) / math.hypot(1, taper)
                assert abs(gap.min() - CLEAR / 2) < 2e-7, gap.min()
    result = CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "o"), "--set",
                                       "follower.roller_shape='conical'", "--set", "output.formats=['stl','json']"])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "o" / "barrel-oscillating.json").read_text())
    assert report["mesh"]["watertight"] and report["wall_max_error_mm"] <= report["tolerance_mm"]


@pytest.mark.parametrize("template, change, message", [
    ("rdrd.toml", {"follower.roller_shape": "conical"}, "follower.roller_shape: not a key of a translating-roller "
                                                        "follower (did you mean 'roller_width'?); it takes: "),
    ("barrel-conical.toml", {"follower.roller_shape": "spherical"}, "follower.roller_shape: unknown value 'spherical'"),
    ("barrel-conical.toml", {"follower.roller_radius": 30.0}, "follower.roller_radius: a conical roller's must be < "
                                                              "cam.pitch_radius = 30 mm, its apex on the cam's axis "
                                                              "(got 30)"),
    ("barrel-conical.toml", {"cam.length": 30.0}, "cam.length: must be > 31.2028 mm, the follower's travel and the "
                                                  "groove's width (got 30)"),
])
def test_bad_values_are_one_line_exit_2_nothing_written(tmp_path, template, change, message):
    assert_refused(ROOT / "templates" / template, change, message, tmp_path)
