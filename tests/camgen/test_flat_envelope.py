"""Flat faces with cam.allow_undercut: the envelope of the face's lines with its folds cut off.

The checks stand on the files as written and on geometry of their own: the face's line is placed at every cam angle
from docs/guides/followers.md's description of each follower (a translating face at y = Rb + s, an arm's face
through its pivot turned clockwise by the swing), never from the follower code; the DXF's outline is read back with
ezdxf; the motion of a follower riding the cut cam is found by brute force as the support of that polygon; the cut
cam is compared with shapely's intersection of the face's half-planes.
"""
from __future__ import annotations

import functools
import json
import math

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from camgen.analysis import profile_rho_min
from camgen.flat import build_cam
from camgen.cli import main
from camgen.core.errors import DesignError
from camgen.api import design_cam
from camgen.spec import load_spec
from tests.conftest import ROOT

FLAT = ROOT / "templates" / "flat-face.toml"
TOL = 0.01
#: cam angles at which the face is placed (0.25 degree apart)
ANGLES = np.radians(np.arange(0.0, 360.0, 0.25))

#: a rise of 30 mm in 90 degrees on a 25 mm base circle: the profile's radius of curvature falls to -12.6 mm
SMOOTH = ["motion.0.angle=90", "motion.1.angle=90", "motion.0.lift=30", "motion.2.lift=30", "cam.base_radius=25"]
#: a uniform rise: the velocity jumps up at 0 degrees (a flat) and drops at 150 (the profile folds back at once)
DROP = ["motion.0.law='uniform'", "cam.base_radius=60"]
OSCILLATING = ["follower.type='oscillating-flat'"]
#: an arm swinging 30 degrees in 90 on a 20 mm base circle, pivot 80 mm off: radius of curvature down to -22 mm
ARM_SMOOTH = [*OSCILLATING, "follower.pivot_distance=80", "motion.0.lift=30", "motion.2.lift=30", "motion.0.angle=90",
              "motion.1.angle=90", "cam.base_radius=20"]
ARM_DROP = [*OSCILLATING, "follower.pivot_distance=150", "motion.0.lift=8", "motion.2.lift=8", *DROP]

CASES = {
    "translating, smooth fold": SMOOTH,
    "translating, velocity drop": DROP,
    "translating, velocity drop, cw, biarcs, kerf": [*DROP, "cam.rotation='cw'", "output.curves='biarcs'",
                                                     "output.kerf=0.3"],
    "oscillating, smooth fold": ARM_SMOOTH,
    "oscillating, smooth fold, cw, kerf": [*ARM_SMOOTH, "cam.rotation='cw'", "output.kerf=0.2"],
    "oscillating, velocity drop": ARM_DROP,
}


def _spec(sets: list[str], allow: bool = True):
    return load_spec(FLAT, ["cam.bore=0", f"cam.allow_undercut={'true' if allow else 'false'}", *sets])


def _build(tmp_path, sets: list[str], allow: bool = True) -> tuple[np.ndarray, dict]:
    """``camgen build`` of the flat-face template with ``sets``: points on the DXF's outline read back (its
    vertices, and points every 0.1 degree along its arcs) and the report."""
    import ezdxf

    args = ["build", str(FLAT), "-o", str(tmp_path), "--set", "cam.bore=0", "--set", "output.formats=['dxf','json']",
            "--set", f"cam.allow_undercut={'true' if allow else 'false'}"]
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    [outline] = ezdxf.readfile(tmp_path / "flat-face.dxf").modelspace().query('LWPOLYLINE[layer=="OUTLINE"]')
    assert outline.closed
    return _on(np.array(outline.get_points("xyb"))), json.loads((tmp_path / "flat-face.json").read_text())


