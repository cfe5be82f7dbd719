"""Kinetostatics: every joint's force, the driver's effort and the frame's shaking, with the links' inertia, at a
given input speed and acceleration (Newton-Euler, vectorised over the poses; pure numpy).

Each moving link obeys Newton-Euler: the forces on it add up to m a_G and their moments about G to I_G alpha. The
unknowns are the forces the linkage's constraints carry, one pair of bodies at a time as the solve order uses them
(:func:`pairs_of`): at a pin, the force (x, y) on one body from the other; at a slide, the force along the guide's
normal, through the sliding point, and the couple; and the driver's effort (a torque on a crank, a force along a
slide input's guide). A linkage of one input and no redundant constraint has as many unknowns as equations, three a
link: one linear system a pose (:func:`system`). Its unknowns fall into the solve order's steps (the input, then a
dyad or a class-III group at a time), each step's bodies held only by its own unknowns and the steps placed after
it, so the system is block-triangular: :func:`kinetostatics` solves it a step at a time from the last
(``np.linalg.solve`` on the stacked 3x3 and 6x6 blocks of all poses at once, 12x12 for a triad), or whole
(``method="dense"``, the same system in one stacked solve).

Units and signs: SI throughout (N, N*m, kg, m, s) but positions, given in the drawing's frame in mm. Forces are in the
drawing's frame (x, y); moments and torques counter-clockwise. A pair's force is the force on its ``on`` body from
its ``by`` body (its ``by`` body feels the opposite). A crank's effort is the torque on the input link from the link
it is measured from (the frame, usually); a slide input's the force on its sliding link along the guide's direction.
Gravity is a vector in the plane (m/s^2); loads are forces at joints (on the joint's first moving holder) and torques
on links; springs pull their two points together with k (L - L0) (a push where negative).

The inertia is the links': at input speed qdot and acceleration qddot, a_G = a_G' qdot^2 + v_G' qddot with v_G',
a_G' the velocity and acceleration per unit input speed (:mod:`linkgen.kinematics.inertia`). The shaking force is
-sum m a_G, what the links' inertia puts on the frame; the shaking moment -sum (I_G alpha + r_G x m a_G) about the
drawing's origin. The frame's joint reactions (the forces the linkage puts on the frame through its joints and the
driver's reaction) add up to the shaking force plus the weights, the loads and the springs' pulls on the links.
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics.dyads import cross, perp
from linkgen.kinematics.inertia import MM, LinkMass, centre_motion, input_scale, moving_links
from linkgen.kinematics.linkage import Linkage, Solution
from linkgen.kinematics.statics import LinkTorque, PointForce
from linkgen.kinematics.structure import GROUND, DyadStep, GroupStep, InputStep, Pin, Structure

#: standard gravity (m/s^2)
G0 = 9.80665
#: an input's speed or acceleration: one for every pose, or an array of one a pose
Rate = float | np.ndarray


@dataclass(frozen=True)
class Spring:
    """A spring between joint ``a`` on link ``on_a`` and joint ``b`` on link ``on_b`` (either may be the ground):
    stiffness ``stiffness`` (N/mm), free length ``free_length`` (mm); it pulls its ends together with
    k (L - L0) N (pushes them apart where L < L0)."""

    a: str
    on_a: str
    b: str
    on_b: str
    stiffness: float
    free_length: float


@dataclass(frozen=True)
class Pair:
    """A constraint between two bodies as the solve order uses it: a ``pin`` at joint ``point`` (unknowns: the force
    x, y on ``on`` from ``by``), or a ``slide`` of slider ``slider`` (unknowns: the force along the guide's normal
    through the sliding point ``point``, and the couple, on the sliding body ``on`` from the guide ``by``). ``step``
    is the index of the solve order's step that places it."""

    kind: Literal["pin", "slide"]
    point: str
    by: str
    on: str
    step: int
    slider: str = ""

    @property
    def name(self) -> str:
        """``joint by-on`` (a pin) or ``slider by-on`` (a slide)."""
        return f"{self.slider or self.point} {self.by}-{self.on}"


@dataclass(frozen=True)
class Loads:
    """What acts on the links beyond the joints and the driver: gravity in the plane (gx, gy; m/s^2), forces at
    joints, torques on links and springs."""

    gravity: tuple[float, float] = (0.0, 0.0)
    forces: tuple[PointForce, ...] = ()
    torques: tuple[LinkTorque, ...] = ()
    springs: tuple[Spring, ...] = ()


