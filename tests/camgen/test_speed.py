"""The vectorised analysis (every peak from one dense evaluation of all segments and one refinement round) against a
brute force: a million points over the cycle, then the best one refined locally on ever finer grids; for every law,
every follower and a plate cam, both senses of rotation. No test here asserts a time."""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from camgen.analysis import analyze, face_extent
from camgen.flat import build_cam
from camgen.core.spec import apply_overrides
from camgen import numeric
from camgen.laws import make_law
from camgen.numeric import piecewise_maxima
from camgen.program import build_program
from camgen.spec import validate_spec
from tests.conftest import RDRD

#: points of the brute force's first grid over the whole cycle (spread over the smooth pieces by their angle)
POINTS = 1_000_000
LAWS = {
    "uniform": {}, "modified-uniform": {}, "modified-uniform/parabolic": {"blend": 0.1, "blend_law": "parabolic"},
    "modified-uniform/drafted": {"form": "drafted"}, "parabolic": {}, "parabolic/2.5": {"ratio": 2.5},
    "harmonic": {}, "cycloidal": {}, "polynomial-345": {}, "polynomial-4567": {}, "modified-trapezoid": {},
    "modified-sine": {}, "double-harmonic": {},
    "polynomial": {"conditions": [[0, 0, 0], [0, 1, 0], [0, 2, 0], [1, 0, 1], [1, 1, 0], [1, 2, 0], [0.5, 0, 0.4]]},
    "spline": {"points": [[0, 0], [0.3, 0.2], [0.6, 0.7], [1, 1]]},
}
FOLLOWERS = {
    "translating-roller": {"type": "translating-roller", "roller_radius": 10.0, "offset": 5.0},
    "knife-edge": {"type": "knife-edge", "offset": -3.0},
    "translating-flat": {"type": "translating-flat", "face_margin": 2.0},
    "oscillating-roller": {"type": "oscillating-roller", "roller_radius": 8.0, "pivot_distance": 110.0,
                           "arm_length": 90.0},
    "oscillating-flat": {"type": "oscillating-flat", "pivot_distance": 120.0},
    "plate": {"type": "translating-roller", "roller_radius": 8.0},
}


def _spec(law: str, follower: str, rotation: str):
    raw = copy.deepcopy(RDRD)
    raw["follower"] = dict(FOLLOWERS[follower])
    raw["cam"].update(rotation=rotation, allow_undercut=True)
    if "flat" in follower:
        raw["cam"]["base_radius"] = 60.0
    if follower == "plate":
        raw["cam"] = {"kind": "plate", "travel": 200.0, "base_radius": 20.0, "thickness": 6.0}
    lift = 15.0 if follower.startswith("oscillating") else 20.0
    name, _, _ = law.partition("/")
    for i, angle in ((0, 120.0), (2, 100.0)):
        raw["motion"][i] = {"type": raw["motion"][i]["type"], "law": name, "lift": lift, "angle": angle,
                            **copy.deepcopy(LAWS[law])}
    raw["motion"][3]["angle"] = 80.0
    return validate_spec(apply_overrides(raw, []))


def _brute(cam, *quantities) -> list[tuple[float, float]]:
    """Largest value of each ``quantity(pitch geometry)`` and where (degrees): ~POINTS points spread over every
    smooth piece of every segment (ends included, as one-sided limits), then the best refined on grids of 2001 points
    over its two neighbouring cells, four times (each 1000 times finer)."""
    pieces = [(seg, a, b) for seg in cam.program.segments for a, b in seg.pieces()]
    total = sum((b - a) * seg.beta for seg, a, b in pieces)

    def values(seg, v):
        theta, motion = seg.at_law(v)
        g = cam.follower.pitch(theta, motion)
        return np.stack([q(g) for q in quantities])

    best = [(-math.inf, None, None)] * len(quantities)
    for seg, a, b in pieces:
        v = np.linspace(a, b, max(3, int(POINTS * (b - a) * seg.beta / total)))
        for k, y in enumerate(values(seg, v)):
            i = int(np.argmax(y))
            if y[i] > best[k][0]:
                best[k] = (float(y[i]), seg, (v[max(i - 1, 0)], v[min(i + 1, len(v) - 1)], float(v[i])))
    out = []
    for k, (value, seg, (lo, hi, at)) in enumerate(best):
        for _ in range(4):
            v = np.linspace(lo, hi, 2001)
            y = values(seg, v)[k]
            i = int(np.argmax(y))
            if y[i] >= value:
                value, at = float(y[i]), float(v[i])
            lo, hi = v[max(i - 1, 0)], v[min(i + 1, len(v) - 1)]
        out.append((value, math.degrees(float(seg.angle(at))) % 360.0))
    return out


