"""Newton-Euler kinetostatics of linkages (``linkgen.kinematics.kinetostatics``), checked against what it must equal:
the energy method from the positions alone, virtual-work statics at rest, the balance of every link, the frame's
reactions, a slider-crank's classical harmonics and counterweight, and a flywheel's forward simulation."""
from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

from linkgen.bench import jansen
from linkgen.kinematics import equivalents
from linkgen.kinematics.balance import counterweight, fluctuation, flywheel_inertia
from linkgen.kinematics.fourbar import FourBar
from linkgen.kinematics.inertia import LinkMass, generalised_inertia, moving_links
from linkgen.kinematics import kinetostatics as kinetostatic
from linkgen.kinematics.kinetostatics import Loads, Spring, kinetostatics
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.quickreturn import CrankShaper, Whitworth
from linkgen.kinematics.slidercrank import SliderCrank
from linkgen.kinematics.statics import LinkTorque, PointForce, input_effort
from linkgen.kinematics.structure import GROUND, Input, make_structure
from linkgen.mechanisms.general import LinkageTable, structure_of
from linkgen.spec import load_spec
from tests.conftest import ROOT

#: 10th-order central first-derivative weights on offsets -5 .. 5 (times 1 / h)
D1 = np.array([-1 / 1260, 5 / 504, -5 / 84, 5 / 21, -5 / 6, 0.0, 5 / 6, -5 / 21, 5 / 84, -5 / 504, 1 / 1260])
OFFSETS = np.arange(-5, 6)


def _template_linkage(name: str) -> Linkage:
    spec = load_spec(ROOT / "templates" / f"{name}.toml")
    assert isinstance(spec.linkage, LinkageTable)
    return Linkage.of(structure_of(spec.linkage))


def _fourbar() -> Linkage:
    fb = FourBar(100.0, 30.0, 90.0, 70.0, point_distance=40.0, point_angle=math.radians(30.0))
    return Linkage.of(equivalents.fourbar(fb, 0.0))


def _slider_crank(offset: float = 12.0) -> Linkage:
    return Linkage.of(equivalents.slider_crank(SliderCrank(40.0, 130.0, offset), 0.0))


#: the issue's five, and a crank-shaper and a Whitworth (slides on turning guides), a slide-driven pump and an
#: eight-bar whose triad (a class-III group) is one block of twelve unknowns
LINKAGES = {"four-bar": _fourbar, "slider-crank": _slider_crank, "watt": lambda: _template_linkage("watt1"),
            "stephenson": lambda: _template_linkage("stephenson3"), "jansen": lambda: Linkage.of(jansen(0.0)),
            "crank-shaper": lambda: Linkage.of(equivalents.crank_shaper(CrankShaper(60.0, 150.0, 300.0), 0.3)),
            "whitworth": lambda: Linkage.of(equivalents.whitworth(Whitworth(40.0, 20.0, 60.0, 150.0), 0.3)),
            "pendulum-pump": lambda: _template_linkage("pendulum-pump"),
            "eightbar-triad": lambda: _template_linkage("eightbar-triad")}


def _inputs(linkage: Linkage, n: int, shift: float = 0.0) -> np.ndarray:
    """n input values over a crank's turn from its revolution's start (uniform, its end left out, moved by ``shift``
    of a step), or over 90 % of a slide's range."""
    if linkage.is_crank():
        return linkage.revolution + 2 * math.pi * (np.arange(n) + shift) / n
    lo, hi = linkage.ranges[0]
    pad = 0.05 * (hi - lo)
    return np.linspace(lo + pad, hi - pad, n)


def _speed(linkage: Linkage, rpm: float) -> float:
    """rpm as rad/s for a crank; a slide at rpm mm/s, in m/s."""
    return rpm * 2 * math.pi / 60 if linkage.is_crank() else rpm * 1e-3


