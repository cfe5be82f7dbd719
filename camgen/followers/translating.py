"""Translating followers: roller (centred or offset), knife edge (a roller of radius 0) and flat face.

The follower moves along the line x = ``offset`` parallel to +Y in the fixed frame;
a positive offset puts that line to the right of the cam centre (+X) when the
follower is seen on top. Displacement s is in mm.

Roller: its centre is at (e, d0 + s), d0 = sqrt(Rp^2 - e^2), Rp = base radius +
roller radius (the prime radius); the pressure angle is
phi = atan((s' - sense * e) / (d0 + s)). With a counter-clockwise cam (sense = +1) a
positive offset lowers the pressure angle on rises and raises it on returns.

Flat face (perpendicular to the motion): the face is the line y = Rb + s; it touches
the cam at (sense * s', Rb + s) in the fixed frame, so it must reach from min to
max of sense * s' about the follower's axis; the profile's radius of curvature is
Rb + s + s'' and must stay positive (else the profile folds into a cusp). Its
pressure angle is 0.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from camgen.core.errors import SpecError
from camgen.followers.base import PitchGeometry, from_centre_path, from_support, rotate


@dataclass(frozen=True)
class TranslatingRoller:
    """Roller of ``roller_radius`` mm (0 for a knife edge) on a prime circle of ``prime_radius`` mm, offset mm (+X)."""

    prime_radius: float
    roller_radius: float
    offset: float = 0.0
    sense: int = 1

    flat: ClassVar[bool] = False
    lift_unit: ClassVar[str] = "mm"

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
        zero = np.zeros_like(s)
        q = np.column_stack([np.full_like(s, self.offset), self.d0 + s])
        up = np.column_stack([zero, np.ones_like(s)])
        return from_centre_path(theta, q, np.column_stack([zero, s1]), np.column_stack([zero, s2]), up, self.sense)


@dataclass(frozen=True)
class TranslatingFlat:
    """Flat face perpendicular to the motion, on a cam of ``base_radius`` mm (see the module docstring)."""

    base_radius: float
    sense: int = 1

    flat: ClassVar[bool] = True
    lift_unit: ClassVar[str] = "mm"
    contact_radius: ClassVar[float] = 0.0

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        """The profile: envelope of the face lines, normal angle pi/2 - sense theta in the cam frame."""
        s, s1, s2, s3 = motion
        zero, one = np.zeros_like(s), np.ones_like(s)
        derivs = np.stack([s1, s2, s3, -self.sense * one, zero, zero])
        up = np.column_stack([zero, one])
        return from_support(theta, self.base_radius + s, math.pi / 2 - self.sense * theta, derivs, self.sense,
                            lambda contact: up)

    def face_position(self, geometry: PitchGeometry) -> np.ndarray:
        """Where the face touches the cam: along the face from the follower's axis (mm, +X positive), = sense s'."""
        return rotate(geometry.point, self.sense * geometry.theta)[:, 0]
