"""Four-bar kinematics against hand solutions, an independent textbook formula, Newton-Raphson and
finite differences."""
from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import pytest

from camgen.core.errors import SolverError, SpecError
from linkgen.linkage_design import design_linkage
from linkgen.kinematics.fourbar import FourBar
from linkgen.spec import load_spec
from tests.conftest import ROOT

CRANK_ROCKER = FourBar(180, 80, 200, 150)
CASES = [CRANK_ROCKER, FourBar(6, 2, 7, 9), FourBar(50, 150, 200, 180), FourBar(100, 70, 60, 80),
         FourBar(180, 150, 50, 200)]


def wrap(x):
    return np.angle(np.exp(1j * np.asarray(x)))


def reachable_grid(fb: FourBar, n: int = 361) -> np.ndarray:
    ranges = fb.input_ranges()
    if ranges is None:
        return np.linspace(0, 2 * math.pi, n)
    lo, hi = ranges[0]
    return np.linspace(lo, hi, n)[1:-1]


def test_hand_solved_3_4_5_pose():
    """O2 = (0, 0), O4 = (4, 0), crank 3 at 90 degrees: A = (0, 3), |A O4| = 5; coupler 3 and rocker 4 make a right
    angle at B. Open: B = A + 9/5 u + 12/5 n = (2.88, 3.84); crossed: B = (0, 0). Solved by hand."""
    fb = FourBar(4, 3, 3, 4)
    op = fb.positions([math.pi / 2], "open")
    assert op.b[0] == pytest.approx([2.88, 3.84], abs=1e-14)
    assert math.degrees(op.gamma[0]) == pytest.approx(90.0, abs=1e-12)
    assert math.degrees(op.theta3[0]) == pytest.approx(math.degrees(math.atan2(0.84, 2.88)), abs=1e-12)
    cr = fb.positions([math.pi / 2], "crossed")
    assert cr.b[0] == pytest.approx([0.0, 0.0], abs=1e-14)
    assert math.degrees(wrap(cr.theta4[0])) == pytest.approx(180.0, abs=1e-12)


@pytest.mark.parametrize("fb", CASES, ids=lambda f: f"{f.ground}-{f.crank}-{f.coupler}-{f.rocker}")
def test_rocker_angle_matches_the_freudenstein_form(fb):
    """Independent closed form: Norton, Design of Machinery (5th ed.), eq. 4.10 with K1..K3 (Freudenstein);
    its minus root is the open assembly, the plus root the crossed one."""
    l1, l2, l3, l4 = fb.ground, fb.crank, fb.coupler, fb.rocker
    t2 = reachable_grid(fb)
    k1, k2, k3 = l1 / l2, l1 / l4, (l2**2 - l3**2 + l4**2 + l1**2) / (2 * l2 * l4)
    a = np.cos(t2) - k1 - k2 * np.cos(t2) + k3
    b = -2 * np.sin(t2)
    c = k1 - (k2 + 1) * np.cos(t2) + k3
    root = np.sqrt(np.maximum(b * b - 4 * a * c, 0))
    for assembly, sign in (("open", -1), ("crossed", 1)):
        t4 = 2 * np.arctan2(-b + sign * root, 2 * a)
        assert np.abs(wrap(fb.positions(t2, assembly).theta4 - t4)).max() < 1e-9


@pytest.mark.parametrize("fb", CASES, ids=lambda f: f"{f.ground}-{f.crank}-{f.coupler}-{f.rocker}")
def test_closed_form_and_newton_agree_over_full_sweeps(fb):
    t2 = reachable_grid(fb, 181)
    poses = fb.sweep(t2, "open")
    guess = (poses.theta3[0] + 0.3, poses.theta4[0] - 0.3)
    for k, t in enumerate(t2):
        r = fb.newton(float(t), guess)
        assert abs(wrap(r.theta3 - poses.theta3[k])) < 1e-10
        assert abs(wrap(r.theta4 - poses.theta4[k])) < 1e-10
        guess = (r.theta3, r.theta4)                              # continuation, as a user would sweep


def test_newton_table_converges_quadratically():
    fb = CRANK_ROCKER
    exact = fb.positions([math.radians(30)])
    r = fb.newton(math.radians(30), (exact.theta3[0] + 0.17, exact.theta4[0] - 0.17))
    res = [s.residual for s in r.steps]
    assert res[-1] <= 1e-12 * fb.longest
    assert 3 <= len(res) <= 8
    # quadratic: each step's residual is at most ~C * previous^2
    for before, after in itertools.pairwise(res[1:]):
        assert after <= 10 * before**2 / fb.longest + 1e-12


def test_newton_fails_clearly_at_a_singular_jacobian():
    fb = FourBar(100, 70, 60, 80)
    with pytest.raises(SolverError, match="singular Jacobian at iteration 0"):
        fb.newton(0.5, (0.3, 0.3))                                 # coupler and rocker collinear in the guess
    with pytest.raises(SolverError, match="singular Jacobian"):     # a parallelogram at its change point
        FourBar(4, 2, 4, 2).newton(0.0, (0.1, 0.1))
    with pytest.raises(SolverError, match="did not converge"):
        CRANK_ROCKER.newton(0.5, (2.0, 1.0), max_iter=1)


