"""Small numerical helpers shared by the analyses (no geometry, no I/O)."""
from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable, Generator, Iterable
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


def boundary(holds: Callable[[float], bool], good: float, bad: float, rel: float = 1e-9) -> float:
    """Bisection for where ``holds`` changes between ``good`` (True there) and ``bad`` (False there).

    Returns the last point found on the good side, within ``rel`` of the boundary.
    """
    for _ in range(200):
        if abs(good - bad) <= rel * max(abs(good), abs(bad)):
            break
        mid = 0.5 * (good + bad)
        if holds(mid):
            good = mid
        else:
            bad = mid
    return good


#: grid points per piece in :func:`piecewise_maxima` (a smooth piece's peaks are found on it, then refined)
GRID = 129
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


def _coefficients(windows: np.ndarray) -> list[list[float]]:
    """a1, a2, a3, a4 (the coefficients of t, t^2, t^3, t^4) of the quartic through each row of ``windows`` (m, 5)
    (values at t = -2..2), as floats. One matrix product for all rows: its rounding depends on whether there is one
    row or more (BLAS's vector or matrix kernel), not on the other rows' values or the row's place."""
    return (windows @ _QUARTIC).tolist()


def _coefficients_apart(windows: np.ndarray, from_end: list[bool]) -> list[list[float]]:
    """:func:`_coefficients` of ``windows`` (m, 5), those of the peaks found from an end (``from_end``, see
    :func:`_inward_peaks`) in a product of their own: so their number never changes which BLAS kernel (one row or
    more) rounds the others', and a peak found inside gets the same bits whether or not an end was a candidate
    beside it."""
    if True not in from_end:
        return _coefficients(windows)
    mask = np.array(from_end)
    made = {flag: iter(_coefficients(windows[mask == flag])) for flag in set(from_end)}
    return [next(made[flag]) for flag in from_end]


def _vertex(a1: float, a2: float, a3: float, a4: float, lo: float, hi: float) -> float | None:
    """Where the quartic of coefficients a1..a4 (of t..t^4) peaks within [lo, hi], by three Newton steps on its
    slope from the parabola's vertex; None where it has no maximum there (a step dividing by zero has none)."""
    try:
        t = -a1 / (2 * a2)
        for _ in range(3):
            t -= (a1 + t * (2 * a2 + t * (3 * a3 + t * 4 * a4))) / (2 * a2 + t * (6 * a3 + t * 12 * a4))
    except ZeroDivisionError:                                 # t would be infinite or NaN: no maximum within
        return None
    return t if 2 * a2 + t * (6 * a3 + t * 12 * a4) < 0 and lo <= t <= hi else None   # False where t is NaN


def _breadth(a2: float, a4: float, step: float, size: float) -> float:
    """A peak's breadth from its grid quartic's a2 and a4: a bell of breadth b has a2 / a4 = 2 b^2 / h^2 on a grid
    of step h; kept between 2 h and the piece's ``size`` (the piece's where a4 is zero or the ratio NaN)."""
    try:
        breadth = min(max(step * math.sqrt(abs(a2 / a4) / 2), 2 * step), size)
    except ZeroDivisionError:
        return size
    return size if math.isnan(breadth) else breadth


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
    """What :func:`maxima_steps` knows of a set of pieces before it asks anything (see :func:`_plan`)."""

    lo: list[float]
    hi: list[float]
    width: list[float]
    moving: list[int]                  #: the pieces that are not steady, in order
    #: each steady piece and where its maximum is: its values are all its first, the end :func:`_first_largest` takes
    #: for any finite tie
    resting: list[tuple[int, float]]
    backwards: list[bool]
    ask: tuple[np.ndarray, np.ndarray]


@functools.lru_cache(maxsize=32)
def _plan(lo: bytes, hi: bytes, steady: tuple[Any, ...], reverse: tuple[Any, ...], n: int) -> _Plan:
    """:func:`maxima_steps`' pieces (given by the bytes of their float ``lo`` and ``hi``) and flags (see
    :func:`_key`) as floats and bools, made once for a set of pieces (a program's are mostly [0, 1]); and its first
    ask, read-only: the grid of ``n`` points on each piece that is not ``steady``, then each steady piece's first
    point; and the piece of each."""
    low, high = np.frombuffer(lo), np.frombuffer(hi)
    width = high - low
    p = low.size
    still = _flags(steady, p)
    moving = [i for i, s in enumerate(still) if not s]
    steady_pieces = [i for i, s in enumerate(still) if s]
    x = low[moving, None] + width[moving, None] * _unit(n)[0]
    x[:, -1] = high[moving]
    x = np.concatenate([x.ravel(), low[steady_pieces] + width[steady_pieces] * _unit(n)[0][0]])
    piece = np.concatenate([np.repeat(moving, n), steady_pieces]).astype(np.intp)
    x.flags.writeable = piece.flags.writeable = False
    starts, ends, backwards = low.tolist(), high.tolist(), _flags(reverse, p)
    resting = [(i, _first_largest([(starts[i], 0.0), (ends[i], 0.0)], 0.0, backwards[i])[0]) for i in steady_pieces]
    return _Plan(starts, ends, width.tolist(), moving, resting, backwards, (x, piece))


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


