"""Knife edge, flat faces and oscillating followers, measured on the geometry they produce; sizing."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

from camgen.analysis import analyze, face_extent, pressure_angle_max, profile_rho_min
from camgen.flat import build_cam, size_disc
from camgen.api import design_cam
from camgen.core.errors import DesignError, SpecError
from camgen.followers.base import rotate
from camgen.laws import DraftedUniform, make_law
from camgen.sizing import FACTOR_LAWS, cam_factor, factor_table
from camgen.surface import surface_deviation
from tests.conftest import template

FLAT = {"follower.type": "translating-flat", "follower.roller_radius": None, "follower.offset": None,
        "motion.0.lift": 15.0, "motion.2.lift": 15.0}
OSC_ROLLER = {"follower.type": "oscillating-roller", "follower.offset": None, "follower.roller_radius": 8.0,
              "follower.pivot_distance": 110.0, "follower.arm_length": 90.0, "motion.0.lift": 20.0,
              "motion.2.lift": 20.0, "motion.2.law": "cycloidal"}
OSC_FLAT = {"follower.type": "oscillating-flat", "follower.offset": None, "follower.roller_radius": None,
            "follower.pivot_distance": 120.0, "motion.0.lift": 8.0, "motion.2.lift": 8.0,
            "motion.2.law": "cycloidal", "cam.base_radius": 60.0}


def spec(changes: dict):
    """rdrd with changes; a value of None removes the key."""
    from camgen.spec import validate_spec
    from tests.conftest import RDRD
    import copy

    raw = copy.deepcopy(RDRD)
    for key, value in changes.items():
        head, _, rest = key.partition(".")
        node = raw[head]
        parts = rest.split(".")
        for p in parts[:-1]:
            node = node[int(p)] if isinstance(node, list) else node[p]
        last = parts[-1]
        if value is None:
            node.pop(last, None)
        else:
            node[int(last) if isinstance(node, list) else last] = value
    return validate_spec(raw)


def numeric_curvature(points: np.ndarray, h: float) -> np.ndarray:
    """Signed curvature of points sampled at equal parameter steps h (finite differences of the points only)."""
    d1 = (points[2:] - points[:-2]) / (2 * h)
    d2 = (points[2:] - 2 * points[1:-1] + points[:-2]) / h**2
    return (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3


def test_flat_face_curvature_from_the_sampled_profile():
    """rho = Rb + s + s'' against the curvature of the profile's sampled points."""
    cam = build_cam(spec(FLAT))
    h = 1e-4
    for i, seg in enumerate(cam.program.segments):
        t = np.arange(seg.start + 2 * h, seg.end - 2 * h, h * 50)
        grid = (t[:, None] + np.array([-h, 0.0, h])).ravel()
        pts = cam.segment_pitch(i, grid).point.reshape(-1, 3, 2)
        kappa = np.array([-numeric_curvature(p, h)[0] for p in pts])     # the profile runs clockwise (ccw cam)
        s = seg.evaluate(t)
        assert np.abs(1 / kappa - (40.0 + s[0] + s[2])).max() < 1e-4


def test_flat_face_width_from_the_sampled_profile():
    """Turn densely sampled profile points back by each cam angle: the highest is where the face touches."""
    d = design_cam(spec(FLAT))
    profile = d.cam.pitch(np.radians(np.arange(0, 360, 0.01))).point
    theta = np.radians(np.arange(0, 360, 0.25))
    offsets = []
    for th in theta:
        fixed = rotate(profile, np.full(len(profile), th))
        offsets.append(fixed[np.argmax(fixed[:, 1]), 0])
    lo, hi = face_extent(d.cam)
    assert min(offsets) == pytest.approx(lo, abs=0.05) and max(offsets) == pytest.approx(hi, abs=0.05)
    # textbook: the contact sits at s' from the axis, so the face spans the range of s'
    s1 = d.cam.program.evaluate(np.radians(np.arange(0, 360, 0.01)))[1]
    assert (lo, hi) == (pytest.approx(s1.min(), abs=1e-6), pytest.approx(s1.max(), abs=1e-6))
    from camgen.report import cam_report

    assert cam_report(d)["face_width_mm"] == pytest.approx(hi - lo + 2 * 2.0)
    assert analyze(d.cam).pressure_angle_max_deg == pytest.approx(0.0, abs=1e-12)


