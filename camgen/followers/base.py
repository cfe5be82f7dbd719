"""What every follower gives the cam: its pitch curve and contact geometry in the cam's frame.

Frames and signs (all followers):

* The cam centre is the origin; at theta = 0 the follower lies on +Y.
* ``sense`` is +1 for a cam turning counter-clockwise (viewed from +Z), -1 for clockwise.
  In the cam's own frame the follower then travels the other way round.
* Curvature ``kappa`` is signed: positive where the curve is convex (bulging away
  from the cam centre, like the base circle), negative where concave. The radius of
  curvature is 1 / kappa; an inflection has kappa = 0 (infinite radius).
* ``normal`` is the outward unit normal (away from the cam material).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PitchGeometry:
    """Pitch curve samples in the cam frame (mm, radians); arrays of shape (n,) or (n, 2)."""

    theta: np.ndarray          # cam angle, rad
    point: np.ndarray          # (n, 2) pitch point (roller centre), mm
    d1: np.ndarray             # (n, 2) dP/dtheta, mm/rad
    d2: np.ndarray             # (n, 2) d2P/dtheta2, mm/rad^2
    normal: np.ndarray         # (n, 2) outward unit normal
    kappa: np.ndarray          # (n,) signed curvature of the pitch curve, 1/mm, convex > 0
    pressure_angle: np.ndarray  # (n,) rad, signed (see the follower's docstring)


def rotate(vectors: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotate (n, 2) ``vectors`` counter-clockwise by ``angle`` (n,) radians."""
    c, s = np.cos(angle), np.sin(angle)
    x, y = vectors[:, 0], vectors[:, 1]
    return np.column_stack([c * x - s * y, s * x + c * y])
