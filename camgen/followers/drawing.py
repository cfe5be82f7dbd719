"""How a follower draws itself: the :class:`Stroke` (plain numpy), the :class:`Follower` protocol every follower
answers, and the pieces that several followers' drawings share.

Frames: a turning cam's page draws the follower in the fixed frame (the cam turned under it: a point P of the cam's
frame stands at R(sense theta) P); a plate's page draws it at x = 0 over the sliding plate. A cam figure draws it
once, at theta = 0, in the cam's frame (the same as the fixed frame there).

Styles: ``follower`` (a link: stem, arm, face), ``roller`` (a circle of ``radius`` round each point), ``guide`` (an
open line the follower slides along), ``ground`` (a pivot's circle, closed), ``pivot`` (a pivot's point, marked).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np

from camgen.followers.base import PitchGeometry, rotate

#: a drawn face's ends (mm from its origin along the face: a translating face's axis, an arm's pivot), or None
Face = tuple[float, float] | None


@dataclass(frozen=True)
class Stroke:
    """A piece of a follower's drawing: a polyline through ``points`` (mm), or with ``radius`` > 0 a circle of that
    radius (mm) round each point; ``points`` is (frames, k, 2) for a piece drawn frame by frame (:meth:`Follower.
    sketch`), (k, 2) for one drawn once (:meth:`Follower.still`, :meth:`Follower.pose`). ``style`` says how it is
    drawn (see the module docstring); ``closed`` joins a polyline's ends."""

    name: str
    points: np.ndarray
    style: str
    radius: float = 0.0
    closed: bool = False


@runtime_checkable
class Follower(Protocol):
    """A built follower as a cam's page, its figure and its report see it (besides its pitch geometry,
    :mod:`camgen.followers.base`)."""

    @property
    def flat(self) -> bool:
        """True for a flat face (its profile is the face's envelope; no pressure angle to plot)."""
        ...

    @property
    def lift_unit(self) -> str:
        """``"mm"``, or ``"deg"`` for an arm's swing."""
        ...

    @property
    def contact_radius(self) -> float:
        """The roller's radius (mm); 0 for a knife edge or a face."""
        ...

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        """Its pitch geometry at cam angles ``theta`` (rad) for ``motion`` (s and its derivatives)."""
        ...

    def sketch(self, theta: np.ndarray, geometry: PitchGeometry, reach: float, face: Face,
               roller: float) -> tuple[Stroke, ...]:
        """Its moving pieces frame by frame, each stroke's points (frames, k, 2): ``geometry`` its pitch geometry at
        ``theta`` (rad), ``reach`` (mm) the drawing's size (a stem's length is a fraction of it), ``face`` a flat
        face's drawn ends, ``roller`` the radius (mm) its roller is drawn at."""
        ...

    def still(self, theta: np.ndarray, geometry: PitchGeometry, reach: float) -> tuple[Stroke, ...]:
        """What of it stands still over the frames (a guide, a pivot), each stroke's points (k, 2)."""
        ...

    def pose(self, contact: np.ndarray, reach: float, face: Face) -> tuple[Stroke, ...]:
        """It at theta = 0 for a cam figure, touching at ``contact`` (mm: a roller's centre, a face's contact
        point); ``reach`` (mm) the height a translating stem rises to (less twice the roller's radius)."""
        ...

    def report_fields(self) -> dict[str, Any]:
        """What the report's ``follower`` table adds for it (a pivot's place, an arm's rest angle), unrounded."""
        ...


def circle(centre: np.ndarray, r: float, n: int = 48) -> np.ndarray:
    """``n`` points (n, 2) round a circle of radius ``r`` (mm) about ``centre``, from +X counter-clockwise."""
    a = np.linspace(0, 2 * math.pi, n, endpoint=False)
    return np.column_stack([centre[0] + r * np.cos(a), centre[1] + r * np.sin(a)])


def stem_and_roller(centre: np.ndarray, height: float, roller: float) -> tuple[Stroke, ...]:
    """A stem rising ``height`` mm from the contact points ``centre`` (frames, 2), and a roller of radius ``roller``
    (mm) round them where it has one."""
    rod = np.stack([centre, centre + np.array([0.0, height])], axis=1)
    return (Stroke("stem", rod, "follower"), *((Stroke("roller", centre[:, None, :], "roller", roller),)
                                                if roller > 0 else ()))


def upright(x: float, contact: np.ndarray, reach: float, rr: float) -> tuple[Stroke, ...]:
    """A translating follower at theta = 0: its axis x = ``x`` from the contact up to ``reach`` + 2 ``rr``, and its
    roller of radius ``rr`` (mm) where it has one."""
    axis = np.array([[x, contact[1]], [x, reach + 2 * rr]])
    return (Stroke("follower", axis, "follower"), *((Stroke("roller", contact[None, :], "roller", rr),)
                                                     if rr > 0 else ()))


class Translating:
    """What a follower sliding along a fixed axis x = :attr:`axis_x` draws beside itself: the guide it slides in."""

    sense: int

    @property
    def axis_x(self) -> float:
        """The axis it slides along, x in mm."""
        return 0.0

    def fixed(self, theta: np.ndarray, geometry: PitchGeometry) -> np.ndarray:
        """The contact points (frames, 2) in the fixed frame."""
        return rotate(geometry.point, self.sense * theta)

    def still(self, theta: np.ndarray, geometry: PitchGeometry, reach: float) -> tuple[Stroke, ...]:
        y = self.fixed(theta, geometry)[:, 1]
        stem, x = 0.45 * reach, self.axis_x
        return (Stroke("guide", np.array([[x, y.min() + stem * 0.6], [x, y.max() + stem * 1.1]]), "guide"),)

    def report_fields(self) -> dict[str, Any]:
        return {}


class Pivoted:
    """What a follower on an arm draws beside itself (its pivot) and reports (where the pivot is)."""

    sense: int

    @property
    def pivot(self) -> np.ndarray:
        """The pivot (mm, fixed frame)."""
        raise NotImplementedError

    def arm_end(self, contact: np.ndarray) -> np.ndarray:
        """Where the arm drawn at theta = 0 ends, the contact at ``contact`` (mm)."""
        return contact

    def fixed(self, theta: np.ndarray, geometry: PitchGeometry) -> np.ndarray:
        """The contact points (frames, 2) in the fixed frame."""
        return rotate(geometry.point, self.sense * theta)

    def still(self, theta: np.ndarray, geometry: PitchGeometry, reach: float) -> tuple[Stroke, ...]:
        return (Stroke("pivot", circle(np.asarray(self.pivot, dtype=float), 0.03 * reach), "ground", closed=True),)

    def pose(self, contact: np.ndarray, reach: float, face: Face) -> tuple[Stroke, ...]:
        pivot, end = self.pivot, self.arm_end(contact)
        return (Stroke("pivot", pivot[None, :], "pivot"), Stroke("follower", np.array([pivot, end]), "follower"),
                *((Stroke("roller", contact[None, :], "roller", self.roller),) if self.roller > 0 else ()))

    @property
    def roller(self) -> float:
        """The roller's radius drawn at theta = 0 (mm), 0 for none."""
        return 0.0

    def report_fields(self) -> dict[str, Any]:
        return {"pivot_mm": [float(x) for x in self.pivot]}
