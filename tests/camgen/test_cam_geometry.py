"""Pitch curve, pressure angle, curvature and undercut of the translating roller cam."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.analysis import analyze, largest_roller
from camgen.flat import build_cam, flat_rig
from camgen.api import design_cam
from camgen.core.errors import DesignError
from camgen.rig import disc_mount
from tests.conftest import template


@pytest.mark.parametrize("rotation, offset", [("ccw", 5.0), ("ccw", -7.0), ("cw", 5.0), ("ccw", 0.0)])
def test_pitch_curvature_formula_matches_sampled_curve(rotation, offset):
    """kappa from s, s', s'' equals the curvature of the sampled points (finite differences of the points only)."""
    cam = build_cam(template({"cam.rotation": rotation, "follower.offset": offset}))
    for i, seg in enumerate(cam.program.segments):
        h = 1e-4
        t = np.linspace(seg.start + 3 * h, seg.end - 3 * h, 200)
        p0 = cam.segment_pitch(i, t).point
        pp, pm = cam.segment_pitch(i, t + h).point, cam.segment_pitch(i, t - h).point
        d1, d2 = (pp - pm) / (2 * h), (pp - 2 * p0 + pm) / h**2
        sense = 1 if rotation == "ccw" else -1
        numeric = -sense * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3
        assert np.abs(numeric - cam.segment_pitch(i, t).kappa).max() < 1e-6


def test_base_circle_and_dwell_curvature():
    cam = build_cam(template({"follower.offset": 0.0}))
    g = cam.segment_pitch(3, np.radians([310.0, 350.0]))
    assert g.kappa == pytest.approx(1 / 50.0, rel=1e-13)          # prime circle, Rp = 50
    assert np.linalg.norm(g.point, axis=1) == pytest.approx(50.0, rel=1e-13)
    top = cam.segment_pitch(1, np.radians([150.0]))
    assert top.kappa[0] == pytest.approx(1 / 70.0, rel=1e-13)


def test_first_order_radius_at_a_dwell_to_rise_start():
    """Centred follower, harmonic rise from a dwell: rho = Rp^2 / (Rp - s''(0)) exactly at theta = 0+."""
    cam = build_cam(template({"follower.offset": 0.0, "motion.0.law": "harmonic"}))
    s2 = math.pi**2 / 2 * 20.0 / (2 * math.pi / 3) ** 2
    assert 1 / cam.segment_pitch(0, 0.0).kappa[0] == pytest.approx(50.0**2 / (50.0 - s2), rel=1e-13)


def test_pressure_angle_textbook_value_and_peak():
    """Centred cycloidal rise: phi = atan(s' / (Rp + s)); mid-rise s' = 2h/beta, s = h/2."""
    cam = build_cam(template({"follower.offset": 0.0}))
    beta = 2 * math.pi / 3
    phi = cam.pitch(np.array([beta / 2])).pressure_angle[0]
    assert math.degrees(phi) == pytest.approx(math.degrees(math.atan(2 * 20 / beta / 60.0)), rel=1e-13)
    dense = np.linspace(0, 2 * math.pi, 720001)
    brute = np.degrees(np.abs(cam.pitch(dense).pressure_angle))
    a = analyze(cam)
    assert a.pressure_angle_max_deg == pytest.approx(brute.max(), abs=1e-8)
    assert a.pressure_angle_max_deg >= brute.max() - 1e-12
    assert a.pressure_angle_max_at_deg == pytest.approx(float(np.degrees(dense[np.argmax(brute)])), abs=1e-3)


def test_pressure_angle_equals_angle_of_the_contact_normal():
    """The pressure angle is the angle between the pitch normal (from the sampled curve) and the follower axis."""
    cam = build_cam(template())
    t = np.radians(np.linspace(5, 115, 23))
    h = 1e-6
    d1 = (cam.pitch(t + h).point - cam.pitch(t - h).point) / (2 * h)
    g = cam.pitch(t)
    # rotate the tangent back into the fixed frame (cam turned by +theta for ccw)
    c, s = np.cos(t), np.sin(t)
    tx, ty = c * d1[:, 0] - s * d1[:, 1], s * d1[:, 0] + c * d1[:, 1]
    normal_angle = np.arctan2(-ty, tx)  # the normal (-ty, tx) measured from the follower axis +Y
    assert np.abs(np.abs(normal_angle) - np.abs(g.pressure_angle)).max() < 1e-8


