"""The STEP writer: flat parts as exact B-rep solids (AP214, millimetres), with Open CASCADE through OCP.

The payload is a tuple of solids, each a :class:`~camgen.core.parts.Placed` (or a plain ``(name, parts)`` pair,
at its own place): the parts (:class:`~camgen.core.parts.Part`) stacked from z = 0, each on the one before (one
part for a plain plate; a Geneva driver is its crank with the locking disc on top), fused into one solid that the
file names ``name``, then turned about +Z and moved to where the product places it (a linkage's parts as
assembled, a coupon's as on its sheet), exactly (Open CASCADE's rigid transform of the B-rep).
Every line of an outline is a line edge and every arc a circular edge through its two ends and its exact midpoint
(never chords); a full-circle hole is one circular edge. Each part is its outline's face with the holes cut out,
extruded by its thickness (+Z); a hub boss stands on the top face round the first hole, a radial set-screw hole
runs along +Y at the boss's mid-height, and pockets are cut down from the top face, as :mod:`camgen.core.solids`
makes the meshes; the first part's bed face is chamfered by its ``elephant_foot`` (45 degrees, every edge of the
bed face). The geometry is the part's own, so the solid's volume is the part's exact area x thickness; no tolerance
is involved.

OCP (the ``step`` extra, ``cadquery-ocp-novtk``) is imported only when a STEP file is written. The file's
header carries a fixed time stamp, so the same parts give the same bytes.
"""
from __future__ import annotations

import re
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from camgen.core.errors import ExportError
from camgen.core.parts import Part, Placed
from camgen.core.shapes import Circle, Contour

#: the time stamp written in every file's header (STEP requires one; a fixed one keeps the bytes reproducible)
TIME_STAMP = "2000-01-01T00:00:00"

Solids = Sequence[Placed | tuple[str, Sequence[Part]]]


def _point(x: float, y: float, z: float) -> Any:
    from OCP.gp import gp_Pnt

    return gp_Pnt(float(x), float(y), float(z))


def _wire(shape: Circle | Contour, z: float, ccw: bool) -> Any:
    """A closed wire at height ``z`` (mm): a circle's one circular edge, or a contour's line and arc edges sharing
    their vertices, run counter-clockwise (seen from +Z) when ``ccw``, else clockwise."""
    from OCP.BRep import BRep_Builder
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeVertex
    from OCP.GC import GC_MakeArcOfCircle, GC_MakeSegment
    from OCP.gp import gp_Ax2, gp_Circ, gp_Dir
    from OCP.TopoDS import TopoDS_Wire

    builder, wire = BRep_Builder(), TopoDS_Wire()
    builder.MakeWire(wire)
    if isinstance(shape, Circle):
        axis = gp_Ax2(_point(*shape.centre, z), gp_Dir(0.0, 0.0, 1.0 if ccw else -1.0))
        edges = [BRepBuilderAPI_MakeEdge(gp_Circ(axis, float(shape.radius))).Edge()]
    else:
        contour = shape if (shape.area > 0) == ccw else shape.reversed()
        v, b = contour.vertices, contour.bulges
        points = [_point(x, y, z) for x, y in v]
        corners = [BRepBuilderAPI_MakeVertex(p).Vertex() for p in points]
        edges = []
        for i in range(len(v)):          # piece i runs from vertex i to the next, sharing both (a connected wire)
            j = (i + 1) % len(v)
            if b[i] == 0:
                made = GC_MakeSegment(points[i], points[j])
            else:      # the arc's midpoint: the chord's midpoint moved out by the sagitta, bulge x chord / 2
                dx, dy = v[j] - v[i]
                mid = (v[i] + v[j]) / 2 + b[i] / 2 * np.array([dy, -dx])
                made = GC_MakeArcOfCircle(points[i], _point(mid[0], mid[1], z), points[j])
            edge = BRepBuilderAPI_MakeEdge(made.Value(), corners[i], corners[j]) if made.IsDone() else None
            if edge is None or not edge.IsDone():
                raise ExportError(f"an outline's {'line' if b[i] == 0 else 'arc'} from ({v[i][0]:.9g}, "
                                  f"{v[i][1]:.9g}) mm is too short for an exact edge "
                                  f"({float(np.linalg.norm(v[j] - v[i])):.3g} mm)")
            edges.append(edge.Edge())
    for edge in edges:
        builder.Add(wire, edge)
    wire.Closed(True)
    return wire