def test_flat_face_cusp_is_refused_with_the_smallest_base_radius():
    """rho = Rb + s + s'' moves one for one with Rb, so the smallest base radius is Rb - rho_min."""
    t = spec({**FLAT, "cam.base_radius": 5.0, "cam.bore": 0.0})
    rho = profile_rho_min(build_cam(t))
    assert rho < 0
    with pytest.raises(DesignError, match=rf"cusp at .* smallest cam.base_radius that works is {5.0 - rho:.4g} mm"):
        design_cam(t)
    ok = design_cam(spec({**FLAT, "cam.base_radius": 5.0 - rho + 0.1, "cam.bore": 0.0}))
    assert ok.analysis.profile_rho_min_mm == pytest.approx(0.1, abs=1e-9)


def test_knife_edge_profile_is_the_pitch_curve():
    d = design_cam(spec({"follower.type": "knife-edge", "follower.roller_radius": None}))
    assert d.cam.contact_radius == 0.0
    pts = d.outline.contour.flatten(1e-3)
    assert np.abs(surface_deviation(d.cam, pts)).max() <= 0.01
    assert d.analysis.pitch_rho_min_mm == pytest.approx(d.analysis.profile_rho_min_mm)


def test_oscillating_roller_pressure_angle_measured_on_the_geometry():
    """Angle between the contact normal (from the sampled pitch curve) and the roller centre's path
    (square to the arm)."""
    cam = build_cam(spec(OSC_ROLLER))
    f = cam.follower
    assert math.degrees(f.rest_angle) == pytest.approx(
        math.degrees(math.acos((110**2 + 90**2 - 48**2) / (2 * 110 * 90))), abs=1e-12)
    h = 1e-5
    for i, seg in enumerate(cam.program.segments):
        t = np.linspace(seg.start + 1e-3, seg.end - 1e-3, 40)
        p0 = cam.segment_pitch(i, t).point
        tangent = (cam.segment_pitch(i, t + h).point - cam.segment_pitch(i, t - h).point) / (2 * h)
        centre = rotate(p0, t)                                          # fixed frame (ccw cam)
        tangent = rotate(tangent, t)
        normal = np.column_stack([tangent[:, 1], -tangent[:, 0]])      # outward for a ccw cam
        arm = centre - f.pivot
        path = np.column_stack([-arm[:, 1], arm[:, 0]])
        cosang = np.abs((normal * path).sum(1)) / np.linalg.norm(normal, axis=1) / np.linalg.norm(path, axis=1)
        measured = np.degrees(np.arccos(np.clip(cosang, -1, 1)))
        assert np.abs(measured - np.degrees(np.abs(cam.segment_pitch(i, t).pressure_angle))).max() < 1e-5


def test_oscillating_roller_swings_by_the_lift():
    cam = build_cam(spec(OSC_ROLLER))
    f = cam.follower
    top = rotate(cam.pitch(np.radians([150.0])).point, np.radians([150.0]))[0] - f.pivot
    rest = np.array([0.0, 48.0]) - f.pivot
    angle = math.degrees(math.acos(top @ rest / (np.linalg.norm(top) * np.linalg.norm(rest))))
    assert angle == pytest.approx(20.0, abs=1e-9)
    assert np.linalg.norm(top) == pytest.approx(90.0)


