"""Parts whose outline is their own (a gear, a rack, a ratchet wheel, a pawl), not the rounded hull of their holes.

A :class:`ShapedPart` is a :class:`linkgen.parts.LinkPart` (the same stock, pin holes, slots and placement) whose
outline is a given closed contour of lines and arcs (LWPOLYLINE form, counter-clockwise, mm, in the part's own
frame) and which may have toothed windows (an internal gear's teeth). Allowances move the outline and the windows by
their exact parallel curves (:func:`linkgen.gears.offset.offset_contour`), so arcs stay arcs and every tooth keeps
its shape: a cut gear's outline grows by half the kerf, its toothed windows shrink by it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camgen.core.errors import DesignError
from camgen.core.parts import Part
from camgen.core.shapes import Circle, Contour, Shape, merged_pieces, rounded_hull
from linkgen.gears.offset import offset_contour
from linkgen.parts import LinkPart

#: a contour: vertices (n, 2) mm and bulges (n,)
Pieces = tuple[np.ndarray, np.ndarray]


def contour_of(pieces: Pieces, grow: float = 0.0) -> Contour:
    """The contour of ``pieces`` moved outwards by ``grow`` mm, none of its pieces shorter than the project's least
    piece; a :class:`DesignError` naming ``parts.kerf`` where the move closes a feature."""
    try:
        vertices, bulges = offset_contour(*pieces, grow)
    except DesignError as exc:
        raise DesignError(f"parts.kerf: a kerf of {2 * abs(grow):g} mm is too wide for this outline: {exc}") from None
    return Contour(*merged_pieces(vertices, bulges))


@dataclass(frozen=True)
class ShapedPart(LinkPart):
    """A part with an outline of its own (``shape``), toothed ``windows`` (holes of their own shape), and a printed
    hub ``boss`` (diameter, height; mm) with a radial ``set_screw`` hole (diameter, mm) round its first hole."""

    shape: Pieces | None = None
    windows: tuple[Pieces, ...] = ()
    boss: tuple[float, float] | None = None
    set_screw: float = 0.0

    def outline(self, grow: float = 0.0) -> Contour:
        """The nominal outline moved outwards by ``grow`` mm (exactly: its parallel curve)."""
        if self.shape is None:
            return super().outline(grow)
        return contour_of(self.shape, grow)

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        """The part with its outline moved out by ``outline_grow`` and its holes' and windows' edges by ``hole_grow``
        (mm)."""
        radius = (self.stock.hole + 2 * hole_grow) / 2
        holes: list[Shape] = [Circle((float(x), float(y)), radius) for x, y in self.centres]
        holes += [rounded_hull(np.array(slot), radius) for slot in self.slots]
        holes += [contour_of(w, hole_grow) for w in self.windows]
        return Part(self.name, self.outline(outline_grow), tuple(holes), self.stock.thickness, self.stock.tolerance,
                    boss=self.boss, set_screw=self.set_screw)
