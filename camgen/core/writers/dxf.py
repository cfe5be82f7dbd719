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
import threading
from itertools import pairwise
from pathlib import Path
from typing import Any

import numpy as np

from camgen.core.errors import ExportError
from camgen.core.parts import Drawing, layer_colour
from camgen.core.shapes import Circle, Contour, Polyline, Text
from camgen.core.writers import DXF_FLAVOURS, DXF_VERSIONS, WriteOptions


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


def _lwpolyline(msp: Any, vertices: np.ndarray, bulges: np.ndarray, closed: bool, attribs: dict) -> None:
    """An LWPOLYLINE through ``vertices`` (n, 2) with ``bulges`` (n): its points set as one (x, y, start width,
    end width, bulge) array (ezdxf's ``lwpoints.set``), not point by point as ``add_lwpolyline`` does (the same
    entity: 10 times faster for a cam's outline)."""
    points = np.zeros((len(vertices), 5))
    points[:, :2] = vertices
    points[:, 4] = bulges
    msp.add_lwpolyline([], close=closed, dxfattribs=attribs).lwpoints.set(points)


def _open_line(msp: Any, line: Polyline, attribs: dict, version: str, flavour: str, tolerance: float) -> None:
    if flavour == "segments":
        pts = line.flatten(tolerance)
        for a, b in pairwise(pts):
            msp.add_line(tuple(a), tuple(b), dxfattribs=attribs)
    elif flavour == "lines-arcs":
        _pieces(msp, Contour(line.vertices, np.append(line.bulges, 0.0)), attribs, closed=False)
    else:
        if version == "R12":
            rows = [(x, y, b) for (x, y), b in zip(line.vertices.tolist(), [*line.bulges.tolist(), 0.0], strict=True)]
            msp.add_polyline2d(rows, format="xyb", dxfattribs=attribs)
        else:
            _lwpolyline(msp, line.vertices, np.append(line.bulges, 0.0), False, attribs)


def _new_document(version: str) -> Any:
    """An empty ezdxf document of ``version`` in millimetres (no ezdxf setup: no extra styles or line types)."""
    import ezdxf
    from ezdxf import units

    if version not in DXF_VERSIONS:
        raise ExportError(f"unknown DXF version {version!r}")
    doc = ezdxf.new(version, setup=False)
    if version != "R12":
        doc.units = units.MM
        doc.header["$MEASUREMENT"] = 1
    doc.header["$LUNITS"] = 2
    return doc


def _check(drawing: Drawing) -> None:
    """What ezdxf's audit would find in the entities we add, checked on the drawing instead (ezdxf writes a NaN
    as "nan" without a word; every layer is added before its first entity, owners and handles are ezdxf's own).
    Raises :class:`ExportError` naming the layer."""
    for layer, shape in drawing.items:
        if isinstance(shape, Text):
            numbers, positive = np.array([*shape.position, shape.angle]), shape.height
        elif isinstance(shape, Circle):
            numbers, positive = np.array(shape.centre), shape.radius
        else:
            numbers, positive = np.append(shape.vertices.ravel(), shape.bulges), 1.0
        if not (np.isfinite(numbers).all() and math.isfinite(positive) and positive > 0):
            raise ExportError(f"layer {layer}: a {type(shape).__name__.lower()} with a non-finite or non-positive size "
                              "cannot be written as DXF")


def _add_drawing(doc: Any, drawing: Drawing, version: str, flavour: str) -> list[str]:
    """Add ``drawing``'s layers (each before its first entity) and entities to ``doc``'s modelspace; the names of
    the layers added."""
    if flavour not in DXF_FLAVOURS:
        raise ExportError(f"unknown DXF flavour {flavour!r}")
    msp = doc.modelspace()
    added = []
    for layer, shape in drawing.items:
        if layer not in doc.layers:
            doc.layers.add(layer, color=layer_colour(layer)[0])
            added.append(layer)
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
            if version == "R12":
                pairs = zip(shape.vertices.tolist(), shape.bulges.tolist(), strict=True)
                msp.add_polyline2d([(x, y, b) for (x, y), b in pairs], format="xyb", close=True, dxfattribs=attribs)
            else:
                _lwpolyline(msp, shape.vertices, shape.bulges, True, attribs)
    return added