def _prism(outer: Circle | Contour, holes: Sequence[Circle | Contour], z: float, height: float) -> Any:
    """The region inside ``outer`` and outside ``holes``, from ``z`` to ``z + height`` (mm)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pln, gp_Vec

    face = BRepBuilderAPI_MakeFace(gp_Pln(gp_Ax3(_point(0.0, 0.0, z), gp_Dir(0.0, 0.0, 1.0))), _wire(outer, z, True))
    for hole in holes:
        face.Add(_wire(hole, z, False))
    if not face.IsDone():
        raise ExportError("a section cannot be made a face")
    return BRepPrimAPI_MakePrism(face.Face(), gp_Vec(0.0, 0.0, float(height))).Shape()


def _boolean(kind: str, a: Any, b: Any) -> Any:
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse

    op = (BRepAlgoAPI_Cut if kind == "cut" else BRepAlgoAPI_Fuse)(a, b)
    if not op.IsDone():
        raise ExportError(f"the solid's {kind} failed")
    return op.Shape()


def _chamfered(prism: Any, z: float, size: float) -> Any:
    """``prism`` with every edge of its bed face (at height ``z``, mm) chamfered by ``size`` mm at 45 degrees: the
    outline inset and the holes opened by ``size`` on the bed, the section at and above ``z + size`` untouched (as
    :func:`camgen.core.solids.elephant_foot` makes the meshes, exactly)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepFilletAPI import BRepFilletAPI_MakeChamfer
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    as_face = getattr(TopoDS, "Face", None) or TopoDS.Face_s           # OCP 8 dropped the _s
    as_edge = getattr(TopoDS, "Edge", None) or TopoDS.Edge_s
    chamfer, faces = BRepFilletAPI_MakeChamfer(prism), TopExp_Explorer(prism, TopAbs_FACE)
    while faces.More():
        face = as_face(faces.Current())
        surface = BRepAdaptor_Surface(face)
        if surface.GetType() == GeomAbs_Plane and abs(surface.Plane().Location().Z() - z) < 1e-9:
            edges = TopExp_Explorer(face, TopAbs_EDGE)
            while edges.More():
                chamfer.Add(float(size), as_edge(edges.Current()))
                edges.Next()
        faces.Next()
    chamfer.Build()
    if not chamfer.IsDone():
        raise ExportError(f"the elephant-foot chamfer of {size:g} mm cannot be cut round the bed face")
    return chamfer.Shape()


def part_solid(part: Part, z: float = 0.0) -> Any:
    """``part`` as an exact solid (a TopoDS_Shape) from ``z`` to ``z`` + thickness (mm), with its holes, boss,
    set-screw hole and pockets (see the module docstring)."""
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir

    solid = _prism(part.outline, part.holes, z, part.thickness)
    if part.elephant_foot > 0:
        solid = _chamfered(solid, z, part.elephant_foot)
    top = z + part.thickness
    if part.boss is not None:
        diameter, height = part.boss
        boss = _prism(Circle((0.0, 0.0), diameter / 2), part.holes[:1], top, height)
        solid = _boolean("fuse", solid, boss)
        if part.set_screw > 0:
            axis = gp_Ax2(_point(0.0, 0.0, top + height / 2), gp_Dir(0.0, 1.0, 0.0))
            screw = BRepPrimAPI_MakeCylinder(axis, part.set_screw / 2, float(diameter)).Shape()
            solid = _boolean("cut", solid, screw)
    for pocket in part.pockets:            # cut from the pocket's floor to 1 mm above the top face
        inner = () if pocket.inner is None else (pocket.inner,)
        solid = _boolean("cut", solid, _prism(pocket.outer, inner, top - pocket.depth, pocket.depth + 1.0))
    return solid


