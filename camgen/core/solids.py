"""Solids from parts: a plate part extruded to its thickness with manifold3d.

Arcs and circles become chords within the part's tolerance, so the mesh has no
more triangles than that tolerance needs. manifold3d guarantees a closed,
consistently oriented (outward) two-manifold.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from camgen.core.errors import DesignError, ExportError
from camgen.core.parts import Part
from camgen.core.shapes import Circle, arc_steps


@dataclass(frozen=True)
class Mesh:
    """A triangle mesh in mm: ``vertices`` (n, 3) and ``faces`` (m, 3), outward (counter-clockwise) faces, the
    name of the part it is (3MF files carry it, so a slicer lists the part by name), and whether a slicer prints it
    (a 3MF's build item says so: bought parts shown in an assembly are not printed)."""

    vertices: np.ndarray
    faces: np.ndarray
    name: str = "part"
    printable: bool = True


def _ccw(points: np.ndarray, ccw: bool) -> np.ndarray:
    x, y = points[:, 0], points[:, 1]
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    return points if (area > 0) == ccw else points[::-1]


def extrude(part: Part) -> Mesh:
    """The part as a solid from z = 0 to z = thickness, holes cut through (see :func:`_solid`), its bed face
    chamfered by ``part.elephant_foot`` (see :func:`elephant_foot`).

    Parameters
    ----------
    part : Part
        A flat part (mm): its outline, holes, thickness, and any boss, set screw, pockets and chamfer.

    Returns
    -------
    Mesh
        A closed, outward triangle mesh (mm) named after the part.

    Raises
    ------
    DesignError
        Naming ``output.elephant_foot``: a chamfer not smaller than the thickness, or one that closes up the bed
        face.
    """
    return _mesh(_solid(part), part.name)


def stack(parts: Sequence[Part], name: str) -> Mesh:
    """The parts as one solid named ``name``: each extruded (see :func:`extrude`) and set on the one before it,
    the first from z = 0 (a Geneva driver: the crank with the locking disc on top); only the first, on the bed,
    gets its elephant-foot chamfer."""
    solid, z = None, 0.0
    for k, part in enumerate(parts):
        piece = _solid(part if k == 0 else replace(part, elephant_foot=0.0)).translate((0.0, 0.0, z))
        solid, z = piece if solid is None else solid + piece, z + part.thickness
    return _mesh(solid, name)


def carve(part: Part, vertices: np.ndarray, faces: np.ndarray, name: str) -> Mesh:
    """The part extruded (see :func:`extrude`) less a closed cutter: ``vertices`` (n, 3) mm and ``faces`` (m, 3),
    a two-manifold triangle mesh (a barrel cam's groove), its edges shorter than single precision resolves
    collapsed (:func:`welded`). Raises :class:`ExportError` when the cutter is not a closed solid or the result is
    empty."""
    import manifold3d

    verts = np.asarray(vertices, dtype=np.float32)
    tris = np.asarray(faces, dtype=np.uint32)
    cutter = manifold3d.Manifold(manifold3d.Mesh(vert_properties=verts, tri_verts=tris))
    if cutter.status() != manifold3d.Error.NoError:
        raise ExportError(f"{name}: the cutter is not a closed solid ({cutter.status()})")
    solid = _solid(part) - cutter
    if solid.status() != manifold3d.Error.NoError or solid.is_empty():
        raise ExportError(f"{name}: could not build a solid ({solid.status()})")
    return welded(_mesh(solid, name))


def welded(mesh: Mesh) -> Mesh:
    """``mesh`` with each edge whose two ends fall on one point in single precision collapsed: the later vertex
    merged into the earlier and the triangles on that edge (of no area in the files) dropped, as a reader of the
    STL or 3MF sees it. manifold3d works in double precision and keeps vertices down to its own epsilon apart (a
    subtraction's new vertices where a cutter's edge crosses the blank's a hair from one of its edges, some 1e-6
    mm, while single precision's step is 3.8e-6 mm from 32 to 64 mm), so a finely sampled cut leaves a few such
    edges. The mesh itself when nothing falls together, or when the points that do are not joined by an edge (no
    collapse mends that; :func:`check_mesh` finds them)."""
    single = np.asarray(mesh.vertices, dtype=np.float32)
    _, first, inverse = np.unique(single, axis=0, return_index=True, return_inverse=True)
    keep = first[inverse.ravel()]                 # each vertex's first one on its single-precision point
    gone = np.flatnonzero(keep != np.arange(len(keep)))
    if not gone.size:
        return mesh
    faces = keep[mesh.faces]
    flat = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])
    if not np.all(np.isin(gone, mesh.faces[flat])):
        return mesh
    used = np.ones(len(keep), dtype=bool)
    used[gone] = False
    return Mesh(mesh.vertices[used], (np.cumsum(used) - 1)[faces[~flat]], mesh.name)


