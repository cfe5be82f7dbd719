"""Elliptic Fourier descriptors of plane curves (Kuhl and Giardina, 1982), normalised: pure numpy.

A closed polygon p_0 ... p_{K-1} (mm; it closes back to p_0) is read as x(t), y(t) over its arc
length t in [0, T). Harmonic n (n = 1 ... H) is the ellipse

    x_n(t) = a_n cos(2 pi n t / T) + b_n sin(2 pi n t / T)
    y_n(t) = c_n cos(2 pi n t / T) + d_n sin(2 pi n t / T)

and (A0, C0) is the mean point of the curve along its length. For a polygon the coefficients are
exact sums over its sides (no quadrature). An open curve is closed by retracing it (there and
back, :func:`retrace`), so that its descriptors do not depend on where the closure would be.

Normalisation removes what a similarity and a change of starting point change: the start is moved
to an end of the first harmonic's major axis (phase theta), the curve turned so that axis lies
along +x (angle psi, counter-clockwise) and scaled by its semi-major length E, the mean point moved
to the origin. Then a_1 = 1, b_1 = c_1 = 0 and d_1 = +-(minor / major): positive where the first
harmonic runs counter-clockwise. Every curve here is brought to that sense first (a clockwise one
is traversed backwards: b_n and d_n change sign), so d_1 >= 0. One ambiguity is left: the other
end of the major axis (theta + pi, psi + pi) gives the same coefficients with every even harmonic
negated; :func:`forms` gives both.

Two curves with equal normalised coefficients differ by a similarity: the scale E_t / E_r, the
turn psi_t - psi_r (counter-clockwise) and the shift of the mean point (:func:`similarity`).
Every function broadcasts over leading axes (a batch of curves at once).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

TWO_PI = 2.0 * math.pi
#: curves whose descriptors are computed together at most (more are taken in chunks of this many)
CHUNK = 1024


@dataclass(frozen=True)
class Normalised:
    """The normalised descriptors of curves (leading shape ``S``): ``coefficients`` (S + (H, 4)) the normalised
    (a, b, c, d) of harmonics 1 ... H; ``centre`` (S + (2,)) the mean point (mm); ``scale`` (S) the first
    harmonic's semi-major length E (mm); ``rotation`` (S) its major axis's direction psi (rad, counter-clockwise
    from +x); ``phase`` (S) the start's shift theta (rad of 2 pi t / T); ``reversed`` (S) whether the curve was
    traversed backwards to run counter-clockwise."""

    coefficients: np.ndarray
    centre: np.ndarray
    scale: np.ndarray
    rotation: np.ndarray
    phase: np.ndarray
    reversed: np.ndarray


def retrace(points: np.ndarray) -> np.ndarray:
    """The closed polygon (K + K - 2 points) that runs along the open polyline ``points`` (..., K, 2) and back."""
    return np.concatenate([points, points[..., -2:0:-1, :]], axis=-2)


def coefficients(points: np.ndarray, harmonics: int) -> tuple[np.ndarray, np.ndarray]:
    """(centre (..., 2), coefficients (..., H, 4)) of the closed polygons ``points`` (..., K, 2), K >= 3, no two
    consecutive vertices equal (mm). The mean point is the length-weighted mean of the sides' midpoints.

    With phi_i = 2 pi t_i / T at vertex i (t_i its arc length from p_0) and the slopes (dx/dt, dy/dt) of side i
    (p_i -> p_{i+1}), a_n = T / (2 n^2 pi^2) sum_i (dx/dt)_i (cos n phi_{i+1} - cos n phi_i), b_n likewise with
    sin, c_n and d_n with dy/dt; the powers exp(i n phi) are built by repeated products.
    """
    p = np.asarray(points, dtype=float)
    if p.ndim > 2 and math.prod(p.shape[:-2]) > CHUNK:      # in chunks that stay in the cache: the same numbers
        flat = p.reshape(-1, *p.shape[-2:])
        parts = [coefficients(flat[lo:lo + CHUNK], harmonics) for lo in range(0, len(flat), CHUNK)]
        return (np.concatenate([c for c, _ in parts]).reshape(*p.shape[:-2], 2),
                np.concatenate([d for _, d in parts]).reshape(*p.shape[:-2], harmonics, 4))
    step = np.roll(p, -1, axis=-2) - p                                   # side i: p_i -> p_{i+1}
    length = np.hypot(step[..., 0], step[..., 1])                        # (..., K)
    total = length.sum(axis=-1)                                          # T
    centre = np.sum((p + 0.5 * step) * length[..., None], axis=-2) / total[..., None]
    slope = step / length[..., None]                                     # dx/dt, dy/dt of each side
    start = np.cumsum(length, axis=-1) - length                          # t_i: where side i starts
    unit = np.exp(1j * TWO_PI * start / total[..., None])                # exp(i phi_i)
    power = np.ones_like(unit)
    out = np.empty((*p.shape[:-2], harmonics, 4))
    for n in range(1, harmonics + 1):
        power = power * unit
        change = np.roll(power, -1, axis=-1) - power                     # exp(i n phi_{i+1}) - exp(i n phi_i)
        factor = total / (2.0 * math.pi**2 * n * n)
        for k, (part, axis) in enumerate(((change.real, 0), (change.imag, 0), (change.real, 1),
                                          (change.imag, 1))):
            out[..., n - 1, k] = factor * np.sum(slope[..., axis] * part, axis=-1)
    return centre, out


def _turned(coeffs: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Harmonic n of ``coeffs`` (..., H, 4) with its start moved on by n ``angle`` (...)."""
    n = np.arange(1, coeffs.shape[-2] + 1, dtype=float)
    c, s = np.cos(n * angle[..., None]), np.sin(n * angle[..., None])
    a, b, cc, d = (coeffs[..., k] for k in range(4))
    return np.stack([a * c + b * s, -a * s + b * c, cc * c + d * s, -cc * s + d * c], axis=-1)


