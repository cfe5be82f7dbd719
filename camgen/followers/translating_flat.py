"""The translating flat-faced follower, its face perpendicular to the motion.

The face is the line y = Rb + s in the fixed frame; it touches the cam at
(sense * s', Rb + s), so it must reach from min to max of sense * s' about the
follower's axis; the profile's radius of curvature is Rb + s + s'' and must stay
positive (else the profile folds into a cusp). Its pressure angle is 0.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from camgen.followers.base import FlatFace, FollowerType, PitchGeometry, from_support, rotate


@dataclass(frozen=True)
class TranslatingFlat(FlatFace):
    """Flat face perpendicular to the motion, on a cam of ``base_radius`` mm (see the module docstring).

    Parameters
    ----------
    base_radius : float
        Rb (mm): the face rests on the base circle, y = Rb at s = 0.
    sense : int, optional
        +1 for a cam turning counter-clockwise seen from +Z (the default), -1 for clockwise.
    """

    base_radius: float
    sense: int = 1

    lift_unit: ClassVar[str] = "mm"
    face_origin: ClassVar[str] = "the follower's axis (+X)"

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


FOLLOWER = FollowerType("translating-flat", make=lambda t, rb, rr, sense: TranslatingFlat(rb, sense))
