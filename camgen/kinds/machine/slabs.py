"""Straight-sided flat parts of a machine (a translating follower's stem, its flat face, its guide's rails with their
brackets) as part makers (:class:`~camgen.core.parts.PartMaker`) that grow exactly: the union of axis-parallel
boxes, the first one with an optional round foot. No I/O.

A slab's outline (mm, its own frame) is the union of its ``boxes`` ((x0, y0, x1, y1), each x0 < x1, y0 < y1);
with ``foot`` > 0 the first box's bottom side (y = y0) is replaced by a half circle of that radius about its middle
(the box must be 2 ``foot`` wide: a stem's foot round its roller's axle). Grown by g (mm, negative inwards) every
box is grown by g on each side and the foot's radius by g: the straight corners stay square (the outline moved out
along each side's normal), the foot stays tangent to the sides. Holes are ((x, y), nominal diameter) mm.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camgen.core.parts import Part
from camgen.core.shapes import Circle, Contour

Box = tuple[float, float, float, float]


@dataclass(frozen=True)
class Slab:
    """A part maker: the union of ``boxes`` (mm) with a round ``foot`` (mm, 0 for none) under the first, round
    ``holes`` ((centre, nominal diameter) mm), ``thickness`` and chord ``tolerance`` (mm)."""

    name: str
    boxes: tuple[Box, ...]
    holes: tuple[tuple[tuple[float, float], float], ...]
    thickness: float
    tolerance: float
    foot: float = 0.0

    @property
    def outline(self) -> Contour:
        """The nominal outline, counter-clockwise."""
        return self.contour(0.0)

    def contour(self, grow: float) -> Contour:
        """The outline moved out by ``grow`` mm (see the module's docstring), counter-clockwise."""
        grown = [(x0 - grow, y0 - grow, x1 + grow, y1 + grow) for x0, y0, x1, y1 in self.boxes]
        if self.foot > 0:
            if len(grown) != 1:
                raise ValueError("a slab with a foot is one box")
            x0, y0, x1, y1 = grown[0]
            y0 += grow                                      # the foot's diameter is the bottom side: no square rim
            return Contour(np.array([[x1, y1], [x0, y1], [x0, y0], [x1, y0]]), np.array([0.0, 0.0, 1.0, 0.0]))
        if len(grown) == 1:
            x0, y0, x1, y1 = grown[0]
            return Contour(np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]]))
        import shapely
        from shapely.geometry.polygon import orient

        union = shapely.union_all([shapely.box(*b) for b in grown])
        if not isinstance(union, shapely.Polygon) or len(union.interiors):
            raise ValueError(f"the boxes of {self.name} are not one simply connected outline")
        ring = np.asarray(orient(shapely.simplify(union, 0.0), 1.0).exterior.coords)[:-1]
        return Contour(ring)

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        """The part with its outline moved out by ``outline_grow`` and its holes' edges by ``hole_grow`` (mm)."""
        holes = tuple(Circle(c, d / 2 + hole_grow) for c, d in self.holes)
        return Part(self.name, self.contour(outline_grow), holes, self.thickness, self.tolerance)
