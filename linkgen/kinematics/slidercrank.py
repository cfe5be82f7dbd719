"""Slider-crank (centred or offset) and scotch yoke, exact and vectorised.

Frame: crank pivot at the origin, the slider moves along the line y = ``offset``
parallel to +X (a positive offset puts the line above the crank pivot); the crank
angle theta is counter-clockwise from +X. x is the slider pin's abscissa (mm);
derivatives are with respect to crank angle (mm/rad, mm/rad^2) and, in
:meth:`SliderCrank.motion`, with respect to time for a crank speed omega (rad/s).
Top dead centre (TDC) is the extended position, farthest from the crank.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from linkgen.kinematics.grashof import check_finite

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class SliderMotion:
    """Slider position (mm), velocity (mm/s) and acceleration (mm/s^2), and rod angle (rad), per crank angle."""

    theta: np.ndarray
    x: np.ndarray
    v: np.ndarray
    a: np.ndarray
    rod: np.ndarray


@dataclass(frozen=True)
class SliderCrank:
    """Crank ``crank`` mm, connecting rod ``rod`` mm, slider line offset ``offset`` mm (see module docstring).

    Parameters
    ----------
    crank : float
        The crank's length (mm), from its pivot at the origin to the crank pin.
    rod : float
        The connecting rod's length (mm), from the crank pin to the slider pin.
    offset : float, optional
        The slider line y = offset (mm): + above the crank pivot.

    Raises
    ------
    SpecError
        A crank or rod that is not a finite length > 0, or an offset that is not finite or not below
        crank + rod in size, each naming its ``linkage.<key>``.
    """

    crank: float
    rod: float
    offset: float = 0.0

    def __post_init__(self) -> None:
        for name, value in (("linkage.crank", self.crank), ("linkage.rod", self.rod)):
            if not (value > 0 and math.isfinite(value)):
                raise SpecError(f"must be a finite length > 0 mm (got {value})", name)
        if not math.isfinite(self.offset):
            raise SpecError(f"must be a finite number of mm (got {self.offset})", "linkage.offset")
        if abs(self.offset) >= self.crank + self.rod:
            raise SpecError(f"|offset| must be < crank + rod = {self.crank + self.rod:.6g} mm "
                            f"(got {self.offset:.6g} mm)", "linkage.offset")

    @property
    def turns_fully(self) -> bool:
        """True when the crank can make full turns: rod >= crank + |offset|."""
        return self.rod >= self.crank + abs(self.offset)

    def input_range(self) -> tuple[float, float] | None:
        """Crank angles (rad) reachable when the crank cannot turn fully, else None (see :meth:`turns_fully`)."""
        if self.turns_fully:
            return None
        r, lr, e = self.crank, self.rod, self.offset
        # reachable while |r sin theta - e| <= L: sin theta in [(e - L)/r, (e + L)/r]
        lo = math.asin(max(-1.0, (e - lr) / r))
        hi = math.asin(min(1.0, (e + lr) / r))
        return (lo, hi)

    def _root(self, theta: np.ndarray) -> np.ndarray:
        """sqrt(L^2 - (r sin theta - e)^2), the rod's extent along the slider line; a clear error where negative."""
        h = self.crank * np.sin(theta) - self.offset
        inside = (self.rod - h) * (self.rod + h)
        if np.any(inside < -1e-10 * self.rod**2):
            lo, hi = self.input_range() or (0.0, 0.0)
            raise SpecError(f"the rod cannot reach the slider line at some of these crank angles; reachable crank "
                            f"angles: [{math.degrees(lo):.6g}, {math.degrees(hi):.6g}] degrees", "angle")
        return np.sqrt(np.maximum(inside, 0.0))

    def position(self, theta: ArrayLike) -> np.ndarray:
        """Exact slider position x = r cos theta + sqrt(L^2 - (r sin theta - e)^2), mm, at crank angles ``theta``
        (rad; one that is not a finite number is a :class:`SpecError`)."""
        t = np.asarray(theta, dtype=float)
        check_finite(t, "crank angle")
        return self.crank * np.cos(t) + self._root(t)

    def derivatives(self, theta: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """x, dx/dtheta (mm/rad) and d2x/dtheta2 (mm/rad^2), exact, at crank angles ``theta`` (rad, finite)."""
        t = np.asarray(theta, dtype=float)
        check_finite(t, "crank angle")
        r = self.crank
        h = r * np.sin(t) - self.offset
        q = self._root(t)
        hp, hpp = r * np.cos(t), -r * np.sin(t)
        with np.errstate(divide="ignore", invalid="ignore"):
            x1 = -r * np.sin(t) - h * hp / q
            x2 = -r * np.cos(t) - (hp**2 + h * hpp) / q - (h * hp) ** 2 / q**3
        return r * np.cos(t) + q, x1, x2

    def motion(self, theta: ArrayLike, omega: float) -> SliderMotion:
        """Slider motion at crank angles ``theta`` for a constant crank speed ``omega`` rad/s."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        x, x1, x2 = self.derivatives(t)
        rod = np.arctan2(self.offset - self.crank * np.sin(t), x - self.crank * np.cos(t))
        return SliderMotion(t, x, x1 * omega, x2 * omega**2, rod)

    def dead_centres(self) -> tuple[tuple[str, float, float], ...]:
        """(kind, crank angle rad, slider x mm) at TDC (crank and rod in line, extended) and BDC (folded)."""
        r, lr, e = self.crank, self.rod, self.offset
        out = [("TDC", math.asin(e / (r + lr)), math.sqrt((r + lr) ** 2 - e**2))]
        if self.turns_fully and lr > r:
            x = math.sqrt((lr - r) ** 2 - e**2)
            out.append(("BDC", math.atan2(e, x) + math.pi, x))
        return tuple(out)

    @property
    def stroke(self) -> float:
        """Distance between the dead centres (mm); for a centred slider-crank 2 r."""
        dc = self.dead_centres()
        if len(dc) < 2:
            raise SpecError("the crank cannot turn fully (rod < crank + |offset|): no stroke between dead centres",
                            "linkage.rod")
        return dc[0][2] - dc[1][2]

    @property
    def time_ratio(self) -> float:
        """Quick-return ratio (>= 1): the longer of the two crank travels between dead centres over the shorter."""
        dc = self.dead_centres()
        if len(dc) < 2:
            raise SpecError("the crank cannot turn fully: no time ratio", "linkage.rod")
        travel = (dc[1][1] - dc[0][1]) % TWO_PI
        return max(travel, TWO_PI - travel) / min(travel, TWO_PI - travel)

    def approximation(self, theta: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The classic approximation of a centred slider-crank, as displacement from TDC (mm, per rad, per rad^2).

        d = r (1 - cos t) + (r^2 / 2L) sin^2 t, d' = r (sin t + (r / 2L) sin 2t),
        d'' = r (cos t + (r / L) cos 2t). Its displacement error is about
        r^4 sin^4 t / (8 L^3), the first term it drops.
        """
        if self.offset != 0:
            raise SpecError("the classic approximation is for a centred slider-crank (offset = 0)", "linkage.offset")
        t = np.asarray(theta, dtype=float)
        r, lr = self.crank, self.rod
        return (r * (1 - np.cos(t)) + r**2 / (2 * lr) * np.sin(t) ** 2,
                r * (np.sin(t) + r / (2 * lr) * np.sin(2 * t)),
                r * (np.cos(t) + r / lr * np.cos(2 * t)))


@dataclass(frozen=True)
class ScotchYoke:
    """Scotch yoke of crank ``crank`` mm: x = r (1 - cos theta) from the dead centre, pure simple harmonic motion.

    Parameters
    ----------
    crank : float
        r (mm): the crank's length, its pin running in the yoke's slot.

    Raises
    ------
    SpecError
        Naming ``linkage.crank``: not a finite length > 0.
    """

    crank: float

    def __post_init__(self) -> None:
        if not (self.crank > 0 and math.isfinite(self.crank)):
            raise SpecError(f"must be a finite length > 0 mm (got {self.crank})", "linkage.crank")

    def motion(self, theta: ArrayLike, omega: float) -> SliderMotion:
        """Slider motion at crank angles ``theta`` (rad, finite) for a constant crank speed ``omega`` rad/s."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        check_finite(t, "crank angle")
        r = self.crank
        return SliderMotion(t, r * (1 - np.cos(t)), r * omega * np.sin(t), r * omega**2 * np.cos(t),
                            np.full(t.shape, math.pi / 2))

    def dead_centres(self) -> tuple[tuple[str, float, float], ...]:
        return (("TDC", 0.0, 0.0), ("BDC", math.pi, 2 * self.crank))

    @property
    def stroke(self) -> float:
        return 2 * self.crank

    @property
    def time_ratio(self) -> float:
        return 1.0
