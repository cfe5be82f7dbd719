"""Involute spur gears (issue 34, item 1), checked against closed forms and independent constructions.

* A gear's outline against the textbook: its tip and root circles, its tooth thickness on the reference circle
  (m (pi/2 + 2 x tan a) less the thinning), and the involute of its base circle written out here,
  rb (cos t + t sin t, sin t - t cos t), at 200 points per flank, all within the outline's tolerance.
* The root against a gear cut here by rolling the basic rack over the blank (shapely), undercut included.
* Pairs (external, internal, rack) rolled through two tooth pitches at the tolerance's step: never overlapping,
  the gap between the flanks the asked backlash (normal: j cos a_w, half on each side) at every step.
* The fewest teeth without undercut 2 (1 - x) / sin^2 a flips exactly at it; the contact ratio against the
  textbook formula with a 50-digit working pressure angle, and against the path of contact measured along the
  line of action between the tip circles.
* Bad input refused in one line naming the field, exit code 2, nothing written.
"""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from camgen.core.shapes import Contour
from linkgen.gears.pair import GearPair
from linkgen.gears.tooth import BasicRack, ExternalTooth
from linkgen.mechanisms.gearparts import outlines
from tests.support.refusals import assert_refused_sets

TOL = 0.01            # mm: the outlines' tolerance (the parts table's default)
FINE = 1e-4           # mm: chords of the arcs when an outline is measured


def _tooth(z: int, x: float, m: float = 2.0, a: float = 20.0, thinning: float = 0.0) -> ExternalTooth:
    return ExternalTooth(BasicRack(m, math.radians(a)), z, x, thinning)


def _polygon(pieces, flat: float = FINE) -> np.ndarray:
    return Contour(*pieces).flatten(flat)


def _inv(t: float) -> float:
    return math.tan(t) - t


# ------------------------------------------------------------------------------------------------ one gear

GEARS = [(12, 0.3, 2.0, 20.0, 0.05), (30, 0.0, 1.5, 20.0, 0.0), (18, -0.2, 3.0, 20.0, 0.1),
         (40, 0.5, 1.0, 25.0, 0.02), (24, 0.1, 2.5, 14.5, 0.0)]


