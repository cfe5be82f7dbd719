"""The oscillating flat-faced follower: a straight edge through a fixed pivot.

Displacement s is the arm's swing in degrees (radians inside). The face passes
through the pivot and touches the base circle at (0, Rb) at rest (the pivot at height
Rb, ``pivot_distance`` from the cam centre, on +X); a rise turns it away from the cam
about the pivot. Its profile is the envelope of the face's lines. The pressure angle
is the angle between the contact normal and the direction in which the face's point at
the contact moves (square to the line from the pivot).

Where the contact lies: at the pivot the face makes the angle gamma0 = asin(Rb / C) with the
line to the cam centre at rest, gamma = gamma0 + psi swung by psi; the foot of the
perpendicular from the cam centre onto the face lies C cos(gamma) from the pivot, and the
envelope puts the contact at

    d = C cos(gamma0 + psi) / (1 + sense psi')       (psi' in rad per rad of cam turn)

from the pivot along the face, towards the cam (the rest contact's side) where d > 0. The line
from the pivot to the contact is the face itself, so the face's point there moves square to the
face, along its normal: the pressure angle is 0 wherever d > 0, with no approximation. Past the
pivot (d < 0) it is 180 degrees: the cam, which can only push along the outward normal, would push
the arm back, and no cam drives it there. At the top of the swing psi' = 0, so the design is
possible only if C cos(gamma0 + psi_top) > 0, that is psi_top < acos(Rb / C), or

    C > Rb / cos(psi_top)                             (:func:`least_pivot_distance`)

and :data:`FOLLOWER` refuses a nearer pivot (a steeper return, 1 + sense psi' <= 0, folds the
profile instead, which the design refuses as a cusp).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from camgen.core.errors import SpecError
from camgen.followers.base import FlatFace, FollowerType, PitchGeometry, from_support, perp, positive, rotate
from camgen.followers.drawing import Face, Pivoted, Stroke


@dataclass(frozen=True)
class OscillatingFlat(FlatFace, Pivoted):
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

    def arm_end(self, contact: np.ndarray) -> np.ndarray:
        """The face drawn at theta = 0 runs a fifth past the contact."""
        return self.pivot + 1.2 * (contact - self.pivot)

    def sketch(self, theta: np.ndarray, geometry: PitchGeometry, reach: float, face: Face,
               roller: float) -> tuple[Stroke, ...]:
        """Its face from the pivot to the face's far end (``face[1]`` mm along it; without one, to the contact
        farthest from the pivot)."""
        pivot = np.asarray(self.pivot, dtype=float)
        along = self.fixed(theta, geometry) - pivot
        unit = along / np.linalg.norm(along, axis=1)[:, None]
        far = face[1] if face is not None else float(np.linalg.norm(along, axis=1).max())
        return (Stroke("face", np.stack([np.broadcast_to(pivot, (len(theta), 2)), pivot + unit * far], axis=1),
                       "follower"),)

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


def least_pivot_distance(base_radius: float, top: float) -> float:
    """The nearest pivot (mm from the cam centre) whose face meets a cam of ``base_radius`` mm on the arm's side of
    the pivot all the way up to a swing of ``top`` degrees (0 <= top < 90): Rb / cos(psi_top), see the module
    docstring. Exclusive: at it the contact reaches the pivot at the top of the swing."""
    return base_radius / math.cos(math.radians(max(top, 0.0)))


def largest_base_radius(pivot_distance: float, top: float) -> float:
    """The largest base radius (mm, exclusive) a face pivoted ``pivot_distance`` mm from the cam centre follows up to
    a swing of ``top`` degrees: C cos(psi_top), 0 for a swing of 90 degrees or more."""
    return max(pivot_distance * math.cos(math.radians(max(top, 0.0))), 0.0)


def check_reach(table: Any, base_radius: float, top: float) -> None:
    """Refuse (:class:`SpecError`) a face pivoted ``table.pivot_distance`` mm from the centre of a cam of
    ``base_radius`` mm whose contact would pass the pivot as the arm swings up to ``top`` degrees (see the module
    docstring): one line naming ``follower.pivot_distance`` and its range, or ``motion`` for a swing of 90 degrees
    or more, which no pivot follows."""
    c = table.pivot_distance
    positive(c, "follower.pivot_distance")
    if top >= 90.0:
        raise SpecError(f"the arm's swing peaks at {top:.6g} degrees: a flat face through its pivot meets the cam on "
                        "its arm only while it swings less than 90 degrees from rest", "motion")
    least = least_pivot_distance(base_radius, top)
    if not c > least:
        raise SpecError(f"must be > {least:.6g} mm (base radius {base_radius:.6g} mm / cos {top:.6g} deg, the arm's "
                        f"largest swing), or cam.base_radius < {largest_base_radius(c, top):.6g} mm: nearer, the face "
                        "swung that far touches the cam beyond its pivot, where the cam pushes the arm back "
                        f"(pressure angle 180 degrees) (got {c:g})", "follower.pivot_distance")


FOLLOWER = FollowerType("oscillating-flat", oscillating=True,
                        make=lambda t, rb, rr, sense: OscillatingFlat(t.pivot_distance, rb, sense),
                        base_radius_range=lambda t, rr, top: (0.0, largest_base_radius(t.pivot_distance, top)),
                        path_length=None, fits=check_reach)