def _masses(linkage: Linkage) -> dict[str, LinkMass]:
    """Every moving link a mass off its joints' line (so that no term of Newton-Euler is idle): 20 to 50 g, its
    centre a third of the way from its first joint and 4 mm to the side, an inertia of its own."""
    s = linkage.structure
    out = {}
    for k, body in enumerate(moving_links(s)):
        pts = np.array([s.points[p] for p in s.bodies[body]], dtype=float)
        centre = pts[0] + (pts[-1] - pts[0]) / 3 + np.array([4.0, -3.0])
        out[body] = LinkMass(0.02 + 0.01 * (k % 4), (float(centre[0]), float(centre[1])), 3.0 + 2.0 * k)
    return out


def _loads(linkage: Linkage) -> Loads:
    """Gravity down the drawing at 30 degrees to it, a force at a moving joint, a torque on the last link, and a
    spring from a ground joint to a moving one."""
    s = linkage.structure
    moving = [p for p in s.points if p not in s.bodies[GROUND]]
    last = moving_links(s)[-1]
    point = moving[-1]
    holder = next(b for b in s.holders(point) if b != GROUND)
    anchor = s.bodies[GROUND][0]
    free = 0.8 * math.dist(s.points[anchor], s.points[point])
    return Loads((2.0, -9.0), (PointForce(point, (3.0, -4.0)),), (LinkTorque(last, 0.05),),
                 (Spring(anchor, GROUND, point, holder, 0.02, free),))


def _energy_torque(linkage: Linkage, theta: np.ndarray, masses: dict[str, LinkMass], loads: Loads,
                   speed: float | Callable[[np.ndarray], np.ndarray], acceleration: float = 0.0,
                   h: float = 4e-3) -> np.ndarray:
    """The driving torque by the energy method from the positions alone: T = dE/dtheta - P' + J alpha, with E the
    kinetic energy at ``speed`` plus the potential energy of gravity and the springs, P' the loads' power per unit
    input speed and J = 2 KE / speed^2; every rate by 10th-order central differences of the solver's positions (no
    velocity or acceleration of the solver is used). A slide's values and steps are mm, its speed m/s and its
    effort N. ``speed`` may be a function of the input value (a speed that varies over the motion): E is then the
    kinetic energy at each differenced pose's own speed, whose change carries the acceleration (``acceleration``
    is left at 0)."""
    s = linkage.structure
    per = 1.0 if linkage.is_crank() else 1e-3          # the input's unit in SI
    grid = theta[:, None, None] + h * OFFSETS[None, :, None] + h * OFFSETS[None, None, :]
    sol = linkage.solve(grid.reshape(-1), derivatives=False)
    n = len(theta)

    def shaped(v: np.ndarray) -> np.ndarray:
        return v.reshape((n, len(OFFSETS), len(OFFSETS), *v.shape[1:]))

    def rate(v: np.ndarray) -> np.ndarray:            # d/dtheta along the inner offsets
        return np.tensordot(v, D1, axes=([2], [0])) / h if v.ndim == 3 else \
            np.einsum("nijk,j->nik", v, D1) / h

    def angle(body: str) -> np.ndarray:
        c, sn = sol.rotations[body]
        return np.unwrap(shaped(np.arctan2(sn, c)).reshape(n, -1), axis=1).reshape(n, len(OFFSETS), len(OFFSETS))

    kinetic = np.zeros((n, len(OFFSETS)))
    squared = np.square(speed(theta[:, None] + h * OFFSETS[None, :])) if callable(speed) else speed**2
    potential = np.zeros((n, len(OFFSETS)))
    for body, m in masses.items():
        first = s.bodies[body][0]
        d = np.subtract(m.centre, s.points[first])
        c, sn = sol.rotations[body]
        g = sol.points[first] + np.stack([c * d[0] - sn * d[1], sn * d[0] + c * d[1]], axis=-1)
        g = shaped(g)
        v = rate(g) * 1e-3 / per                               # m per unit input (SI) at the outer offsets
        w = rate(angle(body)) / per
        kinetic += 0.5 * squared * (m.mass * np.sum(v**2, axis=-1) + m.inertia * 1e-6 * w**2)
        potential -= m.mass * (g[:, :, 5] * 1e-3) @ np.asarray(loads.gravity)
    for sp in loads.springs:
        ends = [np.broadcast_to(np.asarray(s.points[p], dtype=float), (len(grid.reshape(-1)), 2)) if b == GROUND
                else sol.points[p] for p, b in ((sp.a, sp.on_a), (sp.b, sp.on_b))]
        length = shaped(np.hypot(*(ends[1] - ends[0]).T))[:, :, 5]
        potential += 0.5 * sp.stiffness * (length - sp.free_length) ** 2 * 1e-3
    power = np.zeros(n)
    for f in loads.forces:
        power += np.einsum("nj,j->n", rate(shaped(sol.points[f.point]))[:, 5] * 1e-3 / per, np.asarray(f.force))
    for t in loads.torques:
        power += t.torque * rate(angle(t.link))[:, 5] / per
    energy = kinetic + potential
    j = 2.0 * kinetic[:, 5] / speed**2 if speed and not callable(speed) else 0.0
    return energy @ D1 / (h * per) - power + j * acceleration