@pytest.mark.parametrize(("z", "x", "m", "a", "thin"), GEARS)
def test_the_outline_meets_the_closed_forms(z, x, m, a, thin):
    tooth = _tooth(z, x, m, a, thin)
    from linkgen.gears.outline import gear_outline

    pts = _polygon(gear_outline(tooth, TOL))
    radius = np.hypot(pts[:, 0], pts[:, 1])
    r, alpha = m * z / 2, math.radians(a)
    assert radius.max() == pytest.approx(r + (1 + x) * m, abs=1e-9)          # tip circle: an exact arc
    assert radius.min() == pytest.approx(r - (1.25 - x) * m, abs=1e-9)       # root circle: the rack's tip line
    # the tooth on +X crosses the reference circle at +-s/2r: s = m (pi/2 + 2 x tan a) - thinning
    boundary = shapely.LinearRing(pts)
    cut = boundary.intersection(shapely.LineString(r * np.column_stack([np.cos(t := np.linspace(-math.pi / z,
                                                                                                 math.pi / z, 4001)),
                                                                         np.sin(t)])))
    angles = sorted(math.atan2(p.y, p.x) for p in cut.geoms)
    assert len(angles) == 2
    thickness = r * (angles[1] - angles[0])
    expected = m * (math.pi / 2 + 2 * x * math.tan(alpha)) - thin
    assert thickness == pytest.approx(expected, abs=2 * TOL / math.sin(alpha))   # a flank's slope to the circle
    # the involute of rb = r cos a in closed form, 200 points per flank from where it starts to the tip circle
    rb = r * math.cos(alpha)
    start = -(expected / (2 * r) + _inv(alpha))          # polar angle where the right flank leaves the base circle
    lo = math.sqrt(max((tooth.form_radius / rb) ** 2 - 1, 0.0))
    hi = math.sqrt(((r + (1 + x) * m) / rb) ** 2 - 1)
    t = np.linspace(lo, hi, 200)
    right = rb * np.column_stack([np.cos(start + t) + t * np.sin(start + t), np.sin(start + t) - t * np.cos(start + t)])
    left = right * [1.0, -1.0]
    for k in (0, z // 3):                                 # tooth 0 and one a third of the way round
        c, s = math.cos(2 * math.pi * k / z), math.sin(2 * math.pi * k / z)
        for flank in (right, left):
            turned = flank @ np.array([[c, s], [-s, c]])
            assert shapely.distance(boundary, shapely.points(turned)).max() <= TOL + FINE


def _cut_by_rack(tooth: ExternalTooth, steps: int = 1500) -> shapely.Polygon:
    """The gear cut here: its blank (the tip circle) less one tooth of the basic rack at each step of its pass
    through the space clockwise of tooth 0; the rack tooth drawn from its own figures (straight flanks at the pressure
    angle, thickness pi m / 2 + the gear's thinning on the datum line, tip 1.25 m below it, tip corners rounded with
    the rack's fillet radius). Generating frame: the gear's tooth 0 on +Y, the rack above it with its datum line
    x m outside the reference circle; as the gear turns by phi counter-clockwise the rack moves by -r phi (the
    reference circle rolls on the line x m below the datum). Turned at the end so that tooth 0 lies on +X."""
    m, a, rho = tooth.module, tooth.pressure_angle, tooth.rack.fillet_radius
    r, x = tooth.pitch_radius, tooth.shift
    half = math.pi * m / 4 + tooth.thinning / 2
    top, tip = 2.0 * m, -1.25 * m
    trapezoid = shapely.Polygon([(-half - top * math.tan(a), top), (half + top * math.tan(a), top),
                                 (half + tip * math.tan(a), tip), (-half - tip * math.tan(a), tip)])
    cutter = trapezoid.buffer(-rho, quad_segs=48).buffer(rho, quad_segs=48)      # the corners rounded by rho
    cutter = shapely.affinity.translate(cutter, xoff=math.pi * m / 2)          # the tooth right of the space at 0
    reach = 6.0 * m
    removed = []
    for phi in np.linspace((math.pi * m / 2 - reach) / r, (math.pi * m / 2 + reach) / r, steps):
        placed = shapely.affinity.translate(cutter, xoff=-r * phi, yoff=r + x * m)
        removed.append(shapely.affinity.rotate(placed, -phi, origin=(0, 0), use_radians=True))
    blank = shapely.Point(0, 0).buffer(tooth.tip_radius, quad_segs=2048)
    cut = blank.difference(shapely.union_all(removed))
    return shapely.affinity.rotate(cut, -math.pi / 2, origin=(0, 0), use_radians=True)


def _segments(lines) -> np.ndarray:
    """The segments (k, 2, 2) of a LineString's or MultiLineString's lines, each (start, end)."""
    return np.concatenate([np.stack([c[:-1], c[1:]], axis=1)
                           for c in map(shapely.get_coordinates, shapely.get_parts(lines))])


def _to_segments(points: np.ndarray, p0: np.ndarray, p1: np.ndarray) -> np.ndarray:
    """Each point's distance to its segment p0 -> p1 (arrays broadcasting to (..., 2)), as GEOS measures it: to the
    segment's closest point, the projection clipped to its ends."""
    d = p1 - p0
    length2 = np.einsum("...i,...i->...", d, d)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(length2 > 0, np.clip(np.einsum("...i,...i->...", points - p0, d) / length2, 0.0, 1.0), 0.0)
    gap = points - (p0 + r[..., None] * d)
    return np.hypot(gap[..., 0], gap[..., 1])


def _oriented(lines, other, densify: float) -> float:
    """The largest distance to ``other`` of ``lines``' vertices and of its segments' points at fractions
    ``densify`` apart (from each segment's start: GEOS's DiscreteHausdorffDistance's points), each point measured
    against the segments of ``other`` that can be nearest it: those within (the nearer of its segment's ends' distance
    to ``other``) + (its segment's length) of its segment, as no point of the segment lies further from ``other``."""
    pieces = round(1 / densify)
    seg, target = _segments(lines), _segments(other)
    ends = shapely.distance(shapely.points(seg.reshape(-1, 2)), other).reshape(-1, 2)
    reach = ends.min(axis=1) + np.hypot(*(seg[:, 1] - seg[:, 0]).T)
    s, t = shapely.STRtree(shapely.linestrings(target)).query(shapely.linestrings(seg), predicate="dwithin",
                                                               distance=reach)
    starts = np.flatnonzero(np.r_[True, s[1:] != s[:-1]])             # each segment's first candidate (s is sorted)
    assert len(starts) == len(seg)                                    # each has one: its nearer end's nearest
    best = np.empty((len(seg), pieces))
    for lo in range(0, len(seg), 256):                                # 256 segments' points at a time
        hi = min(len(seg), lo + 256)
        a, b = starts[lo], starts[hi] if hi < len(seg) else len(s)
        p0, p1 = seg[s[a:b], 0][:, None, :], seg[s[a:b], 1][:, None, :]
        points = p0 + np.arange(pieces)[None, :, None] * ((p1 - p0) / pieces)
        dist = _to_segments(points, target[t[a:b], 0][:, None, :], target[t[a:b], 1][:, None, :])
        best[lo:hi] = np.minimum.reduceat(dist, starts[lo:hi] - a, axis=0)
    return max(float(best.max()), float(ends.max()))


def _hausdorff(a, b, densify: float) -> float:
    """``shapely.hausdorff_distance(a, b, densify=densify)`` (mm) of two LineStrings or MultiLineStrings: the same
    points and distances, each point measured against the few segments that can be nearest it (GEOS measures it
    against every segment: seconds for the cut's thousands)."""
    return max(_oriented(a, b, densify), _oriented(b, a, densify))


def test_the_hausdorff_distance_is_shapely_s():
    """:func:`_hausdorff` is shapely's densified Hausdorff distance to rounding: random lines and pairs of lines,
    short and long segments, far apart, one the other's points moved a little, or bits of the other's segment with
    gaps between them (its largest distance then inside that segment, where only the densified points see it),
    densified coarsely and finely, either way round."""
    rng = np.random.default_rng(38)

    def walk(count: int, scale: float) -> np.ndarray:
        return np.cumsum(rng.normal(scale=scale, size=(count, 2)), axis=0)

    def near(line: np.ndarray) -> np.ndarray:            # points along the line, each moved up to about 1e-3
        at = np.sort(rng.uniform(0, len(line) - 1, 3 * len(line)))
        k = np.minimum(at.astype(int), len(line) - 2)
        return line[k] + (at - k)[:, None] * (line[k + 1] - line[k]) + rng.normal(scale=1e-3, size=(len(at), 2))

    def pieces(line: np.ndarray) -> list[np.ndarray]:     # bits of the line's first segment, gaps between them
        ends = np.sort(rng.uniform(0, 1, 2 * int(rng.integers(1, 4)))).reshape(-1, 2)
        return [line[0] + np.linspace(t0, t1, 3)[:, None] * (line[1] - line[0]) for t0, t1 in ends]

    for trial in range(30):
        a = [walk(int(rng.integers(2, 30)), float(rng.choice([0.01, 1.0]))) for _ in range(rng.integers(1, 3))]
        b = [[walk(int(rng.integers(2, 30)), 1.0)], [near(line) for line in a], pieces(a[0])][trial % 3]
        one, two = (shapely.MultiLineString(p) if len(p) > 1 else shapely.LineString(p[0]) for p in (a, b))
        for densify in (0.5, 0.05, 0.005):
            assert _hausdorff(one, two, densify) == pytest.approx(shapely.hausdorff_distance(one, two, densify=densify),
                                                                  rel=1e-12, abs=1e-15), (trial, densify)


@pytest.mark.parametrize(("z", "x"), [(20, 0.0), (12, 0.0), (12, 0.4), (9, 0.2)])
def test_the_root_is_what_the_basic_rack_cuts(z, x):
    """The outline near tooth 0's right flank (root trochoid, flank) against the gear cut here by rolling the rack:
    within the outline's tolerance (1 um here) and the cut's own chords and steps (0.3 um); undercut gears (12 and 9
    teeth) included. (A tooth 4 um thinner than the cut measures 2.5 um off.)"""
    from linkgen.gears.outline import gear_outline

    tooth = _tooth(z, x, m=2.0, thinning=0.04)
    cut = _cut_by_rack(tooth)
    fit = 1e-3
    ours = shapely.Polygon(_polygon(gear_outline(tooth, fit)))
    pitch = 2 * math.pi / z
    window = shapely.Polygon([(0, 0), *(3 * tooth.tip_radius * np.column_stack(
        [np.cos(t := np.linspace(-pitch, 0.0, 50)), np.sin(t)]))])
    a, b = ours.boundary.intersection(window), cut.boundary.intersection(window)
    assert _hausdorff(a, b, densify=0.005) <= fit + 3e-4
    assert tooth.undercut == (z < 2 * (1 - x) / math.sin(math.radians(20)) ** 2)


# ---------------------------------------------------------------------------------------------- undercut

@pytest.mark.parametrize("a", [14.5, 20.0, 22.0])
@pytest.mark.parametrize("z", [8, 12, 17, 25])
def test_the_fewest_teeth_without_undercut_flips_exactly_at_it(z, a):
    alpha = math.radians(a)
    limit = 1 - z * math.sin(alpha) ** 2 / 2               # the shift at which z = 2 (1 - x) / sin^2 a
    assert _tooth(z, limit, a=a).fewest_teeth == pytest.approx(z, rel=1e-12)
    assert not _tooth(z, limit + 1e-9, a=a).undercut
    assert _tooth(z, limit - 1e-9, a=a).undercut
    assert _tooth(z, limit + 1e-9, a=a).form_radius == pytest.approx(z * math.cos(alpha), abs=1e-6)  # m = 2
    assert _tooth(z, limit - 0.05, a=a).form_radius > z * math.cos(alpha) + 1e-4     # the foot cut away


def test_the_textbook_seventeen():
    assert _tooth(17, 0.0).fewest_teeth == pytest.approx(2 / math.sin(math.radians(20)) ** 2, rel=1e-12)
    assert 17 < _tooth(17, 0.0).fewest_teeth < 17.1
    assert _tooth(17, 0.0).undercut and not _tooth(18, 0.0).undercut


def test_a_sharper_rack_fillet_reaches_deeper_above_22_degrees():
    """At 25 degrees ISO 53's 0.25 m / (1 - sin a) fillet no longer fits the rack's tip; the largest that does
    leaves the straight flank deeper than 1 m, which moves the undercut limit to 2 (h - x) / sin^2 a."""
    rack = BasicRack(1.0, math.radians(25))
    tip_half = (math.pi / 2 - 2.5 * math.tan(rack.pressure_angle)) / 2
    assert rack.fillet_radius == pytest.approx(tip_half / math.tan(math.pi / 4 - rack.pressure_angle / 2))
    assert rack.straight_depth == pytest.approx(1.25 - rack.fillet_radius * (1 - math.sin(rack.pressure_angle)))
    assert rack.straight_depth > 1
    assert BasicRack(1.0, math.radians(20)).straight_depth == pytest.approx(1.0, abs=1e-12)


# -------------------------------------------------------------------------------------------- pairs rolled

def _turn(angle: float) -> np.ndarray:
    """The matrix M of :func:`_pose` (row vectors: p M is p turned by ``angle`` counter-clockwise)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, s], [-s, c]])


def _pose(points: np.ndarray, angle: float, origin) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s], [-s, c]]) + origin


def _near(closed: np.ndarray, angles: np.ndarray, origins: np.ndarray, centre: np.ndarray, reach: float,
          size: int = 16) -> np.ndarray:
    """At each of k poses (a polygon turned by ``angles`` (k,) rad counter-clockwise, then moved by ``origins``
    (k, 2) mm, as :func:`_pose` does), the runs of the polygon's boundary (``closed``: its points, the first again at
    the end) within ``reach`` of ``centre`` (its edges with both ends that near): one MultiLineString a pose, its
    lines cut to at most ``size`` edges each (neighbours share a vertex): the same edges, in boxes small enough that
    ``shapely.distance`` passes over the pairs of lines whose boxes lie further apart than its best so far. The
    points near ``centre`` are picked in the polygon's own frame (``centre`` taken back there), and only they are
    posed."""
    c, s = np.cos(angles), np.sin(angles)
    back = centre - origins                                           # centre - origin, turned back by the angle
    cx, cy = back[:, 0] * c + back[:, 1] * s, back[:, 1] * c - back[:, 0] * s
    box = reach * (1 + 1e-9)                       # the vertices that can be near: within the box of the centres
    near = np.flatnonzero((np.abs(closed[:, 0] - (cx.max() + cx.min()) / 2) <= (cx.max() - cx.min()) / 2 + box)
                          & (np.abs(closed[:, 1] - (cy.max() + cy.min()) / 2) <= (cy.max() - cy.min()) / 2 + box))
    inside = np.zeros((len(angles), len(closed)), dtype=bool)
    inside[:, near] = np.hypot(closed[None, near, 0] - cx[:, None], closed[None, near, 1] - cy[:, None]) <= reach
    flat = np.flatnonzero(inside[:, :-1] & inside[:, 1:])
    pose, edges = np.divmod(flat, len(closed) - 1)
    first = np.concatenate([[True], (np.diff(flat) != 1) | (np.diff(pose) != 0)])   # the first edge of each run
    place = np.arange(len(edges)) - np.maximum.accumulate(np.where(first, np.arange(len(edges)), 0))
    starts = first | (place % size == 0)                               # the first edge of each line
    last = np.concatenate([starts[1:], [True]])
    count = 1 + last                                                   # each edge's start, and a line's end
    vertex, at = np.repeat(edges, count), np.repeat(pose, count)
    vertex[np.cumsum(count)[last] - 1] += 1
    x, y = closed[vertex].T
    posed = np.column_stack([x * c[at] - y * s[at], x * s[at] + y * c[at]]) + origins[at]
    lines = shapely.linestrings(posed, indices=np.repeat(np.cumsum(starts) - 1, count))
    out = shapely.multilinestrings(lines, indices=pose[starts])
    assert len(out) == len(angles)              # every pose has edges near the centre
    return out


PAIRS = [("external", 12, 0.3, 30, 0.0, 20.0, 0.1), ("external", 17, 0.0, 17, 0.0, 20.0, 0.2),
         ("external", 14, 0.5, 40, 0.2, 20.0, 0.15), ("external", 20, -0.2, 28, 0.2, 25.0, 0.1),
         ("internal", 20, 0.0, 50, 0.5, 20.0, 0.1), ("internal", 16, 0.2, 44, 0.6, 20.0, 0.15),
         ("rack", 12, 0.35, 0, 0.0, 20.0, 0.1), ("rack", 20, 0.0, 0, 0.0, 20.0, 0.2)]


@pytest.mark.parametrize(("kind", "z1", "x1", "z2", "x2", "a", "j"), [PAIRS[k] for k in (0, 2, 3, 4, 5, 6)])
def test_a_pair_rolled_two_pitches_keeps_its_backlash_and_never_overlaps(kind, z1, x1, z2, x2, a, j):
    """The outlines made within ``tol`` (chords of a tenth of it where measured), the pinion turned so that its tips
    move ``tol`` a step: the flanks' gap stays the normal backlash's half within both outlines' tolerance."""
    m, tol = 2.0, 2e-3
    pair = GearPair(kind, BasicRack(m, math.radians(a)), z1, x1, z2, x2, j)
    shapes = outlines(pair, tol, travel=60.0)
    flat = tol / 10
    pinion, other = _polygon(shapes.pinion, flat), _polygon(shapes.other, flat)
    c, aw = pair.centre_distance, pair.working_pressure_angle
    rw1 = pair.working_pitch_radii[0]
    pitch_point = {"external": (rw1, 0.0), "internal": (-rw1, 0.0), "rack": (0.0, -rw1)}[kind]
    if kind != "rack":            # the working pitch radius from c and a_w, independently
        assert rw1 == pytest.approx(c * z1 / (z2 + z1 if kind == "external" else z2 - z1), rel=1e-12)
    reach = 3.0 * m + math.sqrt(pair.pinion_tooth.tip_radius**2 - pair.pinion_tooth.base_radius**2)
    tip = pair.pinion_tooth.tip_radius
    steps = math.ceil(2 * (2 * math.pi / z1) * tip / tol)        # the tips move one tolerance a step
    theta0 = pair.mesh_phases[0]
    thetas = theta0 + 2 * (2 * math.pi / z1) * np.arange(steps + 1) / steps
    wheres = pair.gear_angle(thetas)
    if kind == "rack":        # the rack's shift: the pinion's pitch circle rolls on the rack's datum line
        assert wheres == pytest.approx(rw1 * (thetas - theta0) + pair.gear_angle(np.array([theta0]))[0])
        angles, origins = np.zeros_like(thetas), np.column_stack([wheres, np.full_like(thetas, -c)])
    else:
        angles, origins = wheres, np.tile([c, 0.0], (len(thetas), 1))
    closed_pinion, closed_other = np.vstack([pinion, pinion[:1]]), np.vstack([other, other[:1]])
    centre = np.array(pitch_point)
    gaps = []
    for k in range(0, len(thetas), 256):        # 256 poses at a time
        poses = slice(k, k + 256)
        turned = _near(closed_pinion, thetas[poses], np.zeros((len(thetas[poses]), 2)), centre, reach)
        gaps.append(shapely.distance(turned, _near(closed_other, angles[poses], origins[poses], centre, reach)))
    gaps = np.concatenate(gaps)
    # no overlap: the boundaries never meet, and a point of one is not inside the other (the pinion lies inside
    # an internal gear's toothed hole, outside the others): the pinion's first point taken to the other's frame
    solid = shapely.Polygon(other)
    shapely.prepare(solid)
    c_p, s_p = np.cos(thetas), np.sin(thetas)
    back = np.column_stack([pinion[0, 0] * c_p - pinion[0, 1] * s_p, pinion[0, 0] * s_p + pinion[0, 1] * c_p]) - origins
    c_o, s_o = np.cos(angles), np.sin(angles)
    x, y = back[:, 0] * c_o + back[:, 1] * s_o, back[:, 1] * c_o - back[:, 0] * s_o
    assert np.all(shapely.contains_xy(solid, x, y) == (kind == "internal"))
    normal = j * math.cos(aw) / 2                  # the circular backlash j, half on each side, along the normal
    assert gaps.min() > 0
    assert np.abs(gaps - normal).max() <= 2 * tol + 2 * flat, (gaps.min(), gaps.max(), normal)