def test_offset_sign_lowers_rise_pressure_angle_for_ccw():
    rise = np.radians(np.linspace(1, 119, 500))
    ret = np.radians(np.linspace(181, 299, 500))
    peak = {}
    for rot in ("ccw", "cw"):
        for e in (-5.0, 0.0, 5.0):
            cam = build_cam(template({"cam.rotation": rot, "follower.offset": e}))
            g = cam.pitch(np.concatenate([rise, ret]))
            peak[rot, e] = np.abs(g.pressure_angle[:500]).max(), np.abs(g.pressure_angle[500:]).max()
    assert peak["ccw", 5.0][0] < peak["ccw", 0.0][0] < peak["ccw", -5.0][0]
    assert peak["ccw", 5.0][1] > peak["ccw", 0.0][1]
    assert peak["cw", -5.0][0] == pytest.approx(peak["ccw", 5.0][0], rel=1e-12)


def test_clockwise_cam_is_the_mirror_of_counter_clockwise():
    ccw = design_cam(template({"follower.offset": 5.0}))
    cw = design_cam(template({"cam.rotation": "cw", "follower.offset": -5.0}))
    a = np.sort(ccw.outline.contour.vertices * [-1, 1], axis=0)
    b = np.sort(cw.outline.contour.vertices, axis=0)
    assert np.abs(a - b).max() < 1e-9
    assert cw.analysis.pressure_angle_max_deg == pytest.approx(ccw.analysis.pressure_angle_max_deg, rel=1e-12)


def _tight(rr: float, prime: float = 30.0):
    """A tight cam: Rp held at ``prime`` so the pitch curve does not change with the roller."""
    return template({"cam.base_radius": prime - rr, "follower.roller_radius": rr, "follower.offset": 0.0,
                     "cam.bore": 0.0, "motion.0.angle": 50.0, "motion.1.angle": 130.0})


def test_undercut_detected_on_the_right_side_of_rho_equals_roller_radius():
    rho = analyze(build_cam(_tight(1.0))).pitch_rho_min_mm
    assert 5.0 < rho < 20.0
    below, above = analyze(build_cam(_tight(rho - 1e-9))), analyze(build_cam(_tight(rho + 1e-9)))
    assert not below.undercut
    assert above.undercut
    assert below.pitch_rho_min_mm == pytest.approx(rho, abs=1e-11)
    design = design_cam(_tight(rho - 1e-9))          # a cusp-sharp but valid cam still builds
    assert design.outline.max_error_mm <= 0.01


def test_undercut_is_refused_with_angle_radius_and_largest_roller():
    t = template({"cam.base_radius": 10.0, "follower.offset": 0.0, "cam.bore": 0.0,
                  "motion.0.angle": 40.0, "motion.1.angle": 140.0})
    a = analyze(build_cam(t))
    best = largest_roller(flat_rig(t, disc_mount(t.follower, t.cam.rotation)), t.cam.base_radius)
    with pytest.raises(DesignError) as err:
        design_cam(t)
    msg = str(err.value)
    assert f"{a.pitch_rho_min_at_deg:.2f} degrees" in msg
    assert f"{a.pitch_rho_min_mm:.4g} mm" in msg
    assert f"largest roller that fits is {best:.4g} mm" in msg
    # the suggested roller really is the limit: just below fits, just above undercuts
    fits = analyze(build_cam(t, roller_radius=best * (1 - 1e-6)))
    fails = analyze(build_cam(t, roller_radius=best * (1 + 1e-6)))
    assert not fits.undercut and fails.undercut


def test_allowed_undercut_gives_the_cutter_envelope():
    import shapely

    t = template({"cam.base_radius": 10.0, "follower.offset": 0.0, "cam.bore": 0.0, "cam.allow_undercut": True,
                  "motion.0.angle": 40.0, "motion.1.angle": 140.0})
    d = design_cam(t)
    assert d.analysis.undercut and d.outline.envelope
    poly = shapely.Polygon(d.outline.contour.vertices)
    assert poly.is_valid and poly.area > 0
    assert d.outline.max_error_mm <= t.output.tolerance
    assert any("undercut allowed" in w for w in d.warnings)


def test_velocity_jump_makes_a_corner_that_is_refused_or_enveloped():
    t = template({"motion.0.law": "uniform"})
    corners = build_cam(t).corners()
    assert [i for i, turn in corners if turn > 0] == [0]        # end of the rise: convex
    assert [i for i, turn in corners if turn < 0] == [3]        # start of the rise: concave
    with pytest.raises(DesignError, match="convex corner"):
        design_cam(t)
    d = design_cam(template({"motion.0.law": "uniform", "cam.allow_undercut": True}))
    assert d.outline.envelope and d.outline.max_error_mm <= 0.01