@pytest.mark.parametrize("fb", CASES, ids=lambda f: f"{f.ground}-{f.crank}-{f.coupler}-{f.rocker}")
def test_velocity_and_acceleration_match_finite_differences(fb):
    omega, h = 2.5, 1e-6
    t2 = reachable_grid(fb, 40)[2:-2]
    p, pp, pm = fb.positions(t2), fb.positions(t2 + h), fb.positions(t2 - h)
    w3, w4 = fb.velocities(p, omega)
    a3, a4 = fb.accelerations(p, omega)
    assert np.abs(wrap(pp.theta3 - pm.theta3) / (2 * h) * omega - w3).max() < 1e-6
    assert np.abs(wrap(pp.theta4 - pm.theta4) / (2 * h) * omega - w4).max() < 1e-6
    n3 = wrap(pp.theta3 - 2 * p.theta3 + pm.theta3) / h**2 * omega**2
    n4 = wrap(pp.theta4 - 2 * p.theta4 + pm.theta4) / h**2 * omega**2
    assert np.abs(n3 - a3).max() < 1e-2 * max(1.0, np.abs(a3).max())
    assert np.abs(n4 - a4).max() < 1e-2 * max(1.0, np.abs(a4).max())
    ma = fb.mechanical_advantage(p)
    assert np.allclose(ma, np.abs(omega / w4), rtol=1e-9)


def test_crank_rocker_dead_centres_by_hand():
    """Law of cosines in triangle O2-B-O4 with O2B = 80 + 200 (extended) and 200 - 80 (folded)."""
    fb = CRANK_ROCKER
    ext = math.degrees(math.acos((180**2 + 280**2 - 150**2) / (2 * 180 * 280)))
    fold = math.degrees(math.acos((180**2 + 120**2 - 150**2) / (2 * 180 * 120))) + 180
    dead = {d.kind: d for d in fb.dead_centres("open")}
    assert set(dead) == {"extended", "folded"}
    assert math.degrees(dead["extended"].crank) % 360 == pytest.approx(ext, abs=1e-9)
    assert math.degrees(dead["folded"].crank) % 360 == pytest.approx(fold, abs=1e-9)
    travel = fold - ext
    assert fb.time_ratio("open") == pytest.approx(travel / (360 - travel), rel=1e-12)
    # the rocker stops there: its angular velocity is zero, and the mechanical advantage unbounded
    for d in dead.values():
        pose = fb.positions([d.crank])
        assert abs(fb.velocities(pose, 1.0)[1][0]) < 1e-9
        assert math.degrees(pose.theta4[0]) == pytest.approx(math.degrees(d.rocker), abs=1e-9)


def test_transmission_extremes_by_hand():
    (gmin, at_min), (gmax, at_max) = CRANK_ROCKER.transmission_extremes()
    assert math.degrees(gmin) == pytest.approx(math.degrees(math.acos((200**2 + 150**2 - 100**2) / 60000)), abs=1e-10)
    assert math.degrees(gmax) == pytest.approx(math.degrees(math.acos((200**2 + 150**2 - 260**2) / 60000)), abs=1e-10)
    assert (at_min, at_max) == (0.0, pytest.approx(math.pi))
    sweep = CRANK_ROCKER.positions(np.linspace(0, 2 * math.pi, 3601)).gamma
    assert gmin <= sweep.min() + 1e-15 and gmax >= sweep.max() - 1e-15


def test_non_grashof_range_and_out_of_range_error():
    """Toggle where Z = L3 + L4: cos t2 = (L1^2 + L2^2 - (L3 + L4)^2) / (2 L1 L2)."""
    fb = FourBar(100, 70, 60, 80)
    limit = math.acos((100**2 + 70**2 - 140**2) / (2 * 100 * 70))
    assert fb.input_ranges() == ((pytest.approx(-limit), pytest.approx(limit)),)
    with pytest.raises(SpecError, match=r"out of reach; this linkage reaches crank angles \[-109.616, 109.616\]"):
        fb.positions([limit + 1e-3])
    kinds = {d.kind for d in fb.dead_centres()}
    assert "toggle-extended" in kinds


def _reference_pose(fb: FourBar, t2: float, sign: int) -> tuple[float, float]:
    """theta3, theta4 with 50 significant digits (mpmath), by the same triangle but in high precision."""
    mpmath.mp.dps = 50
    l1, l2, l3, l4 = (mpmath.mpf(x) for x in (fb.ground, fb.crank, fb.coupler, fb.rocker))
    t = mpmath.mpf(t2)
    dx, dy = l1 - l2 * mpmath.cos(t), -l2 * mpmath.sin(t)
    z = mpmath.sqrt(dx**2 + dy**2)
    delta = mpmath.atan2(dy, dx)
    # an input that rounds to the toggle may lie a hair beyond it in 50 digits: that pose is the toggle's
    alpha = mpmath.acos(max(-1, min(1, (l3**2 + z**2 - l4**2) / (2 * l3 * z))))
    beta = mpmath.acos(max(-1, min(1, (l4**2 + z**2 - l3**2) / (2 * l4 * z))))
    return float(delta + sign * alpha), float(delta + mpmath.pi - sign * beta)


