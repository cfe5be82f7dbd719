"""Barrel ribs: a ridge round the cylinder between two rollers. Both rollers placed along the exported solid touch
their walls with half the clearance and never cut in; the solid's volume against the exact walls'; the developed
drawing; the thinnest rib; refusals."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.core.errors import DesignError
from camgen.api import design_cam
from camgen.spec import load_spec
from tests.conftest import ROOT
from tests.camgen.kinds.barrel.test_barrel_oscillating import _wall_samples
from tests.camgen.kinds.barrel.test_barrel_tolerances import exact_volume
from tests.support.refusals import assert_refused

RIB = ROOT / "templates" / "barrel-rib.toml"
RR, C = 5.0, 0.2                                    # the rollers' radius, the running clearance (default)


def _build(tmp_path: Path, *sets: str) -> tuple[dict, Path]:
    args = ["build", str(RIB), "-o", str(tmp_path / "out")] + [a for s in sets for a in ("--set", s)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return json.loads((tmp_path / "out" / "barrel-rib.json").read_text()), tmp_path / "out"


def _gaps(samples: np.ndarray, theta: np.ndarray, heights: np.ndarray, sense: int, inner: float, outer: float,
          above: bool) -> np.ndarray:
    """For each cam angle, the least distance from a roller's axis (radial, at the polar angle -sense theta and the
    given height, from the core's radius to the rim's) to the samples on the side of the rib (above it or below)."""
    psi_s = np.arctan2(samples[:, 1], samples[:, 0])
    order = np.argsort(psi_s)
    psi_s, samples = psi_s[order], samples[order]
    out = np.empty(len(theta))
    for k, (t, z) in enumerate(zip(theta, heights, strict=True)):
        psi = -sense * t
        axis = np.array([math.cos(psi), math.sin(psi), 0.0])
        centre = math.atan2(math.sin(psi), math.cos(psi))             # the samples within 0.4 rad, round the seam
        spans = [(centre - 0.4 + shift, centre + 0.4 + shift) for shift in (-2 * math.pi, 0.0, 2 * math.pi)]
        p = np.concatenate([samples[np.searchsorted(psi_s, a):np.searchsorted(psi_s, b)] for a, b in spans])
        p = p[np.abs(p[:, 2] - z) < 12.0]
        p = p[p[:, 2] > z] if above else p[p[:, 2] < z]
        along = np.clip(p @ axis, inner, outer)
        out[k] = np.linalg.norm(p - along[:, None] * axis - np.array([0.0, 0.0, z]), axis=1).min()
    return out


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_both_rollers_run_on_the_exported_rib(tmp_path, rotation):
    """The issue's test for a rib: the roller below the rib and the one above it (cylinders of radius Rr about their
    radial axes, 2 g apart along the cam's axis) placed along the exported STL at 720 cam angles (cw: 240) each touch
    their wall of the rib within the tolerance plus the clearance, and never cut in; nothing of the rib lies on the
    far side of either roller."""
    import trimesh

    report, out = _build(tmp_path, f"cam.rotation='{rotation}'")
    design = design_cam(load_spec(RIB, (f"cam.rotation='{rotation}'",)))
    below, above = design.rib
    assert above.z0 - below.z0 == pytest.approx(2 * (8.0 / 2 + RR + C / 2), abs=1e-12)
    mesh = trimesh.load(out / "barrel-rib.stl")
    assert mesh.is_watertight and report["mesh"]["watertight"]
    samples = _wall_samples(mesh, 27.0)
    tol = report["tolerance_mm"]
    theta = np.linspace(0, 2 * math.pi, 720 if rotation == "ccw" else 240, endpoint=False)
    sense = 1 if rotation == "ccw" else -1
    for walls, up in ((below, True), (above, False)):
        heights = walls.centre(theta)[0]
        gap = _gaps(samples, theta, heights, sense, 27.0, 33.0, up) - RR
        assert np.all(gap >= C / 2 - tol) and np.all(gap <= C / 2 + tol), (gap.min(), gap.max())
        assert gap.min() > 0                                           # never cuts into the roller
    # the rib stays between the rollers: no wall sample below the lower roller's axis or above the upper one's
    zc = design.walls.centre(theta)[0]
    assert samples[:, 2].min() > (zc - (above.z0 - below.z0) / 2).min() - 1e-9
    assert samples[:, 2].max() < (zc + (above.z0 - below.z0) / 2).max() + 1e-9


def test_the_solids_volume_is_the_core_and_the_exact_rib(tmp_path):
    """The exported solid's volume against the core pi (Ri^2 - rb^2) L and the rib from its exact walls
    (:func:`tests.camgen.kinds.barrel.test_barrel_tolerances.exact_volume`: on each cylinder of radius r the rib's
    developed area, the loop integral of z dphi of the upper wall less the lower's, integrated over r by
    Gauss-Legendre); within the tolerance times the walls' area."""
    report, _ = _build(tmp_path, "output.formats=['stl','json']")
    expected = exact_volume(design_cam(load_spec(RIB)))[0]
    rib = expected - math.pi * (27.0 ** 2 - 5.0 ** 2) * 70.0
    walls_area = 2 * (33.0 - 27.0) * 2 * math.pi * 30.0 * 1.3        # both walls, sloped
    assert report["mesh"]["volume_mm3"] == pytest.approx(expected, abs=report["tolerance_mm"] * walls_area)
    assert rib == pytest.approx(8.0 * 6.0 * 2 * math.pi * 30.0, rel=0.05)   # about width x height x circumference


