"""Piecewise laws: uniform, modified uniform (blended and drafted) and parabolic."""
from __future__ import annotations

import math
from abc import abstractmethod
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from camgen.laws.base import Law, as_array


@dataclass(frozen=True)
class Uniform(Law):
    """Uniform (constant velocity): f = u. Acceleration is infinite at both ends."""

    name = "uniform"
    PARAMETERLESS = True

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u = as_array(u)
        return np.stack([u, np.ones_like(u), np.zeros_like(u), np.zeros_like(u)])


@dataclass(frozen=True)
class _LineWithEnds(Law):
    """A straight middle stretch through (1/2, 1/2) between an end piece on [0, u1] and its point mirror.

    Subclasses give the end piece; the last piece is f(u) = 1 - f(1 - u), so the law
    is symmetric and its slope in the middle is the end piece's slope at u1.
    """

    name = "modified-uniform"

    @property
    @abstractmethod
    def u1(self) -> float:
        """Where the first end piece meets the straight stretch (<= 1/2)."""

    @abstractmethod
    def _end(self, u: np.ndarray) -> np.ndarray:
        """f, f', f'', f''' of the first end piece, for u in [0, u1]."""

    @property
    def breakpoints(self) -> tuple[float, ...]:
        return tuple(sorted({self.u1, 1.0 - self.u1}))

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u = as_array(u)
        u1 = self.u1
        slope = float(self._end(np.array(u1))[1])
        out = np.stack([0.5 + slope * (u - 0.5), np.full_like(u, slope), np.zeros_like(u), np.zeros_like(u)])
        lo, hi = u < u1, u >= 1.0 - u1
        if np.any(lo):
            out[:, lo] = self._end(u[lo])
        if np.any(hi):
            m = self._end(1.0 - u[hi])
            out[:, hi] = np.stack([1.0 - m[0], m[1], -m[2], m[3]])
        return out


@dataclass(frozen=True)
class BlendedUniform(_LineWithEnds):
    """Modified uniform, analytic form: constant velocity with blends over ``blend`` of beta at each end.

    ``blend_law = "cycloidal"`` ramps the acceleration as 1 - cos (continuous
    acceleration, finite jerk); ``"parabolic"`` holds it constant (jerk infinite at
    the blend ends). The middle velocity is 1 / (1 - blend) for both.
    """

    blend: float = 0.25
    blend_law: Literal["cycloidal", "parabolic"] = "cycloidal"

    def __post_init__(self) -> None:
        if not 0.0 < self.blend <= 0.5:
            raise SpecError(f"must be > 0 and <= 0.5 of the segment (got {self.blend})", "blend")
        if self.blend_law not in ("cycloidal", "parabolic"):
            raise SpecError(f"must be 'cycloidal' or 'parabolic' (got {self.blend_law!r})", "blend_law")

    @property
    def u1(self) -> float:
        return self.blend

    def _end(self, u: np.ndarray) -> np.ndarray:
        b, v = self.blend, 1.0 / (1.0 - self.blend)
        if self.blend_law == "parabolic":
            return np.stack([v * u**2 / (2 * b), v * u / b, np.full_like(u, v / b), np.zeros_like(u)])
        x = 2 * np.pi * u / b
        return np.stack([
            v * (u**2 / (2 * b) - b / (4 * np.pi**2) * (1 - np.cos(x))),
            v * (u / b - np.sin(x) / (2 * np.pi)),
            v / b * (1 - np.cos(x)),
            v / b * (2 * np.pi / b) * np.sin(x),
        ])


@dataclass(frozen=True)
class DraftedUniform(_LineWithEnds):
    """Modified uniform, classic drafting form.

    In the displacement diagram whose abscissa is the prime-circle arc length
    X = Rp * beta, the straight line is rounded at each end by a circular arc of
    radius equal to the lift h. The law depends only on ``k = Rp * beta / h``, which
    must be at least sqrt(3) (at sqrt(3) the two arcs meet at mid-stroke).
    Acceleration jumps at the ends and where arcs meet the line (jerk infinite).
    """

    k: float = 2.0

    def __post_init__(self) -> None:
        if not self.k >= math.sqrt(3) * (1 - 1e-12):
            raise SpecError(
                f"the drafted form needs prime radius x angle >= sqrt(3) x lift (ratio {self.k:.4g} < 1.732); "
                "lengthen the segment, enlarge the cam or use form = 'blended'", "form")

    @property
    def _alpha(self) -> float:
        """Slope angle of the straight stretch in the drafted diagram (radians)."""
        k = max(self.k, math.sqrt(3))
        return math.asin(min(1.0, 2.0 / math.hypot(k, 1.0))) - math.atan2(1.0, k)

    @property
    def u1(self) -> float:
        return min(0.5, math.sin(self._alpha) / self.k)

    def _end(self, u: np.ndarray) -> np.ndarray:
        k = self.k
        xi = k * u  # abscissa in units of the lift
        w = 1.0 - xi**2
        return np.stack([1 - np.sqrt(w), k * xi / np.sqrt(w), k**2 * w**-1.5, 3 * k**3 * xi * w**-2.5])


@dataclass(frozen=True)
class Parabolic(Law):
    """Parabolic (constant acceleration) with acceleration ratio ``ratio`` = K = a1 / a2.

    Acceleration a1 = 2 / u1 over [0, u1], deceleration a2 = 2 / (1 - u1) after, with
    u1 = 1 / (1 + K) so that the velocity is continuous (peak 2 for any K). K = 1 is
    the symmetric law 2u^2 / 1 - 2(1 - u)^2. Jerk is infinite at the ends and at u1.
    """

    name = "parabolic"
    ratio: float = 1.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.ratio) and self.ratio > 0):
            raise SpecError(f"must be a finite number > 0 (got {self.ratio})", "ratio")

    @property
    def breakpoints(self) -> tuple[float, ...]:
        return (1.0 / (1.0 + self.ratio),)

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u = as_array(u)
        u1 = 1.0 / (1.0 + self.ratio)
        a1, a2 = 2.0 / u1, 2.0 / (1.0 - u1)
        first = u < u1
        zero = np.zeros_like(u)
        return np.stack([
            np.where(first, a1 * u**2 / 2, 1 - a2 * (1 - u) ** 2 / 2),
            np.where(first, a1 * u, a2 * (1 - u)),
            np.where(first, a1, -a2) + zero,
            zero,
        ])