@pytest.mark.parametrize("offset", [0.0, 1e-12, 1e-9])
@pytest.mark.parametrize("fb", [FourBar(100, 70, 60, 80), FourBar(100, 60, 40, 90)], ids=["triple", "double"])
def test_poses_at_and_within_1e_12_of_a_toggle_are_finite_and_correct(fb, offset):
    for lo, hi in fb.input_ranges():
        for t2 in (lo + offset, hi - offset):
            for sign, assembly in ((1, "open"), (-1, "crossed")):
                p = fb.positions([t2], assembly)
                assert np.isfinite(p.theta3).all() and np.isfinite(p.theta4).all()
                assert np.linalg.norm(p.b[0] - p.a[0]) == pytest.approx(fb.coupler, rel=1e-13)
                assert np.linalg.norm(p.b[0] - [fb.ground, 0]) == pytest.approx(fb.rocker, rel=1e-13)
                t3, t4 = _reference_pose(fb, t2, sign)
                # near a toggle the pose moves like sqrt(distance): 1e-12 rad of input is ~1e-6 rad of pose,
                # so compare to what double precision can carry there
                assert abs(wrap(p.theta3[0] - t3)) < 2e-7
                assert abs(wrap(p.theta4[0] - t4)) < 2e-7


def test_parallelogram_swept_through_its_flat_positions_stays_a_parallelogram():
    fb = FourBar(100, 40, 100, 40)
    assert fb.change_points() == (0.0, math.pi)
    t2 = np.radians(np.linspace(10, 730, 1441))          # twice round, through 180, 360, 540 and 720 degrees
    p = fb.sweep(t2, "open")
    assert np.abs(wrap(p.theta3)).max() < 1e-12          # the coupler stays parallel to the ground
    assert np.abs(p.b - p.a - [100, 0]).max() < 1e-13 * 100
    assert np.abs(wrap(p.theta4 - p.theta2)).max() < 1e-12
    anti = fb.sweep(t2, "crossed")                       # the other branch stays the anti-parallelogram
    assert np.abs(wrap(anti.theta3)).max() > 0.5
    d2 = np.abs(np.diff(np.unwrap(anti.theta3), 2)).max()
    assert d2 < 1e-3                                     # smooth: no switch back to the parallelogram


def test_deltoid_coincident_pivot_is_a_clear_error():
    fb = FourBar(100, 100, 40, 40)
    with pytest.raises(SpecError, match="undetermined"):
        fb.positions([0.0])
    assert np.isfinite(fb.positions([0.3]).theta3).all()


def test_rocker_input_positions_close_the_loop():
    fb = CRANK_ROCKER
    t4 = np.radians(np.linspace(66, 136, 15))
    for assembly in ("open", "crossed"):
        p = fb.rocker_positions(t4, assembly)
        assert np.allclose(np.linalg.norm(p.a, axis=1), fb.crank, rtol=1e-13)
        assert np.allclose(np.linalg.norm(p.b - p.a, axis=1), fb.coupler, rtol=1e-13)
        assert np.allclose(p.b, np.column_stack([180 + 150 * np.cos(t4), 150 * np.sin(t4)]), atol=1e-12)


def test_coupler_point_sits_on_the_coupler_plate():
    fb = FourBar(180, 80, 200, 150, point_distance=120.0, point_angle=math.radians(30))
    p = fb.positions(np.linspace(0, 2 * math.pi, 50))
    ab, ap = p.b - p.a, p.point - p.a
    assert np.allclose(np.linalg.norm(ap, axis=1), 120.0, rtol=1e-13)
    angle = np.arctan2(ab[:, 0] * ap[:, 1] - ab[:, 1] * ap[:, 0], (ab * ap).sum(axis=1))
    assert np.allclose(angle, math.radians(30), atol=1e-12)


def test_vectorised_positions_are_fast_and_never_nan():
    t2 = np.linspace(0, 2 * math.pi, 100_000)
    p = CRANK_ROCKER.positions(t2, "crossed")
    assert np.isfinite(p.theta3).all() and np.isfinite(p.gamma).all()


@pytest.mark.parametrize("beyond, angle, limit", [
    (1e-6, "109.61604", "109.61598"), (1e-9, "109.6159792", "109.6159791"), (1e-3, "109.673", "109.616")])
def test_an_angle_just_out_of_reach_does_not_read_as_its_limit(beyond, angle, limit):
    """The issue: "149.703 is out of reach of [.., 149.703]". As many digits (6 to 17) as tell the two apart."""
    fb = FourBar(100, 70, 60, 80)
    end = math.acos((100**2 + 70**2 - 140**2) / (2 * 100 * 70))
    with pytest.raises(SpecError) as err:
        fb.positions([end + beyond])
    assert str(err.value) == (f"angle: crank angle {angle} degrees is out of reach; this linkage reaches crank angles "
                              f"[-{limit}, {limit}] degrees")


def test_an_unreachable_rocker_angle_is_named_as_the_rockers():
    """Driven by the rocker, the message speaks of rocker angles and their range, not the mirror image's crank."""
    fb = FourBar(100, 70, 60, 80)
    mirror_end = math.degrees(math.acos((100**2 + 80**2 - 130**2) / (2 * 100 * 80)))     # Z = L3 + L4 = 130
    with pytest.raises(SpecError, match=r"^angle: rocker angle 10 degrees is out of reach; this linkage reaches "
                                        r"rocker angles \[88.2092, 271.791\] degrees$"):
        fb.rocker_positions([math.radians(10)])
    assert 180 - mirror_end == pytest.approx(88.2092, abs=1e-4)


