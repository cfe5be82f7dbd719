"""Any planar linkage, dyad by dyad (issue 12): kernels against independent intersections, velocities and
accelerations against finite differences of positions, the dedicated mechanisms reproduced, mobility errors,
higher-class groups refused, branches carried through change points."""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from camgen.core.errors import SpecError
from linkgen.kinematics import dyads, equivalents, motion
from linkgen.kinematics.fourbar import FourBar
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.quickreturn import CrankShaper, Whitworth
from linkgen.kinematics.slidercrank import ScotchYoke, SliderCrank
from linkgen.kinematics.straightline import straight_line
from linkgen.kinematics.structure import GroupStep, Input, Slider, make_structure, plan

RNG = np.random.default_rng(12)
CRANK = (Input("crank", "crank", "O"),)


# ---------------------------------------------------------------------- kernels


def test_circle_circle_against_the_textbook_construction():
    p1, p2 = RNG.uniform(-50, 50, (200, 2)), RNG.uniform(-50, 50, (200, 2))
    d = np.hypot(*(p2 - p1).T)
    r1 = d * RNG.uniform(0.3, 0.9, 200)
    r2 = d * RNG.uniform(0.3, 0.9, 200)
    r2 = np.maximum(r2, d - r1 + 1e-3 * d)
    for k in range(200):
        j, margin = dyads.circle_circle(p1[k:k + 1], r1[k], p2[k:k + 1], r2[k], 1.0)
        # a = (d^2 + r1^2 - r2^2) / 2d along P1P2, h = sqrt(r1^2 - a^2) to its left
        a = (d[k] ** 2 + r1[k] ** 2 - r2[k] ** 2) / (2 * d[k])
        h = math.sqrt(r1[k] ** 2 - a * a)
        e = (p2[k] - p1[k]) / d[k]
        ref = p1[k] + a * e + h * np.array([-e[1], e[0]])
        assert np.allclose(j[0], ref, atol=1e-10)
        gamma = math.acos((r1[k] ** 2 + r2[k] ** 2 - d[k] ** 2) / (2 * r1[k] * r2[k]))
        assert margin[0] == pytest.approx(math.sin(gamma), abs=1e-12)


def test_circle_circle_beyond_reach_has_a_negative_margin_and_touching_is_zero():
    p1, p2 = np.array([[0.0, 0.0]]), np.array([[10.0, 0.0]])
    assert dyads.circle_circle(p1, 4.0, p2, 5.0, 1.0)[1][0] < 0
    j, m = dyads.circle_circle(p1, 4.0, p2, 6.0, 1.0)
    assert m[0] == 0.0 and np.allclose(j[0], [4.0, 0.0])


def test_circle_line_and_line_line_against_quadratic_and_linear_solves():
    for _ in range(100):
        p, c = RNG.uniform(-20, 20, 2), RNG.uniform(-20, 20, 2)
        ang = RNG.uniform(0, 2 * math.pi)
        u = np.array([math.cos(ang), math.sin(ang)])
        h = abs(u[0] * (c - p)[1] - u[1] * (c - p)[0])
        r = h * RNG.uniform(1.05, 3.0)
        # |c + t u - p|^2 = r^2: t^2 + 2 t u.(c - p) + |c - p|^2 - r^2 = 0, the larger root
        b, cc = 2 * u @ (c - p), (c - p) @ (c - p) - r * r
        t = (-b + math.sqrt(b * b - 4 * cc)) / 2
        j, margin = dyads.circle_line(p[None], r, c[None], u[None], 1.0)
        assert np.allclose(j[0], c + t * u, atol=1e-10)
        assert margin[0] == pytest.approx(math.sqrt(1 - (h / r) ** 2), abs=1e-12)
        ang2 = ang + RNG.uniform(0.2, 2.9)
        u2 = np.array([math.cos(ang2), math.sin(ang2)])
        c2 = RNG.uniform(-20, 20, 2)
        x, margin = dyads.line_line(c[None], u[None], c2[None], u2[None])
        ts = np.linalg.solve(np.column_stack([u, -u2]), c2 - c)
        assert np.allclose(x[0], c + ts[0] * u, atol=1e-10)
        assert margin[0] == pytest.approx(abs(math.sin(ang2 - ang)), abs=1e-12)


# ---------------------------------------------------------------------- the dedicated mechanisms, reproduced

ANGLES = np.linspace(0, 2 * math.pi, 1441)[:-1]


