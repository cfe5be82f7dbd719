"""The cam a flat face cuts where its profile folds (``cam.allow_undercut``): the envelope of the face's lines with
its folds cut off; where the face leaves the law, and by how much.

Every position of the face leaves the cam on one side of its line: x . n <= p in the cam frame, with n the face's
outward normal and p its distance from the cam centre (mm), both functions of the cam angle theta. The cam a flat
face can cut is the intersection K of these half-planes over the cycle: convex, and holding the circle of radius
min p about the centre. Its edge is made of

* the envelope C(theta) = p n + (dp/dalpha) J n (the profile the law asks for) where C(theta) lies in K: there the
  face touches the cam where the law says; and
* a corner X for each stretch (theta_a, theta_b) of the cycle whose lines miss K (a fold: a swallowtail where the
  profile's radius of curvature p + d2p/dalpha2 goes negative, or where the contact jumps back at a velocity drop):
  X = C(theta_a) = C(theta_b), the point where the envelope crosses itself.

Over such a stretch the law's face stands p - X . n off the cam (its gap, mm along the face normal). A follower held
on the cam rides on the corner instead: its face lies at the cut cam's support X . n along its normal, so its motion
departs from the law; a translating face by the gap itself, an arm by the swing that brings its face onto X.

How: the lines are sampled (every 0.1 degree, and closely round each place where the radius of curvature is least
and negative), and those that bound K are the vertices of the convex hull of their dual points n / p (polar
duality: that hull is the polar of the intersection of the half-planes). A run of lines off the hull is a fold
(a line off the hull misses K too); its corner is found by Newton's method on C(u_a) = C(u_b), u running along the
envelope through every segment and along the straight pieces where the contact jumps at a velocity jump (a flat
where it jumps ahead, part of a fold where it jumps back), each step halved until it brings the two points closer
and kept outside the run's lines, and the corner found is checked to lie in K. A fold whose envelope strays less
than a thousandth of the tolerance from its corner is left as it is (that bound counts in the outline's error). The
stretches kept are made as an exact outline makes them (chords or biarcs measured against the envelope, exact arcs
on dwells); the corners are exact vertices, or, moved out by half a kerf, exact arcs of that radius round them. No
vertex may stand outside any sampled line (moved out as the outline is) by more than the tolerance: that too counts
in the outline's measured error.
"""
from __future__ import annotations

import dataclasses
import functools
import itertools
import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from camgen.cam import Cam
from camgen.core.errors import DesignError
from camgen.core.shapes import Contour
from camgen.numeric import maximise
from camgen.outline import Outline, stretch

#: lines sampled per radian of cam angle (0.1 degree apart) to find the folds
_PER_RAD = 600
#: lines sampled across each place where the profile's radius of curvature is least and negative
_FOLD_SAMPLES = 512
#: the least difference of cam angle (rad) between two lines sampled
_APART = 1e-9
#: a fold whose envelope strays less than this part of the tolerance from its corner may be left uncut when its
#: corner cannot be located (it is below what a cutter or a float can tell)
_NEGLIGIBLE = 1e-3
#: Newton steps allowed to locate a corner
_NEWTON_STEPS = 100
#: runs of lines off the hull tried together as one fold when a run's own corner is not found
_MERGED_RUNS = 4
#: how many samples before and after a fold's run of lines its corner may lie (lines kept by the sampled hull may
#: still miss the cam)
_REACH = 32


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


@dataclass(frozen=True)
class _At:
    """Points of the envelope path: contact point, dC/du, the face's outward normal and distance p, cam angle."""

    point: np.ndarray
    tangent: np.ndarray
    normal: np.ndarray
    p: np.ndarray
    theta: np.ndarray
    piece: np.ndarray


