"""Run by ``freecadcmd``: read a STEP file, check it holds the expected valid solids.

Reads the STEP path (CAMGEN_STEP) and the expected solids (CAMGEN_EXPECT: a JSON list, one entry a solid in the
file's order, each {"volume": mm^3, "box": [xmin, ymin, zmin, xmax, ymax, zmax], "faces": n}) from the
environment; the volume is checked to 1e-6 relative and the box to 1e-6 mm. Prints what FreeCAD found as JSON on
the last line and ends with an explicit exit code (an uncaught exception in freecadcmd still exits 0): 0 all good,
1 a check failed, 2 FreeCAD could not read the file.
"""
import json
import os
import sys

import Part  # FreeCAD's modules, present only inside freecadcmd


def main():
    expect = json.loads(os.environ["CAMGEN_EXPECT"])
    try:
        shape = Part.Shape()
        shape.read(os.environ["CAMGEN_STEP"])
    except Exception as exc:  # FreeCAD raises its own types
        print(json.dumps({"error": str(exc)}))
        return 2
    found = [{"valid": s.isValid(), "volume": s.Volume, "faces": len(s.Faces),
              "box": [s.BoundBox.XMin, s.BoundBox.YMin, s.BoundBox.ZMin, s.BoundBox.XMax, s.BoundBox.YMax,
                      s.BoundBox.ZMax]} for s in shape.Solids]
    ok = len(found) == len(expect) and all(
        f["valid"] and abs(f["volume"] - e["volume"]) <= 1e-6 * e["volume"] and f["faces"] == e["faces"]
        and all(abs(a - b) <= 1e-6 for a, b in zip(f["box"], e["box"], strict=True))
        for f, e in zip(found, expect, strict=True))
    print(json.dumps({"solids": found}))
    return 0 if ok else 1


sys.exit(main())
