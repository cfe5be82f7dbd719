"""Keeping time: the crank motion that brings a four-bar's tracer to its targets at their times, and the cam
program (rise, dwell and return segments of polynomial laws) that makes a follower's arm swing the crank so.

Conventions: a time is the cam's shaft angle (degrees from the machine's start, in the shaft's sense of rotation);
the crank angle theta2 and the rocker angle theta4 are in degrees, counter-clockwise from the four-bar's ground
line, in the linkage's own frame (the crank pivot O2 at the origin, the rocker pivot O4 on +x), radians only inside
the four-bar's own calls. A crank rate w is degrees of crank per degree of shaft, its acceleration a degrees per
degree squared.

The law: between two consecutive points (time, crank angle) the crank follows a quintic (a polynomial law on a
rise, a return, or a dwell where both angles are equal) that meets the crank angle, rate and acceleration given at
both ends, so the motion is continuous to the acceleration (C2) over the turn and its jerk is finite. A target's
rate is the weighted harmonic mean of the two secant slopes beside it (Fritsch and Butland's, as a monotone cubic
takes it), zero where they differ in sign (the crank turns back there), at a dwell and where a neighbour holds
still; its acceleration is the change of those slopes over the mean of the two intervals, zero at a dwell and
beside one. A piece whose rate would change sign between its ends (an overshoot) has both its ends' rate and
acceleration halved until none does: each piece is monotone, checked exactly by the roots of its derivative. An
output's program (the rocker's rise, dwell and return) gives every point's rate and acceleration exactly, by the
inverse function's chain rule (theta2' = theta4' / k4, theta2'' = (theta4'' - k4' theta2'^2) / k4, k4 = d theta4 /
d theta2), so there the pieces reproduce the inverse motion to the step's sixth power.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics.fourbar import Assembly, FourBar

TWO_PI = 2.0 * math.pi
#: crank angles a range is searched at for the point of the tracer's path nearest a target
GRID = 2048
#: how many times a piece's end rates and accelerations are halved before they are set to 0 (monotone then)
HALVINGS = 30
#: a piece's normalised rate may dip this far below 0 and still count as monotone (rounding)
MONOTONE_TOL = 1e-12
#: two crank angles (degrees) this close are one (the piece between them is a dwell)
SAME_DEG = 1e-9


@dataclass(frozen=True)
class Reach:
    """Where the tracer comes nearest a target: the crank angle (degrees, in the representation of the crank's
    range it lies in), the distance (mm), the point of the path (mm) and the index of the crank's range (0 when
    the crank turns fully)."""

    crank_deg: float
    distance: float
    point: tuple[float, float]
    range_index: int


def crank_ranges(fb: FourBar) -> tuple[tuple[float, float], ...]:
    """The crank's reachable ranges (radians, lo < hi): the whole turn [0, 2 pi) when it turns fully."""
    return fb.input_ranges() or ((0.0, TWO_PI),)


