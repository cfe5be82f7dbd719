"""Trigonometric laws: simple harmonic and cycloidal."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from camgen.laws.base import Law, as_array, rows as _rows


@dataclass(frozen=True)
class Harmonic(Law):
    """Simple harmonic: f = (1 - cos(pi u)) / 2. Jerk is infinite at both ends (acceleration jumps)."""

    name = "harmonic"
    PARAMETERLESS = True

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        x = np.pi * as_array(u)
        c, s = np.cos(x), np.sin(x)
        return _rows((1 - c) / 2, np.pi / 2 * s, np.pi**2 / 2 * c, -(np.pi**3) / 2 * s)


@dataclass(frozen=True)
class Cycloidal(Law):
    """Cycloidal: f = u - sin(2 pi u) / (2 pi). Acceleration is zero at both ends."""

    name = "cycloidal"
    PARAMETERLESS = True

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u = as_array(u)
        x = 2 * np.pi * u
        c, s = np.cos(x), np.sin(x)
        return _rows(u - s / (2 * np.pi), 1 - c, 2 * np.pi * s, 4 * np.pi**2 * c)


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
