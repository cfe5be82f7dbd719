"""Any planar linkage solved dyad by dyad in closed form, vectorised over input values.

:class:`Linkage` holds a :class:`~linkgen.kinematics.structure.Structure` and its solve order;
:meth:`Linkage.solve` places every body at every input value at once: each dyad in closed
form (:mod:`linkgen.kinematics.dyads`), then velocities and accelerations per unit input speed
by differentiating each dyad's closure, a 2x2 linear solve per dyad in the same order (never
finite differences).

Frame and signs: the drawing's own frame, mm; angles in radians counter-clockwise. A body's
pose is ``world(x) = R(phi) x + T`` for its drawn points x (the drawing is phi = 0, T = 0).
Velocities are per unit speed of the input(s) (rad or mm per unit of input; multiply by the
input's speed), accelerations at constant input speed.

Branches: each dyad keeps the branch the drawing shows (the side its middle joint lies on).
At a change point (a dyad passes through its in-line position and goes on, the two branches
meeting) the smooth continuation swaps sides; :class:`Linkage` finds those input values on
the revolution (or the stroke) that starts at the drawing and counts them, so a crank angle
is read on the revolution that starts at the drawn angle: theta0 <= theta < theta0 + 2 pi.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from linkgen.kinematics import dyads
from linkgen.kinematics.dyads import cross, dot, perp
from linkgen.kinematics.grashof import check_finite
from linkgen.kinematics.structure import (GROUND, DyadStep, FixedStep, Input, InputStep, Pin, Plan, Slide, Structure,
                                          plan)

#: a dyad whose margin (a sine) is above minus this is taken to close, at its toggle: the margin grows like the
#: square root of the distance past the toggle, so this snaps inputs within about 1e-10 (relative to the links)
#: beyond it, as the four-bar's closed form does
FEASIBILITY_TOL = 1e-5
#: within this of a change point (rad or mm of input) the rates are the branch's limit, interpolated from rates
#: one and two of it away
CHANGE_REACH = 1e-2
TWO_PI = 2.0 * math.pi


@dataclass
class Body:
    """A body's motion over the poses: rotation (cos, sin), translation T (n, 2) mm, angular velocity w and the
    velocity vT of its material point at T, angular acceleration al and the acceleration aT."""

    c: np.ndarray
    s: np.ndarray
    T: np.ndarray
    w: np.ndarray | None = None
    vT: np.ndarray | None = None
    al: np.ndarray | None = None
    aT: np.ndarray | None = None

    def at(self, x: np.ndarray) -> np.ndarray:
        """World positions of drawn point(s) x (2,) -> (n, 2)."""
        return np.stack([self.c * x[0] - self.s * x[1], self.s * x[0] + self.c * x[1]], axis=-1) + self.T

    def rotate(self, v: np.ndarray) -> np.ndarray:
        """A drawn direction v (2,) in the world, (n, 2)."""
        return np.stack([self.c * v[0] - self.s * v[1], self.s * v[0] + self.c * v[1]], axis=-1)

    def vel(self, xw: np.ndarray) -> np.ndarray:
        """Velocity of the body's material point at world position(s) xw (n, 2)."""
        return self.vT + self.w[:, None] * perp(xw - self.T)

    def acc(self, xw: np.ndarray) -> np.ndarray:
        r = xw - self.T
        return self.aT + self.al[:, None] * perp(r) - (self.w**2)[:, None] * r


def _pinned(c: np.ndarray, s: np.ndarray, pw: np.ndarray, pd: np.ndarray) -> Body:
    """A body turned by (c, s) whose drawn point pd is at world pw."""
    return Body(c, s, pw - np.stack([c * pd[0] - s * pd[1], s * pd[0] + c * pd[1]], axis=-1))


@dataclass(frozen=True)
class DyadResult:
    """One dyad over the poses: its margin (>= 0 where it closes, 0 at its toggle) and its transmission angle
    (rad, in [0, pi] for RRR, [0, pi/2] otherwise; 0 or pi at the toggle)."""

    kind: str
    bodies: tuple[str, str]
    joint: str
    margin: np.ndarray
    transmission: np.ndarray
    #: the rate (per unit input) at which the dyad's outer joints move apart (their distance, or the pin's from
    #: the guide line): 0 where the dyad is in line at a change point; None without derivatives
    spread: np.ndarray | None = None