@pytest.mark.parametrize(("kind", "z1", "x1", "z2", "x2"), [("external", 12, 0.3, 30, 0.0),
                                                      ("internal", 20, 0.0, 50, 0.5), ("rack", 18, 0.0, 0, 0.0)])
def test_the_build_time_overlap_check_sees_teeth_too_thick_to_mesh(kind, z1, x1, z2, x2):
    """The check :class:`GearPairMechanism` runs before it makes a pair: teeth thickened by a negative backlash of
    0.05 mm (each 0.025 mm on its pitch circle) are found overlapping; thinned by 0.05 mm they never touch."""
    from linkgen.mechanisms.gearparts import overlap

    rack = BasicRack(2.0, math.radians(20))
    assert overlap(GearPair(kind, rack, z1, x1, z2, x2, 0.05), travel=40.0) is None
    assert overlap(GearPair(kind, rack, z1, x1, z2, x2, -0.05), travel=40.0) is not None


def _every_vertex(pair: GearPair, travel: float) -> dict:
    """The overlap check's sweep worked without its shortcuts: both outlines flattened as the check flattens them,
    and every vertex of each placed at every step of the pitch at once (complex rotations) in the other member's
    frame: the polygons, the vertices, the steps and the placed vertices."""
    from camgen.core.shapes import Circle
    from linkgen.mechanisms.gearparts import CHECK_RESOLUTION

    res = CHECK_RESOLUTION * pair.module
    shapes = outlines(pair, res, travel)
    p_pts, o_pts = Contour(*shapes.pinion).flatten(res), Contour(*shapes.other).flatten(res)
    pinion = shapely.Polygon(p_pts)
    if pair.kind == "internal":
        rim = Circle((0.0, 0.0), pair.gear_tooth.tip_radius + 2 * pair.module).flatten(res)
        other = shapely.Polygon(rim, [o_pts])
    else:
        other = shapely.Polygon(o_pts)
    first, _ = pair.mesh_phases
    pitch = 2 * math.pi / pair.pinion_teeth
    steps = math.ceil(pitch * pair.pinion_tooth.tip_radius / res)
    theta = first + pitch * np.arange(steps + 1) / steps
    where = pair.gear_angle(theta)
    turn = np.zeros_like(where) if pair.kind == "rack" else where
    origin = (np.column_stack([where, np.full_like(where, -pair.centre_distance)]) if pair.kind == "rack"
              else np.tile([pair.centre_distance, 0.0], (len(where), 1)))

    def turned(xy, a):                                      # xy (k or 1, m, 2) each turned by its own of a (k,)
        z = (xy[..., 0] + 1j * xy[..., 1]) * np.exp(1j * a)[:, None]
        return np.stack([z.real, z.imag], -1)

    return {"pinion": pinion, "other": other, "p_pts": p_pts, "o_pts": o_pts, "theta": theta, "where": where,
            "res": res, "reach": pair.pinion_tooth.tip_radius + res,
            "o_in_p": turned(turned(o_pts[None], turn) + origin[:, None], -theta),
            "p_in_o": turned(turned(p_pts[None], theta) - origin[:, None], -turn)}


