"""The involute function, its inverse, and the involute of a circle as a curve.

Angles in radians, lengths in mm. The involute of the base circle of radius ``rb`` that leaves it at the polar angle
``start`` and unwinds counter-clockwise is, at roll angle ``u`` >= 0,

    rb (cos(start + u) + u sin(start + u), sin(start + u) - u cos(start + u)),

at the radius rb sqrt(1 + u^2) and the polar angle start + inv(atan u); its tangent there points along
(cos(start + u), sin(start + u)) and its radius of curvature is rb u.
"""
from __future__ import annotations

import math

import numpy as np


def inv(t: np.ndarray | float) -> np.ndarray:
    """The involute function tan t - t of angles ``t`` (rad, in [0, pi/2))."""
    t = np.asarray(t, dtype=float)
    return np.tan(t) - t


def inv_inverse(y: np.ndarray | float) -> np.ndarray:
    """The angle t in [0, pi/2) (rad) whose involute function tan t - t is ``y`` (>= 0), for arrays.

    Newton's method on the convex tan t - t - y from the smaller of (3 y)^(1/3) and atan(y + pi/2), both of which
    lie at or above the root, so every step moves down to it without overshooting; to 1e-15 rad in a few steps.
    """
    y = np.asarray(y, dtype=float)
    t = np.minimum(np.cbrt(3.0 * y), np.arctan(y + math.pi / 2))
    for _ in range(60):
        tan = np.tan(t)
        slope = tan * tan
        step = np.where(slope > 0, (tan - t - y) / np.where(slope > 0, slope, 1.0), 0.0)
        t = t - step
        if np.all(np.abs(step) <= 1e-16 * np.maximum(1.0, np.abs(t))):
            break
    return t


def roll_of(radius: np.ndarray | float, base_radius: float) -> np.ndarray:
    """The roll angle u (rad) at which the involute of a base circle of ``base_radius`` reaches ``radius`` (mm)."""
    r = np.asarray(radius, dtype=float)
    return np.sqrt(np.maximum((r / base_radius) ** 2 - 1.0, 0.0))


def involute_points(base_radius: float, start: float, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points (n, 2) mm and unit tangents (n, 2) of the counter-clockwise involute of the base circle of
    ``base_radius`` leaving it at polar angle ``start`` (rad), at roll angles ``u`` (n,) rad; the tangent at u = 0
    (the cusp on the base circle) is the limit, radially outwards."""
    u = np.asarray(u, dtype=float)
    a = start + u
    c, s = np.cos(a), np.sin(a)
    points = base_radius * np.column_stack([c + u * s, s - u * c])
    return points, np.column_stack([c, s])


def thickness_angle(radius: np.ndarray | float, base_radius: float, pitch_radius: float,
                    thickness: float) -> np.ndarray:
    """Half the angle (rad) a tooth of circular ``thickness`` (mm) on its reference circle of ``pitch_radius``
    subtends at ``radius`` (mm, >= the base radius): thickness / (2 pitch radius) + inv(a) - inv(a_r), with
    cos a = rb / r_pitch and cos a_r = rb / radius."""
    a = math.acos(base_radius / pitch_radius)
    ar = np.arccos(np.minimum(base_radius / np.asarray(radius, dtype=float), 1.0))
    return thickness / (2 * pitch_radius) + float(inv(a)) - inv(ar)