@dataclass(frozen=True)
class Solution:
    """Every point's position, velocity and acceleration (n, 2) over the poses; every body's angle (rad from the
    drawing), angular velocity and acceleration; each dyad's margin and transmission angle; the inputs."""

    inputs: np.ndarray
    points: dict[str, np.ndarray]
    velocities: dict[str, np.ndarray]
    accelerations: dict[str, np.ndarray]
    rotations: dict[str, tuple[np.ndarray, np.ndarray]]
    omegas: dict[str, np.ndarray]
    alphas: dict[str, np.ndarray]
    dyads: tuple[DyadResult, ...]
    ok: np.ndarray

    @property
    def angles(self) -> dict[str, np.ndarray]:
        """Each body's turn from the drawing (rad, in (-pi, pi]), computed when asked."""
        return {b: np.arctan2(sn, c) for b, (c, sn) in self.rotations.items()}


@dataclass(frozen=True)
class Linkage:
    """A planar linkage with its solve order; ``flips`` holds, per step, the input values (on the revolution or
    stroke from the drawing) where that dyad's branch swaps sides at a change point.

    Made by :meth:`of` from a structure (which finds the flips and checks the redundant constraints); positions
    in the drawing's frame (mm), angles counter-clockwise in radians.

    Parameters
    ----------
    structure : Structure
        The joints' drawn positions, the links, the sliders and the inputs.
    plan : Plan
        The solve order: the inputs, then the dyads.
    flips : tuple of ndarray, optional
        Per step, the input values where its dyad swaps sides.
    """

    structure: Structure
    plan: Plan
    flips: tuple[np.ndarray, ...] = field(default=())

    @classmethod
    def of(cls, structure: Structure) -> Linkage:
        """The linkage of a structure, with its change points found over the motion that starts at the drawing."""
        from linkgen.kinematics.motion import find_flips

        from linkgen.kinematics.motion import check_redundant

        bare = cls(structure, plan(structure))
        linkage = cls(structure, bare.plan, find_flips(bare))
        check_redundant(linkage)
        return linkage

    # ------------------------------------------------------------------ inputs

    @property
    def drawn_inputs(self) -> np.ndarray:
        """Each input's value in the drawing (rad for a crank, 0 mm for a slide)."""
        return np.array([input_angle(self.structure, inp) for inp in self.structure.inputs])

    def is_crank(self) -> bool:
        """Whether the one input turns a link (its values wrap every 2 pi)."""
        return len(self.structure.inputs) == 1 and self.structure.inputs[0].kind == "crank"

    def unwrap(self, values: np.ndarray) -> np.ndarray:
        """Crank angles on the revolution that starts at the drawing: theta0 <= theta < theta0 + 2 pi."""
        if not self.is_crank():
            return values
        t0 = self.drawn_inputs[0]
        return t0 + np.mod(values - t0, TWO_PI)

    def _signs(self, inputs: np.ndarray) -> list[np.ndarray]:
        """Each step's branch sign at each pose: the drawing's, swapped at every change point passed on the way
        there from the drawing."""
        drawn = _drawn_signs(self.structure, self.plan)
        if not any(len(f) for f in self.flips) or len(self.structure.inputs) != 1:
            return [np.full(inputs.shape[1], s) for s in drawn]
        x = self.unwrap(inputs[0])
        x0 = self.drawn_inputs[0]
        out = []
        for s, flips in zip(drawn, self.flips, strict=True):
            ahead = np.searchsorted(flips, x, side="right") - np.searchsorted(flips, x0, side="right")
            out.append(s * np.where(ahead % 2 == 0, 1.0, -1.0))
        return out

    # ------------------------------------------------------------------ solving

    def solve(self, inputs: ArrayLike, rates: ArrayLike | None = None, *, strict: bool = True,
              derivatives: bool = True, upto: int | None = None, signs: list[np.ndarray] | None = None) -> Solution:
        """Every body at each input value: ``inputs`` (n,) for one input, (k, n) for k; ``rates`` the inputs'
        speeds (1 each unless given) for the velocities and accelerations. With ``strict`` a value the linkage does
        not reach is a :class:`SpecError` naming the input's reachable range, and one that is not a finite number
        (NaN, +-inf) one naming it (degrees or mm); else those poses are marked in ``ok``. ``upto`` stops after
        that many steps (for the searches of :mod:`linkgen.kinematics.motion`)."""
        x = np.atleast_2d(np.asarray(inputs, dtype=float))
        k = len(self.structure.inputs)
        if x.shape[0] != k:
            raise SpecError(f"the linkage has {k} input(s); give {k} row(s) of values", "input")
        if strict:
            for given, row in zip(self.structure.inputs, x, strict=True):
                crank = given.kind == "crank"
                check_finite(row, "input", "input", "degrees" if crank else "mm", math.degrees if crank else float)
        r = np.ones(k) if rates is None else np.asarray(rates, dtype=float).reshape(k)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):   # not strict: +-inf marked, unsaid
            x = np.vstack([self.unwrap(x[0]), *x[1:]]) if self.is_crank() else x
            if signs is None:
                signs = self._signs(x)
            sol = _solve(self, x, r, signs, strict, derivatives, upto)
            if derivatives and upto is None and len(x) == 1 and any(len(f) for f in self.flips):
                self._rates_at_change_points(sol, r)
            return sol

    def _rates_at_change_points(self, sol: Solution, rates: np.ndarray) -> None:
        """Rates within ``CHANGE_REACH`` of a change point, where a dyad's 2x2 solve is 0/0: the branch's limit,
        the quintic through the analytic rates at 1, 2 and 3 ``CHANGE_REACH`` either side (the branch is smooth;
        there its rates are conditioned well enough for about 7 digits)."""
        x = sol.inputs[0]
        flips = np.unique(np.concatenate([f for f in self.flips if len(f)]))
        nearest = flips[np.argmin(np.abs(x[:, None] - flips[None, :]), axis=1)]
        near = np.abs(x - nearest) < CHANGE_REACH
        if not near.any():
            return
        centre = nearest[near]
        nodes = np.array([-3.0, -2.0, -1.0, 1.0, 2.0, 3.0])
        stencil = [_solve(self, (centre + h * CHANGE_REACH)[None, :], rates,
                          self._signs((centre + h * CHANGE_REACH)[None, :]), False, True, None) for h in nodes]
        u = (x[near] - centre) / CHANGE_REACH
        weights = [np.prod([(u - nodes[m]) / (nodes[k] - nodes[m]) for m in range(len(nodes)) if m != k], axis=0)
                   for k in range(len(nodes))]
        for rate in ("velocities", "accelerations", "omegas", "alphas"):
            table = getattr(sol, rate)
            for name, values in table.items():
                mixed = sum(w.reshape(w.shape + (1,) * (values.ndim - 1)) * getattr(st, rate)[name]
                            for w, st in zip(weights, stencil, strict=True))
                values = values.copy()
                values[near] = mixed
                table[name] = values