@pytest.mark.parametrize("fb, theta0, assembly", [
    (FourBar(180, 80, 200, 150), 0.5, "open"),
    (FourBar(180, 80, 200, 150, 90, 0.6), 2.0, "crossed"),
    (FourBar(100, 40, 120, 90), 1.0, "open"),                 # double crank? no: crank-rocker, Grashof
    (FourBar(40, 100, 90, 120), 0.3, "open"),                 # drag link (ground shortest)
])
def test_four_bars_through_the_general_solver_agree_with_the_closed_form(fb, theta0, assembly):
    lk = Linkage.of(equivalents.fourbar(fb, theta0, assembly))
    sol = lk.solve(ANGLES)
    ref = fb.sweep(lk.unwrap(ANGLES), assembly)
    assert np.abs(sol.points["B"] - ref.b).max() < 1e-9
    assert np.abs(sol.points["A"] - ref.a).max() < 1e-9
    w3, w4 = fb.velocities(ref, 1.0)
    a3, a4 = fb.accelerations(ref, 1.0)
    assert np.allclose(sol.omegas["coupler"], w3, rtol=0, atol=1e-10)
    assert np.allclose(sol.omegas["rocker"], w4, rtol=0, atol=1e-10)
    assert np.allclose(sol.alphas["coupler"], a3, rtol=0, atol=1e-10)
    assert np.allclose(sol.alphas["rocker"], a4, rtol=0, atol=1e-10)
    if fb.point_distance:
        assert np.abs(sol.points["P"] - ref.point).max() < 1e-9


def test_a_non_grashof_four_bar_reaches_the_same_range_and_toggles():
    fb = FourBar(100, 70, 60, 80)
    lo, hi = fb.input_ranges()[0]
    lk = Linkage.of(equivalents.fourbar(fb, 0.5 * (lo + hi)))
    (a, b), = motion.input_ranges(lk)
    assert a == pytest.approx(lo, abs=1e-12) and b == pytest.approx(hi, abs=1e-12)
    limits = [t for t in motion.toggles(lk) if t.kind == "limit"]
    assert [t.joint for t in limits] == ["B", "B"]
    with pytest.raises(SpecError, match=r"input: input 180 degrees is out of reach; the linkage reaches "
                                        r"\[-109\.6[0-9]+, 109\.6[0-9]+\] degrees"):
        lk.solve([math.pi])


def test_time_ratio_and_swing_of_a_crank_rocker_equal_the_closed_form():
    fb = FourBar(180, 80, 200, 150)
    lk = Linkage.of(equivalents.fourbar(fb, 0.5))
    ext = motion.limit_positions(lk, "rocker", *motion.span(lk))
    assert motion.time_ratio(lk, ext) == pytest.approx(fb.time_ratio(), rel=1e-12)
    dead = {d.kind: d for d in fb.dead_centres()}
    assert sorted(e.value % (2 * math.pi) for e in ext) == pytest.approx(
        sorted(d.crank % (2 * math.pi) for d in dead.values() if d.kind in ("extended", "folded")), abs=1e-9)


@pytest.mark.parametrize("kind", ["chebyshev", "hoekens", "roberts", "watt"])
def test_straight_line_linkages_through_the_general_solver(kind):
    sl = straight_line(kind, 40.0)
    fb = sl.linkage
    ranges = fb.input_ranges()
    lo, hi = (0.0, 2 * math.pi) if ranges is None else ranges[0]
    theta0 = lo + 0.3 * (hi - lo)
    lk = Linkage.of(equivalents.fourbar(fb, theta0, sl.assembly))
    t = np.linspace(lo, hi, 721)
    if ranges is not None:
        t = t[1:-1]
    sol = lk.solve(t)
    ref = fb.sweep(lk.unwrap(t), sl.assembly)
    assert np.abs(sol.points["P"] - ref.point).max() < 1e-9