def _on(rows: np.ndarray) -> np.ndarray:
    """Points on a closed polyline of (x, y, bulge) rows: its vertices and, along each arc, points 0.1 degree
    apart (exactly on the arc, so that no point of the written outline stands out of its chords)."""
    out = []
    for (x, y, bulge), (u, v, _) in zip(rows, np.roll(rows, -1, axis=0), strict=True):
        out.append([(x, y)])
        if bulge:
            sweep = 4 * math.atan(bulge)
            a, b = np.array([x, y]), np.array([u, v])
            mid, chord = 0.5 * (a + b), b - a
            # the centre lies off the chord's midpoint by half the chord / tan(sweep / 2), to the left for a ccw arc
            centre = mid + np.array([-chord[1], chord[0]]) / (2 * math.tan(sweep / 2))
            start, radius = math.atan2(*(a - centre)[::-1]), float(np.linalg.norm(a - centre))
            t = start + sweep * np.linspace(0, 1, max(2, math.ceil(abs(math.degrees(sweep)) * 10)))[1:-1]
            out.append(centre + radius * np.column_stack([np.cos(t), np.sin(t)]))
    return np.concatenate(out)


class Face:
    """The follower's face placed by the law, in the fixed frame (docs/guides/followers.md), from the spec alone."""

    def __init__(self, spec) -> None:
        self.spec = spec
        self.sense = 1 if spec.cam.rotation == "ccw" else -1
        self.program = build_cam(spec).program          # the law itself: s (mm) or the swing (degrees)
        self.rb = spec.cam.base_radius
        self.arm = spec.follower.type == "oscillating-flat"
        if self.arm:
            c = spec.follower.pivot_distance
            self.pivot = np.array([math.sqrt(c**2 - self.rb**2), self.rb])

    def fixed(self, points: np.ndarray, theta: float) -> np.ndarray:
        """Cam-frame ``points`` where the cam has turned by ``theta`` (its sense of rotation)."""
        a = self.sense * theta
        c, s = math.cos(a), math.sin(a)
        return points @ np.array([[c, s], [-s, c]])

    def level(self, theta: np.ndarray) -> np.ndarray:
        return self.program.evaluate(theta)[0]

    def height(self, points: np.ndarray, theta: float, level: float) -> np.ndarray:
        """Signed distance (mm) of fixed-frame ``points`` above the face at ``level`` (> 0: beyond the face)."""
        if not self.arm:
            return points[:, 1] - (self.rb + level)
        psi = math.radians(level)                     # a rise turns the face clockwise about the pivot on +X
        return (points - self.pivot) @ np.array([math.sin(psi), math.cos(psi)])

    def riding(self, points: np.ndarray) -> tuple[float, float]:
        """The level of a follower held on the cam whose fixed-frame outline is ``points``, the face resting on its
        highest point (brute force over every point), and where along the face it touches (mm from the follower's
        axis, or from the pivot)."""
        if not self.arm:
            top = int(np.argmax(points[:, 1]))
            return float(points[top, 1]) - self.rb, float(points[top, 0])
        w = points - self.pivot
        swing = np.degrees(np.arctan(-w[:, 1] / w[:, 0]))              # the swing whose face passes through each
        top = int(np.argmax(swing))
        return float(swing[top]), float(np.linalg.norm(w[top]))


def _inside(deg: np.ndarray, leaves: list[dict]) -> np.ndarray:
    """Which cam angles (degrees) lie in a stretch where the report says the face leaves the cam."""
    out = np.zeros(len(deg), dtype=bool)
    for f in leaves:
        out |= (deg - f["start_deg"]) % 360.0 <= (f["end_deg"] - f["start_deg"]) % 360.0
    return out


