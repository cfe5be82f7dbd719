"""Cut sheets: any parts laid on sheets by their true outlines, with a gap between them and to the sheet's edge.

:func:`nest` places any tuple of :class:`camgen.core.parts.Part` (cams, linkage bars, a kit's frames and spacers)
on as many sheets as they need: each part turned by one of the allowed rotations (degrees, counter-clockwise,
about its own origin; arcs stay exact arcs) and moved, so that no two outlines come closer than ``gap`` (kerf +
margin, mm) and no outline comes closer than ``gap`` to a sheet's edge. Holes are not filled with small parts (a
part in another's hole would need the cutter to cut it first).

The method (ours, on shapely and numpy; docs/guides/cut-sheets.md compares it with the libraries tried):

1. **Raster bottom-left fill.** The sheet is a grid of square cells; each part's footprint (its outline as
   chords, grown by gap / 2 and by the chords' largest distance from the arcs) covers the cells it touches, for
   each allowed rotation. One FFT correlation of the sheet's occupied cells with a footprint gives the overlap at
   every grid position at once; the part goes to the free position that keeps the layout's rectangle from the
   sheet's corner least (then the least right-hand extent, then the lowest), among all its rotations, on the
   first sheet where it fits. Cells that a
   footprint only touches count as covered, so footprints on free cells never overlap: the gap holds exactly.
2. **Exact compaction.** The part then slides left and down by the exact clearance shapely measures between
   its outline and the others' and the sheet's edges, less the gap, so the grid's rounding is given back.
3. **A few orders, the best kept.** The parts are placed largest first; a fixed number of orders (by area, by
   length, by height) are tried, and the shelf layout too, and the layout with the fewest sheets, then the least
   used area, kept: never worse than the shelves.

Everything is deterministic: no random numbers and no clock; the work is bounded by the number of orders and
rotations, not by time, so the same parts always give the same sheets (the golden hashes rely on it). The memory
is bounded too: a part keeps its outline's chords and each rotation's box (a polygon a rotation is made when
needed), and the footprints kept for the later orders take a bit a cell, FOOTPRINT_CACHE_BYTES in all at most.

The shelf packing of bounding rectangles (:func:`shelf`, now with the gap to the edges too) is kept as the
reference: the report gives
both utilisations, each the parts' area over the sheet area the layout uses (:func:`used_area`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import DesignError
from camgen.core.parts import LAYER_HOLES, LAYER_LABELS, LAYER_OUTLINE, Drawing, Part
from camgen.core.shapes import Contour, Polyline, Text, _moved

#: rotations (degrees) a part may take when nothing else is said: quarter turns
QUARTER_TURNS = (0.0, 90.0, 180.0, 270.0)
#: rotations with the grain: the part keeps its direction along the sheet (upside down allowed)
WITH_GRAIN = (0.0, 180.0)
#: the most grid cells a sheet is divided into (the grid's cell is the larger of this bound's and MIN_CELL_MM)
MAX_CELLS = 250_000
#: the finest grid cell (mm)
MIN_CELL_MM = 0.25
#: chord tolerance (mm) of the outlines the nesting works on (the drawing keeps the exact arcs)
NEST_TOLERANCE_MM = 0.05
#: slides of the exact compaction after each placement (each a move left then down)
COMPACTION_PASSES = 4
#: the layouts tried, the best kept: the parts' order (largest area, length or height first) and where a placement
#: leans among positions that keep the same rectangle ("left": the least right-hand extent first, "down": the
#: lowest first)
TRIES = (("area", "left"), ("area", "down"), ("length", "left"), ("height", "down"))
#: the most bytes one :func:`nest` keeps of the footprints it makes for reuse by the later layouts (their cells a bit
#: each, and ENTRY_BYTES an entry); past it a footprint is made each time it is needed, with the same cells
FOOTPRINT_CACHE_BYTES = 32 * 2**20
#: what one kept footprint costs beyond its cells' bits (bytes: the arrays' headers, its corner, the dict's slot)
ENTRY_BYTES = 512
#: engraved labels: the tallest and the smallest worth engraving (mm)
LABEL_MAX_MM = 5.0
LABEL_MIN_MM = 1.0


@dataclass(frozen=True)
class SheetRules:
    """How parts go on a sheet: its ``size`` (width along +X, height along +Y; mm), the ``gap`` (mm) kept between
    parts and to the sheet's edges (kerf + margin), the allowed ``rotations`` (degrees, counter-clockwise) and the
    template field named when a part is too large (``field``)."""

    size: tuple[float, float]
    gap: float
    rotations: tuple[float, ...] = QUARTER_TURNS
    field: str = "sheet"

    def __post_init__(self) -> None:
        if not (self.size[0] > 0 and self.size[1] > 0 and self.gap >= 0 and self.rotations):
            raise ValueError("a sheet needs a positive size, a gap >= 0 and at least one rotation")

    @classmethod
    def of(cls, table: Any, kerf: float, field: str) -> SheetRules:
        """The rules a template's table gives by its keys ``sheet`` (mm), ``margin`` (mm, beyond ``kerf``),
        ``sheet_rotations`` (degrees) and ``grain``; ``field`` names the sheet in refusals."""
        return cls(tuple(table.sheet), kerf + table.margin, rotations_of(table.sheet_rotations, table.grain), field)


@dataclass(frozen=True)
class Placed:
    """A part on a sheet: the part (in its own frame), the sheet (0-based), its rotation (degrees, counter-clockwise
    about its own origin) and then its shift (mm)."""

    part: Part
    sheet: int
    rotation: float
    shift: tuple[float, float]

    @property
    def angle(self) -> float:
        """The rotation in radians."""
        return math.radians(self.rotation)

    def outline(self) -> Contour:
        """Its outline where it lies on the sheet (exact arcs)."""
        return self.part.outline.moved(self.angle, np.array(self.shift))


@dataclass(frozen=True)
class Nest:
    """Parts laid on ``sheets`` sheets by :func:`nest`, and the figures of the layout.

    ``utilisation``: the parts' area (outlines less holes, mm^2) over the sheet area the layout uses
    (:func:`used_area`: every sheet but the last whole, and on the last the rectangle from the sheet's corner to
    the parts' farthest right and top extents, the gap to the lower and left edges included);
    ``shelf_utilisation``: the same figure for
    the shelf packing of the same parts on the same sheets (:func:`shelf`), None where the shelves do not
    fit the sheets.
    """

    placed: tuple[Placed, ...]
    sheets: int
    rules: SheetRules
    utilisation: float
    shelf_utilisation: float | None
    order: str = field(default="area")

    def drawings(self, tolerance: float) -> tuple[Drawing, ...]:
        """One drawing a sheet: each part's outline on ``OUTLINE``, its holes on ``HOLES``, its pockets and marks on
        their own layers, its name to score on ``LABELS``; ``tolerance`` (mm) is the drawings' chord tolerance."""
        items: list[list] = [[] for _ in range(self.sheets)]
        for p in self.placed:
            items[p.sheet] += _placed_items(p)
        return tuple(Drawing(tuple(i), tolerance) for i in items)

    @property
    def report(self) -> dict:
        """The layout as the JSON report gives it."""
        w, h = self.rules.size
        return {"sheets": self.sheets, "sheet_mm": [w, h], "gap_mm": self.rules.gap,
                "rotations_deg": list(self.rules.rotations), "method": "raster bottom-left fill, exact compaction",
                "order": self.order, "utilisation": round(self.utilisation, 4),
                "shelf_utilisation": None if self.shelf_utilisation is None else round(self.shelf_utilisation, 4),
                "parts": [{"name": p.part.name, "sheet": p.sheet + 1, "rotation_deg": p.rotation,
                           "x_mm": round(p.shift[0], 6), "y_mm": round(p.shift[1], 6)} for p in self.placed]}


def sheet_kinds(drawings: tuple[Drawing, ...]) -> tuple[tuple[str, Drawing], ...]:
    """Each sheet's drawing with the name its files take: ``sheet`` when there is one, else ``sheet-1``,
    ``sheet-2``, ..."""
    if len(drawings) == 1:
        return (("sheet", drawings[0]),)
    return tuple((f"sheet-{i + 1}", d) for i, d in enumerate(drawings))


def rotations_of(steps: float | None, grain: bool) -> tuple[float, ...]:
    """The rotations (degrees) allowed by a rotation step (degrees; None or 0 for none: 0 only) and the grain
    (with the grain a part keeps its direction: 0 and 180 only, of those the step allows)."""
    turns = (0.0,) if not steps else tuple(float(a) for a in np.arange(0.0, 360.0 - 1e-9, float(steps)))
    return tuple(a for a in turns if a in WITH_GRAIN) if grain else turns


def nest(parts: tuple[Part, ...], rules: SheetRules) -> Nest:
    """``parts`` laid on sheets of ``rules.size`` (as many as they need), by their true outlines: see the module.

    Raises :class:`DesignError` naming ``rules.field`` and the part's size when a part fits no sheet in any
    allowed rotation.
    """
    flats = [_Flat.of(p, rules) for p in parts]
    reference = shelf(parts, rules.size, rules.gap)
    shelf_figure = None if reference is None else _area(parts) / _used_area(reference, rules)
    footprints = _Footprints(FOOTPRINT_CACHE_BYTES)
    layouts = [(_fill(_ordered(flats, order), flats, rules, lean, footprints), f"{order}, {lean}")
               for order, lean in TRIES]
    if reference is not None and 0.0 in rules.rotations:           # the shelves themselves, should they be best
        layouts.append(((reference, max((p.sheet for p in reference), default=0) + 1), "shelves"))
    best: Nest | None = None
    for (placed, sheets), how in layouts:
        used = _used_area(placed, rules)
        nested = Nest(tuple(sorted(placed, key=lambda p: (p.sheet, p.shift[0], p.shift[1]))), sheets, rules,
                      _area(parts) / used if used > 0 else 1.0, shelf_figure, how)
        if best is None or (nested.sheets, -nested.utilisation) < (best.sheets, -best.utilisation):
            best = nested
    assert best is not None
    return best


@dataclass(frozen=True)
class _Flat:
    """A part as the nesting sees it: its outline as chords (mm, own frame), turned by each rotation into a polygon
    made when needed (:meth:`polygon`: a part keeps no polygon a rotation, so its memory does not grow with the
    rotations' count but by a few numbers each), and how much to grow it for the footprint (gap / 2 and the
    chords' distance from the arcs)."""

    part: Part
    ring: np.ndarray           # the outline's chords' ends (mm, own frame, not turned)
    angles: tuple              # the rotations (radians, counter-clockwise)
    bounds: np.ndarray         # each turned polygon's (xmin, ymin, xmax, ymax), mm: one row a rotation
    boxes: tuple               # the exact outline's (xmin, ymin, xmax, ymax) at each rotation, mm
    grow: float
    chord: float

    @classmethod
    def of(cls, part: Part, rules: SheetRules) -> _Flat:
        ring = part.outline.flatten(NEST_TOLERANCE_MM)
        chord = part.outline.flatten_error(NEST_TOLERANCE_MM)
        angles = tuple(math.radians(a) for a in rules.rotations)
        # each turned polygon's box from its vertices: the least and greatest, the very numbers shapely's bounds give
        bounds = np.array([np.concatenate([t.min(axis=0), t.max(axis=0)])
                           for t in (_moved(ring, a, np.zeros(2)) for a in angles)]).reshape(len(angles), 4)
        boxes = tuple(part.outline.moved(a, np.zeros(2)).bounds() for a in angles)
        flat = cls(part, ring, angles, bounds, boxes, rules.gap / 2 + chord + 1e-9, chord)
        flat._check_fits(rules)
        return flat

    def polygon(self, k: int):
        """Rotation k's polygon (a shapely Polygon, mm, own frame turned), the same at every call."""
        return _turned(self.ring, self.angles[k])

    def _check_fits(self, rules: SheetRules) -> None:
        """Refused, naming the sheet field and the part's size, when no rotation fits an empty sheet."""
        w, h = rules.size
        need = 2 * rules.gap
        spans = [self.span(k) for k in range(len(self.angles))]
        if not any(sw + need <= w + 1e-9 and sh + need <= h + 1e-9 for sw, sh in spans):
            sw, sh = min(spans, key=lambda s: max(s[0] - w, s[1] - h))
            raise DesignError(f"{rules.field}: the parts do not fit a {w:g} x {h:g} mm sheet: {self.part.name} is "
                              f"{sw:.4g} x {sh:.4g} mm and needs gaps of {rules.gap:g} mm to the edges (rotations "
                              f"{', '.join(f'{a:g}' for a in rules.rotations)} degrees); give a larger sheet")

    def span(self, k: int) -> tuple[float, float]:
        """Width and height (mm) of the outline's exact box at rotation k."""
        x0, y0, x1, y1 = self.boxes[k]
        return x1 - x0, y1 - y0

    def frame(self, k: int, cell: float) -> tuple[np.ndarray, tuple[int, int]]:
        """Rotation k's footprint's frame on a grid of ``cell`` mm: the lower-left corner (mm) of its polygon's box
        grown by ``grow``, and its cells' count (rows along +Y, columns along +X) from that corner."""
        x0, y0, x1, y1 = self.bounds[k].tolist()
        lo = np.array([x0 - self.grow, y0 - self.grow])
        rows = math.ceil((y1 - y0 + 2 * self.grow) / cell) + 1
        cols = math.ceil((x1 - x0 + 2 * self.grow) / cell) + 1
        return lo, (rows, cols)

    def footprint(self, k: int, grid: _Grid) -> tuple[np.ndarray, np.ndarray]:
        """Rotation k's footprint on ``grid``'s cells: the lower-left corner (mm) of its polygon's box grown by
        ``grow``, and the cells (rows along +Y) the grown polygon touches with that corner at the origin."""
        lo, shape = self.frame(k, grid.cell)
        return lo, grid.cover(_shift(self.polygon(k), -lo), self.grow, np.zeros(2), shape)


def _turned(ring: np.ndarray, angle: float):
    """The polygon of ``ring`` (mm) turned by ``angle`` (radians, counter-clockwise) about the origin."""
    import shapely

    return shapely.Polygon(_moved(ring, angle, np.zeros(2)))


class _Footprints:
    """Each part's footprint at each rotation (:meth:`_Flat.footprint`), made once for every layout one
    :func:`nest` tries and kept with its cells packed a bit each (np.packbits), up to ``limit`` bytes in all
    (``ENTRY_BYTES`` an entry besides its bits); past the limit a footprint is made each time it is needed. An
    entry is the bits alone (its corner and shape come again from :meth:`_Flat.frame`); every grid of one
    :func:`nest` has the same cell.

    The first ones made stay: every layout visits every part in turn, so a cache that dropped the least recently
    used when full would drop each footprint before its next use and keep none for reuse."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self.used = 0                                   # bytes kept (the bits, and ENTRY_BYTES an entry)
        self.kept: dict[tuple[int, int], np.ndarray] = {}             # {(part, rotation): the cells' bits}

    def get(self, i: int, flat: _Flat, k: int, grid: _Grid) -> tuple[np.ndarray, np.ndarray]:
        """Part i's (``flat``'s) footprint at rotation k on ``grid``'s cells, as :meth:`_Flat.footprint` gives
        it."""
        bits = self.kept.get((i, k))
        if bits is not None:
            lo, shape = flat.frame(k, grid.cell)
            return lo, np.unpackbits(bits, count=shape[0] * shape[1]).reshape(shape).view(bool)
        lo, mask = flat.footprint(k, grid)
        bits = np.packbits(mask)
        if self.used + bits.nbytes + ENTRY_BYTES <= self.limit:
            self.kept[i, k] = bits
            self.used += bits.nbytes + ENTRY_BYTES
        return lo, mask


def _ordered(flats: list[_Flat], order: str) -> list[int]:
    """The parts' indices sorted by ``order`` (see :func:`_order_key`)."""
    keys = [_order_key(f, order) for f in flats]
    return sorted(range(len(flats)), key=keys.__getitem__)


