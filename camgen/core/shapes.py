"""Plane geometry with exact arcs: closed contours of lines and arcs, circles, open lines, text.

Parts and drawings are made of these; nothing here knows a file format. Lengths in
mm, angles in radians; counter-clockwise is positive (seen from +Z).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np



def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


#: the axis directions 0, 90, 180 and 270 degrees at any turn an arc may start from (rad), and their unit vectors
_AXIS_ANGLES = np.array([k * math.pi / 2 for k in range(-4, 9)])
_AXIS_DIRECTIONS = np.array([[math.cos(a), math.sin(a)] for a in _AXIS_ANGLES.tolist()])


def _moved(points: np.ndarray, angle: float, shift: np.ndarray) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s], [-s, c]]) + shift


def arc_steps(radius: float, angle: float, tolerance: float) -> int:
    """Chords needed for an arc of ``radius`` (mm) through ``angle`` (rad) to stay within ``tolerance`` (mm)."""
    if radius <= tolerance:
        return max(1, math.ceil(abs(angle) / (2 * math.pi / 3)))
    max_step = 2.0 * math.acos(1.0 - tolerance / radius)
    return max(1, math.ceil(abs(angle) / max_step))


def reversed_pieces(vertices: np.ndarray, bulges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The vertices (n, 2) and bulges (n,) of a contour (see :class:`Contour`) traversed the other way: the
    vertices from last to first, and piece i's bulge the negated bulge of the piece that ran backwards over it
    (piece n - 2 - i, the closing piece staying last); a line's 0.0 becomes -0.0, as negating it always has."""
    b = np.empty(len(bulges))
    np.negative(bulges[-2::-1], out=b[:-1])
    b[-1] = -bulges[-1]
    return vertices[::-1], b