def body_point(s: Structure, sol: Solution, body: str, point: str) -> np.ndarray:
    """Where ``body`` puts drawn ``point`` at each pose of ``sol`` (n, 2) mm (a redundant joint's holders may
    disagree)."""
    first = s.bodies[body][0]
    d = _pt(s, point) - _pt(s, first)
    c, sn = np.cos(sol.angles[body]), np.sin(sol.angles[body])
    return sol.points[first] + np.stack([c * d[0] - sn * d[1], sn * d[0] + c * d[1]], axis=-1)


def input_angle(s: Structure, inp: Input) -> float:
    """An input's drawn value: for a crank the direction (rad) of its line from the pivot, measured from its
    reference link's line (the +X axis for the ground); for a slide 0 mm."""
    if inp.kind == "slide":
        return 0.0
    return _line_angle(s, inp.link, inp.pivot) - (
        0.0 if inp.relative_to == GROUND else _line_angle(s, inp.relative_to, inp.pivot))


def _line_angle(s: Structure, body: str, pivot: str) -> float:
    """Direction (rad) in the drawing of the line from ``pivot`` to the first other point of ``body``."""
    other = next(p for p in s.bodies[body] if p != pivot)
    (x0, y0), (x1, y1) = s.points[pivot], s.points[other]
    return math.atan2(y1 - y0, x1 - x0)