def volume_check(parts: Sequence[Part], volume_mm3: float) -> dict[str, float]:
    """A solid's volume (mm^3) against its parts' exact one, each part's area x thickness less its pockets' area x
    depth (exact for the arcs; no boss), and the bound the chords allow: a chord within the tolerance t of its arc
    moves a section's area by less than t a unit of the arc's length, so the volume by less than t x (each
    contour's length x its height); an elephant-foot chamfer takes :func:`foot_volume` of each contour's chords.
    Raises :class:`ExportError` when the solid is further off than that."""
    expected = bound = 0.0
    for part in parts:
        tol = part.tolerance
        expected += part.area * part.thickness - sum(p.area * p.depth for p in part.pockets)
        expected -= sum(foot_volume(ring, part.elephant_foot) for ring in _rings(part)) if part.elephant_foot else 0.0
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
    The bed face (z = 0) is chamfered by ``part.elephant_foot`` (see :func:`elephant_foot`).
    """
    import manifold3d

    tol = part.tolerance
    polygons = _rings(part)
    if part.elephant_foot > 0:
        if part.elephant_foot >= part.thickness:
            raise DesignError(f"output.elephant_foot: must be < the thickness of {part.name}, {part.thickness:g} mm "
                              f"(got {part.elephant_foot:g})")
        solid = elephant_foot(polygons, part.thickness, part.elephant_foot, tol, part.name)
    else:
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


def pin(diameter: float, length: float, tolerance: float, foot: float = 0.0) -> Mesh:
    """A pin: a shank of ``diameter`` and ``length`` (mm) under a head 1.8 x as wide and half a diameter high; the
    shank's end on the bed (z = 0) chamfered by ``foot`` mm (see :func:`elephant_foot`)."""
    import manifold3d

    head = 0.9 * diameter
    # the shank made first: manifold3d orders the union's vertices by the order its solids were made
    shank = _round(diameter, 0.0, length, tolerance, foot, "pin")
    cap = manifold3d.Manifold.cylinder(diameter / 2, head, head, arc_steps(head, 2 * np.pi, tolerance))
    return _mesh(shank + cap.translate((0.0, 0.0, length)), "pin")


def spacer(inner: float, outer: float, height: float, tolerance: float, foot: float = 0.0) -> Mesh:
    """A spacer: a tube of ``inner`` and ``outer`` diameter and ``height`` (mm), to fill the layers a pin crosses
    between the two parts it joins; its end on the bed (z = 0) chamfered by ``foot`` mm (see
    :func:`elephant_foot`)."""
    return _mesh(_round(outer, inner, height, tolerance, foot, "spacer"), "spacer")