@pytest.mark.parametrize("name", sorted(LINKAGES))
def test_newton_euler_torque_is_the_energy_methods(name):
    """At 90 rpm, with gravity, a load, a torque and a spring: the Newton-Euler torque equals the energy method's
    at every one of 48 poses over the turn to 1e-8 of its peak; with an input acceleration too. (A slide input: its
    force, at 90 mm/s and 0.04 m/s^2.)"""
    linkage = LINKAGES[name]()
    masses, loads = _masses(linkage), _loads(linkage)
    theta = _inputs(linkage, 48, 0.3)
    speed = _speed(linkage, 90.0)
    sol = linkage.solve(theta)
    for acceleration in (0.0, 40.0 if linkage.is_crank() else 0.04):
        got = kinetostatics(linkage, sol, masses, speed, acceleration, loads).effort
        want = _energy_torque(linkage, theta, masses, loads, speed, acceleration,
                              4e-3 if linkage.is_crank() else 0.1)
        scale = np.abs(want).max()
        assert scale > 1e-3 and np.ptp(want) > 0.1 * scale          # a real, varying torque
        assert np.abs(got - want).max() <= 1e-8 * scale, (name, acceleration, np.abs(got - want).max() / scale)


@pytest.mark.parametrize("name", sorted(LINKAGES))
def test_at_rest_the_torque_is_virtual_work(name):
    """At zero speed, with massive links but no gravity, the torque holding a force and a torque is today's
    virtual-work statics (``linkgen.kinematics.statics``), to 1e-12 of its peak."""
    linkage = LINKAGES[name]()
    loads = _loads(linkage)
    held = Loads(forces=loads.forces, torques=loads.torques)
    sol = linkage.solve(_inputs(linkage, 181, 0.1))
    got = kinetostatics(linkage, sol, _masses(linkage), 0.0, 0.0, held).effort
    want = input_effort(sol, held.forces, held.torques, linkage.is_crank())
    assert np.abs(got - want).max() <= 1e-12 * np.abs(want).max()


@pytest.mark.parametrize("name", sorted(set(LINKAGES) - {"pendulum-pump"}))
def test_mean_torque_over_a_turn_is_zero(name):
    """No loads and no friction, at constant speed: the links' kinetic energy and their weights' and springs'
    potential come back after a turn, so the torque's mean over it is 0 to rounding (1e-12 of its peak)."""
    linkage = LINKAGES[name]()
    loads = _loads(linkage)
    theta = _inputs(linkage, 720)
    sol = linkage.solve(theta)
    for kept in (Loads(), Loads(loads.gravity, springs=loads.springs)):
        torque = kinetostatics(linkage, sol, _masses(linkage), 30.0, 0.0, kept).effort
        assert abs(torque.mean()) <= 1e-12 * np.abs(torque).max()


