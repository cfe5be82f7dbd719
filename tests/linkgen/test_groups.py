"""Class-III groups (a triad: a ternary plate held by three bars) solved by Newton's method with continuation.

Each reference is independent of linkgen's solver: the plate's pose (phi, Tx, Ty) from three distance equations
(or a distance replaced by the plate's point on a slider's line) solved by ``mpmath.findroot`` in 50 digits,
continued from the drawing input by input; the four-bar that drives the eight-bar's triad by circle intersection in
50 digits. A toggle of the group is where those three equations' Jacobian is singular: found by ``findroot`` on
the equations and that determinant, and checked to be the configuration that makes it one (the three bars' lines
meet at a point).
"""
from __future__ import annotations

import dataclasses
import math

import mpmath as mp
import numpy as np
import pytest

from linkgen.kinematics import motion
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.structure import GroupStep, Input, Slider, make_structure
from tests.conftest import ROOT

CRANK = (Input("crank", "crank", "O"),)
#: the six-bar of a crank and a triad: the plate P-Q-R held by bars from the crank pin A and the ground G2, G3
SIX = {"O": (0.0, 0.0), "G2": (120.0, 0.0), "G3": (60.0, -80.0), "A": (20.0, 15.0), "P": (40.0, 70.0),
       "Q": (90.0, 60.0), "R": (70.0, 30.0)}
SIX_LINKS = {"crank": ("O", "A"), "bar1": ("A", "P"), "plate": ("P", "Q", "R"), "bar2": ("G2", "Q"),
             "bar3": ("G3", "R")}


def _eightbar() -> Linkage:
    import linkgen

    return linkgen.design_linkage(linkgen.load_spec(ROOT / "templates" / "eightbar-triad.toml")).kinematics.linkage


def _mp(xy) -> mp.matrix:
    return mp.matrix([mp.mpf(float(xy[0])), mp.mpf(float(xy[1]))])


def _turn(phi, v) -> mp.matrix:
    return mp.matrix([mp.cos(phi) * v[0] - mp.sin(phi) * v[1], mp.sin(phi) * v[0] + mp.cos(phi) * v[1]])


def _plate_equations(drawn: dict, plate: tuple[str, str, str], anchors: list):
    """The plate's three closure equations in (phi, Tx, Ty): for each of its points, ``("bar", K)`` its distance
    to the world point K (mp) equals the drawing's, ``("line", n)`` it stays on the line through its drawn place
    with normal n (a slider's guide on the ground)."""
    def equations(phi, tx, ty):
        out = []
        for name, (kind, k) in zip(plate, anchors, strict=True):
            p = _mp(drawn[name])
            w = _turn(phi, p) + mp.matrix([tx, ty])
            if kind == "bar":
                target, home = k
                out.append(mp.norm(w - target) ** 2 - mp.norm(p - home) ** 2)
            else:
                out.append(k[0] * (w[0] - p[0]) + k[1] * (w[1] - p[1]))
        return out
    return equations


def _continue(equations, anchors_at, xs, start=(0, 0, 0)):
    """The plate's pose at each input of xs (continued from ``start`` at xs[0]), 50 digits."""
    poses, guess = [], [mp.mpf(v) for v in start]
    for x in xs:
        guess = list(mp.findroot(equations(anchors_at(x)), guess, tol=mp.mpf(10) ** -45))
        poses.append(guess)
    return poses


@pytest.fixture(scope="module")
def eightbar() -> Linkage:
    return _eightbar()


def _fourbar_c(lk: Linkage, theta):
    """The eight-bar's coupler point C at crank angle theta (mp): the crank-rocker by circle intersection on the
    drawn side."""
    p = {k: _mp(v) for k, v in lk.structure.points.items()}
    a = mp.matrix([20 * mp.cos(theta), 20 * mp.sin(theta)])
    d = p["O4"] - a
    dist = mp.norm(d)
    along = (70**2 - 50**2 + dist**2) / (2 * dist)
    u = d / dist
    b = a + along * u + mp.sqrt(70**2 - along**2) * mp.matrix([-u[1], u[0]])   # the drawing's side: left of A->O4
    turn = mp.atan2((b - a)[1], (b - a)[0]) - mp.atan2((p["B"] - p["A"])[1], (p["B"] - p["A"])[0])
    return a + _turn(turn, p["C"] - p["A"])