class _Path:
    """The envelope of the face's lines as one closed path, parametrised by u.

    Along segment i, u = u0_i + theta - start_i and the point is the contact C(theta); where the contact jumps at
    the end of a segment (a velocity jump) a straight piece on that instant's face line joins C(end) to the next
    segment's C(start), its u running over |jump| / scale. ``kind`` is 0 for a segment, +1 for a flat (the contact
    jumps ahead: the face lies along the cam) and -1 for a jump back (always inside a fold).
    """

    def __init__(self, cam: Cam) -> None:
        self.cam = cam
        segments = cam.program.segments
        jumps = dict(cam.steps())
        starts: list[float] = []
        kinds: list[int] = []
        owners: list[int] = []
        ends: dict[int, tuple[np.ndarray, np.ndarray]] = {}    # a straight piece's end points, by its place
        u = 0.0
        for i, seg in enumerate(segments):
            starts.append(u)
            kinds.append(0)
            owners.append(i)
            u += seg.end - seg.start
            if i in jumps:
                j = (i + 1) % len(segments)
                a = cam.segment_pitch(i, seg.end).point[0]
                b = cam.segment_pitch(j, segments[j].start).point[0]
                starts.append(u)
                kinds.append(1 if jumps[i] > 0 else -1)
                ends[len(owners)] = a, b
                owners.append(i)
                u += float(np.linalg.norm(b - a)) / self.scale
        self.total = u
        self.starts = np.array([*starts, u])
        self.kinds = np.array(kinds)
        self.owners = np.array(owners)
        self.ends = ends

    @property
    def scale(self) -> float:
        """A length (mm) the cam's size sets: the base radius, at least 1."""
        return max(1.0, self.cam.base_radius)

    def piece_of(self, u: np.ndarray) -> np.ndarray:
        """The piece holding each u (taken round the cycle; a boundary belongs to the piece it starts)."""
        w = np.mod(u, self.total)
        return np.clip(np.searchsorted(self.starts, w, side="right") - 1, 0, len(self.kinds) - 1)

    def at(self, u: Any) -> _At:
        """The path at ``u`` (any array of values, taken round the cycle)."""
        u = np.atleast_1d(np.asarray(u, dtype=float))
        w = np.mod(u, self.total)
        piece = self.piece_of(u)
        point, tangent, normal = (np.empty((len(u), 2)) for _ in range(3))
        theta = np.empty(len(u))
        segments = self.cam.program.segments
        for k in np.unique(piece):
            mask = piece == k
            i = int(self.owners[k])
            seg = segments[i]
            local = w[mask] - self.starts[k]
            if self.kinds[k] == 0:
                t = np.clip(seg.start + local, seg.start, seg.end)
                g = self.cam.segment_pitch(i, t)
                point[mask], tangent[mask], normal[mask], theta[mask] = g.point, g.d1, g.normal, t
            else:
                a, b = self.ends[k]
                length = self.starts[k + 1] - self.starts[k]
                g = self.cam.segment_pitch(i, seg.end)
                point[mask] = a + (local / length)[:, None] * (b - a)
                tangent[mask] = (b - a) / length
                normal[mask], theta[mask] = g.normal[0], seg.end
        return _At(point, tangent, normal, (point * normal).sum(axis=1), theta, piece)

    def u_of(self, index: int, theta: np.ndarray) -> np.ndarray:
        """u along segment ``index`` at cam angles ``theta`` of it."""
        k = int(np.flatnonzero((self.owners == index) & (self.kinds == 0))[0])
        return self.starts[k] + theta - self.cam.program.segments[index].start

    def jump_before(self, index: int) -> float:
        """The u-length of the straight piece just before segment ``index`` (0 without a jump there)."""
        k = int(np.flatnonzero((self.owners == index) & (self.kinds == 0))[0])
        before = (k - 1) % len(self.kinds)
        return float(self.starts[before + 1] - self.starts[before]) if self.kinds[before] != 0 else 0.0


@dataclass(frozen=True)
class _Lines:
    """The face's lines sampled round the cycle, in order: normal, distance p, contact point; and where along the
    path each touches the envelope, from ``first`` to ``last`` (they differ at a velocity jump)."""

    normal: np.ndarray
    p: np.ndarray
    point: np.ndarray
    first: np.ndarray
    last: np.ndarray
    theta: np.ndarray

    def violation(self, points: np.ndarray) -> np.ndarray:
        """max over the lines of x . n - p for each of ``points`` (n, 2): how far each stands outside K as far as
        these lines tell (mm; <= 0 inside)."""
        out = np.empty(len(points))
        for lo in range(0, len(points), 256):
            chunk = points[lo:lo + 256]
            out[lo:lo + 256] = (chunk @ self.normal.T - self.p[None, :]).max(axis=1)
        return out