def test_oscillating_flat_face_touches_its_envelope():
    """Each face line is tangent to the profile: the profile lies on the cam side, touching at the contact."""
    d = design_cam(spec(OSC_FLAT))
    cam, f = d.cam, d.cam.follower
    outline = d.outline.contour.flatten(1e-4)
    for th in np.radians(np.arange(0, 360, 7.0)):
        g = cam.pitch(np.array([th]))
        n = g.normal[0]
        p = g.point[0] @ n                                             # distance of the face line from the centre
        assert p - 0.01 <= (outline @ n).max() <= p + 1e-9          # within the outline's chord tolerance
    # a face through the pivot is pushed square to itself: pressure angle 0
    assert analyze(cam).pressure_angle_max_deg == pytest.approx(0.0, abs=1e-9)
    assert pressure_angle_max(cam) < 1e-9
    assert np.linalg.norm(f.pivot) == pytest.approx(120.0)


def test_factor_table_against_the_laws_peak_slopes():
    table = factor_table()
    assert list(table) == list(FACTOR_LAWS)
    assert list(table["cycloidal"]) == [str(a) for a in range(10, 50, 5)]
    for law in ("uniform", "harmonic", "parabolic", "cycloidal"):
        cv = make_law(law).peaks()[0]
        for angle, f in table[law].items():
            assert f * math.tan(math.radians(int(angle))) == pytest.approx(cv, rel=1e-12)


def test_drafted_modified_uniform_factor_from_its_arcs():
    """With k = f, the drafted law's straight stretch climbs at exactly the allowed pressure angle."""
    for angle in range(10, 50, 5):
        law = DraftedUniform(cam_factor("modified-uniform", angle))
        assert math.degrees(law._alpha) == pytest.approx(angle, abs=1e-9)


@pytest.mark.parametrize("changes, decided", [
    ({}, "pressure angle"),
    ({"cam.min_rho_margin": 45.0}, "curvature"),
    ({**OSC_ROLLER, "cam.max_pressure_angle": 35.0}, "pressure angle"),
    (FLAT, "curvature"),
])
def test_sized_radius_meets_its_limit_and_099_of_it_does_not(changes, decided):
    t = spec(changes)
    s = size_disc(t)
    assert s.decided_by == decided
    at = build_cam(t, base_radius=s.base_radius_mm)
    below = build_cam(t, base_radius=0.99 * s.base_radius_mm)
    if decided == "pressure angle":
        assert pressure_angle_max(at) <= s.max_pressure_angle_deg
        assert pressure_angle_max(below) > s.max_pressure_angle_deg
    else:
        assert profile_rho_min(at) > s.min_rho_margin_mm
        assert profile_rho_min(below) <= s.min_rho_margin_mm


def test_auto_base_radius_builds_at_the_sized_radius():
    d = design_cam(spec({"cam.base_radius": "auto", "cam.bore": 0.0}))
    assert d.sizing is not None and d.sizing.decided_by == "pressure angle"
    assert d.cam.base_radius == pytest.approx(d.sizing.base_radius_mm)
    assert d.analysis.pressure_angle_max_deg <= 30.0 + 1e-9


@pytest.mark.parametrize("changes, message", [
    ({"follower.type": "oscillating-roller", "follower.offset": None, "follower.pivot_distance": 110.0},
     "follower.arm_length: missing: give oscillating roller: pivot to roller centre in mm"),
    ({"follower.type": "oscillating-roller"}, "follower.offset: not a key of an oscillating-roller follower; it takes: "
     "roller_radius, pivot_distance, arm_length,"),
    ({"follower.type": "translating-flat", "follower.offset": None},
     "follower.roller_radius: not a key of a translating-flat follower; it takes: face_margin, spring_rate,"),
    ({**OSC_ROLLER, "follower.arm_length": 10.0}, "follower.arm_length: the arm cannot put the roller"),
    ({**OSC_ROLLER, "motion.0.lift": 95.0, "motion.2.lift": 95.0}, "motion[0].lift: an arm swing must be < 90"),
])
def test_follower_errors_name_the_field(changes, message):
    with pytest.raises(SpecError, match=message.replace("[", r"\[").replace("]", r"\]")):
        design_cam(spec(changes))