def test_slider_crank_scotch_yoke_and_quick_returns_through_the_general_solver():
    """RRP, RPP, RPR and PRP dyads, with their velocities and accelerations (Coriolis' terms included)."""
    sc = SliderCrank(50, 140, 12)
    lk = Linkage.of(equivalents.slider_crank(sc, 0.3))
    sol, m = lk.solve(ANGLES), sc.motion(lk.unwrap(ANGLES), 1.0)
    assert [s.kind for s in lk.plan.steps[1:]] == ["RRP"]
    assert np.abs(sol.points["B"][:, 0] - m.x).max() < 1e-9
    assert np.abs(sol.velocities["B"][:, 0] - m.v).max() < 1e-9
    assert np.abs(sol.accelerations["B"][:, 0] - m.a).max() < 1e-9
    sy = ScotchYoke(30)
    lk = Linkage.of(equivalents.scotch_yoke(sy, 0.3))
    sol, m = lk.solve(ANGLES), sy.motion(lk.unwrap(ANGLES), 1.0)
    assert [s.kind for s in lk.plan.steps[1:]] == ["PPR"]
    # the yoke's point sits at the crank pin's x plus three cranks: 4R - x of the dedicated form, x = R (1 - cos t)
    assert np.abs(sol.points["Y"][:, 0] - (120 - m.x)).max() < 1e-9
    assert np.abs(sol.accelerations["Y"][:, 0] + m.a).max() < 1e-9
    cs = CrankShaper(40, 100, 160)
    lk = Linkage.of(equivalents.crank_shaper(cs, 0.3))
    sol, m = lk.solve(ANGLES), cs.motion(lk.unwrap(ANGLES), 1.0)
    assert [s.kind for s in lk.plan.steps[1:]] == ["RPR", "PRP"]
    assert np.abs(sol.points["R"][:, 1] + m.x).max() < 1e-9
    assert np.abs(sol.velocities["R"][:, 1] + m.v).max() < 1e-9
    assert np.abs(sol.accelerations["R"][:, 1] + m.a).max() < 1e-9
    w = Whitworth(100, 40, 50, 180)
    lk = Linkage.of(equivalents.whitworth(w, 0.3))
    sol, m = lk.solve(ANGLES), w.motion(lk.unwrap(ANGLES), 1.0)
    assert np.abs(sol.points["D"][:, 1] - m.x).max() < 1e-9
    assert np.abs(sol.accelerations["D"][:, 1] - m.a).max() < 1e-9


# ---------------------------------------------------------------------- velocities against positions


def watt_ii() -> Linkage:
    """A Watt II six-bar: the crank-rocker O-A-B-Q, and a dyad C-D-R driven by a point C of the rocker's plate,
    its lengths chosen so that it closes over the whole crank turn."""
    fb = FourBar(180, 60, 190, 150)
    q, r = np.array([180.0, 0.0]), np.array([330.0, 60.0])
    turn = np.array([[math.cos(0.9), -math.sin(0.9)], [math.sin(0.9), math.cos(0.9)]])
    sweep = fb.sweep(np.linspace(0, 2 * math.pi, 721))
    c_path = q + 1.3 * (sweep.b - q) @ turn.T
    far = np.hypot(*(c_path - r).T).max()
    p = fb.positions([0.4])
    a, b = p.a[0], p.b[0]
    c = q + 1.3 * turn @ (b - q)
    d, _ = dyads.circle_circle(c[None], 0.7 * far, r[None], 0.6 * far, -1.0)
    pts = {"O": (0.0, 0.0), "Q": (180.0, 0.0), "R": tuple(r), "A": tuple(a), "B": tuple(b), "C": tuple(c),
           "D": tuple(d[0])}
    s = make_structure(pts, {"crank": ("O", "A"), "coupler": ("A", "B"), "rocker": ("Q", "B", "C"),
                             "link5": ("C", "D"), "output": ("R", "D")}, ("O", "Q", "R"), (), CRANK)
    return Linkage.of(s)


@pytest.mark.parametrize("make", [watt_ii, lambda: Linkage.of(equivalents.crank_shaper(CrankShaper(40, 100, 160),
                                                                                        0.3))])
def test_velocities_and_accelerations_equal_high_order_differences_of_positions(make):
    lk = make()
    lo, hi = motion.input_ranges(lk)[0] if motion.input_ranges(lk) else (0.0, 2 * math.pi)
    t = np.linspace(lo, hi, 41)[4:-4] + 0.0123
    h = 1e-4
    sol = lk.solve(t)
    stencil = [lk.solve(t + k * h) for k in (-2, -1, 1, 2)]
    for name in sol.points:
        pm2, pm1, pp1, pp2 = (s.points[name] for s in stencil)
        v = (pm2 - 8 * pm1 + 8 * pp1 - pp2) / (12 * h)                       # O(h^4)
        a = (-pm2 + 16 * pm1 - 30 * sol.points[name] + 16 * pp1 - pp2) / (12 * h * h)
        scale = 1.0 + np.abs(sol.velocities[name]).max()
        assert np.abs(sol.velocities[name] - v).max() < 1e-8 * scale, name
        assert np.abs(sol.accelerations[name] - a).max() < 1e-5 * (1 + np.abs(a).max()), name


# ---------------------------------------------------------------------- structure errors


