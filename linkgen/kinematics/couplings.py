"""The course's couplings and double sliders in closed form: Oldham's coupling, the elliptic trammel and Rapson's
slide; vectorised over arrays of inputs.

Frames (mm, angles in radians counter-clockwise from +X):

* **Oldham**: hub 1 (the input) turns about O1 = (0, 0), hub 2 about O2 = (offset, 0); hub 1's slot runs through O1
  at the input angle theta, hub 2's through O2 square to it (theta + pi/2); the middle disc holds both tongues, so
  its centre C lies where the slots cross: the foot of O2 on hub 1's slot.
* **Trammel**: block A slides on the X axis, block B on the Y axis, the rod A-B of length ``rod``; the input is the
  rod's direction from A to B measured as phi in A = (rod cos phi, 0), B = (0, rod sin phi) (so that the rod's
  midpoint M = (rod / 2)(cos phi, sin phi) turns about the origin like a crank of half the rod); the tracer P lies
  on the rod's line ``point`` mm from A towards B.
* **Rapson**: the tiller turns about the rudder stock at the origin; the crosshead slides on the line x =
  ``distance`` (square to the ship's centre line, +X) at height y (the input, mm) and carries the swivel block the
  tiller slides through, so the tiller's angle is atan(y / distance).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike


def _array(x: ArrayLike) -> np.ndarray:
    return np.atleast_1d(np.asarray(x, dtype=float))


@dataclass(frozen=True)
class OldhamMotion:
    """Oldham's coupling at inputs ``theta`` (rad): hub 2's and the disc's angles (rad), the disc's centre C (n, 2)
    mm, its velocity (mm/s) and acceleration (mm/s^2), and each tongue's slide along its slot from its hub's
    centre (mm; along hub 1's slot direction, and along hub 2's) with their rates (mm/s)."""

    theta: np.ndarray
    output: np.ndarray
    disc: np.ndarray
    centre: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    slide: np.ndarray
    slide_rate: np.ndarray


@dataclass(frozen=True)
class Oldham:
    """Oldham's coupling of two parallel shafts ``offset`` mm apart (see the module's frame).

    The disc keeps both tongues square to each other, so hub 2 turns exactly with hub 1 (its slot at theta +
    pi/2, its angle theta); C = O1 + (offset cos theta)(cos theta, sin theta) runs on the circle on O1-O2 as
    diameter (Thales), centre (offset / 2, 0), at twice the input's speed.
    """

    offset: float

    @property
    def thales_centre(self) -> tuple[float, float]:
        """The centre of the disc centre's circle (mm): the midpoint of O1-O2."""
        return self.offset / 2, 0.0

    @property
    def thales_radius(self) -> float:
        """The radius of the disc centre's circle (mm): half the offset."""
        return self.offset / 2

    @property
    def stroke(self) -> float:
        """Each tongue's travel along its slot (mm): twice the offset."""
        return 2 * self.offset

    def motion(self, theta: ArrayLike, omega: float) -> OldhamMotion:
        """The coupling at input angles ``theta`` (rad) turning at ``omega`` rad/s (constant)."""
        t = _array(theta)
        d = self.offset
        c, s = np.cos(t), np.sin(t)
        centre = d * np.column_stack([c * c, c * s])
        two = 2 * t
        velocity = d * omega * np.column_stack([-np.sin(two), np.cos(two)])
        acceleration = -2 * d * omega**2 * np.column_stack([np.cos(two), np.sin(two)])
        slide = d * np.column_stack([c, s])
        slide_rate = d * omega * np.column_stack([-s, c])
        return OldhamMotion(t, t.copy(), t.copy(), centre, velocity, acceleration, slide, slide_rate)


@dataclass(frozen=True)
class TrammelMotion:
    """The trammel at inputs ``phi`` (rad): the blocks' positions along their axes (mm), their velocities (mm/s),
    the tracer's position (n, 2) mm, velocity (mm/s) and acceleration (mm/s^2), and the rod's angle (rad, its
    direction from A to B)."""

    phi: np.ndarray
    a: np.ndarray
    b: np.ndarray
    a_rate: np.ndarray
    b_rate: np.ndarray
    point: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    rod_angle: np.ndarray


@dataclass(frozen=True)
class Trammel:
    """The double slider (elliptic trammel): rod ``rod`` mm between block A (on X) and block B (on Y), tracer
    ``point`` mm from A along A-B (negative: behind A; beyond ``rod``: past B). See the module's frame.

    P = ((rod - point) cos phi, point sin phi): an ellipse centred on the guides' crossing with semi-axes
    |rod - point| along X and |point| along Y.
    """

    rod: float
    point: float

    @property
    def semi_axes(self) -> tuple[float, float]:
        """The tracer's ellipse's semi-axes along X and along Y (mm)."""
        return abs(self.rod - self.point), abs(self.point)

    def motion(self, phi: ArrayLike, omega: float) -> TrammelMotion:
        """The trammel at inputs ``phi`` (rad) turning at ``omega`` rad/s (constant)."""
        f = _array(phi)
        c, s = np.cos(f), np.sin(f)
        ax, by = self.rod - self.point, self.point
        point = np.column_stack([ax * c, by * s])
        velocity = omega * np.column_stack([-ax * s, by * c])
        acceleration = -omega**2 * point
        rod_angle = np.arctan2(s, -c)
        return TrammelMotion(f, self.rod * c, self.rod * s, -self.rod * omega * s, self.rod * omega * c, point,
                             velocity, acceleration, rod_angle)


@dataclass(frozen=True)
class RapsonMotion:
    """Rapson's slide at crosshead heights ``y`` (mm): the tiller's angle (rad), its angular velocity (rad/s) and
    acceleration (rad/s^2) for a crosshead moving at a constant speed, the block's slide along the tiller from the
    stock (mm), and the tiller's torque per unit crosshead force (N mm per N)."""

    y: np.ndarray
    angle: np.ndarray
    rate: np.ndarray
    acceleration: np.ndarray
    radius: np.ndarray
    leverage: np.ndarray


@dataclass(frozen=True)
class Rapson:
    """Rapson's slide: the crosshead's guide ``distance`` mm from the rudder stock (see the module's frame).

    tan(angle) = y / distance; by virtual work the tiller's torque per unit crosshead force is dy / d(angle) =
    distance / cos^2(angle), which grows with the helm: the slide's point.
    """

    distance: float

    def travel(self, max_angle: float) -> float:
        """The crosshead's height (mm) at the tiller's angle ``max_angle`` (rad)."""
        return self.distance * math.tan(max_angle)

    def motion(self, y: ArrayLike, speed: float) -> RapsonMotion:
        """The slide at crosshead heights ``y`` (mm), the crosshead moving at ``speed`` mm/s (constant)."""
        h = _array(y)
        d = self.distance
        r2 = d * d + h * h
        rate = d * speed / r2
        acceleration = -2 * d * h * speed**2 / r2**2
        return RapsonMotion(h, np.arctan2(h, d), rate, acceleration, np.sqrt(r2), r2 / d)
