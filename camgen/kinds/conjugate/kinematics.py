"""The second roller of a conjugate pair's follower, as a follower of its own. Numpy only.

Frames as in :mod:`camgen.followers.base`: the cam centre at the origin, the first roller on +Y at theta = 0 at
rest, ``sense`` +1 for a counter-clockwise cam, curvature positive where convex. Both cams share the motion
program s(theta) (the first roller's: mm for a yoke, degrees of swing for an arm) and the cam frame, so their
keyways, marks and angles agree. The second roller's centre q2(theta) follows from the follower's pose, and
:func:`~camgen.followers.base.from_centre_path` turns it into the second cam's pitch geometry exactly as it does
for any roller: its pitch curve is that path in the cam frame, its profile the path offset inwards by the
roller's radius.

The second cam drives the follower's return, so its pressure angle is measured from the direction in which the
second roller's centre moves while the follower returns: below 90 degrees wherever the second cam can drive the
follower back.

* Translating yoke: the second roller is ``span`` mm from the first along the follower's line, on the far side
  of the shaft: q2 = (e, d0 + s - span). In polar terms, for a centred yoke, the pitch curves' radii at opposite
  polar angles add up to the span: r1(phi) + r2(phi + pi) = span.
* Bell crank (oscillating arm): the second arm is the first turned by ``arm_angle`` about the pivot, towards the
  cam centre, and ``arm_length`` long; it swings with the first, so q2 = pivot + R(k psi) w2.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from camgen.followers.base import PitchGeometry, from_centre_path, perp, rotate
from camgen.followers.oscillating_roller import OscillatingRoller
from camgen.followers.translating_roller import TranslatingRoller


@dataclass(frozen=True)
class SecondRoller:
    """What the second roller shares with the first: the cam's sense of rotation, the unit of the follower's
    displacement, and its radius unless ``radius`` (mm) gives its own (``first`` is the follower's own roller)."""

    first: Any
    radius: float | None = field(default=None, kw_only=True)

    flat: ClassVar[bool] = False

    @property
    def contact_radius(self) -> float:
        return self.first.roller_radius if self.radius is None else self.radius

    @property
    def sense(self) -> int:
        return self.first.sense

    @property
    def lift_unit(self) -> str:
        return self.first.lift_unit

    def report_fields(self) -> dict[str, Any]:
        """What the report's ``follower`` table adds for this roller's cam (see
        :meth:`camgen.followers.drawing.Follower.report_fields`): nothing of its own."""
        return {}


@dataclass(frozen=True)
class YokeRoller(SecondRoller):
    """The second roller of a translating yoke (``first`` a
    :class:`~camgen.followers.translating_roller.TranslatingRoller`): its centre ``span`` mm below the first's, at
    (e, d0 + s - span)."""

    span: float

    def centre(self, s: np.ndarray) -> np.ndarray:
        """The second roller's centre (n, 2; mm, fixed frame) at displacements ``s`` (mm)."""
        return np.column_stack([np.full_like(s, self.first.offset), self.first.d0 - self.span + s])

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        """Pitch geometry of the second cam at cam angles ``theta`` (rad) for ``motion`` = s, s', s'' (mm/rad^k)."""
        s, rate, accel = motion[:3]
        still = np.zeros_like(s)
        down = np.column_stack([still, -np.ones_like(s)])            # the way the second cam drives the yoke
        return from_centre_path(theta, self.centre(s), np.column_stack([still, rate]),
                                np.column_stack([still, accel]), down, self.sense)


def yoke_span(first: TranslatingRoller, s_max: float, prime: float) -> float:
    """The span (mm) putting the second roller's centre ``prime`` mm from the cam centre at its nearest (where the
    follower's displacement is largest, ``s_max`` mm): d0 + s_max + sqrt(prime^2 - e^2)."""
    e = first.offset
    return first.d0 + s_max + math.sqrt((prime - e) * (prime + e))


def yoke_prime(first: TranslatingRoller, s_max: float, span: float) -> float:
    """The second roller's nearest distance (mm) from the cam centre with a yoke of ``span`` mm (the second cam's
    prime radius); its inverse is :func:`yoke_span`."""
    return math.hypot(first.offset, span - first.d0 - s_max)


@dataclass(frozen=True)
class ArmRoller(SecondRoller):
    """The second roller of a bell crank (``first`` an
    :class:`~camgen.followers.oscillating_roller.OscillatingRoller`): on an arm ``arm_length`` mm long,
    ``arm_angle`` radians from the first arm about the same pivot, turned from it towards the cam centre; it swings
    with the first."""

    arm_angle: float
    arm_length: float

    @property
    def pivot(self) -> np.ndarray:
        """The pivot (mm, fixed frame): the first arm's."""
        return self.first.pivot

    def report_fields(self) -> dict[str, Any]:
        """The pivot (mm), as the first arm's cam reports it."""
        return {"pivot_mm": [float(x) for x in self.pivot]}

    @property
    def away(self) -> float:
        """k: +1 if a counter-clockwise turn of the crank takes the first roller away from the cam centre (the
        follower's rise), else -1."""
        arm = np.array([0.0, self.first.prime_radius]) - self.pivot
        return 1.0 if float(perp(arm[None, :])[0] @ (arm + self.pivot)) >= 0 else -1.0

    @property
    def rest(self) -> np.ndarray:
        """The second arm at rest, pivot to roller centre (mm): the first turned by -k arm_angle and scaled."""
        first = np.array([0.0, self.first.prime_radius]) - self.pivot
        turn = -self.away * self.arm_angle
        return self.arm_length / self.first.arm_length * rotate(first[None, :], np.array([turn]))[0]

    def centre(self, swing: np.ndarray) -> np.ndarray:
        """The second roller's centre (n, 2; mm, fixed frame) at arm swings ``swing`` (degrees)."""
        return self.pivot + rotate(np.tile(self.rest, (len(swing), 1)), self.away * np.radians(swing))

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        """Pitch geometry of the second cam for arm swing ``motion`` = psi, psi', psi'' (degrees per rad^k)."""
        arm = self.centre(motion[0]) - self.pivot
        rate, accel = np.radians(motion[1]), np.radians(motion[2])
        across = self.away * perp(arm)                   # d(arm)/d(psi): the way the roller moves on a rise
        velocity = rate[:, None] * across
        acceleration = accel[:, None] * across - (rate**2)[:, None] * arm
        return from_centre_path(theta, self.pivot + arm, velocity, acceleration, -across / self.arm_length,
                                self.sense)


def arm_turn(first: OscillatingRoller, swing_max: float, arm_length: float, prime: float) -> float:
    """The arm angle (rad) putting the second roller's centre ``prime`` mm from the cam centre at its nearest (at
    the largest swing, ``swing_max`` rad): psi0 + swing_max + alpha, alpha the angle at the pivot between the cam
    centre and the second roller there, from prime^2 = C^2 + L2^2 - 2 C L2 cos(alpha)."""
    c = first.pivot_distance
    alpha = math.acos((c * c + arm_length * arm_length - prime * prime) / (2 * c * arm_length))
    return first.rest_angle + swing_max + alpha


def arm_prime(first: OscillatingRoller, swing_max: float, arm_length: float, turn: float) -> float:
    """The second roller's nearest distance (mm) from the cam centre with the arm at ``turn`` rad from the first
    (the second cam's prime radius, while the second arm stays on its side of the line from the pivot to the cam
    centre); its inverse is :func:`arm_turn`."""
    c, alpha = first.pivot_distance, turn - first.rest_angle - swing_max
    return math.sqrt(c * c + arm_length * arm_length - 2 * c * arm_length * math.cos(alpha))