@pytest.mark.parametrize("name", sorted(LINKAGES))
def test_every_link_balances_and_the_frame_carries_the_shaking(name):
    """Each link's forces and moments, inertia included, add up (computed here from the solved forces) to 1e-9 of
    their terms; without gravity and loads the frame's reactions add up to the shaking force -sum m a_G and their
    moment to the shaking moment -sum (I alpha + r x m a); the stacked blocks give the whole system's solution."""
    linkage = LINKAGES[name]()
    s = linkage.structure
    masses = _masses(linkage)
    sol = linkage.solve(_inputs(linkage, 90))
    speed, acceleration = (25.0, -15.0) if linkage.is_crank() else (0.3, -0.5)
    k = kinetostatics(linkage, sol, masses, speed, acceleration, _loads(linkage))
    dense = kinetostatics(linkage, sol, masses, speed, acceleration, _loads(linkage), method="dense")
    assert np.abs(k.effort - dense.effort).max() <= 1e-12 * np.abs(k.effort).max()
    free = kinetostatics(linkage, sol, masses, speed, acceleration)
    for result, loads in ((k, _loads(linkage)), (free, Loads())):
        sums, sizes, inertial = _balance(linkage, sol, masses, speed, acceleration, loads, result)
        for body in moving_links(s):
            assert np.abs(sums[body] - inertial[body]).max(axis=1).max() <= 1e-9 * sizes[body].min()
    frame, moment = np.zeros((90, 2)), np.zeros(90)
    for pf in free.pairs:
        for body, sign in ((pf.pair.on, 1.0), (pf.pair.by, -1.0)):
            if body == GROUND:
                frame += sign * pf.force
                moment += sign * (_cross(pf.where * 1e-3, pf.force) + (0.0 if pf.couple is None else pf.couple))
    inp = s.inputs[0]
    if inp.kind == "crank":
        moment -= free.effort                              # the driver's reaction on the frame
    else:
        sl = s.slider_by_name[inp.slider]
        along = np.array([math.cos(sl.angle), math.sin(sl.angle)]) * free.effort[:, None]
        frame -= along
        moment -= _cross(sol.points[sl.point] * 1e-3, along)
    shaking, shaking_moment = np.zeros((90, 2)), np.zeros(90)
    _, _, inertial = _balance(linkage, sol, masses, speed, acceleration, Loads(), free)
    for body, m in masses.items():
        centre = _centre(linkage, sol, body, m)[0] * 1e-3
        shaking -= inertial[body][:, :2]
        shaking_moment -= inertial[body][:, 2] + _cross(centre, inertial[body][:, :2])
    scale = np.abs(shaking).max()
    assert scale > 0 and np.abs(frame - shaking).max() <= 1e-9 * scale
    assert np.abs(free.shaking_force - shaking).max() <= 1e-12 * scale
    assert np.abs(moment - shaking_moment).max() <= 1e-9 * np.abs(shaking_moment).max()


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _centre(linkage: Linkage, sol, body: str, m: LinkMass) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A link's centre (mm) and its velocity and acceleration per unit input, from the solver's rigid-body rates."""
    s = linkage.structure
    first = s.bodies[body][0]
    d = np.subtract(m.centre, s.points[first])
    c, sn = sol.rotations[body]
    r = np.stack([c * d[0] - sn * d[1], sn * d[0] + c * d[1]], axis=-1)
    w, al = sol.omegas[body], sol.alphas[body]
    k_r = np.stack([-r[:, 1], r[:, 0]], axis=-1)
    return (sol.points[first] + r, sol.velocities[first] + w[:, None] * k_r,
            sol.accelerations[first] + al[:, None] * k_r - (w**2)[:, None] * r)


def _balance(linkage, sol, masses, speed, acceleration, loads, result):
    """Each link's sum of forces and of moments about its centre (Fx, Fy, M), the size of their terms, and m a_G and
    I alpha, from the solved pair forces and the driver's effort, summed here."""
    s = linkage.structure
    n = sol.inputs.shape[1]
    sums = {b: np.zeros((n, 3)) for b in moving_links(s)}
    sizes = {b: np.zeros(n) for b in moving_links(s)}
    inertial, centres = {}, {}
    for body in moving_links(s):
        m = masses.get(body, LinkMass(0.0, s.points[s.bodies[body][0]], 0.0))
        g, v, a = _centre(linkage, sol, body, m)
        centres[body] = g * 1e-3
        per = 1.0 if linkage.is_crank() else 1e-3      # the input's unit in SI
        acc = (a * speed**2 / per**2 + v * acceleration / per) * 1e-3
        alpha = sol.alphas[body] * speed**2 / per**2 + sol.omegas[body] * acceleration / per
        inertial[body] = np.column_stack([m.mass * acc, m.inertia * 1e-6 * alpha])
        weight = np.tile(m.mass * np.asarray(loads.gravity), (n, 1))
        sums[body][:, :2] += weight
        sizes[body] += np.abs(inertial[body]).sum(axis=1) + np.abs(weight).sum(axis=1)

    def push(body, force, at, couple=0.0):
        if body == GROUND:
            return
        moment = _cross(at * 1e-3 - centres[body], force) + couple
        sums[body][:, :2] += force
        sums[body][:, 2] += moment
        sizes[body] += np.abs(force).sum(axis=1) + np.abs(moment)

    for pf in result.pairs:
        for body, sign in ((pf.pair.on, 1.0), (pf.pair.by, -1.0)):
            push(body, sign * pf.force, pf.where, 0.0 if pf.couple is None else sign * pf.couple)
    inp = s.inputs[0]
    if inp.kind == "crank":
        sums[inp.link][:, 2] += result.effort
    else:
        sl = s.slider_by_name[inp.slider]
        push(sl.body, np.array([math.cos(sl.angle), math.sin(sl.angle)]) * result.effort[:, None],
             sol.points[sl.point])
    for f in loads.forces:
        push(next(b for b in s.holders(f.point) if b != GROUND), np.tile(f.force, (n, 1)), sol.points[f.point])
    for t in loads.torques:
        sums[t.link][:, 2] += t.torque
    for sp in loads.springs:
        ends = [np.tile(s.points[p], (n, 1)) if b == GROUND else sol.points[p] for p, b in ((sp.a, sp.on_a),
                                                                                          (sp.b, sp.on_b))]
        d = ends[1] - ends[0]
        length = np.hypot(*d.T)
        pull = (sp.stiffness * (length - sp.free_length))[:, None] * d / length[:, None]
        push(sp.on_a, pull, ends[0])
        push(sp.on_b, -pull, ends[1])
    return sums, sizes, inertial


