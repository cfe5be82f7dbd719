"""Run by ``freecadcmd``: read several STEP files in one process and print the solids FreeCAD finds in each.

Reads the STEP paths from the environment (CAMGEN_STEPS: a JSON list). Prints one JSON object on the last line,
{path: [solid, ...]} in each file's order, each solid {"valid": bool, "volume": mm^3, "box": [xmin, ymin, zmin,
xmax, ymax, zmax]}, or {path: {"error": text}} for a file FreeCAD could not read; ends with an explicit exit code
(an uncaught exception in freecadcmd still exits 0): 0 every file read, 2 one could not be.
"""
import json
import os
import sys

import Part  # FreeCAD's modules, present only inside freecadcmd


def _solids(path):
    shape = Part.Shape()
    shape.read(path)
    return [{"valid": s.isValid(), "volume": s.Volume,
             "box": [s.BoundBox.XMin, s.BoundBox.YMin, s.BoundBox.ZMin, s.BoundBox.XMax, s.BoundBox.YMax,
                     s.BoundBox.ZMax]} for s in shape.Solids]


def main():
    found, code = {}, 0
    for path in json.loads(os.environ["CAMGEN_STEPS"]):
        try:
            found[path] = _solids(path)
        except Exception as exc:  # FreeCAD raises its own types
            found[path], code = {"error": str(exc)}, 2
    print(json.dumps(found))
    return code


sys.exit(main())
