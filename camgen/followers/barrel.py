"""The roller on a barrel cam: its pose over the cycle, its contact with the groove's walls on any cylinder, and
the groove developed on a cylinder as a plane pitch curve. numpy only.

Frames. The cam's axis is +Z. At theta = 0 the roller stands on +X in the fixed frame; its axis is square to
the cam's axis. Everything here is worked in "theta-space": the cam's frame, reflected for a counter-clockwise
cam (``sense`` +1) so that the roller at cam angle theta stands at the polar angle +theta (see
:mod:`camgen.kinds.barrel.kinematics`); turned by theta, the roller's axis runs along x at the height zc and the
tangential offset e from the cam's axis: the line (t, e, zc).

Two followers move the roller. A translating one (``arm`` None) slides it along the cam's axis, zc = z0 + s,
e = 0: its axis is radial. An oscillating one swings it on an arm of length L about a pivot whose axis is
parallel to the roller's, square to the cam's axis, a distance C (``pivot_distance``) from it, at the height
z0: with the arm's angle psi measured from square to the cam's axis, the roller's centre is at the height
zc = z0 + L sin(psi) and the fixed frame's y = C - L cos(psi) (e = -sense y), so its axis passes y from the cam's
axis: the arm's chordal error. The program gives the swing s (degrees); psi = s - mid puts the arm square to
the cam's axis at mid-swing (``mid`` half the swing), which halves the axial stroke's departure from the arc.

The cutter. The groove is swept by a surface of revolution about the roller's axis whose radius grows along
it, R(a) = r0 + taper a (a measured along the axis from its point nearest the cam's axis): a cylinder (taper
0, r0 = Rr + c/2) or a cone (a conical roller with its apex there, taper = Rr / Rm, grown by c/2 normal to its
surface). Its contact with the wall on the cylinder of radius r at angle theta: with w = r sin(phi - theta) - e
and v = z - zc, rho = sqrt(w^2 + v^2) = R(a) and the envelope condition

    w (a + e') + v zc' + taper rho (w + e) = 0,   a = sqrt(r^2 - (w + e)^2),

solved by Newton's method for (beta, rho), w = rho sin(beta), v = side rho cos(beta) (side -1 the lower wall,
+1 the upper). The pressure angle is the angle between the cutter's normal there and the roller's path (0, e',
zc'), in 3D.

:class:`BarrelGeometry` holds what a barrel's tables fix (the pitch cylinder, the roller and its cutter, the
arm, the rest height, a rib's span), from their values, for the kind's checks and its design.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from camgen.core.errors import DesignError
from camgen.followers.base import PitchGeometry, Swing, perp
from camgen.followers.plate import PlateRoller

#: Newton steps of the contact, and the residual (relative to the radius) that counts as solved
_STEPS, _SOLVED = 40, 1e-12


@dataclass(frozen=True)
class Arm:
    """An oscillating arm on a barrel (see the module docstring): ``length`` L and ``pivot_distance`` C (mm), the
    swing ``mid`` (degrees of s) where it is square to the cam's axis, the pivot's ``height`` z0 (mm) and the
    cam's ``sense`` of rotation."""

    length: float
    pivot_distance: float
    mid: float
    height: float
    sense: int = 1

    def pose(self, motion: np.ndarray) -> np.ndarray:
        """zc, zc', zc'', e, e', e'' (mm per rad^k) from s, s', s'' (degrees per rad^k of cam angle)."""
        psi, p1, p2 = np.radians(motion[0] - self.mid), np.radians(motion[1]), np.radians(motion[2])
        c, s, arm = np.cos(psi), np.sin(psi), self.length
        y = (self.pivot_distance - arm * c, arm * s * p1, arm * (s * p2 + c * p1**2))
        return np.array([self.height + arm * s, arm * c * p1, arm * (c * p2 - s * p1**2),
                         *(-self.sense * k for k in y)])

    def chordal_error(self, swing: float) -> float:
        """The largest distance (mm) of the roller's axis from the cam's axis over a ``swing`` (degrees, s from 0
        to swing, psi from -swing/2 to +swing/2 when ``mid`` is half of it): |C - L cos(psi)| largest at psi = 0
        or at an end."""
        psi = np.radians(np.array([0.0, swing, self.mid]) - self.mid)
        return float(np.abs(self.pivot_distance - self.length * np.cos(psi)).max())


