"""Biarcs: two tangent-continuous circular arcs joining two points with given tangents.

Pure array geometry (no cams): :func:`biarcs` builds the equal-tangent-length biarc
of each span, and :func:`arc_distance` measures how far points lie from an arc given
LWPOLYLINE-style (start, end, bulge = tan(included angle / 4), counter-clockwise +).
"""
from __future__ import annotations

import numpy as np


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _bulge(start: np.ndarray, end: np.ndarray, tangent: np.ndarray) -> np.ndarray:
    """Bulge of the arc leaving ``start`` along unit ``tangent`` and ending at ``end``: tan(half the turn)."""
    chord = end - start
    half_sweep = np.arctan2(_cross(tangent, chord), (tangent * chord).sum(axis=-1))
    return np.tan(half_sweep / 2.0)


def biarcs(p0: np.ndarray, t0: np.ndarray, p1: np.ndarray, t1: np.ndarray) -> tuple[np.ndarray, ...]:
    """For spans (n, 2) from p0 (unit tangent t0) to p1 (unit tangent t1): junctions (n, 2) and both bulges (n,).

    The equal-tangent-length biarc: with v = p1 - p0 and t = t0 + t1, d solves
    2 (1 - t0.t1) d^2 + 2 (v.t) d - v.v = 0; the arcs meet at the midpoint of
    p0 + d t0 and p1 - d t1 with the tangent along that segment.
    """
    v = p1 - p0
    t = t0 + t1
    vt, vv = (v * t).sum(axis=1), (v * v).sum(axis=1)
    denom = 2.0 * (1.0 - (t0 * t1).sum(axis=1))
    with np.errstate(divide="ignore", invalid="ignore"):
        general = (-vt + np.sqrt(vt**2 + denom * vv)) / denom
        parallel = vv / (2.0 * vt)
    d = np.where(denom > 1e-12, general, parallel)
    q0, q1 = p0 + d[:, None] * t0, p1 - d[:, None] * t1
    junction = 0.5 * (q0 + q1)
    tj = q1 - q0
    tj = tj / np.linalg.norm(tj, axis=1)[:, None]
    return junction, _bulge(p0, junction, t0), _bulge(junction, p1, tj)


def arc_distance(points: np.ndarray, start: np.ndarray, end: np.ndarray, bulge: np.ndarray) -> np.ndarray:
    """Distance of points (n, k, 2) from the arcs (n, 2), (n, 2), (n,): k points measured against each arc."""
    chord = end - start
    length = np.linalg.norm(chord, axis=1)
    sweep = 4.0 * np.arctan(bulge)
    straight = np.abs(bulge) < 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        h = np.where(straight, 0.0, length / (2.0 * np.tan(sweep / 2.0)))
    unit = chord / np.where(length > 0, length, 1.0)[:, None]
    centre = 0.5 * (start + end) + np.column_stack([-unit[:, 1], unit[:, 0]]) * h[:, None]
    radius = np.where(straight, np.inf, length / (2.0 * np.abs(np.sin(sweep / 2.0))))
    rel = points - centre[:, None, :]
    a0 = np.arctan2(start[:, 1] - centre[:, 1], start[:, 0] - centre[:, 0])
    ang = np.arctan2(rel[..., 1], rel[..., 0]) - a0[:, None]
    ang = np.where(sweep[:, None] >= 0, np.mod(ang, 2 * np.pi), -np.mod(-ang, 2 * np.pi))
    within = np.abs(ang) <= np.abs(sweep)[:, None]
    on_circle = np.abs(np.linalg.norm(rel, axis=2) - radius[:, None])
    ends = np.minimum(np.linalg.norm(points - start[:, None, :], axis=2),
                      np.linalg.norm(points - end[:, None, :], axis=2))
    # a straight piece: distance to the segment
    t = np.clip(((points - start[:, None, :]) * chord[:, None, :]).sum(axis=2)
                / np.where(length > 0, length**2, 1.0)[:, None], 0.0, 1.0)
    seg = np.linalg.norm(start[:, None, :] + t[..., None] * chord[:, None, :] - points, axis=2)
    return np.where(straight[:, None], seg, np.where(within, on_circle, ends))
