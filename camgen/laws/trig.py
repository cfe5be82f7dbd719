"""Trigonometric laws: simple harmonic and cycloidal.

Each fills its rows in place (a law is evaluated on every evaluation of a cam, where each numpy call costs more than
its arithmetic): the same operations on the same numbers as the formulas in the docstrings, term by term."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from camgen.laws.base import Law, as_array, blank, rows as _rows
from camgen.numeric import constant

TWO_PI = 2 * np.pi
#: the laws' factors as read-only 0-d arrays, which numpy takes faster than Python numbers (the same float64 values)
_ONE, _TWO, _PI, _TWO_PI = constant(1.0), constant(2.0), constant(np.pi), constant(TWO_PI)
_HALF_PI, _HALF_PI2, _HALF_PI3 = constant(np.pi / 2), constant(np.pi**2 / 2), constant(-(np.pi**3) / 2)
_FOUR_PI2 = constant(4 * np.pi**2)


def _sin_cos(u: ArrayLike, k: Any, sin_row: int, cos_row: int) -> tuple[np.ndarray, np.ndarray, tuple, Any, Any]:
    """``u`` as an array, an empty array for f and its derivatives (4, *u.shape) and its rows (see :func:`blank`),
    and sin(k u) and cos(k u) made in the rows ``sin_row`` and ``cos_row`` (k u made in f's row, filled after)."""
    u = as_array(u)
    out, rows = blank(u)
    x = np.multiply(k, u, out=rows[0])
    return u, out, rows, np.sin(x, out=rows[sin_row]), np.cos(x, out=rows[cos_row])


@dataclass(frozen=True)
class Harmonic(Law):
    """Simple harmonic: f = (1 - cos(pi u)) / 2. Jerk is infinite at both ends (acceleration jumps).

    f' = pi/2 sin(pi u), f'' = pi^2/2 cos(pi u), f''' = -pi^3/2 sin(pi u)."""

    name = "harmonic"
    PARAMETERLESS = True

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u, out, (f, _, _, f3), s, c = _sin_cos(u, _PI, 1, 2)
        np.multiply(_HALF_PI3, s, out=f3)
        np.subtract(_ONE, c, out=f)                 # before c is scaled
        s *= _HALF_PI
        c *= _HALF_PI2
        f /= _TWO
        return out


@dataclass(frozen=True)
class Cycloidal(Law):
    """Cycloidal: f = u - sin(2 pi u) / (2 pi). Acceleration is zero at both ends.

    f' = 1 - cos(2 pi u), f'' = 2 pi sin(2 pi u), f''' = 4 pi^2 cos(2 pi u)."""

    name = "cycloidal"
    PARAMETERLESS = True

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u, out, (f, f1, _, _), s, c = _sin_cos(u, _TWO_PI, 2, 3)
        np.subtract(u, np.divide(s, _TWO_PI, out=f), out=f)
        np.subtract(_ONE, c, out=f1)
        s *= _TWO_PI
        c *= _FOUR_PI2
        return out


@dataclass(frozen=True)
class DoubleHarmonic(Law):
    """Double harmonic: f = ((1 - cos(pi u)) - (1 - cos(2 pi u)) / 4) / 2.

    Zero acceleration at the start, -pi^2 at the end: meant for a rise followed at
    once by a return (no dwell), where its acceleration then runs on smoothly.
    """

    name = "double-harmonic"
    PARAMETERLESS = True

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        x = np.pi * as_array(u)
        c1, s1, c2, s2 = np.cos(x), np.sin(x), np.cos(2 * x), np.sin(2 * x)
        pi = np.pi
        return _rows(((1 - c1) - (1 - c2) / 4) / 2, (pi * s1 - pi / 2 * s2) / 2,
                     (pi**2 * c1 - pi**2 * c2) / 2, (-(pi**3) * s1 + 2 * pi**3 * s2) / 2)