@pytest.mark.parametrize("sets", CASES.values(), ids=CASES.keys())
def test_the_face_touches_the_exported_outline_without_crossing_it(tmp_path, sets):
    """At 1440 cam angles the law's face (moved out by half the kerf, as the cut file is) has every point of the
    DXF's outline on the cam's side, and touches it within the tolerance wherever the report does not say it
    leaves the cam; where it does, it stands off by the reported gap."""
    points, report = _build(tmp_path, sets)
    spec = _spec(sets)
    face, half_kerf = Face(spec), spec.output.kerf / 2
    leaves = report["face_leaves_cam"]
    assert report["envelope"] and report["undercut"] and leaves
    assert report["outline_max_error_mm"] <= TOL
    # chords and exact arcs lie on the cam's side of every face line; biarcs may stray either side of the surface
    crossing = TOL if spec.output.curves == "biarcs" else 1e-9
    gap = np.empty(len(ANGLES))
    for k, (theta, level) in enumerate(zip(ANGLES, face.level(ANGLES), strict=True)):
        above = face.height(face.fixed(points, theta), theta, level) - half_kerf
        assert above.max() <= crossing, f"the face crosses the outline at {math.degrees(theta)} degrees"
        gap[k] = -above.max()
    off = _inside(np.degrees(ANGLES), leaves)
    assert gap[~off].max() <= TOL                          # touching wherever the follower keeps the law's contact
    assert gap[off].max() > 3 * TOL                        # and standing off over a fold cut off
    for f in leaves:
        theta = math.radians(f["gap_at_deg"])
        level = face.level(np.array([theta]))[0]
        at = -(face.height(face.fixed(points, theta), theta, level) - half_kerf).max()
        assert at == pytest.approx(f["gap_mm"], abs=TOL)


@pytest.mark.parametrize("sets", [SMOOTH, DROP, ARM_SMOOTH, ARM_DROP], ids=["translating, smooth", "translating, drop",
                                                                           "oscillating, smooth", "oscillating, drop"])
def test_the_motion_of_a_follower_riding_the_cut_cam_is_reported(tmp_path, sets):
    """The follower held on the cam read back from the DXF (brute force: its face resting on the outline's highest
    point at each angle) falls short of the law as the report says: by the reported largest deviation at its angle,
    and by no more than the tolerance outside the stretches reported."""
    points, report = _build(tmp_path, sets)
    face = Face(_spec(sets))
    law = face.level(ANGLES)
    riding, touching = np.array([face.riding(face.fixed(points, t)) for t in ANGLES]).T
    unit = "deg" if face.arm else "mm"
    # the tolerance in the follower's unit: an arm turns by tol / (distance of the contact from the pivot)
    slack = math.degrees(TOL / np.linalg.norm(points - face.pivot, axis=1).min()) if face.arm else TOL
    short = law - riding
    assert short.min() >= -slack                           # never above the law: the cam is only ever cut away
    off = _inside(np.degrees(ANGLES), report["face_leaves_cam"])
    assert short[~off].max() <= slack
    for f in report["face_leaves_cam"]:
        theta = math.radians(f["deviation_at_deg"])
        there = face.level(np.array([theta]))[0] - face.riding(face.fixed(points, theta))[0]
        assert there == pytest.approx(f[f"deviation_{unit}"], abs=slack)
        inside = _inside(np.degrees(ANGLES), [f])
        assert short[inside].max() == pytest.approx(f[f"deviation_{unit}"], abs=slack)
        if not face.arm:                                   # a translating face falls short by its gap exactly
            assert f["deviation_mm"] == pytest.approx(f["gap_mm"], abs=1e-9)
    # the face's extent covers where it really touches the cam (its corners included), and no more: the outline's
    # highest vertex stands at most a chord from the contact
    chord = np.linalg.norm(np.diff(points, axis=0), axis=1).max()
    lo, hi = report["face_position_min_mm"], report["face_position_max_mm"]
    assert touching.min() == pytest.approx(lo, abs=chord) and touching.max() == pytest.approx(hi, abs=chord)


@pytest.mark.parametrize("sets", [SMOOTH, DROP, ARM_SMOOTH], ids=["translating, smooth", "translating, drop",
                                                               "oscillating, smooth"])
