"""Motion programs: rise, dwell and return segments covering exactly 360 degrees.

Units: angles in radians inside (degrees only at the interface), displacement in mm
(or degrees of arm swing for an oscillating follower). Derivatives are with respect
to cam angle: s' in mm/rad, s'' in mm/rad^2, s''' in mm/rad^3. Theta is measured from
the start of the first segment, in the cam's sense of rotation.
"""
from __future__ import annotations

import functools
import math
import operator
from collections.abc import Callable, Generator
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from camgen.laws import Law
from camgen.numeric import TIE, drive, grid_counts, left_of, maxima_steps, present, search_grid

Kind = Literal["rise", "dwell", "return"]
TWO_PI = 2.0 * math.pi
#: relative size of a derivative jump that counts as a discontinuity
JUMP_TOL = 1e-9
QUANTITIES = {1: "velocity", 2: "acceleration", 3: "jerk"}
CONSEQUENCES = {1: "infinite acceleration", 2: "infinite jerk", 3: "finite jerk step"}


@dataclass(frozen=True)
class Segment:
    """One segment of a program.

    A rise takes s from ``level`` to ``level + lift`` with s = level + h f(u); a return
    mirrors it, s = level - h + h f(1 - u), from ``level`` down to ``level - lift``;
    a dwell holds ``level``. ``start`` and ``beta`` are in radians.

    Parameters
    ----------
    kind : str
        ``"rise"``, ``"dwell"`` or ``"return"``.
    start : float
        The cam angle the segment starts at (radians).
    beta : float
        The segment's cam angle (radians, > 0).
    lift : float, optional
        h: the follower's travel over it (mm, or degrees of an arm's swing; 0 for a dwell).
    level : float, optional
        s at the segment's start (mm, or degrees of an arm's swing).
    law : Law or None, optional
        The motion law of a rise or return; None for a dwell.
    """

    kind: Kind
    start: float
    beta: float
    lift: float = 0.0
    level: float = 0.0
    law: Law | None = None

    @property
    def end(self) -> float:
        return self.start + self.beta

    @property
    def end_level(self) -> float:
        return _end_level(self.kind, self.level, self.lift)

    def scale(self) -> np.ndarray:
        """Natural magnitudes h/beta^k of s, s', s'', s''' in this segment (k = 0..3)."""
        return _natural(np.array([self.lift if self.kind != "dwell" else 0.0]), np.array([self.beta]))[0]

    def evaluate(self, theta: ArrayLike) -> np.ndarray:
        """s, s', s'', s''' (shape ``(4, *theta.shape)``) at cam angles inside this segment (radians)."""
        theta = np.asarray(theta, dtype=float)
        flat = theta.ravel()
        if self.kind == "dwell" or self.law is None:
            out = np.zeros((4, flat.size))
            out[0] = self.level
        else:
            u = np.minimum(np.maximum((flat - self.start) / self.beta, 0.0), 1.0)      # np.clip's result
            out = self._from_law(self.law.derivatives(u if self.kind == "rise" else 1.0 - u))
        return out.reshape((4, *theta.shape))

    def _from_law(self, f: np.ndarray) -> np.ndarray:
        """s, s', s'', s''' from the law's f, f', f'', f''' (shape (4, n)) at the law's own argument."""
        factor, level = self._factors
        out = f * factor
        out[0] += level
        return out

    @cached_property
    def _factors(self) -> tuple[np.ndarray, float]:
        """What turns the law's derivatives into the segment's: each row's factor (4, 1), the natural scale with a
        return's odd rows negated (a sign: exact), and the level added to s (mm). Made once a segment."""
        factor = self.scale()[:, None]
        if self.kind == "return":
            return factor * _RETURN[:, None], self.level - self.lift
        return factor, self.level

    def at_law(self, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Cam angles (radians) and s, s', s'', s''' (shape ``(4, n)``) where the law's own variable is ``v`` (u for
        a rise, 1 - u for a return; a dwell's u), the law's pieces taken exactly as the law evaluates them."""
        if self.kind == "dwell" or self.law is None:
            out = np.zeros((4, v.size))
            out[0] = self.level
            return self.angle(v), out
        return self.angle(v), self._from_law(self.law.derivatives(v))

    def angle(self, v: ArrayLike) -> np.ndarray:
        """The cam angle (radians) where the law's own variable is ``v`` (see :meth:`at_law`)."""
        v = np.asarray(v, dtype=float)
        return self.start + self.beta * (1.0 - v if self.kind == "return" and self.law is not None else v)

    def pieces(self) -> list[tuple[float, float]]:
        """Closed intervals of the law's own variable (see :meth:`at_law`) on which s is smooth, with left limits
        at their right ends."""
        if self.kind == "dwell" or self.law is None:
            return [(0.0, 1.0)]
        return self.law.smooth_intervals()

    def inner_limits(self) -> list[tuple[float, np.ndarray, np.ndarray]]:
        """``(theta, left, right)``: s, s', s'', s''' on each side of every breakpoint of the law.

        Limits are taken exactly in the law's own variable; a return runs its law
        backwards, so there the law's left limit is the limit from the right in theta.
        """
        if self.law is None or self.kind == "dwell":
            return []
        out = []
        breakpoints = self.law.breakpoints
        for b in sorted(set(breakpoints)) if breakpoints else ():
            lo = self._from_law(self.law.derivatives(np.array([left_of(b)])))[:, 0]
            hi = self._from_law(self.law.derivatives(np.array([b])))[:, 0]
            if self.kind == "rise":
                out.append((self.start + b * self.beta, lo, hi))
            else:
                out.append((self.start + (1.0 - b) * self.beta, hi, lo))
        return out


@dataclass(frozen=True)
class Jump:
    """A discontinuity of a derivative of s at cam angle ``at_deg``.

    ``order`` 1, 2, 3 for s', s'', s''' (velocity, acceleration, jerk); ``jump`` is
    right minus left in mm/rad^order; ``inside`` is True when it lies inside a
    segment's law rather than at a segment boundary.
    """

    at_deg: float
    order: int
    jump: float
    inside: bool

    @property
    def quantity(self) -> str:
        return QUANTITIES[self.order]

    @property
    def consequence(self) -> str:
        return CONSEQUENCES[self.order]

    def as_dict(self) -> dict:
        return {"at_deg": self.at_deg, "quantity": self.quantity, "jump": self.jump,
                "units": f"mm/rad^{self.order}" if self.order > 1 else "mm/rad",
                "consequence": self.consequence, "where": "inside segment" if self.inside else "segment boundary"}


def _pair(v: np.ndarray, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:meth:`Program.maxima_steps`' ask unless told: the points' segments and law variables, ``(index, v)``."""
    return index, v


@dataclass(frozen=True)
class Program:
    """Ordered segments covering exactly one turn; s is continuous and returns to its start.

    Parameters
    ----------
    segments : tuple of Segment
        The segments in order from theta = 0, each starting where the one before ends.

    Raises
    ------
    SpecError
        Naming ``motion``: no segment, angles that do not add up to 2 pi, an end level that is not the start's, or
        a level below s = 0.
    """

    segments: tuple[Segment, ...]

    def __post_init__(self) -> None:
        segments = self.segments
        if not segments:
            raise SpecError("needs at least one segment", "motion")
        total = 0.0
        levels: list[float] = []
        for seg in segments:                            # the angles' running sum, each segment's start and end
            total += seg.beta
            levels += (seg.level, seg.end_level)
        _check_turn(total, levels)

    @property
    def max_lift(self) -> float:
        return max(max(seg.level, seg.end_level) for seg in self.segments)

    def top(self) -> float:
        """The largest displacement over the turn (mm, or degrees of swing), a law's overshoot included (a
        spline's or a polynomial's between its ends), by :meth:`peak`."""
        segments = self.segments
        return self.peak(lambda i, t: segments[i].evaluate(t)[0])[0]

    @property
    def starts(self) -> np.ndarray:
        return np.array([seg.start for seg in self.segments])

    def segment_index(self, theta: ArrayLike) -> np.ndarray:
        """Index of the segment holding each angle (a boundary belongs to the segment it starts)."""
        t = np.mod(np.asarray(theta, dtype=float), TWO_PI)
        return np.clip(np.searchsorted(self.starts, t, side="right") - 1, 0, len(self.segments) - 1)

    def evaluate(self, theta: ArrayLike) -> np.ndarray:
        """s, s', s'', s''' (shape ``(4, n)``) at any cam angles (radians, taken modulo 2 pi)."""
        t = np.mod(np.atleast_1d(np.asarray(theta, dtype=float)), TWO_PI)
        idx = self.segment_index(t)
        out = np.empty((4, t.size))
        for i in np.unique(idx):
            mask = idx == i
            out[:, mask] = self.segments[i].evaluate(t[mask])
        return out

    def maxima(self, func: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray],
               scale: ArrayLike = 0.0) -> list[tuple[float, float]]:
        """Largest value over the cycle of each row of ``func(theta, motion, index)`` -> (k, n), and where (degrees
        in [0, 360)): ``theta`` (n,) cam angles in radians, ``motion`` (4, n) s, s', s'', s''' there and ``index``
        (n,) the segment each lies in. :meth:`maxima_steps` with the values from ``func``."""
        table = self._table

        def answer(ask: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
            index, v = ask
            return func(table.angle(index, v), table.at_law(index, v), index)

        return drive(self.maxima_steps(lambda values: values, scale), answer)

    def maxima_steps(self, values: Callable[[Any], np.ndarray], scale: ArrayLike = 0.0, steady: bool = False,
                     ask: Callable[[np.ndarray, np.ndarray], Any] = _pair
                     ) -> Generator[Any, Any, list[tuple[float, float]]]:
        """:meth:`maxima` as a generator: it yields ``ask(v, index)`` (``(index, v)`` unless told), points given by
        their law variable (n,) (see :meth:`Segment.at_law`) and their segment (n,), and is sent what the caller
        evaluated there, which ``values`` turns into the rows (k, n) to maximise; it returns each row's (largest
        value, where in degrees). ``ask`` puts the points in the form the caller's evaluator takes, so that a maker
        of :meth:`camgen.cam.Cam.serve` is this generator itself; this one delegates to the search's own (see
        :func:`camgen.numeric.maxima_steps`), whose asks and answers pass no generator of its own.

        Every smooth piece of every segment is searched at once on its closed interval, with one-sided values at
        its ends (a segment's ends, and where its law changes piece), the maximiser located to ~1e-13 of the
        piece's angle (see :func:`camgen.numeric.maxima_steps`). Values within ``TIE`` (1e-12) of a row's
        magnitude (the larger of ``scale``, (k,) or a number, and its largest |value| seen) are equal: of equal
        peaks the one at the smallest angle is taken, so that rounding does not choose between them. ``steady``
        says that the values depend on the motion only, not on the cam angle, so that a dwell's are constant: its
        grid is then one point (see :func:`camgen.numeric.maxima_steps`).
        """
        owner, lo, hi, still, backwards, angles = self._pieces
        at, value, magnitude = yield from maxima_steps(
            lo, hi, scale=scale, reverse=backwards, steady=still if steady else False, n=self._grids, answer=values,
            ask=ask if owner is None else lambda v, piece: ask(v, owner[piece]))     # a piece's segment
        start, beta, back = angles
        x, v = np.array(at), np.array(value)
        # Segment.angle's, in degrees: the same operations on the same numbers
        degrees = np.degrees(start + beta * np.where(back, 1.0 - x, x)) % 360.0
        near = v >= (v.max(axis=1) - TIE * np.array(magnitude))[:, None]
        best = np.where(near, degrees, math.inf).argmin(axis=1)          # the first of the least angles
        rows = np.arange(len(at))
        return list(zip(v[rows, best].tolist(), degrees[rows, best].tolist(), strict=True))

    def search_grid(self, steady: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """The points :meth:`maxima_steps` (with this ``steady``) asks first, where every segment is one smooth
        piece, else None: their segments and law variables ((m,) each, read-only), the very arrays of its ask, so
        that an ask of them in the same round of :meth:`camgen.cam.Cam.serve` is evaluated once with it; and the
        count of points (read-only) of each grid that leads them, every moving segment's, segment after segment,
        each from its law variable 0 to 1 (:func:`camgen.numeric.grid_counts` of its angle; see
        :func:`camgen.numeric.search_grid`)."""
        owner, lo, hi, still, backwards, _ = self._pieces
        if owner is not None:
            return None
        v, index, sizes = search_grid(lo, hi, reverse=backwards, steady=still if steady else False, n=self._grids)
        return index, v, sizes

    @cached_property
    def _grids(self) -> np.ndarray:
        """Each smooth piece's count of search-grid points (see :func:`camgen.numeric.grid_counts`), from the cam
        angle it spans (its segment's angle times the law variable's span)."""
        _, lo, hi, _, _, (_, beta, _) = self._pieces
        return grid_counts(beta * (np.asarray(hi) - np.asarray(lo)))

    @cached_property
    def _table(self) -> _Table:
        """The segments as arrays, to evaluate any of them at once (see :class:`_Table`)."""
        return _Table(self.segments)

    def extents(self, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The start and angle (radians, (m,) each) of the segments ``index`` (m,): their ``start`` and ``beta`` (see
        :class:`Segment`), taken from the table's rows in one pass."""
        rows = self._table.rows
        return rows[_START].take(index), rows[_BETA].take(index)

    @property
    def dwells(self) -> np.ndarray:
        """Whether each segment is a dwell by its kind, (m,) bool (read-only)."""
        return self._table.dwells

    def evaluate_on(self, index: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """s, s', s'', s''' (shape ``(4, n)``) at cam angles ``theta`` (n,) (radians) each on the segment ``index``
        (n,) gives, as :meth:`Segment.evaluate` makes them (one-sided at the segment's ends), all at once."""
        return self._table.evaluate(index, np.asarray(theta, dtype=float))

    @cached_property
    def boundaries(self) -> tuple[np.ndarray, np.ndarray]:
        """Cam angles (2n,) (radians) and s, s', s'', s''' there (4, 2n): every segment's end (its left-hand limit),
        then the next segment's start (its right-hand limit; the last segment's next is the first), from one
        evaluation (as :meth:`Segment.evaluate` makes them)."""
        theta, index = self.boundary_points
        return theta, self.evaluate_on(index, theta)

    @cached_property
    def boundary_points(self) -> tuple[np.ndarray, np.ndarray]:
        """The angles (2n,) of :attr:`boundaries` (radians) and the segment each is evaluated on (2n,)."""
        segments = self.segments
        theta = np.array([seg.start + seg.beta for seg in segments] + [seg.start for seg in segments[1:]]
                         + [segments[0].start])            # Segment.end's sums, then the next segments' starts
        return theta, _boundary_segments(len(segments))

    @cached_property
    def _pieces(self) -> tuple[np.ndarray | None, np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                               tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """Every segment's smooth pieces (see :meth:`Segment.pieces`) as :meth:`maxima_steps` searches them: the
        owning segment of each (an array, to map asks; None where each segment is one piece, its own), the law
        variable's ends, whether its segment holds still (a dwell) and whether it runs its law backwards (a
        return, see :meth:`Segment.angle`), and the segments' starts, angles (radians) and backwards flags (arrays, a
        piece each), all from :class:`_Table`'s, a group's law's pieces asked once. Made once a program (read-only for
        its readers): a roller's design searches its program once, a flat face's or one with a speed up to eight
        times."""
        table = self._table
        # each group's law's pieces, once a group (a dwell's, and a law's without breakpoints, [0, 1] whole)
        intervals = [[(0.0, 1.0)] if law is None else law.smooth_intervals() for law in table.laws]
        count = np.array([len(iv) for iv in intervals], dtype=np.intp).take(table.group)     # pieces a segment
        rows, back = table.rows, table.back
        still = ~table.moves                            # a dwell, or a segment without a law
        angles = (rows[_START], rows[_BETA], back)
        if not (count > 1).any():                       # each segment one piece, its own: no mapping of the asks
            m = count.size
            return None, np.zeros(m), np.ones(m), still, back, angles
        owner = np.repeat(np.arange(count.size), count)
        ends = [np.array(iv, dtype=float).reshape(-1, 2) for iv in intervals]
        # each piece's place among its segment's: its group's interval of that rank
        first = np.cumsum(count) - count
        rank = np.arange(owner.size) - first[owner]
        flat = np.concatenate(ends)
        start = (np.cumsum([len(e) for e in ends]) - [len(e) for e in ends])
        pick = start.take(table.group)[owner] + rank
        lo, hi = flat[pick, 0], flat[pick, 1]
        return owner, lo, hi, still[owner], back[owner], (angles[0][owner], angles[1][owner], back[owner])

    def peak(self, func: Callable[[int, np.ndarray], np.ndarray]) -> tuple[float, float]:
        """Largest value of ``func(segment index, theta array)`` over the cycle, and where (degrees in [0, 360)),
        by :meth:`maxima` (``func`` called once a segment with that segment's angles)."""
        def values(theta: np.ndarray, motion: np.ndarray, index: np.ndarray) -> np.ndarray:
            out = np.empty(theta.size)
            for i in present(index):
                mask = index == i
                out[mask] = func(int(i), theta[mask])
            return out[None]

        return self.maxima(values)[0]

    def jumps(self, motion: np.ndarray | None = None) -> list[Jump]:
        """Every jump of s', s'', s''' at segment boundaries (360 wrapping to 0) and inside laws.

        A jump counts when it exceeds 1e-9 of the larger natural scale h/beta^k of
        the segments on either side. ``motion`` (4, 2n): the motion at :attr:`boundary_points` where it has been
        evaluated with other points (the same numbers as :attr:`boundaries`' own), else :attr:`boundaries`'.
        """
        n = len(self.segments)
        theta = self.boundary_points[0]
        if motion is None:
            motion = self.boundaries[1]
        # the boundaries all at once: each segment's end (its scales) against the next one's start (the next's)
        table = self._table
        step = motion[1:, n:] - motion[1:, :n]
        limit = JUMP_TOL * np.maximum(np.maximum(table.rates, table.next_rates), 1e-300)
        order, at = (np.abs(step) > limit).nonzero()
        degrees = _degrees(theta.take(at))
        # by angle, then by order, stably: the nonzero's order (by order, then by boundary) among equal ones
        ranked = np.lexsort((order, degrees))
        found = _found(degrees[ranked], order[ranked], step[order, at][ranked], inside=False)
        inner = self._inner_jumps()
        if inner:                                       # merged in the order of the list's own sort
            found += inner
            found.sort(key=_AT_ORDER)
        return found

    def _inner_jumps(self) -> list[Jump]:
        """The jumps inside the laws (see :meth:`Segment.inner_limits`), every segment's at once: each law group's
        breakpoints asked once, the limits on either side of all its segments' evaluated in one pass (the numbers
        of :meth:`Segment.inner_limits`), in the order of segment, breakpoint and order."""
        table = self._table
        index, v, low = [], [], []
        for g, law in enumerate(table.laws):
            if law is None or not law.breakpoints:
                continue
            cuts = sorted(set(law.breakpoints))
            members = (table.group == g).nonzero()[0]
            index.append(members.repeat(len(cuts)))
            v.append(np.tile(cuts, members.size))
            low.append(np.tile([left_of(b) for b in cuts], members.size))
        if not index:
            return []
        seg, b = np.concatenate(index), np.concatenate(v)
        keep = np.argsort(seg, kind="stable")           # segment by segment, each one's breakpoints in order
        seg, b, lo = seg[keep], b[keep], np.concatenate(low)[keep]
        m = seg.size
        motion = table.at_law(np.concatenate([seg, seg]), np.concatenate([lo, b]))
        left, right = motion[:, :m], motion[:, m:]
        back = table.back.take(seg)
        rows = table.rows
        start, beta = rows[_START].take(seg), rows[_BETA].take(seg)
        theta = np.where(back, start + (1.0 - b) * beta, start + b * beta)
        left, right = np.where(back, right, left), np.where(back, left, right)      # a return runs backwards
        jump = (right - left)[1:]
        own = table.rates.take(seg, axis=1)
        order, at = (np.abs(jump) > JUMP_TOL * np.maximum(own, 1e-300)).nonzero()
        ranked = np.lexsort((order, at))                # by point, then by order
        order, at = order[ranked], at[ranked]
        return _found(_degrees(theta.take(at)), order, jump[order, at], inside=True)


def _found(degrees: np.ndarray, order: np.ndarray, jump: np.ndarray, inside: bool) -> list[Jump]:
    """The :class:`Jump` of each derivative ``order`` (0 for s', (m,)) jumping by ``jump`` (m,) at ``degrees`` (m,),
    a cam angle as :func:`_degrees` gives it."""
    return [Jump(d, k, j, inside)
            for d, k, j in zip(degrees.tolist(), (order + 1).tolist(), jump.tolist(), strict=True)]


def _degrees(theta: np.ndarray) -> np.ndarray:
    """Cam angles ``theta`` (radians, (m,)) in degrees, rounded to 1e-9 and taken into [0, 360): for each,
    ``round(math.degrees(t), 9) % 360.0`` to the bit, all at once. np.degrees is math.degrees' product; the
    rounding is the integer nearest t 1e9 (ties to even) over 1e9, a correctly rounded quotient of two exact
    numbers, which is Python's round wherever the product t 1e9, itself rounded, lies further from a half than
    1e-15 of itself (more than twice its unit in the last place; a product of 1e15 or more never does, nor a NaN):
    the rest are rounded by Python's round, one by one. np.remainder is Python's float %."""
    with np.errstate(over="ignore", invalid="ignore"):  # a huge or infinite angle: Python's round and % decide
        degrees = np.degrees(theta)
        scaled = degrees * 1e9
        out = np.rint(scaled)
        off = np.abs(scaled - out)                      # to the nearest integer, exact: at most a half
        out /= 1e9
        for i in (~(np.abs(off - 0.5) > 1e-15 * np.abs(scaled))).nonzero()[0].tolist():
            out[i] = round(float(degrees[i]), 9)
        return np.remainder(out, 360.0, out=out)


class _Table:
    """A program's segments as arrays, so that points on any of them are evaluated in one pass: one call of each law
    for all its segments' points, the same operations on the same numbers as each segment's own evaluation (so the
    same values to the last bit).

    ``rows`` (12, m) holds, a segment a column, every number of it a point needs (see :data:`_START` and the rest),
    so that one gather gives each point its own (see :meth:`_gather`): its start and angle (radians), the sign and
    offset that turn u into the law's variable (-1 and 1 on a return, whose law runs backwards; 1 and 0 elsewhere),
    what is added to s, s', s'' and s''' (its level, mm, then three zeros: +0.0 on a dwell or a segment without a
    law, which makes a -0.0 +0.0, and -0.0 elsewhere, which leaves every number as it is) and the four factors of
    :meth:`Segment._from_law` (0 on a dwell); ``scales`` is every segment's :meth:`Segment.scale`, as floats."""

    def __init__(self, segments: tuple[Segment, ...]) -> None:
        m = len(segments)
        kinds = [seg.kind for seg in segments]
        laws_of = [seg.law for seg in segments]
        moving = np.fromiter((k != "dwell" and law is not None for k, law in zip(kinds, laws_of, strict=True)), bool, m)
        back = moving & np.fromiter((k == "return" for k in kinds), bool, m)
        lift = np.fromiter((seg.lift for seg in segments), float, m)
        level = np.fromiter((seg.level for seg in segments), float, m)
        sign = np.where(back, -1.0, 1.0)
        even = moving.astype(float)
        zero = np.where(moving, -0.0, 0.0)
        table = np.empty((_WIDTH, m))                   # a segment a column, every row filled in one pass
        table[_START] = np.fromiter((seg.start for seg in segments), float, m)
        table[_BETA] = np.fromiter((seg.beta for seg in segments), float, m)
        table[_SIGN] = sign
        table[_OFFSET] = back
        table[_ADDED.start] = np.where(back, level - lift, level)
        table[_ADDED.start + 1:_ADDED.stop] = zero
        table[_FACTORS.start::2][:2] = even
        table[_FACTORS.start + 1::2][:2] = np.where(moving, sign, 0.0)
        dwells = np.fromiter((k == "dwell" for k in kinds), bool, m)
        table[_H] = np.where(dwells, 0.0, lift)
        dwells.setflags(write=False)
        #: whether each segment is a dwell by its kind (m,) bool, read-only (see :attr:`Program.dwells`)
        self.dwells = dwells
        laws: list[Law | None] = []
        group = _groups(laws, [law if move else None for law, move in zip(laws_of, moving.tolist(), strict=True)])
        # every segment's Segment.scale, made in one pass from the table's contiguous h and beta rows: in _natural's
        # (m, 4) layout, whose power gives Segment.scale's bits at any m (an order a row, (4, m), differs in the last
        # bits of some from about 2 700 segments on)
        natural = _natural(table[_H], table[_BETA])
        self.scales: list[list[float]] = natural.tolist()
        #: the natural scales of the three derivatives (3, m), and the next segment's (the last's next is the first)
        self.rates = np.ascontiguousarray(natural[:, 1:].T)
        self.next_rates = np.concatenate([self.rates[:, 1:], self.rates[:, :1]], axis=1)
        # the factors: natural scales times the signs in their place, 1 (a rise), +-1 (a return's even and odd orders)
        # or 0 (a dwell): exact
        table[_FACTORS] *= natural.T
        self.rows = table[:_H]                                  # (12, m), C-ordered: gathered along its rows
        self.laws = laws
        #: each segment's law's place in :attr:`laws` (m,); whether it moves by a law (not a dwell) and whether it
        #: runs its law backwards (a return), (m,) bool each
        self.group = group
        self.moves, self.back = moving, back
        #: each law but a dwell's, with the segments it evaluates (m,) bool (a law alone evaluates every point)
        self.moving = [(law, group == k) for k, law in enumerate(laws) if law is not None]

    def angle(self, index: np.ndarray, v: np.ndarray) -> np.ndarray:
        """:meth:`Segment.angle` of each law variable ``v`` (n,) on its segment ``index`` (n,) (radians)."""
        out = np.empty(v.shape)
        self._angle(v, self._gather(index), out)
        return out

    def _gather(self, index: np.ndarray) -> np.ndarray:
        """The rows (12, n) of the points on the segments ``index`` (n,), each point's numbers in its column (rows
        :data:`_START` and the rest): a take along the second axis of :attr:`rows`, C-ordered (4 us for 600 points;
        a take of whole segment rows from a (m, 12) table is 1.7 us, but its transposed copy 4.6 us more)."""
        return self.rows.take(index, axis=1)

    @staticmethod
    def _angle(v: np.ndarray, rows: np.ndarray, out: np.ndarray) -> None:
        """:meth:`angle` into ``out``, the points' ``rows`` gathered: start + beta (1 - v) on a return, start + beta v
        elsewhere (the offset and sign give 1 + -v = 1 - v and 0 + v = v, or +0.0 for v = -0.0, which makes the
        same angle: start >= +0.0)."""
        np.multiply(v, rows[_SIGN], out=out)
        out += rows[_OFFSET]
        out *= rows[_BETA]
        out += rows[_START]

    @staticmethod
    def _variable(theta: np.ndarray, rows: np.ndarray, out: np.ndarray) -> None:
        """:meth:`variable` into ``out``, the points' ``rows`` gathered: u into [0, 1] (np.maximum gives +0.0 for
        -0.0, so that u is never -0.0), then 1 + -u = 1 - u on a return, 0 + u = u elsewhere."""
        np.subtract(theta, rows[_START], out=out)
        out /= rows[_BETA]
        np.maximum(out, 0.0, out=out)
        np.minimum(out, 1.0, out=out)                   # np.clip's result
        out *= rows[_SIGN]
        out += rows[_OFFSET]

    def evaluate(self, index: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """:meth:`Segment.evaluate` of each angle ``theta`` (n,) on its segment ``index`` (n,): (4, n)."""
        return self.on(index, theta, 0)[1]

    def variable(self, index: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The law variable (see :meth:`Segment.at_law`) at each angle ``theta`` (n,) (radians) on its segment
        ``index`` (n,), u taken into [0, 1] as :meth:`Segment.evaluate` takes it (one-sided at the segment's ends)."""
        out = np.empty(theta.shape)
        self._variable(theta, self._gather(index), out)
        return out

    def at_law(self, index: np.ndarray, v: np.ndarray) -> np.ndarray:
        """:meth:`Segment.at_law`'s motion at each law variable ``v`` (n,) on its segment ``index`` (n,): (4, n);
        one call of each law for every point on its segments."""
        return self._motion(index, v, self._gather(index))

    def on(self, index: np.ndarray, x: np.ndarray, cut: int) -> tuple[np.ndarray, np.ndarray]:
        """Cam angles (n,) (radians) and s, s', s'', s''' (4, n) at points ``x`` (n,) each on its segment ``index``
        (n,): the first ``cut`` of them given by the law's variable (see :meth:`Segment.at_law`), the rest by cam
        angle (one-sided at their segment's ends, as :meth:`Segment.evaluate` takes them)."""
        rows = self._gather(index)
        theta, v = x.copy(), x.copy()                   # each then made where it is not given
        if cut:
            self._angle(x[:cut], rows[:, :cut], theta[:cut])
        if cut < x.size:
            self._variable(x[cut:], rows[:, cut:], v[cut:])
        return theta, self._motion(index, v, rows)

    def _motion(self, index: np.ndarray, v: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """s, s', s'', s''' (4, n) at law variables ``v`` (n,) on the segments ``index`` (n,), their ``rows``
        gathered. A program of one law evaluates it at every point: a dwell's factors are 0, so that its s is
        (+-0) + level, its level to the bit (never -0.0), and its s', s'', s''' +-0, made +0.0 by adding +0.0 (a NaN
        ``v`` stays NaN there, as in s: no finite angle makes one). With more laws each evaluates its own points, a
        dwell's left 0. The levels and zeros are added in one call (see :class:`_Table`: -0.0 elsewhere, which changes
        no number)."""
        if len(self.moving) == 1:
            out = self.moving[0][0].derivatives(v) * rows[_FACTORS]
        else:
            out = np.zeros((4, v.size))
            for law, member in self.moving:
                sel = member.take(index).nonzero()[0]
                if sel.size:
                    out[:, sel] = law.derivatives(v.take(sel)) * rows[_FACTORS].take(sel, axis=1)
        out += rows[_ADDED]
        return out


#: the rows of :attr:`_Table.rows` and of what :meth:`_Table._gather` gives (the columns of the table it is made from):
#: start, angle, sign, offset, the level and three zeros added to s, s', s'', s''', and the four factors
_START, _BETA, _SIGN, _OFFSET, _ADDED, _FACTORS = 0, 1, 2, 3, slice(4, 8), slice(8, 12)
#: the column of the table after them (not in :attr:`_Table.rows`): each segment's h (the lift, 0 on a dwell); and
#: the columns' count
_H, _WIDTH = 12, 13
#: the signs that turn a rise's factors into a return's (the law runs backwards: odd derivatives change sign)
_RETURN = np.array([1.0, -1.0, 1.0, -1.0])


@functools.cache
def _boundary_segments(n: int) -> np.ndarray:
    """The segments (2n,) :attr:`Program.boundary_points` are evaluated on, read-only: each of the n segments (its
    end), then the next (its start; the last's next is the first)."""
    out = np.array([*range(n), *range(1, n), 0])
    out.setflags(write=False)
    return out


def _natural(h: np.ndarray, beta: np.ndarray) -> np.ndarray:
    """Natural magnitudes h/beta^k (k = 0..3) of s, s', s'', s''' of segments of lifts ``h`` (m,) (mm, 0 on a
    dwell) and angles ``beta`` (m,) (radians): (m, 4), see :meth:`Segment.scale`."""
    return h[:, None] / beta[:, None] ** _POWERS


_POWERS = np.arange(4.0)


def _groups(laws: list[Law | None], each: list[Law | None]) -> np.ndarray:
    """Where each law of ``each`` (None for a dwell) stands in ``laws``, the laws evaluated, each once (appended to
    it in the order they first come): the first it is or is :func:`_alike` (one class without parameters) to.
    Returns the group of each (m,) (intp); one dictionary look-up a segment, by identity or by a parameterless
    law's class."""
    known: dict[Any, int] = {}
    out = np.empty(len(each), dtype=np.intp)
    for i, law in enumerate(each):
        key = type(law) if law is not None and type(law).PARAMETERLESS else id(law)
        g = known.get(key)
        if g is None:
            g = known[key] = len(laws)
            laws.append(law)
        out[i] = g
    return out


def _alike(a: Law | None, b: Law | None) -> bool:
    """True when the laws ``a`` and ``b`` are one function: of one class that declares itself without parameters
    (:attr:`Law.PARAMETERLESS`: a cycloidal rise and a cycloidal return), so that one call evaluates both segments'
    points (each point's numbers are its own)."""
    return a is not None and type(a) is type(b) and type(a).PARAMETERLESS


#: the order of :meth:`Program.jumps`: by angle, then by order
_AT_ORDER = operator.attrgetter("at_deg", "order")


def _check_turn(total: float, levels: list[float]) -> None:
    """:class:`Program`'s checks of its segments' angles adding up to ``total`` (radians) and their start and end
    levels ``levels`` (2 a segment, mm, in order): one turn, back to the start, never below s = 0."""
    if not abs(total - TWO_PI) <= 1e-9:                 # NaN too (a NaN angle, which no spec lets through)
        raise SpecError(f"segment angles add up to {math.degrees(total):.6g} degrees; they must add up to 360",
                        "motion")
    first, last = levels[0], levels[-1]
    if abs(last - first) > 1e-9 * max(1.0, max(levels)):      # max(1, max_lift)
        raise SpecError(f"the follower ends the turn at s = {last:.6g} mm but starts at "
                        f"s = {first:.6g} mm; rises and returns must balance over 360 degrees", "motion")
    low = min(levels)
    if low < -1e-9:
        i = levels.index(low) // 2
        raise SpecError(f"takes the follower to s = {low:.6g} mm, below its lowest position (s = 0); "
                        "start the program with a rise or dwell", f"motion[{i}]")


def _end_level(kind: str, level: float, lift: float) -> float:
    """The follower's level (mm) at the end of a segment of ``kind`` starting at ``level``: up by ``lift`` on a
    rise, down on a return, where it was on a dwell (whatever its ``lift``)."""
    return level + (lift if kind == "rise" else -lift if kind == "return" else 0.0)


def build_program(steps: list[tuple[Kind, float, float, Law | None]]) -> Program:
    """A program from ``(kind, angle in degrees, lift in mm, law)`` steps, laid end to end from theta = 0.

    Parameters
    ----------
    steps : list of tuple
        Each segment as (kind, angle, lift, law): ``"rise"``, ``"dwell"`` or ``"return"``; its cam angle in
        degrees; its lift (mm, or degrees of an arm's swing; ignored on a dwell); its :class:`Law` (None for a
        dwell).

    Returns
    -------
    Program
        The segments in order, each starting where the one before ends (radians inside).

    Raises
    ------
    SpecError
        Naming ``motion``: no segment, angles that do not add up to 360 degrees, rises and returns that do not
        balance over the turn, or a return below the follower's lowest position (s = 0).
    """
    if not steps:
        return Program(())
    kinds, angles, lifts, laws = zip(*steps, strict=True)
    m = len(steps)
    beta = np.radians(np.fromiter(angles, float, m))   # math.radians' numbers: the same product
    given = np.fromiter(lifts, float, m)
    dwell = np.fromiter((k == "dwell" for k in kinds), bool, m)
    rise = np.fromiter((k == "rise" for k in kinds), bool, m)
    fall = np.fromiter((k == "return" for k in kinds), bool, m)
    # each start the sum of the angles before it, each level of the lifts before it (up on a rise, down on a return,
    # none on a dwell, whatever its lift: _end_level's), summed in order as one segment after another sums them
    start = np.zeros(m)
    np.cumsum(beta[:-1], out=start[1:])
    level = np.zeros(m)
    np.cumsum(np.where(rise, given, np.where(fall, -given, 0.0))[:-1], out=level[1:])
    lift = np.where(dwell, 0.0, given)
    moving = [None if d else law for d, law in zip(dwell.tolist(), laws, strict=True)]
    return Program(tuple(Segment(k, a, b, h, v, law) for k, a, b, h, v, law in zip(
        kinds, start.tolist(), beta.tolist(), lift.tolist(), level.tolist(), moving, strict=True)))