def _first_overlap_every_vertex(sweep: dict) -> float | None:
    """The first step of :func:`_every_vertex`'s sweep at which a vertex lies inside the other member, or None."""
    o_in_p, p_in_o = sweep["o_in_p"], sweep["p_in_o"]
    hit = (shapely.contains_xy(sweep["pinion"], o_in_p[..., 0], o_in_p[..., 1]).any(axis=1)
           | shapely.contains_xy(sweep["other"], p_in_o[..., 0], p_in_o[..., 1]).any(axis=1))
    return float(sweep["theta"][np.argmax(hit)]) if hit.any() else None


#: pairs whose teeth clear (0.05 mm of backlash), just touch (0) and overlap by a little and by more (negative)
OVERLAPS = [("external", 12, 0.3, 30, 0.0, 0.05), ("external", 8, 0.0, 40, 0.0, -0.002),
            ("internal", 20, 0.0, 50, 0.5, 0.0), ("internal", 12, 0.0, 30, 0.3, -0.05),
            ("rack", 18, 0.0, 0, 0.0, -0.002), ("rack", 12, 0.35, 0, 0.0, 0.05)]


@pytest.mark.parametrize(("kind", "z1", "x1", "z2", "x2", "backlash"), OVERLAPS)
def test_the_overlap_check_is_every_vertex_at_every_step(kind, z1, x1, z2, x2, backlash):
    """The build's overlap check (which tests only the vertices that can come near, a block of steps at a time)
    gives the first step the brute force over every vertex at every step gives, or None with it; and the vertices
    it leaves out are never near the pinion's centre nor inside the other member at any step."""
    from linkgen.mechanisms.gearparts import _reachable, overlap

    pair = GearPair(kind, BasicRack(2.0, math.radians(20)), z1, x1, z2, x2, backlash)
    travel = 40.0 if kind == "rack" else 0.0
    sweep = _every_vertex(pair, travel)
    expected = _first_overlap_every_vertex(sweep)
    assert overlap(pair, travel) == (None if expected is None else pytest.approx(expected, abs=1e-12))
    assert (expected is None) == (backlash > 0) or backlash == 0
    o_kept, p_kept = _reachable(pair, sweep["o_pts"], sweep["p_pts"], sweep["other"], sweep["theta"],
                                sweep["where"], sweep["reach"], sweep["res"])
    o_in_p, p_in_o = sweep["o_in_p"], sweep["p_in_o"]
    near = (np.hypot(o_in_p[..., 0], o_in_p[..., 1]) <= sweep["reach"]).any(axis=0)
    inside = shapely.contains_xy(sweep["other"], p_in_o[..., 0], p_in_o[..., 1]).any(axis=0)
    assert not (near & ~o_kept).any() and not (inside & ~p_kept).any()
    assert (o_kept.sum() + p_kept.sum()) / (len(o_kept) + len(p_kept)) < 0.3      # and it leaves most out
    assert near.any() and (inside.any() or backlash > 0)                 # the comparison is not of nothing