def test_a_structure_is_refused_with_its_mobility():
    pts = {"O": (0.0, 0.0), "Q": (100.0, 0.0), "A": (50.0, 60.0)}
    with pytest.raises(SpecError, match=r"over-constrained|mobility 0"):
        Linkage.of(make_structure(pts, {"crank": ("O", "A"), "bar": ("A", "Q")}, ("O", "Q"), (), CRANK))


def test_a_two_degree_of_freedom_chain_asks_for_another_input():
    pts = {"O": (0.0, 0.0), "Q": (100.0, 0.0), "A": (20.0, 30.0), "B": (60.0, 60.0), "C": (100.0, 40.0)}
    links = {"crank": ("O", "A"), "b1": ("A", "B"), "b2": ("B", "C"), "b3": ("C", "Q")}
    with pytest.raises(SpecError, match=r"linkage: links .* are not fixed by the inputs \(mobility 2, 1 input"):
        Linkage.of(make_structure(pts, links, ("O", "Q"), (), CRANK))
    two = (Input("crank", "crank", "O"), Input("crank", "b3", "Q"))
    lk = Linkage.of(make_structure(pts, links, ("O", "Q"), (), two))
    sol = lk.solve([[lk.drawn_inputs[0] + 0.1], [lk.drawn_inputs[1] - 0.05]])
    assert math.dist(sol.points["A"][0], sol.points["B"][0]) == pytest.approx(math.dist((20, 30), (60, 60)))


def test_a_class_three_group_is_planned_as_one_group_naming_its_joints():
    """A ternary plate held by three bars, one from the crank: no dyad closes it, so it is solved as one group
    (tests/linkgen/test_groups.py checks its solution)."""
    pts = {"O": (0.0, 0.0), "G2": (120.0, 0.0), "G3": (60.0, -80.0), "A": (20.0, 15.0), "P": (40.0, 70.0),
           "Q": (90.0, 60.0), "R": (70.0, 30.0)}
    links = {"crank": ("O", "A"), "bar1": ("A", "P"), "plate": ("P", "Q", "R"), "bar2": ("G2", "Q"),
             "bar3": ("G3", "R")}
    steps = plan(make_structure(pts, links, ("O", "G2", "G3"), (), CRANK)).steps
    assert [s.joints for s in steps if isinstance(s, GroupStep)] == [("A", "G2", "G3", "P", "Q", "R")]


def test_a_paradoxical_parallelogram_with_a_third_parallel_bar_moves():
    pts = {"O": (0.0, 0.0), "Q": (100.0, 0.0), "M": (50.0, 0.0), "A": (20.0, 30.0), "B": (120.0, 30.0),
           "C": (70.0, 30.0)}
    links = {"crank": ("O", "A"), "coupler": ("A", "C", "B"), "rocker": ("Q", "B"), "extra": ("M", "C")}
    s = make_structure(pts, links, ("O", "Q", "M"), (), CRANK)
    assert s.mobility == 0
    lk = Linkage.of(s)
    assert [r.name for r in lk.plan.redundant] == ["C"]
    sol = lk.solve(np.linspace(0, 2 * math.pi, 73))
    # the redundant bar keeps its length over the turn: the linkage moves although Gruebler says it cannot
    assert np.allclose(np.hypot(*(sol.points["C"] - np.array([50.0, 0.0])).T), math.hypot(20, 30), atol=1e-9)


@pytest.mark.parametrize("points, links, ground, words", [
    ({"O": (0.0, 0.0), "A": (0.0, 0.0)}, {"crank": ("O", "A")}, ("O",), "drawn at the same place"),
    ({"O": (0.0, 0.0), "A": (1.0, 0.0)}, {"crank": ("O", "X")}, ("O",), "no joint 'X'"),
    ({"O": (0.0, 0.0), "A": (1.0, 0.0), "B": (5.0, 5.0), "C": (6, 6)}, {"crank": ("O", "A"), "loose": ("B", "C")},
     ("O",), "loose is not joined to the rest"),
])
def test_bad_drawings_are_named(points, links, ground, words):
    with pytest.raises(SpecError, match=words):
        make_structure(points, links, ground, (), CRANK)


# ---------------------------------------------------------------------- branches


