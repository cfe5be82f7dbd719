"""Small numerical helpers shared by the analyses (no geometry, no I/O)."""
from __future__ import annotations

import functools
import math
from collections.abc import Callable, Generator
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

ArrayFunc = Callable[[np.ndarray], np.ndarray]


def maximise(func: ArrayFunc, a: float, b: float, *, n: int = 1025, rounds: int = 10) -> tuple[float, float]:
    """Global maximum of a smooth ``func`` on the closed interval [a, b].

    ``func`` maps an array of abscissae to an array of values (vectorised). A grid of
    ``n`` points finds the best cell; each refinement round re-grids the two cells
    around the best point with 33 points, shrinking the bracket 16-fold, so ten
    rounds locate the maximiser to ~1e-12 of the interval (the value to ~1e-24
    relative near a smooth maximum). Returns ``(x, func(x))``.
    """
    x = np.linspace(a, b, n)
    for _ in range(rounds + 1):
        y = func(x)
        if not np.all(np.isfinite(y)):
            raise FloatingPointError("function is not finite on the search grid")
        i = int(np.argmax(y))
        best_x, best_y = float(x[i]), float(y[i])
        lo, hi = x[max(i - 1, 0)], x[min(i + 1, len(x) - 1)]
        if hi <= lo:
            break
        x = np.linspace(lo, hi, 33)
    return best_x, best_y


def constant(value: float) -> np.ndarray:
    """The number ``value`` (anything ``float()`` takes) as a read-only 0-d float64 array, so that a module's shared
    constant cannot be written into by a stray ``out=``. Raises TypeError for what is not one number (None, a list,
    an array of more than one)."""
    out = np.array(float(value))
    out.setflags(write=False)
    return out


def left_of(x: float) -> float:
    """The float just below ``x``: evaluates a piecewise function's left-hand limit."""
    return float(np.nextafter(x, -np.inf))


def boundary(holds: Callable[[float], bool], good: float, bad: float, rel: float = 1e-9,
             floor: float = 0.0) -> float:
    """Bisection for where ``holds`` changes between ``good`` (True there) and ``bad`` (False there).

    Returns the last point found on the good side, within ``rel`` of the boundary, or within ``floor`` of it (an
    absolute width, in the unit of the points): a boundary at 0 is never reached to a relative width, and halving
    towards it would run on to the 200 steps' limit.
    """
    for _ in range(200):
        if abs(good - bad) <= max(rel * max(abs(good), abs(bad)), floor):
            break
        mid = 0.5 * (good + bad)
        if holds(mid):
            good = mid
        else:
            bad = mid
    return good


#: grid points per piece in :func:`piecewise_maxima` (a smooth piece's peaks are found on it, then refined)
GRID = 129
#: the most cam angle (radians) a step of a program's search grid spans: that of GRID points on a 45-degree piece
#: (0.35 degrees), and the fewest points a piece's grid takes (32 steps: a law's shape in its own variable)
GRID_STEP, LEAST_GRID = (math.pi / 4) / (GRID - 1), 33