def test_a_corner_is_a_turn_over_1e_9():
    """A corner is where the pitch tangent turns by more than 1e-9 radians across a segment end, by that turn times
    -sense: a uniform rise's two velocity jumps, none on a cycloidal one; tangents turned by 5e-11 and 5e-10 are no
    corner, by 2e-9 one, opposite tangents a cusp's pi."""
    from camgen.cam import corner_turns

    for law in ("uniform", "cycloidal"):
        cam = build_cam(template({"motion.0.law": law}))
        ends, starts = cam.boundary_geometry()
        expected = [(i, -cam.follower.sense * math.atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]))
                    for i, (a, b) in enumerate(zip(ends.d1, starts.d1, strict=True))]
        found = cam.corners()
        assert [i for i, _ in found] == [i for i, turn in expected if abs(turn) > 1e-9]
        assert [t for _, t in found] == pytest.approx([t for _, t in expected if abs(t) > 1e-9], rel=1e-12)
        assert len(found) == (2 if law == "uniform" else 0)
    left = np.array([[3.0, 4.0], [3.0, 4.0], [3.0, 4.0], [3.0, 4.0], [-2.0, 0.5]])
    turns = np.array([5e-11, 5e-10, 2e-9, 0.0, 0.0])
    c, s = np.cos(turns), np.sin(turns)
    right = np.column_stack([left[:, 0] * c - left[:, 1] * s, left[:, 0] * s + left[:, 1] * c]) * 1.5
    right[3] = -right[3]
    sense = build_cam(template({})).follower.sense
    found = corner_turns(left, right, sense)                  # tangents of our own
    assert [i for i, _ in found] == [2, 3]
    assert -sense * found[0][1] == pytest.approx(2e-9, rel=1e-6)
    assert abs(found[1][1]) == pytest.approx(math.pi)


def test_concave_corner_is_an_exact_arc_of_the_roller_radius():
    """Uniform start from a dwell, then a polynomial matching its velocity: one concave pitch corner."""
    raw = {"motion.0.law": "uniform", "motion.0.lift": 10.0, "motion.0.angle": 60.0}
    from camgen.spec import validate_spec
    from camgen.core.spec import apply_overrides
    from tests.conftest import RDRD

    data = apply_overrides(RDRD, list(raw.items()))
    data["motion"].insert(1, {"type": "rise", "law": "polynomial", "lift": 10.0, "angle": 60.0,
                              "conditions": [[0, 0, 0], [0, 1, 1], [1, 0, 1], [1, 1, 0], [1, 2, 0]]})
    t = validate_spec(data)
    cam = build_cam(t)
    assert [turn < 0 for _, turn in cam.corners()] == [True]
    d = design_cam(t)
    assert not d.outline.envelope
    corner = cam.segment_pitch(0, 0.0).point[0]
    _, centres, radii, _ = d.outline.contour.arcs()
    at_corner = np.linalg.norm(centres - corner, axis=1) < 1e-9
    assert at_corner.sum() == 1
    assert radii[at_corner][0] == pytest.approx(10.0, abs=1e-9)
    top = math.hypot(5.0, cam.follower.d0 + 20.0) - 10.0
    assert np.sort(radii[~at_corner]) == pytest.approx([40.0, top], abs=1e-9)  # dwells: arcs about the centre
    assert np.linalg.norm(centres[~at_corner], axis=1).max() < 1e-9


def test_drafted_modified_uniform_takes_its_ratio_from_the_prime_circle():
    """Drafted form: k = Rp * beta / h, so the diagram's end arcs have radius h on the prime-circle arc length."""
    d = design_cam(template({"motion.0.law": "modified-uniform", "motion.0.form": "drafted"}))
    law = d.cam.program.segments[0].law
    assert law.k == pytest.approx(50.0 * math.radians(120.0) / 20.0, rel=1e-15)
    # s in mm against x = Rp * theta in mm: the first arc is a circle of radius h = 20 about (0, h)
    theta = np.linspace(0, law.u1 * math.radians(120.0), 30)
    s = d.cam.program.evaluate(theta)[0]
    assert np.abs((50.0 * theta) ** 2 + (s - 20.0) ** 2 - 20.0**2).max() < 1e-9
    assert not d.analysis.undercut and d.outline.max_error_mm <= 0.01
