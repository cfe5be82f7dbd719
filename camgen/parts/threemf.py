"""The project's one 3MF writer (via trimesh; millimetres, 3MF's default unit)."""
from __future__ import annotations

from camgen.parts.mesh import Mesh
from camgen.parts.stl import trimesh_of


def threemf_bytes(mesh: Mesh) -> bytes:
    """``mesh`` as a 3MF package."""
    return trimesh_of(mesh).export(file_type="3mf")
