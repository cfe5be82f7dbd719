"""The Geneva law: the wheel's angle, velocity, acceleration and jerk against the driver's angle. numpy only.

Frame and signs. The driver's axis is the origin, the wheel's axis is at (C, 0) on +X (the
centre line). The driver turns counter-clockwise; its angle alpha is the pin's direction,
counter-clockwise from the centre line, in (-pi, pi]: the pin is at a (cos alpha, sin alpha).
The wheel turns the other way (clockwise); its angle beta is measured in its own sense of
rotation from the centre line to the engaged slot (the slot through the pin), so it grows
with alpha. The pin is engaged while |alpha| <= alpha_e = pi/2 - pi/n, where the crank is
square to the slot (radial, tangential entry: a = C sin(pi/n), lambda = a / C = sin(pi/n)):

    tan(beta) = lambda sin(alpha) / (1 - lambda cos(alpha))    (= sin(alpha) / (C/a - cos(alpha)))

so beta runs from -pi/n at entry to +pi/n at exit, and the wheel stays at -pi/n before entry
and +pi/n after exit (the dwell; the next index starts from the next slot). With
D = 1 - 2 lambda cos(alpha) + lambda^2, per radian of driver angle:

    beta'   = lambda (cos(alpha) - lambda) / D
    beta''  = -lambda (1 - lambda^2) sin(alpha) / D^2
    beta''' = -lambda (1 - lambda^2) (cos(alpha) D - 4 lambda sin(alpha)^2) / D^3

(multiply by omega, omega^2, omega^3 of the driver for time derivatives). The velocity is 0 at
entry and exit; the acceleration jumps there from 0 to beta'' = tan(pi/n) (entry) and from
-tan(pi/n) back to 0 (exit), so the jerk is infinite at both.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class GenevaLaw:
    """An external Geneva drive of ``slots`` slots (n >= 3) with radial entry; angles in radians.

    Lengths do not enter the law: it depends on n alone (lambda = sin(pi/n)); ``centre_distance`` (mm) gives the
    crank radius a = C sin(pi/n) and the wheel's radius to the pin at entry, b = C cos(pi/n).

    Parameters
    ----------
    slots : int
        n, the wheel's slots (3 or more).
    centre_distance : float, optional
        C (mm): the driver's axis to the wheel's.

    Raises
    ------
    ValueError
        Fewer than 3 slots, or not a whole number of them.
    """

    slots: int
    centre_distance: float = 1.0

    def __post_init__(self) -> None:
        if not (isinstance(self.slots, int) and self.slots >= 3):
            raise ValueError(f"a Geneva drive needs 3 or more slots (got {self.slots!r})")

    @property
    def ratio(self) -> float:
        """lambda = a / C = sin(pi / n)."""
        return math.sin(math.pi / self.slots)

    @property
    def crank_radius(self) -> float:
        """a = C sin(pi / n) (mm): the pin's circle, for a radial (tangential) entry."""
        return self.centre_distance * self.ratio

    @property
    def entry_radius(self) -> float:
        """b = C cos(pi / n) (mm): the pin's distance from the wheel's axis at entry and exit."""
        return self.centre_distance * math.cos(math.pi / self.slots)

    @property
    def engagement(self) -> float:
        """alpha_e = pi/2 - pi/n: the pin is in a slot while |alpha| <= alpha_e (rad)."""
        return math.pi / 2 - math.pi / self.slots

    @property
    def index(self) -> float:
        """The wheel's turn in one index, 2 pi / n (rad)."""
        return 2 * math.pi / self.slots

    @property
    def acceleration_jump(self) -> float:
        """|beta''| just inside entry and exit: tan(pi / n) per rad^2 of driver angle (0 in the dwell)."""
        return math.tan(math.pi / self.slots)

    def motion(self, alpha: np.ndarray) -> np.ndarray:
        """beta, beta', beta'', beta''' (rad, per rad^k of driver angle), shape (4, len(alpha)), at driver angles
        ``alpha`` (rad, any real: taken modulo 2 pi into (-pi, pi]). Engaged for |alpha| <= alpha_e, both ends
        included (one-sided values of the engagement there); elsewhere the dwell: beta = -pi/n before entry, pi/n
        after exit, derivatives 0."""
        alpha = np.asarray(alpha, dtype=float)
        a = np.atleast_1d(alpha)
        outside = (a > math.pi) | (a <= -math.pi)
        a = np.where(outside, math.pi - np.mod(math.pi - a, 2 * math.pi), a)     # into (-pi, pi], exact inside
        lam = self.ratio
        c, s = np.cos(a), np.sin(a)
        d = 1.0 - 2.0 * lam * c + lam**2
        k = lam * (1.0 - lam**2)
        engaged = np.abs(a) <= self.engagement
        dwell = np.sign(a) * math.pi / self.slots
        out = np.array([np.where(engaged, np.arctan2(lam * s, 1.0 - lam * c), dwell),
                        np.where(engaged, lam * (c - lam) / d, 0.0),
                        np.where(engaged, -k * s / d**2, 0.0),
                        np.where(engaged, -k * (c * d - 4.0 * lam * s**2) / d**3, 0.0)])
        return out.reshape((4, *alpha.shape))

    def velocity_peak(self) -> tuple[float, float]:
        """(largest beta', at alpha in rad): lambda / (1 - lambda) at alpha = 0."""
        lam = self.ratio
        return lam / (1.0 - lam), 0.0

    def acceleration_peak(self) -> tuple[float, float]:
        """(largest |beta''| inside the engagement, at alpha in rad, the exit side; the entry side is its mirror).

        d/dalpha [sin(alpha) / D^2] = 0 gives 2 lambda cos^2 + (1 + lambda^2) cos - 4 lambda = 0, so
        cos(alpha_m) = sqrt(k^2 + 2) - k with k = (1 + lambda^2) / (4 lambda); for n >= 3 it lies inside the
        engagement and its value exceeds the jump tan(pi/n) at the ends."""
        lam = self.ratio
        k = (1.0 + lam**2) / (4.0 * lam)
        at = math.acos(math.sqrt(k * k + 2.0) - k)
        return float(abs(self.motion(np.array([at]))[2, 0])), at
