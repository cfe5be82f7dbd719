"""The bore and hole checks decided by bounds (issue 16): design_cam settles them without flattening the outline
where bounds make them certain, and is otherwise the exact check on the flattened outline as before. A bound must
never pass what the exact check refuses; the wall it no longer measures is measured when read, to the same bits."""
from __future__ import annotations

import numpy as np
import pytest
import shapely

import camgen.profile
from camgen.core.errors import DesignError
from camgen.core.shapes import Contour
from camgen.api import design_cam
from camgen.profile import THIN_WALL, _inside_clear
from tests.conftest import template


def _random_contour(rng: np.random.Generator, trial: int) -> Contour:
    """A closed contour of lines and arcs (bulges up to 1.2): star-shaped round the origin, a circle of arcs with
    a few lines, or vertices anywhere (self-crossing, perhaps not round the origin)."""
    n = int(rng.integers(3, 30))
    angles = np.sort(rng.uniform(0, 2 * np.pi, n))
    radii = rng.uniform(5, 50, n)
    bulges = np.where(rng.random(n) < 0.3, rng.uniform(-1.2, 1.2, n), 0.0)
    if trial % 3 == 1:                                   # arcs about the origin, as a cam's dwells are
        radii = np.full(n, rng.uniform(10, 50))
        bulges = np.where(rng.random(n) < 0.5, np.tan(np.diff(angles, append=angles[0] + 2 * np.pi) / 4), bulges)
    elif trial % 3 == 2:
        angles = rng.uniform(0, 2 * np.pi, n)
    return Contour(np.column_stack([radii * np.cos(angles), radii * np.sin(angles)]), bulges)


def test_a_bound_passes_no_point_that_the_flattened_outline_does_not_hold_clear():
    """Wherever a point is passed with a reach, shapely finds it inside the outline flattened at that tolerance
    and further than the reach from it; and the bounds pass most points that are (they are worth having)."""
    rng = np.random.default_rng(16)
    passed = clear = 0
    for trial in range(400):
        contour = _random_contour(rng, trial)
        points = np.concatenate([[0j], rng.normal(0, 15, 4) + 1j * rng.normal(0, 15, 4)])
        reach = rng.uniform(0, 20, len(points))
        for tol in (1.0, 0.01, 1e-4):
            polygon = shapely.Polygon(contour.flatten(tol))
            for point, r in zip(points, reach, strict=True):
                at = shapely.Point(point.real, point.imag)
                exact = polygon.contains(at) and polygon.exterior.distance(at) > r
                if _inside_clear(contour, tol, np.array([point]), np.array([r])):
                    passed += 1
                    assert exact, (trial, tol, point, r)
                clear += exact and polygon.is_valid
    assert passed > 0.5 * clear


def test_several_points_pass_together_only_where_each_passes_alone():
    rng = np.random.default_rng(3)
    for trial in range(200):
        contour = _random_contour(rng, trial)
        points = rng.normal(0, 10, 3) + 1j * rng.normal(0, 10, 3)
        reach = rng.uniform(0, 10, 3)
        alone = [_inside_clear(contour, 0.01, points[i:i + 1], reach[i:i + 1]) for i in range(3)]
        assert _inside_clear(contour, 0.01, points, reach) == all(alone)


def test_the_bound_for_all_pieces_at_once_passes_only_where_each_piece_s_own_does():
    """_far_from_all (nearest vertex, longest chord, widest bulge) is the pieces' own bounds taken at their worst:
    where it passes, each piece's own passes too; it passes the rdrd template's bore, so that path is taken."""
    rng = np.random.default_rng(7)
    passed = 0
    for trial in range(600):
        contour = _random_contour(rng, trial)
        bulge = np.abs(contour.bulges)
        if bulge.max() > 1.0:
            continue
        points = np.concatenate([[0j], rng.normal(0, 5, 2) + 1j * rng.normal(0, 5, 2)])
        reach = rng.uniform(0, 8, len(points))
        z = contour.vertices.view(np.complex128)[:, 0]
        ring = np.concatenate((z, z[:1])) - points[:, None]
        near, length = np.abs(ring), np.abs(np.diff(ring[0]))
        margin = camgen.profile._CERTAIN * (1.0 + near.max() ** 2)
        if camgen.profile._far_from_all(near, length, float(bulge.max()), reach, margin):
            passed += 1
            low, half = np.minimum(near[:, :-1], near[:, 1:]), length / 2
            assert (low * low - half * half - (reach[:, None] + half * bulge) ** 2 > margin).all(), trial
    assert passed > 20
    design = design_cam(template())
    z = design.outline.contour.vertices.view(np.complex128)[:, 0]
    ring = np.concatenate((z, z[:1]))[None, :]
    bore = np.array([design.spec.cam.bore / 2 + THIN_WALL])
    assert camgen.profile._far_from_all(np.abs(ring), np.abs(np.diff(ring[0])),
                                       float(np.abs(design.outline.contour.bulges).max()), bore, 1e-6)