def test_size_command(tmp_path):
    import json

    from click.testing import CliRunner

    from camgen.cli import main
    from tests.conftest import ROOT

    table = json.loads(CliRunner().invoke(main, ["size", "--factors", "--json"]).output)
    assert all(table[law] == pytest.approx(row) for law, row in factor_table().items())
    assert set(table) == {"uniform", "modified-uniform", "harmonic", "parabolic", "cycloidal"}
    assert set(table["harmonic"]) == {"10", "15", "20", "25", "30", "35", "40", "45"}
    r = json.loads(CliRunner().invoke(main, ["size", str(ROOT / "templates" / "rdrd.toml"), "--json"]).output)
    assert r["decided_by"] == "pressure angle"
    assert r["base_radius_mm"] == pytest.approx(size_disc(template()).base_radius_mm)
    bad = CliRunner().invoke(main, ["size"])
    assert bad.exit_code == 2 and "give a TEMPLATE" in bad.stderr


def _osc_flat(pivot: float, base: float, lift: float, rotation: str = "ccw") -> dict:
    return {**OSC_FLAT, "follower.pivot_distance": pivot, "cam.base_radius": base, "motion.0.lift": lift,
            "motion.2.lift": lift, "cam.rotation": rotation, "cam.bore": 0.0}


def _turn(v: np.ndarray, angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]])


def _face_lines(pivot: float, base: float, sense: int, program, theta: np.ndarray):
    """The face's line at each cam angle in the cam's frame (a point, a unit direction), from its definition alone:
    through the pivot (sqrt(C^2 - Rb^2), Rb), pointing along -X (to the rest contact (0, Rb)) at rest and turned
    clockwise by the swing psi; the cam's frame is the fixed one turned by -sense theta."""
    p = np.array([math.sqrt(pivot**2 - base**2), base])
    psi = np.radians(program.evaluate(theta)[0])
    u = np.column_stack([-np.cos(psi), np.sin(psi)])
    back = -sense * theta
    return _turn(np.tile(p, (theta.size, 1)), back), _turn(u, back), p, u


def _meet(pivot: float, base: float, sense: int, program, theta: np.ndarray, h: float) -> np.ndarray:
    """Where the face's lines at theta - h and theta + h meet (cam frame, mm): the contact, to O(h^2)."""
    a1, d1, _, _ = _face_lines(pivot, base, sense, program, theta - h)
    a2, d2, _, _ = _face_lines(pivot, base, sense, program, theta + h)
    gap = a2 - a1
    cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    t1 = (gap[:, 0] * d2[:, 1] - gap[:, 1] * d2[:, 0]) / cross
    return a1 + t1[:, None] * d1


def _envelope(pivot: float, base: float, sense: int, program, theta: np.ndarray, h: float = 1e-3) -> np.ndarray:
    """Contact points (cam frame, mm): neighbouring face lines' meeting points at h and h / 2, extrapolated
    (Richardson: error O(h^4), about 1e-11 mm here)."""
    return (4 * _meet(pivot, base, sense, program, theta, h / 2) - _meet(pivot, base, sense, program, theta, h)) / 3


def _numeric_face(pivot: float, base: float, sense: int, program, theta: np.ndarray):
    """An independent evaluation of the oscillating flat face: its contact's signed distance from the pivot along
    the face (mm, towards the rest contact), and the pressure angle (rad): the angle between the profile's outward
    normal (finite differences of the envelope's points) and the way the arm's point at the contact moves as the
    arm rises (square to the pivot-to-contact line, turning clockwise)."""
    q = _envelope(pivot, base, sense, program, theta)
    delta = 1e-4
    tangent = (_envelope(pivot, base, sense, program, theta + delta)
               - _envelope(pivot, base, sense, program, theta - delta)) / (2 * delta)
    normal = np.column_stack([tangent[:, 1], -tangent[:, 0]])
    normal *= np.sign((normal * q).sum(axis=1))[:, None]           # outward: the cam's centre lies behind the face
    _, _, p, u = _face_lines(pivot, base, sense, program, theta)
    fixed, normal = _turn(q, sense * theta), _turn(normal, sense * theta)
    arm = fixed - p
    rising = np.column_stack([arm[:, 1], -arm[:, 0]])             # clockwise about the pivot
    angle = np.arctan2(rising[:, 0] * normal[:, 1] - rising[:, 1] * normal[:, 0], (rising * normal).sum(axis=1))
    return (arm * u).sum(axis=1), angle


