"""The project's one STL writer (binary STL, via trimesh), and the mesh checks users' slicers make."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from camgen.parts.mesh import Mesh


@dataclass(frozen=True)
class MeshCheck:
    """What trimesh says of a mesh: closed, consistently wound, outward, and its volume (mm^3)."""

    watertight: bool
    winding_consistent: bool
    volume_mm3: float
    triangles: int

    @property
    def ok(self) -> bool:
        return self.watertight and self.winding_consistent and self.volume_mm3 > 0


def trimesh_of(mesh: Mesh) -> Any:
    """``mesh`` as a trimesh.Trimesh (trimesh is imported here, lazily)."""
    import trimesh

    return trimesh.Trimesh(vertices=mesh.vertices, faces=mesh.faces, process=False)


def check_mesh(mesh: Mesh) -> MeshCheck:
    """Check ``mesh`` with trimesh (positive volume means outward normals)."""
    tm = trimesh_of(mesh)
    return MeshCheck(bool(tm.is_watertight), bool(tm.is_winding_consistent), float(tm.volume), len(tm.faces))


def stl_bytes(mesh: Mesh) -> bytes:
    """``mesh`` as binary STL."""
    return trimesh_of(mesh).export(file_type="stl")

