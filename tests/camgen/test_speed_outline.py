"""The outline made at once (issue 16): every stretch of a cam asks for the angles it needs and one evaluation of the
follower a round serves them all. Its result is each stretch's own, to the last bit, and the number of evaluations is
what the design says (a count, not a time). So are the cuts in numpy calls under it: a program evaluating points on
all its segments at once, and a translating roller's pitch geometry from numbers instead of constant arrays."""
from __future__ import annotations

import copy
import dataclasses
import warnings
from typing import Any

import numpy as np
import pytest

from camgen.flat import build_cam
from camgen.laws import TABLE_LAWS
from camgen.outline import exact_outline, stretch
from camgen.spec import validate_spec
from tests.conftest import RDRD

FOLLOWERS = {
    "offset roller": {},
    "knife edge": {"follower.type": "knife-edge", "follower.roller_radius": None, "motion.2.law": "cycloidal"},
    "flat face": {"follower.type": "translating-flat", "follower.roller_radius": None, "follower.offset": None,
                  "cam.base_radius": 60.0},
    "oscillating roller": {"follower.type": "oscillating-roller", "follower.offset": None,
                           "follower.pivot_distance": 110.0, "follower.arm_length": 90.0, "follower.roller_radius": 8.0,
                           "motion.0.lift": 15.0, "motion.2.lift": 15.0},
    "clockwise": {"cam.rotation": "cw"},
}


class _Counting:
    """A follower that counts its evaluations and is otherwise the one it wraps."""

    def __init__(self, inner: Any) -> None:
        self.inner, self.calls = inner, []

    def __getattr__(self, name: str) -> Any:
        return getattr(self.inner, name)

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> Any:
        self.calls.append(theta.size)
        return self.inner.pitch(theta, motion)


def _raw(changes: dict) -> dict:
    """The rdrd mapping with dotted keys set (None: removed)."""
    raw = copy.deepcopy(RDRD)
    for key, value in changes.items():
        *path, last = key.split(".")
        table = raw
        for part in path:
            table = table[int(part)] if part.isdigit() else table[part]
        if value is None:
            table.pop(last, None)
        else:
            table[last] = value
    return raw


def _cam(changes: dict):
    """rdrd with dotted keys set (None: removed), built."""
    return build_cam(validate_spec(_raw(changes)))


def _contains(whole: np.ndarray, block: np.ndarray, start: int) -> int:
    """Where ``block`` (rows) next appears in ``whole`` from row ``start`` on, exactly; -1 if it does not."""
    for at in range(start, len(whole) - len(block) + 1):
        if np.array_equal(whole[at:at + len(block)], block):
            return at
    return -1


@pytest.mark.parametrize("curves", ["polylines", "biarcs"])
@pytest.mark.parametrize("follower", list(FOLLOWERS))
def test_the_outline_is_each_stretch_made_alone(follower, curves):
    cam = _cam(FOLLOWERS[follower])
    outline = exact_outline(cam, 0.01, curves)
    verts = outline.contour.vertices
    if outline.contour.area < 0 or not np.array_equal(verts, exact_outline(cam, 0.01, curves).contour.vertices):
        pytest.fail("the outline is not reproducible")
    at, worst = 0, 0.0
    for i, _ in enumerate(cam.program.segments):
        v, _, err = stretch(cam, i, 0.01, cam.contact_radius, curves)
        found = _contains(verts, v, at)
        if found < 0:                                   # the contour may have been turned round to run ccw
            verts = verts[::-1]
            found = _contains(verts, v, 0)
        assert found >= 0, f"motion[{i}]'s stretch is not in the outline as made alone"
        at, worst = found + len(v), max(worst, err)
    assert outline.max_error_mm == worst <= 0.01


def test_a_cam_takes_two_evaluations_of_its_follower():
    cam = _cam({})
    counting = _Counting(cam.follower)
    counted = dataclasses.replace(cam, follower=counting)
    outline = exact_outline(counted, 0.01)
    # one round for every spacing grid, dwell and the segment ends (the corners, made from them), and one for every
    # rise's and return's vertices and probes together
    assert len(counting.calls) == 2
    assert np.array_equal(outline.contour.vertices, exact_outline(cam, 0.01).contour.vertices)
    counting.calls.clear()
    exact_outline(counted, 0.01, "biarcs")
    assert len(counting.calls) == 3          # the ends known: the grids and dwells, then both stretches' biarcs twice