def translating_pose(motion: np.ndarray, z0: float) -> np.ndarray:
    """zc, zc', zc'', e, e', e'' of a roller sliding along the cam's axis, its centre at z0 + s: e = 0."""
    zero = np.zeros_like(motion[0])
    return np.array([z0 + motion[0], motion[1], motion[2], zero, zero, zero])


def contact(radius: float | np.ndarray, pose: np.ndarray, r0: float, taper: float, side: int) -> tuple:
    """The cutter's contact with the wall ``side`` on the cylinder of ``radius`` (broadcast with the pose's rows):
    (w, v, rho, a) in mm, see the module docstring. Refused (DesignError) where Newton's method does not settle,
    which a spec's checks leave for degenerate groove shapes only."""
    _, z1, _, e, e1, _ = pose
    radius = np.broadcast_to(radius, z1.shape).astype(float)
    a0 = np.sqrt(np.maximum(radius**2 - e**2, 0.0))
    beta = np.arctan2(-side * z1, a0 + e1)
    rho = r0 + taper * a0
    for _ in range(_STEPS):
        s, c = np.sin(beta), np.cos(beta)
        q = rho * s + e
        a = np.sqrt(np.maximum(radius**2 - q**2, 1e-300))
        a_beta, a_rho = -q * rho * c / a, -q * s / a
        f1 = rho - r0 - taper * a
        f2 = s * (a + e1 + taper * rho) + side * c * z1 + taper * e
        j11, j12 = -taper * a_beta, 1.0 - taper * a_rho
        j21, j22 = c * (a + e1 + taper * rho) + s * a_beta - side * s * z1, s * (a_rho + taper)
        det = j11 * j22 - j12 * j21
        d_beta = (f1 * j22 - f2 * j12) / det
        d_rho = (j11 * f2 - j21 * f1) / det
        beta = np.clip(beta - d_beta, -0.5 * math.pi + 1e-9, 0.5 * math.pi - 1e-9)
        rho = rho - d_rho
        if float(np.abs(d_beta).max(initial=0.0)) < 1e-15 and float(np.abs(d_rho).max(initial=0.0)) < 1e-13:
            break
    s, c = np.sin(beta), np.cos(beta)
    q = rho * s + e
    a = np.sqrt(np.maximum(radius**2 - q**2, 0.0))
    residual = np.abs(s * (a + e1 + taper * rho) + side * c * z1 + taper * e) + np.abs(rho - r0 - taper * a)
    if not np.all(residual <= _SOLVED * np.maximum(radius, 1.0)) or not np.all(np.abs(q) < radius):
        raise DesignError("the roller's contact with the groove's wall was not found (the groove is too steep or "
                          "the roller too large for the cylinder): use a smaller roller or a larger cam.pitch_radius")
    return rho * s, side * rho * c, rho, a