def _check_turning(cam: Cam) -> None:
    """Refuse a face whose line stops turning with the cam or turns back (an arm swinging as fast as the cam turns):
    its lines do not go round the cam once, and its envelope runs off to infinity."""
    theta, normals = [], []
    for i, seg in enumerate(cam.program.segments):
        m = max(16, math.ceil((seg.end - seg.start) * _PER_RAD))
        t = seg.start + (seg.end - seg.start) * np.arange(m) / m
        with np.errstate(all="ignore"):                  # where it stops turning its contact is infinitely far
            normals.append(cam.segment_pitch(i, t).normal)
        theta.append(t)
    normal = np.concatenate(normals)
    turning = _cross(normal, np.roll(normal, -1, axis=0))
    if not (np.all(turning > 0) or np.all(turning < 0)):
        at = math.degrees(np.concatenate(theta)[int(np.argmin(turning * np.sign(turning.sum())))]) % 360.0
        raise DesignError(f"the face turns back on the cam near {at:.4g} degrees (the arm swings faster than the "
                          "cam turns): no cam can be cut for it")


def _fold_depth(cam: Cam, index: int, theta: np.ndarray) -> np.ndarray:
    """-rho (mm) of the face's profile along segment ``index`` at cam angles ``theta`` (rad): positive in a fold."""
    return -cam.segment_pitch(index, theta).face_rho


def _sample(cam: Cam, path: _Path) -> _Lines:
    segments = cam.program.segments
    thetas, uf, ul = [], [], []
    for i, seg in enumerate(segments):
        m = max(16, math.ceil((seg.end - seg.start) * _PER_RAD))
        grid = seg.start + (seg.end - seg.start) * np.arange(m) / m
        extra = []
        if seg.kind != "dwell":
            rho = cam.segment_pitch(i, grid).face_rho
            before, after = np.r_[rho[:1], rho[:-1]], np.r_[rho[1:], rho[-1:]]
            at, least = maximise(functools.partial(_fold_depth, cam, i), seg.start, seg.end)
            centres = [*grid[(rho < 0) & (rho <= before) & (rho <= after)], *([at] if -least < 0 else [])]
            h = (seg.end - seg.start) / m
            for c in centres:
                extra.append(np.linspace(max(seg.start, c - 2 * h), min(seg.end, c + 2 * h), _FOLD_SAMPLES))
        theta = np.unique(np.concatenate([grid, *extra]))      # lines closer than 1e-9 rad tell nothing more
        theta = theta[(theta < seg.end - _APART) & np.concatenate([[True], np.diff(theta) > _APART])]
        u = path.u_of(i, theta)
        thetas.append(theta)
        ul.append(u)
        first = u.copy()
        first[0] -= path.jump_before(i)              # the line at a segment's start also touches the jump before it
        uf.append(first)
    theta_all = np.concatenate(thetas)
    index = np.concatenate([np.full(len(t), i) for i, t in enumerate(thetas)])
    point, normal = np.empty((len(theta_all), 2)), np.empty((len(theta_all), 2))
    for i in range(len(segments)):
        mask = index == i
        g = cam.segment_pitch(i, theta_all[mask])
        point[mask], normal[mask] = g.point, g.normal
    return _Lines(normal, (point * normal).sum(axis=1), point, np.concatenate(uf), np.concatenate(ul), theta_all)


def _hull_vertices(q: np.ndarray) -> np.ndarray:
    """Which of the points ``q`` (n, 2), in angular order round the origin inside their hull, are vertices of the
    hull (Graham's scan from the point farthest from the origin, a vertex; collinear points are not vertices)."""
    turn = 1.0 if _cross(q, np.roll(q, -1, axis=0)).sum() > 0 else -1.0
    start = int(np.argmax((q**2).sum(axis=1)))
    order = [int(k) for k in np.roll(np.arange(len(q)), -start)]
    stack: list[int] = []
    for k in [*order, start]:
        while len(stack) >= 2 and turn * float(_cross(q[stack[-1]] - q[stack[-2]], q[k] - q[stack[-1]])) <= 0:
            stack.pop()
        stack.append(k)
    keep = np.zeros(len(q), dtype=bool)
    keep[stack] = True
    return keep