def path(fb: FourBar, assembly: Assembly, theta2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The tracer's point P (n, 2) (mm) and d P / d theta2 (n, 2) (mm/rad) at crank angles ``theta2`` (radians,
    within reach and clear of the toggles, where the rate is unbounded)."""
    poses = fb.positions(theta2, assembly)
    k3 = fb.rates(poses)[0]
    ang = poses.theta3 + fb.point_angle
    rate = np.column_stack((-fb.crank * np.sin(theta2) - fb.point_distance * np.sin(ang) * k3,
                            fb.crank * np.cos(theta2) + fb.point_distance * np.cos(ang) * k3))
    return poses.point, rate


def nearest(fb: FourBar, assembly: Assembly, target: Sequence[float]) -> Reach:
    """The crank angle at which the tracer comes nearest ``target`` (x, y mm) on ``assembly``: the roots of
    (P - T) . P' (half the derivative of the squared distance) where it turns from negative to positive on a grid
    of :data:`GRID` angles a range, each refined by Brent's method to 1e-14 radians, and the ranges' ends."""
    t = np.asarray(target, dtype=float)

    def slope(x: float) -> float:
        p, d = path(fb, assembly, np.array([x]))
        return float((p[0] - t) @ d[0])

    best: Reach | None = None
    full = fb.input_ranges() is None
    for index, (lo, hi) in enumerate(crank_ranges(fb)):
        step = (hi - lo) / GRID
        grid = lo + step * (np.arange(GRID) + (0.0 if full else 0.5))       # clear of a limited crank's toggles
        p, d = path(fb, assembly, grid)
        g = np.einsum("ij,ij->i", p - t, d)
        left, right = (grid, grid + step) if full else (grid[:-1], grid[1:])
        g_left, g_right = (g, np.roll(g, -1)) if full else (g[:-1], g[1:])
        found = [_root(slope, float(a), float(b)) if gb > 0 else float(b)
                 for a, b, ga, gb in zip(left, right, g_left, g_right, strict=True) if ga < 0 <= gb]
        candidates = np.array([*found, *([] if full else [lo, hi]), float(grid[int(np.argmin(np.hypot(*(p - t).T)))])])
        points = fb.positions(candidates, assembly).point
        dist = np.hypot(*(points - t).T)
        i = int(np.argmin(dist))
        if best is None or dist[i] < best.distance:
            angle = float(candidates[i]) % TWO_PI if full else float(candidates[i])
            best = Reach(math.degrees(angle), float(dist[i]), (float(points[i, 0]), float(points[i, 1])), index)
    assert best is not None
    return best


def _root(slope: Callable[[float], float], a: float, b: float) -> float:
    """Where ``slope`` turns from negative at ``a`` to positive at ``b`` (radians), by Brent's method to 1e-14; the
    end nearer zero where a single evaluation does not see the sign change the grid's did (a root at an end)."""
    from scipy.optimize import brentq

    fa, fb = slope(a), slope(b)
    if fa * fb > 0 or fa == 0 or fb == 0:
        return a if abs(fa) <= abs(fb) else b
    return float(brentq(slope, a, b, xtol=1e-14))


def unwrapped(angles_deg: Sequence[float], full: bool) -> np.ndarray:
    """Crank angles (degrees) in one interval, shortest round the circle: for a crank that turns fully, cut at the
    widest gap between them (the arm that swings it never crosses that gap); a limited crank's as they are."""
    a = np.asarray(angles_deg, dtype=float)
    if not full or len(a) < 2:
        return a
    m = np.mod(a, 360.0)
    order = np.sort(m)
    gaps = np.diff(np.r_[order, order[0] + 360.0])
    low = order[(int(np.argmax(gaps)) + 1) % len(order)]
    return low + np.mod(m - low, 360.0)


@dataclass(frozen=True)
class Piece:
    """The crank's motion from shaft angle ``t0`` to ``t1`` (degrees): from ``y0`` to ``y1`` (degrees of crank),
    leaving at rate ``w0`` and acceleration ``a0`` and arriving at ``w1`` and ``a1`` (degrees per degree of shaft,
    per degree squared)."""

    t0: float
    t1: float
    y0: float
    y1: float
    w0: float = 0.0
    a0: float = 0.0
    w1: float = 0.0
    a1: float = 0.0

    @property
    def still(self) -> bool:
        """Whether the crank holds still over it (a dwell)."""
        return abs(self.y1 - self.y0) <= SAME_DEG

    def progress(self) -> tuple[float, float, float, float]:
        """p'(0), p''(0), p'(1), p''(1) of the normalised progress p(u) = (y - y0) / (y1 - y0), u = (t - t0) /
        (t1 - t0): the piece's ends in a polynomial law's units."""
        beta, h = self.t1 - self.t0, self.y1 - self.y0
        return self.w0 * beta / h, self.a0 * beta ** 2 / h, self.w1 * beta / h, self.a1 * beta ** 2 / h

    def quintic(self) -> np.ndarray:
        """The power coefficients c0..c5 of p(u) (see :meth:`progress`)."""
        v0, q0, v1, q1 = self.progress()
        c2 = q0 / 2.0
        rhs = np.array([1.0 - v0 - c2, v1 - v0 - 2.0 * c2, q1 - 2.0 * c2])
        c345 = np.linalg.solve(np.array([[1.0, 1.0, 1.0], [3.0, 4.0, 5.0], [6.0, 12.0, 20.0]]), rhs)
        return np.r_[0.0, v0, c2, c345]

    def monotone(self) -> bool:
        """Whether the crank moves one way only over the piece: p' >= 0 on [0, 1], checked at the ends and at the
        real roots of p'' inside (a dwell always is)."""
        if self.still:
            return True
        c = np.polynomial.Polynomial(self.quintic())
        d1, d2 = c.deriv(), c.deriv(2)
        roots = d2.roots()
        inside = [float(r.real) for r in roots if abs(r.imag) < 1e-12 and 0.0 < float(r.real) < 1.0]
        return float(min(d1(np.array([0.0, 1.0, *inside])))) >= -MONOTONE_TOL

    def segment(self) -> dict[str, object]:
        """The piece as a cam template's ``[[motion]]`` entry: a dwell, or a rise or return of law
        ``"polynomial"`` whose conditions are its ends (a return runs its law backwards: f(v) = 1 - p(1 - v))."""
        angle = float(self.t1 - self.t0)
        if self.still:
            return {"type": "dwell", "angle": angle}
        v0, q0, v1, q1 = (float(v) for v in self.progress())
        rise = bool(self.y1 > self.y0)
        start, end = ((0.0, v0, q0), (1.0, v1, q1)) if rise else ((0.0, v1, -q1), (1.0, v0, -q0))
        conditions = [[0.0, 0, 0.0], [0.0, 1, start[1]], [0.0, 2, start[2]],
                      [1.0, 0, 1.0], [1.0, 1, end[1]], [1.0, 2, end[2]]]
        return {"type": "rise" if rise else "return", "angle": angle, "lift": float(abs(self.y1 - self.y0)),
                "law": "polynomial", "conditions": conditions}


