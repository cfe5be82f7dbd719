"""The exported outline: within tolerance of the exact surface, with vertices the tolerance needs."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.flat import build_cam
from camgen.convergence_study import contour_error
from camgen.outline import exact_outline
from tests.conftest import template


@pytest.mark.parametrize("tol", [1e-1, 1e-2, 1e-3, 1e-4])
def test_outline_within_tolerance_by_two_measures(tol):
    cam = build_cam(template())
    outline = exact_outline(cam, tol)
    assert 0 < outline.max_error_mm <= tol
    # independent: distance of points of the polyline to the pitch curve, minus the roller radius
    deviation = contour_error(cam, outline.contour, tol)
    assert deviation <= tol
    assert deviation == pytest.approx(outline.max_error_mm, rel=0.05)


def test_vertex_count_follows_the_tolerance_not_a_fixed_count():
    """Chord error ~ spacing^2, so 100x tighter tolerance needs ~10x the vertices."""
    cam = build_cam(template())
    counts = [len(exact_outline(cam, tol).contour.vertices) for tol in (1e-2, 1e-4)]
    assert 8.5 < counts[1] / counts[0] < 11.5
    # and the error sits close to the tolerance: no vertex is wasted
    assert exact_outline(cam, 1e-3).max_error_mm > 0.7e-3


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_outline_is_a_valid_counter_clockwise_ring(rotation):
    """Either way the cam turns, its outline runs counter-clockwise (its contact point runs round the centre against
    the cam's turn), a valid ring of read-only vertices."""
    import shapely

    outline = exact_outline(build_cam(template({"cam.rotation": rotation})), 0.01)
    assert outline.contour.area > 0 and not outline.contour.vertices.flags.writeable
    ring = outline.contour.flatten(0.001)
    assert shapely.Polygon(ring).is_valid
    steps = np.linalg.norm(np.diff(np.vstack([ring, ring[:1]]), axis=0), axis=1)
    assert steps.min() > 1e-6                                       # no duplicate or zero-length pieces


def test_dwells_are_exact_arcs_about_the_cam_centre():
    cam = build_cam(template())
    outline = exact_outline(cam, 0.01)
    _, centres, radii, angles = outline.contour.arcs()
    assert np.abs(centres).max() < 1e-9
    base = math.hypot(5.0, cam.follower.d0) - 10.0
    top = math.hypot(5.0, cam.follower.d0 + 20.0) - 10.0
    assert sorted(radii) == pytest.approx([base, top], abs=1e-9)
    assert np.abs(angles) == pytest.approx([math.radians(60)] * 2, abs=1e-12)


def test_area_converges_to_the_exact_area():
    cam = build_cam(template())
    areas = [exact_outline(cam, tol).contour.area for tol in (1e-2, 1e-3, 1e-4, 1e-5)]
    diffs = np.abs(np.diff(areas))
    assert diffs[1] < diffs[0] / 5 and diffs[2] < diffs[1] / 5


def test_biarcs_within_tolerance_with_far_fewer_entities():
    cam = build_cam(template())
    for tol in (1e-2, 1e-4):
        poly, arcs = exact_outline(cam, tol), exact_outline(cam, tol, "biarcs")
        assert arcs.max_error_mm <= tol
        assert contour_error(cam, arcs.contour, tol) <= tol
        assert len(arcs.contour.vertices) < len(poly.contour.vertices) / 3
        assert arcs.contour.n_lines == 0


def test_error_order_of_polylines_about_2_and_of_biarcs_at_least_2_5():
    from camgen.convergence_study import convergence, error_order

    cam = build_cam(template())
    poly = convergence(cam, [1e-2, 1e-3, 1e-4], "polylines", repeats=1)
    arcs = convergence(cam, [1e-2, 1e-3, 1e-4], "biarcs", repeats=1)
    assert all(r.max_error_mm <= r.tolerance_mm for r in poly + arcs)
    assert 1.8 < error_order(poly) < 2.2
    assert error_order(arcs) >= 2.5


def test_biarcs_read_back_from_the_dxf_are_tangent_continuous(tmp_path):
    """At every vertex the arc arriving and the arc leaving share their tangent (G1), as a CNC controller wants."""
    import ezdxf

    from camgen.api import write_cam
    from camgen.api import design_cam
    from camgen.core.shapes import Contour

    design = design_cam(template({"output.curves": "biarcs", "output.formats": ["dxf"]}))
    write_cam(design, tmp_path)
    pl = ezdxf.readfile(tmp_path / "rdrd.dxf").modelspace().query("LWPOLYLINE")[0]
    pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
    c = Contour(pts[:, :2], pts[:, 2])
    p, q = c.vertices, np.roll(c.vertices, -1, axis=0)
    chord = np.arctan2(q[:, 1] - p[:, 1], q[:, 0] - p[:, 0])
    half = 2 * np.arctan(c.bulges)                       # half the included angle
    leave, arrive = chord - half, chord + half           # tangent directions at a piece's start and end
    turn = np.angle(np.exp(1j * (leave - np.roll(arrive, 1))))
    assert np.abs(turn).max() < 1e-6
    # the dwells are still exact arcs about the cam centre
    _, centres, radii, _ = c.arcs()
    at_centre = np.linalg.norm(centres, axis=1) < 1e-9
    cam = design.cam
    assert sorted(np.round(radii[at_centre], 9)) == pytest.approx(
        [math.hypot(5.0, cam.follower.d0) - 10.0, math.hypot(5.0, cam.follower.d0 + 20.0) - 10.0], abs=1e-9)
