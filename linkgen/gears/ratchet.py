"""A ratchet wheel and its pawl: the wheel's saw teeth, where the pawl's pivot sits, whether the pawl holds, and how
far a driving lever indexes the wheel.

Frame: the wheel's centre at the origin; tooth 0's tip on +Y at (0, R), R the tip radius; the teeth follow
counter-clockwise every 2 pi / z. The wheel is driven counter-clockwise and held against turning clockwise: each
tooth's **face** (the steep side the pawl bears on) is its clockwise side, its **back** the slope from its tip down to
the next tooth's face. The face leans by the **face angle** theta (rad) from the radial line through the tip, positive
hooked (the tip overhanging the face's root clockwise, so the pawl is trapped under it). The face's normal out of
the tooth at its tip is, for tooth 0, (cos theta, -sin theta).

**Holding**: the load turns the wheel clockwise and the face pushes the pawl's nose along its normal, turned by up
to the friction angle atan mu either way. The pawl's pivot P sits ``length`` from the contact C at ``angle`` gamma
above the tangent at C (positive away from the wheel). The contact force pulls the pawl into the tooth for every
force in the friction cone when the **engagement angle** psi, from the line C -> P to the face's normal (positive
towards the wheel), is at least atan mu; for tooth 0, psi = theta + gamma.

**Index**: a lever swinging ``swing`` (rad) about the wheel's axis with a pawl of the same figure drives the wheel
through whole teeth: floor(swing / pitch) of them per stroke (its pawl drops into the next tooth only after a pitch
of travel).

Lengths mm, angles rad.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camgen.core.errors import DesignError


@dataclass(frozen=True)
class RatchetWheel:
    """A wheel of ``teeth`` saw teeth on a tip circle of ``tip_radius`` (mm), ``depth`` mm deep, their faces leaning
    ``face_angle`` (rad, hooked positive) from the radial line."""

    teeth: int
    tip_radius: float
    depth: float
    face_angle: float

    @property
    def pitch(self) -> float:
        """2 pi / z (rad)."""
        return 2 * math.pi / self.teeth

    @property
    def root_radius(self) -> float:
        """R - depth (mm)."""
        return self.tip_radius - self.depth

    @property
    def face_length(self) -> float:
        """The face's length from the tip to the root circle (mm): R cos theta - sqrt(rf^2 - R^2 sin^2 theta)."""
        r, rf, t = self.tip_radius, self.root_radius, self.face_angle
        return r * math.cos(t) - math.sqrt(rf * rf - (r * math.sin(t)) ** 2)

    @property
    def root_shift(self) -> float:
        """How far (rad) counter-clockwise of its tip the face meets the root circle (negative for a face leaning
        back)."""
        root = self.face_root(0)
        return math.atan2(-root[0], root[1])

    def face_root(self, k: int) -> np.ndarray:
        """Where tooth ``k``'s face meets the root circle (mm)."""
        t, s = self.face_angle, self.face_length
        x, y = -s * math.sin(t), self.tip_radius - s * math.cos(t)
        a = k * self.pitch
        return np.array([x * math.cos(a) - y * math.sin(a), x * math.sin(a) + y * math.cos(a)])

    def tip(self, k: int) -> np.ndarray:
        """Tooth ``k``'s tip (mm)."""
        a = math.pi / 2 + k * self.pitch
        return self.tip_radius * np.array([math.cos(a), math.sin(a)])

    def check(self) -> None:
        """Refuse a wheel whose teeth cannot be drawn: a root circle at the centre, a face that misses the root
        circle, or a face leaning so far that its root passes the next tooth's back."""
        if not self.root_radius > 0:
            raise DesignError(f"the teeth ({self.depth:g} mm deep) reach the wheel's centre")
        if not self.root_radius > self.tip_radius * abs(math.sin(self.face_angle)):
            raise DesignError(f"a face leaning {math.degrees(self.face_angle):g} degrees misses the root circle")
        if not -self.pitch / 2 < self.root_shift < self.pitch / 2:
            raise DesignError(f"a face leaning {math.degrees(self.face_angle):g} degrees reaches past half a pitch")

    def outline(self) -> tuple[np.ndarray, np.ndarray]:
        """The wheel's outline, counter-clockwise: for each tooth its face's root, its tip, then the back down to the
        next face's root; vertices (2 z, 2) mm and bulges (2 z,), all lines."""
        self.check()
        points = [p for k in range(self.teeth) for p in (self.face_root(k), self.tip(k))]
        return np.array(points), np.zeros(2 * self.teeth)


@dataclass(frozen=True)
class Pawl:
    """A pawl bearing on tooth 0's face at its tip, its pivot ``length`` mm away at ``angle`` (rad) above the
    tangent there (see the module's notes)."""

    wheel: RatchetWheel
    length: float
    angle: float

    @property
    def contact(self) -> np.ndarray:
        """C = (0, R) (mm)."""
        return np.array([0.0, self.wheel.tip_radius])

    @property
    def pivot(self) -> np.ndarray:
        """P = C + length (cos gamma, sin gamma) (mm)."""
        return self.contact + self.length * np.array([math.cos(self.angle), math.sin(self.angle)])

    @property
    def normal(self) -> np.ndarray:
        """The face's unit normal out of tooth 0 at C: (cos theta, -sin theta)."""
        return np.array([math.cos(self.wheel.face_angle), -math.sin(self.wheel.face_angle)])

    @property
    def engagement_angle(self) -> float:
        """psi (rad): from the line C -> P to the face's normal, positive clockwise (towards the wheel here)."""
        e = (self.pivot - self.contact) / self.length
        n = self.normal
        return math.atan2(e[0] * n[1] - e[1] * n[0], float(e @ n)) * -1.0

    def holds(self, friction: float) -> bool:
        """Whether the contact force pulls the pawl in for every force in the cone of ``friction`` (mu)."""
        return self.engagement_angle >= math.atan(friction)


def teeth_per_stroke(teeth: int, swing: float) -> int:
    """The whole teeth (of ``teeth`` on the wheel) a lever swinging ``swing`` rad indexes: floor(swing z / 2 pi),
    with 1e-9 of a tooth's grace for a swing given as an exact multiple."""
    return math.floor(swing * teeth / (2 * math.pi) + 1e-9)
