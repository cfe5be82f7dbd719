"""The project's one STL writer: binary STL, written with numpy (no mesh library loaded on a build)."""
from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from camgen.core.solids import Mesh, face_normals

_FACET = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attributes", "<u2")])


def stl_bytes(mesh: Mesh) -> bytes:
    """``mesh`` as binary STL: an empty 80-byte header, the triangle count, and each triangle's unit normal and
    corners in single precision (the bytes trimesh writes for the same mesh).

    Parameters
    ----------
    mesh : Mesh
        A triangle mesh (mm), its faces wound counter-clockwise seen from outside.

    Returns
    -------
    bytes
        The file's bytes (mm: STL has no units).
    """
    facets = np.zeros(len(mesh.faces), dtype=_FACET)
    facets["normal"] = face_normals(mesh)
    facets["vertices"] = mesh.vertices[mesh.faces]
    return bytes(80) + np.uint32(len(mesh.faces)).astype("<u4").tobytes() + facets.tobytes()


def write_stl(mesh: Mesh, path: Path, options: Any = None) -> None:
    path.write_bytes(stl_bytes(mesh))


WRITERS = {"stl": write_stl}