def _round(outer: float, inner: float, height: float, tolerance: float, foot: float, name: str) -> Any:
    """A round bar (``inner`` 0) or tube of ``outer`` and ``inner`` diameter and ``height`` (mm) standing on z = 0,
    as a manifold3d solid: its bed end chamfered by ``foot`` mm (:func:`elephant_foot`, on the circles' chords within
    ``tolerance``), else manifold3d's own cylinders (a tube's bore cut 1 mm past either end)."""
    import manifold3d

    ro, ri = outer / 2, inner / 2
    if foot > 0:
        rings = [_ccw(Circle((0.0, 0.0), ro).flatten(tolerance), True)]
        rings += [_ccw(Circle((0.0, 0.0), ri).flatten(tolerance), False)] if ri > 0 else []
        return elephant_foot(rings, height, foot, tolerance, name)
    solid = manifold3d.Manifold.cylinder(height, ro, ro, arc_steps(ro, 2 * np.pi, tolerance))
    if ri > 0:
        solid = solid - manifold3d.Manifold.cylinder(height + 2.0, ri, ri, arc_steps(ri, 2 * np.pi, tolerance)
                                                     ).translate((0.0, 0.0, -1.0))
    return solid


def _rings(part: Part) -> list[np.ndarray]:
    """The part's section as chords within its tolerance: the outline counter-clockwise, the holes clockwise (the
    material on the left of every ring)."""
    tol = part.tolerance
    return [_ccw(part.outline.flatten(tol), True)] + [_ccw(h.flatten(tol), False) for h in part.holes]


