"""The six-bar tests' own kinematics, independent of the solver: circle intersections and rigid bodies by hand."""
from __future__ import annotations

import numpy as np


def circles(c1: np.ndarray, r1: float, c2: np.ndarray, r2: float, side: float) -> np.ndarray:
    """The intersection (n, 2) of circles about c1 (n, 2) and c2 (n, 2) on ``side`` (+1: left of c1 -> c2)."""
    d = c2 - c1
    dist = np.hypot(d[:, 0], d[:, 1])
    a = (r1**2 - r2**2 + dist**2) / (2 * dist)
    h = np.sqrt(r1**2 - a**2)
    u = d / dist[:, None]
    return c1 + a[:, None] * u + side * h[:, None] * np.column_stack([-u[:, 1], u[:, 0]])


def rigid(p0: np.ndarray, q0: np.ndarray, x0: np.ndarray, p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Where drawn point x0 goes on the body whose drawn points p0, q0 are at p, q (n, 2)."""
    z0, w0 = complex(*(q0 - p0)), complex(*(x0 - p0))
    z = (q[:, 0] - p[:, 0]) + 1j * (q[:, 1] - p[:, 1])
    out = (p[:, 0] + 1j * p[:, 1]) + w0 / z0 * z
    return np.column_stack([out.real, out.imag])


def side(a: np.ndarray, b: np.ndarray, x: np.ndarray) -> float:
    """+1 where drawn x lies left of the line a -> b."""
    d, e = b - a, x - a
    return float(np.sign(d[0] * e[1] - d[1] * e[0]))