def test_the_developed_drawing_carries_the_rib_and_both_rollers(tmp_path):
    import ezdxf

    report, out = _build(tmp_path, "output.formats=['dxf','json']")
    doc = ezdxf.readfile(out / "barrel-rib-developed.dxf")
    lines = {layer: [np.array([(p[0], p[1]) for p in e.get_points("xy")]) for e in doc.modelspace()
                     if e.dxf.layer == layer] for layer in ("GROOVE", "PITCH")}
    assert len(lines["GROOVE"]) == 2 and len(lines["PITCH"]) == 2
    design = design_cam(load_spec(RIB))
    below, above = design.rib
    for walls, side, pts in ((below, 1, lines["GROOVE"][0]), (above, -1, lines["GROOVE"][1])):
        phi, z = walls.developed(pts[:, 0] / 30.0, 30.0, side)       # the walls at the pitch cylinder, about there
        assert np.interp(pts[:, 0], 30.0 * phi, z) == pytest.approx(pts[:, 1], abs=0.02)
    low, high = (np.interp(np.linspace(1, 180, 50), p[:, 0], p[:, 1]) for p in lines["PITCH"])
    assert high - low == pytest.approx(np.full(50, 18.2), abs=1e-9)    # the rollers' axes, 2 g apart
    assert report["cam"]["form"] == "rib" and report["cam"]["roller_centres_apart_mm"] == pytest.approx(18.2)


def test_the_thinnest_rib_and_its_limit():
    """The rib's thinnest normal width 2 g cos(alpha) - 2 Rw, alpha the track's steepest slope on the core (tan
    alpha = max s' / Ri); refused at the limit width and 1e-12 below, built 1e-9 above."""
    design = design_cam(load_spec(RIB))
    s1 = 2 * 20.0 / math.radians(150.0)                               # the cycloid's steepest s' (mm/rad)
    cos = math.cos(math.atan(s1 / 27.0))
    rw = RR + C / 2
    assert design.rib_thinnest[0] == pytest.approx(2 * (4.0 + rw) * cos - 2 * rw, rel=1e-9)
    limit = 2 * rw / cos - 2 * rw
    for width, ok in ((limit, False), (limit * (1 - 1e-12), False), (limit * (1 + 1e-9), True)):
        if ok:
            assert design_cam(load_spec(RIB, (f"cam.rib_width={width!r}",))).rib_thinnest[0] > 0
        else:
            with pytest.raises(DesignError, match=r"cam.rib_width: the rollers leave the rib no width near 75.00"):
                design_cam(load_spec(RIB, (f"cam.rib_width={width!r}",)))


@pytest.mark.parametrize("change, message", [
    ({"cam.rib_width": None}, "cam.rib_width: required for a barrel rib"),
    ({"cam.barrel_form": "groove"}, 'cam.rib_width: only for a barrel rib (cam.barrel_form = "rib")'),
    ({"cam.length": 45.0}, "cam.length: must be > 48.4 mm, the follower's travel, the rib and both rollers"),
    ({"follower.roller_shape": "conical"}, "cam.barrel_form: a rib takes a translating-roller follower with "
                                           "cylindrical rollers"),
    ({"cam.barrel_form": "ridge"}, "cam.barrel_form: "),
    ({"cam.bore": 56.0}, "cam.bore: must be < 54 mm, so the bore (its radius grown by output.clearance / 2: 28 mm from "
                         "the axis) stays inside the rib's core, cam.pitch_radius - groove_depth / 2 = 27 mm from the "
                         "axis (got 56); or cam.groove_depth < 4 mm"),
])
def test_bad_rib_values_are_refused_by_name(tmp_path, change, message):
    if change.get("cam.rib_width", 0) is None:
        text = RIB.read_text().replace("rib_width = 8.0", "")
        (tmp_path / "t.toml").write_text(text)
        assert_refused(tmp_path / "t.toml", {}, message, tmp_path)
        return
    assert_refused(RIB, change, message, tmp_path)


def test_rib_keys_are_only_for_a_barrel(tmp_path):
    assert_refused(ROOT / "templates" / "rdrd.toml", {"cam.rib_width": 5.0},
                   'cam.rib_width: not a key of a disc cam (a key of cam.kind = "barrel"); it takes: ', tmp_path)
