"""The classical construction both quick-return syntheses stand on: where a chord subtends a given angle.

The crank pivot O2 sees the output's two limit positions (the rocker pin's, or the slider pin's)
under alpha = 180 (Q - 1) / (Q + 1) degrees, Q the time ratio: the crank and coupler are in line
at both (extended at one, folded at the other), so |O2 P1| = coupler + crank and |O2 P2| = coupler -
crank (or the other way round), and the crank turns 180 + alpha one way and 180 - alpha the other.
O2 therefore lies on one of the two circles through P1 and P2 on which the chord P1 P2 subtends
alpha (for Q = 1, alpha = 0: on the line P1 P2, outside the segment). Points are complex numbers (mm).
"""
from __future__ import annotations

import math

import numpy as np


def alpha_of(time_ratio: float) -> float:
    """The angle (rad) between the crank's directions at the two limit positions for time ratio Q (>= 1)."""
    return math.pi * (time_ratio - 1.0) / (time_ratio + 1.0)


def circles(p1: complex, p2: complex, alpha: float) -> list[tuple[complex, float]]:
    """The two circles (centre, radius) through p1 and p2 on which the chord p1 p2 subtends ``alpha`` (0 < alpha
    < pi): mirror images across the chord."""
    half = abs(p2 - p1) / 2.0
    normal = 1j * (p2 - p1) / abs(p2 - p1)
    mid = (p1 + p2) / 2.0
    offset = half / math.tan(alpha)
    return [(mid + s * offset * normal, half / math.sin(alpha)) for s in (1.0, -1.0)]


def pivots(p1: complex, p2: complex, alpha: float, samples: int, reach: float) -> np.ndarray:
    """Candidate crank pivots: ``samples`` points round each of the :func:`circles` (``alpha`` > 0), or on the line
    p1 p2 beyond either end out to ``reach`` mm (``alpha`` = 0), geometrically spaced from the end."""
    if alpha > 0:
        t = np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False) + math.pi / samples
        return np.concatenate([c + r * np.exp(1j * t) for c, r in circles(p1, p2, alpha)])
    u = (p2 - p1) / abs(p2 - p1)
    s = np.geomspace(1e-3 * abs(p2 - p1), reach, samples)
    return np.concatenate([p2 + s * u, p1 - s * u])


def circle_meets_circle(c1: complex, r1: float, c2: complex, r2: float) -> np.ndarray:
    """The points (0, 1 or 2) where two circles meet."""
    d = abs(c2 - c1)
    if d == 0 or d > r1 + r2 or d < abs(r1 - r2):
        return np.array([], dtype=complex)
    a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d)
    h = math.sqrt(max(0.0, r1 * r1 - a * a))
    u = (c2 - c1) / d
    return np.unique(np.array([c1 + a * u + s * h * 1j * u for s in (1.0, -1.0)]))


def line_meets_circle(p: complex, u: complex, c: complex, r: float) -> np.ndarray:
    """The points (0, 1 or 2) where the line through p along unit u meets a circle."""
    w = p - c
    b = (w * u.conjugate()).real
    disc = b * b - (abs(w) ** 2 - r * r)
    if disc < 0:
        return np.array([], dtype=complex)
    return np.unique(np.array([p + (-b + s * math.sqrt(disc)) * u for s in (1.0, -1.0)]))


def limit_lengths(o2: np.ndarray, p1: complex, p2: complex) -> tuple[np.ndarray, np.ndarray]:
    """(crank, coupler) for crank pivots ``o2`` whose crank and coupler lie in line at p1 and at p2."""
    d1, d2 = np.abs(o2 - p1), np.abs(o2 - p2)
    return np.abs(d1 - d2) / 2.0, (d1 + d2) / 2.0


def info(what: str, alpha: float, tried: int, valid: int) -> dict:
    """How a construction went, for the summary."""
    return {"method": f"classical construction: the crank pivot on the circle through the {what} where they "
                      "subtend 180 (Q - 1) / (Q + 1) degrees", "alpha_deg": math.degrees(alpha), "tried": tried,
            "valid": valid}
