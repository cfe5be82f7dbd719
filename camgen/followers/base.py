"""What every follower gives the cam: its pitch curve and contact geometry in the cam's frame.

Frames and signs (all followers):

* The cam centre is the origin; at theta = 0 the follower lies on +Y.
* ``sense`` is +1 for a cam turning counter-clockwise (viewed from +Z), -1 for clockwise.
  In the cam's own frame the follower then travels the other way round.
* Curvature ``kappa`` is signed: positive where the curve is convex (bulging away
  from the cam centre, like the base circle), negative where concave. The radius of
  curvature is 1 / kappa; an inflection has kappa = 0 (infinite radius).
* ``normal`` is the outward unit normal (away from the cam material).
* The pressure angle is the angle between the contact normal and the direction in
  which the follower's contact point (a roller's centre) moves as the follower
  rises; its sign is positive while the follower is driven "uphill" on a
  counter-clockwise cam.

Two shared constructions serve every follower: :func:`from_centre_path` for
rollers and knife edges (the pitch curve is the path of the roller's centre) and
:func:`from_support` for flat faces (the cam profile is the envelope of the face's
line, given by its distance p from the cam centre and its normal angle alpha).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from camgen.core.errors import SpecError


@dataclass(frozen=True)
class PitchGeometry:
    """Pitch curve samples in the cam frame (mm, radians); arrays of shape (n,) or (n, 2).

    For flat-faced followers the "pitch curve" is the cam profile itself (the contact
    radius is 0) and ``rho`` carries its radius of curvature, finite even where the
    profile would fold into a cusp (rho <= 0).
    """

    theta: np.ndarray          # cam angle, rad
    point: np.ndarray          # (n, 2) pitch point (roller centre, or contact point of a flat face), mm
    d1: np.ndarray             # (n, 2) dP/dtheta, mm/rad
    d2: np.ndarray             # (n, 2) d2P/dtheta2, mm/rad^2
    normal: np.ndarray         # (n, 2) outward unit normal
    kappa: np.ndarray          # (n,) signed curvature of the pitch curve, 1/mm, convex > 0
    pressure_angle: np.ndarray  # (n,) rad, signed (see the module docstring)
    rho: np.ndarray | None = None  # (n,) radius of curvature of a flat face's profile, mm

    @property
    def face_rho(self) -> np.ndarray:
        """:attr:`rho` (mm) of a flat face's profile, which always carries it; a roller's or a knife edge's pitch
        curve has none (ValueError)."""
        if self.rho is None:
            raise ValueError("a roller's or a knife edge's pitch curve has no face radius of curvature")
        return self.rho

    def part(self, start: int, stop: int) -> PitchGeometry:
        """The samples ``start`` to ``stop`` (a slice, views of the same arrays)."""
        rho = None if self.rho is None else self.rho[start:stop]
        return PitchGeometry(self.theta[start:stop], self.point[start:stop], self.d1[start:stop], self.d2[start:stop],
                             self.normal[start:stop], self.kappa[start:stop], self.pressure_angle[start:stop], rho)


def rotate(vectors: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotate (n, 2) ``vectors`` counter-clockwise by ``angle`` (n,) radians."""
    return _turned(np.cos(angle), np.sin(angle), vectors)


