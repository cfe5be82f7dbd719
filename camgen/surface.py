"""Distance from points to the exact cam surface, for measuring exported outlines.

The exact surface is the envelope of the roller: the points at distance Rr from
the pitch curve (on the cam's side). So a point's deviation from the surface is its
distance to the pitch curve minus Rr. This holds for undercut envelopes too, and it
uses nothing of the outline code, so it checks that code independently.
"""
from __future__ import annotations

import numpy as np

from camgen.cam import Cam

#: spacing of the coarse pitch samples that start the Newton refinement (mm), and their least number a segment
_COARSE_MM = 0.25
_COARSE_MIN = 64
_NEWTON_STEPS = 8


def pitch_distance(cam: Cam, points: np.ndarray) -> np.ndarray:
    """Distance (mm) from each of ``points`` (n, 2) to the exact pitch curve.

    For each segment: the nearest of a coarse sample every 0.25 mm along the curve, then Newton's method on
    (P(theta) - X) . P'(theta) = 0 within the segment; the smallest over segments, and over the straight
    flats where a flat face's contact jumps (see :meth:`Cam.steps`).

    A segment is measured only for the points it could bring closer: each point first against the segment whose
    box (its samples' bounding box grown by their largest spacing, which holds the whole stretch of curve) lies
    nearest, then against every other segment whose box lies no farther than that distance. The rest cannot
    lower the smallest distance, so the result is that of measuring every point against every segment; every
    segment's points are evaluated in one call (:meth:`Cam.pitch_of`, each point's numbers its own).
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    segments = cam.program.segments
    m = len(segments)
    start = np.fromiter((seg.start for seg in segments), float, m)
    end = np.fromiter((seg.end for seg in segments), float, m)
    every = np.arange(m)
    aux = np.linspace(start, end, 257, axis=1)                         # (m, 257)
    aux_points = _pitch(cam, np.repeat(every, 257), aux.ravel()).reshape(m, 257, 2)
    length = np.linalg.norm(np.diff(aux_points, axis=1), axis=2).sum(axis=1)
    grids = [np.linspace(seg.start, seg.end, max(_COARSE_MIN, int(float(length[i]) / _COARSE_MM) + 2))
             for i, seg in enumerate(segments)]
    counts = np.array([len(g) for g in grids])
    flat = _pitch(cam, np.repeat(every, counts), np.concatenate(grids))
    coarse = np.split(flat, np.cumsum(counts)[:-1])
    low = np.array([c.min(axis=0) - _spacing(c) for c in coarse]).reshape(m, 2)
    high = np.array([c.max(axis=0) + _spacing(c) for c in coarse]).reshape(m, 2)
    best = np.full(len(points), np.inf)
    rows = max(1, 2**21 // max(m, 1))                  # points at a time: their distances to every box
    for first in range(0, len(points) if m else 0, rows):
        chunk = points[first:first + rows]
        box = np.linalg.norm(np.maximum(np.maximum(low - chunk[:, None, :], chunk[:, None, :] - high), 0.0), axis=2)
        nearest = np.argmin(box, axis=1)
        here = np.arange(len(chunk))
        mine = _distance(cam, grids, coarse, start, end, nearest, chunk)   # an upper bound: the nearest box's
        box[here, nearest] = np.inf
        point, other = np.nonzero(box <= mine[:, None])   # every other segment that could come closer
        closer = _distance(cam, grids, coarse, start, end, other, chunk[point])
        out = mine.copy()
        np.minimum.at(out, point, closer)
        best[first:first + rows] = out
    for i, jump in cam.steps():                        # a flat face's flats: the face line between two contacts
        if jump > 0:
            j = (i + 1) % len(segments)
            a = cam.segment_pitch(i, segments[i].end).point[0]
            b = cam.segment_pitch(j, segments[j].start).point[0]
            t = np.clip((points - a) @ (b - a) / float((b - a) @ (b - a)), 0.0, 1.0)
            best = np.minimum(best, np.linalg.norm(a + t[:, None] * (b - a) - points, axis=1))
    return best


def _pitch(cam: Cam, index: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Pitch points (n, 2) at cam angles ``theta`` (n,) (radians) each on its segment ``index`` (n,)."""
    [g] = cam.pitch_of([(index, theta, False)])
    return g.point


def _spacing(c: np.ndarray) -> float:
    """The largest distance (mm) between neighbouring samples ``c`` (n, 2)."""
    return float(np.linalg.norm(np.diff(c, axis=0), axis=1).max(initial=0.0))


def _distance(cam: Cam, grids: list[np.ndarray], coarse: list[np.ndarray], start: np.ndarray, end: np.ndarray,
              index: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Distance (mm) from each of ``points`` (n, 2) to segment ``index`` (n,)'s stretch of the pitch curve: from
    the nearest of the segment's ``coarse`` samples (at its cam angles ``grids``, rad), Newton's method within the
    segment (``start`` to ``end``, rad, every segment's)."""
    theta = np.empty(len(points))
    order = np.argsort(index, kind="stable")
    bounds = np.searchsorted(index[order], np.arange(len(grids) + 1))
    for i in np.flatnonzero(np.diff(bounds)):
        for lo in range(bounds[i], bounds[i + 1], 4096):
            sel = order[lo:min(lo + 4096, bounds[i + 1])]
            d2 = ((points[sel, None, :] - coarse[i][None, :, :]) ** 2).sum(axis=2)
            theta[sel] = grids[i][np.argmin(d2, axis=1)]
    lo, hi = start[index], end[index]
    for _ in range(_NEWTON_STEPS):
        [g] = cam.pitch_of([(index, theta, False)])
        diff = g.point - points
        f1 = (diff * g.d1).sum(axis=1)
        f2 = (g.d1 * g.d1).sum(axis=1) + (diff * g.d2).sum(axis=1)
        step = np.where(f2 > 0, f1 / np.where(f2 > 0, f2, 1.0), 0.0)
        theta = np.clip(theta - step, lo, hi)
    return np.linalg.norm(_pitch(cam, index, theta) - points, axis=1)


def surface_deviation(cam: Cam, points: np.ndarray, offset: float = 0.0) -> np.ndarray:
    """Deviation (mm) of points from the exact cam surface moved out by ``offset`` mm: their distance to the pitch
    curve less the surface's, |contact radius - offset|.

    Where the surface lies inside the pitch curve (a roller, less half a kerf) it is signed:
    negative outside the cam (towards the roller), positive into the material. Where it lies
    outside (a knife edge or flat face moved out by half a kerf) the sign is the other way
    round, and with no offset it is the plain distance, never negative.
    """
    return pitch_distance(cam, points) - abs(cam.contact_radius - offset)
