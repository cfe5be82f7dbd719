"""A four-bar placed anywhere in the plane, vectorised over designs and crank angles: pure numpy.

A design is the crank pivot O2 = (x0, y0), the ground line's direction theta0 (O2 -> O4), the
lengths r1 (ground), r2 (crank), r3 (coupler), r4 (rocker), the coupler point (cx, cy) in the
coupler's frame (cx along A -> B from the crank pin A, cy square to it, counter-clockwise) and the
branch: +1 puts B to the left of the line from A to O4 (the four-bar's ``open`` assembly), -1 to
the right (``crossed``). Crank angles theta2 are measured counter-clockwise from the ground line,
radians. Every argument broadcasts like a numpy ufunc's, so a whole population of designs at all
target angles is one call.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Placed:
    """Pins and coupler point (mm) and how far each pose is out of reach (mm; 0 where it assembles)."""

    ax: np.ndarray
    ay: np.ndarray
    bx: np.ndarray
    by: np.ndarray
    px: np.ndarray
    py: np.ndarray
    z: np.ndarray               # |A O4|
    out_of_reach: np.ndarray    # how far z lies outside [|r3 - r4|, r3 + r4]


def place(x0, y0, theta0, r1, r2, r3, r4, cx, cy, branch, theta2) -> Placed:
    """The four-bar's pins and coupler point at crank angles ``theta2`` (see the module for the arguments).

    Out of reach, B is put where the coupler and rocker are as nearly closed as they can be (in line), and
    ``out_of_reach`` says by how much the loop is open.
    """
    th = theta0 + theta2
    ax, ay = x0 + r2 * np.cos(th), y0 + r2 * np.sin(th)
    dx, dy = x0 + r1 * np.cos(theta0) - ax, y0 + r1 * np.sin(theta0) - ay
    z = np.hypot(dx, dy)
    out = np.maximum(0.0, z - (r3 + r4)) + np.maximum(0.0, np.abs(r3 - r4) - z)
    safe = np.where(z > 0, z, 1.0)
    cos_a = np.clip((r3 * r3 + z * z - r4 * r4) / (2.0 * r3 * safe), -1.0, 1.0)
    sin_a = np.where(np.asarray(branch) >= 0, 1.0, -1.0) * np.sqrt(1.0 - cos_a * cos_a)
    ux, uy = dx / safe, dy / safe
    ex, ey = cos_a * ux - sin_a * uy, cos_a * uy + sin_a * ux
    bx, by = ax + r3 * ex, ay + r3 * ey
    px, py = ax + cx * ex - cy * ey, ay + cx * ey + cy * ex
    return Placed(ax, ay, bx, by, px, py, z, out)


def transmission_cosines(r1, r2, r3, r4, theta2) -> np.ndarray:
    """cos of the transmission angle (at B, between coupler and rocker) at crank angles ``theta2`` (rad)."""
    z2 = r1 * r1 + r2 * r2 - 2.0 * r1 * r2 * np.cos(theta2)
    return (r3 * r3 + r4 * r4 - z2) / (2.0 * r3 * r4)


def side(ax, ay, bx, by, ox, oy) -> np.ndarray:
    """+1 where B lies to the left of the line from A to O4 (``open``), -1 to the right, 0 on it."""
    return np.sign((ox - ax) * (by - ay) - (oy - ay) * (bx - ax))


def frame_of(o2: np.ndarray, o4: np.ndarray, a: np.ndarray, b: np.ndarray, p: np.ndarray) -> dict[str, float]:
    """A four-bar drawn by its pivots, pins and coupler point (mm, one pose) in this module's terms."""
    theta0 = math.atan2(o4[1] - o2[1], o4[0] - o2[0])
    coupler = math.dist(a, b)
    ex, ey = (b - a) / coupler
    rel = p - a
    return {"x0": float(o2[0]), "y0": float(o2[1]), "theta0": theta0, "r1": math.dist(o2, o4),
            "r2": math.dist(o2, a), "r3": coupler, "r4": math.dist(o4, b),
            "cx": float(rel[0] * ex + rel[1] * ey), "cy": float(-rel[0] * ey + rel[1] * ex),
            "branch": float(side(a[0], a[1], b[0], b[1], o4[0], o4[1]) or 1.0)}