def stacked_solid(parts: Sequence[Part]) -> Any:
    """``parts`` stacked from z = 0, each on the one before, as one exact solid."""
    solid, z = None, 0.0
    for k, part in enumerate(parts):
        piece = part_solid(part if k == 0 else replace(part, elephant_foot=0.0), z)    # only the bed's part
        solid, z = piece if solid is None else _boolean("fuse", solid, piece), z + part.thickness
    return _checked(solid)


def placed_solid(entry: Placed) -> Any:
    """The solid of ``entry``: its parts stacked (:func:`stacked_solid`), turned by its angle about +Z and moved by
    its shift (mm)."""
    solid = stacked_solid(entry.parts)
    if entry.angle == 0 and not any(entry.shift):
        return solid
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Ax1, gp_Dir, gp_Trsf, gp_Vec

    turn, move = gp_Trsf(), gp_Trsf()
    turn.SetRotation(gp_Ax1(_point(0.0, 0.0, 0.0), gp_Dir(0.0, 0.0, 1.0)), float(entry.angle))
    move.SetTranslation(gp_Vec(*(float(v) for v in entry.shift)))
    # turned, then moved: a rigid motion of the solid checked above, so only its one solid is taken (checking
    # the copy again was a third of a machine's STEP time and cannot find what the first check did not)
    return _one_solid(BRepBuilderAPI_Transform(solid, move.Multiplied(turn), True).Shape())


def _one_solid(shape: Any) -> Any:
    """The one solid of ``shape``, or an :class:`ExportError` if it is made of none or several."""
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    explorer, found = TopExp_Explorer(shape, TopAbs_SOLID), []
    while explorer.More():
        found.append(explorer.Current())
        explorer.Next()
    if len(found) != 1:
        raise ExportError(f"the exact solid is not one valid solid ({len(found)} solids)")
    return found[0]


def _checked(shape: Any) -> Any:
    """The one solid of ``shape`` if Open CASCADE finds it valid and made of exactly one solid, else an
    :class:`ExportError`."""
    from OCP.BRepCheck import BRepCheck_Analyzer

    solid = _one_solid(shape)
    if not BRepCheck_Analyzer(solid).IsValid():
        raise ExportError("the exact solid is not one valid solid (1 solids)")
    return solid


@contextmanager
def _quiet() -> Iterator[None]:
    """Open CASCADE's messages (the STEP writer's statistics go to standard output) held back to failures while
    the block runs: the library never prints."""
    from OCP.Message import Message, Message_Gravity

    printers = list(Message.DefaultMessenger_s().Printers())
    levels = [p.GetTraceLevel() for p in printers]
    for printer in printers:
        printer.SetTraceLevel(Message_Gravity.Message_Fail)
    try:
        yield
    finally:
        for printer, level in zip(printers, levels, strict=True):
            printer.SetTraceLevel(level)


def write_step(solids: Solids, path: Path, options: Any = None) -> None:
    """Write ``solids`` (:class:`~camgen.core.parts.Placed` entries or ``(name, parts)`` pairs, see the module
    docstring) as one AP214 STEP file in mm, each a named product in its place."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.STEPControl import STEPControl_AsIs
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    doc = TDocStd_Document(TCollection_ExtendedString("MDTV-XCAF"))
    shapes = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    for entry in solids:
        entry = Placed(*entry)
        try:
            solid = placed_solid(entry)
        except ExportError as exc:
            raise ExportError(f"{entry.name}: {exc}") from None
        TDataStd_Name.Set_s(shapes.AddShape(solid, False), TCollection_ExtendedString(entry.name))
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    writer = STEPCAFControl_Writer()
    writer.SetNameMode(True)
    with _quiet():
        done = writer.Transfer(doc, STEPControl_AsIs) and writer.Write(str(path)) == IFSelect_RetDone
    if not done:
        raise ExportError(f"{path.name}: Open CASCADE could not write the STEP file")
    text = path.read_text(encoding="ascii")
    path.write_text(re.sub(r"(FILE_NAME\('[^']*',)'[^']*'", rf"\1'{TIME_STAMP}'", text, count=1), encoding="ascii")


WRITERS = {"step": write_step}