def normalise(centre: np.ndarray, coeffs: np.ndarray) -> Normalised:
    """The normalised descriptors (see the module) of curves with these raw descriptors, each first brought to run
    counter-clockwise. A first harmonic that is a circle (major = minor) leaves the start undetermined: its phase
    is then that of the curve's own start."""
    c0 = np.asarray(coeffs, dtype=float)
    a1, b1, c1, d1 = (c0[..., 0, k] for k in range(4))
    backwards = a1 * d1 - b1 * c1 < 0                                    # the first harmonic runs clockwise
    flip = np.where(backwards, -1.0, 1.0)[..., None]
    c0 = np.stack([c0[..., 0], c0[..., 1] * flip, c0[..., 2], c0[..., 3] * flip], axis=-1)
    a1, b1, c1, d1 = (c0[..., 0, k] for k in range(4))
    theta = 0.5 * np.arctan2(2.0 * (a1 * b1 + c1 * d1), a1**2 - b1**2 + c1**2 - d1**2)
    started = _turned(c0, theta)
    psi = np.arctan2(started[..., 0, 2], started[..., 0, 0])
    scale = np.hypot(started[..., 0, 0], started[..., 0, 2])
    cos, sin = (f(psi)[..., None] / scale[..., None] for f in (np.cos, np.sin))
    a, b, cc, d = (started[..., k] for k in range(4))
    out = np.stack([cos * a + sin * cc, cos * b + sin * d, -sin * a + cos * cc, -sin * b + cos * d], axis=-1)
    return Normalised(out, np.asarray(centre, dtype=float), scale, psi, theta, backwards)


def forms(coeffs: np.ndarray) -> np.ndarray:
    """The two normalised forms (2, ..., H, 4) of normalised ``coeffs``: as given, and from the major axis's other
    end (every even harmonic negated)."""
    sign = np.where(np.arange(1, coeffs.shape[-2] + 1) % 2 == 0, -1.0, 1.0)[:, None]
    return np.stack([coeffs, coeffs * sign])


def mirrored(points: np.ndarray) -> np.ndarray:
    """``points`` reflected in the x axis (y -> -y)."""
    return np.asarray(points, dtype=float) * np.array([1.0, -1.0])


def similarity(target: Normalised, reference: Normalised, other_end: bool | np.ndarray = False
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(scale, turn (rad, counter-clockwise), shift (..., 2) mm) of the similarity x -> scale R(turn) x + shift that
    takes the reference curve onto the target where their normalised coefficients agree; ``other_end``: the
    target's coefficients agree in their second form (:func:`forms`)."""
    scale = target.scale / reference.scale
    turn = target.rotation - reference.rotation + np.where(other_end, math.pi, 0.0)
    c, s = np.cos(turn), np.sin(turn)
    rx, ry = reference.centre[..., 0], reference.centre[..., 1]
    shift = target.centre - np.stack([scale * (c * rx - s * ry), scale * (s * rx + c * ry)], axis=-1)
    return scale, turn, shift


def curve_of(centre: np.ndarray, coeffs: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The truncated series at parameters ``t`` (rad of 2 pi t / T): points (..., len(t), 2) mm."""
    n = np.arange(1, coeffs.shape[-2] + 1, dtype=float)
    c, s = np.cos(np.outer(t, n)), np.sin(np.outer(t, n))          # (m, H)
    xs = centre[..., 0, None] + np.einsum("mh,...h->...m", c, coeffs[..., 0]) + np.einsum("mh,...h->...m", s,
                                                                                           coeffs[..., 1])
    ys = centre[..., 1, None] + np.einsum("mh,...h->...m", c, coeffs[..., 2]) + np.einsum("mh,...h->...m", s,
                                                                                           coeffs[..., 3])
    return np.stack([xs, ys], axis=-1)
