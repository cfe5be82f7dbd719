"""Cam design's per-segment work done in one pass over all segments, on grids sized by each segment's angle (issue
38 item 2): the one-pass table, pieces and jumps against the per-segment code they replace (kept here as the
reference) and each law's closed form; the search on grids of 33 to 129 points against the search on 129 points
everywhere; short (down to 1e-9 degrees), long and exact-zero segments; and the outline against the exact
surface."""
from __future__ import annotations

import math
import random

import numpy as np
import pytest

from camgen.api import design_cam
from camgen.bench import BASE, program_template
from camgen.flat import build_cam
from camgen.laws import make_law
from camgen.numeric import GRID, LEAST_GRID, TIE, drive, grid_counts, maxima_steps
from camgen.program import JUMP_TOL, Jump, build_program
from camgen.spec import validate_spec
from camgen.surface import surface_deviation

#: laws without parameters, one with (parabolic's split), and laws of several smooth pieces (breakpoints inside)
LAWS = ["cycloidal", "harmonic", "polynomial-345", "polynomial-4567", "modified-sine", "modified-trapezoid",
        "double-harmonic", "parabolic"]

#: closed forms of f, f', f'', f''' (Norton's): the independent evaluation of the laws
CLOSED = {
    "cycloidal": lambda u: (u - np.sin(2 * np.pi * u) / (2 * np.pi), 1 - np.cos(2 * np.pi * u),
                            2 * np.pi * np.sin(2 * np.pi * u), 4 * np.pi**2 * np.cos(2 * np.pi * u)),
    "harmonic": lambda u: ((1 - np.cos(np.pi * u)) / 2, np.pi / 2 * np.sin(np.pi * u),
                           np.pi**2 / 2 * np.cos(np.pi * u), -np.pi**3 / 2 * np.sin(np.pi * u)),
    "polynomial-345": lambda u: (10 * u**3 - 15 * u**4 + 6 * u**5, 30 * u**2 - 60 * u**3 + 30 * u**4,
                                 60 * u - 180 * u**2 + 120 * u**3, 60 - 360 * u + 360 * u**2),
    "polynomial-4567": lambda u: (35 * u**4 - 84 * u**5 + 70 * u**6 - 20 * u**7,
                                  140 * u**3 - 420 * u**4 + 420 * u**5 - 140 * u**6,
                                  420 * u**2 - 1680 * u**3 + 2100 * u**4 - 840 * u**5,
                                  840 * u - 5040 * u**2 + 8400 * u**3 - 4200 * u**4),
}