def _same(a: Any, b: Any) -> bool:
    """Equal to the last bit, signs of zero included (None only to None)."""
    if a is None or b is None:
        return a is b
    return bool(np.array_equal(a, b) and np.array_equal(np.signbit(a), np.signbit(b)))


@pytest.mark.parametrize("law", TABLE_LAWS)
def test_a_program_evaluates_all_its_segments_at_once_as_each_alone(law):
    program = _cam({"motion.0.law": law, "motion.2.law": law}).program
    rng = np.random.default_rng(16)
    index, theta, alone = [], [], []
    for i, seg in enumerate(program.segments):      # the ends, the float below the end, and inside
        inside = seg.start + seg.beta * rng.random(40)
        t = np.concatenate([[seg.start, seg.end, np.nextafter(seg.end, -np.inf)], inside])
        index.append(np.full(t.size, i))
        theta.append(t)
        alone.append(seg.evaluate(t))
    index, theta, want = np.concatenate(index), np.concatenate(theta), np.concatenate(alone, axis=1)
    assert _same(program.evaluate_on(index, theta), want)
    mixed = rng.permutation(theta.size)                  # the segments' points interleaved
    assert _same(program.evaluate_on(index[mixed], theta[mixed]), want[:, mixed])
    angles, motion = program.boundaries
    n = len(program.segments)
    for i, seg in enumerate(program.segments):
        nxt = program.segments[(i + 1) % n]
        assert angles[i] == seg.end and angles[n + i] == nxt.start
        assert _same(motion[:, i], seg.evaluate(np.array(seg.end)))
        assert _same(motion[:, n + i], nxt.evaluate(np.array(nxt.start)))


def test_a_design_takes_two_evaluations_of_its_follower(monkeypatch):
    from camgen.analysis import analyze
    from camgen.api import design_cam
    from camgen.followers.translating_roller import TranslatingRoller

    spec = validate_spec(copy.deepcopy(RDRD))
    calls = []
    pitch = TranslatingRoller.pitch

    def counted(self: Any, theta: np.ndarray, motion: np.ndarray) -> Any:
        calls.append(theta.size)
        return pitch(self, theta, motion)

    monkeypatch.setattr(TranslatingRoller, "pitch", counted)
    design = design_cam(spec)
    # the analysis's grid (every second point of it the spacing's grids), the segment ends and the dwells in one; the
    # peaks' refinement and the rise's and return's vertices and probes in the other
    assert len(calls) == 2
    monkeypatch.undo()
    cam = build_cam(spec)                               # each made alone: the same to the last bit
    assert design.analysis == analyze(cam)
    # the outline alone spaces its chords on grids of its own: the same fractions of the same segments, a return's
    # angles made from its end (within an ulp), so the same vertices to rounding and the same bulges to the bit
    alone = exact_outline(cam, spec.output.tolerance).contour
    assert len(design.outline.contour.vertices) == len(alone.vertices)
    assert np.abs(design.outline.contour.vertices - alone.vertices).max() <= 1e-12
    assert _same(design.outline.contour.bulges, alone.bulges)
    assert design.jumps == tuple(build_cam(spec).program.jumps())


@pytest.mark.parametrize("law", TABLE_LAWS)
@pytest.mark.parametrize("follower", ["offset roller", "knife edge", "oscillating roller", "clockwise"])
def test_a_dwell_searched_at_one_point_is_the_search_of_its_grid(follower, law, monkeypatch):
    from camgen.analysis import analyze

    changes = {**FOLLOWERS[follower], "motion.0.law": law}
    cam = _cam(changes)
    assert cam.follower.steady
    dwell = next(i for i, seg in enumerate(cam.program.segments) if seg.kind == "dwell")
    seg = cam.program.segments[dwell]
    g = cam.segment_pitch(dwell, np.linspace(seg.start, seg.end, 129))     # constant to the last bit on a dwell
    assert (g.kappa == g.kappa[0]).all() and (g.pressure_angle == g.pressure_angle[0]).all()
    steady = analyze(cam)
    monkeypatch.setattr(type(cam.follower), "steady", False)
    assert analyze(_cam(changes)) == steady



