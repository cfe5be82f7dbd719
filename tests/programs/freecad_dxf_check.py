"""Run by ``freecadcmd``: import a DXF, check every contour is a closed wire making a valid face.

Reads the DXF path and the expected areas (pairs of area and allowed difference)
and bounding box (JSON) from the environment (CAMGEN_DXF, CAMGEN_EXPECT), prints what FreeCAD found as JSON on the last
line, and ends with an explicit exit code (an uncaught exception in freecadcmd still
exits 0): 0 all good, 1 a check failed, 2 FreeCAD could not read the file.
"""
import json
import os
import sys

import FreeCAD  # FreeCAD's modules, present only inside freecadcmd
import Import
import Part


def main():
    path = os.environ["CAMGEN_DXF"]
    expect = json.loads(os.environ["CAMGEN_EXPECT"])
    try:
        doc = FreeCAD.newDocument("check")
        Import.readDXF(path)
        edges = [e for o in doc.Objects if hasattr(o, "Shape") for e in o.Shape.Edges]
    except Exception as exc:  # FreeCAD raises its own types
        print(json.dumps({"error": str(exc)}))
        return 2
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
    print(json.dumps(found))
    return 0 if ok else 1


sys.exit(main())