def test_a_parallelogram_stays_a_parallelogram_through_its_change_points():
    fb = FourBar(128, 10, 128, 10)
    lk = Linkage.of(equivalents.fourbar(fb, 0.7))
    assert [t.kind for t in motion.toggles(lk)] == ["change point", "change point"]
    assert [t.value for t in motion.toggles(lk)] == pytest.approx([math.pi, 2 * math.pi], abs=1e-15)
    t = np.concatenate([np.linspace(0, 2 * math.pi, 2001), math.pi + np.array([-1e-6, -1e-9, 1e-9, 1e-6])])
    sol = lk.solve(t)
    ref = fb.sweep(lk.unwrap(t), "open")
    assert np.abs(np.sin(sol.angles["coupler"])).max() < 1e-7        # the coupler stays parallel to the ground
    far = np.abs(np.remainder(lk.unwrap(t) - math.pi + 1e-3, math.pi)) > 2e-3
    assert np.abs(sol.points["B"] - ref.b)[far].max() < 1e-9
    # velocities away from the change point: the rocker turns with the crank
    assert np.allclose(sol.omegas["rocker"][far], 1.0, atol=1e-9)


def test_a_kite_folds_and_carries_its_branch():
    """A deltoid 114/114/178/178: the crank pin meets the rocker pivot; branches swap there and stay smooth."""
    fb = FourBar(114, 114, 178, 178)
    lk = Linkage.of(equivalents.fourbar(fb, 1.0))
    flips = [t.value for t in motion.toggles(lk) if t.kind == "change point"]
    assert flips, "a kite has change points"
    t = np.linspace(1.0, 1.0 + 2 * math.pi, 4001)[:-1]     # one revolution from the drawing
    sol = lk.solve(t)
    step = np.hypot(*np.diff(sol.points["B"], axis=0).T)
    assert step.max() < 5 * np.median(step)                           # no jump between neighbouring poses


def test_poses_at_and_within_1e12_of_a_toggle_are_finite_and_close():
    fb = FourBar(100, 70, 60, 80)
    lo, hi = fb.input_ranges()[0]
    lk = Linkage.of(equivalents.fourbar(fb, 0.0))
    r_lo, r_hi = motion.input_ranges(lk)[0]
    assert (r_lo, r_hi) == pytest.approx((lo, hi), abs=1e-12)      # the general range is the closed form's
    sol = lk.solve([r_hi, r_hi - 1e-12, r_lo + 1e-12])
    assert np.isfinite(sol.points["B"]).all()
    assert np.allclose(np.hypot(*(sol.points["B"] - sol.points["A"]).T), 60, atol=1e-9)
    with np.errstate(all="raise"):
        lk.solve([r_hi - 1e-9])


# ---------------------------------------------------------------------- a 50-digit reference