def dxf_document(drawing: Drawing, version: str = "R2010", flavour: str = "polyline-bulge") -> Any:
    """A new ezdxf document holding ``drawing``; raises :class:`ExportError` if ezdxf's audit finds errors.

    The ``segments`` flavour turns arcs into chords within the drawing's tolerance. :func:`write_dxf` writes the
    same bytes as this document's ``write`` (CLASSES sorted) without making a new document for every file
    (:class:`_Boilerplate`); the tests hold the two to each other and audit the files written.
    """
    doc = _new_document(version)
    _add_drawing(doc, drawing, version, flavour)
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


class _Boilerplate:
    """One DXF version's document, reused for file after file, and the text of its sections that are the same in
    every file (header, classes, most tables, blocks, most objects: 80 % of the time of ``Drawing.write``).

    For each file the document's handles restart where a new document's do, the drawing's layers and entities
    are added and ezdxf's ``update_all`` (what ``write`` does first) makes what a write makes (the next handle,
    R2010's "written by" marker object, R12's two application ids); ezdxf's own exporters then write the parts
    that change (the LAYER and APPID tables, the entities, the objects from ezdxf's marker dictionary on) between
    the fixed text, and what was added is removed again. The header's one changing value, $HANDSEED (the next
    handle), goes between the two fixed parts of the header's text. The tests hold the bytes to a new document's
    (:func:`dxf_document`) for every flavour and version. Used under :data:`_LOCK` only.
    """

    def __init__(self, version: str) -> None:
        from ezdxf.lldxf.const import DXF12

        self.version = version
        self.doc = _new_document(version)
        self.seed = int(str(self.doc.entitydb.handles), 16)
        self.size = (len(self.doc.entitydb), len(self.doc.layers), len(self.doc.appids))
        self.handles = self.doc.dxfversion > DXF12 or bool(self.doc.header.get("$HANDLING", 0))
        self.fixed: dict[str, str] | None = None
        self.meta = None

    def _writer(self, stream: io.StringIO) -> Any:
        from ezdxf.lldxf.tagwriter import TagWriter

        return TagWriter(stream, write_handles=self.handles, dxfversion=self.doc.dxfversion)

    def _export(self, *parts: Any) -> str:
        stream = io.StringIO()
        writer = self._writer(stream)
        for part in parts:
            part.export_dxf(writer)
        return stream.getvalue()

    def _fixed(self) -> dict[str, str]:
        """The fixed text, exported by ezdxf once (after the first file's ``update_all``)."""
        from ezdxf.document import EZDXF_META
        from ezdxf.lldxf.const import DXF12

        doc, tables = self.doc, self.doc.tables
        header = self._export(doc.header)
        mark = f"  9\n$HANDSEED\n  5\n{doc.header['$HANDSEED']}\n"
        head, _, tail = header.partition(mark) if self.handles else (header, "", "")
        objects: list = []
        if doc.dxfversion > DXF12:
            self.meta = doc.rootdict[EZDXF_META]
            objects = list(doc.objects)
            objects = objects[:objects.index(self.meta)]
        return {"head": head + ("  9\n$HANDSEED\n  5\n" if self.handles else ""), "tail": tail,
                "classes": _sorted_classes(self._export(doc.classes)) if doc.dxfversion > DXF12 else "",
                "tables1": "  0\nSECTION\n  2\nTABLES\n" + self._export(tables.viewports, tables.linetypes),
                "tables2": self._export(tables.styles, tables.views, tables.ucs),
                "tables3": self._export(tables.dimstyles, *([tables.block_records] if doc.dxfversion > DXF12
                                                            else [])) + "  0\nENDSEC\n",
                "blocks": self._export(doc.blocks),
                "objects": "  0\nSECTION\n  2\nOBJECTS\n" + self._export(*objects) if objects else ""}

    def text(self, drawing: Drawing, flavour: str) -> str:
        """The DXF file's text for ``drawing``: byte for byte what :func:`dxf_document`'s ``write`` gives."""
        from ezdxf.document import WRITTEN_BY_EZDXF
        from ezdxf.lldxf.const import DXF12

        doc = self.doc
        doc.entitydb.handles.reset(f"{self.seed:X}")
        try:
            _add_drawing(doc, drawing, self.version, flavour)
            doc.commit_pending_changes()
            doc.update_all()
            if self.fixed is None:
                self.fixed = self._fixed()
            fixed, stream = self.fixed, io.StringIO()
            writer = self._writer(stream)
            stream.write(fixed["head"] + (f"{doc.header['$HANDSEED']}\n" if self.handles else "") + fixed["tail"])
            stream.write(fixed["classes"] + fixed["tables1"])
            doc.tables.layers.export_dxf(writer)
            stream.write(fixed["tables2"])
            doc.tables.appids.export_dxf(writer)
            stream.write(fixed["tables3"] + fixed["blocks"])
            doc.entities.export_dxf(writer)
            if doc.dxfversion > DXF12:
                stream.write(fixed["objects"])
                objects = list(doc.objects)
                for entity in objects[objects.index(self.meta):]:
                    entity.export_dxf(writer)
                writer.write_tag2(0, "ENDSEC")
            writer.write_tag2(0, "EOF")
            return stream.getvalue()
        finally:                                   # back to the state of a new document
            msp = doc.modelspace()
            for entity in list(msp):        # not delete_all_entities: it takes each out of a list, n squared
                doc.entitydb.delete_entity(entity)
            msp.purge()
            for table in (doc.layers, doc.appids):
                for entry in [e for e in table if int(e.dxf.handle, 16) >= self.seed]:
                    table.remove(entry.dxf.name)
            if doc.dxfversion > DXF12 and WRITTEN_BY_EZDXF in doc.ezdxf_metadata():
                del doc.ezdxf_metadata()[WRITTEN_BY_EZDXF]
            doc.entitydb.purge()
            if (len(doc.entitydb), len(doc.layers), len(doc.appids)) != self.size:
                _PLATES.pop(self.version, None)            # not as new: the next file starts afresh


