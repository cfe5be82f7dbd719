"""Small numerical helpers shared by the analyses (no geometry, no I/O)."""
from __future__ import annotations

from collections.abc import Callable, Generator
from typing import Any

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
_OFFSETS = np.arange(-2.0, 3.0)
_UNIT = np.linspace(0.0, 1.0, GRID)


#: the quartic through five values at t = -2..2: its coefficients of t, t^2, t^3, t^4 (columns)
_QUARTIC = (np.array([[1, -1, -1, 1], [-8, 16, 2, -4], [0, -30, 0, 6], [8, 16, -2, -4], [-1, -1, 1, 1]])
            / [12, 24, 12, 24])


def _vertex(y: np.ndarray, lo: float | np.ndarray, hi: float | np.ndarray) -> tuple[np.ndarray, ...]:
    """Where the quartic through each row of ``y`` (m, 5) (at t = -2..2) peaks, by Newton's method on its slope from
    the parabola's vertex: t (m,), zero where ``ok`` (m,) is False (no maximum within [lo, hi]); the quartic's value
    there; and its coefficients a2 and a4 (of t^2, t^4)."""
    a1, a2, a3, a4 = (y @ _QUARTIC).T
    twice, thrice, six = 2 * a2, 3 * a3, 6 * a3               # the same numbers each step: made once
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = -a1 / twice
        for _ in range(3):
            t = t - (a1 + t * (twice + t * (thrice + t * 4 * a4))) / (twice + t * (six + t * 12 * a4))
        ok = (twice + t * (six + t * 12 * a4) < 0) & (t >= lo) & (t <= hi)     # False where t is NaN
    t = np.where(ok, t, 0.0)
    return t, ok, y[:, 2] + t * (a1 + t * (a2 + t * (a3 + t * a4))), a2, a4


