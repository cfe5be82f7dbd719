"""The project's one DXF writer: a :class:`~camgen.core.parts.Drawing` to a DXF file.

Millimetres are declared in the header ($INSUNITS = 4, $MEASUREMENT = 1; R12 has no
units header, its numbers are millimetres all the same). Each drawing layer becomes
a DXF layer. Three flavours, for the readers users have:

* ``polyline-bulge`` (default): each contour a closed LWPOLYLINE (R12: POLYLINE) whose
  arcs are exact bulges; circles as CIRCLE.
* ``lines-arcs``: each piece a LINE or an ARC, circles as CIRCLE, for readers that
  ignore bulges (OpenSCAD's import drops them without a word).
* ``segments``: LINEs only, arcs and circles as chords within the tolerance.

ezdxf is imported here only (0.4 s).
"""
from __future__ import annotations

import io
import math
from itertools import pairwise
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from camgen.core.errors import ExportError
from camgen.core.shapes import Circle, Contour, Polyline, Text
from camgen.core.writers import DXF_FLAVOURS, DXF_VERSIONS, WriteOptions

from camgen.core.parts import layer_colour

if TYPE_CHECKING:
    from camgen.core.parts import Drawing
from camgen.core.parts import Drawing



def _pieces(msp: Any, contour: Contour, attribs: dict, closed: bool = True) -> None:
    """A contour (or, ``closed`` False, an open line) as LINE and ARC entities."""
    idx, centres, radii, sweeps = contour.arcs()
    arcs = {int(i): (c, r, s) for i, c, r, s in zip(idx, centres, radii, sweeps, strict=True)}
    p, q = contour.vertices, np.roll(contour.vertices, -1, axis=0)
    for i in range(len(p) if closed else len(p) - 1):
        if i not in arcs:
            msp.add_line(tuple(p[i]), tuple(q[i]), dxfattribs=attribs)
            continue
        c, r, sweep = arcs[i]
        a0 = math.degrees(math.atan2(p[i][1] - c[1], p[i][0] - c[0]))
        a1 = math.degrees(math.atan2(q[i][1] - c[1], q[i][0] - c[0]))
        start, end = (a0, a1) if sweep > 0 else (a1, a0)      # DXF arcs run counter-clockwise
        msp.add_arc(tuple(c), float(r), start, end, dxfattribs=attribs)


def _open_line(msp: Any, line: Polyline, attribs: dict, version: str, flavour: str, tolerance: float) -> None:
    if flavour == "segments":
        pts = line.flatten(tolerance)
        for a, b in pairwise(pts):
            msp.add_line(tuple(a), tuple(b), dxfattribs=attribs)
    elif flavour == "lines-arcs":
        _pieces(msp, Contour(line.vertices, np.append(line.bulges, 0.0)), attribs, closed=False)
    else:
        pts = [(x, y, b) for (x, y), b in zip(line.vertices.tolist(), [*line.bulges.tolist(), 0.0], strict=True)]
        if version == "R12":
            msp.add_polyline2d(pts, format="xyb", dxfattribs=attribs)
        else:
            msp.add_lwpolyline([(x, y, 0.0, 0.0, b) for x, y, b in pts], format="xyseb", dxfattribs=attribs)


def dxf_document(drawing: Drawing, version: str = "R2010", flavour: str = "polyline-bulge") -> Any:
    """An ezdxf document holding ``drawing``; raises :class:`ExportError` if ezdxf's audit finds errors.

    The ``segments`` flavour turns arcs into chords within the drawing's tolerance.
    """
    import ezdxf
    from ezdxf import units

    if version not in DXF_VERSIONS or flavour not in DXF_FLAVOURS:
        raise ExportError(f"unknown DXF version {version!r} or flavour {flavour!r}")
    doc = ezdxf.new(version, setup=False)
    if version != "R12":
        doc.units = units.MM
        doc.header["$MEASUREMENT"] = 1
    doc.header["$LUNITS"] = 2
    msp = doc.modelspace()
    for layer, shape in drawing.items:
        if layer not in doc.layers:
            doc.layers.add(layer, color=layer_colour(layer)[0])
        attribs = {"layer": layer}
        if isinstance(shape, Text):
            msp.add_text(shape.text, height=shape.height, rotation=shape.angle,
                         dxfattribs=attribs).set_placement(shape.position)
        elif isinstance(shape, Polyline):
            _open_line(msp, shape, attribs, version, flavour, drawing.tolerance)
        elif flavour == "segments":
            ring = shape.flatten(drawing.tolerance)
            for a, b in zip(ring, np.roll(ring, -1, axis=0), strict=True):
                msp.add_line(tuple(a), tuple(b), dxfattribs=attribs)
        elif isinstance(shape, Circle):
            msp.add_circle(shape.centre, shape.radius, dxfattribs=attribs)
        elif flavour == "lines-arcs":
            _pieces(msp, shape, attribs)
        else:
            pairs = zip(shape.vertices.tolist(), shape.bulges.tolist(), strict=True)
            if version == "R12":
                msp.add_polyline2d([(x, y, b) for (x, y), b in pairs], format="xyb", close=True, dxfattribs=attribs)
            else:
                msp.add_lwpolyline([(x, y, 0.0, 0.0, b) for (x, y), b in pairs], format="xyseb", close=True,
                                   dxfattribs=attribs)
    auditor = doc.audit()
    if auditor.has_errors:
        raise ExportError(f"the DXF failed ezdxf's audit: {auditor.errors[0].message}")
    return doc


def _sorted_classes(text: str) -> str:
    """The CLASSES section's records sorted by class name.

    ezdxf adds a CLASS for each entity type in use by iterating a set, whose order
    follows Python's per-process string hashing; the records are independent, so
    sorting them makes the same drawing give the same bytes in every process.
    """
    head, sep, rest = text.partition("  0\nSECTION\n  2\nCLASSES\n")
    if not sep:
        return text
    body, end, tail = rest.partition("  0\nENDSEC\n")
    records = ["  0\nCLASS\n" + r for r in body.split("  0\nCLASS\n") if r]
    return head + sep + "".join(sorted(records, key=lambda r: r.split("\n")[3])) + end + tail


def write_dxf(drawing: Drawing, path: Path, options: WriteOptions | None = None) -> None:
    """Write ``drawing`` to ``path`` as DXF, in the flavour and version ``options`` ask for (default: R2010 with
    bulged polylines), its text as TEXT entities or, with ``options.text = "outline"``, as the glyphs' outlines."""
    options = options or WriteOptions()
    import logging

    import ezdxf

    log = logging.getLogger("ezdxf")
    level, fixed = log.level, ezdxf.options.write_fixed_meta_data_for_testing
    log.setLevel(logging.ERROR)           # R12 has no units header; ezdxf's notice of it is not the user's concern
    # fixed dates and GUIDs: the same drawing always gives the same bytes (reproducible builds and families)
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        shown = drawing.with_outlined_text() if options.text == "outline" else drawing
        doc = dxf_document(shown, options.dxf_version, options.dxf_flavour)
        stream = io.StringIO()
        doc.write(stream)
        path.write_text(_sorted_classes(stream.getvalue()), encoding=doc.output_encoding, errors="replace")
    finally:
        log.setLevel(level)
        ezdxf.options.write_fixed_meta_data_for_testing = fixed


WRITERS = {"dxf": write_dxf}