@dataclass(frozen=True)
class PairForce:
    """A pair's force over the poses: ``force`` (n, 2) N on ``pair.on`` from ``pair.by`` in the drawing's frame,
    acting at ``where`` (n, 2) mm; for a slide also ``couple`` (n,) N*m and ``normal`` (n,) N, the force along the
    guide's normal (k x the guide's direction)."""

    pair: Pair
    force: np.ndarray
    where: np.ndarray
    couple: np.ndarray | None = None
    normal: np.ndarray | None = None


@dataclass(frozen=True)
class Kinetostatics:
    """Newton-Euler over the poses (see the module's note for units and signs).

    Attributes
    ----------
    inputs : ndarray
        The input's values (n,): rad (a crank) or mm (a slide).
    speed, acceleration : float or ndarray
        The input's speed and acceleration: rad/s and rad/s^2, or m/s and m/s^2 (one for every pose, or (n,): a
        motion's own at each pose).
    effort : ndarray
        The driver's effort (n,): N*m on a crank, N along a slide; +-inf where it cannot move the linkage.
    pairs : tuple of PairForce
        Every pair's force, in the solve order's order.
    shaking_force : ndarray
        (n, 2) N, -sum m a_G.
    shaking_moment : ndarray
        (n,) N*m about the drawing's origin, -sum (I_G alpha + r_G x m a_G).
    frame_force : ndarray
        (n, 2) N, what the joints and the driver's reaction put on the frame.
    frame_moment : ndarray
        (n,) N*m about the origin, the same forces' moment (the driver's reaction couple included).
    power : ndarray
        (n,) W, the driver's power: effort x speed.
    residual : ndarray or None
        (n,) the largest imbalance of any link's equations with the solved forces put back, relative to the size of
        their terms (when asked for: ``check``).
    """

    inputs: np.ndarray
    speed: float | np.ndarray
    acceleration: float | np.ndarray
    effort: np.ndarray
    pairs: tuple[PairForce, ...]
    shaking_force: np.ndarray
    shaking_moment: np.ndarray
    frame_force: np.ndarray
    frame_moment: np.ndarray
    power: np.ndarray
    residual: np.ndarray | None = field(default=None, repr=False)


def pairs_of(linkage: Linkage) -> tuple[Pair, ...]:
    """The constraints of a one-input linkage in the order its solve places them (each step's pairs: an input's
    pivot or guide, then a dyad's two attachments and its joint, a group's pins and slides); a :class:`SpecError` on
    ``dynamics`` for a linkage whose joint forces the links' equations cannot fix (more than one input, a redundant
    constraint)."""
    s, plan = linkage.structure, linkage.plan
    if len(s.inputs) != 1:
        raise SpecError("a linkage of one input has one effort; with two, the forces cannot be shared out",
                        "dynamics")
    if plan.redundant or any(not isinstance(step, (InputStep, DyadStep, GroupStep)) for step in plan.steps):
        named = ", ".join(r.name for r in plan.redundant) or "a link held at three places"
        raise SpecError(f"the linkage has a redundant constraint ({named}): its joint forces are statically "
                        "indeterminate (any share of them holds the links), so they are not computed", "dynamics")
    sliders = s.slider_by_name
    out: list[Pair] = []
    for k, step in enumerate(plan.steps):
        if isinstance(step, InputStep):
            inp = s.inputs[step.index]
            if inp.kind == "crank":
                out.append(Pair("pin", inp.pivot, inp.relative_to, inp.link, k))
            else:
                sl = sliders[inp.slider]
                out.append(Pair("slide", sl.point, sl.guide, sl.body, k, sl.name))
            continue
        if isinstance(step, GroupStep):
            out += _group_pairs(s, step, k)
            continue
        assert isinstance(step, DyadStep)
        for body, att in zip(step.bodies, step.attachments, strict=True):
            if isinstance(att, Pin):
                out.append(Pair("pin", att.point, att.body, body, k))
            else:
                sl = sliders[att.slider]
                out.append(Pair("slide", sl.point, sl.guide, sl.body, k, sl.name))
        if step.prismatic:
            sl = sliders[step.joint]
            out.append(Pair("slide", sl.point, sl.guide, sl.body, k, sl.name))
        else:
            out.append(Pair("pin", step.joint, step.bodies[0], step.bodies[1], k))
    return tuple(out)