#: what :func:`maxima_steps` asks for, abscissae (m,) and their pieces (m,); it is sent the values (k, m)
Steps = Generator[tuple[np.ndarray, np.ndarray], np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray]]


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
    its values from ``func(x, piece)``."""
    return drive(maxima_steps(lo, hi, scale=scale, reverse=reverse, n=n), lambda ask: func(*ask))


def maxima_steps(lo: ArrayLike, hi: ArrayLike, *, scale: ArrayLike = 0.0, reverse: ArrayLike = False,
                 steady: ArrayLike = False, n: int = GRID) -> Steps:
    """Global maxima of k smooth functions on each of p closed intervals, all at once, as a generator: it yields
    ``(x, piece)`` and is sent the functions' values there (see below), so that a caller can evaluate what it asks
    together with other work (one evaluation serving several searches).

    The values sent for an ask ``(x, piece)``, abscissae ``x`` (m,) on the pieces ``piece`` (m,) (indices into
    ``lo``, ``hi``), are the k functions' values there, shape (k, m); each must be smooth (analytic) on each
    closed piece, whose ends it evaluates as given (pass a left limit's abscissa as ``hi``). Returns
    ``(x, value, magnitude)``: x and value (k, p), and each function's magnitude (k,), the larger of ``scale`` (k,)
    and its largest |value| on the grid.

    One dense evaluation (``n`` points a piece) finds each function's interior local maxima on each piece that may
    be its largest (none on a piece where it is constant, within ``TIE``); the quartic through the five grid
    values about each puts its maximiser within ~1e-9 of the piece and tells the peak's breadth; a second
    evaluation, at five points ``STENCIL`` of that breadth apart about the estimate, gives a quartic whose peak is
    the maximiser within ~1e-12 of the breadth and the maximum to the rounding of the values (a peak the estimate
    missed by more than the stencil gets further rounds, at most ``ROUNDS``). A piece's maximum is the first of its
    ends and peaks within ``TIE`` of each function's magnitude of the largest, from its low end (from its high end
    where ``reverse``, (p,) or one for all, is True). A piece where ``steady`` ((p,) or one for all) is True is one
    on which the caller knows every function to be constant to the last bit: its grid is asked for its first point
    only, whose values stand for the rest (the same search as if all were asked).
    Raises FloatingPointError where a value is not finite on the grid or near a peak.
    """
    lo, hi = np.atleast_1d(np.asarray(lo, dtype=float)), np.atleast_1d(np.asarray(hi, dtype=float))
    p = lo.size
    width = hi - lo
    x = lo[:, None] + width[:, None] * (_UNIT if n == GRID else np.linspace(0.0, 1.0, n))
    x[:, -1] = hi
    steady = np.broadcast_to(np.asarray(steady, dtype=bool), (p,))
    if steady.any():                                          # such a piece's grid: its first point's values
        moving = np.flatnonzero(~steady)
        still = np.flatnonzero(steady)
        got = yield (np.concatenate([x[moving].ravel(), x[still, 0]]),
                     np.concatenate([np.repeat(moving, n), still]))
        k = got.shape[0]
        y = np.empty((k, p, n))
        y[:, moving] = got[:, :moving.size * n].reshape(k, moving.size, n)
        y[:, still] = got[:, moving.size * n:, None]
    else:
        y = yield x.ravel(), np.repeat(np.arange(p), n)
        k = y.shape[0]
    y = y.reshape(k * p, n)                                   # a row for each function on each piece
    if not np.isfinite(y).all():
        raise FloatingPointError("function is not finite on the search grid")
    magnitude = np.maximum(np.asarray(scale, dtype=float), np.abs(y).reshape(k, -1).max(axis=1))
    tie = np.repeat(TIE * magnitude, p)
    owner = np.arange(k * p) % p                              # the piece of each row
    # candidates: interior local maxima within what a peak can rise above its grid points (a second difference)
    inner = y[:, 1:-1]
    bend = np.abs(y[:, :-2] - 2 * inner + y[:, 2:])
    peak = (inner >= y[:, :-2]) & (inner >= y[:, 2:]) & (y.max(axis=1) - y.min(axis=1) > tie)[:, None]
    top = np.where(peak, inner, -np.inf).max(axis=1)
    row, j = np.nonzero(peak & (inner >= (top - bend.max(axis=1))[:, None]))
    j = j + 1
    piece = owner[row]
    left, right, size = lo[piece], hi[piece], width[piece]
    step = size / (n - 1)
    c = np.minimum(np.maximum(j, 2), n - 3)                 # np.clip's result, without its dispatch
    value, at = y[row, j], x[piece, j]
    shift = (j - c).astype(float)
    t, ok, _, a2, a4 = _vertex(y[row[:, None], c[:, None] + np.arange(-2, 3)], shift - 1.0, shift + 1.0)
    centre = np.minimum(np.maximum(x[piece, c] + np.where(ok, t, shift) * step, left), right)
    # the peak's breadth: a bell of breadth b has a2 / a4 = 2 b^2 / h^2 on a grid of step h (between 2 h and the piece)
    with np.errstate(divide="ignore", invalid="ignore"):
        breadth = np.minimum(np.maximum(step * np.sqrt(np.abs(a2 / a4) / 2), 2 * step), size)
    breadth = np.where(np.isnan(breadth), size, breadth)
    active = np.arange(row.size)
    for _ in range(ROUNDS):
        c = centre[active]
        d = np.minimum(STENCIL * breadth[active], 0.5 * np.minimum(c - left[active], right[active] - c))
        keep = d > 1e-12 * size[active]                      # at an end already: the grid's point stands
        active, c, d = active[keep], c[keep], d[keep]
        if not active.size:
            break
        px = c[:, None] + d[:, None] * _OFFSETS
        ys = yield px.ravel(), np.repeat(piece[active], 5)
        ys = ys[np.repeat(row[active] // p, 5), np.arange(5 * active.size)].reshape(-1, 5)   # each its own function
        if not np.isfinite(ys).all():
            raise FloatingPointError("function is not finite near a peak")
        t, ok, model, _, _ = _vertex(ys, -2.0, 2.0)
        rows = np.arange(active.size)
        best = np.argmax(ys, axis=1)
        high = ys[rows, best]
        moved = np.where(ok, c + t * d, px[rows, best])
        at[active] = np.where(ok | (high >= value[active]), moved, at[active])
        value[active] = np.maximum(value[active], np.where(ok, np.maximum(model, high), high))
        centre[active] = moved
        active = active[~ok | (np.abs(t) > 0.5)]            # the peak well inside the stencil: its quartic's is exact
    # of the ends and the peaks, the first from the low end (the high end where reversed) within TIE of the largest
    every = np.arange(k * p)
    cand_row = np.concatenate([every, every, row])
    cand_x = np.concatenate([lo[owner], hi[owner], at])
    cand_v = np.concatenate([y[:, 0], y[:, -1], value])
    largest = np.full(k * p, -np.inf)
    np.maximum.at(largest, cand_row, cand_v)
    equal = np.flatnonzero(cand_v >= largest[cand_row] - tie[cand_row])
    backwards = np.asarray(reverse, dtype=bool)
    backwards = np.full(p, backwards) if backwards.ndim == 0 else backwards
    ahead = np.where(backwards[owner[cand_row[equal]]], -1.0, 1.0)
    order = equal[np.lexsort((ahead * cand_x[equal], cand_row[equal]))]
    sorted_rows = cand_row[order]
    starts = np.empty(sorted_rows.size, dtype=bool)           # where a row's candidates begin: its first
    starts[:1] = True
    np.not_equal(sorted_rows[1:], sorted_rows[:-1], out=starts[1:])
    first = order[starts]
    return cand_x[first].reshape(k, p), cand_v[first].reshape(k, p), magnitude


def present(index: np.ndarray) -> np.ndarray:
    """The distinct values of the non-negative integers ``index``, in order (np.unique without loading numpy.ma)."""
    return np.flatnonzero(np.bincount(index)) if index.size else index
