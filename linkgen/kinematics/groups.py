"""Assur groups above class II (a triad, as in some eight-bars) solved by Newton's method, continued along the input.

A group no dyad order solves (:class:`~linkgen.kinematics.structure.GroupStep`) is placed all at once: each of its
bodies has three unknowns, its pose ``(phi, Tx, Ty)`` from the drawing (``world(x) = R(phi) x + T``, phi in rad
counter-clockwise, T in mm), and its pairs give as many closure equations:

- a revolute at drawn point p between bodies a and b: ``R(phi_a) p + T_a - R(phi_b) p - T_b = 0`` (two rows, mm);
- a slider of point p of body a along a guide of body g drawn in direction u: ``phi_a - phi_g = 0`` (rad) and
  ``N_g . (P_a(p) - P_g(p)) = 0`` (mm), ``N_g = R(phi_g) perp(u)`` the guide's normal.

The known bodies (placed by earlier steps) enter as given poses. Positions come from a *track*: the group's poses
continued from the drawn assembly (the drawing is the pose phi = 0, T = 0 at the drawn input) in steps of
:data:`TRACK_STEPS` per span of the input, each step predicted by the secant through the last two poses and
corrected by Newton; a step that does not converge, or moves a joint more than :data:`JUMP` times the drawing's
size, is halved, down to :data:`MIN_STEP` of the span, where the track ends: a toggle (the group's Jacobian
singular) that stops the input. The branch is the one the drawing shows, kept by continuity. Any input values are
then solved together (vectorised) by Newton from the track interpolated at them.

Rates per unit input speed: the closure differentiated once, ``J qdot = -(the known bodies' part)``, and twice,
``J qddot = -(the known part and the quadratic terms)``: linear solves with the group's Jacobian J.
The group's margin (and slack) is the smallest singular value of its scaled Jacobian over its largest (rad-rows
and angle columns scaled by the drawing's size): 1 well conditioned, 0 at a toggle, -1 where Newton finds no pose.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Protocol

import numpy as np

from linkgen.kinematics.structure import GroupStep, Structure

#: the kinds of :class:`~linkgen.kinematics.structure.GroupStep` (their results are among a solution's ``dyads``)
GROUP_KINDS = ("triad", "group")
#: the continuation: steps a crank's turn (two degrees each) or a slide's travel of the drawing's size; the least
#: step (a fraction of the span) halving goes down to before the track ends at a toggle; the most a step may move a
#: group's point (times the drawing's size) before it is refused as a branch jump
TRACK_STEPS, MIN_STEP, JUMP = 180, 1e-10, 0.05
#: the coarse walk tried first steps this many of the fine grid's steps at a time (then refined in one solve)
COARSE = 10
#: Newton's iterations at most, from the track and from a continuation step's prediction; the steps without
#: progress before a pose is given up; the residual (relative to the drawing's scale) taken as converged
MAX_ITER, STEP_ITER, STALL, RESIDUAL = 40, 8, 6, 1e-12


class Pose(Protocol):
    """A body's pose over n poses: rotation (c, s) (n,) and translation T (n, 2) mm."""

    @property
    def c(self) -> np.ndarray: ...
    @property
    def s(self) -> np.ndarray: ...
    @property
    def T(self) -> np.ndarray: ...


class Movement(Protocol):
    """A body's rates over n poses: w, al (n,) rad per unit input (squared); vT, aT (n, 2) mm the velocity and
    acceleration of its material point at T."""

    @property
    def w(self) -> np.ndarray: ...
    @property
    def vT(self) -> np.ndarray: ...
    @property
    def al(self) -> np.ndarray: ...
    @property
    def aT(self) -> np.ndarray: ...


@dataclass(frozen=True)
class Frames:
    """Every body's pose a group's equations need: rotation (c, s) and translation T by body name."""

    c: Mapping[str, np.ndarray]
    s: Mapping[str, np.ndarray]
    T: Mapping[str, np.ndarray]


def _perp(v: np.ndarray) -> np.ndarray:
    out = np.empty_like(v)
    out[..., 0], out[..., 1] = -v[..., 1], v[..., 0]
    return out


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.sum(a * b, axis=-1)


