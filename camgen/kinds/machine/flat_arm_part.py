"""An oscillating flat face's arm as a part that is cut and printed (``<machine>-<cam>-arm``): its exact outline
(lines and arcs), grown exactly for the kerf and the printer, the outline its clash body is cut from
(:mod:`camgen.kinds.machine.flat_arm`). No I/O.

In the arm's own frame (mm) the pivot is the origin and +X runs along the face: the arm is the rectangle
[0, ``far``] x [0, ``side`` depth] and an ear round each hole on the face's line (the pivot pin's at the origin, a
coupled four-bar's crank pin ``crank`` mm out), a disc of the hole's radius plus the ear's wall. The ears stand out
of the face's side (towards the cam) as arcs, the pivot's also behind the pivot; the rectangle is made long enough
that no ear passes its far end and deep enough that none passes its back, so the outline is: the face's line from
ear to ear (the envelope of the ears' circles where they overlap), the far end, the back, the pivot's end down to
the pivot's ear. Grown by g (mm, negative inwards) the rectangle moves out by g on each side and each ear's radius
by g, so the straight sides stay square and the arcs keep their centres (the exact offset of the union).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camgen.core.parts import Part
from camgen.core.shapes import Circle, Contour

#: (mm) the least room behind the deepest ear (the arm is made deeper where a large pin needs it)
BACK_WALL_MM = 1.0


@dataclass(frozen=True)
class FlatArmPart:
    """A part maker (:class:`~camgen.core.parts.PartMaker`): the arm of the module's docstring.

    Parameters
    ----------
    name : str
        ``<cam>-arm``.
    far : float
        The face's far end (mm from the pivot, along +X); lengthened to the farthest ear's edge.
    side : float
        +1 where the arm lies on +Y of the face (the cam on -Y), -1 the other way.
    depth : float
        The arm's depth away from the face (mm); deepened to the deepest ear's radius plus :data:`BACK_WALL_MM`.
    holes : tuple
        ((x, 0), nominal diameter) mm: round holes on the face's line, the first the pivot pin's at the origin.
    ears : tuple
        Each hole's ear radius (mm, nominal: the hole's clearance radius plus the ear's wall), in ``holes``' order.
    thickness, tolerance : float
        mm.
    """

    name: str
    far: float
    side: float
    depth: float
    holes: tuple[tuple[tuple[float, float], float], ...]
    ears: tuple[float, ...]
    thickness: float
    tolerance: float

    def __post_init__(self) -> None:
        xs = [c[0] for c, _ in self.holes]
        if not xs or xs[0] != 0.0 or any(c[1] != 0.0 for c, _ in self.holes) or len(self.ears) != len(xs):
            raise ValueError("a flat face's arm has its pivot's hole at the origin and every hole on the face")
        if any(x < e for x, e in zip(xs[1:], self.ears[1:], strict=True)):
            raise ValueError("a crank pin's ear reaches behind the flat face's pivot")
        object.__setattr__(self, "far", max(self.far, *(x + e for x, e in zip(xs, self.ears, strict=True))))
        object.__setattr__(self, "depth", max(self.depth, max(self.ears) + BACK_WALL_MM))

    @property
    def outline(self) -> Contour:
        """The nominal outline, counter-clockwise."""
        return self.contour(0.0)

    def contour(self, grow: float) -> Contour:
        """The outline moved out by ``grow`` mm (see the module's docstring), counter-clockwise."""
        g = grow
        radii = [e + g for e in self.ears]
        if min(radii) <= abs(g):
            raise ValueError(f"{self.name}: an ear of radius {min(self.ears):g} mm grown by {g:g} mm")
        vertices, bulges = _face_side([c[0] for c, _ in self.holes], radii, g)
        top = self.depth + g
        vertices += [(self.far + g, -g), (self.far + g, top), (-g, top)]
        bulges += [0.0, 0.0, 0.0]
        contour = Contour(np.array(vertices), np.array(bulges))
        if self.side < 0:                                   # mirrored about the face: reversed to stay ccw
            contour = Contour(contour.vertices * np.array([1.0, -1.0]), -contour.bulges).reversed()
        return contour

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        """The part with its outline moved out by ``outline_grow`` and its holes' edges by ``hole_grow`` (mm)."""
        holes = tuple(Circle(c, d / 2 + hole_grow) for c, d in self.holes)
        return Part(self.name, self.contour(outline_grow), holes, self.thickness, self.tolerance)


def _bulge(start: float, end: float) -> float:
    """The bulge of the counter-clockwise arc from angle ``start`` to ``end`` (rad): tan(sweep / 4)."""
    return math.tan(((end - start) % (2 * math.pi)) / 4)


def _face_side(centres: list[float], radii: list[float], g: float) -> tuple[list[tuple[float, float]], list[float]]:
    """The outline's run round the pivot's ear and along the face's side, counter-clockwise: from where the pivot's
    ear meets the back end (x = -g) round the ear and on along the line y = -g, each ear's circle (centre (c, 0),
    radius r) an arc from (c - h, -g) to (c + h, -g), h = sqrt(r^2 - g^2), or from and to the lower crossing of its
    neighbour's circle where the two overlap. Its vertices and their pieces' bulges, up to the last ear's end (the
    caller goes on to the far end).

    Raises ``ValueError`` where an ear lies within another or overlaps one that is not its neighbour."""
    order = sorted(range(len(centres)), key=lambda i: centres[i])
    c = [centres[i] for i in order]
    r = [radii[i] for i in order]
    h = [math.sqrt(x * x - g * g) for x in r]
    spans = []                                              # each ear's arc: its end points
    for i in range(len(c)):
        begin: tuple[float, float] = (-g, h[0]) if i == 0 else (c[i] - h[i], -g)
        spans.append([begin, (c[i] + h[i], -g)])
    for i in range(len(c) - 1):
        if any(c[j] - h[j] < c[i] + h[i] for j in range(i + 2, len(c))):
            raise ValueError("the ears of a flat face's arm overlap beyond their neighbours")
        if c[i + 1] - h[i + 1] < c[i] + h[i]:               # overlapping: they meet at their circles' lower crossing
            if c[i + 1] - r[i + 1] <= c[i] - r[i] or c[i + 1] + r[i + 1] <= c[i] + r[i]:
                raise ValueError("an ear of a flat face's arm lies within another")
            x = (r[i] ** 2 - r[i + 1] ** 2 + c[i + 1] ** 2 - c[i] ** 2) / (2 * (c[i + 1] - c[i]))
            crossing = (x, -math.sqrt(max(r[i] ** 2 - (x - c[i]) ** 2, 0.0)))
            spans[i][1] = spans[i + 1][0] = crossing
    vertices: list[tuple[float, float]] = []
    bulges: list[float] = []
    for i, (begin, finish) in enumerate(spans):
        vertices.append(begin)
        bulges.append(_bulge(math.atan2(begin[1], begin[0] - c[i]), math.atan2(finish[1], finish[0] - c[i])))
        if i + 1 == len(spans) or spans[i + 1][0] != finish:   # on along the face's line
            vertices.append(finish)
            bulges.append(0.0)
    return vertices, bulges