def _pt(s: Structure, name: str) -> np.ndarray:
    return np.asarray(s.points[name], dtype=float)


def _direction(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


def _drawn_signs(s: Structure, p: Plan) -> list[float]:
    """Each step's branch in the drawing (+1 or -1; +1 for steps without a branch)."""
    out = []
    sliders = s.slider_by_name
    for step in p.steps:
        sign = 1.0
        if isinstance(step, DyadStep):
            a1, a2 = step.attachments
            kind = step.kind
            if kind == "RRR":
                p1, p2, j = _pt(s, a1.point), _pt(s, a2.point), _pt(s, step.joint)
                sign = float(np.sign(cross(p2 - p1, j - p1))) or 1.0
            elif kind in ("RRP", "PRR"):
                pin = a1 if isinstance(a1, Pin) else a2
                slide = a2 if isinstance(a1, Pin) else a1
                u = _direction(sliders[slide.slider].angle)
                sign = float(np.sign(dot(_pt(s, step.joint) - _pt(s, pin.point), u))) or 1.0
            elif kind == "RPR":
                sl = sliders[step.joint]
                pin_m, pin_g = (a1, a2) if step.bodies[0] == sl.body else (a2, a1)
                d = _pt(s, pin_m.point) - _pt(s, pin_g.point)
                sign = float(np.sign(cross(d, perp(_direction(sl.angle))))) or 1.0
        out.append(sign)
    return out


# ---------------------------------------------------------------------- the solve, step by step


@dataclass
class _Unknown:
    """A dyad body's one unknown over the poses: its turn about a pin (``pin`` the world point, ``pd`` drawn) or
    its slide along ``u`` (world) relative to the known body ``ref`` (sign ``sigma``)."""

    name: str
    attachment: Pin | Slide
    ref: Body
    pin: np.ndarray | None = None
    pd: np.ndarray | None = None
    u: np.ndarray | None = None
    sigma: float = 1.0
    t: np.ndarray | None = None

    @classmethod
    def of(cls, s: Structure, name: str, attachment: Pin | Slide, bodies: dict[str, Body]) -> _Unknown:
        ref = bodies[attachment.body]
        if isinstance(attachment, Pin):
            pd = _pt(s, attachment.point)
            return cls(name, attachment, ref, pin=ref.at(pd), pd=pd)
        sl = s.slider_by_name[attachment.slider]
        return cls(name, attachment, ref, u=ref.rotate(_direction(sl.angle)), sigma=1.0 if attachment.moving else -1.0)

    # the body once its unknown is known
    def turned(self, c: np.ndarray, sn: np.ndarray) -> Body:
        return _pinned(c, sn, self.pin, self.pd)

    def slid(self, t: np.ndarray) -> Body:
        self.t = t
        return Body(self.ref.c, self.ref.s, self.ref.T + self.sigma * t[:, None] * self.u)

    @property
    def pinned(self) -> bool:
        return self.pin is not None

    # velocity level: v(x) = base(x) + unknown * g(x); omega = wbase + unknown * dw. A sliding body's point moves
    # with the known body's coincident point plus its slide (and, at acceleration level, Coriolis' term)
    def base_v(self, xw: np.ndarray) -> np.ndarray:
        if self.pinned:
            return np.broadcast_to(self.ref.vel(self.pin), xw.shape)
        return self.ref.vel(xw)

    def base_a(self, xw: np.ndarray, w: np.ndarray, tdot: np.ndarray | None) -> np.ndarray:
        if self.pinned:
            return self.ref.acc(self.pin) - (w**2)[:, None] * (xw - self.pin)
        return self.ref.acc(xw) + 2.0 * self.sigma * (tdot * self.ref.w)[:, None] * perp(self.u)

    def g(self, xw: np.ndarray) -> np.ndarray:
        return perp(xw - self.pin) if self.pinned else np.broadcast_to(self.sigma * self.u, xw.shape)

    def w_base(self) -> np.ndarray:
        return np.zeros(len(self.ref.c)) if self.pinned else self.ref.w

    def al_base(self) -> np.ndarray:
        return np.zeros(len(self.ref.c)) if self.pinned else self.ref.al

    @property
    def dw(self) -> float:
        return 1.0 if self.pinned else 0.0

    def finish_velocity(self, body: Body, x: np.ndarray) -> None:
        """Set the body's angular velocity and vT from its solved unknown rate."""
        if self.pinned:
            body.w = x
            body.vT = self.ref.vel(self.pin) + x[:, None] * perp(body.T - self.pin)
        else:
            body.w = self.ref.w
            body.vT = self.ref.vT + self.sigma * (x[:, None] * self.u
                                                   + (self.t * self.ref.w)[:, None] * perp(self.u))

    def finish_acceleration(self, body: Body, y: np.ndarray, tdot: np.ndarray | None) -> None:
        if self.pinned:
            body.al = y
            r = body.T - self.pin
            body.aT = self.ref.acc(self.pin) + y[:, None] * perp(r) - (body.w**2)[:, None] * r
        else:
            ref = self.ref
            body.al = ref.al
            body.aT = ref.aT + self.sigma * (y[:, None] * self.u + 2.0 * (tdot * ref.w)[:, None] * perp(self.u)
                                             + self.t[:, None] * (ref.al[:, None] * perp(self.u)
                                                                  - (ref.w**2)[:, None] * self.u))


def _ratio(num: np.ndarray, den: np.ndarray) -> np.ndarray:
    """num / den; +-inf where den is 0 (0 where both are): a toggle, never NaN."""
    with np.errstate(divide="ignore", invalid="ignore"):
        out = num / den
    bad = den == 0
    out[bad] = np.where(num[bad] == 0, 0.0, np.copysign(np.inf, num[bad]))
    return out


def _solve2(rows: list[tuple[np.ndarray, np.ndarray, np.ndarray]]) -> tuple[np.ndarray, np.ndarray]:
    """Solve two linear rows a x1 + b x2 = r by Cramer's rule; +-inf where singular (a toggle)."""
    (a1, b1, r1), (a2, b2, r2) = rows
    det = a1 * b2 - a2 * b1
    return _ratio(r1 * b2 - r2 * b1, det), _ratio(a1 * r2 - a2 * r1, det)


def _rows(step: DyadStep, s: Structure, u1: _Unknown, u2: _Unknown, bodies: dict[str, Body],
          level: str, rates: tuple | None = None) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The dyad's two closure rows at velocity (``level`` 'v') or acceleration ('a') level, in its unknowns."""
    b1, b2 = bodies[u1.name], bodies[u2.name]

    def base(u: _Unknown, body: Body, xw: np.ndarray) -> np.ndarray:
        if level == "v":
            return u.base_v(xw)
        return u.base_a(xw, body.w, None if rates is None else rates[u.name])

    if not step.prismatic:
        jw = b1.at(_pt(s, step.joint))
        g1, g2 = u1.g(jw), u2.g(jw)
        rhs = base(u2, b2, jw) - base(u1, b1, jw)
        return [(g1[:, 0], -g2[:, 0], rhs[:, 0]), (g1[:, 1], -g2[:, 1], rhs[:, 1])]
    sl = s.slider_by_name[step.joint]
    moving_first = step.bodies[0] == sl.body
    um, ug = (u1, u2) if moving_first else (u2, u1)
    bm, bg = (b1, b2) if moving_first else (b2, b1)
    uw = bg.rotate(_direction(sl.angle))
    n = perp(uw)
    jw = bm.at(_pt(s, sl.point))
    ones = np.ones(len(jw))
    # the two bodies turn together, and the moving body's point does not leave the guide's line (the relative
    # velocity of the coincident points lies along it; at acceleration level, less Coriolis' term)
    if level == "v":
        turn_rhs = ug.w_base() - um.w_base()
        line_rhs = dot(n, ug.base_v(jw) - um.base_v(jw))
    else:
        turn_rhs = ug.al_base() - um.al_base()
        slip = dot(uw, bm.vel(jw) - bg.vel(jw))
        line_rhs = dot(n, base(ug, bg, jw) - base(um, bm, jw)) + 2.0 * bg.w * slip
    rows = [(um.dw * ones, -ug.dw * ones, turn_rhs), (dot(n, um.g(jw)), -dot(n, ug.g(jw)), line_rhs)]
    return rows if moving_first else [(b, a, r) for a, b, r in rows]


def _place_dyad(step: DyadStep, s: Structure, u1: _Unknown, u2: _Unknown, sign: np.ndarray,
                bodies: dict[str, Body]) -> tuple[np.ndarray, np.ndarray]:
    """Place both bodies of a dyad; its margin and transmission angle."""
    kind = step.kind
    sliders = s.slider_by_name
    if kind == "RRR":
        jd = _pt(s, step.joint)
        r1, r2 = float(np.linalg.norm(jd - u1.pd)), float(np.linalg.norm(jd - u2.pd))
        jw, margin = dyads.circle_circle(u1.pin, r1, u2.pin, r2, sign)
        for u in (u1, u2):
            bodies[u.name] = _turn_to(u, jw - u.pin, jd - u.pd)
        a, b = u1.pin - jw, u2.pin - jw
        return margin, np.arctan2(np.abs(cross(a, b)), dot(a, b))
    if kind in ("RRP", "PRR"):
        up, us = (u1, u2) if u1.pinned else (u2, u1)
        jd = _pt(s, step.joint)
        r = float(np.linalg.norm(jd - up.pd))
        c = us.ref.at(jd)
        jw, margin = dyads.circle_line(up.pin, r, c, us.u, sign)
        bodies[up.name] = _turn_to(up, jw - up.pin, jd - up.pd)
        bodies[us.name] = us.slid(us.sigma * dot(jw - c, us.u))
        rod = jw - up.pin
        return margin, np.arctan2(np.abs(dot(rod, us.u)), np.abs(cross(us.u, rod)))
    if kind == "RPR":
        sl = sliders[step.joint]
        um, ug = (u1, u2) if step.bodies[0] == sl.body else (u2, u1)
        nd = perp(_direction(sl.angle))
        offset = float(dot(nd, um.pd - ug.pd))
        rot, margin = dyads.line_through(ug.pin, um.pin, math.atan2(nd[1], nd[0]), offset, sign)
        for u in (um, ug):
            bodies[u.name] = u.turned(rot[:, 0], rot[:, 1])
        d = um.pin - ug.pin
        dist = np.hypot(d[:, 0], d[:, 1])
        return margin, np.arctan2(np.sqrt(np.maximum((dist - abs(offset)) * (dist + abs(offset)), 0.0)), abs(offset))
    if kind == "PRP":
        jd = _pt(s, step.joint)
        c1, c2 = u1.ref.at(jd), u2.ref.at(jd)
        jw, margin = dyads.line_line(c1, u1.u, c2, u2.u)
        bodies[u1.name] = u1.slid(u1.sigma * dot(jw - c1, u1.u))
        bodies[u2.name] = u2.slid(u2.sigma * dot(jw - c2, u2.u))
        return margin, np.arcsin(np.minimum(margin, 1.0))
    # RPP / PPR: the pinned body takes the sliding one's angle; the sliding one's travel follows (a linear solve)
    up, us = (u1, u2) if u1.pinned else (u2, u1)
    turned = up.turned(us.ref.c, us.ref.s)
    bodies[up.name] = turned
    sl = sliders[step.joint]
    moving = sl.body == us.name
    guide_body = turned if moving else us.ref
    uw = guide_body.rotate(_direction(sl.angle))
    n = perp(uw)
    qd = _pt(s, sl.point)
    # the sliding body's point qd moves by sigma t u along its own guide; the constraint n . (moving - guide) = 0
    gap = (us.ref.at(qd) - turned.at(qd)) if moving else (turned.at(qd) - us.ref.at(qd))
    rate = dot(n, us.sigma * us.u) * (1.0 if moving else -1.0)
    margin = np.abs(rate)
    t = _ratio(-dot(n, gap), rate)
    bodies[us.name] = us.slid(np.where(np.isfinite(t), t, 0.0))
    return margin, np.arcsin(np.minimum(margin, 1.0))


def _turn_to(u: _Unknown, now: np.ndarray, drawn: np.ndarray) -> Body:
    """The pinned body turned so that its drawn vector ``drawn`` lies along ``now``."""
    length = float(np.hypot(*drawn))
    c = (now[:, 0] * drawn[0] + now[:, 1] * drawn[1]) / length**2
    sn = (drawn[0] * now[:, 1] - drawn[1] * now[:, 0]) / length**2
    return u.turned(c, sn)


def _solve(linkage: Linkage, x: np.ndarray, rates: np.ndarray, signs: list[np.ndarray], strict: bool,
           derivatives: bool, upto: int | None) -> Solution:
    s, p = linkage.structure, linkage.plan
    n = x.shape[1]
    zero2 = np.zeros((n, 2))
    ground = Body(np.ones(n), np.zeros(n), zero2.copy(), np.zeros(n), zero2.copy(), np.zeros(n), zero2.copy())
    bodies: dict[str, Body] = {GROUND: ground}
    results: list[DyadResult] = []
    ok = np.ones(n, dtype=bool)
    drawn = linkage.drawn_inputs
    for index, step in enumerate(p.steps[:upto]):
        if isinstance(step, InputStep):
            _place_input(s, step, x[step.index] - drawn[step.index], rates[step.index], bodies, derivatives)
        elif isinstance(step, FixedStep):
            _place_fixed(s, step, bodies, derivatives)
        else:
            u1, u2 = (_Unknown.of(s, b, a, bodies) for b, a in zip(step.bodies, step.attachments, strict=True))
            margin, gamma = _place_dyad(step, s, u1, u2, signs[index], bodies)
            if u1.pinned and u2.pinned:
                _check_apart(linkage, step, u1, u2, x, strict, ok)
            spread = _spread(u1, u2) if derivatives else None
            results.append(DyadResult(step.kind, step.bodies, step.joint, margin, gamma, spread))
            ok &= margin >= -FEASIBILITY_TOL
            if derivatives:
                xv = _solve2(_rows(step, s, u1, u2, bodies, "v"))
                for u, rate in zip((u1, u2), xv, strict=True):
                    u.finish_velocity(bodies[u.name], rate)
                tdots = {u.name: rate for u, rate in zip((u1, u2), xv, strict=True)}
                ya = _solve2(_rows(step, s, u1, u2, bodies, "a", tdots))
                for u, acc in zip((u1, u2), ya, strict=True):
                    u.finish_acceleration(bodies[u.name], acc, tdots[u.name])
    if strict and not ok.all():
        from linkgen.kinematics.motion import out_of_reach

        out_of_reach(linkage, x[:, ~ok][:, 0])
    return _gather(s, x, bodies, tuple(results), ok, derivatives)


def _check_apart(linkage: Linkage, step: DyadStep, u1: _Unknown, u2: _Unknown, x: np.ndarray, strict: bool,
                 ok: np.ndarray) -> None:
    """Refuse (or, not strict, mark) poses where a dyad's two pins meet: its joint could be anywhere on a circle
    (a deltoid's change point)."""
    met = np.hypot(*(u2.pin - u1.pin).T) <= 1e-12 * linkage.structure.scale
    if not met.any():
        return
    if strict:
        value = float(x[0, np.flatnonzero(met)[0]])
        crank = linkage.structure.inputs[0].kind == "crank"
        shown = f"{math.degrees(value):.9g} degrees" if crank else f"{value:.9g} mm"
        raise SpecError(f"at input {shown} the joints {u1.attachment.point} and {u2.attachment.point} meet, so "
                        f"joint {step.joint} could be anywhere on its circle (a deltoid's change point); step off it",
                        "input")
    ok &= ~met


def _spread(u1: _Unknown, u2: _Unknown) -> np.ndarray | None:
    """How fast the dyad's outer joints move apart: the pins' relative velocity along the line between them, or a
    pin's velocity off the guide line relative to the guide (None for dyads of two slides)."""
    if u1.pinned and u2.pinned:
        return dot(u2.pin - u1.pin, u2.ref.vel(u2.pin) - u1.ref.vel(u1.pin))
    if u1.pinned != u2.pinned:
        up, us = (u1, u2) if u1.pinned else (u2, u1)
        return dot(perp(us.u), up.ref.vel(up.pin) - us.ref.vel(up.pin))
    return None


def _place_input(s: Structure, step: InputStep, delta: np.ndarray, rate: float, bodies: dict[str, Body],
                 derivatives: bool) -> None:
    """The driven body moved by ``delta`` (rad or mm) from the drawing, at unit ``rate`` of its input."""
    inp = s.inputs[step.index]
    n = len(delta)
    if inp.kind == "crank":
        ref = bodies[inp.relative_to]
        c, sn = np.cos(delta), np.sin(delta)
        cc, ss = ref.c * c - ref.s * sn, ref.s * c + ref.c * sn
        pd = _pt(s, inp.pivot)
        pw = ref.at(pd)
        body = _pinned(cc, ss, pw, pd)
        if derivatives:
            r = body.T - pw
            body.w = ref.w + rate
            body.vT = ref.vel(pw) + body.w[:, None] * perp(r)
            body.al = ref.al.copy()
            body.aT = ref.acc(pw) + body.al[:, None] * perp(r) - (body.w**2)[:, None] * r
    else:
        sl = s.slider_by_name[inp.slider]
        ref = bodies[sl.guide]
        u = ref.rotate(_direction(sl.angle))
        body = Body(ref.c, ref.s, ref.T + delta[:, None] * u)
        if derivatives:
            tdot = np.full(n, rate)
            body.w, body.al = ref.w, ref.al
            body.vT = ref.vT + tdot[:, None] * u + (delta * ref.w)[:, None] * perp(u)
            body.aT = ref.aT + 2.0 * (tdot * ref.w)[:, None] * perp(u) + delta[:, None] * (
                ref.al[:, None] * perp(u) - (ref.w**2)[:, None] * u)
    bodies[step.body] = body


def _place_fixed(s: Structure, step: FixedStep, bodies: dict[str, Body], derivatives: bool) -> None:
    """A body held by two attachments: two pins fix its angle by their direction; a pin and a slide by the
    slide's."""
    a1, a2 = step.attachments
    if isinstance(a1, Slide):
        a1, a2 = a2, a1
    pd = _pt(s, a1.point)
    pw = bodies[a1.body].at(pd)
    if isinstance(a2, Pin):
        qd = _pt(s, a2.point)
        qw = bodies[a2.body].at(qd)
        now, drawn = qw - pw, qd - pd
        length2 = float(dot(drawn, drawn))
        c, sn = dot(now, drawn) / length2, cross(drawn, now) / length2
        norm = np.hypot(c, sn)
        body = _pinned(c / norm, sn / norm, pw, pd)
        if derivatives:
            d = qw - pw
            dd = dot(d, d)
            body.w = cross(d, bodies[a2.body].vel(qw) - bodies[a1.body].vel(pw)) / dd
            body.al = cross(d, bodies[a2.body].acc(qw) - bodies[a1.body].acc(pw)) / dd
    else:
        ref = bodies[a2.body]
        body = _pinned(ref.c, ref.s, pw, pd)
        if derivatives:
            body.w, body.al = ref.w, ref.al
    if derivatives:
        r = body.T - pw
        body.vT = bodies[a1.body].vel(pw) + body.w[:, None] * perp(r)
        body.aT = bodies[a1.body].acc(pw) + body.al[:, None] * perp(r) - (body.w**2)[:, None] * r
    bodies[step.body] = body


def _unbounded(x: np.ndarray) -> np.ndarray:
    """Rates past a toggle (where a dyad's 2x2 solve is singular) are unbounded: +inf, never NaN."""
    return np.where(np.isnan(x), np.inf, x)


def _gather(s: Structure, x: np.ndarray, bodies: dict[str, Body], results: tuple[DyadResult, ...], ok: np.ndarray,
            derivatives: bool) -> Solution:
    """Each point from the first body placed that holds it."""
    points, vels, accs = {}, {}, {}
    for name in s.points:
        holder = next((b for b in s.holders(name) if b in bodies), None)
        if holder is None:
            continue
        body = bodies[holder]
        xw = body.at(_pt(s, name))
        points[name] = xw
        if derivatives:
            vels[name], accs[name] = _unbounded(body.vel(xw)), _unbounded(body.acc(xw))
    rotations = {b: (body.c, body.s) for b, body in bodies.items()}
    omegas: dict[str, Any] = {b: _unbounded(body.w) for b, body in bodies.items()} if derivatives else {}
    alphas: dict[str, Any] = {b: _unbounded(body.al) for b, body in bodies.items()} if derivatives else {}
    return Solution(x, points, vels, accs, rotations, omegas, alphas, results, ok)