# ------------------------------------------------------------------------------------------ contact ratio

def _aw_50_digits(a: float, total: float, span: int) -> float:
    """a_w of inv a_w = inv a + 2 tan a total / span, solved to 50 digits."""
    mpmath.mp.dps = 50
    a_mp = mpmath.mpf(a)
    target = mpmath.tan(a_mp) - a_mp + 2 * mpmath.tan(a_mp) * mpmath.mpf(total) / span
    return float(mpmath.findroot(lambda t: mpmath.tan(t) - t - target, a_mp + 0.1))


def _segment_in_circle(p: np.ndarray, q: np.ndarray, centre: np.ndarray, radius: float) -> tuple[float, float]:
    """The stretch (parameters in [0, 1] from p to q) of the segment inside a circle."""
    d, f = q - p, p - centre
    aa, bb, cc = d @ d, 2 * f @ d, f @ f - radius**2
    root = math.sqrt(bb * bb - 4 * aa * cc)
    return max((-bb - root) / (2 * aa), 0.0), min((-bb + root) / (2 * aa), 1.0)


@pytest.mark.parametrize(("kind", "z1", "x1", "z2", "x2", "a", "j"), PAIRS)
def test_the_contact_ratio_is_the_textbooks(kind, z1, x1, z2, x2, a, j):
    m, alpha = 2.0, math.radians(a)
    pair = GearPair(kind, BasicRack(m, alpha), z1, x1, z2, x2, j)
    r1, r2 = m * z1 / 2, m * z2 / 2
    rb1, rb2 = r1 * math.cos(alpha), r2 * math.cos(alpha)
    ra1 = r1 + (1 + x1) * m
    pb = math.pi * m * math.cos(alpha)
    if kind == "external":
        aw = _aw_50_digits(alpha, x1 + x2, z1 + z2)
        c = (r1 + r2) * math.cos(alpha) / math.cos(aw)
        ra2 = r2 + (1 + x2) * m
        textbook = (math.sqrt(ra1**2 - rb1**2) + math.sqrt(ra2**2 - rb2**2) - c * math.sin(aw)) / pb
        # the path of contact: the line of action from T1 to T2 inside both tip circles
        t1, t2 = rb1 * np.array([math.cos(aw), -math.sin(aw)]), np.array([c, 0.0]) + rb2 * np.array(
            [-math.cos(aw), math.sin(aw)])
        s1, e1 = _segment_in_circle(t1, t2, np.zeros(2), ra1)
        s2, e2 = _segment_in_circle(t1, t2, np.array([c, 0.0]), ra2)
        measured = (min(e1, e2) - max(s1, s2)) * float(np.hypot(*(t2 - t1))) / pb
    elif kind == "internal":
        aw = _aw_50_digits(alpha, x2 - x1, z2 - z1)
        c = (r2 - r1) * math.cos(alpha) / math.cos(aw)
        ra2 = r2 - (1 - x2) * m
        textbook = (math.sqrt(ra1**2 - rb1**2) - math.sqrt(ra2**2 - rb2**2) + c * math.sin(aw)) / pb
        # the line of action touches both base circles on the same side: from T2 (on the ring's) past T1 and the
        # pitch point; contact from where it leaves the ring's tip circle to where it leaves the pinion's
        t2 = np.array([c, 0.0]) + rb2 * np.array([-math.cos(aw), math.sin(aw)])
        t1 = rb1 * np.array([-math.cos(aw), math.sin(aw)])
        length = float(np.hypot(*(t1 - t2))) + 2 * ra1
        far = t2 + length * (t1 - t2) / float(np.hypot(*(t1 - t2)))
        _, e1 = _segment_in_circle(t2, far, np.zeros(2), ra1)
        _, e2 = _segment_in_circle(t2, far, np.array([c, 0.0]), ra2)
        measured = (e1 - e2) * length / pb
    else:
        aw = alpha
        c = r1 + x1 * m
        textbook = (math.sqrt(ra1**2 - rb1**2) - r1 * math.sin(alpha) + (1 - x1) * m / math.sin(alpha)) / pb
        # from the rack's tip line (c - m below the pinion's centre, above the pitch point) down the line of action
        # through the pitch point to where it leaves the pinion's tip circle
        t1 = rb1 * np.array([-math.sin(alpha), -math.cos(alpha)])
        direction = np.array([math.cos(alpha), -math.sin(alpha)])
        s_tip = (-(c - m) - t1[1]) / direction[1]
        length = 2 * ra1
        _, e1 = _segment_in_circle(t1, t1 + length * direction, np.zeros(2), ra1)
        measured = (e1 * length - s_tip) / pb
    assert pair.working_pressure_angle == pytest.approx(aw, abs=1e-13)
    assert pair.centre_distance == pytest.approx(c, rel=1e-13)
    assert pair.contact_ratio == pytest.approx(textbook, rel=1e-12)
    assert pair.contact_ratio == pytest.approx(measured, rel=1e-9)
    assert pair.contact_ratio > 1