def _order_key(flat: _Flat, order: str) -> tuple:
    span = flat.span(0)
    main = {"area": -flat.part.outline.area, "length": -max(span), "height": -min(span)}[order]
    return (main, flat.part.name)


class _Grid:
    """A sheet's occupied cells (rows along +Y, columns along +X), ``cell`` mm square from the sheet's corner."""

    def __init__(self, rules: SheetRules, cell: float) -> None:
        import shapely

        w, h = rules.size
        self.cell = cell
        self.shape = (math.ceil(h / cell), math.ceil(w / cell))
        ys, xs = (np.arange(n) * cell for n in self.shape)
        # a cell is blocked where any of it lies outside the region a footprint may cover (gap / 2 from the edges)
        lo, hi_x, hi_y = rules.gap / 2, w - rules.gap / 2, h - rules.gap / 2
        free_x = (xs >= lo) & (xs + cell <= hi_x)
        free_y = (ys >= lo) & (ys + cell <= hi_y)
        self.occupied = ~(free_y[:, None] & free_x[None, :])
        self.inside = free_y, free_x                     # the rows and columns free on an empty sheet
        self.outlines: list = []                         # the placed polygons (sheet frame, not grown)
        self.ends = np.zeros(2)                          # their farthest right and top extents (mm)
        self._shapely = shapely

    def cover(self, polygon, grow: float, origin: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
        """The cells (a boolean array ``shape`` from cell ``origin`` (x, y) mm) that the polygon grown by ``grow``
        touches: every cell whose centre is within ``grow`` + half the cell's diagonal."""
        shapely = self._shapely
        # shapely's round joins are chords with their ends on the arc: divided by cos(half a chord's angle), every
        # chord lies at least the distance asked from the polygon
        reach = shapely.buffer(polygon, (grow + self.cell * math.sqrt(0.5)) * (1 + 1e-9) / math.cos(math.pi / 32),
                               quad_segs=8)
        ys = origin[1] + (np.arange(shape[0]) + 0.5) * self.cell
        xs = origin[0] + (np.arange(shape[1]) + 0.5) * self.cell
        gx, gy = np.meshgrid(xs, ys)
        shapely.prepare(reach)
        return shapely.contains_xy(reach, gx, gy)


def _fill(order: list[int], flats: list[_Flat], rules: SheetRules, lean: str,
          footprints: _Footprints) -> tuple[list[Placed], int]:
    """Place the parts in ``order`` (first fit over the sheets, a new sheet when none has room), their footprints
    from ``footprints``."""
    w, h = rules.size
    cell = max(MIN_CELL_MM, math.sqrt(w * h / MAX_CELLS))
    grids: list[_Grid] = []
    placed: list[Placed] = []
    slack = 2 * max(f.chord for f in flats) + 1e-9 if flats else 0.0
    for i in order:
        flat = flats[i]
        for s in range(len(grids) + 1):
            if s == len(grids):
                grids.append(_Grid(rules, cell))
            spot = _best_spot(grids[s], flat, lean, footprints, i)
            if spot is None and not grids[s].outlines:
                spot = _corner_spot(flat, rules)
            if spot is not None:
                k, shift = spot
                polygon = flat.polygon(k)
                shift = _compact(grids[s], polygon, flat.boxes[k], shift, slack, rules)
                polygon = _shift(polygon, shift)
                _occupy(grids[s], polygon, flat.grow)
                placed.append(Placed(flat.part, s, rules.rotations[k], (float(shift[0]), float(shift[1]))))
                break
            if not grids[s].outlines:                       # an empty sheet has no room: checked before, but safe
                raise DesignError(f"{rules.field}: {flat.part.name} does not fit an empty {w:g} x {h:g} mm sheet "
                                  f"with gaps of {rules.gap:g} mm; give a larger sheet")
    return placed, len(grids)


def _corner_spot(flat: _Flat, rules: SheetRules) -> tuple[int, np.ndarray] | None:
    """On an empty sheet the grid may have no room for a part that fits only just: the first rotation whose exact
    box fits, in the sheet's lower-left corner, ``gap`` from both edges."""
    w, h = rules.size
    for k in range(len(flat.angles)):
        sw, sh = flat.span(k)
        if sw + 2 * rules.gap <= w + 1e-9 and sh + 2 * rules.gap <= h + 1e-9:
            x0, y0, _, _ = flat.boxes[k]
            return k, np.array([rules.gap - x0, rules.gap - y0])
    return None


def _shift(polygon, shift: np.ndarray):
    import shapely

    return shapely.transform(polygon, lambda p: p + shift)


def _fast_length(n: int) -> int:
    """The least length >= ``n`` whose only prime factors are 2, 3 and 5 (an FFT of it is fast; numpy's FFT, so a
    build does not import scipy for it)."""
    best = 2 * n
    p5 = 1
    while p5 < best:
        p35 = p5
        while p35 < best:
            length = p35
            while length < n:
                length *= 2
            best = min(best, length)
            p35 *= 3
        p5 *= 5
    return best


def _best_spot(grid: _Grid, flat: _Flat, lean: str, footprints: _Footprints, i: int) -> tuple[int, np.ndarray] | None:
    """The rotation and shift (mm) of the free grid position that keeps the layout's rectangle from the sheet's
    corner least, then the part's upper right corner nearest the sheet's corner, then (``lean``) the least
    right-hand extent or the lowest; ``flat`` is part i, its footprints from ``footprints``.

    Every key grows with the position's right and top, and the sheet is empty past the layout's extents, so the
    best position lies within the layout's extents plus the part's size: only that window is searched. A rotation
    is searched only if the least rectangle it could keep (:func:`_least_used`, at the sheet's very corner) is no
    larger than the best one found: the rotations are tried from the least such rectangle up, and one that cannot
    win is left out unmade (its footprint and its transforms), with the same spot found."""
    reach = max(max(b[2] - b[0], b[3] - b[1]) for b in flat.boxes) + 2 * flat.grow
    window = (min(grid.shape[0], math.ceil((grid.ends[1] + reach) / grid.cell) + 3),
              min(grid.shape[1], math.ceil((grid.ends[0] + reach) / grid.cell) + 3))
    overlap = _Overlap(grid, window)
    best = None
    bounds = flat.bounds.tolist()
    least = [_least_used(b, grid.ends) for b in bounds]
    for k in sorted(range(len(bounds)), key=least.__getitem__):
        if best is not None and least[k] > best[0][0]:
            break                                   # this rotation and the rest keep a larger rectangle
        x0, y0, x1, y1 = bounds[k]
        lo, mask = footprints.get(i, flat, k, grid)
        if mask.shape[0] > window[0] or mask.shape[1] > window[1]:
            continue
        free = _first_free(overlap.free(mask))
        if not len(free):
            continue
        right = free[:, 1] * grid.cell + (x1 - x0)
        top = free[:, 0] * grid.cell + (y1 - y0)
        used = np.round(np.maximum(right, grid.ends[0]) * np.maximum(top, grid.ends[1]), 6)
        first, second = (right, top) if lean == "left" else (top, right)
        corner = np.round(right + top, 6)
        j = int(np.lexsort((second, first, corner, used))[0])
        key = (float(used[j]), float(corner[j]), round(float(first[j]), 9), round(float(second[j]), 9), k)
        if best is None or key < best[0]:
            best = (key, k, np.array([free[j, 1] * grid.cell, free[j, 0] * grid.cell]) - lo)
    return None if best is None else (best[1], best[2])


def _least_used(bounds: list[float], ends: np.ndarray) -> float:
    """The least layout rectangle (mm^2, rounded as :func:`_best_spot` rounds its keys) a rotation whose polygon's
    box is ``bounds`` (xmin, ymin, xmax, ymax) could keep on a sheet whose layout reaches ``ends`` (x, y): at a
    position's least right and top, the polygon's width and height (a position's column and row are >= 0), and
    numpy's rounding (the very one the keys take) keeps the order of the products it rounds, so no position of
    the rotation keeps less."""
    x0, y0, x1, y1 = bounds
    return float(np.round(max(x1 - x0, float(ends[0])) * max(y1 - y0, float(ends[1])), 6))


class _Overlap:
    """Where a footprint may lie in a window (rows, columns from the sheet's corner) of a grid: the positions of
    its lower-left cell at which it covers no occupied cell, and lies wholly in the window.

    The count of occupied cells under the footprint at every position is a correlation, made by FFT (numpy's:
    a build imports no scipy for it) once for the window and once for each footprint, with no wrap-around where
    it is read; a count is a whole number, so "free" is a count under 0.5 whatever the transform's rounding (about
    1e-10 here). On an empty sheet the occupied cells are the border only, and a footprint is free where its
    covered cells' extent lies within the free rectangle: no transform is needed."""

    def __init__(self, grid: _Grid, window: tuple[int, int]) -> None:
        from numpy import fft

        self.window = window
        self.empty = not grid.outlines
        self.inside = grid.inside
        if not self.empty:
            self.size = tuple(_fast_length(n) for n in window)
            self.occupied = fft.rfft2(grid.occupied[:window[0], :window[1]].astype(float), s=self.size)

    def free(self, mask: np.ndarray) -> np.ndarray:
        """A boolean array (rows, columns) of the positions, each the footprint ``mask``'s lower-left cell, at
        which it lies wholly in the window and covers no occupied cell."""
        from numpy import fft

        rows, cols = self.window[0] - mask.shape[0] + 1, self.window[1] - mask.shape[1] + 1
        if self.empty:
            return _within(mask.any(axis=1), self.inside[0][:self.window[0]], rows)[:, None] & \
                _within(mask.any(axis=0), self.inside[1][:self.window[1]], cols)[None, :]
        # the footprint's transform: its rows along +X first (the rest of the padded rows are zeros), then along
        # +Y; the inverse transform's rows only as far as positions are read
        spectrum = fft.fft(fft.rfft(mask.astype(float), n=self.size[1], axis=1), n=self.size[0], axis=0)
        counts = fft.irfft(fft.ifft(self.occupied * np.conj(spectrum), axis=0)[:rows], n=self.size[1], axis=1)
        return counts[:, :cols] < 0.5


def _within(covered: ArrayLike, inside: np.ndarray, positions: int) -> np.ndarray:
    """Along one axis of an empty sheet: at which of ``positions`` a footprint whose ``covered`` cells (a
    boolean per cell from its first) all fall on ``inside`` cells (a run of free cells between the blocked
    borders)."""
    cells = np.flatnonzero(covered)
    free = np.flatnonzero(inside)
    at = np.arange(positions)
    if not len(cells):
        return np.ones(positions, dtype=bool)
    if not len(free):
        return np.zeros(positions, dtype=bool)
    return (at + cells[0] >= free[0]) & (at + cells[-1] <= free[-1])


def _first_free(free: np.ndarray) -> np.ndarray:
    """The (row, column) of each row's first free position, rows in order (a row with none left out).

    Every key :func:`_best_spot` orders positions by (the layout's rectangle, the part's upper right corner, its
    right-hand extent, its top) grows with the column and the corner's strictly (columns are a cell, >= 0.25 mm,
    apart), so along a row the first free position comes before every other: the best of all free positions is
    the best of these, and the same one, since they keep their row-major order."""
    rows = np.flatnonzero(free.any(axis=1))
    return np.column_stack([rows, free[rows].argmax(axis=1)])


def _compact(grid: _Grid, polygon, box: tuple, shift: np.ndarray, slack: float, rules: SheetRules) -> np.ndarray:
    """The shift slid left, then down, by the exact clearance left to the placed parts and the sheet's edges less
    the gap: to the edges from the outline's exact ``box`` (unshifted), to the others from the polygons, which are
    chords, so it keeps ``slack`` (mm: the most two outlines' chords are from their arcs) as well."""
    import shapely

    others = shapely.union_all(grid.outlines) if grid.outlines else None
    for _ in range(COMPACTION_PASSES):
        moved = False
        for axis in (0, 1):
            here = _shift(polygon, shift)
            room = box[axis] + shift[axis] - rules.gap
            if others is not None:
                room = min(room, float(shapely.distance(here, others)) - rules.gap - slack)
            if room > 1e-7:
                shift = shift.copy()
                shift[axis] -= room - 1e-9
                moved = True
        if not moved:
            break
    return shift


def _occupy(grid: _Grid, polygon, grow: float) -> None:
    """Mark the cells the placed footprint touches."""
    x0, y0, x1, y1 = polygon.bounds
    c0 = max(0, math.floor((x0 - grow) / grid.cell) - 1)
    r0 = max(0, math.floor((y0 - grow) / grid.cell) - 1)
    c1 = min(grid.shape[1], math.ceil((x1 + grow) / grid.cell) + 1)
    r1 = min(grid.shape[0], math.ceil((y1 + grow) / grid.cell) + 1)
    grid.occupied[r0:r1, c0:c1] |= grid.cover(polygon, grow, np.array([c0, r0]) * grid.cell, (r1 - r0, c1 - c0))
    grid.outlines.append(polygon)
    grid.ends = np.maximum(grid.ends, (x1, y1))


def _area(parts: tuple[Part, ...]) -> float:
    return float(sum(p.area for p in parts))


def _used_area(placed: list[Placed], rules: SheetRules) -> float:
    """The sheet area the layout uses (mm^2): see :func:`used_area`."""
    ends: dict[int, np.ndarray] = {}
    for p in placed:
        _, _, x1, y1 = p.outline().bounds()
        ends[p.sheet] = np.maximum(ends.get(p.sheet, np.zeros(2)), (x1, y1))
    return used_area([ends[s] for s in sorted(ends)], rules.size)


def used_area(ends: list[np.ndarray], size: tuple[float, float]) -> float:
    """The sheet area (mm^2) a layout uses, given each sheet's farthest right and top extents (mm): every sheet
    but the last whole, and the last's rectangle from its corner to those extents."""
    return float((len(ends) - 1) * size[0] * size[1] + ends[-1][0] * ends[-1][1]) if ends else 0.0


def shelf(parts: tuple[Part, ...], size: tuple[float, float], gap: float) -> list[Placed] | None:
    """The reference: the parts as drawn (not turned), their exact boxes in shelves (rows left to right from the
    sheet's corner, tallest first, ``gap`` mm apart and from the edges), a new sheet when a sheet is full; None if
    a part does not fit a sheet."""
    width, height = size
    x = y = row = 0.0
    sheet = 0
    out = []
    for part in sorted(parts, key=lambda p: (p.outline.bounds()[1] - p.outline.bounds()[3], p.name)):
        x0, y0, x1, y1 = part.outline.bounds()
        span = np.array([x1 - x0, y1 - y0])
        if x > 0 and x + span[0] + 2 * gap > width:
            x, y, row = 0.0, y + row + gap, 0.0
        if y > 0 and y + span[1] + 2 * gap > height:
            x, y, row, sheet = 0.0, 0.0, 0.0, sheet + 1
        if x + span[0] + 2 * gap > width or y + span[1] + 2 * gap > height:
            return None
        out.append(Placed(part, sheet, 0.0, (float(x + gap - x0), float(y + gap - y0))))
        x, row = x + span[0] + gap, max(row, span[1])
    return out


def _placed_items(p: Placed) -> list:
    """A placed part's drawing items in the sheet's frame, with its label."""
    angle, shift = p.angle, np.array(p.shift)
    part = p.part
    items: list = [(LAYER_OUTLINE, p.outline()), *((LAYER_HOLES, h.moved(angle, shift)) for h in part.holes)]
    items += [(pocket.layer, c.moved(angle, shift)) for pocket in part.pockets for c in pocket.contours]
    items += [(layer, _move_mark(mark, angle, shift)) for layer, mark in part.marks]
    return items + _label(p)


def _move_mark(mark: Polyline | Text, angle: float, shift: np.ndarray) -> Polyline | Text:
    if isinstance(mark, Text):
        (x, y), = _moved(np.array([mark.position]), angle, shift)
        return Text(mark.text, (float(x), float(y)), mark.height, mark.angle + math.degrees(angle))
    return Polyline(_moved(mark.vertices, angle, shift), mark.bulges)


def _label(p: Placed) -> list[tuple[str, Text]]:
    """The part's name to score on ``LABELS``: centred on the point of the part farthest from its edges and holes,
    along the sheet's X or Y (whichever allows the taller text), at most LABEL_MAX_MM high and fitting inside the
    material; none where it would be under LABEL_MIN_MM high."""
    from camgen.core.kit import footprint

    part = p.part
    body = footprint(part, p.angle, np.array(p.shift), NEST_TOLERANCE_MM)
    if body.is_empty:
        return []
    from shapely.ops import polylabel

    centre = polylabel(body if body.geom_type == "Polygon" else max(body.geoms, key=lambda g: g.area), 0.05)
    c = np.array([centre.x, centre.y])
    n = len(part.name)
    best: tuple[float, float] = (0.0, 0.0)
    for text_angle in (0.0, 90.0):
        lo, hi = 0.0, LABEL_MAX_MM
        for _ in range(20):                                  # the tallest text whose box lies in the material
            mid = (lo + hi) / 2
            if body.contains(_text_box(c, mid, n, text_angle)):
                lo = mid
            else:
                hi = mid
        if lo > best[0] + 1e-9:
            best = (lo, text_angle)
    height, text_angle = math.floor(best[0] * 100) / 100, best[1]
    if height < LABEL_MIN_MM:
        return []
    half = np.array([0.3 * height * n, height / 2])
    (x, y), = _moved(-half[None, :], math.radians(text_angle), c)
    return [(LAYER_LABELS, Text(part.name, (round(float(x), 6), round(float(y), 6)), height, text_angle))]


def _text_box(centre: np.ndarray, height: float, n: int, angle: float):
    import shapely

    w, h = 0.3 * height * n, height / 2
    box = np.array([[-w, -h], [w, -h], [w, h], [-w, h]])
    return shapely.Polygon(_moved(box, math.radians(angle), centre))


__all__ = ["QUARTER_TURNS", "WITH_GRAIN", "Nest", "Placed", "SheetRules", "nest", "rotations_of", "sheet_kinds",
           "shelf", "used_area"]