def test_newton_converges_at_a_reachable_toggle():
    """The issue's case: crank 120, coupler 140 (ground 180, rocker 150; S + L > P + Q, a triple rocker) at
    149.703449697 degrees, 6e-12 rad past the toggle where Z = L3 + L4 (accepted, and placed on the toggle, by the
    closed form). The Jacobian is singular at the double root and there is no exact root: Newton used to oscillate
    at a residual of 1e-9 mm for 50 iterations. Now each step is halved until it lowers the residual, and it stops at
    the least-squares pose, the toggle's: 1.1e-7 degrees from the closed form (measured), the residual 2.3e-10 mm,
    the loop's own gap there."""
    fb = FourBar(180, 120, 140, 150)
    theta2 = math.radians(149.703449697)
    assert theta2 > fb.input_ranges()[0][1]
    exact = fb.positions([theta2])
    assert math.degrees(exact.gamma[0]) == pytest.approx(180.0, abs=1e-12)        # the extended toggle
    gap = math.hypot(*fb._z(np.array(theta2))) - (fb.coupler + fb.rocker)
    r = fb.newton(theta2, (exact.theta3[0] + math.radians(10), exact.theta4[0] - math.radians(10)))
    assert r.least_squares and len(r.steps) <= 40
    assert r.steps[-1].residual == pytest.approx(gap, rel=1e-3)
    assert abs(math.degrees(wrap(r.theta3 - exact.theta3[0]))) < 1e-6
    assert abs(math.degrees(wrap(r.theta4 - exact.theta4[0]))) < 1e-6
    # linear convergence on the way in: the residual falls by about 4 a step (the angles' error halves)
    res = [s.residual for s in r.steps]
    assert all(3 < before / after < 5 for before, after in itertools.pairwise(res[2:14]))


@pytest.mark.parametrize("fb", [FourBar(100, 70, 60, 80), FourBar(100, 60, 40, 90), FourBar(180, 120, 140, 150)],
                         ids=["triple-rocker", "double-rocker", "issue"])
@pytest.mark.parametrize("past", [0.0, 1e-13, 5e-12, -1e-12, -1e-9])
def test_newton_at_and_near_every_toggle_agrees_with_the_closed_form(fb, past):
    """At each end of the reach, on it, a hair past it (within the closed form's tolerance) or just inside: Newton
    from 10 degrees off ends on the closed form's pose (to 1e-7 rad: a double root's angles are known to about the
    square root of the residual's rounding), or, just inside where the two assemblies are 1e-4 rad apart, on one
    of the two."""
    for lo, hi in fb.input_ranges():
        for theta2 in (lo - past, hi + past):
            both = [fb.positions([theta2], a) for a in ("open", "crossed")]
            p = both[0]
            r = fb.newton(theta2, (p.theta3[0] + math.radians(10), p.theta4[0] - math.radians(10)))
            assert min(max(abs(wrap(r.theta3 - q.theta3[0])), abs(wrap(r.theta4 - q.theta4[0])))
                       for q in both) < 1e-7
            assert r.steps[-1].residual <= (1e-12 + 1e-10) * fb.longest


def test_newton_report_at_the_issues_toggle():
    """The report of ``linkgen analyze templates/crank-rocker.toml --set linkage.crank=120 --set linkage.coupler=140
    --angle 149.703449697 --method newton``: the table converges to the closed form and says where it stopped."""
    spec = load_spec(ROOT / "templates" / "crank-rocker.toml", ["linkage.crank=120", "linkage.coupler=140"])
    newton = design_linkage(spec, 149.703449697, "newton").report["newton"]
    assert newton["agrees_with_closed_form_deg"] < 1e-6
    assert newton["stopped"].startswith("at a toggle's least-squares pose")
    rows = newton["iterations"]
    assert rows[0]["residual_mm"] > 1 and rows[-1]["residual_mm"] < 3e-10


@pytest.mark.parametrize("fb", [*CASES, FourBar(100, 40, 100, 40), FourBar(100, 70, 60, 80),
                                FourBar(180, 80, 200, 150, point_distance=120.0, point_angle=0.5)],
                         ids=lambda fb: f"{fb.ground:g}-{fb.crank:g}-{fb.coupler:g}-{fb.rocker:g}")
def test_poses_in_chunks_are_those_of_one_pass_to_the_last_bit(monkeypatch, fb):
    """The angles are placed a chunk at a time (fourbar.CHUNK); each angle's pose does not depend on the chunk it
    is in, nor on whether its angles and crank pin were placed with B (up to fourbar.EAGER angles) or derived when
    first read: chunks of 7 and of 1 000, eager or not, agree with one eager chunk of all, bit for bit, toggles
    (range ends) included, for positions, sweeps and rocker-driven poses; an angle out of reach in a later chunk
    is the same error."""
    from linkgen.kinematics import fourbar

    ranges = fb.input_ranges()
    t = np.linspace(*(ranges[0] if ranges else (-1.0, 8.0)), 2_501)
    mirrored = FourBar(fb.ground, fb.rocker, fb.coupler, fb.crank).input_ranges()    # the rocker as the input
    t4 = math.pi - np.linspace(*(mirrored[0] if mirrored else (-1.0, 8.0)), 2_501)
    fields = ("theta2", "theta3", "theta4", "gamma", "a", "b", "point", "assembly")
    runs = {}
    for chunk, eager in ((7, 0), (7, 10**9), (1_000, 0), (10**9, 0), (10**9, 10**9)):
        monkeypatch.setattr(fourbar, "CHUNK", chunk)
        monkeypatch.setattr(fourbar, "EAGER", eager)
        poses = [fb.positions(t, "open"), fb.positions(t, "crossed"), fb.sweep(t, "open"),
                 fb.rocker_positions(t4, "crossed")]
        runs[chunk, eager] = [{field: getattr(p, field) for field in fields} for p in poses]   # read while set
    for key, run in runs.items():
        for ours, one in zip(run, runs[10**9, 10**9], strict=True):
            for field in fields:
                assert np.array_equal(ours[field], one[field]), (key, field)
                assert ours[field].tobytes() == one[field].tobytes(), (key, field)    # -0.0 too
    if ranges:
        monkeypatch.setattr(fourbar, "CHUNK", 7)
        with pytest.raises(SpecError, match="out of reach") as small:
            fb.positions(np.append(t, ranges[0][1] + 1e-3))
        monkeypatch.setattr(fourbar, "CHUNK", 10**9)
        with pytest.raises(SpecError, match="out of reach") as one:
            fb.positions(np.append(t, ranges[0][1] + 1e-3))
        assert str(small.value) == str(one.value)