def _runs(keep: np.ndarray) -> list[tuple[int, int]]:
    """The runs of False in the cyclic ``keep``: (last True before, first True after) index pairs."""
    n = len(keep)
    if keep.all():
        return []
    first = int(np.argmax(keep))             # start the walk at a kept line
    out, k = [], first
    for step in range(1, n + 1):
        j = (first + step) % n
        if keep[j]:
            if (j - k) % n > 1:
                out.append((k, j))
            k = j
    return out


@dataclass(frozen=True)
class FaceLeaves:
    """A stretch of the cycle where the face, placed by the law, misses the cut cam (its fold is cut off).

    ``start_deg``, ``end_deg``: cam angles (degrees in [0, 360)) where the face leaves the envelope and comes back
    to it; ``corner_mm``: the cut cam's corner, in the cam frame at theta = 0 (mm), on which a follower held on the
    cam rides meanwhile; ``gap_mm``: the most the law's face stands off the cam, along its normal, at
    ``gap_at_deg``; ``deviation``: the most the motion of a follower riding the cam falls short of the law, in the
    follower's unit (mm of travel, or degrees of the arm's swing) at ``deviation_at_deg``.
    """

    start_deg: float
    end_deg: float
    corner_mm: tuple[float, float]
    gap_mm: float
    gap_at_deg: float
    deviation: float
    deviation_at_deg: float
    unit: str

    def as_dict(self) -> dict[str, Any]:
        """The report's entry (figures rounded to 1e-9)."""
        def r(x: float) -> float:
            return round(float(x), 9)

        return {"start_deg": r(self.start_deg), "end_deg": r(self.end_deg), "corner_mm": [r(x) for x in self.corner_mm],
                "gap_mm": r(self.gap_mm), "gap_at_deg": r(self.gap_at_deg),
                f"deviation_{self.unit}": r(self.deviation), "deviation_at_deg": r(self.deviation_at_deg)}


@dataclass(frozen=True)
class _Corner:
    """A fold cut off: the path from ``ua`` to ``ub`` (ua < ub, ub maybe past the cycle's end) replaced by ``point``."""

    ua: float
    ub: float
    point: np.ndarray
    residual: float


