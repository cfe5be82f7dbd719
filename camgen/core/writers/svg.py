"""The project's one SVG cut-file writer: a drawing in millimetres for laser software.

The page is the drawing's bounding box plus a margin, sized in mm (width="..mm"), with
a viewBox in the same millimetres, so 1 user unit is 1 mm. SVG's y axis points down:
points are mirrored (y -> top - y), which turns counter-clockwise arcs clockwise.
Each layer is a group with its own colour; strokes are hairlines (0.01 mm), no
fill, as laser software expects for cut and score lines. Arcs stay exact (A commands).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from xml.sax.saxutils import escape

import numpy as np

from camgen.core.shapes import Circle, Contour, Polyline, Text

from camgen.core.parts import layer_colour

if TYPE_CHECKING:
    from camgen.core.parts import Drawing

HAIRLINE_MM = 0.01
MARGIN_MM = 2.0
#: chord tolerance (mm) of the points that size the page; the 2 mm margin absorbs far more
PAGE_SAMPLING_MM = 0.01


def _bounds(drawing: Drawing) -> tuple[float, float, float, float]:
    pts = [s.flatten(PAGE_SAMPLING_MM) for _, s in drawing.items]
    allp = np.vstack(pts)
    return float(allp[:, 0].min()), float(allp[:, 1].min()), float(allp[:, 0].max()), float(allp[:, 1].max())


def _num(x: float) -> str:
    return f"{x:.6f}".rstrip("0").rstrip(".")


def svg_document(drawing: Drawing, stroke_width: float = HAIRLINE_MM) -> str:
    """The drawing as an SVG document (text); ``stroke_width`` in mm (hairline for laser software).

    Parameters
    ----------
    drawing : Drawing
        The shapes on their layers (mm); each layer is a group in its colour, arcs stay exact arcs.
    stroke_width : float, optional
        The lines' width (mm); by default a hairline, which laser software cuts along.

    Returns
    -------
    str
        The document, sized in mm (one user unit a millimetre), +Y up as in the drawing.
    """
    x0, y0, x1, y1 = _bounds(drawing)
    left, top = x0 - MARGIN_MM, y1 + MARGIN_MM
    width, height = (x1 - x0) + 2 * MARGIN_MM, (y1 - y0) + 2 * MARGIN_MM

    def pt(p: np.ndarray) -> str:
        return f"{_num(p[0] - left)},{_num(top - p[1])}"

    groups: dict[str, list[str]] = {}
    for layer, shape in drawing.items:
        if isinstance(shape, Text):
            x, y = shape.position
            groups.setdefault(layer, []).append(
                f'<text x="{_num(x - left)}" y="{_num(top - y)}" font-size="{_num(shape.height)}" '
                f'font-family="sans-serif" stroke="none" fill="currentColor" '
                f'transform="rotate({_num(-shape.angle)} {_num(x - left)} {_num(top - y)})">'
                f'{escape(shape.text)}</text>')
            continue
        if isinstance(shape, Polyline):
            groups.setdefault(layer, []).append(
                f'<path d="{_path(Contour(shape.vertices, np.append(shape.bulges, 0.0)), pt, closed=False)}"/>')
            continue
        if isinstance(shape, Circle):
            cx, cy = shape.centre
            groups.setdefault(layer, []).append(
                f'<circle cx="{_num(cx - left)}" cy="{_num(top - cy)}" r="{_num(shape.radius)}"/>')
            continue
        groups.setdefault(layer, []).append(f'<path d="{_path(shape, pt)}"/>')
    body = []
    for layer, items in groups.items():
        colour = layer_colour(layer)[1]
        body.append(f'<g id="{layer}" fill="none" stroke="{colour}" color="{colour}" '
                    f'stroke-width="{stroke_width}">')
        body.extend(f"  {item}" for item in items)
        body.append("</g>")
    return ("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{_num(width)}mm" '
            f'height="{_num(height)}mm" viewBox="0 0 {_num(width)} {_num(height)}">\n'
            + "\n".join(body) + "\n</svg>\n")


def _path(contour: Contour, pt: Callable[[np.ndarray], str], closed: bool = True) -> str:
    idx, _, radii, sweeps = contour.arcs()
    arcs = {int(i): (r, s) for i, r, s in zip(idx, radii, sweeps, strict=True)}
    v = contour.vertices
    parts = [f"M{pt(v[0])}"]
    for i in range(len(v) if closed else len(v) - 1):
        end = v[(i + 1) % len(v)]
        if i in arcs:
            r, sweep = arcs[i]
            large = 1 if abs(sweep) > math.pi else 0
            flag = 0 if sweep > 0 else 1           # mirrored y: counter-clockwise becomes clockwise
            parts.append(f"A{_num(r)},{_num(r)} 0 {large} {flag} {pt(end)}")
        elif i < len(v) - 1:                       # a closed path's last line is drawn by Z
            parts.append(f"L{pt(end)}")
    if closed:
        parts.append("Z")
    return " ".join(parts)


def write_svg(drawing: Drawing, path: Path, options: Any = None) -> None:
    """Write ``drawing`` to ``path`` as an SVG: hairline strokes for cutting, or the drawing's own ``stroke`` for
    one made to be looked at; its text as ``<text>`` or, with ``options.text = "outline"``, as the glyphs'
    outlines."""
    if options is not None and options.text == "outline":
        drawing = drawing.with_outlined_text()
    path.write_text(svg_document(drawing, drawing.stroke or HAIRLINE_MM), encoding="utf-8")


WRITERS = {"cut-svg": write_svg}