@dataclass(frozen=True)
class Group:
    """A group's closure: its bodies (three unknowns each: phi, Tx, Ty, in that order of columns), its pins
    (point, body, other body) and its sliders (point, sliding body, guide body, the guide's drawn normal)."""

    bodies: tuple[str, ...]
    pins: tuple[tuple[np.ndarray, str, str], ...]
    slides: tuple[tuple[np.ndarray, str, str, np.ndarray], ...]
    size: float
    scale: float
    #: each body's drawn points (2,) mm, in body order
    drawn: tuple[tuple[np.ndarray, ...], ...] = ()

    @property
    def m(self) -> int:
        """Unknowns (and equations): three per body."""
        return 3 * len(self.bodies)

    def column(self, body: str) -> int | None:
        """The first column of a group body's unknowns; None for a known body."""
        return 3 * self.bodies.index(body) if body in self.bodies else None

    def frames(self, q: np.ndarray, known: Mapping[str, Pose]) -> Frames:
        """The poses of the group's bodies at unknowns q (n, m), with the known bodies'."""
        c = {b: p.c for b, p in known.items()}
        s = {b: p.s for b, p in known.items()}
        t = {b: p.T for b, p in known.items()}
        for j, b in enumerate(self.bodies):
            c[b], s[b], t[b] = np.cos(q[:, 3 * j]), np.sin(q[:, 3 * j]), q[:, 3 * j + 1:3 * j + 3]
        return Frames(c, s, t)

    def residual(self, q: np.ndarray, known: Mapping[str, Pose], jacobian: bool = True
                 ) -> tuple[np.ndarray, np.ndarray]:
        """The closure's residuals F (n, m) (mm, rad for a slider's angle row) and its Jacobian J (n, m, m) in the
        group's unknowns (an empty array unless ``jacobian``)."""
        return self._residual(q, self._known_poses(known), known, jacobian)

    def _known_poses(self, known: Mapping[str, Pose]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The known bodies' poses the pins need, in :attr:`_pin_table`'s order: c, s (n, k) and T (n, k, 2)."""
        names = self._pin_table[0][len(self.bodies):]
        if not names:
            return np.empty((0, 0)), np.empty((0, 0)), np.empty((0, 0, 2))
        return (np.stack([known[b].c for b in names], axis=1), np.stack([known[b].s for b in names], axis=1),
                np.stack([known[b].T for b in names], axis=1))

    def _residual(self, q: np.ndarray, poses: tuple[np.ndarray, np.ndarray, np.ndarray],
                  known: Mapping[str, Pose], jacobian: bool) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`residual` with the known bodies' poses the pins need already gathered (:meth:`_known_poses`);
        ``known`` is read only by the sliders."""
        n = len(q)
        res = np.zeros((n, self.m))
        # the rows' constant entries (the translations' and the angle rows') once, then the angles' columns
        jac = np.broadcast_to(self._constant, (n, self.m, self.m)).copy() if jacobian else np.zeros((n, self.m, 0))
        if self.pins:                   # every pin's two rows at once: R(phi_a) p + T_a - R(phi_b) p - T_b
            _, sides, points, entries, pin_rows, cols, signs = self._pin_table
            nb = len(self.bodies)
            phi = q[:, 0:3 * nb:3]
            if poses[0].shape[1]:       # the group's bodies, then the known ones; a column per pin side
                c = np.concatenate([np.cos(phi), poses[0]], axis=1)[:, sides]
                sn = np.concatenate([np.sin(phi), poses[1]], axis=1)[:, sides]
                t = np.concatenate([q.reshape(n, nb, 3)[:, :, 1:], poses[2]], axis=1)[:, sides]
            else:
                c, sn, t = np.cos(phi)[:, sides], np.sin(phi)[:, sides], q.reshape(n, nb, 3)[:, sides, 1:]
            r = np.empty((n, len(sides), 2))
            r[..., 0], r[..., 1] = c * points[:, 0] - sn * points[:, 1], sn * points[:, 0] + c * points[:, 1]
            k = len(self.pins)
            res[:, :2 * k] = (r[:, :k] + t[:, :k] - r[:, k:] - t[:, k:]).reshape(n, 2 * k)
            if jacobian:                # d/dphi of +-R(phi) p: +-perp(R(phi) p) in the body's angle column
                jac[:, pin_rows, cols] = -signs * r[:, entries, 1]
                jac[:, pin_rows + 1, cols] = signs * r[:, entries, 0]
        if self.slides:
            f = self.frames(q, known)
            row = 2 * len(self.pins)
            for p, a, g, n0 in self.slides:
                ang = np.arctan2(f.s[a] * f.c[g] - f.c[a] * f.s[g], f.c[a] * f.c[g] + f.s[a] * f.s[g])
                res[:, row] = ang
                ra, rg = _rot(f, a, p), _rot(f, g, p)
                normal = _rot(f, g, n0)
                d = ra + f.T[a] - rg - f.T[g]
                res[:, row + 1] = _dot(normal, d)
                ca, cg = self.column(a), self.column(g)
                if ca is not None and jacobian:
                    jac[:, row + 1, ca] = _dot(normal, _perp(ra))
                    jac[:, row + 1, ca + 1:ca + 3] = normal
                if cg is not None and jacobian:
                    jac[:, row + 1, cg] = _dot(_perp(normal), d) - _dot(normal, _perp(rg))
                    jac[:, row + 1, cg + 1:cg + 3] = -normal
                row += 2
        return res, jac

    @cached_property
    def _pin_table(self) -> tuple[tuple[str, ...], np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                                  np.ndarray]:
        """The pins as arrays for :meth:`residual`: the group's bodies, then the known ones the pins join; for each
        of the 2 k sides (every pin's a, then every pin's b) its body's index among them and the drawn point (2 k, 2)
        mm; and the sides on a group body: which side, its pin's first row, the body's angle column, the sign (+1 a,
        -1 b)."""
        joined = dict.fromkeys(body for _, a, b in self.pins for body in (a, b))
        names = self.bodies + tuple(b for b in joined if b not in self.bodies)
        k = len(self.pins)
        sides = np.array([names.index(a) for _, a, _ in self.pins] + [names.index(b) for _, _, b in self.pins])
        points = np.array([p for p, _, _ in self.pins] * 2, dtype=float).reshape(2 * k, 2)
        entries = [e for e in range(2 * k) if self.column(names[sides[e]]) is not None]
        cols = [self.column(names[sides[e]]) for e in entries]
        return (names, sides, points, np.array(entries, dtype=int), 2 * (np.array(entries, dtype=int) % k),
                np.array(cols, dtype=int), np.array([1.0 if e < k else -1.0 for e in entries]))

    @cached_property
    def _constant(self) -> np.ndarray:
        """The Jacobian's entries that do not change with the pose (m, m): +-1 for a pin row's translations and a
        slider's angle row."""
        out = np.zeros((self.m, self.m))
        row = 0
        for _, a, b in self.pins:
            for body, sign in ((a, 1.0), (b, -1.0)):
                col = self.column(body)
                if col is not None:
                    out[row, col + 1] = out[row + 1, col + 2] = sign
            row += 2
        for _, a, g, _ in self.slides:
            for body, sign in ((a, 1.0), (g, -1.0)):
                col = self.column(body)
                if col is not None:
                    out[row, col] = sign
            row += 2
        return out

    def rows_scale(self) -> np.ndarray:
        """Each row's scale to mm: the drawing's size for a slider's angle row, else 1."""
        out = np.ones(self.m)
        for k in range(len(self.slides)):
            out[2 * len(self.pins) + 2 * k] = self.size
        return out

    def error(self, res: np.ndarray) -> np.ndarray:
        """The largest residual at each pose, mm, relative to the drawing's scale."""
        return np.max(np.abs(res * self._rows_scale), axis=1) / self.scale

    @cached_property
    def _rows_scale(self) -> np.ndarray:
        """:meth:`rows_scale`, once per group (read-only)."""
        out = self.rows_scale()
        out.flags.writeable = False
        return out

    def margin(self, q: np.ndarray, jac: np.ndarray) -> np.ndarray:
        """The smallest singular value of the scaled Jacobian over its largest (n,): 0 at a toggle. Each body's
        turn is taken about the centroid of its points (so that where the drawing sits does not matter) and in mm
        at the drawing's size, as a slider's angle row is."""
        scaled = jac * self.rows_scale()[None, :, None]
        for j, pts in enumerate(self.drawn):
            cx, cy = np.mean(pts, axis=0)
            c, s = np.cos(q[:, 3 * j]), np.sin(q[:, 3 * j])
            rx, ry = c * cx - s * cy, s * cx + c * cy
            scaled[:, :, 3 * j] = (scaled[:, :, 3 * j] + ry[:, None] * scaled[:, :, 3 * j + 1]
                                   - rx[:, None] * scaled[:, :, 3 * j + 2]) / self.size
        scaled = np.where(np.isfinite(scaled), scaled, 0.0)
        with np.errstate(invalid="ignore"):         # the singular values squared: J^T J's eigenvalues, ascending
            ev = np.maximum(np.linalg.eigvalsh(np.swapaxes(scaled, 1, 2) @ scaled), 0.0)
        return np.sqrt(ev[:, 0] / np.maximum(ev[:, -1], 1e-300))

    def points(self, q: np.ndarray) -> np.ndarray:
        """Every drawn point of the group's bodies in the world at q (n, k, 2), for the continuation's jump test."""
        which, p = self._drawn_table
        phi = q[:, 3 * which]
        c, s = np.cos(phi), np.sin(phi)
        out = np.empty((len(q), len(which), 2))
        out[..., 0], out[..., 1] = c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]
        return out + q[:, (3 * which + 1)[:, None] + np.arange(2)]

    @cached_property
    def _drawn_table(self) -> tuple[np.ndarray, np.ndarray]:
        """Each drawn point's body (its index in :attr:`bodies`) and the point (k, 2) mm, in :meth:`points`' order."""
        which = np.array([j for j, pts in enumerate(self.drawn) for _ in pts], dtype=int)
        return which, np.array([p for pts in self.drawn for p in pts], dtype=float).reshape(len(which), 2)



