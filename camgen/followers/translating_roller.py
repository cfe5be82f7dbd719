"""The translating roller follower, centred or offset (the knife edge is the same with a radius of 0).

The follower moves along the line x = ``offset`` parallel to +Y in the fixed frame;
a positive offset puts that line to the right of the cam centre (+X) when the
follower is seen on top. Displacement s is in mm.

Its centre is at (e, d0 + s), d0 = sqrt(Rp^2 - e^2), Rp = base radius + roller
radius (the prime radius); the pressure angle is phi = atan((s' - sense * e) / (d0 + s)).
With a counter-clockwise cam (sense = +1) a positive offset lowers the pressure angle
on rises and raises it on returns.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from camgen.core.errors import SpecError
from camgen.followers.base import FollowerType, PitchGeometry, centre_path
from camgen.followers.drawing import Face, Stroke, Translating, stem_and_roller, upright


@dataclass(frozen=True)
class TranslatingRoller(Translating):
    """Roller of ``roller_radius`` mm (0 for a knife edge) on a prime circle of ``prime_radius`` mm, offset mm (+X).

    Parameters
    ----------
    prime_radius : float
        Rp (mm): the base radius plus the roller's, the circle the roller's centre rides at rest.
    roller_radius : float
        The roller's radius (mm); 0 for a knife edge.
    offset : float, optional
        e (mm): the follower's line x = e, + to the right of the cam centre (+X) with the follower on top.
    sense : int, optional
        +1 for a cam turning counter-clockwise seen from +Z (the default), -1 for clockwise.

    Raises
    ------
    SpecError
        Naming ``follower.offset`` where |offset| is not below the prime radius.
    """

    prime_radius: float
    roller_radius: float
    offset: float = 0.0
    sense: int = 1

    flat: ClassVar[bool] = False
    lift_unit: ClassVar[str] = "mm"
    #: its curvature and pressure angle are made from the motion in the fixed frame, not from the cam angle: constant
    #: on a dwell to the last bit (the analysis then searches a dwell at one point, see Program.maxima_steps)
    steady: ClassVar[bool] = True

    def __post_init__(self) -> None:
        if not abs(self.offset) < self.prime_radius:
            raise SpecError(f"|offset| must be smaller than the prime radius {self.prime_radius:.6g} mm "
                            f"(base radius + roller radius; got {self.offset:.6g} mm)", "follower.offset")

    @property
    def contact_radius(self) -> float:
        return self.roller_radius

    @property
    def d0(self) -> float:
        """Height of the roller centre above the cam centre at s = 0 (mm)."""
        return math.sqrt((self.prime_radius - self.offset) * (self.prime_radius + self.offset))

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        """Pitch geometry at cam angles ``theta`` (rad) for ``motion`` = s, s', s'', s''' (mm per rad^k)."""
        s, s1, s2 = motion[0], motion[1], motion[2]
        return centre_path(theta, (self.offset, self.d0 + s), (0.0, s1), (0.0, s2), (0.0, 1.0), self.sense)

    @property
    def axis_x(self) -> float:
        """Its axis, x = offset (mm)."""
        return float(self.offset or 0.0)

    def sketch(self, theta: np.ndarray, geometry: PitchGeometry, reach: float, face: Face,
               roller: float) -> tuple[Stroke, ...]:
        """Its stem, 0.45 ``reach`` long, and its roller (none for a knife edge)."""
        return stem_and_roller(self.fixed(theta, geometry), 0.45 * reach, roller)

    def pose(self, contact: np.ndarray, reach: float, face: Face) -> tuple[Stroke, ...]:
        return upright(self.offset, contact, reach, self.roller_radius)


def _offset_floor(table: Any, base_radius: float) -> float:
    """The least roller radius (mm) that puts an offset follower's centre on the prime circle."""
    return max(0.0, abs(table.offset) - base_radius)


FOLLOWER = FollowerType(
    "translating-roller", make=lambda t, rb, rr, sense: TranslatingRoller(rb + rr, rr, t.offset, sense),
    base_radius_range=lambda t, rr, top: (max(0.0, abs(t.offset) - rr), math.inf),
    roller_floor=_offset_floor)