def _closed_form_reach(pivot: float, base: float, sense: int, program, theta: np.ndarray) -> np.ndarray:
    """d = C cos(asin(Rb / C) + psi) / (1 + sense psi'): the contact's distance from the pivot (mm)."""
    psi, psi1 = np.radians(program.evaluate(theta)[:2])
    return pivot * np.cos(math.asin(base / pivot) + psi) / (1 + sense * psi1)


#: (pivot distance, base radius, swing, rotation): ordinary arms with no cusp, and one a millionth beyond the nearest
#: pivot Rb / cos(swing) (the contact then passes within about 2e-4 mm of the pivot at the top of the swing)
FACE_GEOMETRIES = [(120.0, 60.0, 8.0, "ccw"), (150.0, 70.0, 12.0, "cw"), (90.0, 76.0, 20.0, "ccw"),
                   (76.0 / math.cos(math.radians(20.0)) * (1 + 1e-6), 76.0, 20.0, "ccw"),
                   (76.0 / math.cos(math.radians(20.0)) * (1 + 1e-6), 76.0, 20.0, "cw")]


@pytest.mark.parametrize("pivot, base, lift, rotation", FACE_GEOMETRIES)
def test_oscillating_flat_pressure_angle_against_finite_differences(pivot, base, lift, rotation):
    """A face through its pivot is pushed along its own normal wherever it touches the cam on the arm's side of the
    pivot: pressure angle 0, measured on the envelope of its lines, and the contact where the closed form puts it."""
    cam = build_cam(spec(_osc_flat(pivot, base, lift, rotation)))
    sense = cam.follower.sense
    theta = np.radians(np.arange(0.25, 360.0, 1.5))
    g = cam.pitch(theta)
    reach, angle = _numeric_face(pivot, base, sense, cam.program, theta)
    assert np.abs(g.point - _envelope(pivot, base, sense, cam.program, theta)).max() < 1e-6
    assert reach.min() > 0
    assert np.abs(reach - _closed_form_reach(pivot, base, sense, cam.program, theta)).max() < 1e-6
    assert np.abs(cam.follower.face_position(g) - reach).max() < 1e-6
    assert np.abs(angle).max() < 1e-6
    assert np.abs(g.pressure_angle).max() < 1e-9
    assert analyze(cam).pressure_angle_max_deg == pytest.approx(0.0, abs=1e-7)
    assert analyze(cam).profile_rho_min_mm > 0


def test_oscillating_flat_face_past_its_pivot_is_pushed_back():
    """The issue's arm (pivot 80 mm from the centre of a 76 mm cam, 20 degrees of swing: the nearest pivot is
    76 / cos 20 = 80.88 mm), evaluated without the refusal: where the closed form puts the contact beyond the pivot
    (d < 0) the finite differences and the follower both give 180 degrees, and 0 elsewhere."""
    from camgen.followers.oscillating_flat import OscillatingFlat

    program = build_cam(spec(_osc_flat(120.0, 76.0, 20.0))).program
    theta = np.radians(np.arange(0.25, 360.0, 0.5))
    follower = OscillatingFlat(80.0, 76.0, 1)
    g = follower.pitch(theta, program.evaluate(theta))
    reach, angle = _numeric_face(80.0, 76.0, 1, program, theta)
    beyond = _closed_form_reach(80.0, 76.0, 1, program, theta) < 0
    assert beyond.any() and not beyond.all()
    assert np.array_equal(reach < 0, beyond)
    assert np.abs(np.abs(angle[beyond]) - math.pi).max() < 1e-6 and np.abs(angle[~beyond]).max() < 1e-6
    assert np.abs(np.abs(g.pressure_angle[beyond]) - math.pi).max() < 1e-9
    assert np.abs(g.pressure_angle[~beyond]).max() < 1e-9