def test_a_standard_pair_meshes_at_its_reference_centre_distance():
    pair = GearPair("external", BasicRack(3.0, math.radians(20)), 19, 0.0, 41, 0.0, 0.1)
    assert pair.working_pressure_angle == pytest.approx(math.radians(20), abs=1e-15)
    assert pair.centre_distance == pytest.approx(3.0 * (19 + 41) / 2, abs=1e-12)
    assert pair.speed_ratio == pytest.approx(-19 / 41)


# ------------------------------------------------------------------------------------------------ refusals

BASE = """name = "g"
[linkage]
type = "gear-pair"
kind = "{kind}"
module = 2.0
[linkage.pinion]
teeth = 18
{other}
[parts]
width = 12.0
thickness = 4.0
pin_diameter = 4.0
"""
GEAR = "[linkage.gear]\nteeth = 36"
RACK = "[linkage.slider]\ntravel = 40.0"


@pytest.mark.parametrize(("kind", "other", "sets", "message"), [
    ("external", GEAR, ["linkage.pinion.teeth=0"], "linkage.pinion.teeth: "),
    ("external", GEAR, ["linkage.gear.teeth=10000"], "linkage.gear.teeth: "),
    ("external", GEAR, ["linkage.module=0"], "linkage.module: "),
    ("external", GEAR, ["linkage.pressure_angle=60"], "linkage.pressure_angle: "),
    ("rack", "", [], "linkage.slider: a rack rides on a slider"),
    ("external", GEAR, ["linkage.centre_distance=55"], "linkage.centre_distance: these teeth and shifts mesh at "
                                                       "54.000000 mm (got 55)"),
    ("external", GEAR + "\n" + RACK, [], "linkage.slider: only a rack rides on a slider"),
    ("internal", "[linkage.gear]\nteeth = 16", [], "linkage.gear.teeth: an internal gear needs more teeth"),
    ("internal", "[linkage.gear]\nteeth = 22\nshift = 0.8", ["linkage.pinion.teeth=16", "linkage.pinion.shift=0.2"],
     "linkage.gear.shift: the internal gear's tooth spaces close before its root circle"),
    ("external", GEAR, ["linkage.pinion.teeth=6", "linkage.pinion.shift=0.8"], "linkage.pinion.shift: the teeth "
                                                                              "come to a point"),
    ("external", GEAR, ["linkage.backlash=2"], "linkage.backlash: must be > 0 and <= 0.785398 mm"),
])
@pytest.mark.parametrize("command", ["analyze", "build"])
def test_bad_input_is_one_line_naming_the_field(tmp_path, kind, other, sets, message, command):
    from linkgen.cli import main

    path = tmp_path / "g.toml"
    path.write_text(BASE.format(kind=kind, other=other))
    assert_refused_sets(path, sets, message, tmp_path, main, command)


@pytest.mark.parametrize(("kind", "other", "line"), [
    ("external", GEAR, "at pinion 10.0000 deg (360 deg/s): gear 170.000000 deg, -180 deg/s"),
    ("rack", RACK, "at pinion 10.0000 deg (360 deg/s): rack 6.283185 mm, 113.097 mm/s")])
def test_analyze_prints_the_pair_and_where_it_is(tmp_path, kind, other, line):
    """18 teeth drive 36 at half the speed the other way (the gear's tooth space faces the pinion's tooth 0 at
    180 - 5 degrees when the pinion is at 0); a rack moves r = 18 mm a radian from 0 where a pinion tooth points
    straight down at it (-90 degrees, -10 less whole pitches of 20)."""
    from linkgen.cli import main

    path = tmp_path / "g.toml"
    path.write_text(BASE.format(kind=kind, other=other))
    result = CliRunner().invoke(main, ["analyze", str(path), "--angle", "10", "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert line in result.output.splitlines()
    assert f"{kind} pair: centre distance {54 if kind == 'external' else 18} mm" in result.output
