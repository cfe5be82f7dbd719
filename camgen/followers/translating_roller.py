"""Translating roller follower, centred or offset (a knife edge is the case Rr = 0).

The follower moves along the line x = ``offset`` parallel to +Y in the fixed frame;
a positive offset puts that line to the right of the cam centre (+X) when the
follower is seen on top. The roller centre is at (e, d0 + s) with
d0 = sqrt(Rp^2 - e^2), Rp = base radius + roller radius (the prime radius).

The pressure angle is phi = atan((s' - sense * e) / (d0 + s)): positive while the
follower is pushed up harder than the offset relieves it. With a counter-clockwise
cam (sense = +1) a positive offset lowers the pressure angle on rises and raises it
on returns; with a clockwise cam a negative offset does that.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camgen.errors import SpecError
from camgen.followers.base import PitchGeometry, rotate


@dataclass(frozen=True)
class TranslatingRoller:
    """Roller of ``roller_radius`` (mm) on a prime circle of ``prime_radius`` (mm), offset ``offset`` mm (+X)."""

    prime_radius: float
    roller_radius: float
    offset: float = 0.0
    sense: int = 1

    def __post_init__(self) -> None:
        if not abs(self.offset) < self.prime_radius:
            raise SpecError(f"|offset| must be smaller than the prime radius {self.prime_radius:.6g} mm "
                            f"(base radius + roller radius; got {self.offset:.6g} mm)", "follower.offset")

    @property
    def d0(self) -> float:
        """Height of the roller centre above the cam centre at s = 0 (mm)."""
        return math.sqrt((self.prime_radius - self.offset) * (self.prime_radius + self.offset))

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        """Pitch geometry at cam angles ``theta`` (rad) for follower motion ``motion`` = s, s', s'', s''' (mm/rad^k).

        Exact: the pitch point P = R(-sense theta) q with q = (e, d0 + s); its
        derivatives and curvature follow analytically from s, s', s''.
        """
        sigma, e = self.sense, self.offset
        s, s1, s2 = motion[0], motion[1], motion[2]
        r = self.d0 + s
        w = s1 - sigma * e
        # fixed-frame tangent t = q' - sigma J q and second derivative a = q'' - 2 sigma J q' - q
        t = np.column_stack([sigma * r, w])
        a = np.column_stack([2 * sigma * s1 - e, s2 - r])
        speed2 = r**2 + w**2
        kappa = (r**2 - r * s2 + w * (w + s1)) / speed2**1.5
        normal = np.column_stack([-sigma * w, r]) / np.sqrt(speed2)[:, None]
        q = np.column_stack([np.full_like(s, e), r])
        turn = -sigma * theta
        return PitchGeometry(theta=theta, point=rotate(q, turn), d1=rotate(t, turn), d2=rotate(a, turn),
                             normal=rotate(normal, turn), kappa=kappa, pressure_angle=np.arctan2(w, r))
