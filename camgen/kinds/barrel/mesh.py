"""A barrel cam's carved mesh as the files hold it: no edge shorter than a few steps of single precision.

The cut of the groove's tube through the blank's rim puts a vertex wherever an edge of one crosses a face of the
other, and the two meshes are laid out independently, so now and then two of those crossings fall a few
micrometres apart or less (some 2 edges under 1.5e-5 mm for barrel-conical.toml at 1e-4 mm). Rounded to single
precision (a step of 3.8e-6 mm from 32 to 64 mm) such an edge turns or vanishes, and a needle triangle on it may
fold over its neighbour: a self-intersection in the STL. :func:`without_short_edges` collapses each edge shorter
than the bound, as the file rounds it, into its earlier end (an exact point of the cut, so the surface moves by
less than the edge's length) and drops the two triangles on it, then checks what is left: no edge under the bound,
and no triangle turned over, or made flat, by the collapse or by the rounding (closed and outward: the caller's
one :func:`camgen.core.solids.check_mesh` of the mesh it writes).
"""
from __future__ import annotations

import numpy as np

from camgen.core.solids import Mesh

#: the shortest edge the files hold, in steps of single precision at the cam's size (the larger of the rim's radius
#: and the length): rounding moves each end by under 0.87 of a step, so such an edge keeps its sense
SHORTEST_STEPS = 4
#: how many rounds of collapses (a collapse may shorten a neighbouring edge)
_ROUNDS = 4


def _edges(faces: np.ndarray) -> np.ndarray:
    """The mesh's edges (k, 2), each once, its lower vertex first."""
    pairs = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    count = int(faces.max(initial=0)) + 1
    key = np.sort(pairs[:, 0].astype(np.int64) * count + pairs[:, 1])
    key = key[np.r_[True, key[1:] != key[:-1]]]                    # (numpy's unique hashes: slower here)
    return np.stack([key // count, key % count], axis=1)


def _rounded(vertices: np.ndarray) -> np.ndarray:
    """The vertices as the files hold them: rounded to single precision."""
    return np.asarray(vertices, dtype=np.float32).astype(np.float64)


def shortest_edge(mesh: Mesh) -> float:
    """The length (mm) of the mesh's shortest edge once its vertices are rounded to single precision."""
    edges = _edges(mesh.faces)
    held = _rounded(mesh.vertices)
    return float(np.linalg.norm(held[edges[:, 0]] - held[edges[:, 1]], axis=1).min(initial=np.inf))


def _normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Each triangle's cross product of its first two edges (k, 3): its normal times twice its area."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return np.cross(b - a, c - a)


def _root(into: dict[int, int], vertex: int) -> int:
    """Where ``vertex`` ends up, following ``into`` (each collapsed vertex to the one it went into)."""
    while vertex in into:
        vertex = into[vertex]
    return vertex


def without_short_edges(mesh: Mesh, shortest: float) -> Mesh | None:
    """``mesh`` with every edge shorter than ``shortest`` (mm, as single precision rounds it) collapsed into its
    earlier end and the triangles on it dropped (the mesh itself when there is none), checked: no edge under
    ``shortest``, every triangle a collapse moved facing as it did, and every triangle still facing so once rounded
    (its rounded normal within 90 degrees of its exact one, and not of zero area). None where that check fails
    (another layout of the cut is needed). Whether what is left is a closed, outward solid whose vertices stay apart
    in single precision is :func:`camgen.core.solids.check_mesh`'s to say: the caller checks the mesh it writes
    once, whichever this returns."""
    vertices, faces = np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces)
    held = _rounded(vertices)
    before = _normals(vertices, faces)
    keep = np.arange(len(vertices))                  # the vertex each one's faces hold once collapsed
    for _ in range(_ROUNDS):
        edges = _edges(faces)
        short = edges[np.linalg.norm(held[edges[:, 0]] - held[edges[:, 1]], axis=1) < shortest]
        if not short.size:
            break
        into: dict[int, int] = {}                   # the later end (and what went into it) into the earlier
        for low, high in short.tolist():
            first, later = sorted((_root(into, low), _root(into, high)))
            if first != later:
                into[later] = first
        moved = np.array(sorted(into), dtype=np.int64)
        keep[moved] = [_root(into, v) for v in moved.tolist()]
        faces = keep[faces]
        flat = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])
        faces, before = faces[~flat], before[~flat]
        if not len(faces):
            return None
    else:
        return None
    exact = _normals(vertices, faces)
    if not (np.all(np.einsum("ij,ij->i", exact, before) > 0)
            and np.all(np.einsum("ij,ij->i", _normals(held, faces), exact) > 0)):
        return None
    if faces.shape == mesh.faces.shape:
        return mesh
    used = np.zeros(len(vertices), dtype=bool)
    used[faces.ravel()] = True
    return Mesh(vertices[used], (np.cumsum(used) - 1)[faces], mesh.name)