def test_the_cut_cam_is_the_intersection_of_the_face_half_planes(sets):
    """shapely's intersection of the half-planes the face leaves at 8000 cam angles is the nominal outline to
    within the tolerance (plus what 8000 lines leave of the corners)."""
    design = design_cam(_spec(sets))
    face = Face(design.spec)
    theta = np.linspace(0, 2 * np.pi, 8000, endpoint=False)
    level = face.level(theta)
    # each face's half-plane, a rectangle 900 mm by 450 on the cam's side of its line, in the fixed frame
    if face.arm:
        psi = np.radians(level)
        m, t = np.column_stack([np.sin(psi), np.cos(psi)]), np.column_stack([np.cos(psi), -np.sin(psi)])
        base = np.broadcast_to(face.pivot, m.shape)
    else:
        m, t = np.broadcast_to([0.0, 1.0], (len(theta), 2)), np.broadcast_to([1.0, 0.0], (len(theta), 2))
        base = np.column_stack([np.zeros(len(theta)), face.rb + level])
    half = np.stack([base + 450 * t, base - 450 * t, base - 450 * t - 900 * m, base + 450 * t - 900 * m], axis=1)
    a = -face.sense * theta                                # turned back into the cam's frame
    c, s = np.cos(a)[:, None], np.sin(a)[:, None]
    half = np.stack([c * half[..., 0] - s * half[..., 1], s * half[..., 0] + c * half[..., 1]], axis=-1)
    halves = shapely.polygons(half)
    while len(halves) > 1:                                 # pairwise, so that every step meets small polygons
        if len(halves) % 2:
            halves = np.append(halves, halves[-1])
        halves = shapely.intersection(halves[0::2], halves[1::2])
    cut = halves[0]
    ours = shapely.Polygon(design.outline.contour.flatten(1e-4))
    assert ours.is_valid and cut.is_valid
    assert ours.hausdorff_distance(cut) <= TOL
    assert abs(ours.area - cut.area) <= TOL * cut.length


def test_kerf_moves_the_cut_cam_out_exactly(tmp_path):
    """The cut file's outline is the nominal one grown by half the kerf: each corner of a fold cut off becomes an
    arc of that radius round it."""
    sets = [*SMOOTH, "output.kerf=0.4"]
    design = design_cam(_spec(sets))
    nominal = shapely.Polygon(design.outline.contour.flatten(1e-4))
    cut = shapely.Polygon(design.cut_outline.contour.flatten(1e-4))
    assert cut.hausdorff_distance(nominal.buffer(0.2, quad_segs=256)) <= TOL
    assert design.cut_outline.max_error_mm <= TOL and design.cut_outline.envelope
    (corner,) = design.face_leaves
    arcs = design.cut_outline.contour.arcs()
    centres = arcs[1][np.isclose(arcs[2], 0.2, atol=1e-9)]
    assert np.linalg.norm(centres - np.array(corner.corner_mm), axis=1).min() < 1e-9


@pytest.mark.parametrize("sets", [["cam.base_radius=60"], [*OSCILLATING, "follower.pivot_distance=150",
                                                           "motion.0.lift=8", "motion.2.lift=8", "cam.base_radius=60"]],
                         ids=["translating", "oscillating"])
def test_with_no_undercut_allowing_one_changes_nothing(tmp_path, sets):
    for allow in (False, True):
        _build(tmp_path / str(allow), sets, allow)
    assert (tmp_path / "True" / "flat-face.dxf").read_bytes() == (tmp_path / "False" / "flat-face.dxf").read_bytes()
    report = json.loads((tmp_path / "True" / "flat-face.json").read_text())
    assert not report["undercut"] and not report["envelope"] and "face_leaves_cam" not in report


@pytest.mark.parametrize("sets, words", [
    (SMOOTH, r"cusp at 55.78 degrees: the profile's radius of curvature falls to -12.59 mm, so the flat face cannot "
             r"follow the law there; the smallest cam.base_radius that works is 37.59 mm \(or set "
             r"cam.allow_undercut = true"),
    (DROP, r"motion\[0\]: cusp at 150 degrees: the follower velocity drops there, .* or set cam.allow_undercut = true"),
    (ARM_SMOOTH, r"cusp at .* degrees: the profile's radius of curvature falls to -22.\d* mm"),
    (ARM_DROP, r"motion\[0\]: cusp at 150 degrees: the follower velocity drops there"),
], ids=["translating, smooth", "translating, drop", "oscillating, smooth", "oscillating, drop"])
def test_without_allow_undercut_the_cusp_is_still_refused(sets, words):
    with pytest.raises(DesignError, match=words):
        design_cam(_spec(sets, allow=False))


