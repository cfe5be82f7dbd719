"""The oscillating flat-faced follower: a straight edge through a fixed pivot.

Displacement s is the arm's swing in degrees (radians inside). The face passes
through the pivot and touches the base circle at (0, Rb) at rest (the pivot at height
Rb, ``pivot_distance`` from the cam centre, on +X); a rise turns it away from the cam
about the pivot. Its profile is the envelope of the face's lines. The pressure angle
is the angle between the contact normal and the direction in which the face's point at
the contact moves (square to the line from the pivot).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from camgen.core.errors import SpecError
from camgen.followers.base import FlatFace, FollowerType, PitchGeometry, from_support, perp, positive, rotate


@dataclass(frozen=True)
class OscillatingFlat(FlatFace):
    """Flat-faced arm pivoted ``pivot_distance`` mm from the cam centre, on a cam of ``base_radius`` mm.

    Parameters
    ----------
    pivot_distance : float
        The cam centre to the pivot (mm), on +X at the base circle's height; more than ``base_radius``.
    base_radius : float
        Rb (mm): at rest the face touches the base circle at (0, Rb).
    sense : int, optional
        +1 for a cam turning counter-clockwise seen from +Z (the default), -1 for clockwise.

    Raises
    ------
    SpecError
        Naming ``follower.pivot_distance``: not a finite length > 0, or not beyond the base radius.
    """

    pivot_distance: float
    base_radius: float
    sense: int = 1

    lift_unit: ClassVar[str] = "deg"
    face_origin: ClassVar[str] = "the pivot, along the face"
    #: a rise turns the face clockwise about a pivot on +X
    _swing: ClassVar[float] = -1.0

    def __post_init__(self) -> None:
        positive(self.pivot_distance, "follower.pivot_distance")
        if not self.pivot_distance > self.base_radius:
            raise SpecError(f"must be > the base radius {self.base_radius:.6g} mm (the face touches the base circle "
                            "on +Y and passes through the pivot)", "follower.pivot_distance")

    @property
    def pivot(self) -> np.ndarray:
        rb = self.base_radius
        return np.array([math.sqrt(self.pivot_distance**2 - rb**2), rb])

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        """The profile for arm swing ``motion`` = psi, psi', psi'', psi''' in degrees per rad^k."""
        psi, psi1, psi2, psi3 = (np.radians(m) for m in motion)
        k, sigma, pv = self._swing, self.sense, self.pivot
        m = np.column_stack([-np.sin(k * psi), np.cos(k * psi)])      # the face normal (0, 1) turned by k psi
        pm, pj = m @ pv, perp(m) @ pv                                    # P . m and P . J m
        p = pm
        p1 = k * psi1 * pj
        p2 = k * psi2 * pj - psi1**2 * pm
        p3 = k * psi3 * pj - 3 * psi1 * psi2 * pm - k * psi1**3 * pj
        derivs = np.stack([p1, p2, p3, k * psi1 - sigma, k * psi2, k * psi3])
        alpha = math.pi / 2 + k * psi - sigma * theta

        def travel(contact: np.ndarray) -> np.ndarray:
            arm = contact - pv
            length = np.linalg.norm(arm, axis=1)
            return k * perp(arm) / np.where(length > 0, length, 1.0)[:, None]

        return from_support(theta, p, alpha, derivs, sigma, travel)

    def face_position(self, geometry: PitchGeometry) -> np.ndarray:
        """Distance (mm) from the pivot along the face to the contact point, for each sample."""
        back = self.sense * geometry.theta
        contact = rotate(geometry.point, back)
        return np.linalg.norm(contact - self.pivot, axis=1)


FOLLOWER = FollowerType("oscillating-flat", needs=frozenset({"pivot_distance"}), takes=frozenset({"face_margin"}),
                        oscillating=True, make=lambda t, rb, rr, sense: OscillatingFlat(t.pivot_distance, rb, sense),
                        base_radius_range=lambda t, rr: (0.0, t.pivot_distance), path_length=None)