def pressure_angle(pose: np.ndarray, w: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The angle (rad, 0 to pi/2) between the contact normal (0, w, v) square to the roller's axis and the roller's
    path (0, e', zc'), in 3D: 0 where the roller stands still. (A cone's normal also leans along its axis by its
    half-angle: a thrust its bearing takes, not a pressure angle.)"""
    z1, e1 = pose[1], pose[4]
    return np.arctan2(np.abs(w * z1 - v * e1), np.abs(w * e1 + v * z1))


def rolling_slip(pose: np.ndarray, radius: float, pitch: float, r0: float, taper: float, side: int) -> np.ndarray:
    """The roller's slip along the way it rolls at its contact with the wall ``side`` on the cylinder of ``radius``,
    as a fraction of the cam's surface speed there, the roller spinning so that it rolls without slip on the
    cylinder of ``pitch`` (the roller itself: no clearance, R(a) = r0 + taper a).

    In the roller's frame turning with it (its axis along x, theta-space) the roller's point (a, w + e, zc + v) moves
    over the cam at (-(w + e), a, 0) + (0, e', zc') + Omega (0, -v, w); along the way it rolls, (0, -v, w) / rho,
    that is (zc' w - (a + e') v) / rho + Omega rho, the spin Omega making it 0 on the ``pitch`` cylinder; a is about
    the cam's surface speed. A cylinder slips by |a - a_pitch| / a in a dwell; a cone with its apex where the axis
    passes the cam's axis rolls there without slip, and nearly so while the roller moves."""
    def along(r: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        w, v, rho, a = contact(np.full_like(pose[1], r), pose, r0, taper, side)
        return (pose[1] * w - (a + pose[4]) * v) / rho, rho, a

    drift, rho, _ = along(pitch)
    spin = -drift / rho
    drift, rho, a = along(radius)
    return (drift + spin * rho) / a


@dataclass(frozen=True)
class DevelopedRoller(Swing):
    """The groove's pitch curve developed on the cylinder of ``radius``: where the roller's axis pierces it,
    (radius (theta + asin(e / radius)), zc), a plane curve the walls there are offset from by about the cutter's
    radius r0 + taper radius (the checks of undercut take it so); its pressure angle is the 3D one at the contact
    on that cylinder (the larger of the two walls'), signed as the swing's rate. Lifts in degrees of swing."""

    arm: Arm
    radius: float
    r0: float
    taper: float = 0.0

    sense: ClassVar[int] = 1          # the developed curve runs left to right, as a plate cam's

    @property
    def contact_radius(self) -> float:
        """The cutter's radius on this cylinder (mm)."""
        return self.r0 + self.taper * self.radius

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        pose = self.arm.pose(motion)
        zc, z1, z2, e, e1, e2 = pose
        r = self.radius
        root = np.sqrt(r**2 - e**2)
        k1 = e1 / root
        point = np.column_stack([r * (theta + np.arcsin(e / r)), zc])
        d1 = np.column_stack([r * (1 + k1), z1])
        d2 = np.column_stack([r * (e2 / root + e * e1**2 / root**3), z2])
        speed = np.linalg.norm(d1, axis=1)
        kappa = -(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / speed**3
        angles = [pressure_angle(pose, *contact(r, pose, self.r0, self.taper, side)[:2]) for side in (-1, 1)]
        return PitchGeometry(theta=theta, point=point, d1=d1, d2=d2, normal=perp(d1) / speed[:, None], kappa=kappa,
                             pressure_angle=np.sign(motion[1]) * np.maximum(*angles))


@dataclass(frozen=True)
class BarrelGeometry:
    """A barrel cam's geometry from its tables' values (mm, degrees): the pitch cylinder's ``pitch_radius`` Rm, the
    cylinder's ``length``, the groove's ``groove_depth`` and ``running_clearance`` c, the roller's ``roller_radius``
    Rr and whether it is ``conical``, the program's ``levels`` at the segments' ends (from 0; mm, or degrees of an
    arm's swing), an arm's ``arm_length`` and ``pivot_distance`` (None for a translating roller), the cam's
    ``sense`` of rotation (+1 counter-clockwise) and a rib's ``rib_width`` (None for a groove).

    :meth:`of` reads them from a template's ``[cam]`` and ``[follower]`` tables and its motion; the kind's checks
    (:mod:`camgen.kinds.barrel`) and its design (:mod:`camgen.kinds.barrel.design`) read what follows from them."""

    pitch_radius: float
    length: float
    groove_depth: float
    running_clearance: float
    roller_radius: float
    conical: bool
    levels: tuple[float, ...]
    arm_length: float | None = None
    pivot_distance: float | None = None
    sense: int = 1
    rib_width: float | None = None

    @classmethod
    def of(cls, cam: Any, follower: Any, motion: Any) -> BarrelGeometry:
        """The geometry a barrel template's ``[cam]`` and ``[follower]`` tables and its ``motion`` (segments with
        ``type`` and ``lift``) describe (any objects with those attributes)."""
        steps = [seg.lift if seg.type == "rise" else -seg.lift if seg.type == "return" else 0.0 for seg in motion]
        oscillating = follower.oscillating
        return cls(cam.pitch_radius, cam.length, cam.groove_depth, cam.running_clearance, follower.roller_radius,
                   follower.roller_shape == "conical", (0.0, *itertools.accumulate(steps)),
                   follower.arm_length if oscillating else None, follower.pivot_distance if oscillating else None,
                   1 if cam.rotation == "ccw" else -1, cam.rib_width if cam.barrel_form == "rib" else None)

    @property
    def oscillating(self) -> bool:
        """True for a roller on an arm (its lifts in degrees of swing)."""
        return self.arm_length is not None

    @property
    def swing(self) -> float:
        """The follower's whole travel (mm), or an arm's whole swing (degrees)."""
        return max(self.levels) - min(self.levels)

    @property
    def rest_height(self) -> float:
        """z0 (mm): the roller centre's height at s = 0, putting the program's travel mid-length; for an arm, its
        pivot's height, mid-length (the arm square to the cam's axis at mid-swing puts the stroke there)."""
        if self.oscillating:
            return self.length / 2
        return (self.length - max(self.levels) - min(self.levels)) / 2

    @property
    def taper(self) -> float:
        """How fast the roller's radius grows along its axis: Rr / Rm for a conical roller (its apex where its axis
        passes nearest the cam's axis, its radius Rr on the pitch cylinder), 0 for a cylindrical one."""
        return self.roller_radius / self.pitch_radius if self.conical else 0.0

    @property
    def cutter(self) -> float:
        """The radius (mm) the groove is cut with on the pitch cylinder: Rw = Rr + c/2 for a cylindrical roller, for
        a conical one Rr + c/2 / cos(half-angle) (the cone grown by c/2 square to its surface)."""
        if self.conical:
            return self.roller_radius + self.running_clearance / 2 * math.hypot(1.0, self.taper)
        return self.roller_radius + self.running_clearance / 2

    def cutter_at(self, radius: float) -> float:
        """The cutter's radius (mm) where its axis is ``radius`` from the cam's axis (about: the axis passes the
        cam's by the chordal error at most): the same at every radius for a cylindrical roller."""
        return self.cutter + self.taper * (radius - self.pitch_radius)

    @property
    def floor_room(self) -> float:
        """The least radius (mm) of the groove's floor (a rib's core) that holds the cutter: its radius there, r0 +
        taper r, below r: Rw for a cylindrical roller, r0 / (1 - taper) for a cone."""
        rw, t = self.cutter, self.taper
        return rw if not t else (rw - t * self.pitch_radius) / (1 - t)

    @property
    def arm(self) -> Arm | None:
        """The arm of an oscillating roller (None for a translating one)."""
        if self.arm_length is None or self.pivot_distance is None:
            return None
        return Arm(self.arm_length, self.pivot_distance, self.swing / 2, self.rest_height, self.sense)

    @property
    def rib_span(self) -> float | None:
        """A rib's rollers' centres' half-distance g (mm): half the rib's width, the roller's radius and half the
        running clearance (the rib's walls are the rollers' envelopes at Rw = Rr + c/2 from their axes); None for a
        groove."""
        return None if self.rib_width is None else self.rib_width / 2 + self.cutter

    def developed(self, base_height: float, roller_radius: float) -> PlateRoller | DevelopedRoller:
        """The developed pitch curve on the pitch cylinder: a plate cam of travel 2 pi Rm whose roller (of
        ``roller_radius`` mm) runs ``base_height`` mm above its base line (z0 + s with the base height z0 - Rr), or,
        for an arm, where its roller's axis pierces the pitch cylinder (its cutter's radius there)."""
        arm = self.arm
        if arm is not None:
            return DevelopedRoller(arm, self.pitch_radius, self.cutter - self.taper * self.pitch_radius, self.taper)
        return PlateRoller(base_height, roller_radius, 2 * math.pi * self.pitch_radius)