def _second_harmonic(lam: float) -> float:
    """The classical slider-crank's second-harmonic coefficient A2 = lam + lam^3/4 + 15 lam^5/128 + ...: the
    coefficient of cos 2 theta in -x_B'' / r (per unit crank speed) for x_B = r cos theta + L sqrt(1 - lam^2 sin^2
    theta), 4 L c2 / r with c2 the root's cos 2 theta coefficient, from the
    binomial series of the root (sin^2k theta's cos 2 theta term is -2^(1-2k) C(2k, k-1)), summed to rounding."""
    total, k = 0.0, 1
    while True:
        binom = math.prod(0.5 - j for j in range(k)) / math.factorial(k)
        term = binom * (-1) ** k * lam ** (2 * k) * -(2.0 ** (1 - 2 * k)) * math.comb(2 * k, k - 1)
        total += term
        if abs(term) < 1e-20:
            break
        k += 1
    return 4.0 * total / lam


def test_slider_crank_shaking_force_is_the_classical_harmonics():
    """A centred slider-crank (crank r = 40, rod L = 130 mm) at 300 rpm: with the rod as two lumped masses (m b/L at
    the crank pin, m a/L at the wrist pin), the shaking force across the guide is the rotating masses' exactly,
    (m2 rG + mA r) w^2 sin theta, and along it the primary harmonic (m2 rG + (mA + mB + m4) r) w^2 and the secondary
    (mB + m4) r w^2 A2 (A2 = lam + lam^3/4 + ...), to 1e-9; the counterweight is the rotating masses and half the
    reciprocating ones, m r = m2 rG + mA r + (mB + m4) r / 2, opposite the crank pin."""
    r, big_l = 40.0, 130.0
    linkage = _slider_crank(0.0)
    m2, r_g, m3, a_rod, m4 = 0.03, 12.0, 0.05, 50.0, 0.02
    masses = {"crank": LinkMass(m2, (r_g, 0.0), 4.0), "rod": LinkMass(m3, (r + a_rod, 0.0), 70.0),
              "slider": LinkMass(m4, (r + big_l, 0.0), 1.0)}      # drawn at theta = 0: A at (r, 0), B at (r + L, 0)
    n, w = 720, 300 * 2 * math.pi / 60
    theta = 2 * math.pi * np.arange(n) / n
    k = kinetostatics(linkage, linkage.solve(theta), masses, w, 0.0)
    ma, mb = m3 * (big_l - a_rod) / big_l, m3 * a_rod / big_l
    rotating = (m2 * r_g + ma * r) * 1e-3 * w**2
    reciprocating = (mb + m4) * r * 1e-3 * w**2
    fx, fy = k.shaking_force.T
    assert np.abs(fy - rotating * np.sin(theta)).max() <= 1e-9 * rotating
    spectrum = np.fft.rfft(fx) * 2 / n
    assert spectrum[1].real == pytest.approx(rotating + reciprocating, rel=1e-9)
    assert abs(spectrum[1].imag) <= 1e-9 * reciprocating
    assert spectrum[2].real == pytest.approx(reciprocating * _second_harmonic(r / big_l), rel=1e-9)
    assert abs(spectrum[2].imag) <= 1e-9 * reciprocating
    cw = counterweight(theta, k.shaking_force, w)
    assert cw.mass_radius * 1e3 == pytest.approx(m2 * r_g + ma * r + (mb + m4) * r / 2, rel=1e-9)
    assert math.cos(cw.angle) == pytest.approx(-1.0, abs=1e-12)
    assert cw.backward == pytest.approx(reciprocating / 2, rel=1e-9)          # what no crank's weight cancels
    assert cw.peak_after < cw.peak_before