def through_targets(times: Sequence[float], crank: Sequence[float], dwells: Sequence[float]) -> list[Piece]:
    """The pieces that take the crank through angles ``crank`` (degrees) at shaft angles ``times`` (degrees,
    increasing over less than a turn), holding at each for its ``dwells`` (degrees of shaft), round the turn (see
    the module's law)."""
    t, y, d = (np.asarray(v, dtype=float) for v in (times, crank, dwells))
    n = len(t)
    leave = t + d
    arrive = np.r_[t[1:], t[0] + 360.0]
    gap = arrive - leave
    slope = (np.roll(y, -1) - y) / gap                      # the move from target k to k + 1
    before, gap_before = np.roll(slope, 1), np.roll(gap, 1)
    w, a = np.zeros(n), np.zeros(n)
    for k in range(n):
        if d[k] > 0 or abs(slope[k]) * gap[k] <= SAME_DEG or abs(before[k]) * gap_before[k] <= SAME_DEG:
            continue                                        # a dwell, or beside a piece that holds still
        a[k] = (slope[k] - before[k]) / ((gap[k] + gap_before[k]) / 2.0)
        if slope[k] * before[k] > 0:
            w1, w2 = 2.0 * gap[k] + gap_before[k], gap[k] + 2.0 * gap_before[k]
            w[k] = (w1 + w2) / (w1 / before[k] + w2 / slope[k])
    scale = np.ones(n)

    def pieces() -> list[Piece]:
        out = []
        for k in range(n):
            j = (k + 1) % n
            if d[k] > 0:
                out.append(Piece(t[k], leave[k], y[k], y[k]))
            out.append(Piece(leave[k], arrive[k], y[k], y[j], w[k] * scale[k], a[k] * scale[k], w[j] * scale[j],
                             a[j] * scale[j]))
        return out

    for round_ in range(HALVINGS + 1):
        made = pieces()
        bad = [k for k, p in zip(_mover_of(d), made, strict=True) if k >= 0 and not p.monotone()]
        if not bad:
            return made
        for k in bad:
            for node in (k, (k + 1) % n):
                scale[node] = 0.0 if round_ >= HALVINGS - 1 else scale[node] / 2.0
    return pieces()                                        # every rate and acceleration 0: each piece monotone


def _mover_of(dwells: np.ndarray) -> list[int]:
    """For each piece :func:`through_targets` makes, the target its move leaves from, or -1 for a dwell."""
    out: list[int] = []
    for k, d in enumerate(dwells):
        out += ([-1] if d > 0 else []) + [k]
    return out


