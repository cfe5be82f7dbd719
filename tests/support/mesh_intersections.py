"""A check of a triangle mesh for self-intersection, for the tests.

The candidates are every two faces that share a corner (pymeshlab passes those over, so it misses a sliver folded
onto its neighbour) and the faces pymeshlab's ``compute_selection_by_self_intersections_per_face`` selects, each
with every face whose bounding box meets its own; each pair is then decided by the separating-axis test over
the 17 directions that decide it (the two normals, the nine cross products of an edge of one with an edge of the
other, and the six in-plane normals of the edges, which decide coplanar pairs); two triangles intersect when no
direction separates them (touching counts). Neighbours, which share a corner or an edge, are shrunk towards their
centroids by a part in a million first, so that only a fold or a crossing beyond what they share counts.
pymeshlab's filter alone also selects coplanar triangles that neither overlap nor touch (long thin ones on a
cylinder's facet, 0.014 mm apart, which it selects even as a mesh of those two alone), hence the second test.
"""
from __future__ import annotations

import numpy as np

#: how much neighbours shrink towards their centroids (a fraction of their size)
SHRINK = 1e-6


def _separated(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """For triangles p and q (k, 3, 3): whether some direction separates them strictly."""
    ep, eq = np.roll(p, -1, axis=1) - p, np.roll(q, -1, axis=1) - q
    np_, nq = np.cross(ep[:, 0], ep[:, 1]), np.cross(eq[:, 0], eq[:, 1])
    axes = [np_, nq]
    axes += [np.cross(ep[:, i], eq[:, j]) for i in range(3) for j in range(3)]
    axes += [np.cross(np_, ep[:, i]) for i in range(3)] + [np.cross(nq, eq[:, i]) for i in range(3)]
    scale = (np.abs(p).max(axis=(1, 2)) + np.abs(q).max(axis=(1, 2))) ** 2
    apart = np.zeros(len(p), dtype=bool)
    for axis in axes:
        length = np.linalg.norm(axis, axis=1)
        usable = length > 1e-14 * scale                  # a direction only where it is one
        u = axis / np.where(usable, length, 1.0)[:, None]
        sp, sq = np.einsum("kvi,ki->kv", p, u), np.einsum("kvi,ki->kv", q, u)
        apart |= usable & ((sp.max(axis=1) < sq.min(axis=1)) | (sq.max(axis=1) < sp.min(axis=1)))
    return apart


def flagged(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """The faces pymeshlab's ``compute_selection_by_self_intersections_per_face`` selects (indices)."""
    import pymeshlab

    meshes = pymeshlab.MeshSet()
    meshes.add_mesh(pymeshlab.Mesh(vertex_matrix=np.asarray(vertices, dtype=np.float64),
                                   face_matrix=np.asarray(faces, dtype=np.int32)))
    meshes.compute_selection_by_self_intersections_per_face()
    return np.flatnonzero(meshes.current_mesh().face_selection_array())


def _neighbours(faces: np.ndarray) -> np.ndarray:
    """The pairs of faces (k, 2) that share a corner (or an edge), each once."""
    corner = faces.ravel()
    owner = np.repeat(np.arange(len(faces)), 3)
    order = np.argsort(corner, kind="stable")
    corner, owner = corner[order], owner[order]
    starts = np.flatnonzero(np.r_[True, corner[1:] != corner[:-1]])
    sizes = np.diff(np.r_[starts, len(corner)])
    later = np.repeat(np.r_[starts[1:], len(corner)], sizes) - np.arange(len(corner)) - 1
    i = np.repeat(np.arange(len(corner)), later)
    j = i + 1 + (np.arange(later.sum()) - np.repeat(np.cumsum(later) - later, later))
    a, b = owner[i], owner[j]
    return np.unique(np.stack([np.minimum(a, b), np.maximum(a, b)], axis=1), axis=0)


def self_intersections(vertices: np.ndarray, faces: np.ndarray, chunk: int = 200_000) -> np.ndarray:
    """The pairs of triangles (k, 2) of the mesh that intersect beyond the corners and edges they share, by the
    separating-axis test: every pair of neighbours (a fold), and each face pymeshlab flags (:func:`flagged`) with
    every face whose bounding box meets its own."""
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces)
    tri = v[f]
    lo, hi = tri.min(axis=1), tri.max(axis=1)
    pairs = [_neighbours(f)]
    pairs += [np.stack([np.full(len(near), k), near], axis=1)
              for k in flagged(v, f)
              for near in [np.flatnonzero(np.all((lo <= hi[k]) & (lo[k] <= hi), axis=1) & (np.arange(len(f)) != k))]]
    pairs = np.unique(np.sort(np.concatenate(pairs), axis=1), axis=0)
    found = []
    for start in range(0, len(pairs), chunk):
        part = pairs[start:start + chunk]
        p, q = tri[part[:, 0]].copy(), tri[part[:, 1]].copy()
        shared = (f[part[:, 0]][:, :, None] == f[part[:, 1]][:, None, :]).any(axis=(1, 2))
        for t in (p, q):
            centre = t.mean(axis=1, keepdims=True)
            t[shared] = centre[shared] + (t[shared] - centre[shared]) * (1 - SHRINK)
        found.append(part[~_separated(p, q)])
    return np.concatenate(found) if found else np.zeros((0, 2), dtype=np.int64)
