"""A roller (or knife edge) on a linear (plate) cam: the plate slides, the follower translates across it.

The plate's frame: its bottom edge on y = 0, the program's 360 degrees spread over
``travel`` mm along +X (x = travel theta / 2 pi); the roller's centre rides at
y = base_height + roller radius + s. The plate's top edge is that path offset down by
the roller radius. Pressure angle: atan(ds/dx), positive while the follower rises.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from camgen.followers.base import PitchGeometry, perp
from camgen.followers.drawing import Face, Stroke, stem_and_roller, upright


@dataclass(frozen=True)
class PlateRoller:
    """Roller of ``roller_radius`` mm (0: knife edge) over a plate ``base_height`` mm high, ``travel`` mm long.

    Parameters
    ----------
    base_height : float
        The plate's height under the profile at s = 0 (mm): the template's ``cam.base_radius``.
    roller_radius : float
        The roller's radius (mm); 0 for a knife edge.
    travel : float
        How far the plate slides over the program's 360 degrees (mm), along +X.
    """

    base_height: float
    roller_radius: float
    travel: float

    flat: ClassVar[bool] = False
    lift_unit: ClassVar[str] = "mm"
    sense: ClassVar[int] = 1          # the top edge runs left to right: convex corners turn clockwise

    @property
    def contact_radius(self) -> float:
        return self.roller_radius

    def pitch(self, theta: np.ndarray, motion: np.ndarray) -> PitchGeometry:
        """The roller centre's path in the plate frame at parameters ``theta`` (rad) of the program."""
        s, s1, s2 = motion[0], motion[1], motion[2]
        c = self.travel / (2 * math.pi)                      # dx / dtheta
        point = np.column_stack([c * theta, self.base_height + self.roller_radius + s])
        d1 = np.column_stack([np.full_like(s, c), s1])
        d2 = np.column_stack([np.zeros_like(s), s2])
        speed = np.hypot(c, s1)
        normal = perp(d1) / speed[:, None]                   # up, away from the plate
        kappa = -c * s2 / speed**3                           # bulging up is convex
        return PitchGeometry(theta=theta, point=point, d1=d1, d2=d2, normal=normal, kappa=kappa,
                             pressure_angle=np.arctan2(s1, c))

    def sketch(self, theta: np.ndarray, geometry: PitchGeometry, reach: float, face: Face,
               roller: float) -> tuple[Stroke, ...]:
        """Its stem at x = 0 (the plate slides under it), 0.3 ``reach`` long, and its roller (none for a knife
        edge)."""
        centre = np.column_stack([np.zeros_like(theta), geometry.point[:, 1]])
        return stem_and_roller(centre, 0.3 * reach, roller)

    def still(self, theta: np.ndarray, geometry: PitchGeometry, reach: float) -> tuple[Stroke, ...]:
        """Nothing: the plate's page shows no guide."""
        return ()

    def pose(self, contact: np.ndarray, reach: float, face: Face) -> tuple[Stroke, ...]:
        return upright(float(contact[0]), contact, reach, self.roller_radius)

    def report_fields(self) -> dict[str, Any]:
        return {}
