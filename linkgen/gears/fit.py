"""Smooth plane curves as chains of circular arcs (biarcs) within a tolerance.

A curve is a function of a parameter returning points (n, 2) mm and unit tangents (n, 2) along the increasing
parameter. :func:`fit_arcs` splits the parameter range until the biarc of each span (two tangent arcs that leave its
start along the start tangent and reach its end along the end tangent) lies within the tolerance of the curve at
:data:`SAMPLES` points inside the span, and returns the chain in LWPOLYLINE form: each piece's start vertex and its
bulge tan(included angle / 4), positive counter-clockwise. Spans are split at their middle, so a curve of slowly
changing curvature (an involute, a trochoid) takes a few arcs where it is flat and more where it turns sharply.
"""
from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from camgen.core.errors import DesignError

#: a curve: parameter values (n,) -> points (n, 2) mm and unit tangents (n, 2)
Curve = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
#: points inside each span at which the curve's distance from its biarc is measured
SAMPLES = 24
#: the fit keeps the measured distance within this share of the tolerance: the curve between two samples may stray
#: a little further than at them
MARGIN = 0.9
#: the most times a span may be halved
MAX_DEPTH = 30


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def arc_bulge(start: np.ndarray, end: np.ndarray, tangent: np.ndarray) -> float:
    """The bulge of the arc that leaves ``start`` along the unit ``tangent`` and ends at ``end``: the tangent turns
    by twice the angle it makes with the chord."""
    chord = end - start
    half = math.atan2(_cross(tangent, chord), float(tangent @ chord))
    return math.tan(half / 2.0)


def biarc(p0: np.ndarray, t0: np.ndarray, p1: np.ndarray, t1: np.ndarray) -> tuple[np.ndarray, float, float] | None:
    """The junction and the two bulges of the biarc from ``p0`` (unit tangent ``t0``) to ``p1`` (unit tangent
    ``t1``) whose two tangent legs are equally long, or None where no such biarc exists (the tangents turn away
    from the chord).

    With v = p1 - p0 and the leg length d, the legs' far ends p0 + d t0 and p1 - d t1 are 2 d apart:
    |v - d (t0 + t1)| = 2 d, that is 2 (1 - t0.t1) d^2 + 2 (v.(t0 + t1)) d - v.v = 0; the arcs meet halfway
    between those ends.
    """
    v = p1 - p0
    s = t0 + t1
    a = 2.0 * (1.0 - float(t0 @ t1))
    b = float(v @ s)
    c = float(v @ v)
    if a < 1e-12:
        if b <= 0:
            return None
        d = c / (2.0 * b)
    else:
        d = (math.sqrt(b * b + a * c) - b) / a
    if not d > 0:
        return None
    q0, q1 = p0 + d * t0, p1 - d * t1
    junction = (q0 + q1) / 2.0
    leg = q1 - q0
    norm = float(np.hypot(*leg))
    tj = leg / norm if norm > 0 else t0
    return junction, arc_bulge(p0, junction, t0), arc_bulge(junction, p1, tj)


def distance_to_arc(points: np.ndarray, start: np.ndarray, end: np.ndarray, bulge: float) -> np.ndarray:
    """The distance (mm) of ``points`` (n, 2) from the arc (or line, bulge 0) from ``start`` to ``end``."""
    chord = end - start
    length = float(np.hypot(*chord))
    along = np.clip((points - start) @ chord / max(length * length, 1e-300), 0.0, 1.0)
    if abs(bulge) < 1e-12 or length == 0:
        return np.hypot(*(start + along[:, None] * chord - points).T)
    sweep = 4.0 * math.atan(bulge)
    radius = length / (2.0 * abs(math.sin(sweep / 2.0)))
    normal = np.array([-chord[1], chord[0]]) / length
    centre = (start + end) / 2.0 + normal * (length / (2.0 * math.tan(sweep / 2.0)))
    rel = points - centre
    first = math.atan2(start[1] - centre[1], start[0] - centre[0])
    turn = np.arctan2(rel[:, 1], rel[:, 0]) - first
    turn = np.mod(turn, 2 * math.pi) if sweep > 0 else -np.mod(-turn, 2 * math.pi)
    on_arc = np.abs(turn) <= abs(sweep)
    ends = np.minimum(np.hypot(*(points - start).T), np.hypot(*(points - end).T))
    return np.where(on_arc, np.abs(np.hypot(rel[:, 0], rel[:, 1]) - radius), ends)


def fit_arcs(curve: Curve, t0: float, t1: float, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """The curve from parameter ``t0`` to ``t1`` as biarcs within ``tolerance`` mm: the pieces' start vertices (k, 2)
    mm and bulges (k,); the chain ends at ``curve(t1)``, which it leaves out (the next piece's start).

    Raises
    ------
    DesignError
        A span halved :data:`MAX_DEPTH` times still strays from the curve (a cusp inside the range).
    """
    vertices: list[np.ndarray] = []
    bulges: list[float] = []
    spans = [(t0, t1, 0)]
    while spans:
        a, b, depth = spans.pop()
        inner = np.linspace(a, b, SAMPLES + 2)
        points, tangents = curve(inner)
        arcs = biarc(points[0], tangents[0], points[-1], tangents[-1])
        if arcs is not None:
            junction, first, second = arcs
            error = np.minimum(distance_to_arc(points[1:-1], points[0], junction, first),
                               distance_to_arc(points[1:-1], junction, points[-1], second)).max()
            if error <= MARGIN * tolerance:
                vertices += [points[0], junction]
                bulges += [first, second]
                continue
        if depth >= MAX_DEPTH:
            raise DesignError(f"a curve of the outline could not be fitted with arcs within {tolerance:g} mm")
        middle = (a + b) / 2.0
        spans += [(middle, b, depth + 1), (a, middle, depth + 1)]     # the first half is taken next
    return np.array(vertices), np.array(bulges)
