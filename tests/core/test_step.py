"""The STEP writer (``output.formats`` "step", the ``step`` extra): every file re-read, with Open CASCADE (OCP) and
with FreeCAD, as valid solids of the parts' exact volume (area x thickness, arcs exact) and bounding box, one face a
piece of outline and hole plus the two flat faces, the arcs as circular edges; refusals are one line, exit 2."""
from __future__ import annotations

import itertools
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.core.parts import Part
from camgen.core.shapes import Circle, Contour
from camgen.core.writers import FORMATS
from camgen.core.writers.step import _quiet, write_step
from camgen.api import design_cam
from camgen.profile import step_part
from camgen.spec import load_spec
from linkgen.cli import main as linkgen_main
from tests.conftest import ROOT, template
from tests.support.freecad import freecad_check

HOLES = {"cam.bore": 20.0, "hub.keyway": True, "hub.bolt_circle": 50.0, "hub.bolt_holes": 4,
         "hub.bolt_hole_diameter": 4.0}
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}


def read_step(path) -> list[tuple[str, object]]:
    """The file's top-level shapes with their product names, read by Open CASCADE's XDE reader."""
    from OCP.STEPCAFControl import STEPCAFControl_Reader
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    try:
        from OCP.TDF import TDF_LabelSequence
    except ImportError:                          # OCP 8 wraps it as a collection
        from OCP.OCP.collections import Sequence_TDF_Label as TDF_LabelSequence
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    doc = TDocStd_Document(TCollection_ExtendedString("MDTV-XCAF"))
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    with _quiet():
        assert reader.ReadFile(str(path)) == 1 and reader.Transfer(doc)
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    labels = TDF_LabelSequence()
    tool.GetFreeShapes(labels)
    out = []
    for k in range(1, labels.Length() + 1):
        label, name = labels.Value(k), TDataStd_Name()
        assert label.FindAttribute(TDataStd_Name.GetID_s(), name)
        out.append((name.Get().ToExtString(), tool.GetShape_s(label)))
    return out


def measure(shape) -> dict:
    """What Open CASCADE finds in a shape: solids, validity, volume (mm^3), exact box (mm), faces, and edges by
    their curve's type."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepBndLib import BRepBndLib
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GeomAbs import GeomAbs_Circle, GeomAbs_Line
    from OCP.GProp import GProp_GProps
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SOLID
    from OCP.TopExp import TopExp
    from OCP.TopoDS import TopoDS
    try:
        from OCP.TopTools import TopTools_IndexedMapOfShape
    except ImportError:                          # OCP 8 wraps it as a collection
        from OCP.OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as TopTools_IndexedMapOfShape

    def unique(kind):
        found = TopTools_IndexedMapOfShape()
        TopExp.MapShapes_s(shape, kind, found)
        return [found.FindKey(i) for i in range(1, found.Extent() + 1)]

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, 1e-10)      # adaptive, to 1e-10 relative (the default is coarser)
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, box, False, False)
    as_edge = getattr(TopoDS, "Edge", None) or TopoDS.Edge_s            # OCP 8 dropped the _s
    types = [BRepAdaptor_Curve(as_edge(e)).GetType() for e in unique(TopAbs_EDGE)]
    corners = np.array([c.Coord(k) for c in (box.CornerMin(), box.CornerMax()) for k in (1, 2, 3)])
    return {"solids": len(unique(TopAbs_SOLID)), "valid": BRepCheck_Analyzer(shape).IsValid(),
            "volume": props.Mass(), "box": corners, "faces": len(unique(TopAbs_FACE)),
            "circles": types.count(GeomAbs_Circle), "lines": types.count(GeomAbs_Line), "edges": len(types)}


def _pieces(shape) -> tuple[int, int]:
    """A plan shape's pieces (a circle is one) and its arcs (a circle is one)."""
    return (1, 1) if isinstance(shape, Circle) else (len(shape.bulges), shape.n_arcs)


def expect_plate(part: Part, z: float = 0.0) -> dict:
    """A plain extruded part, exactly: its volume, box, faces (a side face a piece of outline and holes, top and
    bottom) and circular edges (each arc and circle at the top and at the bottom)."""
    pieces = [_pieces(s) for s in (part.outline, *part.holes)]
    x0, y0, x1, y1 = part.outline.bounds()
    return {"solids": 1, "valid": True, "volume": part.area * part.thickness,
            "box": np.array([x0, y0, z, x1, y1, z + part.thickness]), "faces": sum(p for p, _ in pieces) + 2,
            "circles": 2 * sum(a for _, a in pieces)}


def assert_plate(found: dict, part: Part) -> None:
    want = expect_plate(part)
    assert found["solids"] == 1 and found["valid"]
    assert found["volume"] == pytest.approx(want["volume"], rel=1e-6)
    assert np.abs(found["box"] - want["box"]).max() <= 1e-6
    assert (found["faces"], found["circles"]) == (want["faces"], want["circles"])
    # every other edge a line: the outline's lines at the top and bottom, and one vertical edge a vertex (a seam for
    # a circle)
    assert found["lines"] == found["edges"] - found["circles"]