@dataclass(frozen=True)
class Contour:
    """A closed contour in LWPOLYLINE form.

    Piece i runs from ``vertices[i]`` to ``vertices[i + 1]`` (the last back to the
    first): a straight line where ``bulges[i]`` is 0, otherwise a circular arc with
    bulge = tan(included angle / 4), positive for a counter-clockwise arc.

    Parameters
    ----------
    vertices : array-like
        The n >= 2 vertices (mm), an (n, 2) array; copied and made read-only.
    bulges : array-like, optional
        The n pieces' bulges, each from its vertex to the next; all 0 (straight lines) by default.

    Raises
    ------
    ValueError
        Vertices that are not an (n, 2) array of n >= 2, or bulges that are not n.
    """

    vertices: np.ndarray
    bulges: np.ndarray = field(default=None)  # type: ignore[arg-type]

    def __post_init__(self) -> None:
        v = _frozen(self.vertices)
        b = _frozen(np.zeros(len(v)) if self.bulges is None else self.bulges)
        if v.ndim != 2 or v.shape[1] != 2 or len(v) < 2 or b.shape != (len(v),):
            raise ValueError("a contour needs n >= 2 vertices (n, 2) and n bulges")
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "bulges", b)

    @property
    def n_arcs(self) -> int:
        return int(np.count_nonzero(self.bulges))

    @property
    def n_lines(self) -> int:
        return len(self.bulges) - self.n_arcs

    def _arcs(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Per piece: start, end, chord length, signed included angle, centre (arcs only meaningful)."""
        p, q = self.vertices, np.roll(self.vertices, -1, axis=0)
        chord = np.linalg.norm(q - p, axis=1)
        angle = 4.0 * np.arctan(self.bulges)
        with np.errstate(divide="ignore", invalid="ignore"):
            h = np.where(self.bulges != 0, chord / (2.0 * np.tan(angle / 2.0)), 0.0)
            d = (q - p) / np.where(chord > 0, chord, 1.0)[:, None]
        centre = (p + q) / 2.0 + np.column_stack([-d[:, 1], d[:, 0]]) * h[:, None]
        return p, q, chord, angle, centre

    @cached_property
    def _arc_pieces(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`_arcs` of the arc pieces only (the same operations on the same numbers): their indices, starts,
        chord lengths, signed included angles and centres; made once a contour (its area and its flattening both
        need them, and a cam's outline has hundreds of chords and a few arcs)."""
        idx = self.bulges.nonzero()[0]
        p = self.vertices[idx]
        q = self.vertices[(idx + 1) % len(self.vertices)]
        qp = q - p
        square = qp**2
        chord = np.sqrt(square[:, 0] + square[:, 1])      # np.linalg.norm's sum of squares and root
        angle = 4.0 * np.arctan(self.bulges[idx])
        with np.errstate(divide="ignore", invalid="ignore"):
            h = chord / (2.0 * np.tan(angle / 2.0))
            d = qp / np.where(chord > 0, chord, 1.0)[:, None]
        return idx, p, chord, angle, (p + q) / 2.0 + np.column_stack([-d[:, 1], d[:, 0]]) * h[:, None]

    def arcs(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The arc pieces: their indices, centres (k, 2), radii (k,) and signed included angles (k,) in rad."""
        _, _, chord, angle, centre = self._arcs()
        idx = np.flatnonzero(self.bulges)
        radius = chord[idx] / (2.0 * np.abs(np.sin(angle[idx] / 2.0)))
        return idx, centre[idx], radius, angle[idx]

    def bounds(self) -> tuple[float, float, float, float]:
        """Exact (xmin, ymin, xmax, ymax) in mm: the vertices and the extreme points of the arcs (where an arc
        crosses an axis direction from its centre), all arcs at once with the numbers one arc at a time gave."""
        _, start_point, chord, sweep, centre = self._arc_pieces
        radius = chord / (2.0 * np.abs(np.sin(sweep / 2.0)))            # as arcs() has it
        p = start_point - centre
        start = np.array([math.atan2(dy, dx) for dx, dy in p.tolist()]).reshape(-1, 1)
        off = np.where(sweep[:, None] > 0, _AXIS_ANGLES[None, :] - start, start - _AXIS_ANGLES[None, :])
        arc, k = np.nonzero((off > 0) & (off < np.abs(sweep)[:, None]))
        allp = np.vstack([self.vertices, centre[arc] + radius[arc, None] * _AXIS_DIRECTIONS[k]])
        return float(allp[:, 0].min()), float(allp[:, 1].min()), float(allp[:, 0].max()), float(allp[:, 1].max())

    @property
    def area(self) -> float:
        """Signed area (mm^2, counter-clockwise positive), exact for the arcs."""
        p = self.vertices
        q = np.concatenate([p[1:], p[:1]])                              # np.roll's result
        polygon = 0.5 * float(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))
        idx, _, chord, angle, _ = self._arc_pieces
        segments = np.zeros(len(p))                                     # a line's segment is 0 (summed as such)
        with np.errstate(divide="ignore", invalid="ignore"):
            radius = chord / (2.0 * np.abs(np.sin(angle / 2.0)))
        segments[idx] = 0.5 * radius**2 * (angle - np.sin(angle))
        return polygon + float(np.sum(segments))

    def reversed(self) -> "Contour":
        """The same contour traversed the other way."""
        return Contour(*reversed_pieces(self.vertices, self.bulges))

    def moved(self, angle: float, shift: np.ndarray) -> "Contour":
        """The contour turned by ``angle`` (rad, ccw) about the origin, then moved by ``shift`` (mm); arcs stay arcs."""
        return Contour(_moved(self.vertices, angle, shift), self.bulges)

    def flatten(self, tolerance: float) -> np.ndarray:
        """Polygon vertices (m, 2), first not repeated, with every arc split into chords within ``tolerance`` mm."""
        idx, p, chord, angle, centre = self._arc_pieces
        # each arc's radius, chord count and start angle from its own numbers (scalar maths, as one arc at a time)
        to_start = (p - centre).tolist()
        radius, steps, start = [], [], []
        for c, a, (dx, dy) in zip(chord.tolist(), angle.tolist(), to_start, strict=True):
            r = c / (2.0 * abs(math.sin(a / 2.0)))
            radius.append(r)
            steps.append(arc_steps(r, a, tolerance))
            start.append(math.atan2(dy, dx))
        n = np.array(steps, dtype=int)
        # then every arc's inner chord ends at once: start + angle j / n for j = 1 .. n - 1
        arc = np.repeat(np.arange(len(idx)), n - 1)
        j = np.arange(len(arc)) - np.repeat(np.cumsum(n - 1) - (n - 1), n - 1) + 1
        a = np.array(start)[arc] + angle[arc] * j / n[arc]
        turn = np.empty((len(a), 2))
        turn[:, 0], turn[:, 1] = np.cos(a), np.sin(a)
        # each vertex, then (an arc's start) its arc's inner points
        count = np.ones(len(self.vertices), dtype=int)
        count[idx] += n - 1
        first = np.cumsum(count) - count
        out = np.empty((int(count.sum()), 2))
        out[first] = self.vertices
        out[first[idx][arc] + j] = centre[arc] + np.array(radius)[arc, None] * turn
        return out

    def flatten_error(self, tolerance: float) -> float:
        """The largest distance (mm) between this contour's arcs and the chords :meth:`flatten` puts for them."""
        idx, _, radius, angle = self.arcs()
        steps = np.array([arc_steps(r, a, tolerance) for r, a in zip(radius, angle, strict=True)])
        return float((radius * (1.0 - np.cos(np.abs(angle) / (2 * steps)))).max()) if len(idx) else 0.0


@dataclass(frozen=True)
class Circle:
    """A full circle: ``centre`` (x, y) in mm and ``radius`` in mm.

    Parameters
    ----------
    centre : tuple of float
        The centre (x, y), mm.
    radius : float
        The radius, mm.
    """

    centre: tuple[float, float]
    radius: float

    @property
    def area(self) -> float:
        return math.pi * self.radius**2

    def moved(self, angle: float, shift: np.ndarray) -> "Circle":
        """The circle turned by ``angle`` (rad, ccw) about the origin, then moved by ``shift`` (mm)."""
        c, s = math.cos(angle), math.sin(angle)
        x, y = self.centre
        return Circle((c * x - s * y + shift[0], s * x + c * y + shift[1]), self.radius)

    def flatten(self, tolerance: float) -> np.ndarray:
        """Counter-clockwise polygon (m, 2) with vertices on the circle, chords within ``tolerance`` mm."""
        n = max(arc_steps(self.radius, 2 * math.pi, tolerance), 8)
        a = 2 * math.pi * np.arange(n) / n
        return np.column_stack([self.centre[0] + self.radius * np.cos(a), self.centre[1] + self.radius * np.sin(a)])


@dataclass(frozen=True)
class Polyline:
    """An open line (marks to engrave): vertices (n, 2) in mm; ``bulges`` (n - 1) as in :class:`Contour`."""

    vertices: np.ndarray
    bulges: np.ndarray

    def flatten(self, tolerance: float) -> np.ndarray:
        """Points along the line, arcs within ``tolerance`` mm (the closing piece of a contour left off)."""
        pts = Contour(self.vertices, np.append(self.bulges, 0.0)).flatten(tolerance)
        end = int(np.flatnonzero(np.all(np.isclose(pts, self.vertices[-1]), axis=1))[-1])
        return pts[:end + 1]


@dataclass(frozen=True)
class Text:
    """A line of text to engrave: lower-left ``position`` (mm), ``height`` (mm), ``angle`` (degrees, ccw)."""

    text: str
    position: tuple[float, float]
    height: float
    angle: float = 0.0

    def flatten(self, tolerance: float) -> np.ndarray:
        """Its anchor point only (for bounds)."""
        return np.array([self.position])

    @property
    def box_width(self) -> float:
        """The width (mm) the text is laid out in: 0.6 of its height a character."""
        return 0.6 * self.height * len(self.text)

    def outlines(self, tolerance: float) -> tuple[Polyline, ...]:
        """The glyphs' outlines (closed polylines, mm; curves flattened by matplotlib at 100 units a text height,
        finer than ``tolerance`` for engraving sizes) in DejaVu Sans, scaled to fit the text's box (``box_width`` by
        ``height`` from ``position``) and turned by its angle about ``position``."""
        from matplotlib.font_manager import FontProperties
        from matplotlib.textpath import TextPath

        # drawn 100 units high, where matplotlib's flattening of the glyphs' curves is fine, then scaled down
        path = TextPath((0.0, 0.0), self.text, size=100.0, prop=FontProperties(family="DejaVu Sans"))
        rings = [ring for ring in (np.asarray(r, dtype=float) for r in path.to_polygons(closed_only=True))
                 if len(ring) >= 3]
        if not rings:
            return ()
        allp = np.vstack(rings)
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        scale = min(self.box_width / max(hi[0] - lo[0], 1e-12), self.height / max(hi[1] - lo[1], 1e-12))
        c, s = np.cos(np.radians(self.angle)), np.sin(np.radians(self.angle))
        turn = np.array([[c, -s], [s, c]])
        out = []
        for ring in rings:
            local = (ring - lo) * scale
            if np.allclose(local[0], local[-1]):
                local = local[:-1]
            closed = np.vstack([local, local[:1]]) @ turn.T + np.asarray(self.position)
            out.append(Polyline(closed, np.zeros(len(closed) - 1)))
        return tuple(out)


Shape = Contour | Circle

#: the shortest piece (line or arc) of a rounded hull's outline, as the distance between its two vertices (mm): two
#: vertices closer than this are merged into one (their midpoint), so that no reader (Open CASCADE, whose own
#: confusion distance is 1e-7 mm; FreeCAD, which makes an arc with coincident ends a full circle) gets a piece of
#: no length. Merging moves the outline by at most half of it.
MIN_PIECE_MM = 1e-6


def merged_pieces(vertices: np.ndarray, bulges: np.ndarray,
                  shortest: float = MIN_PIECE_MM) -> tuple[np.ndarray, np.ndarray]:
    """A closed contour's vertices (n, 2) and bulges (n,) (see :class:`Contour`) with every piece whose two
    vertices are less than ``shortest`` mm apart taken out: its two vertices become one at their midpoint, the
    pieces before and after it keep their bulges (an arc's ends move by at most ``shortest`` / 2, its included
    angle kept). The shortest piece goes first, until none is shorter or two vertices are left. For outlines whose
    arcs turn through at most half a turn (a short chord is then a short piece)."""
    vertices, bulges = np.asarray(vertices, dtype=float), np.asarray(bulges, dtype=float)
    if len(vertices) <= 2 or np.linalg.norm(np.roll(vertices, -1, axis=0) - vertices, axis=1).min() >= shortest:
        return vertices, bulges
    v, b = list(vertices), list(bulges)
    while len(v) > 2:
        chords = [math.dist(v[i], v[(i + 1) % len(v)]) for i in range(len(v))]
        i = min(range(len(v)), key=chords.__getitem__)
        if chords[i] >= shortest:
            break
        j = (i + 1) % len(v)
        v[i] = (v[i] + v[j]) / 2
        del v[j]
        del b[i]
    return np.array(v), np.array(b, dtype=float)


def rounded_hull(centres: np.ndarray, radius: float) -> Contour:
    """Counter-clockwise outline at ``radius`` mm round the convex hull of ``centres`` (k, 2): lines and exact arcs,
    none shorter than :data:`MIN_PIECE_MM` (a hull corner that turns so little, or two hull points so close, that its
    arc or line would be shorter is merged into one vertex: :func:`merged_pieces`)."""
    pts = np.asarray(centres, dtype=float)
    hull = convex_hull(pts)
    n = len(hull)
    if n == 1:
        c = hull[0]
        return Contour(np.array([c + np.array([radius, 0.0]), c - np.array([radius, 0.0])]), np.array([1.0, 1.0]))
    verts, bulges = [], []
    for i in range(n):
        a, b, c = hull[i], hull[(i + 1) % n], hull[(i + 2) % n]
        d1, d2 = b - a, c - b
        n1 = np.array([d1[1], -d1[0]]) / np.linalg.norm(d1)            # outward for a ccw hull
        n2 = np.array([d2[1], -d2[0]]) / np.linalg.norm(d2)
        turn = math.atan2(n1[0] * n2[1] - n1[1] * n2[0], float(n1 @ n2))
        if turn <= 0:                                                   # a straight-through vertex
            turn += 2 * math.pi if n == 2 else 0.0
        verts += [a + radius * n1, b + radius * n1]
        bulges += [0.0, math.tan(turn / 4)]
    return Contour(*merged_pieces(np.array(verts), np.array(bulges)))


def _turn(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> float:
    """Twice the signed area of triangle a, b, c: > 0 for a counter-clockwise turn."""
    return float((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))


def convex_hull(pts: np.ndarray) -> np.ndarray:
    """Convex hull of points (k, 2), counter-clockwise (monotone chain); collinear points dropped."""
    unique = np.unique(np.round(pts, 12), axis=0)
    if len(unique) <= 2:
        return unique

    def half(points: np.ndarray) -> list:
        out: list = []
        for p in points:
            while len(out) >= 2 and _turn(out[-2], out[-1], p) <= 0:
                out.pop()
            out.append(p)
        return out

    lower, upper = half(unique), half(unique[::-1])
    return np.array(lower[:-1] + upper[:-1])
