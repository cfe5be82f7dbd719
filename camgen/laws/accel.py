"""Laws defined by their acceleration: modified trapezoid and modified sine.

Each is a chain of pieces a(u) = c0 + c1 sin(w (u - ua) + p) on [ua, ub], integrated
exactly piece by piece (velocity and displacement continuous, starting at rest) and
scaled so that f(1) = 1. Their published peak coefficients (Norton, Design of
Machinery, Table 8-3): modified trapezoid Cv 2.000, Ca 4.888, Cj 61.43; modified sine
Cv 1.760, Ca 5.528, Cj 69.47.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike

from camgen.laws.base import Law, as_array

#: a piece: (start u, end u, c0, c1, w, p)
Piece = tuple[float, float, float, float, float, float]
PI = math.pi


def _integrate(piece: Piece, x: np.ndarray, v0: float, f0: float) -> np.ndarray:
    """f, f', f'', f''' of one piece at x = u - ua, from its starting velocity and displacement."""
    _, _, c0, c1, w, p = piece
    s, c = np.sin(w * x + p), np.cos(w * x + p)
    acc = c0 + c1 * s
    jerk = c1 * w * c
    vel = v0 + c0 * x - c1 / w * (c - math.cos(p))
    disp = f0 + v0 * x + c0 * x**2 / 2 - c1 / w * ((s - math.sin(p)) / w - math.cos(p) * x)
    return np.stack([disp, vel, acc, jerk])


@dataclass(frozen=True)
class AccelerationLaw(Law):
    """A rise law built from acceleration pieces covering [0, 1] (see the module docstring)."""

    name: ClassVar[str] = "acceleration-pieces"
    pieces: tuple[Piece, ...]
    _starts: tuple[tuple[float, float], ...] = field(init=False, repr=False, compare=False)
    _scale: float = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        starts, v, f = [], 0.0, 0.0
        for piece in self.pieces:
            starts.append((v, f))
            end = _integrate(piece, np.array([piece[1] - piece[0]]), v, f)
            f, v = float(end[0, 0]), float(end[1, 0])
        object.__setattr__(self, "_starts", tuple(starts))
        object.__setattr__(self, "_scale", 1.0 / f)

    @property
    def breakpoints(self) -> tuple[float, ...]:
        return tuple(p[0] for p in self.pieces[1:])

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u = as_array(u)
        flat = u.ravel()
        out = np.empty((4, flat.size))
        edges = np.array([p[0] for p in self.pieces[1:]])
        index = np.searchsorted(edges, flat, side="right")
        for i in np.flatnonzero(np.bincount(index)):          # the pieces present (np.unique loads numpy.ma)
            mask = index == i
            piece = self.pieces[i]
            v0, f0 = self._starts[i]
            out[:, mask] = _integrate(piece, flat[mask] - piece[0], v0, f0)
        return (out * self._scale).reshape((4, *u.shape))


def modified_trapezoid() -> AccelerationLaw:
    """Modified trapezoid: sine ramps over the first and last eighth and round the middle, constant between."""
    w = 4 * PI
    return AccelerationLaw((
        (0.0, 0.125, 0.0, 1.0, w, 0.0),
        (0.125, 0.375, 1.0, 0.0, 1.0, 0.0),
        (0.375, 0.625, 0.0, 1.0, w, PI / 2),
        (0.625, 0.875, -1.0, 0.0, 1.0, 0.0),
        (0.875, 1.0, 0.0, 1.0, w, -PI / 2),
    ))


def modified_sine() -> AccelerationLaw:
    """Modified sine: a short sine ramp over the first and last eighth, a long cosine between."""
    return AccelerationLaw((
        (0.0, 0.125, 0.0, 1.0, 4 * PI, 0.0),
        (0.125, 0.875, 0.0, 1.0, 4 * PI / 3, PI / 2),
        (0.875, 1.0, 0.0, 1.0, 4 * PI, -PI / 2),
    ))