def _rot(f: Frames, body: str, p: np.ndarray) -> np.ndarray:
    """Drawn vector p turned by the body's rotation (n, 2)."""
    c, s = f.c[body], f.s[body]
    out = np.empty((len(c), 2))
    out[:, 0], out[:, 1] = c * p[0] - s * p[1], s * p[0] + c * p[1]
    return out


def group_of(s: Structure, step: GroupStep) -> Group:
    """The closure of a planned group."""
    def pt(name: str) -> np.ndarray:
        return np.asarray(s.points[name], dtype=float)

    sliders = s.slider_by_name
    slides = []
    for name in step.sliders:
        sl = sliders[name]
        slides.append((pt(sl.point), sl.body, sl.guide, np.array([-np.sin(sl.angle), np.cos(sl.angle)])))
    drawn = tuple(tuple(pt(p) for p in s.bodies[b]) for b in step.bodies)
    return Group(step.bodies, tuple((pt(p), a, b) for p, a, b in step.pins), tuple(slides), s.size, s.scale, drawn)


def _lsolve(jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve J x = rhs pose by pose (n, m); +inf where J is singular (a toggle), never NaN."""
    with np.errstate(all="ignore"):
        try:
            out = np.linalg.solve(jac, rhs[..., None])[..., 0]
        except np.linalg.LinAlgError:
            det = np.linalg.det(jac)
            safe = np.where((det != 0.0)[:, None, None], jac, np.eye(jac.shape[-1]))
            out = np.linalg.solve(safe, rhs[..., None])[..., 0]
            out[det == 0.0] = np.inf
    return np.where(np.isnan(out), np.inf, out)


def newton(group: Group, q: np.ndarray, known: Mapping[str, Pose], iterations: int = MAX_ITER
           ) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method from q (n, m) at every pose at once; the poses and where they converged (residual at most
    :data:`RESIDUAL` of the drawing's scale within ``iterations`` steps, then one more step to polish). A pose whose
    residual has not fallen below nine tenths of its best for :data:`STALL` steps is given up (no pose there)."""
    q = np.array(q, dtype=float)
    n = len(q)
    done = np.zeros(n, dtype=bool)
    live = np.ones(n, dtype=bool)                # still stepping: not polished, not given up
    best = np.full(n, np.inf)
    since = np.zeros(n, dtype=int)
    poses = group._known_poses(known)
    for _ in range(iterations + 1):
        rows = np.flatnonzero(live)
        if not len(rows):
            break
        sub = {b: _Row(p.c[rows], p.s[rows], p.T[rows]) for b, p in known.items()} if group.slides else known
        at = (poses[0][rows], poses[1][rows], poses[2][rows]) if poses[0].shape[1] else poses
        res, jac = group._residual(q[rows], at, sub, True)
        err = group.error(res)
        better = err < 0.9 * best[rows]
        best[rows] = np.minimum(best[rows], err)
        since[rows] = np.where(better, 0, since[rows] + 1)
        step = _lsolve(jac, res)
        finite = np.isfinite(step).all(axis=1) & np.isfinite(err)
        q[rows[finite]] -= step[finite]
        converged = err <= RESIDUAL
        done[rows] |= converged
        live[rows] = ~converged & finite & (since[rows] < STALL)
    res, _ = group._residual(q, poses, known, False)
    return q, done & (group.error(res) <= 10.0 * RESIDUAL)


@dataclass(frozen=True)
class Track:
    """A group's poses continued from the drawing: input values xs (k,) sorted and unknowns qs (k, m); ``period``
    (rad) for a crank, whose input values are read on the track by whole turns."""

    xs: np.ndarray
    qs: np.ndarray
    period: float | None = None
    #: whether the track stopped at a toggle going down and going up (else it reached the end of the span)
    stopped: tuple[bool, bool] = (False, False)

    def _on(self, x: np.ndarray) -> np.ndarray:
        return x if self.period is None else self.xs[0] + np.mod(x - self.xs[0], self.period)

    def guess(self, x: np.ndarray) -> np.ndarray:
        """The unknowns interpolated at inputs x (n,), the track's ends held beyond them (n, m)."""
        x = self._on(x)
        return np.column_stack([np.interp(x, self.xs, self.qs[:, k]) for k in range(self.qs.shape[1])])

    def covers(self, x: np.ndarray) -> np.ndarray:
        """Where inputs x (n,) lie on the track, or past an end of it that did not stop at a toggle: beyond a
        toggle (by more than :data:`MIN_STEP` of the track's length) the group has no pose on this assembly, even
        where Newton's method finds one of another."""
        x = self._on(x)
        tol = MIN_STEP * max(float(self.xs[-1] - self.xs[0]), 1.0)
        return ((x >= self.xs[0] - tol) | (not self.stopped[0])) & ((x <= self.xs[-1] + tol) | (not self.stopped[1]))


Upstream = Callable[[np.ndarray], Mapping[str, Pose]]


def track(group: Group, x0: float, lo: float, hi: float, upstream: Upstream, period: float | None = None) -> Track:
    """The group continued from the drawing (unknowns 0 at input x0) up to ``hi``, then down to ``lo`` unless the way
    up got there (a crank's full turn: ``lo`` is then ``hi`` less a turn, which the way up covers), stopping at the
    toggles that stop it; ``upstream`` gives the known bodies' poses at input values (n,); ``period`` the crank's
    turn, by which input values are read on it."""
    q0 = np.zeros((1, group.m))
    ahead = _walk(group, x0, q0, hi, upstream, period is not None)
    behind = (np.empty(0), np.empty((0, group.m)))
    if not len(ahead[0]) or ahead[0][-1] != hi:
        behind = _walk(group, x0, q0, lo, upstream, period is not None)
    up = not len(ahead[0]) or ahead[0][-1] != hi
    down = up and (not len(behind[0]) or behind[0][-1] != lo)
    low, high = (down, up) if hi >= lo else (up, down)
    return Track(np.concatenate([behind[0][::-1], [x0], ahead[0]]), np.concatenate([behind[1][::-1], q0, ahead[1]]),
                 period, (low, high))


def _grid(group: Group, x0: float, end: float, period: bool, per_span: int) -> np.ndarray:
    """The inputs a walk from x0 to ``end`` steps to: a crank's turn, or a slide's travel of the drawing's size, in
    ``per_span`` equal steps (the last one ``end``)."""
    span = abs(end - x0)
    steps = max(1, math.ceil(per_span * span / (2.0 * math.pi if period else group.size)))
    grid = x0 + (end - x0) / steps * np.arange(1, steps + 1)
    grid[-1] = end
    return grid


def _walk(group: Group, x0: float, q0: np.ndarray, end: float, upstream: Upstream, period: bool
          ) -> tuple[np.ndarray, np.ndarray]:
    """One way of :func:`track`: the inputs passed and the poses there.

    The walk is the same on the fine grid (:data:`TRACK_STEPS` a span) as step by step, but is first tried as a
    coarse walk (a step every :data:`COARSE` of the grid's) and one vectorised Newton solve at every point of the
    fine grid from the coarse track: taken if every point converges within :data:`JUMP` of the drawing's size of
    its guess and of the point before it (the step-by-step walk's own test), and the coarse walk reached ``end``
    (no toggle on the way). Anything else (a toggle, a point refused) is walked step by step on the fine grid."""
    if end == x0:
        return np.empty(0), np.empty((0, group.m))
    grid = _grid(group, x0, end, period, TRACK_STEPS)
    known_grid = upstream(grid)
    coarse = _steps(group, x0, q0, _grid(group, x0, end, period, max(1, TRACK_STEPS // COARSE)), upstream)
    if len(coarse[0]) and coarse[0][-1] == end:
        refined = _refined(group, x0, q0, grid, known_grid, coarse)
        if refined is not None:
            return grid, refined
    return _steps(group, x0, q0, grid, upstream, known_grid)


def _refined(group: Group, x0: float, q0: np.ndarray, grid: np.ndarray, known: Mapping[str, Pose],
             coarse: tuple[np.ndarray, np.ndarray]) -> np.ndarray | None:
    """The poses (k, m) at every point of ``grid`` (k,) by one vectorised Newton solve from the ``coarse`` walk's
    track interpolated there, or None unless every point converged within :data:`JUMP` of the drawing's size of its
    guess and of the point before it (x0's pose q0 before the first)."""
    xs, qs = np.concatenate([[x0], coarse[0]]), np.concatenate([q0, coarse[1]])
    order = np.argsort(xs)
    guess = np.column_stack([np.interp(grid, xs[order], qs[order, k]) for k in range(group.m)])
    q, ok = newton(group, guess, known, MAX_ITER)
    if not ok.all():
        return None
    moved = group.points(q)
    path = np.concatenate([group.points(q0), moved])
    if np.max(np.hypot(*np.moveaxis(moved - group.points(guess), -1, 0))) > JUMP * group.size or \
            np.max(np.hypot(*np.moveaxis(np.diff(path, axis=0), -1, 0))) > JUMP * group.size:
        return None
    return q


def _steps(group: Group, x0: float, q0: np.ndarray, grid: np.ndarray, upstream: Upstream,
           known_grid: Mapping[str, Pose] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The walk step by step from x0 (pose q0) through ``grid``'s inputs (``known_grid`` the known bodies' poses
    there, else asked of ``upstream``): each step predicted by the secant, corrected by Newton, halved where it does
    not converge or jumps, down to :data:`MIN_STEP` of the span (a toggle: the walk ends there)."""
    if known_grid is None:
        known_grid = upstream(grid)
    end = float(grid[-1])
    span = abs(end - x0)
    h = (end - x0) / len(grid)
    xs: list[float] = []
    qs: list[np.ndarray] = []
    x, q, prev = x0, q0, None
    here = group.points(q)
    smallest = MIN_STEP * max(span, 1e-300)
    i, step = 0, h
    while i < len(grid):
        # the grid point when the step reaches it (to rounding: grid[i] - x may be h and a few ulps, which once
        # stepped just short of it and then the ulps, two solves for one step)
        target = float(grid[i]) if abs(step) >= abs(grid[i] - x) * (1.0 - 1e-9) else x + step
        at_grid = target == float(grid[i])
        known = {b: _take(p, i) for b, p in known_grid.items()} if at_grid else upstream(np.array([target]))
        guess = q if prev is None else q + (q - prev[1]) * (target - x) / (x - prev[0])
        qn, ok = newton(group, guess, known, STEP_ITER)
        moved = group.points(qn) if ok[0] else here
        if ok[0] and np.max(np.hypot(*(moved - here)[0].T)) <= JUMP * group.size:
            prev, x, q, here = (x, q), target, qn, moved
            xs.append(x)
            qs.append(q[0])
            i += at_grid
            step = 2.0 * step if abs(2.0 * step) <= abs(h) else h
        elif abs(step) <= smallest:
            break                               # the group locks here: a toggle
        else:
            step = 0.5 * (target - x)
    return np.array(xs), np.array(qs).reshape(len(xs), group.m)


@dataclass(frozen=True)
class _Row:
    """Some poses of a known body (a :class:`Pose`)."""

    c: np.ndarray
    s: np.ndarray
    T: np.ndarray


def _take(p: Pose, i: int) -> Pose:
    """Pose i of a known body's poses, as one pose."""
    return _Row(p.c[i:i + 1], p.s[i:i + 1], p.T[i:i + 1])


def derivatives(group: Group, q: np.ndarray, known: Mapping[str, Pose], moving: Mapping[str, Movement]
                ) -> dict[str, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """Each group body's rates per unit input speed at the poses q: (w, vT, al, aT), from the known bodies' by the
    closure differentiated once and twice (two linear solves with the group's Jacobian; +inf at a toggle)."""
    f = group.frames(q, known)
    _, jac = group.residual(q, known)
    n = len(q)
    zero1, zero2 = np.zeros(n), np.zeros((n, 2))
    rates = {b: (mv.w, mv.vT, mv.al, mv.aT) for b, mv in moving.items()}
    for b in group.bodies:
        rates[b] = (zero1, zero2, zero1, zero2)
    first, _ = _closure_rates(group, f, rates)
    qd = _lsolve(jac, -first)
    for j, b in enumerate(group.bodies):
        rates[b] = (qd[:, 3 * j], qd[:, 3 * j + 1:3 * j + 3], zero1, zero2)
    _, second = _closure_rates(group, f, rates)
    qdd = _lsolve(jac, -second)
    return {b: (qd[:, 3 * j], qd[:, 3 * j + 1:3 * j + 3], qdd[:, 3 * j], qdd[:, 3 * j + 1:3 * j + 3])
            for j, b in enumerate(group.bodies)}


def _closure_rates(group: Group, f: Frames, rates: Mapping[str, tuple[np.ndarray, ...]]
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The closure's first and second time derivatives (n, m) at the bodies' rates (w, v, al, a) per body."""
    n = len(next(iter(f.c.values())))
    first, second = np.zeros((n, group.m)), np.zeros((n, group.m))

    def moved(body: str, p: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        r = _rot(f, body, p)
        w, v, al, a = rates[body]
        return r, w[:, None] * _perp(r) + v, al[:, None] * _perp(r) - (w**2)[:, None] * r + a

    row = 0
    for p, a, b in group.pins:
        (_, da, dda), (_, db, ddb) = moved(a, p), moved(b, p)
        first[:, row:row + 2], second[:, row:row + 2] = da - db, dda - ddb
        row += 2
    for p, a, g, n0 in group.slides:
        wa, _, ala, _ = rates[a]
        wg, _, alg, _ = rates[g]
        first[:, row], second[:, row] = wa - wg, ala - alg
        (ra, da, dda), (rg, dg, ddg) = moved(a, p), moved(g, p)
        normal = _rot(f, g, n0)
        d = ra + f.T[a] - rg - f.T[g]
        dn = wg[:, None] * _perp(normal)
        ddn = alg[:, None] * _perp(normal) - (wg**2)[:, None] * normal
        first[:, row + 1] = _dot(dn, d) + _dot(normal, da - dg)
        second[:, row + 1] = _dot(ddn, d) + 2.0 * _dot(dn, da - dg) + _dot(normal, dda - ddg)
        row += 2
    return first, second
