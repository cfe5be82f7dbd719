"""Quick-return inversions of the slider-crank: the crank-shaper (oscillating lever) and Whitworth.

Frame: the driving crank's pivot O2 at the origin, the slotted link's pivot O4 at
(ground, 0) on +X; crank angle theta counter-clockwise from +X; the crank turns at
constant speed. A block on the crank pin A slides in the slotted link O4-A.

* Crank-shaper (crank < ground): the lever oscillates by +-asin(crank / ground)
  about the line O4 -> O2; its far end drives the ram along the line perpendicular
  to O2-O4 at ``lever`` mm from O4, so the ram sits at u = lever tan(phi), phi being
  the lever angle from O4 -> O2 (counter-clockwise positive).
* Whitworth (crank > ground): the slotted link turns fully; an ``arm`` on its shaft
  drives the ram through a ``rod`` along the line through O4 perpendicular to
  O2-O4 (+Y), a slider-crank whose crank angle psi is the slotted link's angle
  from +Y.

In both the working stroke takes the longer crank travel: time ratio
Q = (pi + 2 asin(k)) / (pi - 2 asin(k)), k = crank / ground (shaper) or ground /
crank (Whitworth).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from linkgen.kinematics.grashof import check_finite
from linkgen.kinematics.slidercrank import SliderCrank, SliderMotion


def _positive(**lengths: float) -> None:
    for name, value in lengths.items():
        if not (value > 0 and math.isfinite(value)):
            raise SpecError(f"must be a finite length > 0 mm (got {value})", f"linkage.{name}")


def _slot(crank: float, ground: float, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Angle of O4 -> A (rad, from +X) and its first and second derivatives with respect to theta.

    rate = N / D with N = r^2 - r d cos theta and D = |O4 A|^2 = r^2 + d^2 - 2 r d cos theta. A crank angle that
    is not a finite number is a :class:`SpecError`.
    """
    check_finite(theta, "crank angle")
    r, d = crank, ground
    c, s = np.cos(theta), np.sin(theta)
    num, den = r**2 - r * d * c, r**2 + d**2 - 2 * r * d * c
    rate = num / den
    rate1 = (r * d * s * den - num * 2 * r * d * s) / den**2
    return np.arctan2(r * s, r * c - d), rate, rate1


def _ratio(k: float) -> float:
    return (math.pi + 2 * math.asin(k)) / (math.pi - 2 * math.asin(k))


@dataclass(frozen=True)
class CrankShaper:
    """Crank ``crank``, pivots ``ground`` apart (> crank), lever reaching the ram line at ``lever`` (mm).

    Parameters
    ----------
    crank : float
        The driving crank O2-A (mm).
    ground : float
        O2 to the lever's pivot O4 on +X (mm); more than the crank, so the lever oscillates.
    lever : float
        O4 to the ram's line, square to O2-O4 (mm).

    Raises
    ------
    SpecError
        A length that is not finite and > 0, or a ground not longer than the crank (naming ``linkage.ground``).
    """

    crank: float
    ground: float
    lever: float

    def __post_init__(self) -> None:
        _positive(crank=self.crank, ground=self.ground, lever=self.lever)
        if not self.crank < self.ground:
            raise SpecError(f"must be > crank ({self.crank:.6g} mm) for an oscillating lever; a longer crank makes "
                            "the slotted link turn fully: use type = 'whitworth'", "linkage.ground")

    @property
    def swing(self) -> float:
        """Lever swing, full angle (rad): 2 asin(crank / ground)."""
        return 2 * math.asin(self.crank / self.ground)

    @property
    def time_ratio(self) -> float:
        return _ratio(self.crank / self.ground)

    @property
    def stroke(self) -> float:
        """Ram stroke (mm): 2 lever tan(swing / 2)."""
        return 2 * self.lever * math.tan(self.swing / 2)

    def dead_centres(self) -> tuple[tuple[str, float, float], ...]:
        """(kind, crank angle rad, ram position mm) where the crank is square to the lever (its extremes)."""
        c = math.acos(self.crank / self.ground)
        return (("end", c, float(self.motion(np.array([c]), 1.0).x[0])),
                ("end", -c, float(self.motion(np.array([-c]), 1.0).x[0])))

    def motion(self, theta: ArrayLike, omega: float) -> SliderMotion:
        """Ram position (mm), velocity (mm/s) and acceleration (mm/s^2), exact."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        angle, rate, rate1 = _slot(self.crank, self.ground, t)
        phi = np.angle(np.exp(1j * (angle - math.pi)))      # lever angle from O4 -> O2
        sec2 = 1.0 / np.cos(phi) ** 2
        u1 = self.lever * sec2 * rate
        u2 = self.lever * sec2 * (2 * np.tan(phi) * rate**2 + rate1)
        return SliderMotion(t, self.lever * np.tan(phi), u1 * omega, u2 * omega**2, phi)


@dataclass(frozen=True)
class Whitworth:
    """Crank ``crank`` (> ``ground``), ram ``arm`` and ``rod`` (mm), see the module docstring.

    Parameters
    ----------
    crank : float
        The driving crank O2-A (mm); longer than the ground, so the slotted link turns fully.
    ground : float
        O2 to the slotted link's pivot O4 on +X (mm).
    arm : float
        The arm on the slotted link's shaft (mm), the ram's crank.
    rod : float
        The rod from the arm to the ram (mm); longer than the arm.

    Raises
    ------
    SpecError
        A length that is not finite and > 0, a ground not shorter than the crank (naming ``linkage.ground``), or
        a rod not longer than the arm (naming ``linkage.rod``).
    """

    crank: float
    ground: float
    arm: float
    rod: float

    def __post_init__(self) -> None:
        _positive(crank=self.crank, ground=self.ground, arm=self.arm, rod=self.rod)
        if not self.ground < self.crank:
            raise SpecError(f"must be < crank ({self.crank:.6g} mm) so the slotted link turns fully; a shorter "
                            "crank makes it oscillate: use type = 'crank-shaper'", "linkage.ground")
        if not self.rod > self.arm:
            raise SpecError(f"must be > arm ({self.arm:.6g} mm) for the arm to turn fully", "linkage.rod")

    @property
    def ram(self) -> SliderCrank:
        """The slider-crank the slotted link drives: crank ``arm``, rod ``rod``, centred."""
        return SliderCrank(self.arm, self.rod)

    @property
    def time_ratio(self) -> float:
        return _ratio(self.ground / self.crank)

    @property
    def stroke(self) -> float:
        return 2 * self.arm

    def dead_centres(self) -> tuple[tuple[str, float, float], ...]:
        """(kind, crank angle rad, ram position mm) at the ram's two ends."""
        c = math.acos(self.ground / self.crank)
        return (("TDC", c, self.arm + self.rod), ("BDC", -c, self.rod - self.arm))

    def motion(self, theta: ArrayLike, omega: float) -> SliderMotion:
        """Ram position from O4 along +Y (mm), velocity (mm/s), acceleration (mm/s^2)."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        angle, rate, rate1 = _slot(self.crank, self.ground, t)
        psi = angle - math.pi / 2
        x, x1, x2 = self.ram.derivatives(psi)
        return SliderMotion(t, x, x1 * rate * omega, (x2 * rate**2 + x1 * rate1) * omega**2, psi)
