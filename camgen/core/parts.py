"""Flat parts and drawings, and the process allowances applied to them in one place.

A :class:`Part` is what a cutter cuts or a printer extrudes: one outer contour, holes,
marks to engrave, a thickness. A :class:`Drawing` is shapes on named layers, ready for
any 2-D writer. :class:`Allowances` turns a nominal part into the part as cut (kerf)
and as printed (clearance), for every product alike. Lengths in mm.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import NamedTuple, Protocol

from camgen.core.errors import DesignError
from camgen.core.shapes import Circle, Contour, Polyline, Shape, Text


@dataclass(frozen=True)
class Part:
    """A flat part: one outer contour (counter-clockwise), holes, a thickness (mm) and a tolerance (mm).

    ``tolerance`` is the chord tolerance used wherever exact arcs must become
    polygons (meshes, plots). ``marks`` are (layer, shape) pairs drawn but not cut
    (engraving). A hub ``boss`` (diameter, height; mm) stands on the top face round
    the first hole, with a radial ``set_screw`` hole (diameter, mm) through it. ``pockets`` are recesses into
    the top face (a grooved cam's groove). ``elephant_foot`` (mm, 0 for none) is the 45-degree chamfer a printed
    solid gets round its bed face (z = 0), against the first layer's squashed outline (see
    :func:`camgen.core.solids.extrude`).

    Parameters
    ----------
    name : str
        The part's name (file names and labels).
    outline : Contour
        The outer contour, counter-clockwise (mm).
    holes : tuple of Contour or Circle
        The holes through it, the bore first.
    thickness : float
        The plate's thickness (mm), the solid's extrusion along +Z.
    tolerance : float
        The chord tolerance (mm) wherever arcs become polygons.
    marks : tuple of tuple, optional
        (layer, shape) pairs drawn but not cut.
    boss : tuple of float, optional
        A hub boss (diameter, height; mm) on the top face round the first hole; None for none.
    set_screw : float, optional
        The diameter (mm) of a radial set-screw hole through the boss along +Y; 0 for none.
    pockets : tuple of Pocket, optional
        Recesses into the top face.
    elephant_foot : float, optional
        The printed solid's 45-degree chamfer round its bed face (mm); 0 for none.
    """

    name: str
    outline: Contour
    holes: tuple[Shape, ...]
    thickness: float
    tolerance: float
    marks: tuple[tuple[str, Polyline | Text], ...] = ()
    boss: tuple[float, float] | None = None
    set_screw: float = 0.0
    pockets: tuple[Pocket, ...] = ()
    elephant_foot: float = 0.0

    @property
    def area(self) -> float:
        """Plan area in mm^2: outline minus holes, exact."""
        return self.outline.area - sum(abs(h.area) for h in self.holes)

    def _repr_svg_(self) -> str:
        return Drawing.of_part(self)._repr_svg_()


class Placed(NamedTuple):
    """One solid of a file of several (a STEP file): its ``name``, its ``parts`` stacked from its own z = 0, each on
    the one before, and where it goes: turned by ``angle`` (rad, counter-clockwise seen from +Z) about its own
    origin, then moved by ``shift`` (x, y, z; mm). A plain ``(name, parts)`` pair is one at its own place."""

    name: str
    parts: Sequence[Part]
    angle: float = 0.0
    shift: tuple[float, float, float] = (0.0, 0.0, 0.0)


#: layer names used in every drawing
LAYER_OUTLINE = "OUTLINE"
LAYER_HOLES = "HOLES"
LAYER_ENGRAVE = "ENGRAVE"
LAYER_GROOVE = "GROOVE"
#: part names on a cut sheet: scored, not cut
LAYER_LABELS = "LABELS"

#: the AutoCAD Colour Index (ACI) numbers the drawings use, with their RGB in ACI's standard palette (as AutoCAD,
#: LibreCAD and ezdxf's ``aci2rgb`` give them): the one source of every layer's colour, written as the number in a
#: DXF and as this RGB in an SVG and a figure, so that both show the same colour. ACI 7 is the foreground colour
#: (white on a dark screen, black on paper): black here, since SVGs and figures are drawn on white
ACI_RGB = {1: "#ff0000", 3: "#00ff00", 4: "#00ffff", 5: "#0000ff", 6: "#ff00ff", 7: "#000000", 30: "#ff7f00",
           94: "#007f00"}


def _aci(number: int) -> tuple[int, str]:
    return number, ACI_RGB[number]


#: each layer's colour, the same in every format, as (ACI number, RGB) (:data:`ACI_RGB`): laser programs that assign
#: operations by colour see red outlines, blue holes (cut first), green marks to score and magenta pockets to engrave
#: to a depth, orange labels; an assembly's poses (layers ``DC1-...``, ``DC2-...``) each their own colour from
#: :data:`POSE_COLOURS`; other layers black
LAYER_COLOURS = {LAYER_OUTLINE: _aci(1), LAYER_HOLES: _aci(5), LAYER_ENGRAVE: _aci(3), LAYER_GROOVE: _aci(6),
                 LAYER_LABELS: _aci(30)}
POSE_COLOURS = tuple(_aci(n) for n in (5, 1, 94, 6, 30, 4))
OTHER_LAYER_COLOUR = _aci(7)


def layer_colour(layer: str) -> tuple[int, str]:
    """(AutoCAD colour index, RGB hex) of ``layer``."""
    if layer.startswith("DC") and layer[2:].partition("-")[0].isdigit():
        return POSE_COLOURS[(int(layer[2:].partition("-")[0]) - 1) % len(POSE_COLOURS)]
    return LAYER_COLOURS.get(layer, OTHER_LAYER_COLOUR)


@dataclass(frozen=True)
class Pocket:
    """A recess into a part's top face, ``depth`` mm deep (less than the part's thickness): the region inside
    ``outer`` and outside ``inner`` (both counter-clockwise; ``inner`` None for a plain pocket), drawn on
    ``layer`` (a groove's two flanks: a laser engraves or pockets that layer, it does not cut it)."""

    outer: Contour
    inner: Contour | None
    depth: float
    layer: str = LAYER_GROOVE

    @property
    def contours(self) -> tuple[Contour, ...]:
        """Its boundary: ``outer``, then ``inner`` if any."""
        return (self.outer,) if self.inner is None else (self.outer, self.inner)

    @property
    def area(self) -> float:
        """Plan area in mm^2, exact for the arcs."""
        return self.outer.area - (self.inner.area if self.inner is not None else 0.0)


def preview_stroke(items: tuple | list) -> float:
    """A line width (mm) for a preview drawing of ``items`` ((layer, shape) pairs): 1/500 of its contours' larger
    extent, at least 0.2 (0.2 with no contour)."""
    boxes = [shape.bounds() for _, shape in items if isinstance(shape, Contour)]
    if not boxes:
        return 0.2
    x0, y0, x1, y1 = (f(b[i] for b in boxes) for i, f in enumerate((min, min, max, max)))
    return round(max(0.2, max(x1 - x0, y1 - y0) / 500.0), 2)


@dataclass(frozen=True)
class Drawing:
    """Shapes on named layers, in mm, ready for any 2-D writer.

    ``tolerance`` (mm) is the chord tolerance wherever a writer must turn arcs into
    lines (the DXF ``segments`` flavour, previews). ``stroke`` (mm) is the SVG's line width for a
    drawing made to be looked at (an assembly); None keeps the hairline a laser cuts along.

    Parameters
    ----------
    items : tuple of tuple
        (layer, shape) pairs in drawing order: a :class:`~camgen.core.shapes.Contour`, a
        :class:`~camgen.core.shapes.Circle`, an open polyline or a text, in mm.
    tolerance : float
        The chord tolerance (mm) wherever arcs become lines.
    stroke : float or None, optional
        The SVG's line width (mm); None for a hairline.
    """

    items: tuple[tuple[str, Shape | Polyline | Text], ...]
    tolerance: float
    stroke: float | None = None

    def _repr_svg_(self) -> str:
        """Jupyter shows the drawing (strokes 0.3 mm wide, so they show on screen)."""
        from camgen.core.writers.svg import svg_document

        return svg_document(self, stroke_width=0.3)

    def with_outlined_text(self) -> "Drawing":
        """The same drawing with every text as its glyphs' outlines, on the text's layer."""
        items: list = []
        for layer, shape in self.items:
            items += [(layer, line) for line in shape.outlines(self.tolerance)] if isinstance(shape, Text) else [
                (layer, shape)]
        return Drawing(tuple(items), self.tolerance, self.stroke)

    @classmethod
    def of_part(cls, part: Part) -> "Drawing":
        """A part's outline on ``OUTLINE``, its holes on ``HOLES``, its pockets' boundaries and its marks on their
        own layers."""
        pockets = ((p.layer, c) for p in part.pockets for c in p.contours)
        return cls(((LAYER_OUTLINE, part.outline), *((LAYER_HOLES, h) for h in part.holes), *pockets, *part.marks),
                   part.tolerance)


class PartMaker(Protocol):
    """Anything that can make its part with its outline and holes moved outwards (into the air) by given
    distances (mm, negative inwards), exactly: cams regenerate their outline from the offset surface,
    bars round their hole centres at a larger radius."""

    def part(self, outline_grow: float, hole_grow: float) -> Part: ...


@dataclass(frozen=True)
class Allowances:
    """Process allowances (mm), the one place they are applied.

    ``kerf``: the laser burns kerf/2 either side of its path, so a cut part's outline
    is moved out by kerf/2 and its holes in by kerf/2 (a hole's diameter less the kerf).
    ``clearance``: a printed hole is opened by this in diameter (clearance/2 a side).
    ``elephant_foot``: a printed part's bed face is chamfered by this at 45 degrees (its outline inset, its holes
    opened by it), against the first layer's squashed, widened outline.

    Parameters
    ----------
    kerf : float, optional
        The laser's kerf (mm): cut outlines grow and holes shrink by half of it.
    clearance : float, optional
        The printing clearance (mm): printed holes grow by it in diameter.
    kerf_field : str, optional
        The template key that sets the kerf, named when it closes a hole (``output.kerf``).
    elephant_foot : float, optional
        The printed bed face's 45-degree chamfer (mm).
    """

    kerf: float = 0.0
    clearance: float = 0.0
    #: the template field that sets the kerf, named when it is too wide for a hole
    kerf_field: str = "kerf"
    elephant_foot: float = 0.0

    def cut(self, maker: PartMaker) -> Part:
        """The part as the cut files carry it; refused when the kerf would close a hole."""
        part = maker.part(self.kerf / 2, -self.kerf / 2)
        for hole in part.holes:
            if (hole.radius if isinstance(hole, Circle) else hole.area) <= 0:
                raise DesignError(f"{self.kerf_field}: a kerf of {self.kerf:g} mm closes a hole of {part.name} "
                                  "(the laser would burn away more than the hole); the kerf must be smaller than the "
                                  "narrowest hole")
        return part

    def printed(self, maker: PartMaker) -> Part:
        """The part as the printed files carry it."""
        part = maker.part(0.0, self.clearance / 2)
        return replace(part, elephant_foot=self.elephant_foot) if self.elephant_foot else part

    def cut_diameter(self, diameter: float) -> float:
        """A hole of ``diameter`` mm as drawn in a cut file."""
        return diameter - self.kerf

    def printed_diameter(self, diameter: float) -> float:
        """A hole of ``diameter`` mm as made in a printed file."""
        return diameter + self.clearance