#: the :class:`_Boilerplate` of each DXF version in this process
_PLATES: dict[str, _Boilerplate] = {}
#: held while a file is made: the documents and ezdxf's options are this process's, and a Dask worker runs
#: members in threads
_LOCK = threading.Lock()


def write_dxf(drawing: Drawing, path: Path, options: WriteOptions | None = None) -> None:
    """Write ``drawing`` to ``path`` as DXF, in the flavour and version ``options`` ask for (default: R2010 with
    bulged polylines), its text as TEXT entities or, with ``options.text = "outline"``, as the glyphs' outlines.

    The bytes are those of :func:`dxf_document`'s ``write`` (ezdxf's audit of it is run by the tests on what is
    written: for the entities added here, a check of the drawing's numbers, :func:`_check`, is what it guards).

    Parameters
    ----------
    drawing : Drawing
        The shapes on their layers (mm); the file declares millimetres (R12 has no units header).
    path : Path
        The file to write (replaced if it exists).
    options : WriteOptions, optional
        The DXF version (``"R2010"``, ``"R12"``), flavour (``"polyline-bulge"``, ``"lines-arcs"``,
        ``"segments"``) and text mode (``"text"``, ``"outline"``).

    Raises
    ------
    ExportError
        An unknown version or flavour, or a shape with a non-finite or non-positive size.
    """
    options = options or WriteOptions()
    import logging

    import ezdxf

    version, flavour = options.dxf_version, options.dxf_flavour
    if version not in DXF_VERSIONS or flavour not in DXF_FLAVOURS:
        raise ExportError(f"unknown DXF version {version!r} or flavour {flavour!r}")
    shown = drawing.with_outlined_text() if options.text == "outline" else drawing
    _check(shown)
    log = logging.getLogger("ezdxf")
    with _LOCK:
        level, fixed = log.level, ezdxf.options.write_fixed_meta_data_for_testing
        log.setLevel(logging.ERROR)       # R12 has no units header; ezdxf's notice of it is not the user's concern
        # fixed dates and GUIDs: the same drawing always gives the same bytes (reproducible builds and families)
        ezdxf.options.write_fixed_meta_data_for_testing = True
        try:
            plate = _PLATES.get(version) or _PLATES.setdefault(version, _Boilerplate(version))
            text, encoding = plate.text(shown, flavour), plate.doc.output_encoding
        finally:
            log.setLevel(level)
            ezdxf.options.write_fixed_meta_data_for_testing = fixed
    path.write_text(text, encoding=encoding, errors="replace")


WRITERS = {"dxf": write_dxf}