def _close(ours: float, brute: float, scale: float, rel: float = 1e-9) -> bool:
    return abs(ours - brute) <= rel * max(abs(brute), scale)


def _at_value(cam, quantity, at_deg: float) -> float:
    """``quantity`` at ``at_deg``: the largest of its values on the segments meeting there, there and 1e-12 radians
    either side (its one-sided limits where it jumps)."""
    out = -math.inf
    for i, seg in enumerate(cam.program.segments):
        for turn in (0.0, 2 * math.pi, -2 * math.pi):
            theta = math.radians(at_deg) + turn + np.array([-1e-12, 0.0, 1e-12])
            theta = np.clip(theta[(theta >= seg.start - 1e-12) & (theta <= seg.end + 1e-12)], seg.start, seg.end)
            if theta.size:
                out = max(out, float(quantity(cam.segment_pitch(i, theta)).max()))
    return out


#: every law with the offset roller in both senses; every follower (and a plate cam) with a smooth law, one whose
#: acceleration jumps inside it and one whose velocity jumps at its ends
CASES = sorted({(law, "translating-roller", rotation) for law in LAWS for rotation in ("ccw", "cw")}
               | {(law, follower, rotation) for law in ("cycloidal", "modified-uniform/parabolic", "uniform")
                  for follower in FOLLOWERS for rotation in ("ccw", "cw")
                  if not (follower == "plate" and rotation == "cw")})


def _pressure(g):
    return np.abs(g.pressure_angle)


@pytest.mark.parametrize(("law", "follower", "rotation"), CASES)
def test_peaks_against_a_brute_force(law, follower, rotation):
    """Every peak of the analysis within 1e-9 (relative) of the brute force's, and located where the quantity
    takes that value (a peak's place is only as sharp as the peak: its value is checked there)."""
    cam = build_cam(_spec(law, follower, rotation))
    a = analyze(cam)
    if cam.follower.flat:
        position = cam.follower.face_position
        cusp, far = (lambda g: -g.rho), (lambda g: -position(g))
        (pressure, _), (neg, _), (hi, _), (lo, _) = _brute(cam, _pressure, cusp, position, far)
        if not math.isinf(a.pitch_rho_min_mm):                         # no fold at a segment end
            assert _close(-a.pitch_rho_min_mm, neg, cam.base_radius)
            assert _close(_at_value(cam, cusp, a.pitch_rho_min_at_deg), neg, cam.base_radius)
        extent = face_extent(cam)
        assert _close(extent[1], hi, cam.base_radius) and _close(-extent[0], lo, cam.base_radius)
    else:
        convex, concave = (lambda g: g.kappa), (lambda g: -g.kappa)
        (pressure, _), (kmax, _), (kmin, _) = _brute(cam, _pressure, convex, concave)
        scale = 1.0 / cam.base_radius
        if a.pitch_rho_min_mm > 0:                                      # no convex corner
            assert _close(1.0 / a.pitch_rho_min_mm, kmax, scale)
            assert _close(_at_value(cam, convex, a.pitch_rho_min_at_deg), kmax, scale)
        if a.pitch_concave_rho_min_mm is None:
            assert kmin <= 1e-12 * scale
        else:
            assert _close(1.0 / a.pitch_concave_rho_min_mm, kmin, scale)
            assert _close(_at_value(cam, concave, a.concave_at_deg), kmin, scale)
    assert _close(math.radians(a.pressure_angle_max_deg), pressure, 1.0)
    assert _close(_at_value(cam, _pressure, a.pressure_angle_max_at_deg), pressure, 1.0)


def test_piecewise_maxima_on_known_functions():
    """Interior peaks, peaks at either end, a peak narrower than the grid, and equal peaks (the first taken)."""
    lo, hi = np.array([0.0, 0.0, 1.0, -1.0]), np.array([1.0, 2.0, 3.0, 1.0])

    def func(x, piece):
        return np.stack([np.where(piece == 0, np.sin(3 * x + 0.1), np.where(piece == 1, x**2, -np.cos(np.pi * x))),
                         np.exp(-((x - 0.3137) / 0.02) ** 2) * (piece == 3) + (piece == 0) * x * (1 - x)])

    at, value, _ = piecewise_maxima(func, lo, hi)
    assert at[0, 0] == pytest.approx((math.pi / 2 - 0.1) / 3, abs=1e-13) and value[0, 0] == pytest.approx(1.0)
    assert at[0, 1] == 2.0 and value[0, 1] == 4.0
    assert at[0, 2] == 1.0 and value[0, 2] == 1.0                      # equal peaks at both ends: the first
    # a peak 50 times narrower than the piece: its value exact, its place as sharp as the stencil's width allows
    assert at[1, 3] == pytest.approx(0.3137, abs=1e-7) and value[1, 3] == pytest.approx(1.0, rel=1e-15)
    assert at[1, 0] == pytest.approx(0.5, abs=1e-13) and value[1, 0] == 0.25