NON_FINITE = [float("nan"), float("inf"), -float("inf")]


def _refused(call, angles, field: str, said: str) -> None:
    """``call(angles)`` refuses with ``field: said ... is not a finite number``, and warns of nothing on the way."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(SpecError, match=rf"^{field}: {said} is not a finite number \(any finite number of "):
            call(np.array(angles))


@pytest.mark.parametrize("bad", NON_FINITE, ids=["nan", "inf", "-inf"])
@pytest.mark.parametrize("fb", [CRANK_ROCKER, FourBar(100, 70, 60, 80), FourBar(180, 80, 200, 150, 90, 0.6)])
def test_a_four_bar_refuses_a_crank_or_rocker_angle_that_is_not_a_number(fb, bad):
    shown = {"nan": "nan", "inf": "inf", "-inf": "-inf"}[str(bad)]
    lo, hi = fb.input_ranges()[0] if fb.input_ranges() else (0.0, 2 * math.pi)
    ok = [lo + 0.25 * (hi - lo), lo + 0.5 * (hi - lo)]          # reachable angles before and after it
    for call in (fb.positions, fb.sweep, lambda t: fb.sweep(t, "crossed")):
        _refused(call, [bad], "angle", f"crank angle {shown} degrees")
        _refused(call, [*ok, bad, ok[0]], "angle", f"crank angle {shown} degrees")
    # the rocker drives the mirror image: its angle theta4 is said as given (180 - (180 - theta4) degrees)
    _refused(fb.rocker_positions, [1.0, bad], "angle", f"rocker angle {shown} degrees")
    assert np.isfinite(fb.positions(np.array(ok)).b).all()


@pytest.mark.parametrize("bad", NON_FINITE, ids=["nan", "inf", "-inf"])
def test_every_mechanism_refuses_an_input_that_is_not_a_number(bad):
    import linkgen
    from linkgen.kinematics import equivalents
    from linkgen.kinematics.linkage import Linkage
    from linkgen.kinematics.quickreturn import CrankShaper, Whitworth
    from linkgen.kinematics.slidercrank import ScotchYoke, SliderCrank
    from linkgen.kinematics.straightline import straight_line

    shown = {"nan": "nan", "inf": "inf", "-inf": "-inf"}[str(bad)]
    crank = f"crank angle {shown} degrees"
    slider = SliderCrank(40.0, 120.0, 10.0)
    for call in (slider.position, slider.derivatives, lambda t: slider.motion(t, 10.0),
                 lambda t: ScotchYoke(40.0).motion(t, 10.0), lambda t: CrankShaper(40.0, 100.0, 200.0).motion(t, 10.0),
                 lambda t: Whitworth(100.0, 40.0, 50.0, 150.0).motion(t, 10.0), straight_line("watt", 20.0).trace):
        _refused(call, [0.5, bad], "angle", crank)
    general = Linkage.of(equivalents.fourbar(CRANK_ROCKER, 0.3))
    _refused(general.solve, [0.1, bad], "input", f"input {shown} degrees")
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert general.solve(np.array([0.1, bad]), strict=False).ok.tolist() == [True, False]   # marked, unsaid
    pump = linkgen.design_linkage(linkgen.load_spec(ROOT / "templates" / "pendulum-pump.toml")).kinematics.linkage
    _refused(pump.solve, [bad], "input", f"input {shown} mm")


def test_the_largest_finite_angles_are_not_refused_as_non_finite():
    huge = np.array([np.finfo(float).max, -np.finfo(float).max, 1e-300, -0.0])
    poses = FourBar(40, 100, 90, 120).positions(huge)                    # a drag link turns fully: every angle
    assert np.isfinite(poses.b).all() and np.isfinite(poses.theta4).all()


EPS = np.finfo(float).eps
#: crank-rockers, double-cranks, rockers (one with a coupler point), parallelograms, deltoids and kites, and
#: lengths 1e-6 to 1e6 apart
ACCURACY_CASES = [(180, 80, 200, 150, 120, 0.6), (6, 2, 7, 9), (50, 150, 200, 180), (100, 70, 60, 80),
                  (40, 100, 90, 120), (100, 60, 40, 90), (100, 40, 100, 40, 30, 2.0), (100, 100, 40, 40),
                  (40, 100, 40, 100), (100, 40, 40, 100), (1e6, 1, 1e6, 3, 1e3, -1.0), (1, 1e-6, 1, 3e-6),
                  (1e-3, 1e3, 1e3, 1e3), (1.0, 1e6, 1e6, 1e6 + 0.5), (1e6, 1e6, 1.0, 1.5), (1e-6, 1.0, 1.0, 1.0)]


def _exact_pose(lengths, d, pa, t, sign) -> dict:
    """Every pin and angle of the crank-driven pose at crank angle t (an mpf: exactly the double given, or
    pi - theta4 of a rocker drive), 50 digits; and the condition of the pose, L z / (4 area) + L / z (the
    rounding of z and of the direction of A -> O4 are what the pose carries of an error in the last bit)."""
    l1, l2, l3, l4 = (mpmath.mpf(x) for x in lengths)
    ax, ay = l2 * mpmath.cos(t), l2 * mpmath.sin(t)
    z2 = (l1 - ax) ** 2 + ay**2
    area4 = mpmath.sqrt(max(0, ((l3 + l4) ** 2 - z2) * (z2 - (l3 - l4) ** 2)))
    t3 = mpmath.atan2(-ay, l1 - ax) + mpmath.atan2(sign * area4, l3**2 - l4**2 + z2)
    bx, by = ax + l3 * mpmath.cos(t3), ay + l3 * mpmath.sin(t3)
    z, longest = mpmath.sqrt(z2), max(lengths)
    condition = min(z * longest / area4 + longest / z, 1 / math.sqrt(EPS)) if area4 else 1 / math.sqrt(EPS)
    return {"a": (ax, ay), "b": (bx, by), "point": (ax + d * mpmath.cos(t3 + pa), ay + d * mpmath.sin(t3 + pa)),
            "theta3": t3, "theta4": mpmath.atan2(by, bx - l1), "gamma": mpmath.atan2(area4, l3**2 + l4**2 - z2),
            "condition": float(condition)}


def _accuracy_angles(fb: FourBar, rng) -> list[float]:
    """Random reachable crank angles, each end of the reach (a toggle) and 1 ulp, 1e-15, 1e-12 and 1e-9 rad
    inside it, and 0, pi and 2 pi (change points of the folding linkages) and 5e-16 to 1e-9 either side."""
    ranges = fb.input_ranges()
    out = list(rng.uniform(-math.pi, 3 * math.pi, 16)) if ranges is None else []
    for lo, hi in ranges or ():
        out += list(rng.uniform(lo, hi, 16 // len(ranges)))
        for end, inward in ((lo, 1.0), (hi, -1.0)):
            out += [end, np.nextafter(end, end + inward)] + [end + inward * x for x in (1e-15, 1e-12, 1e-9)]
    return out + [cp + x for cp in (0.0, math.pi, 2 * math.pi) for x in (0.0, 5e-16, -5e-16, 1e-12, -1e-12, 1e-9)]


@pytest.mark.parametrize("lengths", ACCURACY_CASES, ids=lambda x: "-".join(f"{v:g}" for v in x))
def test_poses_are_exact_to_rounding_against_50_digits(lengths):
    """Every field of every pose, crank- and rocker-driven, both assemblies, within 16 units in the last place of
    what it measures times the pose's condition (1 + L z / (4 area) + L / z, see _exact_pose) of the 50-digit
    pose: to rounding at random angles, at toggles and 1 ulp to 1e-9 rad inside them, at change points and beside
    them, with lengths 1e-6 to 1e6 apart. (Measured: at most 8.6 units, the same as the code before B was placed
    without angles; docs/guides/speed.md.)"""
    mpmath.mp.dps = 50
    fb = FourBar(*lengths)
    d, pa = mpmath.mpf(fb.point_distance), mpmath.mpf(fb.point_angle)
    l1, l2, l3, l4 = lengths[:4]
    longest = max(lengths[:4])
    scale = {"a": longest, "b": longest, "point": longest + fb.point_distance, "theta2": longest / l2,
             "theta3": longest / l3, "theta4": longest / l4, "gamma": longest / min(l3, l4)}
    mirror = FourBar(l1, l4, l3, l2)
    rng = np.random.default_rng(16)
    checked = 0
    for driven, angles in (("crank", _accuracy_angles(fb, rng)), ("rocker", [math.pi - t for t in
                                                                            _accuracy_angles(mirror, rng)])):
        for t in angles:
            for sign, assembly in ((1, "open"), (-1, "crossed")):
                try:
                    pose = fb.positions([t], assembly) if driven == "crank" else fb.rocker_positions([t], assembly)
                except SpecError as error:
                    assert "out of reach" in str(error) or "undetermined" in str(error)
                    continue
                if driven == "crank":
                    want = _exact_pose(lengths[:4], d, pa, mpmath.mpf(t), sign)
                else:          # the mirror's pose at pi - theta4, reflected; theta4 is the input itself
                    m = _exact_pose((l1, l4, l3, l2), 0, 0, mpmath.pi - mpmath.mpf(t), sign)
                    a, b = (l1 - m["b"][0], m["b"][1]), (l1 - m["a"][0], m["a"][1])
                    t3 = mpmath.atan2(b[1] - a[1], b[0] - a[0])
                    want = {"a": a, "b": b, "theta3": t3, "theta4": mpmath.mpf(t), "gamma": m["gamma"],
                            "theta2": mpmath.atan2(a[1], a[0]), "condition": m["condition"],
                            "point": (a[0] + d * mpmath.cos(t3 + pa), a[1] + d * mpmath.sin(t3 + pa))}
                for field, unit in scale.items():
                    if field not in want:
                        continue
                    got = getattr(pose, field)[0]
                    if field in ("a", "b", "point"):
                        error = float(mpmath.hypot(got[0] - want[field][0], got[1] - want[field][1]))
                    else:
                        error = abs(float(got - want[field]) + math.pi) % (2 * math.pi) - math.pi
                        error = abs(error)
                    assert error <= 16 * EPS * unit * (1 + want["condition"]), (driven, t, assembly, field, error)
                checked += 1
    assert checked > 100


@pytest.mark.parametrize("fb, top", [
    (FourBar(20, 20, 20, 20), math.pi),                        # rhombus: flat and extended at 180 degrees
    (FourBar(100, 100, 40, 40), math.acos(0.68)),              # kite: toggles where z = L3 + L4 = 80
    (FourBar(164, 164, 135, 135), math.acos(1 - 270**2 / (2 * 164**2)))])
def test_a_deltoid_whose_crank_pin_meets_the_rocker_pivot_gives_its_extremes_without_a_warning(fb, top):
    """At crank angle 0 the crank pin sits on the rocker pivot (ground = crank): no pose is determined there, but
    coupler and rocker (equal) overlap whatever B is, so the transmission angle is 0; the largest is 180 degrees
    where z = L3 + L4 (law of cosines in O2-A-O4: cos t = 1 - z^2 / (2 L1^2) with L1 = L2) or at 180 degrees.
    These were placed with z = 0 (numpy's 'divide by zero' and 'invalid value' warnings, NaN poses)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        (gmin, at_min), (gmax, at_max) = fb.transmission_extremes()
        dead = fb.dead_centres("open") + fb.dead_centres("crossed")
    assert (gmin, at_min) == (0.0, 0.0)
    assert gmax == pytest.approx(math.pi, abs=1e-7) and abs(at_max) == pytest.approx(top, abs=1e-12)
    assert all(math.isfinite(d.rocker) for d in dead)


@pytest.mark.parametrize("lengths, args, ok", [
    ((20, 20, 20, 20), [], True),                              # a rhombus, as the issue gives it
    ((100, 100, 40, 40), ["--json"], True),                    # a kite
    ((100, 125, 75, 88), ["--angle", "180"], False),           # a non-Grashof linkage asked for a full turn's angle
    ((100, 125, 75, 88), ["--angle", "180", "--set", "linkage.input='rocker'"], False)])
def test_the_issues_linkages_analyze_with_warnings_as_errors(tmp_path, lengths, args, ok):
    """Run as a user runs it, with Python's warnings turned into errors: a result, or one line and exit 2."""
    import subprocess
    import sys

    path = tmp_path / "t.toml"
    body = "\n".join(f"{k} = {float(v)}" for k, v in zip(("ground", "crank", "coupler", "rocker"), lengths,
                                                          strict=True))
    path.write_text(f'name = "t"\n[linkage]\ntype = "four-bar"\n{body}\n')
    run = subprocess.run([sys.executable, "-W", "error", "-m", "linkgen", "analyze", str(path), "-o",
                          str(tmp_path / "out"), *args], capture_output=True, text=True, cwd=ROOT)
    if ok:
        assert run.returncode == 0 and run.stderr == "", run.stderr
    else:
        assert run.returncode == 2 and run.stderr.count("\n") == 1
        assert run.stderr.startswith("error: --angle: ") and "out of reach" in run.stderr


def test_a_rhombus_builds_its_parts_with_warnings_as_errors(tmp_path):
    """Its crank pin meets the rocker pivot at crank angle 0, where no pose is determined: the parts' layout, the
    sketch and the thumbnail sweep a full turn half a step off it (they were refused there, 'angle: ... undetermined',
    naming an angle nobody gave)."""
    import subprocess
    import sys

    from linkgen.kinematics.circuits import input_grid

    grid = input_grid(FourBar(20, 20, 20, 20), 8)
    assert grid == pytest.approx(np.radians(22.5 + 45 * np.arange(8)), abs=1e-15)
    assert input_grid(CRANK_ROCKER, 5) == pytest.approx(np.linspace(0, 2 * math.pi, 5), abs=0)
    path = tmp_path / "t.toml"
    path.write_text('name = "t"\n[linkage]\ntype = "four-bar"\nground = 20.0\ncrank = 20.0\ncoupler = 20.0\n'
                    'rocker = 20.0\n[parts]\nwidth = 6.0\nthickness = 3.0\npin_diameter = 3.0\n')
    run = subprocess.run([sys.executable, "-W", "error", "-m", "linkgen", "build", str(path), "-o",
                          str(tmp_path / "out"), "--set", "output.formats=['dxf', 'json']"],
                         capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0 and run.stderr == "", run.stderr
    assert (tmp_path / "out" / "t.json").exists()


#: deltoids whose crank pin meets the rocker pivot at crank angle 0: a rhombus and a kite (full turns), and a
#: double rocker whose range, +-acos(1 - (L3 + L4)^2 / (2 L1^2)) = +-60 degrees, holds the fold in its middle
DELTOIDS = [(20, 20, 20, 20), (20, 20, 40, 40), (40, 40, 20, 20)]


def _deltoid_gamma(lengths: tuple[float, ...], theta: np.ndarray) -> np.ndarray:
    """The transmission angle (rad) of a deltoid (L1 = L2, L3 = L4) from the law of cosines alone:
    z^2 = 2 L1^2 (1 - cos theta2) and cos gamma = 1 - z^2 / (2 L3^2)."""
    l1, _, l3, _ = lengths
    return np.arccos(np.clip(1 - (l1 / l3) ** 2 * (1 - np.cos(theta)), -1, 1))


@pytest.mark.parametrize("lengths", DELTOIDS)
def test_the_shared_input_grid_steps_round_a_deltoids_fold(lengths):
    """n angles over the full turn in the middle of n equal steps; over a range, its ends and equal steps, but the
    one on the fold (0 of [-60, 60] with 7 angles) gives way to the two half a step either side of it."""
    from linkgen.kinematics.circuits import input_grid, input_spans

    fb = FourBar(*lengths)
    (lo, hi), = input_spans(fb)
    grid = input_grid(fb, 7)
    if fb.input_ranges() is None:
        assert (lo, hi) == (0.0, 2 * math.pi)
        assert grid == pytest.approx((np.arange(7) + 0.5) * 2 * math.pi / 7, abs=1e-15)
    else:
        top = math.acos(1 - (lengths[2] + lengths[3]) ** 2 / (2 * lengths[0] ** 2))
        assert (lo, hi) == (pytest.approx(-top, abs=1e-12), pytest.approx(top, abs=1e-12))
        step = 2 * top / 6
        assert grid == pytest.approx([-top, -top + step, -top + 2 * step, -step / 2, step / 2, top - 2 * step,
                                      top - step, top], abs=1e-12)
    poses = fb.sweep(grid, "open")                        # every one of them is drawn
    assert np.degrees(poses.gamma) == pytest.approx(np.degrees(_deltoid_gamma(lengths, grid)), abs=1e-6)


@pytest.mark.parametrize("lengths", DELTOIDS)
def test_a_deltoids_figures_draw_round_its_fold(lengths):
    """The figures sweep every curve over the shared grid (they were refused at the fold, naming an 'angle' nobody
    gave): the transmission angle drawn is the law of cosines' at every crank angle it is drawn at, over the whole
    span; the rocker pin's path lies on its circle about O4."""
    from linkgen import plots

    fb = FourBar(*lengths)
    fig = plots.transmission_figure("t", fb, "open")
    curve = fig.axes[0].lines[0]
    x, y = np.radians(curve.get_xdata()), curve.get_ydata()
    assert len(x) >= 721 and np.all(np.diff(x) > 0)
    assert np.degrees(_deltoid_gamma(lengths, x)) == pytest.approx(y, abs=1e-6)
    span = (0.0, 2 * math.pi) if fb.input_ranges() is None else fb.input_ranges()[0]
    assert x[0] - span[0] <= 2 * math.pi / 721 and span[1] - x[-1] <= 2 * math.pi / 721
    assert np.abs(np.remainder(x + math.pi, 2 * math.pi) - math.pi).min() > 1e-4       # never on the fold
    fig = plots.dead_centre_figure("t", fb, "open")
    pin = np.column_stack([fig.axes[0].lines[1].get_xdata(), fig.axes[0].lines[1].get_ydata()])
    assert np.hypot(pin[:, 0] - lengths[0], pin[:, 1]) == pytest.approx(lengths[3], abs=1e-9)


@pytest.mark.parametrize("lengths", [*DELTOIDS, (20, 50, 60, 55)])
def test_deltoids_and_a_drag_link_analyze_and_build_every_file(tmp_path, lengths):
    """`linkgen analyze --figures` and `linkgen build` with every format, Python's warnings as errors: a deltoid's
    sweep passes its fold; a drag link (ground shortest) and the full-turn deltoids have no dead centre, so the STEP
    file stands the parts at the motion's first pose (it was a traceback, 'NoneType' has no attribute 'angles')."""
    import subprocess
    import sys

    from linkgen.parts import SWEEP

    path = tmp_path / "t.toml"
    body = "\n".join(f"{k} = {float(v)}" for k, v in zip(("ground", "crank", "coupler", "rocker"), lengths,
                                                          strict=True))
    path.write_text(f'name = "t"\n[linkage]\ntype = "four-bar"\n{body}\n[parts]\nwidth = 4.0\nthickness = 3.0\n'
                    'pin_diameter = 2.0\n')
    for args in (["analyze", "--figures"], ["build", "--set", "output.formats=['dxf', 'stl', 'step', 'json', 'png']"]):
        out = tmp_path / args[0]
        run = subprocess.run([sys.executable, "-W", "error", "-m", "linkgen", args[0], str(path), "-o", str(out),
                              *args[1:]], capture_output=True, text=True, cwd=ROOT)
        assert run.returncode == 0 and run.stderr == "", run.stderr
        assert (out / "t-transmission.png").exists() and (out / "t-dead-centres.png").exists()
    assert (tmp_path / "analyze" / "t-dead-centres.svg").exists() and (tmp_path / "build" / "t.step").exists()
    design = design_linkage(load_spec(path), parts=True)
    fb, pose = design.kinematics, design.build.pose
    if not fb.dead_centres("open"):                   # at the sweep's first angle: a full turn's first grid point
        first = math.pi / SWEEP if fb.folds()[0] and lengths[0] == lengths[1] else 0.0
        assert pose.angles["crank"][0] == pytest.approx(first, abs=1e-15)
        assert pose.joints["A"][1][0] == pytest.approx([lengths[1] * math.cos(first), lengths[1] * math.sin(first)],
                                                       abs=1e-12)