def test_the_eightbar_plans_its_triad_as_one_group(eightbar):
    groups = [s for s in eightbar.plan.steps if isinstance(s, GroupStep)]
    assert len(groups) == 1 and groups[0].kind == "triad"
    assert set(groups[0].bodies) == {"bar1", "bar2", "bar3", "triad"}
    assert groups[0].joints == ("C", "E", "F", "G", "O6", "O8")
    assert eightbar.plan.mobility == 1 and not eightbar.plan.redundant
    assert eightbar.ranges is None                          # the crank turns fully: the triad never locks


def test_the_eightbar_against_a_50_digit_solution_at_200_inputs(eightbar):
    mp.mp.dps = 50
    s = eightbar.structure
    x0 = float(eightbar.drawn_inputs[0])
    xs = x0 + 2 * math.pi * np.arange(200) / 200
    drawn = s.points
    plate = ("E", "F", "G")

    def equations(c):
        return _plate_equations(drawn, plate, [("bar", (c, _mp(drawn["C"]))), ("bar", (_mp(drawn["O6"]),
                                               _mp(drawn["O6"]))), ("bar", (_mp(drawn["O8"]), _mp(drawn["O8"])))])

    poses = _continue(equations, lambda x: _fourbar_c(eightbar, mp.mpf(float(x))), xs)
    sol = eightbar.solve(xs)
    worst = 0.0
    for k, (phi, tx, ty) in enumerate(poses):
        for name in plate:
            ref = _turn(phi, _mp(drawn[name])) + mp.matrix([tx, ty])
            worst = max(worst, float(mp.norm(ref - _mp(sol.points[name][k]))))
    assert worst <= 1e-9
    assert float(mp.norm(_fourbar_c(eightbar, mp.mpf(x0)) - _mp(drawn["C"]))) < 1e-8   # the reference's drawing


def test_the_eightbar_branch_is_continuous(eightbar):
    """Neighbouring inputs 0.1 degree apart: no group point moves further than its speed and acceleration allow
    over the step (another assembly would be tens of mm away)."""
    x = float(eightbar.drawn_inputs[0]) + np.radians(np.arange(3601) / 10.0)
    sol = eightbar.solve(x)
    h = float(x[1] - x[0])
    for name in ("E", "F", "G"):
        step = np.hypot(*np.diff(sol.points[name], axis=0).T)
        speed = np.maximum(np.hypot(*sol.velocities[name][:-1].T), np.hypot(*sol.velocities[name][1:].T))
        acc = np.hypot(*sol.accelerations[name].T).max()
        assert np.all(step <= h * speed + 0.5 * h * h * acc + 1e-9)
        assert step.max() > 0.01 and speed.max() > 1.0      # it moves: the bound is not vacuous


def test_the_track_refined_from_a_coarse_walk_is_the_step_by_step_walk(monkeypatch):
    """The eight-bar's track (a crank's turn in 180 steps) found by a coarse walk and one vectorised solve of every
    step is the step-by-step walk's: the same inputs, each pose to 1e-10 (rad and mm), and the solution at 3,600
    inputs to 1e-11 mm; the refinement is taken (not refused and walked again), at a fraction of the walk's Newton
    solves; its drawing moved by up to 0.3 mm (a slack sample: its own track, not the nominal's)."""
    from linkgen.kinematics import groups

    calls = {"newton": 0, "refined": 0}
    newton, refined = groups.newton, groups._refined

    def counted(*args, **kwargs):
        calls["newton"] += 1
        return newton(*args, **kwargs)

    def spied(*args, **kwargs):
        out = refined(*args, **kwargs)
        calls["refined"] += out is not None
        return out

    monkeypatch.setattr(groups, "newton", counted)
    monkeypatch.setattr(groups, "_refined", spied)
    base = _eightbar()
    rng = np.random.default_rng(4)
    moved = {k: (x + rng.uniform(-0.3, 0.3), y + rng.uniform(-0.3, 0.3)) for k, (x, y) in base.structure.points.items()}
    for points in (base.structure.points, moved):
        structure = dataclasses.replace(base.structure, points=points)
        x = float(Linkage.of(structure).drawn_inputs[0]) + np.radians(np.arange(3600) / 10.0)
        solved, newtons = {}, {}
        for way in ("refined", "walked"):
            if way == "walked":
                monkeypatch.setattr(groups, "_refined", lambda *args, **kwargs: None)
            calls.update(newton=0, refined=0)
            linkage = Linkage.of(structure)
            solved[way] = linkage.solve(x, derivatives=False)
            [track] = linkage.tracks.values()
            solved[way + " track"] = track
            newtons[way] = calls["newton"]
            assert calls["refined"] == (way == "refined")
        monkeypatch.setattr(groups, "_refined", spied)
        a, b = solved["refined track"], solved["walked track"]
        assert np.array_equal(a.xs, b.xs) and a.stopped == b.stopped == (False, False)
        assert np.max(np.abs(a.qs - b.qs)) <= 1e-10
        for name in ("E", "F", "G"):
            assert np.max(np.abs(solved["refined"].points[name] - solved["walked"].points[name])) <= 1e-11
        assert newtons["refined"] * 3 <= newtons["walked"], newtons