def test_a_designs_tentative_outline_raises_only_where_it_is_used(monkeypatch):
    import camgen.outline
    from camgen.core.errors import DesignError
    from camgen.api import design_cam

    spec = validate_spec(copy.deepcopy(RDRD))
    small = copy.deepcopy(RDRD)
    for i, angle in enumerate((1.0, 179.0, 120.0, 60.0)):   # a rise over 1 degree: an undercut
        small["motion"][i]["angle"] = angle
    allowed = copy.deepcopy(small)
    allowed["cam"]["allow_undercut"] = True
    envelope = design_cam(validate_spec(allowed))
    monkeypatch.setattr(camgen.outline, "MAX_SEGMENT_VERTICES", 10)    # the exact outline fails at its spacing
    with pytest.raises(DesignError, match=r"^output.tolerance: the outline of motion\[0\] would need .*at most 10"):
        design_cam(spec)
    with pytest.raises(DesignError, match=r"undercut at .* degrees"):  # the undercut's own error, not the outline's
        design_cam(validate_spec(small))

    def broken(*args: Any) -> Any:                      # fails, warning first, where a tentative outline runs
        np.float64(1.0) / np.float64(0.0)
        raise ValueError("the exact outline was made")
        yield

    monkeypatch.undo()
    monkeypatch.setattr(camgen.outline, "_chords", broken)
    before = np.geterr()
    with warnings.catch_warnings(), pytest.raises(ValueError, match="the exact outline was made"):
        warnings.simplefilter("error")                  # its warning silenced in its own steps
        design_cam(spec)
    assert np.geterr() == before                        # and the caller's state as it was
    again = design_cam(validate_spec(allowed))          # the envelope's design: the failed outline unseen
    assert _same(again.outline.contour.vertices, envelope.outline.contour.vertices)


def test_a_hole_is_refused_where_it_touches_or_leaves_the_outline_as_measured_by_distance():
    import shapely

    from camgen.core.shapes import Circle
    from camgen.api import design_cam

    design = design_cam(validate_spec(copy.deepcopy(RDRD)))
    outline = design.outline.contour.flatten(0.01)
    body = shapely.Polygon(outline)
    rng = np.random.default_rng(16)
    rings = []
    for vertex in outline[rng.choice(len(outline), 60)]:   # holes about the edge: in, touching, across, out
        for reach in (-3.0, -1e-9, 0.0, 1e-9, 3.0):
            centre = vertex * (1 - (2.0 + reach) / np.linalg.norm(vertex))
            rings.append(shapely.Polygon(Circle((float(centre[0]), float(centre[1])), 2.0).flatten(0.01)))
    rings.append(shapely.Polygon([outline[0], outline[0] * 0.9, outline[1] * 0.9]))    # a corner on the outline
    for ring in rings:
        assert body.contains_properly(ring) == (body.contains(ring) and body.exterior.distance(ring) > 0)


def _segment_distance(points: np.ndarray, ring: np.ndarray) -> float:
    """The least distance (mm) from ``points`` (m, 2) to the closed polygon ``ring`` (n, 2), in numpy."""
    a, b = ring, np.roll(ring, -1, axis=0)
    ab, ap = b - a, points[:, None, :] - a
    t = np.clip((ap * ab).sum(-1) / (ab * ab).sum(-1), 0.0, 1.0)
    return float(np.sqrt(((ap - t[..., None] * ab) ** 2).sum(-1)).min())


