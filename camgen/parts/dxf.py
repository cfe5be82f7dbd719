"""The project's one DXF writer: a :class:`~camgen.parts.drawing.Drawing` to a DXF file.

Millimetres are declared in the header ($INSUNITS = 4, $MEASUREMENT = 1); contours
become closed LWPOLYLINEs whose arcs are exact bulges, circles become CIRCLEs; each
drawing layer becomes a DXF layer. ezdxf is imported here only (0.4 s).
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

from camgen.errors import ExportError
from camgen.parts.drawing import Circle, Contour, Drawing

#: ACI colour of each layer a laser job usually maps to an operation
LAYER_COLOURS = {"OUTLINE": 7, "HOLES": 1}


def dxf_document(drawing: Drawing, version: str = "R2010") -> Any:
    """An ezdxf document holding ``drawing``; raises :class:`ExportError` if ezdxf's audit finds errors."""
    import ezdxf
    from ezdxf import units

    doc = ezdxf.new(version, setup=False)
    doc.units = units.MM
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LUNITS"] = 2
    msp = doc.modelspace()
    for layer, shape in drawing.items:
        if layer not in doc.layers:
            doc.layers.add(layer, color=LAYER_COLOURS.get(layer, 7))
        attribs = {"layer": layer}
        if isinstance(shape, Circle):
            msp.add_circle(shape.centre, shape.radius, dxfattribs=attribs)
        elif isinstance(shape, Contour):
            pairs = zip(shape.vertices.tolist(), shape.bulges.tolist(), strict=True)
            points = [(x, y, 0.0, 0.0, b) for (x, y), b in pairs]
            msp.add_lwpolyline(points, format="xyseb", close=True, dxfattribs=attribs)
        else:
            raise ExportError(f"cannot write a {type(shape).__name__} to DXF")
    auditor = doc.audit()
    if auditor.has_errors:
        raise ExportError(f"the DXF failed ezdxf's audit: {auditor.errors[0].message}")
    return doc


def write_dxf(drawing: Drawing, path: Path, version: str = "R2010") -> None:
    """Write ``drawing`` to ``path`` as DXF."""
    dxf_document(drawing, version).saveas(path)