def test_an_arm_whose_face_turns_back_is_refused():
    """An arm returning faster than the cam turns (2 rad of swing a radian of cam) turns its face back: its lines
    do not go once round the cam and no cam can be cut for them."""
    sets = [*OSCILLATING, "follower.pivot_distance=130", "cam.base_radius=40", "motion.2.lift=30", "motion.0.lift=30",
            "motion.2.angle=30", "motion.3.angle=150"]
    with pytest.raises(DesignError, match=r"^the face turns back on the cam near \d+.?\d* degrees \(the arm swings "
                                          r"faster than the cam turns\): no cam can be cut for it$"):
        design_cam(_spec(sets))


def test_the_report_and_warnings_say_where_and_how_far(tmp_path):
    _, report = _build(tmp_path, SMOOTH)
    (f,) = report["face_leaves_cam"]
    assert set(f) == {"start_deg", "end_deg", "corner_mm", "gap_mm", "gap_at_deg", "deviation_mm", "deviation_at_deg"}
    assert f["start_deg"] < report["pitch_rho_min_at_deg"] < f["end_deg"]
    [warning] = [w for w in report["warnings"] if w.startswith("undercut allowed")]
    assert (f"from {f['start_deg']:.2f} to {f['end_deg']:.2f} degrees the face leaves the law's profile" in warning
            and f"falls short of the law by up to {f['deviation_mm']:.4g} mm" in warning)
    lo, hi = report["face_position_min_mm"], report["face_position_max_mm"]
    assert lo < 0 < hi
    _, arm = _build(tmp_path / "arm", ARM_DROP)
    assert "deviation_deg" in arm["face_leaves_cam"][0]
    assert any("falls short of the law by up to" in w and w.endswith("degrees") for w in arm["warnings"])


@functools.cache
def _limit(sets: tuple[str, ...]) -> float:
    """The base radius (mm) at which the profile's least radius of curvature is 0, to the last float: by bisection
    on profile_rho_min (increasing with the base radius), from 1 mm to 60 mm; found once for each set of
    overrides (the three shifts of a case share it)."""
    def rho(rb: float) -> float:
        return profile_rho_min(build_cam(_spec(list(sets)), base_radius=rb))

    lo, hi = 1.0, 60.0
    assert rho(lo) < 0 < rho(hi)
    while np.nextafter(lo, hi) < hi:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (mid, hi) if rho(mid) < 0 else (lo, mid)
    return hi


@pytest.mark.parametrize("sets", [SMOOTH, ARM_SMOOTH], ids=["translating", "oscillating"])
@pytest.mark.parametrize("shift", [-1e-12, 0.0, 1e-12])
def test_at_and_a_hair_from_the_limit_base_radius(sets, shift):
    """At the base radius where the profile's radius of curvature just reaches 0, and 1e-12 mm either side: a sound
    outline within the tolerance that the face touches all round (the fold is far below what can be cut); refused
    without allow_undercut exactly where the radius of curvature is not positive."""
    rb = _limit(tuple(sets)) + shift
    spec = _spec([*sets, f"cam.base_radius={rb!r}"])
    design = design_cam(spec)
    assert shift == 0 or design.analysis.undercut == (shift < 0)
    contour = design.outline.contour
    assert shapely.Polygon(contour.flatten(1e-4)).is_valid and contour.area > 0
    assert design.outline.max_error_mm <= TOL
    assert not design.face_leaves                          # nothing to cut off: the face keeps its contact
    face = Face(spec)
    points = contour.flatten(1e-4)
    for theta, level in zip(ANGLES[::4], face.level(ANGLES[::4]), strict=True):
        above = face.height(face.fixed(points, theta), theta, level)
        assert -TOL <= above.max() <= 1e-9
    if design.analysis.undercut:
        assert any("too small to cut off" in w for w in design.warnings)
        with pytest.raises(DesignError, match="cusp at"):
            design_cam(_spec([*sets, f"cam.base_radius={rb!r}"], allow=False))
    else:
        same = design_cam(_spec([*sets, f"cam.base_radius={rb!r}"], allow=False)).outline.contour
        assert np.array_equal(same.vertices, contour.vertices) and np.array_equal(same.bulges, contour.bulges)
