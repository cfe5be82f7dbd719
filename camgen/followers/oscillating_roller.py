"""The oscillating roller follower: an arm on a fixed pivot carrying a roller.

Displacement s is the arm's swing in degrees (radians inside). The pivot lies on the
+X side of the follower's rest position, at ``pivot_distance`` C from the cam centre.
The arm ``arm_length`` L runs from the pivot to the roller's centre, which rests on
the prime circle at (0, Rp); the arm's angle at rest psi0 (between the pivot-to-cam
line and the arm) follows from Rp^2 = C^2 + L^2 - 2 C L cos(psi0). A rise swings
the arm away from the cam, psi0 growing to psi0 + psi.

The pressure angle comes from the geometry: the angle between the contact normal and
the direction in which the roller's centre moves (square to the arm), with no
small-angle approximation.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from camgen.core.errors import SpecError
from camgen.followers.base import FollowerType, PitchGeometry, Swing, from_centre_path, perp, positive, rotate
from camgen.followers.drawing import Face, Pivoted, Stroke


@dataclass(frozen=True)
class OscillatingRoller(Swing, Pivoted):
    """Roller follower on an arm (see the module docstring); lengths in mm.

    Parameters
    ----------
    pivot_distance : float
        C (mm): the cam centre to the arm's pivot, on the +X side of the roller at rest.
    arm_length : float
        L (mm): the pivot to the roller's centre.
    prime_radius : float
        Rp (mm): the base radius plus the roller's; the roller's centre rests at (0, Rp).
    roller_radius : float
        The roller's radius (mm).
    sense : int, optional
        +1 for a cam turning counter-clockwise seen from +Z (the default), -1 for clockwise.

    Raises
    ------
    SpecError
        A pivot distance or arm length that is not a finite length > 0, or an arm that cannot put the roller on
        the prime circle (|C - L| < Rp < C + L; naming ``follower.arm_length``).
    """

    #: its curvature and pressure angle are made from the arm's swing in the fixed frame, not from the cam angle:
    #: constant on a dwell to the last bit (the analysis then searches a dwell at one point, see Program.maxima_steps)
    steady: ClassVar[bool] = True

    pivot_distance: float
    arm_length: float
    prime_radius: float
    roller_radius: float
    sense: int = 1

    def __post_init__(self) -> None:
        positive(self.pivot_distance, "follower.pivot_distance")
        positive(self.arm_length, "follower.arm_length")
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

    @property
    def roller(self) -> float:
        return self.roller_radius

    def sketch(self, theta: np.ndarray, geometry: PitchGeometry, reach: float, face: Face,
               roller: float) -> tuple[Stroke, ...]:
        """Its arm from the pivot to the roller's centre, and the roller."""
        centre = self.fixed(theta, geometry)
        pivot = np.asarray(self.pivot, dtype=float)
        arm = np.stack([np.broadcast_to(pivot, (len(theta), 2)), centre], axis=1)
        return Stroke("arm", arm, "follower"), Stroke("roller", centre[:, None, :], "roller", roller)

    def report_fields(self) -> dict[str, Any]:
        """Its pivot and the arm's rest angle (degrees)."""
        return {**super().report_fields(), "rest_angle_deg": math.degrees(self.rest_angle)}


def _arm_floor(table: Any, base_radius: float) -> float:
    """The least roller radius (mm) whose centre the arm can put on the prime circle."""
    return max(0.0, abs(table.pivot_distance - table.arm_length) - base_radius)


FOLLOWER = FollowerType(
    "oscillating-roller", oscillating=True,
    make=lambda t, rb, rr, sense: OscillatingRoller(t.pivot_distance, t.arm_length, rb + rr, rr, sense),
    base_radius_range=lambda t, rr, top: (max(0.0, abs(t.pivot_distance - t.arm_length) - rr),
                                          t.pivot_distance + t.arm_length - rr),
    roller_floor=_arm_floor,
    path_length=lambda t, lift: t.arm_length * math.radians(lift))