def grid_counts(angle: ArrayLike) -> np.ndarray:
    """The points of the search grid of pieces spanning ``angle`` (radians, (p,)): 2^k + 1 of them, the fewest from
    :data:`LEAST_GRID` to :data:`GRID` whose step spans at most :data:`GRID_STEP` (GRID where no fewer do: a piece
    over 45 degrees, whose step is then wider). A function of cam angle whose second derivative is at most M
    (per radian squared) rises above a step's higher end by at most M step^2 / 8 inside it: every piece's grid
    bounds that as a 45-degree piece's grid of GRID points does (or more tightly), and a short piece takes few
    points. A quantity's features in the law's own variable (its law's shape) take the fewest: 32 steps place each
    of a law's peaks within its step, where the refinement takes over (see :func:`maxima_steps`)."""
    a = np.asarray(angle, dtype=float).reshape(-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        steps = np.ceil(a / GRID_STEP * (1.0 - 1e-12))           # a whole number of steps exactly stays
        power = np.ceil(np.log2(np.maximum(steps, LEAST_GRID - 1.0)))
    power = np.where(np.isfinite(power), power, math.log2(GRID - 1))
    return (2 ** np.minimum(power, math.log2(GRID - 1))).astype(np.intp) + 1


#: spacing of the refinement stencil, as a fraction of the peak's breadth
STENCIL = 1e-3
#: most refinement rounds (one is the rule: more only where the first estimate was off, a peak narrower than the grid)
ROUNDS = 8
#: values this close (relative to the function's magnitude) are equal: the first of them is taken, so that rounding
#: does not choose between a symmetric cam's equal peaks, or where a function is constant
TIE = 1e-12
_UNIT = np.linspace(0.0, 1.0, GRID)
#: a quartic's five grid points from its first
_FIVE = np.arange(5)
#: a refinement stencil's five points about its centre, in its spacings
_OFFSETS = (-2.0, -1.0, 0.0, 1.0, 2.0)


#: the quartic through five values at t = -2..2: its coefficients of t, t^2, t^3, t^4 (columns)
_QUARTIC = (np.array([[1, -1, -1, 1], [-8, 16, 2, -4], [0, -30, 0, 6], [8, 16, -2, -4], [-1, -1, 1, 1]])
            / [12, 24, 12, 24])


def _coefficients(windows: np.ndarray) -> np.ndarray:
    """a1, a2, a3, a4 (the coefficients of t, t^2, t^3, t^4; columns (m, 4)) of the quartic through each row of
    ``windows`` (m, 5) (values at t = -2..2). One matrix product for all rows: its rounding depends on whether there
    is one row or more (BLAS's vector or matrix kernel), not on the other rows' values or the row's place."""
    return windows @ _QUARTIC


def _coefficients_apart(windows: np.ndarray, from_end: np.ndarray) -> np.ndarray:
    """:func:`_coefficients` of ``windows`` (m, 5), those of the peaks found from an end (``from_end``, (m,) bool, see
    :func:`_inward_ends`) in a product of their own: so their number never changes which BLAS kernel (one row or
    more) rounds the others', and a peak found inside gets the same bits whether or not an end was a candidate
    beside it."""
    if not from_end.any():
        return _coefficients(windows)
    out = np.empty((windows.shape[0], 4))
    inside = ~from_end
    out[from_end] = _coefficients(windows[from_end])
    if inside.any():
        out[inside] = _coefficients(windows[inside])
    return out


def _vertex(a1: np.ndarray, a2: np.ndarray, a3: np.ndarray, a4: np.ndarray, lo: ArrayLike,
            hi: ArrayLike) -> np.ndarray:
    """Where each quartic of coefficients a1..a4 (of t..t^4; arrays (m,)) peaks within [lo, hi], by three Newton steps
    on its slope a1 + 2 a2 t + 3 a3 t^2 + 4 a4 t^3 from the parabola's vertex; NaN where it has none there (a step
    that divides by zero makes t infinite or NaN: no maximum within). The slope's and its derivative's coefficients
    are made once (2 a2 and 4 a4 exactly: their products with t round as t's with the products do)."""
    b2, b3, b4, c3 = 2 * a2, 3 * a3, 4 * a4, 6 * a3
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = -a1 / b2
        for _ in range(3):
            t = t - (a1 + t * (b2 + t * (b3 + t * b4))) / (b2 + t * (c3 + t * 12 * a4))
        peaks = (b2 + t * (c3 + t * 12 * a4) < 0) & (lo <= t) & (t <= hi)       # False where t is NaN
    return np.where(peaks, t, np.nan)


def _breadth(a2: ArrayLike, a4: ArrayLike, step: np.ndarray | float, size: np.ndarray | float) -> np.ndarray:
    """Each peak's breadth from its grid quartic's a2 and a4 (arrays): a bell of breadth b has a2 / a4 = 2 b^2 / h^2
    on a grid of step h; kept between 2 h and the piece's ``size`` (the piece's where a4 is zero or the ratio NaN)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        breadth = np.minimum(np.maximum(step * np.sqrt(np.abs(np.divide(a2, a4)) / 2), 2 * step), size)
    return np.where(np.isnan(breadth), size, breadth)


#: what :func:`maxima_steps` asks for, abscissae (m,) and their pieces (m,) (as its ``ask`` puts them); it is sent
#: the values (k, m) (as its ``answer`` makes them)
Steps = Generator[Any, Any, tuple[list[list[float]], list[list[float]], list[float]]]


def _points(x: np.ndarray, piece: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`maxima_steps`' ask unless told: its points as they are, ``(x, piece)``."""
    return x, piece


def _values(got: np.ndarray) -> np.ndarray:
    """:func:`maxima_steps`' answer unless told: the values as they are sent."""
    return got


def drive(steps: Generator[Any, Any, Any], answer: Callable[[Any], Any]) -> Any:
    """Run the generator ``steps`` to its end, sending it ``answer(ask)`` for each ``ask`` it yields; its result."""
    try:
        ask = next(steps)
        while True:
            ask = steps.send(answer(ask))
    except StopIteration as done:
        return done.value


def piecewise_maxima(func: Callable[[np.ndarray, np.ndarray], np.ndarray], lo: ArrayLike, hi: ArrayLike, *,
                     scale: ArrayLike = 0.0, reverse: ArrayLike = False,
                     n: int = GRID) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Global maxima of k smooth functions on each of p closed intervals, all at once: :func:`maxima_steps` with
    its values from ``func(x, piece)``, as arrays (x and value (k, p), magnitude (k,))."""
    at, value, magnitude = drive(maxima_steps(lo, hi, scale=scale, reverse=reverse, n=n), lambda ask: func(*ask))
    return np.array(at), np.array(value), np.array(magnitude)


def _flags(flag: ArrayLike, p: int) -> list[bool]:
    """``flag``, one for all (a bool or one element) or one a piece, as p bools."""
    a = np.asarray(flag, dtype=bool).reshape(-1)
    return a.tolist() * p if a.size == 1 else a.reshape(p).tolist()


def _exact(values: ArrayLike) -> bytes:
    """``values`` as the bytes of their float64s, to look a :func:`_plan` up by (exact: -0.0 is not 0.0)."""
    return np.asarray(values, dtype=float).reshape(-1).tobytes()


def _key(flag: ArrayLike) -> tuple[bool, ...]:
    """``flag`` (a bool, or a sequence or array of them) as a tuple of bools, to look a :func:`_plan` up by."""
    return tuple(np.asarray(flag, dtype=bool).reshape(-1).tolist())


class _Plan(NamedTuple):
    """What :func:`maxima_steps` knows of a set of pieces before it asks anything (see :func:`_plan`); arrays
    read-only."""

    lo: np.ndarray
    hi: np.ndarray
    width: np.ndarray
    moving: np.ndarray                 #: the pieces that are not steady, in order
    #: the steady pieces, and where each one's maximum is: its values are all its first, and of equal values the
    #: first from its low end (from its high end where it runs backwards) is taken
    resting: np.ndarray
    resting_at: np.ndarray
    backwards: np.ndarray
    ask: tuple[np.ndarray, np.ndarray]
    #: each moving piece's grid points (count,), and where its first and last lie in the first ask (count,)
    sizes: np.ndarray
    first: np.ndarray
    last: np.ndarray
    #: the moving pieces by the size of their grid: (n, their places among the moving (c,), where their grids lie in
    #: the first ask (c, n)) each, in order of size; one block of all, its grids in order, where every grid is alike
    blocks: tuple[tuple[int, np.ndarray, np.ndarray | None], ...]


@functools.lru_cache(maxsize=32)
def _plan(lo: bytes, hi: bytes, steady: tuple[Any, ...], reverse: tuple[Any, ...], n: int | bytes) -> _Plan:
    """:func:`maxima_steps`' pieces (given by the bytes of their float ``lo`` and ``hi``) and flags (see
    :func:`_key`) as arrays, made once for a set of pieces (a program's are mostly [0, 1]); and its first ask: the
    grid of ``n`` points (one count for all, or the bytes of one a piece, see :func:`_counts`) on each piece that is
    not ``steady``, piece after piece, then each steady piece's first point; and the piece of each."""
    low, high = np.frombuffer(lo), np.frombuffer(hi)
    width = high - low
    p = low.size
    still = np.array(_flags(steady, p), dtype=bool)
    backwards = np.array(_flags(reverse, p), dtype=bool)
    moving, steady_pieces = (~still).nonzero()[0], still.nonzero()[0]
    each = np.full(p, n, dtype=np.intp) if isinstance(n, int) else np.frombuffer(n, dtype=np.int64).astype(np.intp)
    sizes = each[moving]
    first = np.cumsum(sizes) - sizes
    blocks: list[tuple[int, np.ndarray, np.ndarray | None]] = []
    if sizes.size and (sizes == sizes[0]).all():       # every grid alike: one block, in order (no gather)
        m = int(sizes[0])
        x = low[moving, None] + width[moving, None] * _unit(m)[0]
        x[:, -1] = high[moving]
        grids = x.ravel()
        blocks.append((m, np.arange(moving.size), None))
    else:
        grids = np.empty(int(sizes.sum()))
        for m in np.unique(sizes).tolist():
            members = (sizes == m).nonzero()[0]
            where = first[members, None] + np.arange(m)
            x = low[moving[members], None] + width[moving[members], None] * _unit(m)[0]
            x[:, -1] = high[moving[members]]
            grids[where] = x
            blocks.append((m, members, where))
    x = np.concatenate([grids, low[steady_pieces] + width[steady_pieces] * 0.0])     # a steady piece's first point
    piece = np.concatenate([np.repeat(moving, sizes), steady_pieces]).astype(np.intp)
    resting_at = np.where(backwards[steady_pieces], high[steady_pieces], low[steady_pieces])
    plan = _Plan(low, high, width, moving, steady_pieces, resting_at, backwards, (x, piece), sizes, first,
                 first + sizes - 1, tuple(blocks))
    for a in (*plan[:7], x, piece, sizes, first, plan.last, *(w for b in blocks for w in b[1:] if w is not None)):
        a.flags.writeable = False
    return plan


def _counts(n: int | ArrayLike) -> int | bytes:
    """A grid's count for :func:`_plan`: one int for every piece, or the bytes of one int64 a piece (each >= 5)."""
    if isinstance(n, (int, np.integer)):
        count = int(n)
        least = count
    else:
        each = np.asarray(n, dtype=np.int64).reshape(-1)
        least = int(each.min()) if each.size else 5
        count = int(each[0]) if each.size and (each == each[0]).all() else -1
        if count < 0:
            if least < 5:
                raise ValueError(f"a grid of {least} points: the search needs 5 a piece at least")
            return each.tobytes()
    if least < 5:
        raise ValueError(f"a grid of {least} points: the search needs 5 a piece at least")
    return count


@functools.lru_cache(maxsize=16)
def _unit(n: int) -> tuple[np.ndarray, list[float]]:
    """``n`` points evenly spread over [0, 1], as an array and as floats."""
    unit = _UNIT if n == GRID else np.linspace(0.0, 1.0, n)
    return unit, unit.tolist()


def _flat_rows(y: np.ndarray, magnitude: list[float], count: int) -> list[int]:
    """The rows of the grid ``y`` (rows, n; finite) that are constant within the tie: whose largest and least value
    differ by no more than ``TIE`` of their function's ``magnitude`` (``count`` rows a function)."""
    spread = (y.max(axis=1) - y.min(axis=1)).tolist()
    return [r for r, d in enumerate(spread) if not d > TIE * magnitude[r // count]]


def _grid_candidates(y: np.ndarray, flat: np.ndarray, magnitude: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each row's local maxima on the grid ``y`` (rows, n; finite) that may be its largest: within what a peak can
    rise above its grid points (the row's largest second difference) of the row's highest; none on the rows
    ``flat`` ((rows,) bool: constant within the tie). The interior points no lower than their neighbours, and an end
    where a peak lies within the grid's first or last step, which no interior point shows (see :func:`_inward_ends`;
    ``magnitude``, each row's function's). Their rows and grid indices ((m,) each), in order of row and index."""
    rows_n, n = y.shape
    inner, before, after = y[:, 1:-1], y[:, :-2], y[:, 2:]
    peak = inner >= np.maximum(before, after)                # as inner >= before and inner >= after (no NaN)
    peak[flat] = False
    rows, inside = peak.nonzero()
    ends = _inward_ends(y[:, _EDGES], magnitude) & ~flat[:, None]
    first, last = ends.T
    cell = np.concatenate([rows * n + inside + 1, first.nonzero()[0] * n, last.nonzero()[0] * n + n - 1])
    cell.sort()                                              # by row, then grid index
    row, j = np.divmod(cell, n)
    if not cell.size:
        return row, j
    values = y.take(cell)
    drop = np.abs(before - 2 * inner + after).max(axis=1)
    top = np.full(rows_n, -math.inf)
    np.maximum.at(top, row, values)
    keep = values >= top[row] - drop[row]
    return row[keep], j[keep]


def _inward_ends(edges: np.ndarray, magnitude: np.ndarray) -> np.ndarray:
    """The ends of the grid rows (``edges`` (rows, 2, 5): each row's first five values and its last five from its
    end) near which a peak may lie inside the grid's first or last step ((rows, 2) bool: the first end, the last):
    where the end is
    no lower than its neighbour and the quartic through it and the next four points rises inwards from it and bends
    down, so that the parabola of its slope and curvature there peaks above the end by more than the row's tie
    (``TIE`` of its function's ``magnitude``, (rows,)). A quartic, not a parabola through three points: where
    the function levels off at the end (a rise ending in a dwell, s = h - k (1 - u)^3, or a cosine's top) a
    parabola's slope there is off by the cubic and quartic terms and would flag the end; the quartic's is off by the
    fifth-order term only. A candidate is kept only where its refined peak beats the end by more than the tie (see
    :func:`maxima_steps`)."""
    a, b, c, d, e = edges.transpose(2, 0, 1)                 # each (rows, 2): both ends at once
    return (a >= b) & _rises_inwards(a, b, c, d, e, (24.0 * TIE * magnitude)[:, None])


def _rises_inwards(a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray, e: np.ndarray,
                   tie: np.ndarray) -> np.ndarray:
    """Whether from an end's values ``a`` (then ``b``, ``c``, ``d``, ``e``, a step apart; arrays) the quartic through
    them rises and bends down: its slope there is S / 12 a step and its curvature -B / 12 a step squared, whose
    parabola rises S^2 / (24 B) above ``a``, by more than ``tie`` / 24 (see :func:`_inward_ends`)."""
    slope = 48.0 * b - 25.0 * a - 36.0 * c + 16.0 * d - 3.0 * e
    bend = 104.0 * b - 35.0 * a - 114.0 * c + 56.0 * d - 11.0 * e
    return (slope > 0.0) & (bend > 0.0) & (slope * slope > tie * bend)


#: the grid indices of a row's first five points and of its last five from its end (see :func:`_inward_ends`)
_EDGES = np.array([[0, 1, 2, 3, 4], [-1, -2, -3, -4, -5]])


class _Peaks(NamedTuple):
    """The peaks being located, all at once (arrays (m,)): each one's grid ``row``, function ``f`` and ``piece``,
    where it is so far (``at``) and the largest value seen (``value``), the next stencil's ``centre`` and the peak's
    ``breadth`` (all in the piece's abscissa); whether it was found from an end (``from_end``, see
    :func:`_inward_ends`) and that end's value (``end``)."""

    row: np.ndarray
    f: np.ndarray
    piece: np.ndarray
    at: np.ndarray
    value: np.ndarray
    centre: np.ndarray
    breadth: np.ndarray
    from_end: np.ndarray
    end: np.ndarray


def _estimates(y: np.ndarray, row: np.ndarray, j: np.ndarray, plan: _Plan, n: int, members: np.ndarray) -> _Peaks:
    """The candidates (grid ``row`` and index ``j``, (m,) each, on the grid rows ``y``, a row for each function on
    each of the moving pieces ``members`` (their places among the plan's ``moving``), all with grids of ``n``
    points), each placed by the quartic through the five grid values about it (its window, kept two points from the
    row's ends; within a grid step of its grid point) and given its breadth and its grid value; their rows
    renumbered as every moving piece's (a function's rows, then the next function's)."""
    count = members.size
    unit = _unit(n)[0]
    centre = np.minimum(np.maximum(j, 2), n - 3)             # each window's centre
    windows = y.take((row * n + centre - 2)[:, None] + _FIVE)
    from_end = (j == 0) | (j == n - 1)
    a1, a2, a3, a4 = _coefficients_apart(windows, from_end).T
    value = y.take(row * n + j)
    f, place = np.divmod(row, count)
    place = members[place]
    piece = plan.moving[place]
    low, size, high = plan.lo[piece], plan.width[piece], plan.hi[piece]
    step = size / (n - 1)
    shift = (j - centre).astype(float)
    t = _vertex(a1, a2, a3, a4, shift - 1.0, shift + 1.0)
    placed = np.minimum(np.maximum(low + size * unit[centre] + np.where(np.isnan(t), shift, t) * step, low), high)
    at = np.where(j == n - 1, high, low + size * unit[j])        # the grid's own point: its last the end
    return _Peaks(f * plan.moving.size + place, f, piece, at, value, placed, _breadth(a2, a4, step, size), from_end,
                  value.copy())


def _joined(peaks: list[_Peaks]) -> _Peaks:
    """The candidates of several blocks of grids as one set (each array concatenated)."""
    return peaks[0] if len(peaks) == 1 else _Peaks(*(np.concatenate(a) for a in zip(*peaks, strict=True)))


def _refined(peaks: _Peaks, plan: _Plan, ask: Callable[[np.ndarray, np.ndarray], Any],
             answer: Callable[[Any], np.ndarray]) -> Generator[Any, Any, None]:
    """Locate the ``peaks`` (in place), all in one ask a round: each round asks five points ``STENCIL`` of a peak's
    breadth apart about its estimate (within half its distance to its piece's nearer end; none where that is within
    1e-12 of the piece: the point stands) and takes the quartic through its values there (or the best of them where
    the quartic has no maximum within); a peak well inside its stencil is done, at most ``ROUNDS`` rounds. Its asks
    and answers are put and read by ``ask`` and ``answer`` (see :func:`maxima_steps`)."""
    active = np.arange(peaks.row.size)
    for _ in range(ROUNDS):
        piece, c = peaks.piece[active], peaks.centre[active]
        d = np.minimum(STENCIL * peaks.breadth[active], 0.5 * np.minimum(c - plan.lo[piece], plan.hi[piece] - c))
        live = d > 1e-12 * plan.width[piece]
        active, piece, c, d = active[live], piece[live], c[live], d[live]
        m = active.size
        if not m:
            return
        got = answer((yield ask((c[:, None] + d[:, None] * _STEPS).ravel(), piece.repeat(5))))
        ys = got.reshape(got.shape[0], m, 5)[peaks.f[active], np.arange(m)]     # each its own function
        if not np.isfinite(ys).all():
            raise FloatingPointError("function is not finite near a peak")
        a1, a2, a3, a4 = _coefficients_apart(ys, peaks.from_end[active]).T
        t = _vertex(a1, a2, a3, a4, -2.0, 2.0)
        high = ys.max(axis=1)
        value = peaks.value[active]
        none = np.isnan(t)
        best = c + d * _STEPS[ys.argmax(axis=1)]                 # the stencil's best point, where no quartic peaks
        t = np.where(none, 0.0, t)
        moved = c + t * d
        fitted = ys[:, 2] + t * (a1 + t * (a2 + t * (a3 + t * a4)))
        peaks.at[active] = np.where(none, np.where(high >= value, best, peaks.at[active]), moved)
        peaks.value[active] = np.where(none, np.maximum(value, high), np.maximum(value, np.maximum(fitted, high)))
        peaks.centre[active] = np.where(none, best, moved)
        active = active[none | (np.abs(t) > 0.5)]                # else the peak is well inside: its quartic's is exact


#: a refinement stencil's five points about its centre, in its spacings
_STEPS = np.array(_OFFSETS)


def _first_largest(row: np.ndarray, x: np.ndarray, v: np.ndarray, ties: np.ndarray, backwards: np.ndarray,
                   rows: int) -> np.ndarray:
    """Of each row's candidates (``row``, abscissa ``x`` and value ``v``, (m,) each, listed in order within a row:
    its ends, then its peaks), the first from the low end (the high end where the row's ``backwards``) whose value
    is within the row's tie (``ties``) of its largest; of equal abscissae the earliest listed. The chosen
    candidate of each of the ``rows`` rows (indices into the candidates, (rows,))."""
    top = np.full(rows, -math.inf)
    np.maximum.at(top, row, v)
    near = (v >= (top - ties)[row]).nonzero()[0]
    key = np.where(backwards, -1.0, 1.0)[row[near]] * x[near]
    ordered = near[np.lexsort((near, key, row[near]))]       # by row, then from the low end, then as listed
    first = np.ones(ordered.size, dtype=bool)
    first[1:] = row[ordered[1:]] != row[ordered[:-1]]
    return ordered[first]


def maxima_steps(lo: ArrayLike, hi: ArrayLike, *, scale: ArrayLike = 0.0, reverse: ArrayLike = False,
                 steady: ArrayLike = False, n: int | ArrayLike = GRID,
                 ask: Callable[[np.ndarray, np.ndarray], Any] = _points,
                 answer: Callable[[Any], np.ndarray] = _values) -> Steps:
    """Global maxima of k smooth functions on each of p closed intervals, all at once, as a generator: it yields
    ``ask(x, piece)`` (``(x, piece)`` unless told) and is sent what ``answer`` turns into the functions' values
    there (see below; as sent unless told), so that a caller can evaluate what it asks together with other work
    (one evaluation serving several searches); a caller whose evaluator takes its points or gives its answers in
    another form says how, and delegates to this generator (yield from) rather than wrapping it.

    The values sent for an ask ``(x, piece)``, abscissae ``x`` (m,) on the pieces ``piece`` (m,) (indices into
    ``lo``, ``hi``; both read-only), are the k functions' values there, shape (k, m); each must be smooth (analytic)
    on each closed piece, whose ends it evaluates as given (pass a left limit's abscissa as ``hi``). Returns
    ``(x, value, magnitude)`` as floats: x and value (k lists of p), and each function's magnitude (k), the larger
    of ``scale`` (k,) and its largest |value| on the grid.

    One dense evaluation (``n`` >= 5 points a piece: one count for all, or one a piece (p,); pieces of one count
    are searched together, a block of rows) finds each function's interior local maxima on each piece that
    may be its largest, and a peak within the grid's first or last step (see :func:`_inward_ends`; none on a piece
    where it is constant, within ``TIE``); the quartic through the five grid
    values about each puts its maximiser within ~1e-9 of the piece and tells the peak's breadth; a second
    evaluation, at five points ``STENCIL`` of that breadth apart about the estimate, gives a quartic whose peak is
    the maximiser within ~1e-12 of the breadth and the maximum to the rounding of the values (a peak the estimate
    missed by more than the stencil gets further rounds, at most ``ROUNDS``). A piece's maximum is the first of its
    ends and peaks within ``TIE`` of each function's magnitude of the largest, from its low end (from its high end
    where ``reverse``, (p,) or one for all, is True). A piece where ``steady`` ((p,) or one for all) is True is one
    on which the caller knows every function to be constant to the last bit: its grid is asked for its first point
    only, whose values stand for the rest (the same search as if all were asked: such a piece has no peak).
    Raises FloatingPointError where a value is not finite on the grid or near a peak.
    """
    plan = _plan(_exact(lo), _exact(hi), _key(steady), _key(reverse), _counts(n))
    p = plan.lo.size
    got = answer((yield ask(*plan.ask)))
    k = got.shape[0]
    count = plan.moving.size
    lead = int(plan.sizes.sum())                               # the moving pieces' grids lead the ask
    largest = np.abs(got).max(axis=1).tolist()                 # NaN or infinite where any value is
    if not all(map(math.isfinite, largest)):
        raise FloatingPointError("function is not finite on the search grid")
    scales = np.broadcast_to(np.asarray(scale, dtype=float).reshape(-1), (k,)).tolist()   # one for all, or one each
    magnitude = [max(s, m) for s, m in zip(scales, largest, strict=True)]
    at, value = np.empty((k, p)), np.empty((k, p))
    at[:, plan.resting] = plan.resting_at
    value[:, plan.resting] = got[:, lead:]                     # each steady piece's value, for each function
    if count:
        rows = k * count
        sizes = np.array(magnitude).repeat(count)              # each row's function's magnitude
        ties = TIE * sizes
        found = []
        for m, members, where in plan.blocks:                  # the grids of m points, a row for each function on each
            c = members.size
            y = got[:, :lead].reshape(k * c, m) if where is None else got[:, where.ravel()].reshape(k * c, m)
            flat = np.zeros(k * c, dtype=bool)
            flat[_flat_rows(y, magnitude, c)] = True
            row, j = _grid_candidates(y, flat, np.array(magnitude).repeat(c))
            found.append(_estimates(y, row, j, plan, m, members))
        peaks = _joined(found)
        if peaks.row.size:
            yield from _refined(peaks, plan, ask, answer)
        # a peak found from an end only where it beats that end by the tie
        kept = ~peaks.from_end | (peaks.value - peaks.end > ties[peaks.row])
        piece = plan.moving[np.arange(rows) % count]           # each row's piece
        every = np.arange(rows)
        row_of = np.concatenate([every, every, peaks.row[kept]])        # each row's ends, then its peaks
        x = np.concatenate([plan.lo[piece], plan.hi[piece], peaks.at[kept]])
        v = np.concatenate([got[:, plan.first].ravel(), got[:, plan.last].ravel(), peaks.value[kept]])
        chosen = _first_largest(row_of, x, v, ties, plan.backwards[piece], rows)
        at[every // count, piece] = x[chosen]
        value[every // count, piece] = v[chosen]
    return at.tolist(), value.tolist(), magnitude


def search_grid(lo: ArrayLike, hi: ArrayLike, *, reverse: ArrayLike = False, steady: ArrayLike = False,
                n: int | ArrayLike = GRID) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points that :func:`maxima_steps` asks first on these pieces and flags (the same arguments): the abscissae
    and pieces ((m,) each, read-only), the very arrays its first ask holds, so that a caller who asks them in the same
    round as the search has them evaluated once (see :meth:`camgen.cam.Cam.pitch_of`); and the count of points of
    each piece that is not ``steady`` (read-only), whose grids lead, piece after piece (the rest are each steady
    piece's first point)."""
    plan = _plan(_exact(lo), _exact(hi), _key(steady), _key(reverse), _counts(n))
    x, piece = plan.ask
    return x, piece, plan.sizes


def present(index: np.ndarray) -> np.ndarray:
    """The distinct values of the non-negative integers ``index``, in order (np.unique without loading numpy.ma)."""
    return np.flatnonzero(np.bincount(index)) if index.size else index