def _group_pairs(s: Structure, group: GroupStep, step: int) -> list[Pair]:
    """A class-III (or higher) group's pairs: its pins (on a body of the group, from the other: of the group or
    placed before it) and its slides; as many unknowns as its bodies have equations (an Assur group), so its block
    is square like a dyad's."""
    sliders = s.slider_by_name
    out = [Pair("pin", point, by, on, step) for point, on, by in group.pins]
    out += [Pair("slide", sliders[name].point, sliders[name].guide, sliders[name].body, step, name)
            for name in group.sliders]
    return out


def _guide(s: Structure, sol: Solution, pair: Pair) -> np.ndarray:
    """A slide's guide direction in the world at each pose (n, 2), unit."""
    angle = s.slider_by_name[pair.slider].angle
    c, sn = sol.rotations[pair.by]
    return np.stack([c * math.cos(angle) - sn * math.sin(angle), sn * math.cos(angle) + c * math.sin(angle)], axis=-1)


@dataclass(frozen=True)
class _Model:
    """What the equations need over the poses (SI): each body's centre (m), its mass and inertia terms (m a_G and
    I alpha), and the loads' resultant on it (Fx, Fy, moment about G)."""

    centres: dict[str, np.ndarray]
    inertial: dict[str, np.ndarray]
    applied: dict[str, np.ndarray]
    size: dict[str, np.ndarray]


def _per_pose(value: Rate, n: int, name: str) -> np.ndarray:
    """An input's speed or acceleration as an array: a scalar (0-d) for one at every pose, else its n values."""
    out = np.asarray(value, dtype=float)
    if out.shape not in ((), (n,)):
        raise ValueError(f"{name}: give one value or one a pose ({n}), not an array of shape {out.shape}")
    return out


def _model(linkage: Linkage, sol: Solution, masses: Mapping[str, LinkMass], speed: Rate, acceleration: Rate,
           loads: Loads, check: bool = False) -> _Model:
    """The equations' terms over the poses; with ``check`` also each body's size of terms (for the residual)."""
    s = linkage.structure
    f = input_scale(s)
    n = sol.inputs.shape[-1]
    squared, rate = _per_pose(speed, n, "speed") ** 2, _per_pose(acceleration, n, "acceleration")
    centres, inertial, applied, size = {}, {}, {}, {}
    g = np.asarray(loads.gravity, dtype=float)
    for body in moving_links(s):
        m = masses.get(body, LinkMass(0.0, s.points[s.bodies[body][0]], 0.0))
        cm = centre_motion(s, sol, body, m.centre)
        a = cm.acceleration * (MM / f**2 * squared)[..., None] + cm.velocity * (MM / f * rate)[..., None]
        alpha = cm.alpha * (squared / f**2) + cm.omega * (rate / f)
        centres[body] = cm.position * MM
        inertial[body] = np.column_stack([m.mass * a, m.inertia * MM**2 * alpha])
        applied[body] = np.column_stack([np.broadcast_to(m.mass * g, (n, 2)), np.zeros(n)])
        if check:
            size[body] = np.abs(inertial[body]).sum(axis=1) + np.abs(applied[body]).sum(axis=1)
    for load in loads.forces:
        holder = next((b for b in s.holders(load.point) if b != GROUND), None)
        if holder is None:
            continue
        force = np.broadcast_to(np.asarray(load.force, dtype=float), (n, 2))
        _add(applied, size, holder, force, sol.points[load.point] * MM - centres[holder])
    for torque in loads.torques:
        if torque.link in applied:
            applied[torque.link][:, 2] += torque.torque
            if check:
                size[torque.link] += abs(torque.torque)
    for spring in loads.springs:
        pa, pb = _spring_end(s, sol, spring.a, spring.on_a), _spring_end(s, sol, spring.b, spring.on_b)
        d = pb - pa
        length = np.hypot(d[:, 0], d[:, 1])
        pull = spring.stiffness * 1e3 * (length - spring.free_length) * MM      # N
        unit = d / np.where(length > 0, length, 1.0)[:, None]
        for body, point, sign in ((spring.on_a, pa, 1.0), (spring.on_b, pb, -1.0)):
            if body in applied:
                _add(applied, size, body, sign * pull[:, None] * unit, point * MM - centres[body])
    return _Model(centres, inertial, applied, size)