class FlatEnvelope:
    """The cut cam of a flat face whose profile folds (see the module docstring), to ``tolerance`` mm, its curved
    stretches written as ``curves`` says (``"polylines"`` or ``"biarcs"``)."""

    def __init__(self, cam: Cam, tolerance: float, curves: str) -> None:
        if not cam.follower.flat or cam.is_plate:
            raise ValueError("a flat envelope is made for a disc cam's flat face")
        self.cam, self.tolerance, self.curves = cam, tolerance, curves
        _check_turning(cam)
        self.path = _Path(cam)
        self.lines = _sample(cam, self.path)
        if not self.lines.p.min() > 0:
            raise DesignError("the face's line passes the cam centre: no cam can be cut for it")
        self.uncut = 0.0                        # how far the folds left uncut stray from K (mm)
        self.corners = self._corners()
        self._outlines: dict[float, Outline] = {}

    # -- the folds -----------------------------------------------------------------------------------------------

    def _corners(self) -> list[_Corner]:
        lines, path = self.lines, self.path
        keep = _hull_vertices(lines.normal / lines.p[:, None])
        runs = _runs(keep)
        found: list[_Corner] = []
        k = 0
        while k < len(runs):
            a = runs[k][0]
            for m in range(k, min(k + _MERGED_RUNS, len(runs))):   # a sample kept by chance may split one fold
                corner = self._solve(a, runs[m][1])
                if corner is not None:
                    break
            if corner is None:
                self._uncut(a, runs[k][1])
                k += 1
                continue
            k = m + 1
            spread = self._spread(corner)
            if spread <= _NEGLIGIBLE * self.tolerance:     # a fold below what a cutter (or a float) can tell
                self.uncut = max(self.uncut, spread)
            else:
                found.append(corner)
        found = self._merged(found)
        for back in np.flatnonzero(path.kinds < 0):     # a jump back is always inside a fold
            mid = 0.5 * (path.starts[back] + path.starts[back + 1])
            if not any(_inside(mid, c, path.total) for c in found):
                raise DesignError(f"the fold at {math.degrees(path.at(mid).theta[0]) % 360:.4g} degrees could not be "
                                  "cut off; loosen output.tolerance or smooth the motion")
        return found

    def _spread(self, corner: _Corner) -> float:
        """How far (mm) the envelope strays from the corner over the stretch it cuts off: a bound on the error of
        leaving it uncut."""
        total, path = self.path.total, self.path
        # evenly, at every sampled line's contact and every piece's ends inside the stretch
        known = np.concatenate([self.lines.first, self.lines.last, path.starts])
        known = corner.ua + (known - corner.ua) % total
        u = np.concatenate([np.linspace(corner.ua, corner.ub, 257), known[known <= corner.ub]])
        return float(np.linalg.norm(path.at(u).point - corner.point, axis=1).max())

    def _uncut(self, a: int, b: int) -> None:
        """A run of lines off the hull whose corner Newton's method could not find: negligible, or refused."""
        lines = self.lines
        k = np.arange(a, a + (b - a) % len(lines.p) + 1) % len(lines.p)
        spread = float(np.linalg.norm(lines.point[k] - lines.point[a], axis=1).max())
        if spread > _NEGLIGIBLE * self.tolerance:
            at = math.degrees(lines.theta[a]) % 360.0
            raise DesignError(f"the fold of the profile near {at:.4g} degrees could not be cut off (its corner was not "
                              "found); loosen output.tolerance or smooth the motion")
        self.uncut = max(self.uncut, spread)

    def _solve(self, a: int, b: int) -> _Corner | None:
        """The corner of the fold whose lines run off the hull from sample ``a`` (kept) to ``b`` (kept), by
        :meth:`_newton` from the kept lines' contacts, each kept where the corner must lie: every line off the hull
        misses K, so the fold's stretch holds every point of the path those lines touch (ua at most where line a + 1
        first touches, ub at least where line b - 1 last touches), and it reaches at most _REACH samples beyond a
        and b. None where no such corner is found."""
        lines, path = self.lines, self.path
        n, total = len(lines.p), path.total
        ua = float(lines.last[a])
        ub = ua + (float(lines.first[b]) - ua) % total

        def ahead(u: float, ref: float) -> float:          # u taken round the cycle to at or after ref
            return ref + (u - ref) % total

        def behind(u: float, ref: float) -> float:
            return ref - (ref - u) % total

        low_a = behind(float(lines.first[(a - _REACH) % n]), ua) if (b - a) % n + 2 * _REACH < n else ua - total
        high_a = ahead(float(lines.first[(a + 1) % n]), ua)
        low_b = behind(float(lines.last[(b - 1) % n]), ub)
        high_b = ahead(float(lines.last[(b + _REACH) % n]), ub) if (b - a) % n + 2 * _REACH < n else ub + total
        if not (low_a <= ua <= high_a < low_b <= ub <= high_b):
            return None

        # from the kept lines' contacts nearest the fold, their far ends where a line touches a whole flat, and the
        # lines before and after them (a fold that starts where a segment does turns the path back right there)
        starts_a = [ua, behind(float(lines.first[a]), ua), behind(float(lines.last[(a - 1) % n]), ua)]
        starts_b = [ub, ahead(float(lines.last[b]), ub), ahead(float(lines.first[(b + 1) % n]), ub)]
        for start_a, start_b in itertools.product(dict.fromkeys(min(max(u, low_a), high_a) for u in starts_a),
                                                  dict.fromkeys(min(max(u, low_b), high_b) for u in starts_b)):
            corner = self._newton(start_a, start_b, (low_a, high_a), (low_b, high_b))
            if corner is not None:
                return corner
        return None

    def _newton(self, ua: float, ub: float, bound_a: tuple[float, float],
                bound_b: tuple[float, float]) -> _Corner | None:
        """Newton's method on C(ua) = C(ub) from ``ua``, ``ub``, each kept within its bounds (see :meth:`_solve`),
        each step halved until it brings the two points closer; the corner found is checked to lie in K. None where
        it does not converge there."""
        path, total, scale = self.path, self.path.total, self.path.scale

        def gap(u: np.ndarray) -> tuple[np.ndarray, _At]:
            at = path.at(u)
            return at.point[0] - at.point[1], at

        f, at = gap(np.array([ua, ub]))
        for _ in range(_NEWTON_STEPS):
            size = float(np.linalg.norm(f))
            if size <= 1e-12 * scale:
                break
            try:
                step = np.linalg.solve(np.column_stack([at.tangent[0], -at.tangent[1]]), -f)
            except np.linalg.LinAlgError:
                return None
            if not np.all(np.isfinite(step)):
                return None
            closer = False
            for _ in range(60):                              # halve the step until it brings the points closer
                ta = min(max(ua + float(step[0]), bound_a[0]), bound_a[1])
                tb = min(max(ub + float(step[1]), bound_b[0]), bound_b[1])
                if ta == ua and tb == ub:                    # the step is lost in the floats: so is any half of it
                    break
                g, there = gap(np.array([ta, tb]))
                closer = bool(np.linalg.norm(g) < size)
                if closer:
                    break
                step = step / 2
            if not closer:
                break                                        # as close as the floats tell: judged below
            ua, ub, f, at = ta, tb, g, there
        else:
            return None
        residual = float(np.linalg.norm(f))
        point = 0.5 * (at.point[0] + at.point[1])
        # what the floats can tell: u to its last bits, moved along the path at its speed there
        floor = 8 * np.finfo(float).eps * max(abs(ua), abs(ub), 1.0) * float(np.linalg.norm(at.tangent, axis=1).sum())
        if not residual <= 1e-11 * scale + floor or not self._in_cam(point, 1e-9 * scale):
            return None
        shift = ua - ua % total
        return _Corner(ua - shift, ub - shift, point, residual)

    def _in_cam(self, point: np.ndarray, slack: float) -> bool:
        """Whether ``point`` lies in K: no line stands inside it by more than ``slack`` mm (the sampled lines, then
        the best of them refined)."""
        lines = self.lines
        excess = point @ lines.normal.T - lines.p
        j = int(np.argmax(excess))
        if excess[j] > slack:
            return False
        n = len(lines.p)
        lo, hi = lines.theta[(j - 1) % n], lines.theta[(j + 1) % n]
        if hi <= lo:
            hi += 2 * math.pi
        _, worst = maximise(lambda t: _excess(self.cam, point, t), lo, hi, n=65, rounds=6)
        return worst <= slack

    def _merged(self, corners: list[_Corner]) -> list[_Corner]:
        """The corners in order round the cycle, each once: two runs of lines may find the same corner (the stretches
        of two corners of a convex cam never overlap, so overlapping ones are one)."""
        total = self.path.total
        out: list[_Corner] = []
        for c in sorted(corners, key=lambda c: c.ua):
            if out and c.ua < out[-1].ub:
                if c.ub - c.ua > out[-1].ub - out[-1].ua:
                    out[-1] = c
                continue
            out.append(c)
        if len(out) > 1 and out[-1].ub > out[0].ua + total:
            out.pop(0 if out[0].ub - out[0].ua < out[-1].ub - out[-1].ua else -1)
        return out

    # -- the outline ---------------------------------------------------------------------------------------------

    def outline(self, offset: float = 0.0) -> Outline:
        """The cut cam's outline moved out by ``offset`` mm (half a kerf; >= 0): the kept stretches of the envelope
        moved out along their normals, each corner an arc of radius ``offset`` round it (a vertex at 0). Its error
        is the largest of the stretches' measured errors, the corners' residuals and of how far any vertex stands
        outside the face's lines moved out by ``offset``."""
        if offset not in self._outlines:
            self._outlines[offset] = self._outline(offset)
        return self._outlines[offset]

    def _outline(self, offset: float) -> Outline:
        budget = self.tolerance - self.uncut
        verts, bulges, worst = [], [], self.uncut
        count = len(self.corners)
        for k, span in enumerate(self._kept()):
            for piece, lo, hi in self._overlaps(*span):
                v, b, err = self._piece(piece, lo, hi, budget, offset)
                verts.append(v)
                bulges.append(b)
                worst = max(worst, err)
            if count and offset > 0:
                corner = self.corners[(k + 1) % count]
                na, nb = self.path.at(corner.ua).normal[0], self.path.at(corner.ub).normal[0]
                turn = math.atan2(float(_cross(na, nb)), float(na @ nb))
                verts.append((corner.point + offset * na)[None, :])
                bulges.append(np.array([math.tan(turn / 4.0)]))
        worst = max([worst, *(c.residual for c in self.corners)])
        v = np.concatenate(verts)
        worst = max(worst, float((self.lines.violation(v) - offset).max()))
        contour = Contour(v, np.concatenate(bulges))
        if not worst <= self.tolerance:
            raise DesignError(f"output.tolerance: the cut-off envelope of the flat face cannot be brought within "
                              f"{self.tolerance:g} mm (reached {worst:.3g} mm); loosen the tolerance")
        return Outline(contour if contour.area > 0 else contour.reversed(), worst, envelope=True)

    def _piece(self, piece: int, lo: float, hi: float, tolerance: float,
               offset: float) -> tuple[np.ndarray, np.ndarray, float]:
        """Vertices and bulges of the path's ``piece`` from local u ``lo`` to ``hi``, moved out by ``offset``, the end
        left to what follows; and their error."""
        path, cam = self.path, self.cam
        i = int(path.owners[piece])
        seg = cam.program.segments[i]
        if path.kinds[piece] < 0:
            raise DesignError(f"the fold at {math.degrees(seg.end) % 360:.4g} degrees could not be cut off; loosen "
                              "output.tolerance or smooth the motion")
        if path.kinds[piece] > 0:                       # a flat: straight on along the face's line
            length = path.starts[piece + 1] - path.starts[piece]
            a, b = path.ends[piece]
            normal = cam.segment_pitch(i, seg.end).normal[0]
            return (a + lo / length * (b - a) + offset * normal)[None, :], np.zeros(1), 0.0
        whole = lo <= 0 and hi >= seg.end - seg.start
        span = None if whole else (seg.start + lo, min(seg.start + hi, seg.end))
        if self.curves == "biarcs" and (span is None or span[1] - span[0] > 1e-6):
            try:
                return stretch(cam, i, tolerance, -offset, "biarcs", span)
            except DesignError:                         # a fold left uncut bends too sharply for arcs: chords
                pass
        return stretch(cam, i, tolerance, -offset, "polylines", span)

    def _kept(self) -> list[tuple[float, float]]:
        """The stretches of the path the cut cam keeps, (from, to) in u in order round the cycle: from each corner's
        end to the next corner's start."""
        total = self.path.total
        if not self.corners:
            return [(0.0, total)]
        out = []
        for k, c in enumerate(self.corners):
            after = self.corners[(k + 1) % len(self.corners)]
            out.append((c.ub, after.ua + (total if k == len(self.corners) - 1 else 0.0)))
        return out

    def _overlaps(self, lo: float, hi: float) -> list[tuple[int, float, float]]:
        """The pieces of the path from u ``lo`` to ``hi`` (round the cycle as needed): (piece, from, to) in u from
        the piece's start, in order."""
        path = self.path
        out = []
        for turn in range(math.floor(lo / path.total), math.floor(hi / path.total) + 1):
            shift = turn * path.total
            for k in range(len(path.kinds)):
                a, b = path.starts[k] + shift, path.starts[k + 1] + shift
                x, y = max(lo, a), min(hi, b)
                if y - x > 1e-12:
                    out.append((k, x - a, y - a))
        return out

    # -- what the follower does ----------------------------------------------------------------------------------

    @cached_property
    def leaves(self) -> tuple[FaceLeaves, ...]:
        """Where the face placed by the law leaves the cut cam, one entry a fold cut off, in order round the cycle."""
        return tuple(self._leaving(c) for c in self.corners)

    def _angles(self, corner: _Corner) -> tuple[float, float]:
        """Cam angles (rad) where the face leaves the envelope and comes back, the second past the first."""
        ta, tb = float(self.path.at(corner.ua).theta[0]), float(self.path.at(corner.ub).theta[0])
        return ta, ta + (tb - ta) % (2 * math.pi)

    def _leaving(self, corner: _Corner) -> FaceLeaves:
        ta, tb = self._angles(corner)
        gap_at, gap = maximise(lambda t: -_excess(self.cam, corner.point, t), ta, tb)
        dev_at, dev = maximise(lambda t: self._shortfall(corner.point, t), ta, tb, n=129, rounds=8)

        def deg(t: float) -> float:
            return math.degrees(t) % 360.0

        return FaceLeaves(deg(ta), deg(tb), (float(corner.point[0]), float(corner.point[1])), max(gap, 0.0),
                          deg(gap_at), max(dev, 0.0), deg(dev_at), self.cam.follower.lift_unit)

    def _shortfall(self, point: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """How far (the follower's unit) the follower held on the cam stands short of the law at cam angles
        ``theta`` while it rides on the corner ``point``: the law's level less the level at which the face's line
        passes through the corner (bisection on the follower's own geometry)."""
        law = self.cam.program.evaluate(theta)[0]

        def inside(level: np.ndarray) -> np.ndarray:   # > 0 where the face at ``level`` cuts into the corner
            motion = np.zeros((4, len(theta)))
            motion[0] = level
            g = self.cam.follower.pitch(theta, motion)
            return g.normal @ point - (g.point * g.normal).sum(axis=1)

        high, step = law.copy(), np.ones_like(law)
        low = law - step
        for _ in range(64):
            short = inside(low) < 0
            if not short.any():
                break
            step = np.where(short, 2 * step, step)
            low = np.where(short, law - step, low)
        for _ in range(64):
            mid = 0.5 * (low + high)
            cut = inside(mid) > 0
            low, high = np.where(cut, mid, low), np.where(cut, high, mid)
        return law - 0.5 * (low + high)

    @cached_property
    def face_extent(self) -> tuple[float, float]:
        """Nearest and farthest contact along the face (mm, from the follower's ``face_origin``) of a follower held
        on the cut cam: the kept stretches, their flats' ends and the corners it rides on."""
        cam, follower = self.cam, self.cam.follower
        values: list[float] = []

        def extremes(func: Any, a: float, b: float) -> None:
            values.extend([maximise(func, a, b)[1], -maximise(lambda t: -func(t), a, b)[1]])

        for span in self._kept():
            for piece, lo, hi in self._overlaps(*span):
                i = int(self.path.owners[piece])
                seg = cam.program.segments[i]
                if self.path.kinds[piece] == 0:
                    extremes(lambda t, i=i: follower.face_position(cam.segment_pitch(i, t)), seg.start + lo,
                             min(seg.start + hi, seg.end))
                else:
                    u = self.path.starts[piece] + np.array([lo, hi])
                    g = cam.segment_pitch(i, np.full(2, seg.end))
                    values.extend(follower.face_position(dataclasses.replace(g, point=self.path.at(u).point)))
        for c in self.corners:
            extremes(lambda t, c=c: follower.face_position(_at_corner(cam, c.point, t)), *self._angles(c))
        return float(min(values)), float(max(values))


def _at_corner(cam: Cam, point: np.ndarray, theta: np.ndarray) -> Any:
    """The cam's pitch geometry at ``theta`` with the contact moved to the corner ``point``."""
    g = cam.pitch(theta)
    return dataclasses.replace(g, point=np.broadcast_to(point, g.point.shape).copy())


def _excess(cam: Cam, point: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """x . n - p of the face's line at cam angles ``theta`` (the law's) for the point x: > 0 where it stands inside."""
    g = cam.pitch(theta)
    return g.normal @ point - (g.point * g.normal).sum(axis=1)


def _inside(u: float, corner: _Corner, total: float) -> bool:
    """Whether path parameter ``u`` lies in the stretch ``corner`` cuts off."""
    return (u - corner.ua) % total < corner.ub - corner.ua


def flat_envelope(cam: Cam, tolerance: float, curves: str = "polylines") -> FlatEnvelope:
    """The cut cam of ``cam``'s flat face with its folds cut off (see :class:`FlatEnvelope`)."""
    return FlatEnvelope(cam, tolerance, curves)
