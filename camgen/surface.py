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
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    best = np.full(len(points), np.inf)
    for i, seg in enumerate(cam.program.segments):
        aux = np.linspace(seg.start, seg.end, 257)
        length = float(np.linalg.norm(np.diff(cam.segment_pitch(i, aux).point, axis=0), axis=1).sum())
        grid = np.linspace(seg.start, seg.end, max(_COARSE_MIN, int(length / _COARSE_MM) + 2))
        coarse = cam.segment_pitch(i, grid).point
        theta = np.empty(len(points))
        for lo in range(0, len(points), 4096):
            chunk = points[lo:lo + 4096]
            d2 = ((chunk[:, None, :] - coarse[None, :, :]) ** 2).sum(axis=2)
            theta[lo:lo + 4096] = grid[np.argmin(d2, axis=1)]
        for _ in range(_NEWTON_STEPS):
            g = cam.segment_pitch(i, theta)
            diff = g.point - points
            f1 = (diff * g.d1).sum(axis=1)
            f2 = (g.d1 * g.d1).sum(axis=1) + (diff * g.d2).sum(axis=1)
            step = np.where(f2 > 0, f1 / np.where(f2 > 0, f2, 1.0), 0.0)
            theta = np.clip(theta - step, seg.start, seg.end)
        dist = np.linalg.norm(cam.segment_pitch(i, theta).point - points, axis=1)
        best = np.minimum(best, dist)
    segments = cam.program.segments
    for i, jump in cam.steps():                        # a flat face's flats: the face line between two contacts
        if jump > 0:
            j = (i + 1) % len(segments)
            a = cam.segment_pitch(i, segments[i].end).point[0]
            b = cam.segment_pitch(j, segments[j].start).point[0]
            t = np.clip((points - a) @ (b - a) / float((b - a) @ (b - a)), 0.0, 1.0)
            best = np.minimum(best, np.linalg.norm(a + t[:, None] * (b - a) - points, axis=1))
    return best


def surface_deviation(cam: Cam, points: np.ndarray, offset: float = 0.0) -> np.ndarray:
    """Deviation (mm) of points from the exact cam surface moved out by ``offset`` mm: their distance to the pitch
    curve less the surface's, |contact radius - offset|.

    Where the surface lies inside the pitch curve (a roller, less half a kerf) it is signed:
    negative outside the cam (towards the roller), positive into the material. Where it lies
    outside (a knife edge or flat face moved out by half a kerf) the sign is the other way
    round, and with no offset it is the plain distance, never negative.
    """
    return pitch_distance(cam, points) - abs(cam.contact_radius - offset)