def _spring_end(s: Structure, sol: Solution, point: str, body: str) -> np.ndarray:
    """Where a spring's end is (mm): the joint's position (its holders agree), or the ground's drawn point."""
    if point in sol.points and body != GROUND:
        return sol.points[point]
    return np.broadcast_to(np.asarray(s.points[point], dtype=float), (sol.inputs.shape[-1], 2))


def _add(applied: dict[str, np.ndarray], size: dict[str, np.ndarray], body: str, force: np.ndarray,
         arm: np.ndarray) -> None:
    """Add a force (n, 2) N acting at ``arm`` (n, 2) m from the body's centre to its applied resultant."""
    moment = cross(arm, force)
    applied[body][:, :2] += force
    applied[body][:, 2] += moment
    if size:
        size[body] += np.abs(force).sum(axis=1) + np.abs(moment)


def _columns(s: Structure, sol: Solution, pair: Pair, centre: np.ndarray, sign: float,
             out: np.ndarray | None = None) -> np.ndarray:
    """How a pair's two unknowns enter the equations (Fx, Fy, moment about G) of a body it acts on with ``sign``
    (+1 its ``on`` body, -1 its ``by`` body): a (3, 2, n) block (the poses last, so that each entry is written
    whole), written into ``out`` (zeros) when given."""
    n = sol.inputs.shape[-1]
    r = sol.points[pair.point] * MM - centre
    out = np.zeros((3, 2, n)) if out is None else out
    if pair.kind == "pin":
        out[0, 0] = sign
        out[1, 1] = sign
        out[2, 0] = -sign * r[:, 1]
        out[2, 1] = sign * r[:, 0]
        return out
    normal = perp(_guide(s, sol, pair))
    out[0, 0] = sign * normal[:, 0]
    out[1, 0] = sign * normal[:, 1]
    out[2, 0] = sign * cross(r, normal)
    out[2, 1] = sign
    return out


def _wrench(s: Structure, sol: Solution, pair: Pair, centre: np.ndarray, sign: float,
            value: np.ndarray) -> np.ndarray:
    """The force and moment about ``centre`` (n, 3) that a pair whose unknowns are ``value`` (n, 2) puts on a body it
    acts on with ``sign``."""
    r = sol.points[pair.point] * MM - centre
    if pair.kind == "pin":
        force = sign * value
        return np.column_stack([force, cross(r, force)])
    normal = perp(_guide(s, sol, pair))
    force = (sign * value[:, 0])[:, None] * normal
    return np.column_stack([force, cross(r, force) + sign * value[:, 1]])


def _effort_column(s: Structure, sol: Solution, first: Pair, centre: np.ndarray, sign: float) -> np.ndarray:
    """How the driver's effort enters a body's equations: (3, n), the poses last."""
    n = sol.inputs.shape[-1]
    out = np.zeros((3, n))
    if s.inputs[0].kind == "crank":
        out[2] = sign
        return out
    u = _guide(s, sol, first)
    out[:2] = sign * u.T
    out[2] = sign * cross(sol.points[first.point] * MM - centre, u)
    return out


