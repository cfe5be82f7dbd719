"""Run by ``freecadcmd``: import a DXF, check every contour is a closed wire making a valid face.

Reads the DXF path and the expected areas (pairs of area and allowed difference)
and bounding box (JSON) from the environment (CAMGEN_DXF, CAMGEN_EXPECT), prints what FreeCAD found as JSON on the last
line, and ends with an explicit exit code (an uncaught exception in freecadcmd still
exits 0): 0 all good, 1 a check failed, 2 FreeCAD could not read the file.

Several files in one process (FreeCAD's start is most of a small file's check): CAMGEN_DXFS, a JSON list of
[path, expected] pairs, instead of the two above; the last line is then a JSON list of {"code": the exit code that
file alone would give, "found": what FreeCAD found in it}, in the list's order, and the exit code the greatest.
"""
import json
import os
import sys

import FreeCAD  # FreeCAD's modules, present only inside freecadcmd
import Import
import Part


def check(path, expect):
    """(exit code, what FreeCAD found) for one DXF file and its ``expect``ed areas and box; see the module. The
    file is read into a new document, closed again when several files are checked (each in a document of its
    own)."""
    doc = FreeCAD.newDocument("check")
    try:
        return _check(doc, path, expect)
    finally:
        if "CAMGEN_DXFS" in os.environ:
            FreeCAD.closeDocument(doc.Name)


def _check(doc, path, expect):
    try:
        Import.readDXF(path)
        edges = [e for o in doc.Objects if hasattr(o, "Shape") for e in o.Shape.Edges]
    except Exception as exc:  # FreeCAD raises its own types
        return 2, {"error": str(exc)}
    found = {"edges": len(edges), "wires": [], "problems": []}
    for group in Part.sortEdges(edges):
        wire = Part.Wire(group)
        if not wire.isClosed():
            found["problems"].append("open wire")
            continue
        face = Part.Face(wire)
        try:
            face.check(True)
        except Exception as exc:
            found["problems"].append(f"invalid face: {exc}")
            continue
        found["wires"].append(round(face.Area, 6))
    box = Part.Compound(edges).BoundBox if edges else None
    found["box"] = [box.XMin, box.YMin, box.XMax, box.YMax] if box else None
    areas = sorted(found["wires"])
    wanted = sorted(expect["areas"])          # [area, allowed difference] pairs, mm^2
    ok = (not found["problems"] and len(areas) == len(wanted)
          and all(abs(a - b) <= tol for a, (b, tol) in zip(areas, wanted, strict=True))
          and all(abs(a - b) <= expect["box_tol"] for a, b in zip(found["box"], expect["box"], strict=True)))
    return (0 if ok else 1), found


def main():
    if "CAMGEN_DXFS" in os.environ:
        results = [check(path, expect) for path, expect in json.loads(os.environ["CAMGEN_DXFS"])]
        print(json.dumps([{"code": code, "found": found} for code, found in results]))
        return max((code for code, _ in results), default=0)
    code, found = check(os.environ["CAMGEN_DXF"], json.loads(os.environ["CAMGEN_EXPECT"]))
    print(json.dumps(found))
    return code


sys.exit(main())