def _inside(points: np.ndarray, ring: np.ndarray) -> np.ndarray:
    """Whether each point lies inside the closed polygon ``ring`` (crossings of a ray along +x), in numpy."""
    a, b = ring, np.roll(ring, -1, axis=0)
    x, y = points[:, None, 0], points[:, None, 1]
    spans = (a[:, 1] > y) != (b[:, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        cross = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return (spans & (x < cross)).sum(axis=1) % 2 == 1


def _hole_gap(outline: np.ndarray, circle: float, count: int, diameter: float, tolerance: float) -> float:
    """The signed clearance (mm) between the bolt holes (as chords within ``tolerance``) and the cam's outline:
    the least distance between their edges, negative if a hole's vertex is outside the outline."""
    from camgen.core.features import bolt_holes

    gaps = []
    for hole in bolt_holes(circle, count, diameter):
        ring = hole.flatten(tolerance)
        gap = min(_segment_distance(ring, outline), _segment_distance(outline, ring))
        gaps.append(gap if _inside(ring, outline).all() else -gap)
    return min(gaps)


def _threshold(accepted: Any, low: float, high: float) -> float:
    """The least float in (low, high] that ``accepted`` refuses, by bisection (``low`` accepted, ``high`` not)."""
    assert accepted(low) and not accepted(high)
    while np.nextafter(low, high) < high:
        mid = low + (high - low) / 2
        low, high = (mid, high) if accepted(mid) else (low, mid)
    return high


@pytest.mark.parametrize("follower", ["offset roller", "oscillating roller"])
def test_a_bolt_hole_touching_the_outline_is_refused_and_one_1e9_mm_inside_is_made(follower):
    from camgen.core.errors import DesignError
    from camgen.core.features import bolt_holes
    from camgen.api import design_cam

    raw = _raw(FOLLOWERS[follower])
    count, diameter = 3, 6.0
    tolerance = raw["output"]["tolerance"]

    def spec(circle: float) -> Any:
        raw["hub"] = {"bolt_circle": circle, "bolt_holes": count, "bolt_hole_diameter": diameter}
        return validate_spec(copy.deepcopy(raw))

    def made(circle: float) -> bool:
        try:
            design_cam(spec(circle))
        except DesignError as error:
            assert str(error).startswith("hub.bolt_circle: a hole reaches the cam's outline (it comes within ")
            return False
        return True

    outline = design_cam(spec(20.0)).outline.contour.flatten(tolerance)
    limit = _threshold(made, 20.0, 200.0)                 # the least bolt circle (mm) the design refuses
    measured = _threshold(lambda c: _hole_gap(outline, c, count, diameter, tolerance) > 0, 20.0, 200.0)
    assert abs(limit - measured) <= 1e-12                 # refused where a hole's edge meets the outline, not sooner
    # at the limit the hole's edge meets the outline: no float puts a hole's vertex exactly on these chords, so
    # "touching" is the first float GEOS's exact predicate finds not strictly inside, within 1e-12 mm of contact
    # (a touch to the last bit, on a square cam: the next test)
    assert abs(_hole_gap(outline, limit, count, diameter, tolerance)) <= 1e-12
    # the hole's centre moves out by half the circle's change: 1e-9 mm either side of touching
    inside, outside = limit - 2e-9, limit + 2e-9
    assert 0 < _hole_gap(outline, inside, count, diameter, tolerance) <= 1.01e-9
    assert _hole_gap(outline, outside, count, diameter, tolerance) < 0
    design = design_cam(spec(inside))
    assert [hole.centre for hole in design.part.holes[1:]] == [h.centre for h in bolt_holes(inside, count, diameter)]
    for circle in (limit, outside):
        with pytest.raises(DesignError, match=r"^hub\.bolt_circle: a hole reaches the cam's outline"):
            design_cam(spec(circle))


@pytest.mark.parametrize("count", [1, 3, 4])
def test_a_hole_touching_the_outline_exactly_is_refused_and_one_1e9_mm_inside_is_not(count):
    """The check design_cam runs, on a square cam of half-width w: bolt hole 0's vertex on +X lies at R + r
    exactly, so w = R + r puts it on the outline to the last bit (the bore's likewise at w = its radius)."""
    import shapely

    from camgen.core.errors import DesignError
    from camgen.profile import Body, check_holes

    raw = copy.deepcopy(RDRD)
    raw["hub"] = {"bolt_circle": 40.0, "bolt_holes": count, "bolt_hole_diameter": 6.0}
    spec = validate_spec(raw)
    for w, field in ((20.0 + 3.0, "hub.bolt_circle"), (5.0, "cam.bore")):
        if field == "cam.bore":
            spec = validate_spec({**raw, "hub": {}})
        body = Body.of(spec.name, spec.cam, spec.hub)
        for half, made in ((w, False), (w + 1e-9, True), (w - 1e-9, False)):
            square = shapely.box(-half, -half, half, half)
            if made:
                check_holes(body, square, 0.01)
                continue
            with pytest.raises(DesignError, match=rf"^{field}: a hole reaches the cam's outline \(it comes within "):
                check_holes(body, square, 0.01)


def _chord_errors_span_by_span(start, end, surface, kappa, rr, count):
    """The chord errors as measured before they were made probe by probe (issue 16): probes (spans, count, 2)
    span by span, np.linalg.norm's lengths, reductions along each span's row, the root before the maximum."""
    x = surface.reshape(len(start), count, 2)
    chain = np.concatenate([start[:, None, :], x, end[:, None, :]], axis=1)
    gap = np.linalg.norm(np.diff(chain, axis=1), axis=2).max(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        bend = (kappa / (1.0 - rr * kappa)).reshape(len(start), count)
    bend = np.where(np.isfinite(bend), bend, np.inf)
    bend = np.maximum(np.abs(bend.min(axis=1)), np.abs(bend.max(axis=1)))
    a, b = start[:, None, :], end[:, None, :]
    ab = b - a
    length2 = (ab**2).sum(axis=-1)
    t = np.minimum(np.maximum(((x - a) * ab).sum(axis=-1) / np.where(length2 > 0, length2, 1.0), 0.0), 1.0)
    return np.linalg.norm(a + t[..., None] * ab - x, axis=2).max(axis=1) + gap**2 * bend / 8


@pytest.mark.parametrize("follower", ["offset roller", "knife edge", "flat face", "oscillating roller"])
def test_chord_errors_probe_by_probe_are_those_measured_span_by_span(follower):
    from camgen.outline import _PROBES, _between, _chord_errors, _planes, _surface

    cam = _cam(FOLLOWERS[follower])
    rr = cam.contact_radius
    seg = cam.program.segments[0]
    rng = np.random.default_rng(16)
    theta = np.sort(seg.start + seg.beta * rng.random(60))
    theta[7] = theta[6]                                     # a span of no length
    ends = cam.segment_pitch(0, theta)
    inner = cam.segment_pitch(0, _between(theta[:-1], theta[1:], _PROBES))     # probe by probe
    at = _surface(ends, rr)
    order = np.arange(inner.theta.size).reshape(_PROBES, -1).T.ravel()          # the same probes span by span
    want = _chord_errors_span_by_span(at[:-1], at[1:], _surface(inner, rr)[order], inner.kappa[order], rr, _PROBES)
    probes = _planes(inner, rr).reshape(2, _PROBES, -1)
    assert _same(_chord_errors(_planes(ends, rr), probes, inner.kappa, rr), want)


def test_chord_errors_where_the_surface_has_no_curvature_are_those_measured_span_by_span():
    from camgen.outline import _PROBES, _between, _chord_errors, _planes, _surface

    cam = _cam(FOLLOWERS["offset roller"])
    rr = cam.contact_radius
    seg = cam.program.segments[0]
    theta = np.linspace(seg.start, seg.end, 40)
    theta[5] = theta[4]                                     # a span of no length
    ends = cam.segment_pitch(0, theta)
    inner = cam.segment_pitch(0, _between(theta[:-1], theta[1:], _PROBES))
    kappa = inner.kappa.copy()
    spans = len(theta) - 1
    for probe, span, value in ((0, 3, np.nan), (2, 6, np.nan), (1, 7, np.inf), (3, 9, -np.inf), (0, 11, 1.0 / rr),
                               (1, 11, np.nan), (2, 13, 0.0), (3, 13, -0.0)):
        kappa[probe * spans + span] = value                 # no curvature, infinite, the roller's own (1 - rr k = 0)
    odd = dataclasses.replace(inner, kappa=kappa)
    at = _surface(ends, rr)
    order = np.arange(inner.theta.size).reshape(_PROBES, -1).T.ravel()
    with np.errstate(divide="ignore", invalid="ignore"):   # as the outline's makers run (outline.quietly)
        want = _chord_errors_span_by_span(at[:-1], at[1:], _surface(odd, rr)[order], kappa[order], rr, _PROBES)
        got = _chord_errors(_planes(ends, rr), _planes(odd, rr).reshape(2, _PROBES, -1), kappa, rr)
    assert np.isinf(want[[3, 6, 7, 9, 11]]).all()
    assert _same(got, want)


def test_an_outline_maker_runs_quietly_and_leaves_the_callers_errstate():
    from camgen.numeric import drive
    from camgen.outline import quietly

    def maker():
        got = yield [1.0]
        got = yield [np.array([1.0]) / np.array([got[0]])]      # a division by zero each step, silenced
        return np.array([-1.0]) / np.array([got[0]])

    with np.errstate(all="raise"):
        out = drive(quietly(maker()), lambda ask: [0.0])
        assert np.isneginf(out[0]) and np.geterr()["divide"] == "raise"
        with pytest.raises(FloatingPointError):
            drive(quietly(maker(), all="raise"), lambda ask: [0.0])
