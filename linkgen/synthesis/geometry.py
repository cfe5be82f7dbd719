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
from collections.abc import Sequence
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


def place_design(design: Sequence[np.ndarray | float], theta2: np.ndarray | float) -> Placed:
    """:func:`place` of a design given as its ten numbers (or arrays, broadcast) in the module's order: x0, y0,
    theta0, r1, r2, r3, r4, cx, cy, branch."""
    x0, y0, theta0, r1, r2, r3, r4, cx, cy, branch = design
    return place(x0, y0, theta0, r1, r2, r3, r4, cx, cy, branch, theta2)


def transmission_range(r1, r2, r3, r4, start, end) -> tuple[np.ndarray, np.ndarray]:
    """(cos gamma_min, cos gamma_max): the cosines of the least and largest transmission angle (gamma, at B between
    coupler and rocker) while the crank turns from ``start`` to ``end`` (rad from the ground line, either sense;
    ``end = start + 2 pi`` for a crank that turns fully). Not clipped: outside [-1, 1] where the loop cannot close.

    The diagonal A O4, z^2 = r1^2 + r2^2 - 2 r1 r2 cos(theta2), is monotonic between multiples of pi, so over the
    arc its extremes lie at the arc's ends or at theta2 = 0 (z = |r1 - r2|) and pi (z = r1 + r2) where the arc holds
    them; gamma grows with z. Exact, no sampling.
    """
    lo, hi = np.minimum(start, end), np.maximum(start, end)
    two_pi = 2.0 * math.pi
    has_zero = np.floor(hi / two_pi) >= np.ceil(lo / two_pi)
    has_pi = np.floor((hi - math.pi) / two_pi) >= np.ceil((lo - math.pi) / two_pi)
    ends = [r1 * r1 + r2 * r2 - 2.0 * r1 * r2 * np.cos(t) for t in (start, end)]
    z2_min = np.minimum(np.minimum(*ends), np.where(has_zero, (r1 - r2) ** 2, np.inf))
    z2_max = np.maximum(np.maximum(*ends), np.where(has_pi, (r1 + r2) ** 2, -np.inf))
    return tuple((r3 * r3 + r4 * r4 - z2) / (2.0 * r3 * r4) for z2 in (z2_min, z2_max))


def worst_transmission(r1, r2, r3, r4, start, end) -> np.ndarray:
    """The worst transmission angle (rad: the smaller of gamma and pi - gamma) while the crank turns from ``start``
    to ``end`` (see :func:`transmission_range`): min(gamma_min, pi - gamma_max); 0 where the loop cannot close."""
    cos_min, cos_max = (np.clip(c, -1.0, 1.0) for c in transmission_range(r1, r2, r3, r4, start, end))
    return np.minimum(np.arccos(cos_min), math.pi - np.arccos(cos_max))


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
