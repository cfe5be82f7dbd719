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


def _array_joints(joints: dict) -> dict[str, np.ndarray]:
    return {k: np.array(v, dtype=float) for k, v in joints.items()}


def _gap(j: dict[str, np.ndarray], a: str, b: str) -> float:
    """The drawn distance (mm) between joints ``a`` and ``b``."""
    return float(np.linalg.norm(j[a] - j[b]))


def four_bar_tracer(joints: dict, directions: np.ndarray) -> np.ndarray:
    """P (n, 2) of a four-bar O2-A-B-O4 drawn at ``joints`` (its coupler A-B-P) with its crank at world
    ``directions`` (rad), by hand."""
    j = _array_joints(joints)
    n = len(directions)
    o4 = np.tile(j["O4"], (n, 1))
    a = j["O2"] + _gap(j, "A", "O2") * np.column_stack([np.cos(directions), np.sin(directions)])
    b = circles(a, _gap(j, "B", "A"), o4, _gap(j, "B", "O4"), side(j["A"], j["O4"], j["B"]))
    return rigid(j["A"], j["B"], j["P"], a, b)


def watt1_tracer(joints: dict, directions: np.ndarray) -> np.ndarray:
    """P (n, 2) of a Watt I drawn at ``joints`` (the four-bar O2-A-B-O4, the ternary coupler A-B-E and rocker
    O4-B-F, the dyad E-G-F, P on the output F-G) with its crank at world ``directions`` (rad), by hand."""
    return watt1_joints(joints, directions)["P"]


def watt1_joints(joints: dict, directions: np.ndarray) -> dict[str, np.ndarray]:
    """Every joint (n, 2) of a Watt I drawn at ``joints`` with its crank at world ``directions`` (rad), by hand:
    each dyad by two circles on the side the drawing shows, the ternary links as rigid bodies."""
    j = _array_joints(joints)
    n = len(directions)
    o2, o4 = np.tile(j["O2"], (n, 1)), np.tile(j["O4"], (n, 1))
    a = o2 + _gap(j, "A", "O2") * np.column_stack([np.cos(directions), np.sin(directions)])
    b = circles(a, _gap(j, "B", "A"), o4, _gap(j, "B", "O4"), side(j["A"], j["O4"], j["B"]))
    e = rigid(j["A"], j["B"], j["E"], a, b)
    f = rigid(j["O4"], j["B"], j["F"], o4, b)
    g = circles(e, _gap(j, "G", "E"), f, _gap(j, "G", "F"), side(j["E"], j["F"], j["G"]))
    return {"O2": o2, "O4": o4, "A": a, "B": b, "E": e, "F": f, "G": g, "P": rigid(j["F"], j["G"], j["P"], f, g)}


def watt1_worst_transmission(joints: dict, directions: np.ndarray) -> float:
    """The worst transmission angle (degrees, 0 to 90) of a Watt I drawn at ``joints`` over the crank's world
    ``directions`` (rad): at B between the coupler and the rocker, at G between the rod and the output."""
    at = watt1_joints(joints, directions)

    def angle(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> np.ndarray:
        u, v = p - q, r - q
        return np.degrees(np.arctan2(np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]), np.sum(u * v, axis=1)))

    return min(float(np.min(np.minimum(a, 180.0 - a))) for a in (angle(at["A"], at["B"], at["O4"]),
                                                                  angle(at["E"], at["G"], at["F"])))
