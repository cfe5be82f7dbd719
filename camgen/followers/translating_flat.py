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
from camgen.followers.drawing import Face, Stroke, Translating


@dataclass(frozen=True)
class TranslatingFlat(FlatFace, Translating):
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

    def sketch(self, theta: np.ndarray, geometry: PitchGeometry, reach: float, face: Face,
               roller: float) -> tuple[Stroke, ...]:
        """Its face from ``face[0]`` to ``face[1]`` mm along it (the contact's travel and the face's margins), at
        the contact's height, and its stem on the axis, 0.45 ``reach`` long."""
        y = self.fixed(theta, geometry)[:, 1]
        n, stem = len(theta), 0.45 * reach
        lo, hi = face if face is not None else (0.0, 0.0)
        line = np.stack([np.column_stack([np.full(n, lo), y]), np.column_stack([np.full(n, hi), y])], axis=1)
        rod = np.stack([np.column_stack([np.zeros(n), y]), np.column_stack([np.zeros(n), y + stem])], axis=1)
        return Stroke("face", line, "follower"), Stroke("stem", rod, "follower")

    def pose(self, contact: np.ndarray, reach: float, face: Face) -> tuple[Stroke, ...]:
        """Its face from ``face[0]`` to ``face[1]`` at the contact's height, and its stem rising half ``reach``."""
        y = float(contact[1])
        lo, hi = face if face is not None else (0.0, 0.0)
        return (Stroke("follower", np.array([[lo, y], [hi, y]]), "follower"),
                Stroke("stem", np.array([[0.0, y], [0.0, y + 0.5 * reach]]), "follower"))


FOLLOWER = FollowerType("translating-flat", make=lambda t, rb, rr, sense: TranslatingFlat(rb, sense))