def program(pieces: Sequence[Piece]) -> tuple[float, float, list[dict[str, object]]]:
    """The cam's program from ``pieces`` (in order round the turn): its phase (the shaft angle it starts at, in
    [0, 360) degrees), the crank's angle there, the lowest of the turn (the follower's rest, swing 0), and its
    ``[[motion]]`` entries, from that lowest point."""
    first = int(np.argmin([p.y0 for p in pieces]))
    order = [*pieces[first:], *pieces[:first]]
    return float(order[0].t0 % 360.0), float(order[0].y0), [p.segment() for p in order]


@dataclass(frozen=True)
class Inverse:
    """An output's program turned into the crank's: at each point, the shaft angle (degrees), the crank angle
    (degrees) and its rate and acceleration (one-sided: the piece before a point sees ``w_in``, ``a_in``, the piece
    after it ``w_out``, ``a_out``)."""

    times: np.ndarray
    crank: np.ndarray
    w_in: np.ndarray
    a_in: np.ndarray
    w_out: np.ndarray
    a_out: np.ndarray

    def pieces(self) -> list[Piece]:
        """One piece between each two points, round the turn (the last point is the first's a turn later)."""
        n = len(self.times) - 1
        return [Piece(self.times[k], self.times[k + 1], self.crank[k], self.crank[k + 1], self.w_out[k],
                      self.a_out[k], self.w_in[k + 1], self.a_in[k + 1]) for k in range(n)]


def crank_for_rocker(fb: FourBar, assembly: Assembly, theta4_deg: np.ndarray,
                     prefer: str = "transmission") -> tuple[np.ndarray, str]:
    """Crank angles (degrees, continuous along the samples) that put the rocker at ``theta4_deg`` on the crank's
    ``assembly``, and the stroke's name: of the two strokes (the rocker-driven linkage's two assemblies, ``open`` and
    ``crossed``) those that are on it, the one whose transmission angle stays farthest from a toggle (``prefer =
    "transmission"``) or whose crank turns least (``"swing"``). Raises :class:`SpecError` when the rocker cannot
    reach those angles (naming ``angle``) or no stroke lies on the assembly (no field)."""
    t4 = np.radians(theta4_deg)
    options = []
    for stroke in ("open", "crossed"):
        theta2 = fb.rocker_positions(t4, stroke).theta2          # its reach refused there, naming 'angle'
        theta2 = np.unwrap(np.asarray(theta2, dtype=float))
        try:
            poses = fb.positions(theta2, assembly)
        except SpecError:
            continue
        if np.abs(np.angle(np.exp(1j * (poses.theta4 - t4)))).max() <= 1e-9:
            margin = float(np.minimum(poses.gamma, math.pi - poses.gamma).min())
            options.append((-margin if prefer == "transmission" else float(np.ptp(theta2)), stroke,
                            np.degrees(theta2)))
    if not options:
        raise SpecError(f"no stroke of the crank on its {assembly} assembly turns the rocker through these angles")
    options.sort(key=lambda o: o[0])
    return options[0][2], options[0][1]


def rocker_inverse(fb: FourBar, assembly: Assembly, times: np.ndarray, theta4: np.ndarray,
                   rates: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
                   prefer: str = "transmission") -> tuple[Inverse, str]:
    """The crank's motion that makes the rocker follow ``theta4`` (degrees) at shaft angles ``times`` (degrees),
    its one-sided rates there ``rates`` = (theta4' before, theta4'' before, after, after) in degrees per degree of
    shaft: the crank angle by :func:`crank_for_rocker` (its stroke by ``prefer``) and its rates by the inverse
    function's chain rule."""
    crank, stroke = crank_for_rocker(fb, assembly, theta4, prefer)
    poses = fb.positions(np.radians(crank), assembly)
    _, k4, _, k4d = fb.rates(poses)
    k4d = k4d * (math.pi / 180.0)                              # 1/rad -> 1/deg
    if np.abs(k4).min() < 1e-6:
        i = int(np.argmin(np.abs(k4)))
        raise SpecError(f"the rocker's program reaches {theta4[i]:.6g} degrees at its limit on this stroke, where "
                        "the crank would have to turn infinitely fast; keep the rocker within its swing")
    w_in, w_out = rates[0] / k4, rates[2] / k4
    a_in, a_out = (rates[1] - k4d * w_in ** 2) / k4, (rates[3] - k4d * w_out ** 2) / k4
    return Inverse(times, crank, w_in, a_in, w_out, a_out), stroke
