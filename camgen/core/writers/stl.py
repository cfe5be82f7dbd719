"""The project's one STL writer: binary STL (via trimesh)."""
from __future__ import annotations

from pathlib import Path
from typing import Any

from camgen.core.solids import Mesh, trimesh_of


def stl_bytes(mesh: Mesh) -> bytes:
    """``mesh`` as binary STL."""
    return trimesh_of(mesh).export(file_type="stl")


def write_stl(mesh: Mesh, path: Path, options: Any = None) -> None:
    path.write_bytes(stl_bytes(mesh))


WRITERS = {"stl": write_stl}
