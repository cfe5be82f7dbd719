"""Slider-crank, scotch yoke, quick-return and straight-line linkages."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.core.errors import SpecError
from linkgen.kinematics.quickreturn import CrankShaper, Whitworth
from linkgen.kinematics.slidercrank import ScotchYoke, SliderCrank
from linkgen.kinematics.straightline import straight_line

T = np.linspace(0, 2 * math.pi, 721)


@pytest.mark.parametrize("r, rod, e", [(50, 200, 0), (50, 200, 30), (40, 90, -35)])
def test_slider_position_is_the_exact_geometry(r, rod, e):
    sc = SliderCrank(r, rod, e)
    m = sc.motion(T, 1.0)
    a = np.column_stack([r * np.cos(T), r * np.sin(T)])
    b = np.column_stack([m.x, np.full_like(m.x, e)])
    assert np.allclose(np.linalg.norm(b - a, axis=1), rod, rtol=1e-13)     # the rod keeps its length
    assert np.all(m.x > a[:, 0])                                            # slider ahead of the crank pin
    rod_dir = np.column_stack([np.cos(m.rod), np.sin(m.rod)])
    assert np.allclose(a + rod * rod_dir, b, atol=1e-10)


@pytest.mark.parametrize("e", [0.0, 25.0])
def test_slider_derivatives_match_finite_differences(e):
    sc, h, omega = SliderCrank(50, 200, e), 1e-5, 3.0
    m, mp, mm = sc.motion(T, omega), sc.motion(T + h, omega), sc.motion(T - h, omega)
    assert np.abs((mp.x - mm.x) / (2 * h) * omega - m.v).max() < 1e-6
    assert np.abs((mp.v - mm.v) / (2 * h) * omega - m.a).max() < 1e-5


def test_approximation_error_has_its_known_size():
    """x ~ r(1 - cos t) + (r^2/2L) sin^2 t drops the series term r^4 sin^4 t / (8 L^3) (then r^6 sin^6 t / 16 L^5)."""
    for r, rod in ((50, 200), (20, 200), (60, 150)):
        sc = SliderCrank(r, rod)
        d, d1, d2 = sc.approximation(T)
        err = (sc.position(0.0) - sc.position(T)) - d
        series = r**4 * np.sin(T) ** 4 / (8 * rod**3) + r**6 * np.sin(T) ** 6 / (16 * rod**5)
        assert np.abs(err - series).max() < 0.1 * np.abs(series).max() * (r / rod) ** 2
        assert np.abs(err).max() == pytest.approx(r**4 / (8 * rod**3), rel=1.5 * (r / rod) ** 2)
        # the approximate velocity and acceleration are the derivatives of the approximate displacement
        h = 1e-5
        dp, _, _ = sc.approximation(T + h)
        dm, _, _ = sc.approximation(T - h)
        assert np.abs((dp - dm) / (2 * h) - d1).max() < 1e-6
        assert np.abs((dp - 2 * d + dm) / h**2 - d2).max() < 1e-3


def test_dead_centres_stroke_and_time_ratio_of_an_offset_slider_crank():
    """Textbook: TDC at asin(e/(L+r)), BDC at pi + asin(e/(L-r)); Q = (180 + a)/(180 - a),
    a = asin(e/(L-r)) - asin(e/(L+r)); stroke = sqrt((L+r)^2 - e^2) - sqrt((L-r)^2 - e^2)."""
    r, rod, e = 50.0, 200.0, 30.0
    sc = SliderCrank(r, rod, e)
    (k1, t1, _), (k2, t2, _) = sc.dead_centres()
    assert (k1, k2) == ("TDC", "BDC")
    assert t1 == pytest.approx(math.asin(e / (rod + r)))
    assert t2 == pytest.approx(math.pi + math.asin(e / (rod - r)))
    assert sc.stroke == pytest.approx(math.sqrt(250**2 - 900) - math.sqrt(150**2 - 900))
    alpha = math.asin(e / (rod - r)) - math.asin(e / (rod + r))
    assert sc.time_ratio == pytest.approx((math.pi + alpha) / (math.pi - alpha), rel=1e-12)
    assert SliderCrank(r, rod).time_ratio == pytest.approx(1.0) and SliderCrank(r, rod).stroke == pytest.approx(2 * r)
    # at the dead centres the slider stops
    assert np.abs(sc.motion(np.array([t1, t2]), 1.0).v).max() < 1e-9


def test_rod_just_longer_than_the_crank_stays_finite():
    sc = SliderCrank(50.0, 50.0 + 1e-9)
    m = sc.motion(T, 1.0)
    assert np.isfinite(m.x).all() and np.isfinite(m.v).all() and np.isfinite(m.a).all()
    assert sc.dead_centres()[1][2] == pytest.approx(1e-9, rel=1e-6)
    assert sc.stroke == pytest.approx(100.0, abs=1e-8)


def test_short_rod_limits_the_crank_with_a_clear_error():
    sc = SliderCrank(50.0, 30.0)
    _, hi = sc.input_range()
    assert math.degrees(hi) == pytest.approx(math.degrees(math.asin(30 / 50)))
    with pytest.raises(SpecError, match="reachable crank angles"):
        sc.position(np.array([math.pi / 2]))


def test_scotch_yoke_is_simple_harmonic():
    y = ScotchYoke(40.0).motion(T, 2.0)
    assert np.allclose(y.x, 40 * (1 - np.cos(T)))
    assert np.allclose(y.a, 4.0 * (40 - y.x))                    # a = omega^2 (r - x): harmonic about mid-stroke
    assert ScotchYoke(40.0).stroke == 80.0


@pytest.mark.parametrize("mech, k", [(CrankShaper(50, 150, 300), 50 / 150), (Whitworth(100, 40, 60, 200), 40 / 100)])
def test_quick_return_time_ratio_stroke_and_derivatives(mech, k):
    """Q = (pi + 2 asin k) / (pi - 2 asin k) (Shigley/Uicker, quick-return mechanisms)."""
    assert mech.time_ratio == pytest.approx((math.pi + 2 * math.asin(k)) / (math.pi - 2 * math.asin(k)))
    ends = mech.dead_centres()
    xs = [x for _, _, x in ends]
    assert abs(xs[0] - xs[1]) == pytest.approx(mech.stroke, rel=1e-12)
    m = mech.motion(T, 1.0)
    assert m.x.max() == pytest.approx(max(xs), rel=1e-5) and m.x.min() == pytest.approx(min(xs), rel=1e-5)
    h = 1e-5
    mp, mm = mech.motion(T + h, 1.0), mech.motion(T - h, 1.0)
    assert np.abs((mp.x - mm.x) / (2 * h) - m.v).max() < 1e-5 * max(1.0, np.abs(m.v).max())
    assert np.abs((mp.v - mm.v) / (2 * h) - m.a).max() < 1e-5 * max(1.0, np.abs(m.a).max())
    # the working stroke (the ram's slow way) takes the longer crank travel
    t_end = sorted(t % (2 * math.pi) for _, t, _ in ends)
    travel = t_end[1] - t_end[0]
    assert max(travel, 2 * math.pi - travel) / min(travel, 2 * math.pi - travel) == pytest.approx(mech.time_ratio)


def test_quick_return_refuses_the_other_inversion():
    with pytest.raises(SpecError, match="whitworth"):
        CrankShaper(100, 50, 200)
    with pytest.raises(SpecError, match="crank-shaper"):
        Whitworth(50, 100, 60, 200)


@pytest.mark.parametrize("kind, limit", [("chebyshev", 2e-3), ("hoekens", 2e-3), ("roberts", 1.2e-3), ("watt", 4e-4)])
def test_straight_line_linkages(kind, limit):
    one, ten = straight_line(kind, 1.0), straight_line(kind, 10.0)
    s1, s10 = one.straightness(), ten.straightness()
    assert s1.error_mm / s1.stroke_mm < limit
    assert s10.error_mm == pytest.approx(10 * s1.error_mm, rel=1e-9)          # scales with the size
    assert math.dist(s10.start, s10.end) == pytest.approx(s10.stroke_mm, rel=1e-2)


def test_chebyshev_tracing_point_runs_level_at_the_height_of_the_mid_position():
    """Chebyshev's lambda: the midpoint of the coupler moves (almost) parallel to the ground line."""
    s = straight_line("chebyshev", 1.0).straightness()
    assert abs(s.start[1] - s.end[1]) < 5e-3
