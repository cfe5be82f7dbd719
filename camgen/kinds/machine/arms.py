"""A follower's arm as the crank of a linkage it drives: where it points at rest, which way a rise turns it, and
its lever (the distance, mm, from its pivot at which a force along its path does the work of a torque about it).

Two followers swing on a pivot. An oscillating roller's arm runs from the pivot to the roller's centre, on the
prime circle at (0, Rp) at rest; a rise turns it counter-clockwise where ``_swing_sign`` is +1. An oscillating
flat face runs from the pivot along the face towards its rest contact, (0, Rb) on the base circle; a rise turns it
by ``_swing`` (-1, clockwise about a pivot on +X). The crank of a four-bar it drives lies along the arm, its pin
``crank`` mm from the pivot: a roller's lever is its arm's length (the load acts at the roller), a flat face's the
crank's length (the face has no fixed point of contact; the load acts at the crank pin, square to the arm).
Lengths mm, angles radians in the cam's fixed frame (the machine's moved to the cam's shaft).
"""
from __future__ import annotations

from typing import Any

import numpy as np


def rest_vector(follower: Any) -> np.ndarray:
    """(2,) mm from the follower's pivot along its arm at rest: to the roller's centre, or to a face's rest
    contact."""
    radius = getattr(follower, "prime_radius", None)
    height = float(follower.base_radius if radius is None else radius)
    return np.array([0.0, height]) - np.asarray(follower.pivot, dtype=float)


def swing_sign(follower: Any) -> float:
    """+1 where a rise turns the arm counter-clockwise, -1 where clockwise."""
    sign = getattr(follower, "_swing_sign", None)
    return float(follower._swing if sign is None else sign)


def lever(follower: Any, crank: float) -> float:
    """The arm's lever (mm, see the module docstring): a roller's ``arm_length``, else the ``crank`` mm from the
    pivot to the crank pin of the linkage it drives."""
    length = getattr(follower, "arm_length", None)
    return float(crank if length is None else length)