def _solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Stacked solves a x = b, (k, k, n) and (k, n) (the poses last), x (n, k); where a pose's system is singular (a
    toggle), +-inf."""
    a, b = a.transpose(2, 0, 1), b.T
    with np.errstate(all="ignore"):
        try:
            return np.linalg.solve(a, b[..., None])[..., 0]
        except np.linalg.LinAlgError:
            pass
        det = np.linalg.det(a)
        bad = ~np.isfinite(det) | (det == 0)
        safe = np.where(bad[:, None, None], np.eye(a.shape[-1]), a)
        x = np.linalg.solve(safe, b[..., None])[..., 0]
        x[bad] = np.inf
        return x


def _unknowns(pairs: Sequence[Pair]) -> list[tuple[int, int]]:
    """Each pair's first column in the whole system (two a pair), then the effort's (after the first pair)."""
    out, col = [], 0
    for k, _ in enumerate(pairs):
        out.append((col, k))
        col += 3 if k == 0 else 2
    return out


def system(linkage: Linkage, sol: Solution, masses: Mapping[str, LinkMass], speed: Rate = 0.0,
           acceleration: Rate = 0.0, loads: Loads = Loads()) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """The whole linear system A x = b of every pose (n, 3L, 3L) and (n, 3L), L moving links, and the bodies in the
    rows' order (three rows each: Fx, Fy, moment about G). The unknowns: each pair's two in :func:`pairs_of`'s order,
    the effort third (after the input's pair)."""
    s = linkage.structure
    pairs = pairs_of(linkage)
    model = _model(linkage, sol, masses, speed, acceleration, loads)
    bodies = moving_links(s)
    row = {b: 3 * i for i, b in enumerate(bodies)}
    n, size = sol.inputs.shape[-1], 3 * len(bodies)
    a, b = np.zeros((size, size, n)), np.zeros((size, n))
    for (col, k), pair in zip(_unknowns(pairs), pairs, strict=True):
        for body, sign in ((pair.on, 1.0), (pair.by, -1.0)):
            if body == GROUND:
                continue
            a[row[body]:row[body] + 3, col:col + 2] += _columns(s, sol, pair, model.centres[body], sign)
            if k == 0:
                a[row[body]:row[body] + 3, col + 2] += _effort_column(s, sol, pair, model.centres[body], sign)
    for body in bodies:
        b[row[body]:row[body] + 3] = (model.inertial[body] - model.applied[body]).T
    return a.transpose(2, 0, 1), b.T, bodies


def kinetostatics(linkage: Linkage, sol: Solution, masses: Mapping[str, LinkMass], speed: Rate = 0.0,
                  acceleration: Rate = 0.0, loads: Loads = Loads(),
                  method: Literal["blocks", "dense"] = "blocks", check: bool = False) -> Kinetostatics:
    """Every joint's force, the driver's effort and the frame's shaking over the poses of ``sol``.

    Parameters
    ----------
    linkage : Linkage
        A linkage of one input without redundant constraints.
    sol : Solution
        Its poses, solved with derivatives at unit input speed (``linkage.solve(values)``).
    masses : mapping of str to LinkMass
        Each moving link's mass properties (centre in the drawing's frame); a missing link is massless.
    speed : float or ndarray
        The input's speed: rad/s for a crank, m/s for a slide; one for all the poses or (n,), one a pose (a motion
        that speeds up and slows down, as forward dynamics integrates it).
    acceleration : float or ndarray
        The input's acceleration: rad/s^2, or m/s^2; one, or (n,).
    loads : Loads
        Gravity, forces at joints, torques on links, springs.
    method : {"blocks", "dense"}
        Solve the system a step of the solve order at a time (its block-triangular form) or whole.
    check : bool
        Also put the solved forces back into every link's equations: the result's ``residual``.

    Returns
    -------
    Kinetostatics
        The forces, the effort, the shaking and the balance's residual (see the module's note for signs).

    Raises
    ------
    SpecError
        A linkage of more than one input or with a redundant constraint (on ``dynamics``).
    """
    s = linkage.structure
    pairs = pairs_of(linkage)
    model = _model(linkage, sol, masses, speed, acceleration, loads, check)
    if method == "dense":
        a, b, _ = system(linkage, sol, masses, speed, acceleration, loads)
        x = _solve(a.transpose(1, 2, 0), b.T)
        values = [x[:, c:c + 2] for c, _ in _unknowns(pairs)]
        effort = x[:, 2]
    else:
        values, effort = _by_blocks(linkage, sol, pairs, model)
    out = []
    for pair, v in zip(pairs, values, strict=True):
        where = sol.points[pair.point]
        if pair.kind == "pin":
            out.append(PairForce(pair, v, where))
        else:
            normal = perp(_guide(s, sol, pair))
            out.append(PairForce(pair, v[:, :1] * normal, where, v[:, 1].copy(), v[:, 0].copy()))
    return _finish(s, sol, tuple(out), effort, model, speed, acceleration, check)


def _step_bodies(linkage: Linkage) -> list[tuple[str, ...]]:
    """The bodies each step of the solve order places: the input's link, a dyad's two, a group's."""
    return [(step.body,) if isinstance(step, InputStep) else step.bodies  # type: ignore[union-attr]
            for step in linkage.plan.steps]


def _by_blocks(linkage: Linkage, sol: Solution, pairs: tuple[Pair, ...],
               model: _Model) -> tuple[list[np.ndarray], np.ndarray]:
    """The system solved a step at a time from the last: each step's bodies are held by its own pairs and the
    later steps' (already known), so its block (3x3 for the input, 6x6 for a dyad, 3 a link for a group) is solved
    on its own."""
    s = linkage.structure
    n = sol.inputs.shape[-1]
    known = {b: np.zeros((n, 3)) for b in model.centres}
    values: list[np.ndarray] = [np.zeros((n, 2))] * len(pairs)
    effort = np.zeros(n)
    toggled = np.zeros(n, dtype=bool)
    placed = _step_bodies(linkage)
    for step in range(len(placed) - 1, -1, -1):
        own = [k for k, p in enumerate(pairs) if p.step == step]
        rows = {b: 3 * i for i, b in enumerate(placed[step])}
        width = 2 * len(own) + (1 if step == 0 else 0)
        b = np.concatenate([(model.inertial[body] - model.applied[body] - known[body]).T for body in rows])
        closed = None
        if step and len(rows) == 2 and all(pairs[k].kind == "pin" for k in own):
            closed = _pinned_dyad(sol, [pairs[k] for k in own], tuple(rows), model.centres, b)
        if closed is None or closed[1].any():
            a = np.zeros((3 * len(rows), width, n))
            for i, k in enumerate(own):
                pair = pairs[k]
                for body, sign in ((pair.on, 1.0), (pair.by, -1.0)):
                    if body in rows:
                        r = rows[body]
                        _columns(s, sol, pair, model.centres[body], sign, a[r:r + 3, 2 * i:2 * i + 2])
                        if k == 0:
                            a[r:r + 3, width - 1] += _effort_column(s, sol, pair, model.centres[body], sign)
        if closed is None:
            x = _solve(a, b)
        else:
            x, weak = closed
            if weak.any():
                x[weak] = _solve(a[..., weak], b[:, weak])
        toggled |= np.isinf(x).any(axis=1)
        if step == 0:
            effort = x[:, width - 1]
        for i, k in enumerate(own):
            values[k] = x[:, 2 * i:2 * i + 2]
            pair = pairs[k]
            for body, sign in ((pair.on, 1.0), (pair.by, -1.0)):
                if body not in rows and body != GROUND:
                    known[body] += _wrench(s, sol, pair, model.centres[body], sign, values[k])
                    if k == 0:
                        known[body] += (_effort_column(s, sol, pair, model.centres[body], sign) * effort).T
    if toggled.any():                  # a toggle's infinite forces carried into the blocks before it: inf, not NaN
        for v in values:
            v[toggled[:, None] & np.isnan(v)] = np.inf
        effort[toggled & np.isnan(effort)] = np.inf
    return values, effort


#: the least sine of the angle between an RRR dyad's two lines (attachment to joint) that its closed form takes;
#: nearer its toggle the cross product of the lines is rounding's (the pins' coordinates cancel in it), and the
#: pose's block is solved whole as before (its forces near 1 / that sine either way)
PINNED_SINE = 1e-6


def _pinned_dyad(sol: Solution, own: list[Pair], bodies: tuple[str, ...], centres: Mapping[str, np.ndarray],
                 b: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """A dyad's block in closed form where its three pairs are pins (an RRR dyad), or None where they are not one
    attachment a body and a joint between the two. The pin forces (n, 6), each pair's two in ``own``'s order, from
    ``b`` (6, n): each body's three right-hand sides (Fx, Fy, moment about its centre), in ``bodies``' order; and
    the poses (n,) bool within :data:`PINNED_SINE` of the dyad's toggle, whose forces the caller solves whole.

    Body i's equations are s_o F_o + s_j F_j = R_i and s_o (r_o x F_o) + s_j (r_j x F_j) = M_i (s a pair's sign on
    the body, r its point from the body's centre): the first gives the attachment's force from the joint's, and
    the moment about the attachment, s_j ((J - O) x F_j) = M_i - r_o x R_i, leaves the joint's force alone: two
    such equations for its two components, the textbook's dyad method, in place of the block's 6 x 6 solve. Their
    determinant is the cross product of the bodies' lines from their attachments to the joint, zero at the dyad's
    toggle."""
    joints = [p for p in own if p.on in bodies and p.by in bodies]
    if len(own) != 3 or len(joints) != 1:
        return None
    joint = joints[0]
    outer, lines, rhs = [], [], []
    for i, body in enumerate(bodies):
        held = [k for k, p in enumerate(own) if p is not joint and body in (p.on, p.by)]
        if len(held) != 1:
            return None
        attach = own[held[0]]
        s_o = 1.0 if attach.on == body else -1.0
        s_j = 1.0 if joint.on == body else -1.0
        force, moment = b[3 * i:3 * i + 2].T, b[3 * i + 2]
        lines.append(s_j * (sol.points[joint.point] - sol.points[attach.point]) * MM)
        rhs.append(moment - cross(sol.points[attach.point] * MM - centres[body], force))
        outer.append((held[0], s_o, s_j, force))
    (u, v), (c1, c2) = lines, rhs
    out = np.empty((len(c1), 6))
    with np.errstate(all="ignore"):
        det = cross(u, v)
        fj = np.column_stack([c1 * v[:, 0] - u[:, 0] * c2, c1 * v[:, 1] - u[:, 1] * c2]) / det[:, None]
        for k, s_o, s_j, force in outer:
            out[:, 2 * k:2 * k + 2] = s_o * (force - s_j * fj)
    k = own.index(joint)
    out[:, 2 * k:2 * k + 2] = fj
    size = np.hypot(u[:, 0], u[:, 1]) * np.hypot(v[:, 0], v[:, 1])
    weak = ~(np.abs(det) > PINNED_SINE * size)         # NaN or infinite lines too: the whole solve's rule
    return out, weak


def _finish(s: Structure, sol: Solution, forces: tuple[PairForce, ...], effort: np.ndarray, model: _Model,
            speed: Rate, acceleration: Rate, check: bool) -> Kinetostatics:
    """The shaking, the frame's reactions, the power and (``check``) the residual of every link's balance."""
    n = sol.inputs.shape[-1]
    shaking = np.zeros((n, 2))
    moment = np.zeros(n)
    for body, centre in model.centres.items():
        inertial = model.inertial[body]
        shaking -= inertial[:, :2]
        moment -= inertial[:, 2] + cross(centre, inertial[:, :2])
    frame_force, frame_moment = np.zeros((n, 2)), np.zeros(n)
    totals = {b: model.applied[b].copy() for b in model.centres} if check else {}
    scale = {b: model.size[b].copy() for b in model.centres} if check else {}

    def put(body: str, wrench: np.ndarray) -> None:
        """A force and moment (n, 3; the moment about the body's centre) on a moving body, into its sums."""
        if check:
            totals[body] += wrench
            scale[body] += np.abs(wrench).sum(axis=1)

    for k, pf in enumerate(forces):
        pair = pf.pair
        for body, sign in ((pair.on, 1.0), (pair.by, -1.0)):
            force = sign * pf.force
            couple = 0.0 if pf.couple is None else sign * pf.couple
            if body == GROUND:
                frame_force += force
                frame_moment += cross(pf.where * MM, force) + couple
            elif check:
                arm = pf.where * MM - model.centres[body]
                put(body, np.column_stack([force, cross(arm, force) + couple]))
        if k == 0:
            for body, sign in ((pair.on, 1.0), (pair.by, -1.0)):
                centre = np.zeros((n, 2)) if body == GROUND else model.centres[body]
                column = (_effort_column(s, sol, pair, centre, sign) * effort).T
                if body == GROUND:
                    frame_force += column[:, :2]
                    frame_moment += column[:, 2]
                else:
                    put(body, column)
    residual = None
    if check:
        residual = np.zeros(n)
        with np.errstate(all="ignore"):
            for body in model.centres:
                miss = np.abs(totals[body] - model.inertial[body]).max(axis=1)
                residual = np.maximum(residual, miss / np.maximum(scale[body], 1e-300))
    return Kinetostatics(np.asarray(sol.inputs[0], dtype=float), speed, acceleration, effort, forces, shaking,
                         moment, frame_force, frame_moment, effort * speed, residual)