def test_the_eightbar_rates_against_finite_differences(eightbar):
    x = float(eightbar.drawn_inputs[0]) + np.radians(np.arange(0.0, 360.0, 17.0))
    h = 1e-5
    sol, up, down = (eightbar.solve(x + d) for d in (0.0, h, -h))
    for name in ("E", "F", "G", "C"):
        fd_v = (up.points[name] - down.points[name]) / (2 * h)
        fd_a = (up.velocities[name] - down.velocities[name]) / (2 * h)
        scale_v, scale_a = np.abs(sol.velocities[name]).max(), np.abs(sol.accelerations[name]).max()
        assert np.abs(sol.velocities[name] - fd_v).max() <= 1e-6 * scale_v
        assert np.abs(sol.accelerations[name] - fd_a).max() <= 1e-6 * scale_a
    turn = np.unwrap(np.stack([up.angle("triad"), down.angle("triad")]), axis=0)
    assert np.abs(sol.omegas["triad"] - (turn[0] - turn[1]) / (2 * h)).max() <= 1e-6 * np.abs(sol.omegas["triad"]).max()
    fd_al = (up.omegas["triad"] - down.omegas["triad"]) / (2 * h)
    assert np.abs(sol.alphas["triad"] - fd_al).max() <= 1e-6 * np.abs(sol.alphas["triad"]).max()


def _six_anchors(theta):
    a = mp.matrix([25 * mp.cos(theta), 25 * mp.sin(theta)])            # the crank pin A: |OA| = 25 mm
    return a


def _six_equations(a):
    return _plate_equations(SIX, ("P", "Q", "R"), [("bar", (a, _mp(SIX["A"]))), ("bar", (_mp(SIX["G2"]),
                                                   _mp(SIX["G2"]))), ("bar", (_mp(SIX["G3"]), _mp(SIX["G3"])))])