def _grid_candidates(y: np.ndarray, flat: list[int], edges: list[list[float]], magnitude: list[float],
                     count: int) -> list[tuple[int, int]]:
    """Each row's local maxima on the grid ``y`` (rows, n; finite) that may be its largest: within what a peak can
    rise above its grid points (the row's largest second difference) of the row's highest; none on the rows ``flat``
    (constant within the tie). ``(row, grid index)`` each, in order of row and index. The interior points no lower
    than their neighbours, and an end (see :func:`_inward_peaks`; ``edges``, each row's first five and last five
    values, ``magnitude`` each function's, ``count`` rows a function) where a peak lies within the grid's first or
    last step, which no interior point shows."""
    inner, before, after = y[:, 1:-1], y[:, :-2], y[:, 2:]
    peak = inner >= np.maximum(before, after)                # as inner >= before and inner >= after (no NaN)
    if flat:
        peak[flat] = False
    rows, inside = peak.nonzero()
    cells = sorted([*zip(rows.tolist(), (inside + 1).tolist(), strict=True),
                    *_inward_peaks(edges, flat, magnitude, count, y.shape[1])])
    if not cells:
        return cells
    values = y[[r for r, _ in cells], [j for _, j in cells]].tolist()
    drop = np.abs(before - 2 * inner + after).max(axis=1).tolist()
    top: dict[int, float] = {}
    for (r, _), v in zip(cells, values, strict=True):
        top[r] = max(top.get(r, -math.inf), v)
    return [(r, j) for (r, j), v in zip(cells, values, strict=True) if v >= top[r] - drop[r]]