def test_flywheel_meets_the_coefficient_in_a_forward_simulation():
    """The four-bar at 120 rpm with a load torque on its rocker, driven by a constant torque (its mean): the
    flywheel sized for Cs = 0.04 keeps (w_max - w_min) / w_mean within 1 % of 0.04 when the motion
    (J_total theta'' + J' theta'^2 / 2 = T - T_load) is integrated here with solve_ivp over several turns."""
    from scipy.integrate import solve_ivp
    from scipy.interpolate import CubicSpline

    linkage = _fourbar()
    masses = _masses(linkage)
    loads = Loads(torques=(LinkTorque("rocker", 0.08),))
    n = 720
    theta = 2 * math.pi * np.arange(n) / n
    sol = linkage.solve(theta)
    w0, cs = 120 * 2 * math.pi / 60, 0.04
    torque = kinetostatics(linkage, sol, masses, w0, 0.0, loads).effort
    fl = fluctuation(theta, torque)
    j, dj = generalised_inertia(linkage.structure, sol, masses)
    _, flywheel = flywheel_inertia(fl.energy, cs, w0, float(j.mean()))
    assert flywheel > 10 * j.mean()
    held = kinetostatics(linkage, sol, {}, 0.0, 0.0, loads).effort          # the load's torque at rest
    periodic = np.append(theta, 2 * math.pi)
    inertia = CubicSpline(periodic, np.append(j, j[0]) + flywheel, bc_type="periodic")
    rate = CubicSpline(periodic, np.append(dj, dj[0]), bc_type="periodic")
    load = CubicSpline(periodic, np.append(held, held[0]), bc_type="periodic")
    drive = fl.mean_torque

    def motion(_t, y):
        q, qd = y
        q = q % (2 * math.pi)
        return [qd, (drive - load(q) - 0.5 * rate(q) * qd**2) / inertia(q)]

    def run(start: float) -> np.ndarray:
        out = solve_ivp(motion, (0.0, 6 * 2 * math.pi / w0), [0.0, start], rtol=1e-10, atol=1e-12,
                        max_step=0.01, dense_output=True)
        t = np.linspace(out.t[-1] / 3, out.t[-1], 20001)
        return out.sol(t)[1]

    start = w0
    for _ in range(4):                       # the start speed that makes the mean speed w0 (a steady turn)
        w = run(start)
        start *= w0 / (0.5 * (w.max() + w.min()))
    w = run(start)
    mean = 0.5 * (w.max() + w.min())
    assert mean == pytest.approx(w0, rel=1e-4)
    assert (w.max() - w.min()) / mean == pytest.approx(cs, rel=0.01)


