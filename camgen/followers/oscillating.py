"""Oscillating followers: an arm on a fixed pivot carrying a roller or a flat face.

Displacement s is the arm's swing in degrees (radians inside). The pivot lies on the
+X side of the follower's rest position, at ``pivot_distance`` C from the cam centre.

Roller: arm ``arm_length`` L from the pivot to the roller's centre, which rests on
the prime circle at (0, Rp); the arm's angle at rest psi0 (between the pivot-to-cam
line and the arm) follows from Rp^2 = C^2 + L^2 - 2 C L cos(psi0). A rise swings
the arm away from the cam, psi0 growing to psi0 + psi.

Flat face: the face is a straight edge through the pivot, touching the base circle
at (0, Rb) at rest (the pivot at height Rb); a rise turns it away from the cam about
the pivot. Its profile is the envelope of the face's lines.

Pressure angles come from the geometry: the angle between the contact normal and the
direction in which the follower's point at the contact moves (square to the line
from the pivot), with no small-angle approximation.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from camgen.core.errors import SpecError
from camgen.followers.base import PitchGeometry, from_centre_path, from_support, perp, rotate


def _positive(value: float, field: str) -> None:
    if not (value > 0 and math.isfinite(value)):
        raise SpecError(f"must be a finite length > 0 mm (got {value})", field)


@dataclass(frozen=True)
class OscillatingRoller:
    """Roller follower on an arm (see the module docstring); lengths in mm."""

    pivot_distance: float
    arm_length: float
    prime_radius: float
    roller_radius: float
    sense: int = 1

    flat: ClassVar[bool] = False
    lift_unit: ClassVar[str] = "deg"

    def __post_init__(self) -> None:
        _positive(self.pivot_distance, "follower.pivot_distance")
        _positive(self.arm_length, "follower.arm_length")
        c, arm, rp = self.pivot_distance, self.arm_length, self.prime_radius
        if not abs(c - arm) < rp < c + arm:
            raise SpecError(f"the arm cannot put the roller on the prime circle: need |pivot_distance - arm_length| "
                            f"< {rp:.6g} mm (base radius + roller radius) < pivot_distance + arm_length",
                            "follower.arm_length")

    @property
    def contact_radius(self) -> float:
        return self.roller_radius

    @property
    def pivot(self) -> np.ndarray:
        """The pivot (mm, fixed frame)."""
        c, rp = self.pivot_distance, self.prime_radius
        py = (c**2 + rp**2 - self.arm_length**2) / (2 * rp)
        return np.array([math.sqrt(max(c**2 - py**2, 0.0)), py])

    @property
    def rest_angle(self) -> float:
        """psi0 (rad): the angle at the pivot between the cam centre and the roller at rest."""
        c, arm, rp = self.pivot_distance, self.arm_length, self.prime_radius
        return math.acos((c**2 + arm**2 - rp**2) / (2 * c * arm))

    @property
    def _swing_sign(self) -> float:
        """+1 if a counter-clockwise turn of the arm takes the roller away from the cam centre."""
        rest = np.array([0.0, self.prime_radius])
        u0 = rest - self.pivot
        return 1.0 if rest @ np.array([-u0[1], u0[0]]) >= 0 else -1.0

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        """Pitch geometry for arm swing ``motion`` = psi, psi', psi'', psi''' in degrees per rad^k."""
        psi, psi1, psi2 = np.radians(motion[0]), np.radians(motion[1]), np.radians(motion[2])
        k = self._swing_sign
        p = self.pivot
        rest = np.array([0.0, self.prime_radius]) - p
        w = rotate(np.tile(rest, (len(psi), 1)), k * psi)               # pivot -> roller centre
        q1 = k * psi1[:, None] * perp(w)
        q2 = k * psi2[:, None] * perp(w) - (psi1**2)[:, None] * w
        return from_centre_path(theta, p + w, q1, q2, k * perp(w) / self.arm_length, self.sense)


@dataclass(frozen=True)
class OscillatingFlat:
    """Flat-faced arm pivoted ``pivot_distance`` mm from the cam centre, on a cam of ``base_radius`` mm."""

    pivot_distance: float
    base_radius: float
    sense: int = 1

    flat: ClassVar[bool] = True
    lift_unit: ClassVar[str] = "deg"
    contact_radius: ClassVar[float] = 0.0
    #: a rise turns the face clockwise about a pivot on +X
    _swing: ClassVar[float] = -1.0

    def __post_init__(self) -> None:
        _positive(self.pivot_distance, "follower.pivot_distance")
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
