"""The construction's geometry: where the inverted follower stands at each station, as plain arrays.

The cam is held still and the follower is turned round it by -theta (against the cam's rotation, the inversion
method); at each station the follower's displacement s(theta), read off the displacement diagram, is laid off
from the reference circle (the prime circle for a roller or a knife edge, the base circle for a flat face):

* translating roller or knife edge, offset e: the follower's axis is the tangent to the offset circle (radius
  |e|) at the foot R(-theta) (e, 0); it meets the prime circle d0 = sqrt(Rp^2 - e^2) from the foot, and the
  roller's centre (the knife's point) stands s further out along it;
* translating flat face: the face is square to the station's ray at Rb + s from the centre; it touches the cam
  sense * s' along the face from that foot (the envelope of the faces);
* oscillating roller: the pivot stands on the pivot circle (radius C) at R(-theta) of its own place; the arm of
  length L makes the angle psi0 + psi at the pivot with the line to the cam centre (psi0 from
  Rp^2 = C^2 + L^2 - 2 C L cos psi0: the roller on the prime circle at rest), on the side the rest position is;
* oscillating flat face: the face passes through the pivot at the angle gamma0 + psi to the line to the cam
  centre (sin gamma0 = Rb / C: tangent to the base circle at rest); it touches the cam
  C cos(gamma0 + psi) / (1 - sense * side * psi') from the pivot along the face (the envelope of the faces; side
  the sense, +1 counter-clockwise, in which the face turns as psi grows, psi' in rad per rad).

Frames and signs are :mod:`camgen.followers.base`'s: the cam centre at the origin, the follower on +Y at
theta = 0, ``sense`` +1 for a counter-clockwise cam; R(a) turns counter-clockwise by a, so the inverted follower
at cam angle theta is turned by -sense theta. Lengths in mm, angles in radians (an arm's swing psi: the program's
degrees turned into radians here). Nothing here evaluates the follower's own pitch geometry: the construction's
points are a check on it, equal to :meth:`camgen.cam.Cam.pitch` at the stations.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camgen.cam import Cam
from camgen.core.errors import SpecError
from camgen.followers.oscillating_flat import OscillatingFlat
from camgen.followers.oscillating_roller import OscillatingRoller
from camgen.followers.translating_flat import TranslatingFlat
from camgen.followers.translating_roller import TranslatingRoller

#: the stations' spacing (degrees) unless asked otherwise; the segments' boundaries are stations too
STEP_DEG = 15.0
#: points of the construction's curves (the displacement diagram, the pitch curve through the stations) a turn
CURVE_POINTS = 721
#: two stations closer than this (degrees) are one (a boundary on a multiple of the step)
_SAME_DEG = 1e-9


@dataclass(frozen=True)
class Positions:
    """The inverted follower at cam angles ``theta`` (n,) (rad): its displacement ``s`` (n,) (mm, or an arm's
    swing in degrees) as the displacement diagram gives it, ``circle`` (n, 2) where it meets the reference circle
    at rest (s = 0), and the line it is drawn along: from ``foot`` (n, 2) in the unit ``direction`` (n, 2), the
    follower's point ``point`` = foot + along * direction (n, 2) at ``along`` (n,) mm. The point is the roller's
    centre (the knife's point) or the flat face's contact with the cam; the line is the translating follower's axis
    (from its foot on the offset circle), the flat face (from its foot on the station's ray, or from the pivot) or
    the arm (from the pivot). All in the cam's frame, mm."""

    theta: np.ndarray
    s: np.ndarray
    circle: np.ndarray
    foot: np.ndarray
    direction: np.ndarray
    along: np.ndarray
    point: np.ndarray


@dataclass(frozen=True)
class Construction:
    """A disc cam's construction: the follower (``follower``, a type name, ``lift_unit`` "mm" or "deg"), the
    circles it is drawn on (``radius``: the reference circle divided into stations, the prime circle or for a flat
    face the base circle; ``base_radius``, ``roller_radius``, the translating axis's ``offset``, an arm's
    ``pivot_distance`` and ``arm_length`` or None, mm; ``sense``), the ``stations`` (:class:`Positions`, ascending
    from theta = 0, numbered 0, 1, ... in that order) with ``boundary`` (n,) True where a segment starts, and
    ``curve``, the same construction over the turn (the pitch curve drawn through the stations, and the
    displacement diagram). The diagram's abscissa is the arc along the reference circle: ``radius * theta`` mm,
    its whole length the circle's perimeter."""

    follower: str
    lift_unit: str
    sense: int
    radius: float
    base_radius: float
    roller_radius: float
    offset: float
    pivot_distance: float | None
    arm_length: float | None
    stations: Positions
    boundary: np.ndarray
    curve: Positions

    @property
    def numbers(self) -> np.ndarray:
        """The stations' numbers (n,), 0 at theta = 0."""
        return np.arange(self.stations.theta.size)

    def arc(self, theta: np.ndarray) -> np.ndarray:
        """The displacement diagram's abscissa (mm) at cam angles ``theta`` (rad): the arc along the reference
        circle."""
        return self.radius * np.asarray(theta)


def station_angles(cam: Cam, step_deg: float = STEP_DEG) -> tuple[np.ndarray, np.ndarray]:
    """The stations' cam angles (rad, ascending in [0, 2 pi)): every ``step_deg`` degrees from 0 and every
    segment's start; and whether each is a segment's start. A ValueError for a step that is not in (0, 180]."""
    if not 0 < step_deg <= 180:
        raise SpecError(f"must be > 0 and <= 180 degrees (got {step_deg:g})", "step_deg")
    count = math.ceil(360.0 / step_deg - 1e-9)
    regular = np.arange(count) * step_deg
    starts = np.degrees([seg.start for seg in cam.program.segments]) % 360.0
    every = np.unique(np.concatenate([regular[regular < 360.0 - _SAME_DEG], starts]))
    keep = np.concatenate([[True], np.diff(every) > _SAME_DEG])
    every = every[keep]
    boundary = np.array([bool(np.any(np.abs(starts - a) <= _SAME_DEG)) for a in every])
    return np.radians(every), boundary


def construct(cam: Cam, step_deg: float = STEP_DEG) -> Construction:
    """The construction of ``cam`` (a disc cam with any translating or oscillating follower) at stations every
    ``step_deg`` degrees and at every segment's start (:func:`station_angles`). A :class:`SpecError` for a cam
    whose follower the construction does not draw (a plate's, a barrel's)."""
    f = cam.follower
    theta, boundary = station_angles(cam, step_deg)
    dense = np.linspace(0.0, 2 * math.pi, CURVE_POINTS)
    pivot = arm = None
    offset = 0.0
    if isinstance(f, TranslatingRoller):
        radius, offset = f.prime_radius, f.offset
    elif isinstance(f, TranslatingFlat):
        radius = f.base_radius
    elif isinstance(f, OscillatingRoller):
        radius, pivot, arm = f.prime_radius, f.pivot_distance, f.arm_length
    elif isinstance(f, OscillatingFlat):
        radius, pivot = f.base_radius, f.pivot_distance
    else:
        raise SpecError("the graphical construction is drawn for a disc cam's translating or oscillating follower",
                        "--construction")
    name = {TranslatingRoller: "knife-edge" if f.contact_radius == 0 else "translating-roller",
            TranslatingFlat: "translating-flat", OscillatingRoller: "oscillating-roller",
            OscillatingFlat: "oscillating-flat"}[type(f)]
    return Construction(name, f.lift_unit, f.sense, radius, cam.base_radius, f.contact_radius, offset, pivot, arm,
                        positions(cam, theta), boundary, positions(cam, dense))


def positions(cam: Cam, theta: np.ndarray) -> Positions:
    """The inverted follower of ``cam`` at cam angles ``theta`` (n,) (rad): see the module docstring."""
    theta = np.asarray(theta, dtype=float)
    motion = cam.program.evaluate(theta)                 # the displacement diagram: s, s' (a boundary: the later)
    f = cam.follower
    turn = -f.sense * theta                              # the inversion: the follower turned against the cam
    if isinstance(f, TranslatingRoller):
        fixed = _translating(f.prime_radius, f.offset, motion[0])
    elif isinstance(f, TranslatingFlat):
        fixed = _translating_flat(f.base_radius, f.sense, motion[0], motion[1])
    elif isinstance(f, OscillatingRoller):
        fixed = _oscillating(f.pivot_distance, f.arm_length, f.prime_radius, np.radians(motion[0]))
    else:
        fixed = _oscillating_flat(f.pivot_distance, f.base_radius, f.sense, np.radians(motion[0]),
                                  np.radians(motion[1]))
    circle, foot, direction, along = fixed
    c, s = np.cos(turn), np.sin(turn)
    circle, foot, direction = (_turn(c, s, v) for v in (circle, foot, direction))
    return Positions(theta, motion[0], circle, foot, direction, along, foot + along[:, None] * direction)


def _turn(c: np.ndarray, s: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(n, 2) vectors ``v`` (or one (2,), the same at every angle) turned counter-clockwise by the angles whose
    cosines and sines are ``c``, ``s`` (n,)."""
    v = np.broadcast_to(v, (c.size, 2))
    return np.column_stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]])


Fixed = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]


def _translating(prime: float, offset: float, s: np.ndarray) -> Fixed:
    """A translating roller (a knife edge) at the follower's own place: the axis x = e from its foot (e, 0) on the
    offset circle, up (+Y); the prime circle d0 up it; the centre s further (mm)."""
    d0 = math.sqrt(prime * prime - offset * offset)
    foot = np.array([offset, 0.0])
    return foot + np.array([0.0, d0]), foot, np.array([0.0, 1.0]), d0 + s


def _translating_flat(base: float, sense: int, s: np.ndarray, s1: np.ndarray) -> Fixed:
    """A translating flat face at its own place: the face y = Rb + s, its foot on the axis (0, Rb + s), the face
    along +X; it touches the cam sense s' from the foot (mm; s' in mm/rad)."""
    foot = np.column_stack([np.zeros_like(s), base + s])
    return np.array([0.0, base]), foot, np.array([1.0, 0.0]), sense * s1


def _side(a: np.ndarray, b: np.ndarray) -> float:
    """+1 if ``b`` lies counter-clockwise of ``a`` (within a half turn), -1 otherwise."""
    return 1.0 if a[0] * b[1] - a[1] * b[0] >= 0 else -1.0


def _rotated(v: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """The vector ``v`` (2,) turned counter-clockwise by each of ``angle`` (n,) (rad): (n, 2)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _oscillating(c: float, arm: float, prime: float, psi: np.ndarray) -> Fixed:
    """An oscillating roller at its own place: the pivot at distance C from the centre and L from the rest
    position (0, Rp) on the +X side; the arm at psi0 + psi (rad) from the pivot's line to the cam centre, on the
    rest position's side."""
    py = (c * c + prime * prime - arm * arm) / (2 * prime)
    pivot = np.array([math.sqrt(max(c * c - py * py, 0.0)), py])
    rest = np.array([0.0, prime])
    to_centre = -pivot / c
    psi0 = math.acos((c * c + arm * arm - prime * prime) / (2 * c * arm))
    side = _side(to_centre, rest - pivot)
    direction = _rotated(to_centre, side * (psi0 + psi))
    return rest, np.broadcast_to(pivot, direction.shape), direction, np.full(psi.shape, arm)


def _oscillating_flat(c: float, base: float, sense: int, psi: np.ndarray, psi1: np.ndarray) -> Fixed:
    """An oscillating flat face at its own place: through the pivot (sqrt(C^2 - Rb^2), Rb), tangent to the base
    circle at (0, Rb) at rest, at gamma0 + psi (rad) from the pivot's line to the cam centre; its contact along the
    face from the pivot as the module docstring says (psi' in rad per rad)."""
    pivot = np.array([math.sqrt(c * c - base * base), base])
    rest = np.array([0.0, base])
    to_centre = -pivot / c
    gamma = math.asin(base / c) + psi
    side = _side(to_centre, rest - pivot)
    direction = _rotated(to_centre, side * gamma)
    along = c * np.cos(gamma) / (1.0 - sense * side * psi1)
    return rest, np.broadcast_to(pivot, direction.shape), direction, along