@pytest.mark.parametrize("name", sorted(LINKAGES))
def test_the_torque_is_the_equation_of_motions_terms(name):
    """What forward dynamics will integrate: the Newton-Euler effort at any speed and acceleration is
    J(q) qddot + 1/2 J'(q) qdot^2 plus the effort at rest (weights, springs, loads), with J and J' of
    :func:`generalised_inertia`, to 1e-12 of its peak, with one speed and acceleration for all the poses or one of
    each a pose (and a pose alone gives the same forces); and J' is the derivative of J along the motion (10th-order
    central differences of J at the neighbouring poses, 1e-10)."""
    linkage = LINKAGES[name]()
    s = linkage.structure
    masses, loads = _masses(linkage), _loads(linkage)
    theta = _inputs(linkage, 60, 0.2)
    sol = linkage.solve(theta)
    j, dj = generalised_inertia(s, sol, masses)
    rest = kinetostatics(linkage, sol, masses, 0.0, 0.0, loads).effort
    speed, acceleration = (20.0, -35.0) if linkage.is_crank() else (0.2, 0.6)
    got = kinetostatics(linkage, sol, masses, speed, acceleration, loads).effort
    want = j * acceleration + 0.5 * dj * speed**2 + rest
    assert np.ptp(j) > 0.05 * j.mean() > 0                               # an inertia that varies over the motion
    assert np.abs(got - want).max() <= 1e-12 * np.abs(got).max()
    # a speed and an acceleration of their own at each pose (a motion speeding up and slowing down)
    speeds = speed * (1.0 + 0.5 * np.sin(np.arange(60)))
    accelerations = acceleration * np.cos(0.3 * np.arange(60))
    varying = kinetostatics(linkage, sol, masses, speeds, accelerations, loads)
    want = j * accelerations + 0.5 * dj * speeds**2 + rest
    assert np.abs(varying.effort - want).max() <= 1e-12 * np.abs(want).max()
    assert np.abs(varying.power - varying.effort * speeds).max() == 0.0
    for i in (0, 17, 59):                                               # each pose as if alone at its own rates
        alone = kinetostatics(linkage, linkage.solve(theta[i:i + 1]), masses, float(speeds[i]),
                              float(accelerations[i]), loads)
        assert alone.effort[0] == pytest.approx(varying.effort[i], rel=1e-12, abs=1e-15)
        for a, b in zip(alone.pairs, varying.pairs, strict=True):
            assert a.force[0] == pytest.approx(b.force[i], rel=1e-12, abs=1e-12)
    with pytest.raises(ValueError, match="speed: give one value or one a pose"):
        kinetostatics(linkage, sol, masses, speeds[:10], 0.0, loads)
    h = 4e-3 if linkage.is_crank() else 0.1                             # rad, or mm of a slide
    per = 1.0 if linkage.is_crank() else 1e-3
    near = linkage.solve((theta[:, None] + h * OFFSETS[None, :]).reshape(-1))
    j_near = generalised_inertia(s, near, masses)[0].reshape(len(theta), len(OFFSETS))
    assert np.abs(j_near @ D1 / (h * per) - dj).max() <= 1e-10 * np.abs(dj).max()