def _random_steps(n: int, seed: int, laws: list[str] = LAWS) -> list:
    """n segments (rise, dwell, return, dwell, ...; a lone segment a dwell) of random angles adding up to 360
    degrees, random laws and lifts that balance."""
    rng = random.Random(seed)
    angles = [rng.uniform(0.2, 3.0) for _ in range(n)]
    total = sum(angles)
    angles = [360.0 * a / total for a in angles]
    angles[-1] = 360.0 - sum(angles[:-1])
    steps, up = [], []
    kinds = ["dwell"] if n == 1 else [("rise", "dwell", "return", "dwell")[i % 4] for i in range(n)]
    if n > 1 and n % 4 in (1, 2):                      # a last rise without its return: a dwell instead
        kinds[4 * (n // 4)] = "dwell"
    for kind, angle in zip(kinds, angles, strict=True):
        if kind == "dwell":
            steps.append(("dwell", angle, 0.0, None))
            continue
        name = rng.choice(laws)
        law = make_law(name, ratio=rng.uniform(0.5, 2.0)) if name == "parabolic" else make_law(name)
        if kind == "rise":
            up.append(rng.uniform(0.1, 5.0))
            steps.append(("rise", angle, up[-1], law))
        else:
            steps.append(("return", angle, up.pop(), law))
    return steps


def _reference_jumps(program) -> list[Jump]:
    """The per-segment jumps the one pass replaced: each boundary compared in a Python loop, each segment's inner
    limits from :meth:`Segment.inner_limits`, by angle then order."""
    found = []
    segments = program.segments
    theta, motion = program.boundaries
    n = len(segments)
    for i in range(n):
        own, other = segments[i].scale(), segments[(i + 1) % n].scale()
        for k in (1, 2, 3):
            step = motion[k, n + i] - motion[k, i]
            if abs(step) > JUMP_TOL * max(own[k], other[k], 1e-300):
                found.append(Jump(round(math.degrees(theta[i]), 9) % 360.0, k, float(step), False))
    for seg in segments:
        scale = seg.scale()
        for t, lo, hi in seg.inner_limits():
            for k in (1, 2, 3):
                step = hi[k] - lo[k]
                if abs(step) > JUMP_TOL * max(scale[k], 1e-300):
                    found.append(Jump(round(math.degrees(t), 9) % 360.0, k, float(step), True))
    return sorted(found, key=lambda j: (j.at_deg, j.order))


@pytest.mark.parametrize("n, seed", [(1, 0), (2, 1), (5, 2), (17, 3), (64, 4), (257, 5), (1024, 6)])
def test_the_one_pass_program_is_the_per_segment_one(n, seed):
    steps = _random_steps(n, seed)
    program = build_program(steps)
    rng = np.random.default_rng(seed)
    index = rng.integers(0, n, 4000)
    segments = program.segments
    start = np.array([s.start for s in segments])[index]
    beta = np.array([s.beta for s in segments])[index]
    theta = start + beta * rng.uniform(0.0, 1.0, index.size)
    theta[:50] = start[:50]                             # exact ends: the segment's one-sided values
    theta[50:100] = start[50:100] + beta[50:100]
    together = program.evaluate_on(index, theta)
    alone = np.stack([segments[i].evaluate(np.array([t]))[:, 0] for i, t in zip(index, theta, strict=True)], axis=1)
    np.testing.assert_allclose(together, alone, rtol=1e-12, atol=1e-12 * np.abs(alone).max())
    # the pieces as each segment's own, and the jumps as the per-segment loops find them
    owner, lo, hi, *_ = program._pieces
    pieces = [(i, a, b) for i, s in enumerate(segments) for a, b in s.pieces()]
    mine = list(zip(range(len(segments)) if owner is None else owner.tolist(), np.asarray(lo).tolist(),
                    np.asarray(hi).tolist(), strict=True))
    assert mine == pieces
    assert program.jumps() == _reference_jumps(program)


@pytest.mark.parametrize("name", sorted(CLOSED))
def test_each_law_in_a_program_is_its_closed_form(name):
    # a rise then a return of the law and two dwells: s, s', s'', s''' at random angles against h f(u), (h / beta)
    # f'(u), ..., the return's mirrored (s = h f(1 - u), odd derivatives negated)
    h, beta = 7.0, math.radians(37.0)
    program = build_program([("rise", 37.0, h, make_law(name)), ("dwell", 100.0, 0.0, None),
                             ("return", 37.0, h, make_law(name)), ("dwell", 186.0, 0.0, None)])
    u = np.random.default_rng(1).uniform(0.0, 1.0, 500)
    rise = program.evaluate_on(np.zeros(u.size, dtype=np.intp), beta * u)
    back = program.evaluate_on(np.full(u.size, 2, dtype=np.intp), math.radians(137.0) + beta * u)
    f = np.array(CLOSED[name](u))
    g = np.array(CLOSED[name](1.0 - u))
    scale = h / beta ** np.arange(4.0)[:, None]
    np.testing.assert_allclose(rise, scale * f, rtol=1e-12, atol=1e-12 * np.abs(scale * f).max())
    np.testing.assert_allclose(back, scale * g * np.array([1, -1, 1, -1])[:, None], rtol=1e-12,
                               atol=1e-12 * np.abs(scale * g).max())


def test_grid_counts_take_the_fewest_points_that_span_the_step():
    deg = np.radians([1e-9, 0.35, 5.6, 5.7, 11.25, 11.3, 22.5, 22.6, 45.0, 45.1, 90.0, 360.0])
    assert grid_counts(deg).tolist() == [33, 33, 33, 33, 33, 65, 65, 129, 129, 129, 129, 129]
    # each count's step is within the bound unless the count is GRID's; none fewer would be
    counts = grid_counts(deg)
    step = deg / (counts - 1)
    bound = (math.pi / 4) / (GRID - 1)
    assert ((step <= bound * (1 + 1e-12)) | (counts == GRID)).all()
    fewer = (counts - 1) // 2
    assert ((deg / fewer > bound) | (counts == LEAST_GRID)).all()
    assert grid_counts([0.0]).tolist() == [LEAST_GRID]


def _search(program, sizes):
    """The largest s', s'' and -s'' over the program, searched on grids of ``sizes`` points a piece."""
    owner, lo, hi, _, back, _ = program._pieces
    table = program._table
    segment = (lambda piece: piece) if owner is None else (lambda piece: owner[piece])

    def values(ask):
        v, piece = ask
        m = table.at_law(segment(piece), v)
        return np.array([m[1], m[2], -m[2]])

    _, value, _ = drive(maxima_steps(lo, hi, reverse=back, n=sizes), values)
    return np.array(value).max(axis=1)


@pytest.mark.parametrize("n, seed", [(4, 7), (16, 8), (64, 9), (256, 10)])
def test_the_sized_grids_find_the_peaks_of_129_points_everywhere(n, seed):
    # every piece's largest velocity and acceleration (both signs): the same to 1e-12 of their size on grids of 33
    # to 129 points as on 129 points a piece
    program = build_program(_random_steps(n, seed))
    sized = _search(program, program._grids)
    dense = _search(program, GRID)
    np.testing.assert_allclose(sized, dense, rtol=1e-12)
    # and the cycloidal peaks at their closed forms: s' = 2 h / beta, s'' = 2 pi h / beta^2
    cyc = build_program(_random_steps(n, seed, ["cycloidal"]))
    h = np.array([s.lift for s in cyc.segments])
    beta = np.array([s.beta for s in cyc.segments])
    top = _search(cyc, cyc._grids)
    assert top[0] == pytest.approx((2 * h / beta).max(), rel=1e-12)
    assert top[1] == pytest.approx((2 * math.pi * h / beta**2).max(), rel=1e-12)


def _program_spec(motion):
    return validate_spec({**BASE, "motion": motion})


def _outline_within(design, tolerance=0.01):
    """The exported outline's vertices and chord midpoints on the exact surface within ``tolerance`` mm."""
    ring = np.asarray(design.outline.contour.flatten(tolerance / 10))
    mid = 0.5 * (ring + np.roll(ring, -1, axis=0))
    for pts in (ring, mid):
        assert np.abs(surface_deviation(design.cam, pts)).max() <= tolerance * (1 + 1e-9)


@pytest.mark.parametrize("segments", [64, 256, 1024])
def test_the_outline_of_short_segments_is_within_its_tolerance_of_the_exact_surface(segments):
    design = design_cam(program_template(segments))
    assert design.outline.max_error_mm <= 0.01
    _outline_within(design)


def test_a_tiny_a_huge_and_exact_zero_segments():
    # a 1e-9-degree rise (33 points), a 300-degree return (129), and s'' exactly 0 at the middle grid point of a
    # cycloidal rise (u = 1/2): the peaks against their closed forms, the outline against the exact surface
    tiny = 1e-9
    spec = _program_spec([
        {"type": "rise", "law": "cycloidal", "lift": 1e-24, "angle": tiny},
        {"type": "rise", "law": "cycloidal", "lift": 3.0, "angle": 20.0},
        {"type": "dwell", "angle": 40.0 - tiny},
        {"type": "return", "law": "cycloidal", "lift": 3.0 + 1e-24, "angle": 300.0}])
    cam = build_cam(spec)
    assert cam.program._grids.tolist() == [33, 65, 129, 129]
    design = design_cam(spec)
    assert design.outline.max_error_mm <= 0.01
    _outline_within(design)
    # the cycloidal rise's velocity peaks at u = 1/2 (a grid point of every grid: its acceleration exactly 0 there)
    program = cam.program
    v = program.evaluate_on(np.array([1]), np.array([program.segments[1].start + program.segments[1].beta / 2]))
    assert v[2, 0] == pytest.approx(0.0, abs=1e-12 * 3.0 / program.segments[1].beta ** 2)
    top = _search(program, program._grids)
    seg = program.segments[1]
    assert top[0] == pytest.approx(2 * 3.0 / seg.beta, rel=1e-12)
    assert top[1] == pytest.approx(2 * math.pi * 3.0 / seg.beta**2, rel=1e-12)
    # the tiny segment's own: 2 h / beta of 1e-24 mm over 1e-9 degrees, found on its 33 points
    _, lo, hi, _, back, _ = program._pieces
    table = program._table

    def velocity(ask):
        v, piece = ask
        return table.at_law(piece, v)[1:2]

    _, value, _ = drive(maxima_steps(lo, hi, reverse=back, n=program._grids), velocity)
    assert value[0][0] == pytest.approx(2e-24 / math.radians(tiny), rel=1e-9)
    assert all(math.isfinite(x) for x in value[0])


def test_the_search_ties_equal_peaks_to_the_first_on_sized_grids():
    # the bench programs repeat rise, dwell, return, dwell: of equal peaks (within TIE) the first, in the first four
    for n in (64, 1024):
        d = design_cam(program_template(n))
        beta = 360.0 / n
        for at in (d.analysis.pressure_angle_max_at_deg, d.analysis.pitch_rho_min_at_deg):
            assert 0.0 <= at < 4 * beta * (1 + TIE)


def test_equal_laws_of_a_template_are_made_once_and_evaluate_as_their_own():
    # 512 cycloidal rises and returns: one law object; parabolic rises of two ratios: one each; a polynomial of
    # conditions (a list): its own for each segment. The motion is the same as with a law made for each segment.
    program = build_cam(program_template(1024)).program
    assert len({id(s.law) for s in program.segments if s.law is not None}) == 1
    conditions = [[0, 0, 0], [0, 1, 0], [1, 0, 1], [1, 1, 0]]
    motion = []
    for ratio in (1.0, 1.5, 1.0, 1.5):
        motion += [{"type": "rise", "law": "parabolic", "ratio": ratio, "lift": 2.0, "angle": 20.0},
                   {"type": "return", "law": "polynomial", "conditions": conditions, "lift": 2.0, "angle": 20.0},
                   {"type": "dwell", "angle": 50.0}]
    program = build_cam(_program_spec(motion)).program
    rises = [s.law for s in program.segments if s.kind == "rise"]
    returns = [s.law for s in program.segments if s.kind == "return"]
    assert rises[0] is rises[2] and rises[1] is rises[3] and rises[0] is not rises[1]
    assert len({id(law) for law in returns}) == 4
    own = build_program([(s.kind, math.degrees(s.beta), s.lift,
                          None if s.law is None else make_law(s.law.name, **_parameters(s.law)))
                         for s in program.segments])
    theta = np.linspace(0.0, 2 * math.pi, 3001)
    np.testing.assert_array_equal(program.evaluate(theta), own.evaluate(theta))


def _parameters(law) -> dict:
    """A law's parameters as :func:`make_law` takes them again (a parabolic's ratio; a polynomial's conditions)."""
    if law.name == "parabolic":
        return {"ratio": law.ratio}
    if law.name == "polynomial":
        return {"conditions": [[0, 0, 0], [0, 1, 0], [1, 0, 1], [1, 1, 0]]}
    return {}