def _turned(c: np.ndarray, s: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """(n, 2) ``vectors`` turned by the angles whose cosines and sines are ``c``, ``s`` (n,)."""
    x, y = vectors[:, 0], vectors[:, 1]
    first = c * x - s * y
    out = np.empty((*first.shape, 2))
    out[:, 0] = first
    out[:, 1] = s * x + c * y
    return out


_PERP = np.array([-1.0, 1.0])


def perp(v: np.ndarray) -> np.ndarray:
    """(n, 2) vectors turned a quarter counter-clockwise: J v."""
    return v[:, ::-1] * _PERP


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def signed_pressure_angle(direction: np.ndarray, normal: np.ndarray, sense: int) -> np.ndarray:
    """Angle (rad) from the follower's direction of travel to the contact normal, both in the fixed frame."""
    return sense * np.arctan2(_cross(direction, normal), (direction * normal).sum(axis=1))


def from_centre_path(theta: np.ndarray, q: np.ndarray, q1: np.ndarray, q2: np.ndarray, direction: np.ndarray,
                     sense: int) -> PitchGeometry:
    """Pitch geometry from the roller centre's path in the fixed frame.

    ``q``, ``q1``, ``q2`` (n, 2): the centre and its first and second derivatives with
    respect to cam angle; ``direction`` (n, 2): unit direction in which the centre
    moves as the follower rises. In the cam frame P = R(-sense theta) q, so
    P' = R(...)(q' - sense J q) and P'' = R(...)(q'' - 2 sense J q' - q).
    """
    return centre_path(theta, (q[:, 0], q[:, 1]), (q1[:, 0], q1[:, 1]), (q2[:, 0], q2[:, 1]),
                       (direction[:, 0], direction[:, 1]), sense)


Pair = tuple[Any, Any]


def centre_path(theta: np.ndarray, q: Pair, q1: Pair, q2: Pair, direction: Pair, sense: int) -> PitchGeometry:
    """:func:`from_centre_path` from the x and y components of ``q``, ``q1``, ``q2`` and ``direction``, each an
    array (n,) or a number for every angle (numpy broadcasts it: a translating follower's fixed x, its zero
    x-velocity). The centre, its two derivatives and the normal are worked in x and y rows of one array and turned
    into the cam's frame together."""
    (qx, qy), (q1x, q1y), (q2x, q2y), (dx, dy) = q, q1, q2, direction
    fixed = np.empty((2, 4, theta.shape[0]))           # x and y rows: q, t, a and the normal, in the fixed frame
    x, y = fixed
    x[0], y[0] = qx, qy
    x[1], y[1] = q1x + sense * qy, q1y - sense * qx                          # t = q' - sense J q
    x[2], y[2] = q2x + 2 * sense * q1y - qx, q2y - 2 * sense * q1x - qy      # a = q'' - 2 sense J q' - q
    tx, ty, ax, ay = x[1], y[1], x[2], y[2]
    speed = np.sqrt(tx * tx + ty * ty)
    kappa = -sense * (tx * ay - ty * ax) / speed**3
    x[3], y[3] = -sense * ty / speed, sense * tx / speed                      # sense J t / |t|
    nx, ny = x[3], y[3]
    pressure = sense * np.arctan2(dx * ny - dy * nx, dx * nx + dy * ny)
    turn = -sense * theta
    c, s = np.cos(turn), np.sin(turn)
    turned = np.empty((4, theta.shape[0], 2))
    turned[:, :, 0] = c * x - s * y
    turned[:, :, 1] = s * x + c * y
    return PitchGeometry(theta, turned[0], turned[1], turned[2], turned[3], kappa, pressure)


def from_support(theta: np.ndarray, p: np.ndarray, alpha: np.ndarray, derivs: np.ndarray, sense: int,
                 travel: Callable[[np.ndarray], np.ndarray]) -> PitchGeometry:
    """Profile of a flat face: the envelope of the lines x . n(alpha) = p in the cam frame.

    ``derivs`` (6, n) holds p', p'', p''', alpha', alpha'', alpha''' with respect to
    cam angle. The contact point is C = p n + p_a J n with p_a = dp/dalpha, the radius
    of curvature rho = p + d2p/dalpha2, and C' = rho alpha' J n. ``travel`` maps the
    contact points in the fixed frame (n, 2) to the unit direction in which the
    face's material point there moves as the follower rises (for the pressure angle).
    """
    p1, p2, p3, a1, a2, a3 = derivs
    n = np.column_stack([np.cos(alpha), np.sin(alpha)])
    t = perp(n)
    pa = p1 / a1
    paa = (p2 * a1 - p1 * a2) / a1**3
    paa1 = ((p3 * a1 - p1 * a3) * a1 - 3 * a2 * (p2 * a1 - p1 * a2)) / a1**4
    rho = p + paa
    rho1 = p1 + paa1
    point = p[:, None] * n + pa[:, None] * t
    d1 = (rho * a1)[:, None] * t
    d2 = (rho1 * a1 + rho * a2)[:, None] * t - (rho * a1**2)[:, None] * n
    with np.errstate(divide="ignore", over="ignore"):        # a vanishing radius is an infinite curvature
        kappa = np.where(rho != 0, 1.0 / rho, np.inf)
    back = sense * theta                     # the fixed frame is the cam frame turned back by the cam's rotation
    pressure = signed_pressure_angle(travel(rotate(point, back)), rotate(n, back), sense)
    return PitchGeometry(theta=theta, point=point, d1=d1, d2=d2, normal=n, kappa=kappa,
                         pressure_angle=pressure, rho=rho)


def positive(value: float, field: str) -> None:
    """Refuse a length that is not finite and > 0 mm, naming ``field``."""
    if not (value > 0 and math.isfinite(value)):
        raise SpecError(f"must be a finite length > 0 mm (got {value})", field)


@dataclass(frozen=True)
class FollowerType:
    """How a follower type enters a design: its unit of lift, and the few functions that read its ``[follower]``
    table (:mod:`camgen.tables.followers`, which holds the keys each type takes). One per follower module,
    registered in :data:`camgen.followers.FOLLOWERS`.

    ``make(table, base radius mm, roller radius mm, sense)`` builds the follower;
    ``base_radius_range(table, roller radius mm, top)`` is the (lowest, highest) base radius that assembles and
    follows a program rising to ``top`` (mm, or degrees of swing), exclusive;
    ``roller_floor(table, base radius mm)`` the least roller radius that assembles; ``path_length(table, lift)``
    the roller's travel (mm) for a lift (the drafted modified-uniform law needs it), None where it has no meaning;
    ``fits(table, base radius mm, top)`` raises :class:`SpecError` naming the field where the follower cannot follow
    a program whose largest displacement is ``top`` (mm, or degrees of swing, overshoots included) on that base
    circle, None where it follows any program it assembles for (checked as a cam is built).
    """

    name: str
    make: Callable[[Any, float, float, int], Any]
    oscillating: bool = False
    base_radius_range: Callable[[Any, float, float], tuple[float, float]] = field(
        default=lambda t, rr, top: (0.0, math.inf))
    roller_floor: Callable[[Any, float], float] = field(default=lambda t, rb: 0.0)
    path_length: Callable[[Any, float], float] | None = field(default=lambda t, lift: lift)
    fits: Callable[[Any, float, float], None] | None = None

    @property
    def lift_unit(self) -> str:
        """``"deg"`` (an arm's swing) or ``"mm"``."""
        return "deg" if self.oscillating else "mm"


class Swing:
    """What every roller on a swinging arm declares: a roller, not a flat face; its lift is the arm's swing in
    degrees."""

    flat: ClassVar[bool] = False
    lift_unit: ClassVar[str] = "deg"


class FlatFace:
    """What every flat-faced follower shares: its profile is the envelope of the face's lines, touched at a point
    (no roller: contact radius 0), and the report measures the contact along the face from ``face_origin``."""

    flat: ClassVar[bool] = True
    contact_radius: ClassVar[float] = 0.0
    face_origin: ClassVar[str]