def _inward_peaks(edges: list[list[float]], flat: list[int], magnitude: list[float], count: int,
                  n: int) -> list[tuple[int, int]]:
    """The ends of the grid rows (``edges``: each row's first five and last five values, of a grid of ``n``) near
    which a peak may lie inside the grid's first or last step: where the end is no lower than its neighbour and the
    quartic through it and the next four points rises inwards from it and bends down, so that the parabola of its
    slope and curvature there peaks above the end by more than the tie (``TIE`` of the row's function's
    ``magnitude``, ``count`` rows a function; none on the rows ``flat``). A quartic, not a parabola through three
    points: where the function levels off at the end (a rise ending in a dwell, s = h - k (1 - u)^3, or a cosine's
    top) a parabola's slope there is off by the cubic and quartic terms and would flag the end; the quartic's is
    off by the fifth-order term only. A candidate is kept only where its refined peak beats the end by more than
    the tie (see :func:`maxima_steps`). ``(row, grid index)`` each: 0 for the first end, n - 1 for the last."""
    out = []
    for r, (a, b, c, d, e, z4, z3, z2, z1, z0) in enumerate(edges):
        tie = 24.0 * TIE * magnitude[r // count]
        if a >= b and _rises_inwards(a, b, c, d, e, tie) and r not in flat:
            out.append((r, 0))
        if z0 >= z1 and _rises_inwards(z0, z1, z2, z3, z4, tie) and r not in flat:
            out.append((r, n - 1))
    return out


def _rises_inwards(a: float, b: float, c: float, d: float, e: float, tie: float) -> bool:
    """Whether from an end's value ``a`` (no lower than its next, ``b``; then ``c``, ``d``, ``e``, a step apart) the
    quartic through them rises and bends down: its slope there is S / 12 a step and its curvature -B / 12 a step
    squared, whose parabola rises S^2 / (24 B) above ``a``, by more than ``tie`` / 24 (see :func:`_inward_peaks`)."""
    slope = 48.0 * b - 25.0 * a - 36.0 * c + 16.0 * d - 3.0 * e
    bend = 104.0 * b - 35.0 * a - 114.0 * c + 56.0 * d - 11.0 * e
    return slope > 0.0 and bend > 0.0 and slope * slope > tie * bend


#: the grid indices of a row's first five and last five points (see :func:`_inward_peaks`)
_EDGES = np.array([0, 1, 2, 3, 4, -5, -4, -3, -2, -1])


class _Peak:
    """A peak being located: its grid ``row``, function ``f`` and ``piece``, where it is so far (``at``) and the
    largest value seen (``value``), the next stencil's ``centre`` and the peak's ``breadth`` (all in the piece's
    abscissa); the value of the end it was found from (``end``, see :func:`_inward_peaks`), None for a peak found
    inside."""

    __slots__ = ("at", "breadth", "centre", "end", "f", "piece", "row", "value")

    def __init__(self, row: int, f: int, piece: int, at: float, value: float, centre: float, breadth: float,
                 end: float | None) -> None:
        self.f, self.piece, self.at, self.value, self.centre, self.breadth = f, piece, at, value, centre, breadth
        self.row, self.end = row, end


def _windows(y: np.ndarray, found: list[tuple[int, int]], n: int) -> tuple[list[int], np.ndarray]:
    """The grid index about which each peak ``found`` (row, grid index) on the grid rows ``y`` is placed (its own,
    kept two points from the row's ends) and the five grid values there (m, 5)."""
    centres, firsts = [], []                             # each window's centre and first point in y's flat order
    for r, j in found:
        c = min(max(j, 2), n - 3)
        centres.append(c)
        firsts.append(r * n + c - 2)
    return centres, y.take(np.add.outer(firsts, _FIVE))


def _estimates(candidates: Iterable[tuple[tuple[int, int], int, list[float], list[float]]], moving: list[int],
               lo: list[float], hi: list[float], width: list[float], n: int) -> list[_Peak]:
    """The ``candidates`` (a peak found on the grid rows, (row, grid index), a row for each function on each piece
    of ``moving``; the grid index of its window's centre; the window's five values and the coefficients of the
    quartic through them, see :func:`_windows`), each placed by its quartic (within a grid step of its grid point)
    and given its breadth and its grid value."""
    count = len(moving)
    unit = _unit(n)[1]
    out = []
    for (r, j), c, near, (a1, a2, a3, a4) in candidates:
        value = near[j - c + 2]
        piece = moving[r % count]
        low, size = lo[piece], width[piece]
        step = size / (n - 1)
        shift = float(j - c)
        t = _vertex(a1, a2, a3, a4, shift - 1.0, shift + 1.0)
        centre = min(max(low + size * unit[c] + (shift if t is None else t) * step, low), hi[piece])
        at = hi[piece] if j == n - 1 else low + size * unit[j]           # the grid's own point: its last the end
        out.append(_Peak(r, r // count, piece, at, value, centre, _breadth(a2, a4, step, size),
                         value if j == 0 or j == n - 1 else None))
    return out


def _stencil(peak: _Peak, lo: list[float], hi: list[float], width: list[float]) -> float:
    """The spacing of ``peak``'s next stencil: ``STENCIL`` of its breadth, within half its distance to its piece's
    nearer end; 0.0 where it is at an end already (within 1e-12 of its piece: the grid's point stands)."""
    c, left, right = peak.centre, lo[peak.piece], hi[peak.piece]
    d = min(STENCIL * peak.breadth, 0.5 * min(c - left, right - c))
    return d if d > 1e-12 * width[peak.piece] else 0.0


def _refined(peaks: list[_Peak], lo: list[float], hi: list[float], width: list[float],
             ask: Callable[[np.ndarray, np.ndarray], Any], answer: Callable[[Any], np.ndarray]) -> Generator[
        Any, Any, None]:
    """Locate the ``peaks`` (in place): each round asks five points ``STENCIL`` of a peak's breadth apart about its
    estimate and takes the quartic through its values there (or the best of them where the quartic has no maximum
    within); a peak well inside its stencil is done, at most ``ROUNDS`` rounds. Its asks and answers are put and
    read by ``ask`` and ``answer`` (see :func:`maxima_steps`)."""
    active = peaks
    for _ in range(ROUNDS):
        stencils, pieces, from_end = [], [], []          # each peak's (peak, centre, spacing), piece, whether
        for peak in active:                              # it was found from an end
            if d := _stencil(peak, lo, hi, width):
                stencils.append((peak, peak.centre, d))
                pieces.append(peak.piece)
                from_end.append(peak.end is not None)
        if not stencils:
            return
        points = [c + d * s for _, c, d in stencils for s in _OFFSETS]     # five a stencil, one flat list
        got = answer((yield ask(np.array(points), np.array(pieces).repeat(5))))
        values = got.tolist()
        ys = [values[peak.f][5 * i:5 * i + 5] for i, (peak, _, _) in enumerate(stencils)]   # each its own function
        if not all(map(math.isfinite, itertools.chain.from_iterable(ys))):
            raise FloatingPointError("function is not finite near a peak")
        active = []
        coefficients = _coefficients_apart(np.array(ys), from_end)
        for (peak, c, d), row, (a1, a2, a3, a4) in zip(stencils, ys, coefficients, strict=True):
            t = _vertex(a1, a2, a3, a4, -2.0, 2.0)
            high = max(row)
            if t is None:
                moved = c + d * _OFFSETS[row.index(high)]          # that stencil point, made again
                if high >= peak.value:
                    peak.at = moved
                peak.value = max(peak.value, high)
                active.append(peak)
            else:
                moved = peak.at = c + t * d
                peak.value = max(peak.value, max(row[2] + t * (a1 + t * (a2 + t * (a3 + t * a4))), high))
                if abs(t) > 0.5:                                 # else the peak is well inside: its quartic's is exact
                    active.append(peak)
            peak.centre = moved


def _first_largest(candidates: list[tuple[float, float]], tie: float, backwards: bool) -> tuple[float, float]:
    """Of a piece's ``candidates`` (abscissa, value), its ends and peaks, the first from the low end (the high end
    where ``backwards``) whose value is within ``tie`` of the largest; of equal abscissae the earliest listed."""
    limit = max(v for _, v in candidates) - tie
    sign = -1.0 if backwards else 1.0
    best, key = candidates[0], math.inf
    for candidate in candidates:
        x, v = candidate
        if v >= limit and sign * x < key:
            best, key = candidate, sign * x
    return best


def maxima_steps(lo: ArrayLike, hi: ArrayLike, *, scale: ArrayLike = 0.0, reverse: ArrayLike = False,
                 steady: ArrayLike = False, n: int = GRID, ask: Callable[[np.ndarray, np.ndarray], Any] = _points,
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

    One dense evaluation (``n`` >= 5 points a piece) finds each function's interior local maxima on each piece that
    may be its largest, and a peak within the grid's first or last step (see :func:`_inward_peaks`; none on a piece
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
    if n < 5:
        raise ValueError(f"a grid of {n} points: the search needs 5 a piece at least")
    plan = _plan(_exact(lo), _exact(hi), _key(steady), _key(reverse), n)
    lo, hi, width, moving, resting, backwards, first = plan
    p = len(lo)
    got = answer((yield ask(*first)))
    k = got.shape[0]
    count = len(moving)
    y = got[:, :count * n].reshape(k * count, n)              # a row for each function on each moving piece
    largest = np.abs(got).max(axis=1).tolist()                 # NaN or infinite where any value is
    if not all(map(math.isfinite, largest)):
        raise FloatingPointError("function is not finite on the search grid")
    scales = np.broadcast_to(np.asarray(scale, dtype=float).reshape(-1), (k,)).tolist()   # one for all, or one each
    magnitude = [max(s, m) for s, m in zip(scales, largest, strict=True)]
    held = got[:, count * n:].tolist()                         # each steady piece's value, for each function
    edges = y[:, _EDGES].tolist()                              # each row's first five and last five
    flat = _flat_rows(y, magnitude, count)
    grid = _grid_candidates(y, flat, edges, magnitude, count) if count else []
    found: list[list[tuple[float, float]]] = [[] for _ in edges]   # each grid row's peaks
    if grid:
        centres, windows = _windows(y, grid, n)
        near = windows.tolist()
        from_end = [j == 0 or j == n - 1 for _, j in grid]
        fits = _coefficients_apart(windows, from_end)
        peaks = _estimates(zip(grid, centres, near, fits, strict=True), moving, lo, hi, width, n)
        yield from _refined(peaks, lo, hi, width, ask, answer)
        for peak in peaks:                  # a peak found from an end only where it beats that end by the tie
            if peak.end is None or peak.value - peak.end > TIE * magnitude[peak.f]:
                found[peak.row].append((peak.at, peak.value))
    at: list[list[float]] = []
    value: list[list[float]] = []
    rows = zip(edges, found, strict=True)
    for f in range(k):
        tie = TIE * magnitude[f]
        row_at, row_value = [0.0] * p, [0.0] * p
        at.append(row_at)
        value.append(row_value)
        for piece, (edge, here) in zip(moving, rows, strict=False):   # this function's rows (moving first: zip
            #                                                           then takes no row past its last piece)
            row_at[piece], row_value[piece] = _first_largest([(lo[piece], edge[0]), (hi[piece], edge[9]), *here], tie,
                                                             backwards[piece])
        for (piece, where), v in zip(resting, held[f], strict=True):
            row_at[piece], row_value[piece] = where, v
    return at, value, magnitude


def present(index: np.ndarray) -> np.ndarray:
    """The distinct values of the non-negative integers ``index``, in order (np.unique without loading numpy.ma)."""
    return np.flatnonzero(np.bincount(index)) if index.size else index