def test_a_toggle_of_the_triad_is_found_where_its_bars_meet_at_a_point():
    """The six-bar's crank cannot turn fully: the triad locks where its closure's Jacobian is singular. The 50-digit
    fold (the three equations and their determinant zero, in theta, phi, Tx, Ty) lies where the three bars' lines
    meet at one point, and linkgen's toggles are within 1e-6 degree of it, named as the group's."""
    mp.mp.dps = 50
    lk = Linkage.of(make_structure(SIX, SIX_LINKS, ("O", "G2", "G3"), (), CRANK))
    toggles = motion.toggles(lk)
    assert [t.kind for t in toggles] == ["limit", "limit"]
    assert all(t.bodies == ("bar1", "plate", "bar2", "bar3") and t.joint == "A, G2, G3, P, Q, R" for t in toggles)
    assert lk.ranges is not None and len(lk.ranges) == 1
    for t in toggles:
        at = lk.solve([t.value], strict=False)
        q = at.points["P"][0], at.points["Q"][0]
        phi0 = math.atan2(*(np.subtract(q[1], q[0])[::-1])) - math.atan2(SIX["Q"][1] - SIX["P"][1],
                                                                           SIX["Q"][0] - SIX["P"][0])
        c, s = math.cos(phi0), math.sin(phi0)
        t0 = at.points["P"][0] - np.array([c * SIX["P"][0] - s * SIX["P"][1], s * SIX["P"][0] + c * SIX["P"][1]])

        def fold(theta, phi, tx, ty):
            f = _six_equations(_six_anchors(theta))
            rows = []           # d|w - K|^2 / d(phi, Tx, Ty) = 2 (w - K) . (perp(R p), 1, 1)
            for name, k in zip(("P", "Q", "R"), (_six_anchors(theta), _mp(SIX["G2"]), _mp(SIX["G3"])), strict=True):
                r = _turn(phi, _mp(SIX[name]))
                d = r + mp.matrix([tx, ty]) - k
                rows.append([2 * (-d[0] * r[1] + d[1] * r[0]), 2 * d[0], 2 * d[1]])
            return [*f(phi, tx, ty), mp.det(mp.matrix(rows)) / mp.mpf(10) ** 6]

        root = mp.findroot(fold, [mp.mpf(t.value), mp.mpf(phi0), mp.mpf(float(t0[0])), mp.mpf(float(t0[1]))],
                           tol=mp.mpf(10) ** -40)
        assert abs(math.degrees(float(root[0]) - t.value)) <= 1e-6
        # built so: at the fold the bars' lines A-P, G2-Q, G3-R are concurrent
        a = _six_anchors(root[0])
        world = {n: _turn(root[1], _mp(SIX[n])) + mp.matrix([root[2], root[3]]) for n in ("P", "Q", "R")}
        lines = [(a, world["P"]), (_mp(SIX["G2"]), world["Q"]), (_mp(SIX["G3"]), world["R"])]
        (p1, d1), (p2, d2) = [(u, v - u) for u, v in lines[:2]]
        cross = d1[0] * d2[1] - d1[1] * d2[0]
        k = ((p2 - p1)[0] * d2[1] - (p2 - p1)[1] * d2[0]) / cross
        meet = p1 + k * d1
        p3, q3 = lines[2]
        d3 = q3 - p3
        off = abs(d3[0] * (meet - p3)[1] - d3[1] * (meet - p3)[0]) / mp.norm(d3)
        assert off < mp.mpf(10) ** -30


def test_a_triad_with_a_slider_against_a_50_digit_solution():
    """The six-bar's third bar replaced by a block on a ground guide at 30 degrees through R (a class-III group
    with a prismatic joint): the plate against findroot in 50 digits over its range, and its rates against finite
    differences."""
    mp.mp.dps = 50
    links = {k: v for k, v in SIX_LINKS.items() if k != "bar3"}
    pts = {k: v for k, v in SIX.items() if k != "G3"}
    guide = math.radians(30.0)
    lk = Linkage.of(make_structure(pts, links, ("O", "G2"), (Slider("block", "R", "ground", guide),), CRANK))
    assert [s.kind for s in lk.plan.steps if isinstance(s, GroupStep)] == ["triad"]
    hi = lk.ranges[0][1] if lk.ranges else lk.revolution + 2 * math.pi
    x0 = float(lk.drawn_inputs[0])
    ahead = np.linspace(x0, hi - 1e-3, 60)
    normal = mp.matrix([-mp.sin(mp.mpf(guide)), mp.cos(mp.mpf(guide))])

    def equations(a):
        return _plate_equations(pts, ("P", "Q", "R"), [("bar", (a, _mp(pts["A"]))),
                                                       ("bar", (_mp(pts["G2"]), _mp(pts["G2"]))), ("line", normal)])

    poses = _continue(equations, lambda x: _six_anchors(mp.mpf(float(x))), ahead)
    sol = lk.solve(ahead)
    worst = max(float(mp.norm(_turn(phi, _mp(pts[n])) + mp.matrix([tx, ty]) - _mp(sol.points[n][k])))
                for k, (phi, tx, ty) in enumerate(poses) for n in ("P", "Q", "R"))
    assert worst <= 1e-9
    h = 1e-5
    x = ahead[5:-5:7]
    mid, up, down = (lk.solve(x + d) for d in (0.0, h, -h))
    for name in ("P", "Q", "R"):
        assert np.abs(mid.velocities[name] - (up.points[name] - down.points[name]) / (2 * h)).max() <= 1e-6 * max(
            1.0, np.abs(mid.velocities[name]).max())
        assert np.abs(mid.accelerations[name] - (up.velocities[name] - down.velocities[name]) / (2 * h)).max() <= (
            1e-6 * max(1.0, np.abs(mid.accelerations[name]).max()))