@pytest.mark.parametrize("reverse", [False, True])
def test_a_peak_within_the_grids_first_or_last_step(reverse):
    """A peak inside a piece's first or last grid step lifts no interior grid point above its neighbours (the end
    is the grid's highest there): the end is a candidate where the parabola through it and the next two grid points
    rises inwards, so the peak itself is found (the end's value falls 2e-4 short of it in the nearest case here). An
    end at which the function is highest, or levels off, stays the answer, at the end's own abscissa."""
    step = 1.0 / (numeric.GRID - 1)
    for peak in (0.2 * step, 0.7 * step, 1.0 - 0.5 * step, 1.0 - 0.05 * step):
        at, value, _ = piecewise_maxima(lambda x, piece, p=peak: (1.0 - 50.0 * (x - p) ** 2)[None], [0.0], [1.0],
                                        reverse=reverse)
        assert value[0, 0] == pytest.approx(1.0, abs=1e-14) and at[0, 0] == pytest.approx(peak, abs=1e-9)
    # rising to the end (no peak inside), and levelling off at it (its slope zero there: the end is the peak), as a
    # parabola, a cubic (a rise ending in a dwell), a quartic and a cosine: the end's own abscissa, never a point
    # inside the piece whose value ties with it
    for func, end in ((lambda x, piece: (x * x)[None], 2.0), (lambda x, piece: (-((x - 2.0) ** 2))[None], 2.0),
                      (lambda x, piece: (-((x - 0.5) ** 2))[None], 0.5),
                      (lambda x, piece: (5.0 - (x - 0.5) ** 3)[None], 0.5),
                      (lambda x, piece: (5.0 - (2.0 - x) ** 3)[None], 2.0),
                      (lambda x, piece: (np.cos(3.0 * (x - 0.5)) - 2.0 * (x - 0.5) ** 3)[None], 0.5),
                      (lambda x, piece: (np.cos(3.0 * (2.0 - x)) - 0.2 * (2.0 - x) ** 4)[None], 2.0)):
        at, value, _ = piecewise_maxima(func, [0.5], [2.0], reverse=reverse)
        assert at[0, 0] == end and value[0, 0] == func(np.array([end]), None)[0, 0]


def test_a_rise_into_a_dwell_peaks_at_its_end():
    """A rise's lift is highest at its end, where it levels off into the dwell (s = h - k (1 - u)^3 for the
    modified sine): the search reports the end itself, 120 degrees, for every law, not a point 1e-4 degrees before
    it whose lift ties with it."""
    for law in ("cycloidal", "modified-sine", "polynomial-345", "polynomial-4567"):
        program = build_program([("rise", 120.0, 20.0, make_law(law)), ("dwell", 60.0, 0.0, None),
                                 ("return", 120.0, 20.0, make_law(law)), ("dwell", 60.0, 0.0, None)])
        (lift, at), (square, square_at) = program.maxima(lambda theta, motion, index: np.stack([motion[0],
                                                                                               motion[0] ** 2]))
        assert (lift, square) == (20.0, 400.0) and at == square_at == pytest.approx(120.0, abs=1e-12)


def test_a_curvature_peak_just_inside_a_piece_against_the_brute_force():
    """A cam whose pitch curve is most sharply curved 0.11 degrees into the middle piece of its modified-sine
    return, within that piece's first grid step (its piece is 58.5 degrees wide): found to 1e-9 of the brute
    force's (an end's value, its piece's start, fell 7e-6 short of it)."""
    raw = copy.deepcopy(RDRD)
    raw["follower"] = {"type": "translating-roller", "roller_radius": 10.0, "offset": 5.0}
    raw["cam"].update(base_radius=60.0, rotation="ccw")
    raw["motion"] = [{"type": "rise", "law": "harmonic", "lift": 28.0, "angle": 107.0},
                     {"type": "dwell", "angle": 115.0},
                     {"type": "return", "law": "modified-sine", "lift": 28.0, "angle": 78.0},
                     {"type": "dwell", "angle": 60.0}]
    cam = build_cam(validate_spec(apply_overrides(raw, [])))
    a = analyze(cam)
    ((kmax, at),) = _brute(cam, lambda g: g.kappa)
    start = 222.0 + 78.0 / 8                                            # the piece's start: 231.75 degrees
    assert 0.0 < at - start < 78.0 * 0.75 / (numeric.GRID - 1)
    assert _close(1.0 / a.pitch_rho_min_mm, kmax, 1.0 / cam.base_radius)
    assert a.pitch_rho_min_at_deg == pytest.approx(at, abs=1e-5)


