"""Solids from parts: a plate part extruded to its thickness with manifold3d.

Arcs and circles become chords within the part's tolerance, so the mesh has no
more triangles than that tolerance needs. manifold3d guarantees a closed,
consistently oriented (outward) two-manifold.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import ExportError
from camgen.core.parts import Part
from camgen.core.shapes import Circle, arc_steps


@dataclass(frozen=True)
class Mesh:
    """A triangle mesh in mm: ``vertices`` (n, 3) and ``faces`` (m, 3), outward (counter-clockwise) faces, and the
    name of the part it is (3MF files carry it, so a slicer lists the part by name)."""

    vertices: np.ndarray
    faces: np.ndarray
    name: str = "part"


def _ccw(points: np.ndarray, ccw: bool) -> np.ndarray:
    x, y = points[:, 0], points[:, 1]
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    return points if (area > 0) == ccw else points[::-1]


def extrude(part: Part) -> Mesh:
    """The part as a solid from z = 0 to z = thickness, holes cut through (see :func:`_solid`)."""
    return _mesh(_solid(part), part.name)


def stack(parts: Sequence[Part], name: str) -> Mesh:
    """The parts as one solid named ``name``: each extruded (see :func:`extrude`) and set on the one before it,
    the first from z = 0 (a Geneva driver: the crank with the locking disc on top)."""
    solid, z = None, 0.0
    for part in parts:
        piece = _solid(part).translate((0.0, 0.0, z))
        solid, z = piece if solid is None else solid + piece, z + part.thickness
    return _mesh(solid, name)


def carve(part: Part, vertices: np.ndarray, faces: np.ndarray, name: str) -> Mesh:
    """The part extruded (see :func:`extrude`) less a closed cutter: ``vertices`` (n, 3) mm and ``faces`` (m, 3),
    a two-manifold triangle mesh (a barrel cam's groove). Raises :class:`ExportError` when the cutter is not a
    closed solid or the result is empty."""
    import manifold3d

    verts = np.asarray(vertices, dtype=np.float32)
    tris = np.asarray(faces, dtype=np.uint32)
    cutter = manifold3d.Manifold(manifold3d.Mesh(vert_properties=verts, tri_verts=tris))
    if cutter.status() != manifold3d.Error.NoError:
        raise ExportError(f"{name}: the cutter is not a closed solid ({cutter.status()})")
    solid = _solid(part) - cutter
    if solid.status() != manifold3d.Error.NoError or solid.is_empty():
        raise ExportError(f"{name}: could not build a solid ({solid.status()})")
    return _mesh(solid, name)


def volume_check(parts: Sequence[Part], volume_mm3: float) -> dict[str, float]:
    """A solid's volume (mm^3) against its parts' exact one, each part's area x thickness less its pockets' area x
    depth (exact for the arcs; no boss), and the bound the chords allow: a chord within the tolerance t of its arc
    moves a section's area by less than t a unit of the arc's length, so the volume by less than t x (each
    contour's length x its height). Raises :class:`ExportError` when the solid is further off than that."""
    expected = bound = 0.0
    for part in parts:
        tol = part.tolerance
        expected += part.area * part.thickness - sum(p.area * p.depth for p in part.pockets)
        bound += tol * sum(_length(c, tol) for c in (part.outline, *part.holes)) * part.thickness
        bound += tol * sum(_length(c, tol) * p.depth for p in part.pockets for c in p.contours)
    if not abs(volume_mm3 - expected) <= bound:
        raise ExportError(f"{parts[0].name}: the solid's volume {volume_mm3:.6g} mm^3 differs from the exact "
                          f"{expected:.6g} mm^3 by more than the tolerance allows ({bound:.3g} mm^3)")
    return {"volume_expected_mm3": round(expected, 6), "volume_error_mm3": round(volume_mm3 - expected, 9),
            "volume_bound_mm3": round(bound, 9)}


def _length(shape: Any, tolerance: float) -> float:
    """The length (mm) of a closed shape's chords within ``tolerance``."""
    ring = shape.flatten(tolerance)
    return float(np.linalg.norm(ring - np.roll(ring, 1, axis=0), axis=1).sum())


def _solid(part: Part) -> Any:
    """The part as a manifold3d solid from z = 0 to z = thickness, holes cut through.

    A hub boss stands on the top face round the first hole (the bore), to
    z = thickness + boss height, and a radial set-screw hole runs from the bore
    through the boss along +Y at the boss's mid-height. Each pocket is cut ``depth`` mm down from the top face.
    """
    import manifold3d

    tol = part.tolerance
    polygons = [_ccw(part.outline.flatten(tol), True)] + [_ccw(h.flatten(tol), False) for h in part.holes]
    section = manifold3d.CrossSection(polygons, manifold3d.FillRule.Positive)
    solid = manifold3d.Manifold.extrude(section, part.thickness)
    if part.boss is not None:
        diameter, height = part.boss
        ring = [_ccw(Circle((0.0, 0.0), diameter / 2).flatten(tol), True)]
        ring += [_ccw(part.holes[0].flatten(tol), False)] if part.holes else []
        boss = manifold3d.Manifold.extrude(manifold3d.CrossSection(ring, manifold3d.FillRule.Positive), height)
        solid = solid + boss.translate((0.0, 0.0, part.thickness))
        if part.set_screw > 0:
            r = part.set_screw / 2
            screw = manifold3d.Manifold.cylinder(diameter, r, r, arc_steps(r, 2 * np.pi, tol))
            screw = screw.rotate((-90.0, 0.0, 0.0)).translate((0.0, 0.0, part.thickness + height / 2))
            solid = solid - screw
    for pocket in part.pockets:                   # cut from the pocket's floor to 1 mm above the top face
        rings = [_ccw(c.flatten(tol), k == 0) for k, c in enumerate(pocket.contours)]
        cutter = manifold3d.Manifold.extrude(manifold3d.CrossSection(rings, manifold3d.FillRule.Positive),
                                             pocket.depth + 1.0)
        solid = solid - cutter.translate((0.0, 0.0, part.thickness - pocket.depth))
    if solid.status() != manifold3d.Error.NoError or solid.is_empty():
        raise ExportError(f"{part.name}: could not build a solid ({solid.status()})")
    return solid


def pin(diameter: float, length: float, tolerance: float) -> Mesh:
    """A pin: a shank of ``diameter`` and ``length`` (mm) under a head 1.8 x as wide and half a diameter high."""
    import manifold3d

    r, head = diameter / 2, 0.9 * diameter
    shank = manifold3d.Manifold.cylinder(length, r, r, arc_steps(r, 2 * np.pi, tolerance))
    cap = manifold3d.Manifold.cylinder(diameter / 2, head, head, arc_steps(head, 2 * np.pi, tolerance))
    return _mesh(shank + cap.translate((0.0, 0.0, length)), "pin")


def spacer(inner: float, outer: float, height: float, tolerance: float) -> Mesh:
    """A spacer: a tube of ``inner`` and ``outer`` diameter and ``height`` (mm), to fill the layers a pin crosses
    between the two parts it joins."""
    import manifold3d

    ro, ri = outer / 2, inner / 2
    tube = manifold3d.Manifold.cylinder(height, ro, ro, arc_steps(ro, 2 * np.pi, tolerance))
    bore = manifold3d.Manifold.cylinder(height + 2.0, ri, ri, arc_steps(ri, 2 * np.pi, tolerance)).translate(
        (0.0, 0.0, -1.0))
    return _mesh(tube - bore, "spacer")


def _mesh(solid: Any, name: str) -> Mesh:
    """A manifold3d solid as a :class:`Mesh` named ``name``."""
    mesh = solid.to_mesh()
    return Mesh(np.asarray(mesh.vert_properties)[:, :3].astype(float), np.asarray(mesh.tri_verts, dtype=np.int64),
                name)


@dataclass(frozen=True)
class MeshCheck:
    """What the check of a mesh found (closed, consistently wound, outward, its volume in mm^3), and whether its
    vertices stay apart in the files' single precision."""

    watertight: bool
    winding_consistent: bool
    volume_mm3: float
    triangles: int
    #: no two vertices fall on one point once rounded to the single precision STL and 3MF readers load
    distinct_in_float32: bool = True

    @property
    def ok(self) -> bool:
        return self.watertight and self.winding_consistent and self.volume_mm3 > 0 and self.distinct_in_float32


def trimesh_of(mesh: Mesh) -> Any:
    """``mesh`` as a trimesh.Trimesh, for the tests' thorough checks (trimesh is imported here, lazily)."""
    import trimesh

    return trimesh.Trimesh(vertices=mesh.vertices, faces=mesh.faces, process=False)


def _crosses(mesh: Mesh) -> tuple[np.ndarray, np.ndarray]:
    """Each triangle's corners (n, 3, 3) and the cross product of its first two edges (n, 3)."""
    corners = mesh.vertices[mesh.faces]
    edges = corners[:, 1:, :] - corners[:, :2, :]
    return corners, np.cross(edges[:, 0], edges[:, 1])


def face_normals(mesh: Mesh) -> np.ndarray:
    """Each triangle's outward unit normal (n, 3); zero for a triangle of no area (as trimesh makes them)."""
    _, crosses = _crosses(mesh)
    norm = np.sqrt(np.dot(crosses * crosses, [1.0, 1.0, 1.0]))
    valid = norm > 100 * np.finfo(np.float64).resolution
    norm[valid] **= -1
    return np.where(valid[:, None], crosses * norm.reshape((-1, 1)), 0.0)


def check_mesh(mesh: Mesh) -> MeshCheck:
    """Check ``mesh`` with numpy alone: closed (every edge shared by exactly two triangles), consistently wound (the
    two run each shared edge in opposite directions), outward (a positive volume, the divergence theorem's sum over
    the triangles) and its vertices distinct in single precision. manifold3d guarantees a closed, outward
    two-manifold; this confirms the mesh as written (the tests also check the files with trimesh)."""
    corners, crosses = _crosses(mesh)
    f = np.asarray(mesh.faces, dtype=np.int64)
    count = max(len(mesh.vertices), 1)
    start, end = f.ravel(), f[:, [1, 2, 0]].ravel()
    shared = np.sort(np.minimum(start, end) * count + np.maximum(start, end))
    watertight = bool(shared.size % 2 == 0 and np.all(shared[0::2] == shared[1::2])
                      and np.all(shared[1:-1:2] != shared[2::2]))
    directed = np.sort(start * count + end)
    consistent = watertight and bool(np.all(directed[1:] != directed[:-1]))
    total = corners[:, 0, :] + corners[:, 1, :] + corners[:, 2, :]
    volume = float((crosses[:, 0] * total[:, 0]).sum() / 6.0)
    single = mesh.vertices.astype(np.float32)
    ordered = single[np.lexsort(single.T[::-1])]
    distinct = not bool(np.any(np.all(ordered[1:] == ordered[:-1], axis=1)))
    return MeshCheck(watertight, consistent, volume, len(f), distinct)
