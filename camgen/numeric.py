"""Small numerical helpers shared by the analyses (no geometry, no I/O)."""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

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