def _xy(k) -> tuple[float, float]:
    return (float(k[0]), float(k[1]))


def _built_at(theta_deg: float, drawn_deg: float) -> dict:
    """A crank and triad drawn so that the triad locks at crank angle ``theta_deg``: there the plate P-Q-R's bars
    A-P, G2-Q and G3-R lie on three lines through one point (Pc), which makes the closure's Jacobian singular; the
    drawing is that linkage continued in 50 digits (findroot, degree by degree) to ``drawn_deg``."""
    mp.mp.dps = 50
    th = mp.radians(theta_deg)
    a = mp.matrix([25 * mp.cos(th), 25 * mp.sin(th)])
    pc, q, r = mp.matrix([35, 140]), mp.matrix([60, 90]), mp.matrix([40, 50])
    p = a + (pc - a) / 2                                  # P on the line A-Pc, Q and R on lines through Pc
    g2, g3 = pc + mp.mpf("2.2") * (q - pc), pc + mp.mpf("1.9") * (r - pc)
    plate, lengths = (p, q, r), (mp.norm(p - a), mp.norm(q - g2), mp.norm(r - g3))

    def equations(theta):
        ks = (mp.matrix([25 * mp.cos(theta), 25 * mp.sin(theta)]), g2, g3)
        return lambda phi, tx, ty: [mp.norm(_turn(phi, x) + mp.matrix([tx, ty]) - k) ** 2 - ln**2
                                    for x, k, ln in zip(plate, ks, lengths, strict=True)]

    step = 1 if drawn_deg > theta_deg else -1
    jac = mp.jacobian(lambda u, v, w: equations(th)(u, v, w), [0, 0, 0])
    assert abs(mp.det(jac)) < mp.mpf(10) ** -10              # singular at the built pose
    _, _, vt = mp.svd_r(jac)
    guess = [mp.mpf("0.05") * vt[2, k] for k in range(3)]    # off the fold along its null direction
    for deg in range(int(theta_deg) + step, int(drawn_deg) + step, step):
        guess = list(mp.findroot(equations(mp.radians(deg)), guess, tol=mp.mpf(10) ** -40))
    phi, tx, ty = guess

    def world(x):
        w = _turn(phi, x) + mp.matrix([tx, ty])
        return (float(w[0]), float(w[1]))

    d = mp.radians(drawn_deg)
    return {"O": (0.0, 0.0), "A": (float(25 * mp.cos(d)), float(25 * mp.sin(d))), "G2": _xy(g2),
            "G3": _xy(g3), "P": world(p), "Q": world(q), "R": world(r)}


def test_a_toggle_built_at_100_degrees_is_found_there():
    """The triad built to lock at crank angle 100 degrees, drawn at 115: linkgen's range ends at 100 degrees within
    1e-6 degree, a 'limit' of the group."""
    pts = _built_at(100.0, 115.0)
    lk = Linkage.of(make_structure(pts, SIX_LINKS, ("O", "G2", "G3"), (), CRANK))
    near = [t for t in motion.toggles(lk) if abs(math.remainder(math.degrees(t.value) - 100.0, 360.0)) < 1.0]
    assert len(near) == 1 and near[0].kind == "limit" and near[0].bodies == ("bar1", "plate", "bar2", "bar3")
    assert abs(math.remainder(math.degrees(near[0].value) - 100.0, 360.0)) <= 1e-6
    assert any(abs(math.remainder(math.degrees(lo) - 100.0, 360.0)) <= 1e-6 for lo, _ in lk.ranges)
    sol = lk.solve([math.radians(100.5)], strict=False)
    assert sol.ok.all() and not lk.solve([math.radians(99.5)], strict=False).ok.any()