@pytest.mark.parametrize("reverse", [False, True])
def test_equal_peaks_inside_a_piece(reverse):
    """Two equal peaks on one piece: the first from the low end, or from the high end where the piece runs
    backwards (a return's law runs against the cam angle)."""
    at, value, _ = piecewise_maxima(lambda x, piece: np.sin(4 * np.pi * x)[None], [0.0], [1.0], reverse=reverse)
    assert at[0, 0] == pytest.approx(0.625 if reverse else 0.125, abs=1e-12) and value[0, 0] == pytest.approx(1.0)


def test_flat_rows_are_those_whose_range_is_within_the_tie():
    """The rows constant within the tie of their function's magnitude: constant rows and signed zeros, rows whose
    spread is half or twice the tie, a row whose ends are equal and whose middle is not, and the same rows as a
    second function a thousand times smaller (its own magnitude, so the same rows)."""
    n, tie = 129, numeric.TIE
    wave = np.sin(np.linspace(0.0, np.pi, n))
    bump = np.full(n, 3.0)
    bump[n // 2] += 6.0 * tie
    rows = [np.zeros(n), np.full(n, -0.0), np.full(n, 3.0), 3.0 + 0.5 * 3.0 * tie * wave, 3.0 + 2.0 * 3.0 * tie * wave,
            bump, 3.0 + wave]
    y = np.array(rows + [row * 1e-3 for row in rows])
    count = len(rows)
    magnitude = [4.0, 4.0e-3]                           # each function's largest |value|: 3 + the sine's 1
    flat = [0, 1, 2, 3]
    assert numeric._flat_rows(y, magnitude, count) == flat + [count + r for r in flat]


def test_the_quartic_vertex_has_no_maximum_where_a_step_divides_by_zero():
    """A flat window (no parabola) or a Newton step with a zero slope's derivative: no maximum, as the arrays' NaN
    and infinities gave; a peak inside the window: the quartic's."""
    a = np.array([[0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 1.0], [0.0, -1.0, 0.0, 0.0], [0.3, -1.0, 0.01, -0.02]])
    flat, step, inside, t = numeric._vertex(*a.T, -2.0, 2.0)
    assert np.isnan(flat) and np.isnan(step) and inside == 0.0
    assert abs(0.3 - 2.0 * t + 0.03 * t**2 - 0.08 * t**3) < 1e-15
    assert np.isnan(numeric._vertex(*a[3:].T, -2.0, 0.1)[0])                 # its peak beyond the window
    alone = [numeric._vertex(*r[:, None], -2.0, 2.0)[0] for r in a]          # all at once: each row as it is alone
    assert np.array_equal(numeric._vertex(*a.T, -2.0, 2.0), alone, equal_nan=True)
    assert numeric._breadth(1.0, 0.0, 0.01, 0.5) == 0.5 and numeric._breadth(-0.0, 0.0, 0.01, 0.5) == 0.5


def test_the_quartic_through_a_window_passes_through_its_values():
    """The coefficients of one window (the vector kernel) and of many give quartics through the windows' values."""
    rng = np.random.default_rng(16)
    for m in (1, 2, 6, 37):
        windows = rng.standard_normal((m, 5)) * 10.0 ** rng.uniform(-6, 6, (m, 1))
        got = np.array(numeric._coefficients(windows))
        t = np.arange(-2.0, 3.0)
        fitted = windows[:, 2:3] + sum(got[:, i:i + 1] * t ** (i + 1) for i in range(4))
        assert np.allclose(fitted, windows, rtol=1e-12, atol=1e-12 * np.abs(windows).max())


def test_the_first_ask_is_made_once_and_read_only():
    """A program's pieces are mostly [0, 1]: the grid asked first is made once for a set of pieces and steady
    flags, and nobody can change it in place."""
    def first(steady):
        return next(numeric.maxima_steps([0.0, 0.0, 0.0], [1.0, 1.0, 1.0], steady=steady))

    x, piece = first([False, True, False])
    again, _ = first([False, True, False])
    assert again is x and not x.flags.writeable and not piece.flags.writeable
    assert x.size == 2 * numeric.GRID + 1 and piece.tolist() == [0] * numeric.GRID + [2] * numeric.GRID + [1]
    assert first(False)[0].size == 3 * numeric.GRID
    with pytest.raises(ValueError, match="5 a piece"):
        next(numeric.maxima_steps([0.0], [1.0], n=4))


def test_pieces_given_as_numbers_find_the_plan_an_array_finds():
    """Pieces' ends given as a list, a tuple or an array look up one plan, -0.0 apart from 0.0, and a constant
    function's maxima stand at the low ends with their signs."""
    x, _ = next(numeric.maxima_steps((0.0, -0.0), (1.0, 1.0)))
    assert x is next(numeric.maxima_steps(np.array([0.0, -0.0]), [1.0, 1.0]))[0]
    assert x is not next(numeric.maxima_steps((0.0, 0.0), (1.0, 1.0)))[0]
    steps = numeric.maxima_steps((0.0, -0.0), (1.0, 1.0))
    at, _, _ = numeric.drive(steps, lambda ask: np.full((1, ask[0].size), 2.0))      # constant: the low ends
    assert [math.copysign(1.0, a) for a in at[0]] == [1.0, -1.0]


def test_a_search_asks_and_reads_answers_in_its_callers_form():
    """A search told how its caller takes points and gives answers asks in that form and reads the answers so,
    finding what it finds asked plainly, to the bit (two pieces, two functions, a narrow peak refined twice)."""
    def f(x, piece):
        return np.array([np.sin(3 * x + piece), np.exp(-((x - 0.3) / 0.02) ** 2) + 0.1 * piece])

    plain = numeric.drive(numeric.maxima_steps([0.0, 0.5], [1.0, 2.0]), lambda ask: f(*ask))
    asks = []
    steps = numeric.maxima_steps([0.0, 0.5], [1.0, 2.0], ask=lambda x, piece: {"x": x, "piece": piece},
                                 answer=lambda sent: sent["rows"])
    told = numeric.drive(steps, lambda ask: asks.append(ask) or {"rows": f(ask["x"], ask["piece"])})
    assert repr(told) == repr(plain) and len(asks) == 3 and all(set(ask) == {"x", "piece"} for ask in asks)


def test_a_constant_is_a_read_only_0d_float64_of_its_value():
    """numeric.constant of a float, an int, a numpy float and a signed zero: a 0-d float64 array holding the value's
    bits, which nothing can write into."""
    for value in (0.5, 3, np.float64(-2.25), -0.0, 1e308):
        c = numeric.constant(value)
        assert c.shape == () and c.dtype == np.float64 and c.tobytes() == np.array(value, dtype=float).tobytes()
        with pytest.raises(ValueError, match="read-only"):
            np.add(c, 1.0, out=c)


def test_values_not_finite_are_refused():
    """On the grid, or near a peak (the refinement's points, off the grid's k / 128)."""
    with pytest.raises(FloatingPointError, match="search grid"), np.errstate(divide="ignore"):
        piecewise_maxima(lambda x, piece: np.log(x)[None], [0.0], [1.0])

    def func(x, piece):
        off_grid = (np.abs(x - 0.3) < 0.01) & (x * 128 != np.round(x * 128))
        return np.where(off_grid, np.nan, np.exp(-((x - 0.3) / 0.05) ** 2))[None]

    with pytest.raises(FloatingPointError, match="near a peak"):
        piecewise_maxima(func, [0.0], [1.0])


def test_a_scale_for_all_functions_or_one_each():
    """``scale`` one for all (a number or one element) or one a function; each magnitude is the larger of its scale
    and the function's largest |value| on the grid."""
    def func(x, piece):
        return np.stack([np.sin(x), np.cos(x), x])

    for scale, expected in ((5.0, [5.0] * 3), ([5.0], [5.0] * 3), ([0.5, 1.5, 0.1], [1.0, 1.5, 2.0])):
        magnitude = piecewise_maxima(func, [0.0, 1.0], [1.0, 2.0], scale=scale)[2]
        assert magnitude.tolist() == pytest.approx(expected, rel=1e-6)         # sin's largest on the grid: ~1
    with pytest.raises(ValueError):
        piecewise_maxima(func, [0.0, 1.0], [1.0, 2.0], scale=[0.5, 1.5])


def test_flags_for_all_pieces_or_one_each():
    """``reverse`` and ``steady`` one for all (a bool or one element) or one a piece, as numpy broadcast them."""
    assert numeric._flags(True, 3) == numeric._flags([True], 3) == [True] * 3
    assert numeric._flags(np.array([1, 0, 1]), 3) == [True, False, True]
    with pytest.raises(ValueError):
        numeric._flags([True, False], 3)
