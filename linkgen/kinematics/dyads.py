"""Closed-form position kernels of the dyads (Assur groups of class II), vectorised over poses.

Pure functions of numpy arrays: points are (n, 2) arrays in mm, directions unit (n, 2)
arrays, signs +1 or -1 (a number or an (n,) array). Each kernel returns the unknown it
places and its *margin*: a number >= 0 where the dyad assembles, 0 at its toggle (its two
links in line), < 0 where it cannot close. Margins are scaled to be dimensionless (the sine
of the dyad's transmission angle, or the like), so one tolerance serves every size.

* :func:`circle_circle` (RRR): the middle joint at distance r1 from P1 and r2 from P2;
  ``sign`` +1 puts it to the left of P1 -> P2. Computed from the triangle's area by
  Kahan's stable form of Heron's formula, exact to rounding up to the toggle.
* :func:`circle_line` (RRP): the point at distance r from P on the line c + t u; ``sign``
  picks the solution ahead of (+1) or behind (-1) the foot of the perpendicular from P,
  along u.
* :func:`line_through` (RPR): the direction of a line that stays at signed distance ``c``
  from P1 (in its own frame) and passes through P2; ``sign`` picks which side.
* :func:`line_line` (PRP): the intersection of two lines.
"""
from __future__ import annotations

import numpy as np


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z-component of a x b for (n, 2) arrays."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def perp(a: np.ndarray) -> np.ndarray:
    """a turned 90 degrees counter-clockwise (k x a)."""
    return np.stack([-a[..., 1], a[..., 0]], axis=-1)


def turn(v: np.ndarray, c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """v turned counter-clockwise by the angle with cosine c and sine s."""
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def area4(a: float, b: float, c: np.ndarray) -> np.ndarray:
    """Four times the area of triangles with sides a, b (numbers) and c (array), by Kahan's stable form of Heron's
    formula with the sides sorted by comparisons alone; where the sides cannot close, minus the square root of the
    product's magnitude, so that it serves as a margin."""
    longer, shorter = max(a, b), min(a, b)
    # sides sorted x >= y >= z by comparisons alone: the middle one is c clipped into [shorter, longer]
    x, y, z = np.maximum(c, longer), np.clip(c, shorter, longer), np.minimum(c, shorter)
    prod = (x + (y + z)) * (z - (x - y)) * (z + (x - y)) * (x + (y - z))
    return np.copysign(np.sqrt(np.abs(prod)), prod)


def circle_circle(p1: np.ndarray, r1: float, p2: np.ndarray, r2: float,
                  sign: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """The point J with |J - P1| = r1 and |J - P2| = r2, to the left of P1 -> P2 for ``sign`` +1; and the margin
    sin(angle at J) (negative beyond reach). Where the circles do not meet J is the nearest point of the
    touching configuration (the caller refuses those poses)."""
    d_vec = p2 - p1
    d = np.hypot(d_vec[:, 0], d_vec[:, 1])
    a4 = area4(r1, r2, d)
    safe = np.where(d > 0, d, 1.0)
    cos_a = (r1 * r1 + d * d - r2 * r2) / (2.0 * r1 * safe)
    sin_a = sign * np.maximum(a4, 0.0) / (2.0 * r1 * safe)
    unit = d_vec / safe[:, None]
    return p1 + r1 * turn(unit, cos_a, sin_a), a4 / (2.0 * r1 * r2)


def circle_line(p: np.ndarray, r: float, c: np.ndarray, u: np.ndarray,
                sign: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """The point J = c + t u at distance r from P, ahead of the foot of the perpendicular (along u) for ``sign``
    +1; its parameter t; and the margin sqrt(1 - (h / r)^2) (the cosine of the angle between PJ and the line's
    normal; negative beyond reach), h being the distance from P to the line."""
    w = c - p
    f = dot(w, u)
    h = cross(u, w)          # signed distance of the line from P
    disc = (r - np.abs(h)) * (r + np.abs(h))
    t = -f + sign * np.sqrt(np.maximum(disc, 0.0))
    return c + t[:, None] * u, np.copysign(np.sqrt(np.abs(disc)), disc) / r


def line_through(p1: np.ndarray, p2: np.ndarray, normal_angle: float, offset: float,
                 sign: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """The rotation (cosine, sine columns of an (n, 2) array) that turns a line of normal direction
    ``normal_angle`` (rad, in the drawing) so that n . (P2 - P1) = ``offset`` (mm); ``sign`` picks the side; and
    the margin sqrt(1 - (offset / |P2 - P1|)^2) (negative where the line cannot reach P2)."""
    d_vec = p2 - p1
    d = np.hypot(d_vec[:, 0], d_vec[:, 1])
    safe = np.where(d > 0, d, 1.0)
    disc = (d - abs(offset)) * (d + abs(offset))
    cos_psi = offset / safe
    sin_psi = sign * np.sqrt(np.maximum(disc, 0.0)) / safe
    normal = turn(d_vec / safe[:, None], cos_psi, sin_psi)      # the turned line's normal, world
    c0, s0 = np.cos(normal_angle), np.sin(normal_angle)
    # rotation R with R n_drawn = normal: cos = n.n0, sin = n0 x n
    rot = np.stack([normal[:, 0] * c0 + normal[:, 1] * s0, c0 * normal[:, 1] - s0 * normal[:, 0]], axis=-1)
    return rot, np.copysign(np.sqrt(np.abs(disc)), disc) / safe


def line_line(c1: np.ndarray, u1: np.ndarray, c2: np.ndarray, u2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The intersection of the lines c1 + t u1 and c2 + s u2, its parameter t on the first, and the margin
    |sin| of the angle between them (0 where they are parallel: no single intersection)."""
    den = cross(u1, u2)
    safe = np.where(den != 0, den, 1.0)
    t = cross(c2 - c1, u2) / safe
    return c1 + t[:, None] * u1, np.abs(den)