def _turns(ring: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each edge's length (mm) and the signed turn (rad) at each vertex of a closed ``ring`` (m, 2): positive where
    it turns left, towards the material on its left (a convex corner), negative at a concave (reflex) one."""
    edges = np.roll(ring, -1, axis=0) - ring
    before = np.roll(edges, 1, axis=0)
    turn = np.arctan2(before[:, 0] * edges[:, 1] - before[:, 1] * edges[:, 0], np.einsum("ij,ij->i", before, edges))
    return np.linalg.norm(edges, axis=1), turn


def _merged(points: np.ndarray, apart: float) -> tuple[np.ndarray, np.ndarray]:
    """The points of a closed ring (m, 2) nearer than ``apart`` (mm) to the one kept before them merged into it:
    each point's index among the kept ones, and the kept points' indices."""
    where = np.zeros(len(points), dtype=np.int64)
    kept = [0]
    for k in range(1, len(points)):
        if np.hypot(*(points[k] - points[kept[-1]])) >= apart:
            kept.append(k)
        where[k] = len(kept) - 1
    if len(kept) > 1 and np.hypot(*(points[kept[-1]] - points[0])) < apart:   # the ring closes on its first point
        where[where == len(kept) - 1] = 0
        kept.pop()
    return where, np.array(kept)


def foot_volume(ring: np.ndarray, size: float) -> float:
    """The volume (mm^3) a 45-degree chamfer of ``size`` mm takes off a prism's bed face along one closed ``ring``
    (m, 2) of its section (the material on the ring's left), while the inset stays free of events (``size`` below
    half the narrowest width and the edges' lengths): the section at height z is the bed section eroded by
    d = size - z, whose area is A - L d + K d^2 (L the ring's length, K the sum of tan(turn / 2) over its convex
    corners, where the inset edges meet in a point, less turn / 2 over its concave ones, where they are joined by
    an arc of radius d), so the volume is L size^2 / 2 - K size^3 / 3 (a disc of radius R: pi size^2 (R - size /
    3); a hole of radius r: pi size^2 (r + size / 3))."""
    lengths, turn = _turns(np.asarray(ring, dtype=float))
    k = float(np.sum(np.where(turn > 0, np.tan(turn / 2), turn / 2)))
    return float(lengths.sum()) * size**2 / 2 - k * size**3 / 3


def elephant_foot(rings: Sequence[np.ndarray], height: float, size: float, tolerance: float, name: str) -> Any:
    """A prism from z = 0 to ``height`` (mm) on the section bounded by ``rings`` (closed polygons (m, 2), the
    material on their left: the outline counter-clockwise, holes clockwise), with its bed face chamfered at 45
    degrees by ``size`` mm, as a manifold3d solid. At height z < size its section is the section eroded by
    size - z: each edge moves into the material along a plane at 45 degrees; at a convex corner the two planes meet
    (the inset's corner, as the erosion has it), at a concave one a cone of slope 1 joins them (its arc on the bed
    in chords within ``tolerance``). So the bed face is the section inset by ``size``, holes opened by it
    (shapely's ``buffer(-size)``, to the arcs' chords), and the section from z = size up is untouched. The solid is
    built as one mesh, every vertex where it belongs (a boolean cut would meet each wall's corner twice, a hair
    apart). Raises :class:`DesignError` naming ``output.elephant_foot`` where the inset would close up (a
    feature narrower than twice ``size``, or a corner's chords shorter than the chamfer)."""
    import manifold3d
    import shapely

    # the rings as manifold3d's own sections hold them (Clipper's rounding), so that this solid's top face meets a
    # boss or a plate stacked on it, made from the same rings, at the very same points
    rings = manifold3d.CrossSection([np.asarray(r, dtype=float) for r in rings], manifold3d.FillRule.Positive
                                    ).to_polygons()
    # bed points nearer each other than single precision tells apart at this size are one (a tiny chamfer's arcs)
    apart = 8 * float(np.spacing(np.float32(max(float(np.abs(np.vstack(rings)).max()), 1.0))))
    blocks: list[np.ndarray] = []
    faces: list[np.ndarray] = []
    bottoms: list[np.ndarray] = []
    tops: list[np.ndarray] = []
    count = 0
    for ring in rings:
        ring = np.asarray(ring, dtype=float)
        n = len(ring)
        unit = np.roll(ring, -1, axis=0) - ring
        unit /= np.linalg.norm(unit, axis=1)[:, None]
        inward = np.column_stack([-unit[:, 1], unit[:, 0]])
        before = np.roll(inward, 1, axis=0)
        _, turn = _turns(ring)
        groups = []
        for i in range(n):
            if turn[i] >= 0:                      # convex: where the two inset edges meet
                groups.append(ring[i] + size * (before[i] + inward[i]) / (1.0 + before[i] @ inward[i]))
            else:                                 # concave: an arc of radius size round the corner
                steps = arc_steps(size, -turn[i], tolerance)
                start = math.atan2(before[i][1], before[i][0])
                angle = start + turn[i] * np.arange(steps + 1) / steps
                groups.append(ring[i] + size * np.column_stack([np.cos(angle), np.sin(angle)]))
        sizes = np.array([len(np.atleast_2d(g)) for g in groups])
        bed = np.vstack([np.atleast_2d(g) for g in groups])
        first = np.concatenate([[0], np.cumsum(sizes)[:-1]])
        last = first + sizes - 1
        ahead = np.roll(first, -1)
        if np.any(np.einsum("ij,ij->i", bed[ahead] - bed[last], unit) < -apart):
            raise DesignError(f"output.elephant_foot: a chamfer of {size:g} mm closes up the bed face of {name} (a "
                              "corner's chords shorter than the chamfer, or a feature narrower than twice it); make "
                              "it smaller")
        where, kept = _merged(bed, apart)
        if len(kept) < 3:
            raise DesignError(f"output.elephant_foot: a chamfer of {size:g} mm closes up the bed face of {name}; "
                              "make it smaller")
        mid, top, low = count, count + n, count + 2 * n
        blocks += [np.column_stack([ring, np.full(n, size)]), np.column_stack([ring, np.full(n, height)]),
                   np.column_stack([bed[kept], np.zeros(len(kept))])]
        count += 2 * n + len(kept)
        at = np.arange(n)
        after = (at + 1) % n
        faces += [np.column_stack([mid + at, mid + after, top + after]),
                  np.column_stack([mid + at, top + after, top + at]),
                  np.column_stack([low + where[last], low + where[ahead], mid + after]),
                  np.column_stack([low + where[last], mid + after, mid + at])]
        for k in np.flatnonzero(sizes > 1):       # the cone's fan at a concave corner
            fan = low + where[first[k] + np.arange(sizes[k])]
            faces.append(np.column_stack([np.full(sizes[k] - 1, mid + k), fan[:-1], fan[1:]]))
        bottoms.append(bed[kept])
        tops.append(ring)
    polygon = shapely.Polygon(bottoms[0], bottoms[1:])
    if not polygon.is_valid:
        raise DesignError(f"output.elephant_foot: a chamfer of {size:g} mm closes up the bed face of {name} (a "
                          "feature narrower than twice the chamfer); make it smaller")
    offsets = np.cumsum([0] + [2 * len(r) + len(b) for r, b in zip(tops, bottoms, strict=True)])[:-1]
    under = manifold3d.triangulate(bottoms)
    over = manifold3d.triangulate(tops)
    low_index = np.concatenate([off + 2 * len(r) + np.arange(len(b))
                                for off, r, b in zip(offsets, tops, bottoms, strict=True)])
    top_index = np.concatenate([off + len(r) + np.arange(len(r)) for off, r in zip(offsets, tops, strict=True)])
    faces += [low_index[np.asarray(under)][:, ::-1], top_index[np.asarray(over)]]
    tris = np.vstack(faces)
    tris = tris[(tris[:, 0] != tris[:, 1]) & (tris[:, 1] != tris[:, 2]) & (tris[:, 2] != tris[:, 0])]
    mesh = manifold3d.Mesh64(vert_properties=np.ascontiguousarray(np.vstack(blocks)),
                             tri_verts=np.ascontiguousarray(tris, dtype=np.uint64))
    solid = manifold3d.Manifold(mesh)
    if solid.status() != manifold3d.Error.NoError or solid.is_empty():
        raise DesignError(f"output.elephant_foot: a chamfer of {size:g} mm leaves no valid solid of {name} "
                          f"({solid.status()}); make it smaller")
    return solid


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
    #: how many separate bodies the mesh holds (triangles joined through shared vertices): a part is one; two are a
    #: part that fell apart (a ring of holes that meet cuts its hub out)
    bodies: int = 1

    @property
    def ok(self) -> bool:
        return (self.watertight and self.winding_consistent and self.volume_mm3 > 0 and self.distinct_in_float32
                and self.bodies == 1)


def checked_mesh(part: Part, name: str | None = None) -> tuple[Mesh, MeshCheck]:
    """The part extruded (:func:`extrude`) and its :func:`closed` check, ``name`` (the file's stem) the part's name
    by default."""
    mesh = extrude(part)
    return mesh, closed(mesh, part.name if name is None else name)


def closed(mesh: Mesh, name: str) -> MeshCheck:
    """:func:`check_mesh` of a mesh about to be written; :class:`ExportError` naming ``name`` (the file's stem) when
    it is not a closed outward solid."""
    check = check_mesh(mesh)
    if not check.ok:
        raise ExportError(f"{name}: the mesh is not a closed outward solid ({check})")
    return check


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
    return MeshCheck(watertight, consistent, volume, len(f), distinct, bodies(f, len(mesh.vertices)))


def bodies(faces: np.ndarray, count: int) -> int:
    """How many separate bodies the triangles ``faces`` (indices into ``count`` vertices) make: sets of triangles
    joined through shared vertices (unused vertices are no body). Vectorised union-find: each round hooks every
    edge's larger root under its smaller, then halves every path by pointer jumping, so the rounds grow with the
    logarithm of the mesh's size, not with its diameter."""
    f = np.asarray(faces, dtype=np.int64)
    if not len(f):
        return 0
    a, b = f.ravel(), f[:, [1, 2, 0]].ravel()
    parent = np.arange(count)
    while True:
        pa, pb = parent[a], parent[b]
        apart = pa != pb
        if not apart.any():
            break
        np.minimum.at(parent, np.maximum(pa[apart], pb[apart]), np.minimum(pa[apart], pb[apart]))
        while True:                                     # every vertex straight under its root
            grand = parent[parent]
            if np.array_equal(grand, parent):
                break
            parent = grand
    return len(np.unique(parent[np.unique(f)]))