#: the linkages with RRR dyads (blocks of three pins: the closed form takes them); the others have none
PINNED = ("eightbar-triad", "four-bar", "jansen", "pendulum-pump", "stephenson", "watt")


@pytest.mark.parametrize("name", sorted(LINKAGES))
def test_every_pairs_force_by_blocks_is_the_whole_systems(name, monkeypatch):
    """The blocks' solution (an RRR dyad's in closed form, the rest by stacked solves) against the whole system
    solved at once (one stacked LU solve of every unknown): every pair's force and the effort to 1e-10 of the
    largest. The closed form is taken wherever the dyads are pins, and only there."""
    taken: list[int] = []
    original = kinetostatic._pinned_dyad

    def counted(*args):
        found = original(*args)
        taken.append(found is not None)
        return found

    monkeypatch.setattr(kinetostatic, "_pinned_dyad", counted)
    linkage = LINKAGES[name]()
    sol = linkage.solve(_inputs(linkage, 120, 0.37))
    masses, loads = _masses(linkage), _loads(linkage)
    speed, acceleration = (25.0, -15.0) if linkage.is_crank() else (0.3, -0.5)
    blocks = kinetostatics(linkage, sol, masses, speed, acceleration, loads)
    dense = kinetostatics(linkage, sol, masses, speed, acceleration, loads, method="dense")
    scale = max(np.abs(pf.force).max() for pf in dense.pairs)
    for ours, whole in zip(blocks.pairs, dense.pairs, strict=True):
        assert np.abs(ours.force - whole.force).max() <= 1e-10 * scale, ours.pair.name
    assert np.abs(blocks.effort - dense.effort).max() <= 1e-10 * np.abs(dense.effort).max()
    assert (any(taken) and all(taken)) if name in PINNED else not any(taken), taken


def test_near_a_dyads_toggle_its_block_is_solved_whole():
    """A four-bar drawn at its coupler and rocker's toggle (crank O2-A 10 mm pointing away from the rocker's
    pivot, coupler 50 + rocker 20 = the 70 mm between A and O4): at the toggle and 1e-12 and 1e-9 rad from it the
    lines' cross product is rounding's, so those poses' block is the whole 6 x 6 solve (forces over 1e60 N, within
    1e-3 of the whole system's, whose rounding they are); 0.3 rad away the closed form, within 1e-12 of it. At the
    toggle every force and the effort are +inf, never NaN, as the whole system's solve gives them."""
    linkage = Linkage.of(make_structure({"O2": (0.0, 0.0), "O4": (60.0, 0.0), "A": (-10.0, 0.0), "B": (40.0, 0.0)},
                                        {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("O4", "B")},
                                        ("O2", "O4"), (), (Input("crank", "crank", "O2"),)))
    masses = {"crank": LinkMass(0.02, (5.0, 1.0), 3.0), "coupler": LinkMass(0.03, (15.0, 2.0), 4.0),
              "rocker": LinkMass(0.04, (50.0, -1.0), 5.0)}
    sol = linkage.solve(math.pi + np.array([0.0, 1e-12, -1e-9, 0.3]))
    with np.errstate(all="ignore"):                   # the toggle's own pose: infinite rates, as before
        blocks = kinetostatics(linkage, sol, masses, 10.0, 0.0, Loads((0.0, -9.81)))
        dense = kinetostatics(linkage, sol, masses, 10.0, 0.0, Loads((0.0, -9.81)), method="dense")
    for ours, whole in zip(blocks.pairs, dense.pairs, strict=True):
        near, far = ours.force[1:3], whole.force[1:3]
        assert np.all(np.abs(near) > 1e60) and np.allclose(near, far, rtol=1e-3), ours.pair.name
        assert np.abs(ours.force[3] - whole.force[3]).max() <= 1e-12 * np.abs(whole.force[3]).max()
        assert np.isposinf(ours.force[0]).all() and np.isposinf(whole.force[0]).all(), ours.pair.name
    assert np.isposinf(blocks.effort[0]) and np.isposinf(dense.effort[0])