def _exact_wall(design) -> float:
    """The wall round the bore as shapely measures it on the nominal outline's chords."""
    body = shapely.Polygon(design.outline.contour.flatten(design.tolerance))
    return float(body.exterior.distance(shapely.Point(0.0, 0.0))) - design.spec.cam.bore / 2


def test_the_reference_cam_is_checked_without_flattening_and_its_wall_measured_when_read(monkeypatch):
    made = []
    real = camgen.profile.outline_body
    monkeypatch.setattr(camgen.profile, "outline_body", lambda *args: made.append(args) or real(*args))
    design = design_cam(template({"hub.bolt_circle": 30.0, "hub.bolt_holes": 4, "hub.bolt_hole_diameter": 4.0}))
    assert made == []
    assert design.wall_mm == _exact_wall(design)
    assert len(made) == 1


@pytest.mark.parametrize("wall", [THIN_WALL + 0.5, THIN_WALL - 0.5, 1e-3])
def test_a_thin_wall_is_measured_and_warned_of_as_before(wall):
    reach = design_cam(template()).wall_mm + 5.0             # how near the outline comes to the centre (mm)
    design = design_cam(template({"cam.bore": 2 * (reach - wall)}))
    assert design.wall_mm == _exact_wall(design)
    thin = [w for w in design.warnings if "of material between the bore" in w]
    assert thin == ([f"only {design.wall_mm:.3g} mm of material between the bore and the outline"]
                    if wall < THIN_WALL else [])


def test_a_bore_as_wide_as_the_outline_is_refused_by_the_exact_check():
    reach = design_cam(template()).wall_mm + 5.0
    assert design_cam(template({"cam.bore": np.nextafter(2 * reach, 0)})).wall_mm > 0
    for bore in (2 * reach, 2 * reach + 1e-9, 100.0):
        with pytest.raises(DesignError, match=r"^cam\.bore: .* leaves no material; the outline comes within "):
            design_cam(template({"cam.bore": bore}))


def _outcome(overrides: dict) -> tuple:
    """What a design of rdrd with ``overrides`` comes to: its error message, or its wall warnings and wall (mm)."""
    try:
        design = design_cam(template(overrides))
    except DesignError as error:
        return ("refused", str(error))
    return ("made", tuple(w for w in design.warnings if "material" in w), design.wall_mm)


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
@pytest.mark.parametrize("keyway", [False, True])
def test_the_bounds_decide_as_the_exact_check_for_holes_touching_the_outline(monkeypatch, rotation, keyway):
    """Bolt holes whose edge lies within 1e-3 to 1e-8 mm of the outline's nearest approach (its flattened dwell), on
    it, or past the dwell's arc, with and without a keyed bore, in both senses: the design with its bounds and the
    design forced to the exact check (shapely on the flattened outline) make the same cam, warnings and wall or
    refuse it with the same message; and some are refused."""
    reach = design_cam(template()).wall_mm + 5.0             # how near the outline comes to the centre (mm)
    outcomes = []
    for diameter in (2.0, 6.0):
        for eps in (-1e-3, -1e-8, 0.0, 1e-8, 1e-3, 0.02):       # 0.02: past the dwell's arc, not only its chords
            overrides = {"cam.rotation": rotation, "hub.keyway": keyway, "cam.bore": 10.0,
                         "hub.bolt_circle": 2 * (reach - diameter / 2 + eps), "hub.bolt_holes": 12,
                         "hub.bolt_hole_diameter": diameter}
            bounded = _outcome(overrides)
            with monkeypatch.context() as m:
                m.setattr(camgen.profile, "_certainly_clear", lambda *args: False)
                assert _outcome(overrides) == bounded, overrides
            outcomes.append(bounded[0])
    assert "refused" in outcomes and "made" in outcomes