def circles(shape) -> np.ndarray:
    """Each circular edge of a shape as Open CASCADE reads it: its centre (x, y, z) and radius (mm), (k, 4)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.GeomAbs import GeomAbs_Circle
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp
    from OCP.TopoDS import TopoDS
    try:
        from OCP.TopTools import TopTools_IndexedMapOfShape
    except ImportError:                          # OCP 8 wraps it as a collection
        from OCP.OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as TopTools_IndexedMapOfShape

    as_edge = getattr(TopoDS, "Edge", None) or TopoDS.Edge_s
    found = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, TopAbs_EDGE, found)
    out = []
    for i in range(1, found.Extent() + 1):
        curve = BRepAdaptor_Curve(as_edge(found.FindKey(i)))
        if curve.GetType() == GeomAbs_Circle:
            c = curve.Circle()
            out.append((c.Location().X(), c.Location().Y(), c.Location().Z(), c.Radius()))
    return np.array(out).reshape(-1, 4)


def holes_at(shape, radius: float) -> np.ndarray:
    """The centres (x, y) of the shape's circles of ``radius`` (to 1e-9 mm), each once, sorted (mm)."""
    found = circles(shape)
    out: list[np.ndarray] = []
    for centre in found[np.abs(found[:, 3] - radius) <= 1e-9][:, :2]:      # a hole's circle at its top and bottom
        if not any(np.abs(centre - c).max() <= 1e-7 for c in out):
            out.append(centre)
    return np.array(sorted(out, key=tuple)).reshape(-1, 2)


def expect_placed(part: Part, angle: float, shift) -> dict:
    """:func:`expect_plate` of ``part`` turned by ``angle`` (rad) about its origin, then moved by ``shift`` (x, y,
    z; mm): its box the moved outline's exact bounds (:meth:`Contour.bounds`)."""
    x0, y0, x1, y1 = part.outline.moved(angle, np.asarray(shift[:2], dtype=float)).bounds()
    z = shift[2]
    return {**expect_plate(part), "box": np.array([x0, y0, z, x1, y1, z + part.thickness])}


def assert_placed(found: dict, part: Part, angle: float, shift) -> None:
    want = expect_placed(part, angle, shift)
    assert found["solids"] == 1 and found["valid"]
    assert found["volume"] == pytest.approx(want["volume"], rel=1e-6)
    assert np.abs(found["box"] - want["box"]).max() <= 1e-6
    assert (found["faces"], found["circles"]) == (want["faces"], want["circles"])


def assert_apart(boxes) -> None:
    """No two solids' bounding boxes coincide (they differ by more than 1e-3 mm somewhere)."""
    for a, b in itertools.combinations(list(boxes), 2):
        assert np.abs(np.asarray(a) - np.asarray(b)).max() > 1e-3


#: the tests of the module's command builds (rdrd_cli, crank_rocker) run on one worker, so each is made once a run
COMMANDS = pytest.mark.xdist_group("core-step-commands")