def test_watt_ii_output_against_a_50_digit_solution():
    lk = watt_ii()
    s = lk.structure
    mpmath.mp.dps = 50
    pts = {k: (mpmath.mpf(x), mpmath.mpf(y)) for k, (x, y) in s.points.items()}

    def dist(a, b):
        return mpmath.sqrt((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2)

    def meet(p1, r1, p2, r2, sign):
        d = dist(p1, p2)
        a = (d * d + r1 * r1 - r2 * r2) / (2 * d)
        h = mpmath.sqrt(r1 * r1 - a * a)
        ex, ey = (p2[0] - p1[0]) / d, (p2[1] - p1[1]) / d
        return (p1[0] + a * ex - sign * h * ey, p1[1] + a * ey + sign * h * ex)

    def side(p1, p2, j):
        return 1 if (p2[0] - p1[0]) * (j[1] - p1[1]) - (p2[1] - p1[1]) * (j[0] - p1[0]) > 0 else -1

    sb, sd = side(pts["A"], pts["Q"], pts["B"]), side(pts["C"], pts["R"], pts["D"])
    for theta in (0.0, 1.0, 2.5, 4.0, 5.5):
        got = lk.solve([theta]).points["D"][0]
        ra = dist(pts["O"], pts["A"])
        a = (ra * mpmath.cos(theta), ra * mpmath.sin(theta))
        b = meet(a, dist(pts["A"], pts["B"]), pts["Q"], dist(pts["Q"], pts["B"]), sb)
        # C turns with the rocker about Q
        ang = mpmath.atan2(b[1] - pts["Q"][1], b[0] - pts["Q"][0]) - mpmath.atan2(pts["B"][1] - pts["Q"][1],
                                                                                   pts["B"][0] - pts["Q"][0])
        cx, cy = pts["C"][0] - pts["Q"][0], pts["C"][1] - pts["Q"][1]
        c = (pts["Q"][0] + cx * mpmath.cos(ang) - cy * mpmath.sin(ang),
             pts["Q"][1] + cx * mpmath.sin(ang) + cy * mpmath.cos(ang))
        d = meet(c, dist(pts["C"], pts["D"]), pts["R"], dist(pts["R"], pts["D"]), sd)
        assert abs(got[0] - float(d[0])) < 1e-10 and abs(got[1] - float(d[1])) < 1e-10


def test_a_prp_dyad_puts_the_joint_where_the_lines_cross():
    """A block sliding along the crank and a block on the line y = 40, pinned together: x = 40 cot(theta)."""
    pts = {"O": (0.0, 0.0), "A": (math.cos(1.0) * 80, math.sin(1.0) * 80), "J": (40 / math.tan(1.0), 40.0)}
    sliders = (Slider("s1", "J", "crank", 1.0), Slider("s2", "J", "ground", 0.0))
    lk = Linkage.of(make_structure(pts, {"crank": ("O", "A")}, ("O",), sliders, CRANK))
    assert [s.kind for s in lk.plan.steps[1:]] == ["PRP"]
    t = np.linspace(0.3, 2.8, 51)
    sol = lk.solve(t)
    assert np.allclose(sol.points["J"][:, 0], 40 / np.tan(t), atol=1e-10)
    assert np.allclose(sol.velocities["J"][:, 0], -40 / np.sin(t) ** 2, atol=1e-9)
    assert np.allclose(sol.accelerations["J"][:, 0], 80 * np.cos(t) / np.sin(t) ** 3, atol=1e-8)


@pytest.mark.parametrize("offset", [1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-3])
def test_rates_at_and_near_change_points_are_the_branchs(offset):
    """A parallelogram's rocker turns with the crank (omega 1, alpha 0) through its fold; a kite's rates equal the
    dedicated four-bar's (themselves checked against 50 digits), where the 2x2 solve alone is 0/0."""
    par = Linkage.of(equivalents.fourbar(FourBar(128, 10, 128, 10), 0.7))
    t = np.array([math.pi - offset, math.pi, math.pi + offset, 2 * math.pi - offset])
    sol = par.solve(t)
    assert np.allclose(sol.omegas["rocker"], 1.0, atol=1e-10)
    assert np.allclose(sol.alphas["rocker"], 0.0, atol=1e-8)
    kite_fb = FourBar(114, 114, 178, 178)
    kite = Linkage.of(equivalents.fourbar(kite_fb, 1.0))
    fold = next(f for f in kite.flips if len(f))[0]
    t = fold + np.array([-offset, offset]) * 1e3 if offset < 1e-6 else fold + np.array([-offset, offset])
    sol = kite.solve(t)
    ref = kite_fb.sweep(kite.unwrap(t), "open")
    w3, w4 = kite_fb.velocities(ref, 1.0)
    a3, a4 = kite_fb.accelerations(ref, 1.0)
    assert np.allclose(sol.omegas["coupler"], w3, atol=1e-9) and np.allclose(sol.omegas["rocker"], w4, atol=1e-9)
    assert np.allclose(sol.alphas["coupler"], a3, atol=1e-8) and np.allclose(sol.alphas["rocker"], a4, atol=1e-8)


def test_a_kite_at_its_fold_is_placed_at_its_branchs_limit():
    """At the fold of a deltoid 114/114/178/178 (the crank pin A on the rocker pivot O4) the circles of B are one:
    B is the limit the motion carries it to, the same from either side: on the coupler's circle about O4, on the
    line through O4 square to the crank pin's velocity there (the crank's tangent, so the x axis), 178 mm from O4:
    x = 114 - 178 = -64 on the drawn branch. Poses a few rounding steps either side agree with it."""
    kite = Linkage.of(equivalents.fourbar(FourBar(114, 114, 178, 178), 1.0))
    fold = 2 * math.pi
    sol = kite.solve([fold, fold - 1e-15, fold + 1e-15, fold - 1e-9, fold + 1e-9])
    assert sol.points["B"][0] == pytest.approx([114.0 - 178.0, 0.0], abs=1e-9)
    assert np.abs(sol.points["B"][:3] - sol.points["B"][0]).max() < 1e-9
    # h rad past the fold B lies on the bisector of A O4: B = (114, 57 h) - 178 (1, h / 2) = (-64, -32 h) to first
    # order (the drawn branch continues to y < 0)
    assert np.abs(sol.points["B"][3:] - np.array([[-64.0, 32e-9], [-64.0, -32e-9]])).max() < 1e-12
    assert np.allclose(np.hypot(*(sol.points["B"] - sol.points["A"]).T), 178.0, atol=1e-9)
    assert np.allclose(np.hypot(*(sol.points["B"] - np.array([114.0, 0.0])).T), 178.0, atol=1e-9)


def test_linkgen_analyze_and_family_take_a_drawn_linkage(tmp_path):
    """The four-bar drawn as joints and links: `linkgen analyze --json` reports what the closed form says, and a
    family sweeps a joint of the drawing."""
    import json

    from click.testing import CliRunner

    from linkgen.cli import main as linkgen

    fb = FourBar(180, 80, 200, 150)
    p = fb.positions([0.5])
    template = tmp_path / "drawn.toml"
    template.write_text(f"""name = "drawn"
[linkage]
type = "linkage"
ground = ["O2", "O4"]
input = {{ link = "crank", pivot = "O2" }}
tracers = ["B"]
[linkage.joints]
O2 = [0, 0]
O4 = [180, 0]
A = [{float(p.a[0, 0])!r}, {float(p.a[0, 1])!r}]
B = [{float(p.b[0, 0])!r}, {float(p.b[0, 1])!r}]
[linkage.links]
crank = ["O2", "A"]
coupler = ["A", "B"]
rocker = ["O4", "B"]
[linkage.lengths]
"A-B" = 200
""")
    result = CliRunner().invoke(linkgen, ["analyze", str(template), "--json", "--angle", "30", "-o",
                                          str(tmp_path / "o"), "--figures"])
    assert result.exit_code == 0, result.output
    r = json.loads(result.output)
    assert r["mobility"] == 1 and [s["step"] for s in r["solve_order"]] == ["input", "RRR"]
    assert r["input_range_deg"] is None and r["toggles"] == []
    assert r["outputs"]["rocker"]["time_ratio"] == pytest.approx(fb.time_ratio(), rel=1e-12)
    (gmin, _), (gmax, _) = fb.transmission_extremes()
    assert r["dyads"][0]["transmission_min_deg"] == pytest.approx(math.degrees(gmin), abs=1e-3)
    assert r["dyads"][0]["transmission_max_deg"] == pytest.approx(math.degrees(gmax), abs=1e-3)
    pose = fb.positions([math.radians(30)])
    assert [r["positions"]["joints"]["B"]["x_mm"], r["positions"]["joints"]["B"]["y_mm"]] == pytest.approx(
        pose.b[0], abs=1e-9)
    assert (tmp_path / "o" / "drawn-pose.png").exists()
    bad = CliRunner().invoke(linkgen, ["analyze", str(template), "--set", "linkage.lengths.A-B=201"])
    assert bad.exit_code == 2 and "linkage.lengths.A-B: the drawing puts A and B 200.000000 mm apart" in bad.stderr
    family = tmp_path / "family.toml"
    family.write_text('base = "drawn.toml"\nname = "fam"\n[sweep]\n"linkage.joints.O4" = [[180, 0], [170, 10]]\n')
    result = CliRunner().invoke(linkgen, ["family", str(family), "-o", str(tmp_path / "fam"), "--jobs", "1"])
    assert result.exit_code == 0, result.output
    rows = json.loads((tmp_path / "fam" / "summary.json").read_text())
    assert [row["status"] for row in rows] == ["ok", "ok"]


def test_per_link_widths_by_name(tmp_path):
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import validate_spec

    fb = FourBar(180, 80, 200, 150)
    p = fb.positions([0.5])
    raw = {"name": "w", "linkage": {"type": "linkage", "ground": ["O2", "O4"], "input": {"link": "crank",
                                                                                          "pivot": "O2"},
                                    "joints": {"O2": [0, 0], "O4": [180, 0], "A": p.a[0].tolist(),
                                               "B": p.b[0].tolist()},
                                    "links": {"crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]}},
           "parts": {"width": 10, "thickness": 3, "pin_diameter": 3, "links": {"coupler": {"width": 16}}}}
    build = design_linkage(validate_spec(raw), parts=True).build
    assert {part.name: 2 * part.half_width for part in build.parts} == {"ground": 20, "crank": 10, "coupler": 16,
                                                                        "rocker": 10}
    raw["parts"]["links"] = {"thigh": {"width": 16}}
    with pytest.raises(SpecError, match=r"parts.links.thigh: no link 'thigh' in this linkage"):
        design_linkage(validate_spec(raw), parts=True)
    raw["parts"]["links"] = {"coupler": {"width": 3}}
    with pytest.raises(SpecError, match=r"links.coupler.width: holes of 3.2 mm leave no material in a bar 3 mm"):
        validate_spec(raw)


def test_an_input_a_rounding_past_a_toggle_snaps_onto_it_and_the_refusal_reads_apart():
    """The general solver takes what the four-bar's closed form takes (within 1e-10 of the links past a toggle);
    a value just out of reach prints with enough digits to differ from the limit, in (-180, 180]."""
    fb = FourBar(180, 120, 140, 150)
    _, hi = fb.input_ranges()[0]
    lk = Linkage.of(equivalents.fourbar(fb, 0.0))
    sol = lk.solve([hi + 1e-13, math.radians(149.703449697)])
    assert np.isfinite(sol.points["B"]).all()
    with pytest.raises(SpecError, match=r"input: input 149\.7035 degrees is out of reach; the linkage reaches "
                                        r"\[-149\.7034, 149\.7034\] degrees"):
        lk.solve([math.radians(149.7035)])


def test_a_crank_sweeping_over_another_ground_pivot_gets_a_top_plate():
    """A drag link (the ground the shortest link): the crank passes over the rocker's pivot, so that pivot comes
    down from a plate above every moving part, and the base plate keeps only the crank's pivot hole."""
    from linkgen.mechanisms.general import analysis_of, general_layout
    from linkgen.parts import build_parts
    from linkgen.spec import PartsTable

    fb = FourBar(40, 100, 90, 120)
    table = PartsTable(width=10, thickness=3, pin_diameter=3, sheet=(1000, 1000))
    build = build_parts(general_layout(analysis_of(equivalents.fourbar(fb, 0.5), ("B",)), table), table)
    fixed = {p.name: p.centres.tolist() for p in build.parts if not p.moving}
    assert fixed == {"ground": [[0.0, 0.0]], "ground-top": [[40.0, 0.0]]}
    assert build.layers["ground-top"] == max(build.layers.values()) > build.layers["rocker"]
    assert build.layer_names[0] == "ground" and build.layer_names[-1] == "ground-top"
    plain = FourBar(180, 80, 200, 150)                       # a crank-rocker needs none
    build = build_parts(general_layout(analysis_of(equivalents.fourbar(plain, 0.5), ("B",)), table), table)
    assert "ground-top" not in build.layers


def test_spacers_fill_the_empty_layers_a_pin_crosses(tmp_path):
    """The crank-shaper: the lever's pivot O4 rises from the base plate (0) to the lever (2) through an empty layer,
    so it takes a spacer one plate high; the crank pin goes through the lever's slot to its block, so none there;
    with pins asked for, the spacer is written as a tube with the printed hole and twice the pin outside."""
    import trimesh

    from linkgen.linkage_design import design_linkage
    from linkgen.outputs import write_linkage
    from linkgen.spec import validate_spec

    spec = validate_spec({"name": "qs", "linkage": {"type": "crank-shaper", "crank": 50.0, "ground": 150.0,
                                                    "lever": 300.0},
                          "parts": {"width": 10.0, "thickness": 3.0, "pin_diameter": 3.0, "sheet": [1000.0, 1000.0],
                                    "pins": True}, "output": {"formats": ["json", "stl"]}})
    design = design_linkage(spec, parts=True)
    layers = design.build.layers
    assert layers["lever"] - layers["ground"] == 2 and layers["block"] - layers["crank"] == 2
    assert design.build.report["spacers"] == [{"joint": "O4", "between": ["ground", "lever"], "height_mm": 3.0,
                                               "inner_diameter_mm": 3.2, "outer_diameter_mm": 6.0}]
    files = write_linkage(design, tmp_path)
    from camgen.core.shapes import arc_steps

    tube = trimesh.load(tmp_path / files["spacer-1_stl"])
    assert tube.is_watertight

    def polygon(r: float) -> float:                       # the inscribed regular polygon the tolerance allows
        n = arc_steps(r, 2 * math.pi, 0.01)
        return n / 2 * r * r * math.sin(2 * math.pi / n)

    assert tube.volume == pytest.approx((polygon(3.0) - polygon(1.6)) * 3.0, rel=1e-6)
    assert abs(tube.volume - math.pi / 4 * (6.0**2 - 3.2**2) * 3.0) < math.pi * (6.0 + 3.2) * 0.01 * 3.0


def test_a_ground_sliders_stroke_and_time_ratio_are_refined():
    """The offset slider-crank's stroke and time ratio from its limit positions, against the closed form:
    stroke = sqrt((L + R)^2 - e^2) - sqrt((L - R)^2 - e^2), crank angles at the dead centres."""
    sc = SliderCrank(50, 140, 12)
    lk = Linkage.of(equivalents.slider_crank(sc, 0.3))
    ext = motion.limit_positions(lk, "slider", *motion.span(lk))
    stroke = math.sqrt(190**2 - 144) - math.sqrt(90**2 - 144)
    assert abs(ext[0].position - ext[1].position) == pytest.approx(stroke, abs=1e-9)
    assert motion.time_ratio(lk, ext) == pytest.approx(sc.time_ratio, rel=1e-9)