@pytest.mark.parametrize("base, lift", [(76.0, 20.0), (40.0, 30.0), (60.0, 8.0)])
def test_oscillating_flat_pivot_nearer_than_rb_over_cos_swing_is_refused(base, lift):
    """At its largest swing psi the face's nearest point to the cam centre lies C cos(asin(Rb / C) + psi) from the
    pivot: on the arm's side only while C > Rb / cos(psi). A hair inside is refused naming the field and its range;
    a hair outside builds, its nearest contact that far from the pivot (at the top dwell, where psi' = 0)."""
    least = base / math.cos(math.radians(lift))
    for pivot in (least * (1 - 1e-9), base, 0.5 * base):
        with pytest.raises(SpecError) as refusal:
            build_cam(spec(_osc_flat(pivot, base, lift)))
        assert refusal.value.field == "follower.pivot_distance"
        assert str(refusal.value).startswith(f"follower.pivot_distance: must be > {least:.6g} mm")
        assert f"cam.base_radius < {pivot * math.cos(math.radians(lift)):.6g} mm" in str(refusal.value)
    pivot = least * (1 + 1e-6)
    cam = build_cam(spec(_osc_flat(pivot, base, lift)))
    nearest = pivot * math.cos(math.asin(base / pivot) + math.radians(lift))
    assert 0 < nearest < 1e-3 * base
    assert face_extent(cam)[0] == pytest.approx(nearest, rel=1e-6)


def test_oscillating_flat_swing_of_90_degrees_follows_no_pivot():
    """Two rises of 50 and 45 degrees: at 95 degrees the face turns its back on the cam, whatever the pivot."""
    t = spec(_osc_flat(500.0, 20.0, 50.0)).model_dump(exclude_unset=True)
    t["motion"] = [{"type": kind, "law": "cycloidal", "lift": lift, "angle": 90.0}
                   for kind, lift in (("rise", 50.0), ("rise", 45.0), ("return", 50.0), ("return", 45.0))]
    from camgen.spec import validate_spec

    with pytest.raises(SpecError, match=r"^motion: the arm's swing peaks at 95 degrees"):
        build_cam(validate_spec(t))


def test_oscillating_flat_pivot_refusal_from_the_command_line(tmp_path):
    """The issue's case: one line naming follower.pivot_distance and its least value 76 / cos 20 deg, exit 2,
    nothing written."""
    from click.testing import CliRunner

    from camgen.cli import main
    from tests.conftest import ROOT

    text = (ROOT / "templates" / "rdrd.toml").read_text()
    text = text.replace('type = "translating-roller"', 'type = "oscillating-flat"\npivot_distance = 80.0')
    text = "\n".join(line for line in text.splitlines() if not line.startswith(("roller_radius", "offset")))
    (tmp_path / "t.toml").write_text(text.replace("base_radius = 40.0", "base_radius = 76.0"))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["build", str(tmp_path / "t.toml"), "-o", str(out)])
    assert result.exit_code == 2, result.output
    least = 76.0 / math.cos(math.radians(20.0))
    assert result.stderr.splitlines() == [result.stderr.strip()]
    assert result.stderr.startswith(f"error: follower.pivot_distance: must be > {least:.6g} mm")
    assert not out.exists()


def test_auto_base_radius_of_an_oscillating_flat_face_stays_below_its_reach():
    """base_radius = "auto" searches only radii under C cos(largest swing) (here 30 cos 60 = 15 mm): no base radius
    meets the curvature there, and the refusal says how far it searched."""
    with pytest.raises(DesignError, match=r"searched up to (\S+) mm") as refusal:
        design_cam(spec({**_osc_flat(30.0, 20.0, 60.0), "cam.base_radius": "auto"}))
    searched = float(re.search(r"searched up to (\S+) mm", str(refusal.value)).group(1))
    assert searched < 30.0 * math.cos(math.radians(60.0))
    d = design_cam(spec({**_osc_flat(45.0, 20.0, 25.0), "cam.base_radius": "auto"}))
    assert 0 < d.cam.base_radius < 45.0 * math.cos(math.radians(25.0))