@pytest.fixture(scope="module")
def rdrd_cli(tmp_path_factory):
    """``camgen build templates/rdrd.toml`` with step, stl and json, run as a process from a folder outside the
    checkout."""
    cwd = tmp_path_factory.mktemp("outside")
    done = subprocess.run([sys.executable, "-m", "camgen", "build", str(ROOT / "templates" / "rdrd.toml"), "--set",
                           'output.formats=["step","stl","json"]'], cwd=cwd, env=ENV, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return cwd / "out" / "rdrd", done


@COMMANDS
def test_rdrd_step_beside_the_stl_one_exact_solid(rdrd_cli):
    """The default outline (polylines, 114 pieces) is written as biarcs: 30 arcs, each a cylindrical face."""
    out, done = rdrd_cli
    assert sorted(p.name for p in out.iterdir()) == ["rdrd.json", "rdrd.step", "rdrd.stl"]
    report = json.loads((out / "rdrd.json").read_text())
    assert report["files"]["step"] == "rdrd.step"
    assert "wrote out/rdrd/rdrd.step" in done.stdout.splitlines()
    design = design_cam(template())
    part, outline = step_part(design)
    assert len(design.printed.outline.bulges) == 114 and part.holes == design.printed.holes
    [(name, shape)] = read_step(out / "rdrd.step")
    found = measure(shape)
    assert name == "rdrd"
    assert_plate(found, part)
    assert found["faces"] == 30 + 1 + 2 and found["circles"] == 2 * (30 + 1)   # 30 pieces, all arcs; a bore
    assert report["step_outline"] == {"curves": "biarcs", "pieces": 30, "arcs": 30,
                                      "max_error_mm": outline.max_error_mm}
    assert 0 < outline.max_error_mm <= 0.01


@pytest.mark.parametrize("case", [
    {"output.curves": "biarcs"},                                  # an outline of arcs: every one a circular edge
    {**HOLES, "output.curves": "biarcs"},                         # a keyway (a contour hole) and bolt holes
    {"output.curves": "biarcs", "output.clearance": 5.0},         # the largest clearance: the printed part's bore
    {"cam.bore": 0.0},                                            # no hole at all
    {"cam.bore": 10.0 + 1e-12},                                   # 1e-12 mm from a round size
    {"output.curves": "biarcs", "output.tolerance": 1e-6},        # the least tolerance: 548 arcs
    {"output.kerf": 0.3},                                         # the kerf is the cut files', not the solid's
], ids=["biarcs", "keyway-bolts", "clearance-5", "no-bore", "bore-1e-12", "tolerance-1e-6", "kerf"])
def test_exact_plate_volume_box_faces_and_arcs(case, tmp_path):
    part = design_cam(template({**case, "output.formats": ["json"]})).printed
    write_step([(part.name, (part,))], tmp_path / "x.step")
    [(name, shape)] = read_step(tmp_path / "x.step")
    found = measure(shape)
    assert name == part.name
    assert_plate(found, part)
    if case.get("output.curves") == "biarcs":
        assert part.outline.n_arcs > 20 and found["circles"] >= 2 * part.outline.n_arcs


def test_the_step_solid_is_the_exact_part_not_its_chords(tmp_path):
    """A disc of two half-circle arcs: the volume is pi r^2 t to 1e-9 relative, where chords within 0.01 mm would
    lose 1e-4 of it; and a circle's radius read back from its edge."""
    r, t = 25.0, 6.0
    disc = Contour(np.array([[r, 0.0], [-r, 0.0]]), np.array([1.0, 1.0]))
    part = Part("disc", disc, (Circle((3.0, 4.0), 2.5),), t, 0.01)
    write_step([("disc", (part,))], tmp_path / "disc.step")
    [(_, shape)] = read_step(tmp_path / "disc.step")
    found = measure(shape)
    assert found["volume"] == pytest.approx((math.pi * r**2 - math.pi * 2.5**2) * t, rel=1e-9)
    assert found["faces"] == 2 + 1 + 2 and found["circles"] == 2 * 2 + 2


def _lateral(shape, z: float = 0.0) -> tuple[dict, object]:
    """The solid's faces counted by their surface's type, and the outer wire of its bottom face (at ``z``, mm)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepTools import BRepTools
    from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Cylinder, GeomAbs_Plane
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    as_face = getattr(TopoDS, "Face", None) or TopoDS.Face_s
    names = {GeomAbs_Plane: "planes", GeomAbs_Cylinder: "cylinders", GeomAbs_BSplineSurface: "bsplines"}
    counts, bottom, explorer = {"planes": 0, "cylinders": 0, "bsplines": 0, "other": 0}, None, TopExp_Explorer(
        shape, TopAbs_FACE)
    while explorer.More():
        face = as_face(explorer.Current())
        surface = BRepAdaptor_Surface(face)
        kind = names.get(surface.GetType(), "other")
        counts[kind] += 1
        if kind == "planes" and abs(surface.Plane().Location().Z() - z) < 1e-12:
            bottom = BRepTools.OuterWire_s(face)
        explorer.Next()
    return counts, bottom


def _exact_surface(cam, n: int) -> np.ndarray:
    """The exact cam surface at ``n`` cam angles over a turn, from the design's kinematics: the pitch point moved in
    by the contact radius along the normal (mm)."""
    g = cam.pitch(np.linspace(0.0, 2 * math.pi, n, endpoint=False))
    return g.point - cam.contact_radius * g.normal


def _wire_points(wire, per_edge: int) -> np.ndarray:
    """``per_edge`` points on each edge of ``wire``, equally spaced in its parameter (mm, x and y)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    as_edge = getattr(TopoDS, "Edge", None) or TopoDS.Edge_s
    out, explorer = [], TopExp_Explorer(wire, TopAbs_EDGE)
    while explorer.More():
        curve = BRepAdaptor_Curve(as_edge(explorer.Current()))
        for u in np.linspace(curve.FirstParameter(), curve.LastParameter(), per_edge):
            p = curve.Value(float(u))
            out.append((p.X(), p.Y()))
        explorer.Next()
    return np.array(out)


@pytest.mark.parametrize("name, sets", [
    ("rdrd", []),                                                         # polylines asked for: biarcs written
    ("rdrd", ['output.tolerance=0.001']),
    ("rdrd", ['output.dxf="segments"']),                                  # the DXF's chords: the STEP's arcs
    ("flat-face", []),
    ("oscillating", []),
    ("rdrd", ['output.curves="biarcs"', 'output.tolerance=1e-6']),       # the least tolerance
], ids=["rdrd", "tolerance-0.001", "dxf-segments", "flat-face", "oscillating", "tolerance-1e-6"])
def test_smooth_outline_within_the_tolerance_of_the_exact_profile(name, sets, tmp_path):
    """Whatever output.curves says, the STEP solid's side is arcs (cylinders), not hundreds of planes; the exact
    profile, sampled from the design's kinematics at 3600 angles, lies within the tolerance of the solid's side
    (Open CASCADE's distance to the bottom face's outer wire, the side being its extrusion), and so does every
    point of that wire (the exact surface's distance to it, measured from the pitch curve); the volume is the exact
    profile's area x thickness within the tolerance x perimeter x thickness."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape

    from camgen.surface import surface_deviation

    design = design_cam(load_spec(ROOT / "templates" / f"{name}.toml", ['output.formats=["json"]', *sets]))
    part, outline = step_part(design)
    tol = design.tolerance
    write_step([(part.name, (part,))], tmp_path / "x.step")
    [(_, shape)] = read_step(tmp_path / "x.step")
    counts, wire = _lateral(shape)
    holes = len(part.holes)
    assert counts == {"planes": 2, "cylinders": part.outline.n_arcs + holes, "bsplines": 0, "other": 0}
    assert part.outline.n_arcs == len(part.outline.bulges) and outline.max_error_mm <= tol
    exact = _exact_surface(design.cam, 3600)
    far = 0.0
    for x, y in exact[::5] if tol < 1e-3 else exact:          # 720 points at the least tolerance (its 548 arcs)
        dist = BRepExtrema_DistShapeShape(BRepBuilderAPI_MakeVertex(_point(x, y)).Vertex(), wire)
        far = max(far, dist.Value())
    assert far <= tol
    assert np.abs(surface_deviation(design.cam, _wire_points(wire, 40))).max() <= tol
    dense = _exact_surface(design.cam, 200_000)                 # chords within 1e-8 mm of the profile
    x, y = dense.T
    shoelace = abs(float(x @ np.roll(y, -1) - y @ np.roll(x, -1))) / 2     # the cam turns either way
    perimeter = np.linalg.norm(dense - np.roll(dense, -1, axis=0), axis=1).sum()
    area = shoelace - sum(math.pi * h.radius**2 for h in part.holes)
    assert abs(measure(shape)["volume"] - area * part.thickness) <= tol * perimeter * part.thickness


def _point(x: float, y: float):
    from OCP.gp import gp_Pnt

    return gp_Pnt(float(x), float(y), 0.0)


def test_elephant_foot_chamfer_by_hand(tmp_path):
    """A disc (r = 25 mm) with a hole (r = 2.5 mm), chamfered 0.5 mm: each ring's chamfer is a triangle of legs e
    turned round the axis, pi e^2 (R - e/3) off the disc and pi e^2 (r + e/3) round the hole, exactly; the box keeps
    the full outline (the chamfer is below it)."""
    r, h, t, e = 25.0, 2.5, 6.0, 0.5
    disc = Contour(np.array([[r, 0.0], [-r, 0.0]]), np.array([1.0, 1.0]))
    part = Part("disc", disc, (Circle((3.0, 4.0), h),), t, 0.01, elephant_foot=e)
    write_step([("disc", (part,))], tmp_path / "foot.step")
    [(_, shape)] = read_step(tmp_path / "foot.step")
    found = measure(shape)
    plain = (math.pi * r**2 - math.pi * h**2) * t
    # a chamfer an edge of the bed
    assert found["solids"] == 1 and found["valid"] and found["faces"] == 2 + 1 + 2 + 3
    assert found["volume"] == pytest.approx(plain - math.pi * e**2 * (r - e / 3) - math.pi * e**2 * (h + e / 3),
                                            rel=1e-12)
    assert np.abs(found["box"] - [-r, -r, 0.0, r, r, t]).max() <= 1e-6


def _arc_length(contour: Contour) -> float:
    """The contour's exact length (mm): each line its chord, each arc its radius x its angle (4 atan bulge)."""
    chords = np.linalg.norm(np.roll(contour.vertices, -1, axis=0) - contour.vertices, axis=1)
    angle = 4 * np.arctan(np.abs(contour.bulges))
    return float(np.sum(np.where(angle > 0, chords * angle / (2 * np.sin(angle / 2) + (angle == 0)), chords)))


def test_elephant_foot_on_the_cam(tmp_path):
    """rdrd printed with a 0.3 mm foot: its biarc outline's chamfer takes L e^2/2 - pi e^3/3 (the section eroded by d
    has area A - L d + pi d^2 for a tangent-continuous outline, while d stays below its least radius) and the bore's
    pi e^2 (r + e/3); only the bed face's edges are chamfered."""
    e = 0.3
    design = design_cam(template({"output.elephant_foot": e, "output.formats": ["json"]}))
    part, _ = step_part(design)
    assert part.elephant_foot == e
    write_step([(part.name, (part,))], tmp_path / "foot.step")
    [(_, shape)] = read_step(tmp_path / "foot.step")
    found = measure(shape)
    [bore] = part.holes
    length = _arc_length(part.outline)
    cut = length * e**2 / 2 - math.pi * e**3 / 3 + math.pi * e**2 * (bore.radius + e / 3)
    assert found["solids"] == 1 and found["valid"]
    assert found["volume"] == pytest.approx(part.area * part.thickness - cut, rel=1e-9)
    assert found["faces"] == expect_plate(part)["faces"] + len(part.outline.bulges) + 1


def test_boss_stands_on_the_bore(tmp_path):
    """A hub boss without a set screw: the plate plus the boss's ring (its circle less the bore) x its height."""
    part = design_cam(template({"cam.bore": 20.0, "hub.boss_diameter": 34.0, "hub.boss_height": 10.0,
                                "output.formats": ["json"]})).printed
    write_step([(part.name, (part,))], tmp_path / "boss.step")
    [(_, shape)] = read_step(tmp_path / "boss.step")
    found = measure(shape)
    ring = math.pi * (17.0**2 - 10.0**2)
    assert found["solids"] == 1 and found["valid"]
    assert found["volume"] == pytest.approx(part.area * part.thickness + ring * 10.0, rel=1e-6)
    assert found["box"][5] == pytest.approx(part.thickness + 10.0, abs=1e-6)


def test_set_screw_hole_through_the_boss(tmp_path):
    """With a set screw: the boss less the screw's hole, which takes from the ring between the bore (r = 10 mm) and
    the boss (r = 17 mm) the integral over the hole's section (r = 2 mm) of the wall it crosses; and the mesh's
    volume within its chords."""
    from scipy.integrate import quad

    from camgen.core.solids import check_mesh, extrude

    part = design_cam(template({"cam.bore": 20.0, "hub.boss_diameter": 34.0, "hub.boss_height": 10.0,
                                "hub.set_screw": 4.0, "output.formats": ["json"]})).printed
    write_step([(part.name, (part,))], tmp_path / "screw.step")
    [(_, shape)] = read_step(tmp_path / "screw.step")
    found = measure(shape)
    plain = part.area * part.thickness + math.pi * (17.0**2 - 10.0**2) * 10.0
    hole, _ = quad(lambda x: 2 * math.sqrt(4.0 - x * x) * (math.sqrt(17.0**2 - x * x) - math.sqrt(10.0**2 - x * x)),
                   -2.0, 2.0, epsabs=1e-12, epsrel=1e-12)
    assert found["solids"] == 1 and found["valid"]
    assert found["volume"] == pytest.approx(plain - hole, rel=1e-6)
    assert found["volume"] == pytest.approx(check_mesh(extrude(part)).volume_mm3, rel=1e-3)   # chords of 0.01 mm


def _design(name: str):
    """The design of a bundled template, made in this process."""
    return design_cam(load_spec(ROOT / "templates" / f"{name}.toml", ['output.formats=["json"]']))


def test_grooved_cam_pocket(tmp_path):
    result = CliRunner().invoke(main, ["build", str(ROOT / "templates" / "grooved.toml"), "-o", str(tmp_path),
                                       "--set", 'output.formats=["step"]'])
    assert result.exit_code == 0, result.output
    from camgen.kinds.grooved.design import step_plate
    from camgen.surface import surface_deviation

    design = _design("grooved")
    part = step_plate(design)
    [(name, shape)] = read_step(tmp_path / "grooved.step")
    found = measure(shape)
    [pocket] = part.pockets
    assert name == "grooved" and found["solids"] == 1 and found["valid"]
    assert found["volume"] == pytest.approx(part.area * part.thickness - pocket.area * pocket.depth, rel=1e-6)
    # the plate's faces, the groove's walls (one a piece of its two flanks) and floor, and the top face the groove
    # cuts in two (the rim and the island)
    walls = len(pocket.outer.bulges) + len(pocket.inner.bulges)
    assert found["faces"] == expect_plate(part)["faces"] + walls + 2
    # both flanks are biarcs (cylindrical walls, not hundreds of planes), each within the tolerance of its exact
    # flank: the island's surface, and the outer flank 2 d out from it (d = roller + clearance / 2)
    counts, _ = _lateral(shape)
    assert counts["cylinders"] == pocket.outer.n_arcs + pocket.inner.n_arcs + part.outline.n_arcs + len(part.holes)
    assert pocket.inner.n_arcs == len(pocket.inner.bulges) and pocket.outer.n_arcs == len(pocket.outer.bulges)
    cam, tol = design.profile.cam, design.spec.output.tolerance
    assert np.abs(surface_deviation(cam, pocket.inner.flatten(tol / 100))).max() <= tol
    assert np.abs(surface_deviation(cam, pocket.outer.flatten(tol / 100), 2 * cam.contact_radius)).max() <= tol


def test_geneva_wheel_and_driver_named_and_stacked(tmp_path):
    """As assembled in the middle of the dwell (driver angle alpha = 180 degrees): the driver (crank with the locking
    disc on top) on the origin turned by alpha, its bore round the origin and its pin hole at (-R, 0) (R the crank
    radius); the wheel on the crank, in the disc's plane, its bore round (C, 0) (C the centre distance) and turned by
    180 - beta degrees, beta where the pin left it: the law's closed form tan(beta) = lambda sin(a) / (1 - lambda
    cos(a)) at the exit a = 90 - 180/n degrees (lambda = R/C = sin(180/n)), which is 180/n; each solid's box is its
    outline moved so, and the two boxes differ."""
    result = CliRunner().invoke(main, ["build", str(ROOT / "templates" / "geneva4.toml"), "-o", str(tmp_path),
                                       "--set", 'output.formats=["step","json"]'])
    assert result.exit_code == 0, result.output
    design = _design("geneva4")
    printed, g = design.printed, design.geometry
    solids = dict(read_step(tmp_path / "geneva4.step"))
    assert list(solids) == ["geneva4-wheel", "geneva4-driver"]
    crank, lock, wheel = printed["crank"], printed["lock"], printed["wheel"]
    lam, exit_ = g.crank_radius / g.centre_distance, math.pi / 2 - math.pi / g.slots
    beta = math.atan2(lam * math.sin(exit_), 1.0 - lam * math.cos(exit_))
    assert beta == pytest.approx(math.pi / g.slots, abs=1e-12)
    found = measure(solids["geneva4-wheel"])
    assert_placed(found, wheel, math.pi - beta, (g.centre_distance, 0.0, crank.thickness))
    bore = wheel.holes[0].radius
    assert holes_at(solids["geneva4-wheel"], bore) == pytest.approx(np.array([[g.centre_distance, 0.0]]), abs=1e-9)
    driver = measure(solids["geneva4-driver"])
    assert driver["solids"] == 1 and driver["valid"]
    assert driver["volume"] == pytest.approx(crank.area * crank.thickness + lock.area * lock.thickness, rel=1e-6)
    assert driver["box"][[2, 5]] == pytest.approx([0.0, crank.thickness + lock.thickness], abs=1e-6)
    pin = crank.holes[1].radius
    assert holes_at(solids["geneva4-driver"], pin) == pytest.approx(np.array([[-g.crank_radius, 0.0]]), abs=1e-9)
    assert_apart([found["box"], driver["box"]])


def test_conjugate_pair_two_named_cams(tmp_path):
    result = CliRunner().invoke(main, ["build", str(ROOT / "templates" / "conjugate.toml"), "-o", str(tmp_path),
                                       "--set", 'output.formats=["step"]'])
    assert result.exit_code == 0, result.output
    names = [name for name, _ in read_step(tmp_path / "conjugate.step")]
    assert names == ["conjugate-1", "conjugate-2"]
    from camgen.kinds.conjugate.design import design_conjugate
    from camgen.surface import surface_deviation

    pair = design_conjugate(load_spec(ROOT / "templates" / "conjugate.toml", ['output.formats=["json"]']))
    boxes = []
    for which, ((_, shape), member) in enumerate(zip(read_step(tmp_path / "conjugate.step"), pair.cams,
                                                     strict=True)):
        found = measure(shape)
        assert found["solids"] == 1 and found["valid"] and found["volume"] > 0
        # as assembled: on one shaft, in the pair's cam frame, the second cam on the first
        assert_placed(found, step_part(member)[0], 0.0, (0.0, 0.0, which * member.spec.cam.thickness))
        bore = member.printed.holes[0]                             # the bore, with its keyway: its arc's radius
        radius = bore.radius if isinstance(bore, Circle) else float(bore.arcs()[2].max())
        assert holes_at(shape, radius) == pytest.approx(np.zeros((1, 2)), abs=1e-9)
        boxes.append(found["box"])
        # each cam's side is its biarc outline's arcs (cylinders), as a disc cam's, within the tolerance of its
        # exact profile (its roller's pitch curve less the roller, from the pair's kinematics)
        part, outline = step_part(member)
        counts, wire = _lateral(shape, which * member.spec.cam.thickness)
        assert counts["cylinders"] == part.outline.n_arcs + len(part.holes) >= 20 and counts["bsplines"] == 0
        assert outline.max_error_mm <= member.tolerance
        assert np.abs(surface_deviation(member.cam, _wire_points(wire, 40))).max() <= member.tolerance
    assert_apart(boxes)


@pytest.fixture(scope="module")
def crank_rocker(tmp_path_factory):
    """``linkgen build templates/crank-rocker.toml`` with step, dxf, stl and json, run from a folder outside the
    checkout; the folder and the build."""
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import load_spec as load_linkage

    cwd = tmp_path_factory.mktemp("outside-linkage")
    template_path = ROOT / "templates" / "crank-rocker.toml"
    done = subprocess.run([sys.executable, "-m", "linkgen", "build", str(template_path), "--set",
                           'output.formats=["step","dxf","stl","json"]'], cwd=cwd, env=ENV, capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    return cwd / "out" / "crank-rocker", design_linkage(load_linkage(template_path), parts=True).build


#: crank-rocker.toml: ground d, crank a, coupler b, rocker c (mm); plate thickness, pin and printed hole diameters
D, A, B, C, T, PIN, HOLE = 180.0, 80.0, 200.0, 150.0, 4.0, 4.0, 4.2


def _first_dead_centre(out, build) -> list:
    """The printed parts' outlines on the assembly drawing's first pose layer (``DC1-...``), read back from the DXF
    in the parts' order (each part's outline, then its holes)."""
    import ezdxf

    layer = f"DC1-{build.positions[0][0]}"
    msp = ezdxf.readfile(out / "crank-rocker-assembly.dxf").modelspace()
    outlines = []
    for pl in msp.query(f'LWPOLYLINE[layer=="{layer}"]'):
        pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
        outlines.append(Contour(pts[:, :2], pts[:, 2]))
    return outlines


def _linkage_expected(out, build) -> list[dict]:
    """What each solid of crank-rocker.step must be, as assembled at the extended dead centre: each part its exact
    volume and faces, its box the drawn outline's at its layer (layer x 4 mm); each pin (a 4 mm shank 13 mm long under
    a 7.2 x 2 mm head) round its joint, the head resting on the highest part it joins."""
    wanted = []
    for part, drawn in zip(build.printed, _first_dead_centre(out, build), strict=True):
        x0, y0, x1, y1 = drawn.bounds()
        z = build.layers[part.name] * T
        wanted.append({"volume": part.area * T, "box": np.array([x0, y0, z, x1, y1, z + T]),
                       "faces": expect_plate(part)["faces"]})
    phi = math.acos(((A + B) ** 2 + D**2 - C**2) / (2 * (A + B) * D))
    joints = {"O2": (0.0, 0.0, 2), "A": (A * math.cos(phi), A * math.sin(phi), 3),
              "B": ((A + B) * math.cos(phi), (A + B) * math.sin(phi), 3), "O4": (D, 0.0, 2)}
    for x, y, top in joints.values():
        wanted.append({"volume": math.pi * (2.0**2 * 13.0 + 3.6**2 * 2.0), "faces": 7,
                       "box": np.array([x - 3.6, y - 3.6, top * T - 13.0, x + 3.6, y + 3.6, top * T + 2.0])})
    return wanted


@COMMANDS
def test_linkage_parts_as_assembled_at_the_first_dead_centre(crank_rocker):
    """crank-rocker.step: every printed part and a pin at each pivot point, as assembled at the first dead centre
    the assembly drawing shows (extended: crank and coupler in line, so |O2 B| = a + b and the crank's angle phi
    from the cosine rule, cos(phi) = ((a + b)^2 + d^2 - c^2) / (2 (a + b) d); drawn above the ground line): each
    part's box is its outline on the drawing's DC1 layer (read back from the DXF) at its layer's height, its pin
    holes (4.2 mm) at the closed form's joints, O2 (0, 0), A = a (cos phi, sin phi), B = (a + b) (cos phi, sin phi),
    O4 (d, 0); each pin's shank (4 mm) round its joint; no two boxes coincide."""
    out, build = crank_rocker
    assert (out / "crank-rocker.step").exists() and (out / "crank-rocker-crank.stl").exists()
    solids = read_step(out / "crank-rocker.step")
    assert [n for n, _ in solids] == ["ground", "crank", "coupler", "rocker", "pin-O2", "pin-A", "pin-B", "pin-O4"]
    assert build.positions[0][0] == "extended"
    found = [measure(shape) for _, shape in solids]
    for f, want in zip(found, _linkage_expected(out, build), strict=True):
        assert f["solids"] == 1 and f["valid"] and f["faces"] == want["faces"]
        assert f["volume"] == pytest.approx(want["volume"], rel=1e-9)
        assert np.abs(f["box"] - want["box"]).max() <= 1e-6
    phi = math.acos(((A + B) ** 2 + D**2 - C**2) / (2 * (A + B) * D))
    o2, a, b, o4 = (0.0, 0.0), A * np.array([math.cos(phi), math.sin(phi)]), (A + B) * np.array(
        [math.cos(phi), math.sin(phi)]), (D, 0.0)
    holes = {name: holes_at(shape, HOLE / 2) for name, shape in solids[:4]}
    for name, where in (("ground", (o2, o4)), ("crank", (o2, a)), ("coupler", (a, b)), ("rocker", (b, o4))):
        assert holes[name] == pytest.approx(np.array(sorted(map(tuple, where))), abs=1e-9), name
    for (name, shape), where in zip(solids[4:], (o2, a, b, o4), strict=True):
        assert holes_at(shape, PIN / 2) == pytest.approx(np.array([where]), abs=1e-9), name
    assert_apart(f["box"] for f in found)


def test_linkage_spacers_are_rings(tmp_path):
    """stephenson1 with pins: a spacer bridges one empty layer, a ring of the spacer's diameters one layer high,
    round its joint at the drawing's first dead centre and on the empty layer between the two parts the joint joins,
    the pins' heads each on the highest part of their pivot; no two boxes coincide."""
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import load_spec as load_linkage

    template_path = ROOT / "templates" / "stephenson1.toml"
    sets = ['output.formats=["step"]', "parts.pins=true"]
    result = CliRunner().invoke(linkgen_main, ["build", str(template_path), "-o", str(tmp_path), *(
        a for s in sets for a in ("--set", s))])
    assert result.exit_code == 0, result.output
    build = design_linkage(load_linkage(template_path, sets), parts=True).build
    solids = dict(read_step(tmp_path / "stephenson1.step"))
    inner, outer = build.spacer_diameters
    t = build.table.thickness
    [(joint, parts, run, first)] = build.spacers
    assert run == 1 and list(solids)[-1] == f"spacer-{joint}-{first}"
    ring = measure(solids[f"spacer-{joint}-{first}"])
    assert ring["valid"] and ring["faces"] == 2 + 1 + 2
    assert ring["volume"] == pytest.approx(math.pi * (outer**2 - inner**2) / 4 * t, rel=1e-9)
    low, high = sorted(build.layers[p] for p in parts)
    assert low < first < high
    x, y = build.pose.joints[joint][1][0]
    assert ring["box"] == pytest.approx([x - outer / 2, y - outer / 2, first * t, x + outer / 2, y + outer / 2,
                                         (first + 1) * t], abs=1e-6)
    for pivot in build.pivots:
        pin = measure(solids[f"pin-{pivot.joints[0]}"])
        assert pin["box"][5] == pytest.approx((pivot.high + 1) * t + build.table.pin_diameter / 2, abs=1e-6)
    assert_apart(measure(shape)["box"] for shape in solids.values())


def test_linkgen_analyze_refuses_step(tmp_path):
    """``linkgen analyze`` makes no parts: asking it for step is one line saying which command does."""
    result = CliRunner().invoke(linkgen_main, ["analyze", str(ROOT / "templates" / "crank-rocker.toml"), "-o",
                                               str(tmp_path / "out"), "--set", 'output.formats=["step","json"]'])
    assert result.exit_code == 2 and "output.formats: 'step' writes the linkage's parts" in result.output
    assert "linkgen build" in result.output and not (tmp_path / "out").exists()


def test_a_build_without_step_never_imports_ocp(tmp_path):
    code = ("import sys; from camgen.api import design_cam, write_cam; "
            "from camgen.spec import load_spec; "
            f"write_cam(design_cam(load_spec({str(ROOT / 'templates' / 'rdrd.toml')!r}, "
            "['output.formats=[\"stl\",\"json\"]'])), 'out'); print('OCP' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=ENV, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "False" and (tmp_path / "out" / "rdrd.stl").exists()


def test_family_members_write_step(tmp_path):
    """A family passes its formats to every member: each writes its own STEP file."""
    text = (ROOT / "templates" / "valve-cams.toml").read_text()
    family = tmp_path / "valves.toml"
    family.write_text(text.replace('formats = ["dxf", "stl", "json"]', 'formats = ["step", "json"]'))
    assert 'formats = ["step", "json"]' in family.read_text()
    result = CliRunner().invoke(main, ["family", str(family), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    steps = sorted(tmp_path.rglob("*.step"))
    assert len(steps) == 3 and all(len(read_step(p)) == 1 for p in steps)


def test_same_parts_same_bytes(tmp_path):
    part = design_cam(template({"output.formats": ["json"]})).printed
    write_step([(part.name, (part,))], tmp_path / "a.step")
    write_step([(part.name, (part,))], tmp_path / "b.step")
    assert (tmp_path / "a.step").read_bytes() == (tmp_path / "b.step").read_bytes()


def test_step_is_never_written_unless_asked():
    assert "step" not in FORMATS
    assert "step" not in template().output.formats


def _refused(args: list[str], cwd, prelude: str = "") -> subprocess.CompletedProcess:
    code = f"import sys; {prelude}sys.argv = ['camgen', *{args!r}]; from camgen.cli import main; main()"
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, env=ENV, capture_output=True, text=True)


def test_without_the_extra_one_line_naming_the_install(tmp_path):
    """OCP made unimportable: asking for step is refused before anything is designed or written."""
    done = _refused(["build", str(ROOT / "templates" / "rdrd.toml"), "--set", 'output.formats=["step","stl"]'],
                    tmp_path, "sys.modules['OCP'] = None; ")
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert done.stderr.count("\n") == 1 and done.stderr.startswith("error: output.formats: 'step' needs")
    assert "pip install 'camgen[step]'" in done.stderr and "pip install '.[step]'" in done.stderr
    assert not (tmp_path / "out").exists()
    plain = _refused(["build", str(ROOT / "templates" / "rdrd.toml"), "--set", 'output.formats=["json"]'],
                     tmp_path, "sys.modules['OCP'] = None; ")
    assert plain.returncode == 0, plain.stderr


def test_barrel_cam_refused_in_one_line(tmp_path):
    done = _refused(["build", str(ROOT / "templates" / "barrel.toml"), "--set", 'output.formats=["step","stl"]'],
                    tmp_path)
    assert done.returncode == 2 and done.stderr.count("\n") == 1
    assert done.stderr.startswith("error: output.formats: a barrel cam has no flat part")
    assert not (tmp_path / "out").exists()


def _fc(want: dict) -> dict:
    return {"volume": want["volume"], "box": want["box"].tolist(), "faces": want["faces"]}


@COMMANDS
def test_freecad_reads_one_valid_solid(rdrd_cli):
    out, _ = rdrd_cli
    part, _ = step_part(design_cam(template()))
    done = freecad_check("step", out / "rdrd.step", [_fc(expect_plate(part))])
    assert done.returncode == 0, done.stdout.strip().splitlines()[-1][:2000]


def test_freecad_reads_a_keyway_and_bolt_holes(tmp_path):
    part = design_cam(template({**HOLES, "output.curves": "biarcs", "output.formats": ["json"]})).printed
    write_step([(part.name, (part,))], tmp_path / "hub.step")
    done = freecad_check("step", tmp_path / "hub.step", [_fc(expect_plate(part))])
    assert done.returncode == 0, done.stdout.strip().splitlines()[-1][:2000]


@COMMANDS
def test_freecad_reads_every_part_of_a_linkage(crank_rocker):
    """FreeCAD reads crank-rocker.step as the eight valid solids of the assembly: each part's and pin's exact volume,
    faces and box as assembled (see :func:`_linkage_expected`)."""
    out, build = crank_rocker
    expected = [{"volume": w["volume"], "box": w["box"].tolist(), "faces": w["faces"]}
                for w in _linkage_expected(out, build)]
    done = freecad_check("step", out / "crank-rocker.step", expected)
    assert done.returncode == 0, done.stdout.strip().splitlines()[-1][:2000]
    assert len(json.loads(done.stdout.strip().splitlines()[-1])["solids"]) == 8


@COMMANDS
def test_freecad_check_rejects_a_wrong_volume(rdrd_cli):
    out, _ = rdrd_cli
    want = _fc(expect_plate(step_part(design_cam(template()))[0]))
    done = freecad_check("step", out / "rdrd.step", [{**want, "volume": want["volume"] * (1 + 1e-5)}])
    assert done.returncode == 1
    assert json.loads(done.stdout.strip().splitlines()[-1])["solids"][0]["valid"]
