"""The cam outline as exported: exact arcs where the surface is an arc, tolerance-driven chords elsewhere.

Vertices lie on the exact surface C = P - Rr n (the pitch curve offset inwards by
the roller radius along its analytic normal). On a rise or return their spacing
follows the surface's own curvature, chord ~ sqrt(8 tol rho), so the vertex count
is what the tolerance needs; the chord error is then measured against the exact
surface and the spacing tightened until it is within the tolerance. Dwells are
arcs about the cam centre and concave pitch corners are arcs of the roller radius
about the corner: both are exported as exact arcs.
"""
from __future__ import annotations

import contextvars
import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from camgen.biarcs import arc_distance, biarcs
from camgen.cam import Ask, Cam, Maker, together
from camgen.core.errors import DesignError
from camgen.followers.base import PitchGeometry
from camgen.core.shapes import Contour, arc_steps, reversed_pieces
from camgen.numeric import grid_counts
from camgen.surface import surface_deviation

#: interior points a span at which a chord's and a biarc's error are measured, and points an edge of an undercut
#: envelope at which its deviation from the exact envelope is
_PROBES, _BIARC_PROBES, _ENVELOPE_PROBES = 4, 16, 8
#: fraction of the tolerance the first spacing aims at
_AIM = 0.9
#: fraction of the tolerance a biarc's probed error must stay under
_BIARC_AIM = 0.95
#: the most vertices one segment's outline may take: a bound on work and memory (a cam needs hundreds)
MAX_SEGMENT_VERTICES = 200_000


@dataclass(frozen=True)
class Outline:
    """A cam outline: a counter-clockwise contour, its measured max error (mm) and how it was made.

    ``envelope`` is True when an undercut was allowed and the contour is the
    envelope a cutter would leave (the offset's loops removed).
    """

    contour: Contour
    max_error_mm: float
    envelope: bool


@dataclass(frozen=True)
class _Made:
    """Stretches made together (every moving stretch's chords, or every dwell's arcs): their vertices (n, 2) and
    bulges (n,), one stretch after another (each one's end left to what follows), each stretch's count of them
    (m,) and its measured error (mm, m floats). ``made[k]`` is stretch ``k``'s (vertices, bulges, error), views of
    the whole."""

    vertices: np.ndarray
    bulges: np.ndarray
    sizes: np.ndarray
    errors: list[float]

    def __len__(self) -> int:
        return len(self.errors)

    def __getitem__(self, k: int) -> tuple[np.ndarray, np.ndarray, float]:
        stop = int(self.sizes[:k + 1].sum())
        start = stop - int(self.sizes[k])
        return self.vertices[start:stop], self.bulges[start:stop], self.errors[k]


def _surface(g: PitchGeometry, rr: float) -> np.ndarray:
    return g.point - rr * g.normal


def _length(v: np.ndarray) -> np.ndarray:
    """The lengths of the 2-vectors along the last axis of ``v`` (mm): np.linalg.norm's sum of squares and root over
    that axis (the same numbers), without its dispatch."""
    x, y = v[..., 0], v[..., 1]
    return np.sqrt(x * x + y * y)


def _inner(theta: np.ndarray, count: int) -> np.ndarray:
    """``count`` equally spaced cam angles inside each span of ``theta``, probe by probe (radians; see
    :func:`_between`)."""
    return _between(theta[:-1], theta[1:], count)


@functools.cache
def _fractions(count: int) -> np.ndarray:
    """Where ``count`` equally spaced probes sit along a span, i / (count + 1) for i = 1 .. count, a column
    (count, 1); made once a count."""
    frac = (np.arange(1, count + 1) / (count + 1))[:, None]
    frac.setflags(write=False)
    return frac


def _between(start: np.ndarray, end: np.ndarray, count: int) -> np.ndarray:
    """``count`` equally spaced cam angles inside each span from ``start`` (k,) to ``end`` (k,), probe by probe:
    every span's first, then every span's second, ... (count k,) (radians): the start plus the span's width times
    i / (count + 1). Probe by probe, a span's largest error is an element-wise maximum over ``count`` contiguous
    rows, not a reduction along short rows (several times slower in numpy)."""
    return _across(start, end - start, count, np.empty((count, len(start)))).ravel()


def _across(start: np.ndarray, width: np.ndarray, count: int, out: np.ndarray) -> np.ndarray:
    """:func:`_between`'s angles, from each span's ``start`` (k,) and ``width`` (k,), made in ``out`` (count, k):
    the width times the fraction, plus the start (a sum is the same either way round)."""
    np.multiply(width, _fractions(count), out=out)
    out += start
    return out


def _planes(g: PitchGeometry, rr: float) -> np.ndarray:
    """The exact surface, ``rr`` mm inside the pitch curve, at the points of ``g`` as x and y planes (2, n) (mm):
    :func:`_surface`'s numbers, one numpy call for both components."""
    out = np.empty((2, len(g.normal)))                 # in rows (numpy would lay out a product as its operand)
    np.multiply(g.normal.T, rr, out=out)
    np.subtract(g.point.T, out, out=out)
    return out


def _gaps(a: np.ndarray, x: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Per span the largest gap (mm) between neighbouring points of the chain from the vertex ``a`` (2, spans)
    through its probes ``x`` (2, count, spans) to the vertex ``b`` (2, spans), all as x and y planes; the root
    of the largest square (the root is monotonic and correctly rounded: the largest root)."""
    count = x.shape[1]
    step = np.empty((2, count + 1, x.shape[2]))
    np.subtract(x[:, 0], a, out=step[:, 0])
    np.subtract(x[:, 1:], x[:, :-1], out=step[:, 1:-1])
    np.subtract(b, x[:, -1], out=step[:, -1])
    step *= step
    return np.sqrt((step[0] + step[1]).max(axis=0))


def _bend(kappa: np.ndarray, rr: float) -> np.ndarray:
    """The signed curvature (1/mm) of the surface ``rr`` mm inside a pitch curve of curvature ``kappa``: infinite
    or NaN where it has none (a division by zero, silenced where the makers run: see :func:`quietly`). Its least
    and greatest over a span bound what probes can miss: a curve parts from a line or an arc between two probes by
    at most gap^2 |curvature difference| / 8."""
    return kappa / (1 - rr * kappa)


def _arc_curvature(start: np.ndarray, end: np.ndarray, bulge: np.ndarray) -> np.ndarray:
    """|curvature| (1/mm) of arcs from ``start`` to ``end`` with ``bulge`` = tan(angle / 4): 2 sin(angle/2) / chord."""
    chord = np.maximum(_length(end - start), 1e-300)
    return 4 * np.abs(bulge) / ((1 + bulge**2) * chord)


def _apart(low: np.ndarray, high: np.ndarray, arc: np.ndarray) -> np.ndarray:
    """The most a surface's curvature (between ``low`` and ``high``, signed) and an arc's (``arc``, unsigned, on
    the same side as the surface) can differ (1/mm); a span where the surface turns both ways, the sum."""
    same = (low >= 0) | (high <= 0)
    near, far = np.minimum(np.abs(low), np.abs(high)), np.maximum(np.abs(low), np.abs(high))
    return np.where(same, np.maximum(np.abs(far - arc), np.abs(near - arc)), far + arc)


def _chord_errors(vertex: np.ndarray, x: np.ndarray, kappa: np.ndarray, rr: float) -> np.ndarray:
    """A bound (mm) on the distance of the exact surface (``rr`` mm inside the pitch curve) from each chord
    between neighbouring vertices ``vertex`` (2, spans + 1): the largest measured at its probes ``x`` (2, count,
    spans; at :func:`_between`'s angles, where the pitch curve's curvature is ``kappa``, count spans), plus what
    the surface's curvature lets it stray between two probes (infinite where it has none). Worked in x and y
    planes: an x and a y step are one numpy call; a sum of squares as numpy's sum along the last axis makes it
    (a square is never -0.0: no 0.0 to start from)."""
    a = vertex[:, None, :-1]                            # (2, 1, spans)
    ab = vertex[:, None, 1:] - a
    gap = _gaps(a[:, 0], x, vertex[:, 1:])
    square = ab * ab
    length2 = square[0] + square[1]
    along = x - a
    along *= ab
    # a span of no length divides by the least float instead of by 1 (fmax: every other square length is no less,
    # a NaN's quotient NaN either way): its probes' products with it are 0, so t is 0 either way, each probe
    # measured from its start (a span under 1e-162 mm, whose square underflows to 0, has t clamped to 0 or 1
    # instead of near 0: a + t ab is a all the same, but within 1e-146 mm of the centre)
    t = along[0] + along[1]
    t /= np.fmax(length2, _LEAST, out=length2)
    np.minimum(np.maximum(t, 0.0, out=t), 1.0, out=t)   # np.clip's result
    off = t * ab                                        # from each probe to its nearest point of the chord:
    off += a                                            # a + t ab - x, made in place
    off -= x
    off *= off
    bend = _bend(kappa, rr).reshape(x.shape[1:])
    bend = np.abs(bend, out=bend).max(axis=0)
    # np.fmin takes the number where the other is NaN: a NaN curvature's bound is infinite
    gap *= gap
    gap *= np.fmin(bend, math.inf, out=bend)
    gap /= 8
    far = (off[0] + off[1]).max(axis=0)
    gap += np.sqrt(far, out=far)
    return gap


#: the least positive float (a subnormal)
_LEAST = 5e-324


#: the points of the grid on which a stretch is measured for its spacing: its trapezoids only integrate the vertex
#: density (the measured error decides the rest); 65 give every bundled outline as many vertices as 129 did, each
#: error within its tolerance (33 gave random cams 1.5 % more vertices and more third rounds)
_AUX = 65


def _aux(cam: Cam, index: int, span: tuple[float, float] | None) -> np.ndarray:
    """The grid (radians) on which the segment ``index`` (or the ``span`` of it) is measured for its spacing."""
    seg = cam.program.segments[index]
    return _grids([(seg.start, seg.end) if span is None else span])[0][1][0]


def _grids(ranges: list[tuple[float, float]]) -> list[tuple[np.ndarray, np.ndarray]]:
    """:func:`_aux`'s grids from each start to its end of ``ranges`` (m pairs, radians), evenly spaced, by their
    size: (the ranges' places (c,), their grids (c, k)) each, in order of size. A range's k is the peaks' search
    grid's count for it (:func:`camgen.numeric.grid_counts`), _AUX where that is more: the same points as the
    search's, every second one of GRID (see :func:`_shared_grid`)."""
    start, end = np.array(ranges, dtype=float).reshape(-1, 2).T
    sizes = _spacing_counts(end - start)
    groups = []
    for k in np.unique(sizes).tolist():
        members = (sizes == k).nonzero()[0]
        groups.append((members, start[members, None] + (end - start)[members, None] * _unit(k)))
    return groups


def _spacing_counts(width: np.ndarray) -> np.ndarray:
    """The points of the spacing grid of stretches ``width`` radians wide (m,): the search's count for them, at most
    _AUX (every second point of GRID)."""
    return np.minimum(grid_counts(width), _AUX)


@functools.cache
def _unit(k: int) -> np.ndarray:
    """``k`` fractions evenly spaced from 0 to 1, read-only; made once a count."""
    out = np.linspace(0.0, 1.0, k)
    out.setflags(write=False)
    return out


def _shared_grid(cam: Cam, stretches: list[tuple[int, Span]],
                 segment: np.ndarray | None = None) -> tuple[Ask, list[tuple[np.ndarray, np.ndarray]]] | None:
    """The peaks' search grid as the ask of the spacing's grids of whole moving ``stretches`` (see
    :meth:`Program.search_grid`: the very arrays, so that a design that searches its peaks in the same round
    evaluates them once), and the spacing's grids in it: every second point of each segment's search grid (of n
    points, n from 33 to GRID: :func:`camgen.numeric.grid_counts`), (n + 1) / 2 of them, from the segment's start to
    its end (a return's law variable runs from its end); the stretches by the size of their grids, (their places
    among the stretches (c,), where their grids lie in the answer (c, (n + 1) / 2)) each. None where the stretches
    are not every moving segment whole, in order, or a segment is several smooth pieces (each then asks its own
    grid). ``segment``: the stretches' segments (m,), where the caller has them."""
    grid = cam.program.search_grid(cam.steady)
    if grid is None or any(span is not None for _, span in stretches):
        return None
    index, v, sizes = grid
    first = np.cumsum(sizes) - sizes
    moving = index.take(first) if sizes.size else first
    if not np.array_equal(moving, _segments(stretches) if segment is None else segment):
        return None
    segments = cam.program.segments
    back = np.array([segments[i].kind == "return" for i in moving.tolist()], dtype=bool)
    groups = []
    for n in np.unique(sizes).tolist():
        members = (sizes == n).nonzero()[0]
        aux = min(n, _AUX)                              # _spacing_counts': every second point of GRID, else each
        stride = (n - 1) // (aux - 1)
        step = np.where(back[members], -stride, stride)
        start = first[members] + np.where(back[members], n - 1, 0)
        groups.append((members, start[:, None] + step[:, None] * np.arange(aux)))
    return (index, v, True), groups


def _spacing(cam: Cam, index: int, tolerance: float, factor: float, rr: float,
             span: tuple[float, float] | None = None) -> np.ndarray:
    """Cam angles for chords within ~``tolerance`` mm of the surface, from its curvature (``factor`` >= 1 densifies),
    over the segment or the ``span`` (start, end, radians) of it."""
    aux = _aux(cam, index, span)
    g = cam.segment_pitch(index, aux)
    return _spaced(index, aux, _density(aux[None, :], g.d1, g.kappa, tolerance, rr)[0], tolerance, factor)


def _density(aux: np.ndarray, d1: np.ndarray, kappa: np.ndarray, tolerance: float, rr: float) -> np.ndarray:
    """The number of chords the surface needs (``factor`` 1 of :func:`_spaced`) from the start of each grid of
    ``aux`` (m, k) (radians) to each of its points (m, k), from the pitch curve's derivative ``d1`` (m k, 2) and
    curvature ``kappa`` (m k,) there: the integral of chord ~ sqrt(8 tol rho_c) along a surface of speed
    |P'| |1 - Rr k| (samples per radian), by the trapezoid rule, grid by grid. Worked on the grids one after
    another (contiguous, one-dimensional: numpy's quicker loops), with one trapezoid too many from each grid's end
    to the next one's start, left out of the sums."""
    root = rr * kappa                                   # sqrt(|k (1 - rr k)| / (8 aim tol)), made in place
    np.subtract(1.0, root, out=root)
    root *= kappa
    np.sqrt(np.divide(np.abs(root, out=root), 8.0 * _AIM * tolerance, out=root), out=root)
    density = _length(d1)
    density *= root
    grid = aux.ravel()
    step = np.empty(grid.size)                          # the trapezoids: 0.5 (sum of the ends) (width), in place
    trapezoid = np.add(density[1:], density[:-1], step[:-1])
    trapezoid *= 0.5
    trapezoid *= grid[1:] - grid[:-1]
    cum = np.zeros(aux.shape)
    step.reshape(aux.shape)[:, :-1].cumsum(axis=1, out=cum[:, 1:])
    return cum


def _spaced(index: int, aux: np.ndarray, cum: np.ndarray, tolerance: float, factor: float) -> np.ndarray:
    """:func:`_spacing` on the grid ``aux`` from its count of chords ``cum`` (see :func:`_density`): one stretch's
    :func:`_spaced_all`."""
    return _spaced_all([index], aux[None, :], cum[None, :], tolerance, np.array([factor]))[0]


def _spaced_all(index: Sequence[int] | np.ndarray, aux: np.ndarray, cum: np.ndarray, tolerance: float,
                factor: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_spaced` of every stretch at once: the grids ``aux`` (m, k) (radians), their counts of chords ``cum``
    (m, k) (see :func:`_density`) and densifications ``factor`` (m,) of the segments ``index`` (m, for the error).
    Returns every stretch's cam angles one after another (radians) and each one's count of them (m,).

    Each stretch's n = max(1, ceil(total factor)) chords put vertex i at the count of chords i total / n (the last
    at the total), placed on its grid by np.interp in its counts (its first and last vertex the grid's ends, or
    where its count first rises and last stops); a stretch of no count is spaced evenly."""
    total = cum[:, -1]
    wanted = total * factor
    bad = ~(wanted <= MAX_SEGMENT_VERTICES)             # also NaN or infinite (a curvature without bound)
    if bad.any():
        j = int(bad.argmax())
        raise DesignError(f"output.tolerance: the outline of motion[{index[j]}] would need {wanted[j]:.3g} "
                          f"vertices to stay within {tolerance:g} mm (at most {MAX_SEGMENT_VERTICES}); loosen the "
                          "tolerance or smooth the motion")
    chords = np.maximum(np.ceil(wanted), 1.0)
    sizes = chords.astype(np.intp) + 1
    row = np.repeat(np.arange(sizes.size), sizes)
    first = np.cumsum(sizes) - sizes                    # each stretch's first vertex among all
    last = first + sizes - 1
    k = np.arange(row.size) - first[row]
    count = k * (total / chords)[row]                   # np.linspace's k step, its last the total itself
    count[last] = total
    # np.interp in each row, its numbers those of the row alone: one search over all rows laid end to end, each
    # raised above the one before by its total and one (so that no count reaches into another row), finds each
    # count's grid point at or below it, or one too far where the raised numbers round equal; then the step back
    # and the interpolation in the row's own numbers, as np.interp makes it
    width = aux.shape[1]
    lift = np.cumsum(total + 1.0) - (total + 1.0)
    flat, grid = cum.ravel(), aux.ravel()
    at = np.searchsorted((cum + lift[:, None]).ravel(), count + lift[row], side="right") - 1
    over = count < flat[at]
    while over.any():                                   # rarely once: a rounding's, at most a row's points
        at -= over
        over = count < flat[at]
    top = row * width + width - 1                       # each count's row's last point
    end = at >= top                                     # at the total: the row's last angle
    at = np.minimum(at, top - 1)
    x0, x1, f0 = flat[at], flat[at + 1], grid[at]
    theta = np.divide(grid[at + 1] - f0, x1 - x0, out=np.zeros(row.size), where=x1 > x0)
    theta *= count - x0
    theta += f0
    theta[end] = grid[top[end]]
    even = total <= 0                                   # no count: evenly spaced, as np.linspace
    if even.any():
        start, stop = aux[:, 0], aux[:, -1]
        spread = start[row] + k * ((stop - start) / chords)[row]
        spread[last] = stop
        theta = np.where(even[row], spread, theta)
    return theta, sizes


def _spaced_groups(groups: list[tuple[np.ndarray, np.ndarray, np.ndarray]], live: np.ndarray, index: np.ndarray,
                   tolerance: float, factor: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_spaced_all` of the stretches ``live`` (their places among all, in that order) whose grids come in
    ``groups`` of one size: (their places among all stretches (c,), their grids (c, k) and counts of chords (c, k))
    each; each group spaced at once, the stretches' angles then put in the order of ``live`` (a single group's as
    they come). ``index``: every stretch's segment (for the error)."""
    if len(groups) == 1:
        members, aux, cum = groups[0]
        return _spaced_all(index[live], aux[live], cum[live], tolerance, factor[live])
    place = np.full(len(factor), -1, dtype=np.intp)
    place[live] = np.arange(len(live))
    parts, sizes = [], np.empty(len(live), dtype=np.intp)
    owner = []
    for members, aux, cum in groups:
        rows = (place[members] >= 0).nonzero()[0]
        if not rows.size:
            continue
        who = members[rows]
        theta, counts = _spaced_all(index[who], aux[rows], cum[rows], tolerance, factor[who])
        parts.append(theta)
        sizes[place[who]] = counts
        owner.append(np.repeat(place[who], counts))
    # every angle to its stretch's place, stably (each stretch's own in order)
    order = np.argsort(np.concatenate(owner), kind="stable")
    return np.concatenate(parts)[order], sizes


Span = tuple[float, float] | None
#: how numpy treats a floating-point error (np.errstate's values)
ErrorMode = Literal["ignore", "warn", "raise", "call", "print", "log"]


def _chords(cam: Cam, stretches: list[tuple[int, Span]], tolerance: float, rr: float, share: bool = False,
            segment: np.ndarray | None = None) -> Maker:
    """Makes the chords of the moving segments (or their spans) ``stretches``, (segment index, span or None) each,
    all at once: vertices spaced from the surface's curvature, then densified until their measured error is within
    ``tolerance``; returns each stretch's vertices (its end's left to what follows), zero bulges and error. With
    ``share`` the spacing's grids are every second point of the peaks' search grid where they can be (see
    :func:`_shared_grid`), for a design that searches its peaks in the same rounds. ``segment``: the stretches'
    segments (m,), where the caller has them."""
    if segment is None:
        segment = _segments(stretches)
    shared = _shared_grid(cam, stretches, segment) if share else None
    if shared is None:
        segments = cam.program.segments
        grids = _grids([(segments[i].start, segments[i].end) if span is None else span for i, span in stretches])
        (g,) = yield [(np.concatenate([segment[members].repeat(aux.shape[1]) for members, aux in grids]),
                       np.concatenate([aux.ravel() for _, aux in grids]), False)]
        groups, start = [], 0
        for members, aux in grids:
            part = g.part(start, start + aux.size)
            start += aux.size
            groups.append((members, aux, _density(aux, part.d1, part.kappa, tolerance, rr)))
    else:
        ask, picks = shared
        (g,) = yield [ask]
        groups = []
        for members, pick in picks:
            aux = g.theta.take(pick)
            d1, kappa = g.d1.take(pick.ravel(), axis=0), g.kappa.take(pick.ravel())
            groups.append((members, aux, _density(aux, d1, kappa, tolerance, rr)))
    del g                                               # the first round's geometry, not held through the next
    factor = np.ones(len(stretches))
    live = np.arange(len(stretches))
    err = np.empty(len(stretches))                     # every stretch's set in the first round
    done: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []     # each round's stretches within the tolerance
    for _ in range(40):
        theta, counts = _spaced_groups(groups, live, segment, tolerance, factor)
        n = theta.size
        # one ask: the vertices, then the probes of every span between neighbouring vertices (probe by probe), one
        # stretch's last to the next one's first too (none of theirs, its error left out): its probes sit at its
        # start (a width of 0.0, as x - x is), a point of its own segment
        angles = np.empty(n + _PROBES * (n - 1))
        vertex = angles[:n]
        vertex[:] = theta
        ahead = np.cumsum(counts)                       # each stretch's end, one past its last vertex
        across = ahead[:-1] - 1                         # the spans from one stretch to the next
        width = vertex[1:] - vertex[:-1]
        width[across] = 0.0
        _across(vertex[:-1], width, _PROBES, angles[n:].reshape(_PROBES, n - 1))
        # each vertex on its stretch's segment, each span's probes on its first vertex's
        on = segment.take(live).repeat(counts)
        (g,) = yield [(np.concatenate([on, *[on[:-1]] * _PROBES]), angles, False)]
        at = _planes(g, rr)
        spans = _chord_errors(at[:, :n], at[:, n:].reshape(2, _PROBES, n - 1), g.kappa[n:], rr)
        spans[across] = 0.0                             # under any error (errors are >= 0 or NaN)
        worst = np.maximum.reduceat(spans, ahead - counts)
        err[live] = worst
        good = worst <= tolerance                       # not NaN
        # the vertices of the stretches within the tolerance, each one's end left to what follows
        keep = good.repeat(counts)
        keep[ahead - 1] = False
        done.append((live[good], counts[good] - 1, at[:, :n].T[keep]))
        bad = ~good
        if not bad.any():
            return _Made(*_in_order(done, len(stretches)), err.tolist())
        # math.sqrt's and max's numbers: fmax keeps 1.1 where the quotient is NaN, as max(1.1, nan) does
        live = live[bad]
        factor[live] *= np.fmax(1.1, np.sqrt(worst[bad] / tolerance))
    first = int(live[0])
    raise DesignError(f"output.tolerance: the outline of motion[{segment[first]}] cannot be brought within "
                      f"{tolerance} mm (reached {err[first]:.3g} mm); loosen the tolerance")


def _in_order(done: list[tuple[np.ndarray, np.ndarray, np.ndarray]],
              m: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The vertices (n, 2) of ``m`` stretches made in rounds (``done``: each round's stretches (k,), in order, their
    counts of vertices (k,) and their vertices, one stretch after another), stretch by stretch, each one's in
    order; zero bulges (n,) and each stretch's count (m,)."""
    if len(done) == 1:                                  # one round: every stretch, in order
        _, sizes, points = done[0]
    else:
        who = np.concatenate([w for w, _, _ in done])
        count = np.concatenate([c for _, c, _ in done])
        order = np.argsort(who.repeat(count), kind="stable")
        points = np.concatenate([v for _, _, v in done])[order]
        sizes = np.empty(m, dtype=np.intp)
        sizes[who] = count
    return points, np.zeros(len(points)), sizes


def _biarcs(cam: Cam, index: int, tolerance: float, rr: float, span: Span) -> Maker:
    """Makes one moving segment's (or its ``span``'s) biarcs, two arcs between neighbouring vertices: returns
    their vertices and bulges and their measured error.

    Spans start coarse (the chord spacing for 1 mm); a span whose exact surface strays
    an error e > ``tolerance`` from its biarc is cut into ceil(1.2 (e / tolerance)^(1/3))
    equal parts, since a biarc's error falls as the cube of its span; until none strays.
    """
    aux = _aux(cam, index, span)
    (g,) = yield [(index, aux, False)]
    theta = _spaced(index, aux, _density(aux[None, :], g.d1, g.kappa, max(tolerance, 1.0), rr)[0],
                    max(tolerance, 1.0), 1.0)
    for _ in range(40):
        g, inner = yield [(index, theta, False), (index, _inner(theta, _BIARC_PROBES), False)]
        pts = _surface(g, rr)
        tan = g.d1 / _length(g.d1)[:, None]
        p0, p1, t0, t1 = pts[:-1], pts[1:], tan[:-1], tan[1:]
        junction, b1, b2 = biarcs(p0, t0, p1, t1)
        probes = _planes(inner, rr).reshape(2, _BIARC_PROBES, len(p0))
        gap = _gaps(p0.T, probes, p1.T)
        bend = _bend(inner.kappa, rr).reshape(_BIARC_PROBES, len(p0))
        bend = np.where(np.isfinite(bend), bend, np.inf)
        low, high = bend.min(axis=0), bend.max(axis=0)
        x = np.ascontiguousarray(probes.transpose(2, 1, 0))      # span by span (spans, count, 2), as measured
        apart = np.max([_apart(low, high, k) for k in (_arc_curvature(p0, junction, b1),
                                                       _arc_curvature(junction, p1, b2))], axis=0)
        err = np.minimum(arc_distance(x, p0, junction, b1), arc_distance(x, junction, p1, b2)).max(axis=1)
        err = err + gap**2 * apart / 8                  # a bound: what the curve and the arcs can part between probes
        bad = err > _BIARC_AIM * tolerance
        if not bad.any():
            verts = np.empty((2 * len(p0), 2))
            verts[0::2], verts[1::2] = p0, junction
            bulges = np.empty(2 * len(p0))
            bulges[0::2], bulges[1::2] = b1, b2
            return verts, bulges, float(err.max())
        parts = np.ceil(1.2 * np.cbrt(err[bad] / (_BIARC_AIM * tolerance))).astype(int)
        cuts = [a + (b - a) * np.arange(1, k) / k for a, b, k in zip(theta[:-1][bad], theta[1:][bad], parts,
                                                                        strict=True)]
        theta = np.sort(np.concatenate([theta, *cuts]))
    raise DesignError(f"output.tolerance: the biarcs of motion[{index}] cannot be brought within {tolerance} mm; "
                      "loosen the tolerance")


def _dwells(cam: Cam, stretches: list[tuple[int, Span]], rr: float, whole: bool = False) -> Maker:
    """Makes the exact arcs about the cam centre (up to 90 degrees an arc) of the dwells (or their spans)
    ``stretches``, (segment index, span or None) each, all at once: each one's vertices and bulges and their
    measured error (a list). A dwell's n arcs need n vertices (its end's left to what follows, as every stretch's)
    and 8 n - 1 probes, asked in one ask (every dwell's vertices, then every dwell's probes). ``whole``: the
    caller knows every stretch to be a whole segment (no span)."""
    turn = -cam.follower.sense
    at, start, beta = _extents(cam, stretches, whole)
    n = np.maximum(np.ceil(beta / (math.pi / 2) - 1e-12), 1.0)
    probes = 8 * n - 1
    dwell, k = _ranks(n.astype(np.intp))                # each vertex's dwell and its place in it
    near, j = _ranks(probes.astype(np.intp))            # each probe's, its place counted from 1
    theta = start[dwell] + beta[dwell] * k / n[dwell]
    probe = start[near] + beta[near] * ((j + 1) / (8 * n[near]))
    (g,) = yield [(at[np.concatenate([dwell, near])], np.concatenate([theta, probe]), False)]
    surface = _surface(g, rr)                           # in rows, as a contour holds them
    vertices = theta.size
    distance = _length(surface)                         # from the cam centre
    # each dwell's error: the most its probes lie off the circle through its first vertex
    ends = np.cumsum(n).astype(np.intp)
    first = ends - n.astype(np.intp)
    off = np.abs(distance[vertices:] - distance[first[near]])
    err = np.maximum.reduceat(off, (np.cumsum(probes) - probes).astype(np.intp)).tolist()
    bulge = np.tan(turn * beta / n / 4.0)[dwell]
    return _Made(surface[:vertices], bulge, n.astype(np.intp), err)


def _segments(stretches: list[tuple[int, Span]]) -> np.ndarray:
    """The segment of each of ``stretches`` (m,) (intp)."""
    return np.array([i for i, _ in stretches], dtype=np.intp)


def _extents(cam: Cam, stretches: list[tuple[int, Span]],
             whole: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The segments (m,) (intp) of ``stretches`` and where each starts and how wide it is (radians, (m,) each): a
    whole segment's ``start`` and ``beta`` (:meth:`Program.extents`), a span's start and
    its end less its start. ``whole``: the caller knows every stretch to be a whole segment."""
    at = _segments(stretches)
    if whole or all(span is None for _, span in stretches):
        return (at, *cam.program.extents(at))
    segments = cam.program.segments
    start, beta = np.array([(segments[i].start, segments[i].beta) if span is None else (span[0], span[1] - span[0])
                            for i, span in stretches], dtype=float).reshape(-1, 2).T
    return at, start, beta


def _ranks(sizes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For groups of ``sizes`` (m,) items laid one after another: each item's group and its place in it (from 0)."""
    group = np.repeat(np.arange(sizes.size), sizes)
    return group, np.arange(group.size) - (np.cumsum(sizes) - sizes)[group]


@dataclass(frozen=True)
class _Plan:
    """Where :func:`_makers`' makers put each stretch's result: whether each stretch is a dwell (m,) bool; the
    segments of the dwells' stretches (made by the first maker, where there are any) and of the moving ones (made
    by the maker at ``moving``, chords, or by one maker a stretch from there, biarcs)."""

    dwell: np.ndarray
    dwells: np.ndarray
    segments: np.ndarray
    moving: int
    biarcs: bool

    def blocks(self, results: list[Any]) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, list[float]]]:
        """The makers' ``results`` as blocks of stretches (the dwells', the moving ones'): the segment of each
        vertex (n,), the vertices (n, 2) and bulges (n,), one stretch after another, and the stretches' errors (k
        floats)."""
        out = []
        if self.dwells.size:
            made = results[0]
            out.append((self.dwells.repeat(made.sizes), made.vertices, made.bulges, made.errors))
        if self.segments.size and self.biarcs:
            pieces = results[self.moving:]
            sizes = np.fromiter((len(b) for _, b, _ in pieces), np.intp, len(pieces))
            out.append((self.segments.repeat(sizes), np.concatenate([v for v, _, _ in pieces]),
                        np.concatenate([b for _, b, _ in pieces]), [e for _, _, e in pieces]))
        elif self.segments.size:
            made = results[self.moving]
            out.append((self.segments.repeat(made.sizes), made.vertices, made.bulges, made.errors))
        return out


def _makers(cam: Cam, stretches: list[tuple[int, Span]], tolerance: float, rr: float,
            curves: str, share: bool = False) -> tuple[list[Maker], _Plan]:
    """What makes the ``stretches`` (segment index, span or None each): one maker for all the dwells' arcs, one
    for all the moving segments' chords, or one a moving segment for biarcs; and where each stretch's result is
    among theirs (see :class:`_Plan`)."""
    segment = _segments(stretches)
    whole = all(span is None for _, span in stretches)
    dwell = cam.program.dwells.take(segment)
    held, moves = dwell.nonzero()[0], (~dwell).nonzero()[0]
    dwells = [stretches[k] for k in held.tolist()]
    moving = [stretches[k] for k in moves.tolist()]
    makers: list[Maker] = [_dwells(cam, dwells, rr, whole)] if dwells else []
    plan = _Plan(dwell, segment.take(held), segment.take(moves), len(makers), curves == "biarcs")
    if curves == "biarcs":
        makers += [_biarcs(cam, i, tolerance, rr, span) for i, span in moving]
    elif moving:
        makers.append(_chords(cam, moving, tolerance, rr, share, plan.segments))
    return makers, plan


def _made(plan: _Plan, results: list[Any]) -> list[Any]:
    """The results of :func:`_makers`' makers in the order of their stretches, as its ``plan`` says: each
    stretch's (vertices, bulges, error)."""
    out, ranks = [], [0, 0]                             # each stretch's place among the dwells' or the moving ones'
    for dwell in plan.dwell.tolist():
        k = ranks[not dwell]
        ranks[not dwell] += 1
        out.append(results[0][k] if dwell else results[plan.moving + k] if plan.biarcs else results[plan.moving][k])
    return out


def stretch(cam: Cam, index: int, tolerance: float, rr: float, curves: str,
            span: tuple[float, float] | None = None) -> tuple[np.ndarray, np.ndarray, float]:
    """The surface ``rr`` mm inside the pitch curve along segment ``index`` of a disc cam (or the ``span``, start and
    end in radians, of it): its vertices and bulges, the end's vertex left to what follows, and the measured error
    (mm). A dwell is exact arcs about the cam centre; a rise or return is biarcs or chords as ``curves`` says."""
    makers, plan = _makers(cam, [(index, span)], tolerance, rr, curves)
    return _made(plan, cam.serve([quietly(together(makers))])[0])[0]


def quietly(maker: Maker, all: ErrorMode | None = None) -> Maker:
    """``maker`` with its steps run in a copy of the caller's context in which numpy's floating-point errors are
    treated as ``all`` says (np.errstate's ``all``; by default a division by zero and an invalid operation are
    silenced: a surface's curvature where it has none, see :func:`_bend`), set once for all its steps rather
    than a np.errstate a step (np.errstate sets a context variable)."""
    quiet = contextvars.copy_context()
    state = np.errstate(divide="ignore", invalid="ignore") if all is None else np.errstate(all=all)
    quiet.run(state.__enter__)                          # the copy's own
    try:
        ask = quiet.run(next, maker)
        while True:
            got = yield ask
            ask = quiet.run(maker.send, got)
    except StopIteration as done:
        return done.value


def _corner_arc(cam: Cam, index: int, rr: float) -> tuple[np.ndarray, float, float]:
    """At the end of segment ``index``: the arc of radius ``rr`` round a concave pitch corner.

    Returns its start vertex, its bulge and its signed included angle (rad).
    """
    segments = cam.program.segments
    j = (index + 1) % len(segments)
    return _arc_round(cam.segment_pitch(index, segments[index].end), cam.segment_pitch(j, segments[j].start), rr)


def _arc_round(before: PitchGeometry, after: PitchGeometry, rr: float) -> tuple[np.ndarray, float, float]:
    """The arc of radius ``rr`` round the pitch point where ``before`` ends and ``after`` starts (one point each):
    its start vertex, its bulge and its signed included angle (rad)."""
    centre = before.point[0]
    a = _surface(before, rr)[0] - centre
    b = _surface(after, rr)[0] - centre
    angle = math.atan2(a[0] * b[1] - a[1] * b[0], float(a @ b))
    return _surface(before, rr)[0], math.tan(angle / 4.0), angle


def exact_outline(cam: Cam, tolerance: float, curves: str = "polylines", offset: float = 0.0) -> Outline:
    """The outline of a cam without undercut (see the module docstring), moved out of the cam by ``offset`` mm
    along its normal (half a laser's kerf for a cut file; exact, not a polygon offset). A convex corner of the
    pitch curve (a velocity jump) stays a sharp vertex for a knife edge and becomes an arc of the offset round it.

    ``curves`` is ``"polylines"`` (chords) or ``"biarcs"`` (tangent-continuous arcs,
    far fewer entities for the same tolerance). A plate cam's dwells are straight,
    and its profile is closed by the plate: flat
    ends one roller radius beyond the travel (where the roller can still sit) and the
    bottom edge on y = 0. Every stretch is made at once (see :func:`outline_maker`).
    """
    return cam.serve([quietly(outline_maker(cam, tolerance, curves, offset, share=False))])[0]


def outline_maker(cam: Cam, tolerance: float, curves: str = "polylines", offset: float = 0.0,
                  share: bool = True) -> Maker:
    """:func:`exact_outline` as a maker of :meth:`Cam.serve`, so that a design evaluates it with its analysis:
    every stretch's maker runs at once (the chords of all moving segments in one), two rounds of evaluation for
    the whole cam where the first spacing holds. Corners, a flat face's flats and a plate's dwells are made from
    the segment boundaries, which the first round evaluates. With ``share`` (for a design that searches its peaks
    in the same rounds, see :func:`camgen.analysis.analysis_maker`) the chords' spacing reads its grids from the
    search's own (see :func:`_shared_grid`): one evaluation serves both; :func:`exact_outline`, on its own, asks its
    smaller grids."""
    rr = cam.contact_radius - offset
    n = len(cam.program.segments)
    plate = cam.is_plate
    dwells = cam.program.dwells
    stretches: list[tuple[int, Span]] = [(i, None) for i in ((~dwells).nonzero()[0].tolist() if plate else range(n))]

    def convex() -> None:
        if rr > 0 and any(turn > 0 for _, turn in cam.corners()):
            raise DesignError("the pitch curve has a convex corner that a roller cannot follow; its outline is the "
                              "cutter's envelope (cam.allow_undercut)")

    makers, plan = _makers(cam, stretches, tolerance, rr, curves, share)
    results = yield from together(makers, convex)
    if not makers:                                      # nothing asked (a plate of dwells): checked all the same
        convex()
    corners = [] if rr == 0 else cam.corners()        # a knife edge's profile: the corner is a vertex of both sides
    flats = [i for i, step in cam.steps() if step > 0]
    ends, starts = cam.boundary_geometry()
    # every piece of the outline with the segment it follows and its rank there: a segment's stretch (0), the arc
    # round a concave corner at its end (1), a flat face's flat straight on from its end (2); in the order of the
    # segments, then of the ranks, each stretch's vertices in order
    verts, bulges, keys, errors = [], [], [], [0.0]
    for at, v, b, errs in plan.blocks(results):
        keys.append(at * 3)
        verts.append(v)
        bulges.append(b)
        errors += errs
    if plate and dwells.any():                          # a plate's dwell: the point where it starts, exact
        held = dwells.nonzero()[0]
        before = (held - 1) % n
        keys.append(held * 3)
        verts.append(starts.point[before] - rr * starts.normal[before])
        bulges.append(np.zeros(held.size))
    for i, _ in corners:
        start, bulge, _ = _arc_round(ends.part(i, i + 1), starts.part(i, i + 1), rr)
        keys.append(np.array([3 * i + 1]))
        verts.append(start[None, :])
        bulges.append(np.array([bulge]))
    for i in flats:                                     # a flat face's flat: straight on from the segment's end
        keys.append(np.array([3 * i + 2]))
        verts.append(_surface(ends.part(i, i + 1), rr))
        bulges.append(np.zeros(1))
    order = np.argsort(np.concatenate(keys), kind="stable")
    pieces, arcs = [np.concatenate(verts)[order]], [np.concatenate(bulges)[order]]
    if plate:
        pieces, arcs = _close_plate(cam, pieces, arcs, offset)
    # the largest error (max passes over a NaN, wherever it stands, as it did segment by segment)
    return Outline(_counter_clockwise(cam, np.concatenate(pieces), np.concatenate(arcs)), max(errors),
                   envelope=False)


def _counter_clockwise(cam: Cam, verts: np.ndarray, bulges: np.ndarray) -> Contour:
    """The contour of a cam's outline ``verts`` (n, 2), ``bulges`` (n,), made in the order of the cam angle, as it
    runs counter-clockwise. A disc cam's contact point runs round its centre against the cam's turn, clockwise in
    the cam's frame for a counter-clockwise cam (``sense`` +1), so that outline is turned round and a clockwise
    cam's kept, without measuring its area; a plate's is measured."""
    if cam.is_plate:
        contour = Contour(verts, bulges)
        return contour if contour.area > 0 else contour.reversed()
    if cam.follower.sense > 0:
        verts, bulges = reversed_pieces(verts, bulges)
    return Contour(verts, bulges)


def _close_plate(cam: Cam, verts: list, bulges: list, offset: float) -> tuple[list, list]:
    """Add a plate's end point, its flat ends and its bottom edge (all moved out by ``offset`` mm) to the
    profile's vertices."""
    segments = cam.program.segments
    last = _surface(cam.segment_pitch(len(segments) - 1, segments[-1].end), cam.contact_radius - offset)[0]
    first = np.concatenate(verts)[0]
    out = cam.contact_radius + offset      # the flat ends, beyond the roller's reach
    low = -offset                          # the bottom edge
    tail = np.array([last, [last[0] + out, last[1]], [last[0] + out, low], [first[0] - out, low],
                     [first[0] - out, first[1]]])
    keep = np.concatenate([[True], np.linalg.norm(np.diff(tail, axis=0), axis=1) > 1e-12])
    return [*verts, tail[keep]], [*bulges, np.zeros(int(keep.sum()))]


def envelope_outline(cam: Cam, tolerance: float, offset: float = 0.0) -> Outline:
    """The surface a cutter of the roller's size would leave: the offset curve with its loops removed.

    The raw offset (chords from the curvature, roller-radius arcs at corners) is
    noded with shapely, split into faces, and the largest face is the cam. Its
    error is measured as the deviation of points along every edge from the exact
    envelope (distance Rr from the pitch curve), and the sampling is tightened
    until that is within the tolerance. ``offset`` moves it out of the cam (mm), as for
    :func:`exact_outline`.
    """
    factor = 1.0
    for _ in range(12):
        outline = _envelope(cam, tolerance, factor, offset)
        if outline.max_error_mm <= tolerance:
            return outline
        factor *= max(1.2, math.sqrt(outline.max_error_mm / tolerance))
    raise DesignError(f"output.tolerance: the undercut envelope cannot be brought within {tolerance} mm "
                      f"(reached {outline.max_error_mm:.3g} mm); loosen the tolerance")


def _envelope(cam: Cam, tolerance: float, factor: float, offset: float) -> Outline:
    """One try at the envelope, its sampling densified by ``factor``. A plate's profile runs from one end of the
    travel to the other and is closed by the plate as in :func:`exact_outline`; only the profile is measured."""
    import shapely

    rr = cam.contact_radius - offset
    pts = []
    segments = cam.program.segments
    for i, seg in enumerate(segments):
        theta = _spacing(cam, i, tolerance, factor, rr)
        pts.append(_surface(cam.segment_pitch(i, theta[:-1]), rr))
        if cam.is_plate and i == len(segments) - 1:
            break                                      # the plate's end: closed below, no turn back to the start
        # the segment's last surface point, then round the pitch point to the next segment's first
        centre = cam.segment_pitch(i, seg.end).point[0]
        start, _, angle = _corner_arc(cam, i, rr)
        n = arc_steps(abs(rr), angle, tolerance / factor**2)
        if n > MAX_SEGMENT_VERTICES:
            raise DesignError(f"output.tolerance: the undercut envelope round the end of motion[{i}] would need "
                              f"{n:.3g} vertices to stay within {tolerance:g} mm (at most {MAX_SEGMENT_VERTICES}); "
                              "loosen the tolerance")
        a = math.atan2(start[1] - centre[1], start[0] - centre[0]) + angle * np.arange(n) / n
        pts.append(centre + abs(rr) * np.column_stack([np.cos(a), np.sin(a)]))
    plate = np.empty((0, 2))
    if cam.is_plate:
        pts, _ = _close_plate(cam, pts, [np.zeros(len(p)) for p in pts], offset)
        plate = pts[-1][1:]                            # the flat ends and the bottom edge: no part of the surface
    ring = np.concatenate(pts)
    line = shapely.LineString(np.vstack([ring, ring[:1]]))
    faces = list(shapely.polygonize(shapely.get_parts(shapely.union_all(line))).geoms)
    if not faces:
        raise DesignError("the cam outline encloses no area")
    body = shapely.orient_polygons(max(faces, key=lambda f: f.area))
    v = np.asarray(body.exterior.coords)[:-1]
    keep = np.linalg.norm(v - np.roll(v, 1, axis=0), axis=1) > 1e-12
    v = v[keep]
    frac = np.arange(_ENVELOPE_PROBES + 1) / (_ENVELOPE_PROBES + 1)
    w = np.roll(v, -1, axis=0)
    on_plate = (np.abs(v[:, None, :] - plate[None, :, :]).max(axis=2) < 1e-9).any(axis=1)
    surface = ~(on_plate | np.roll(on_plate, -1))      # edges of the profile (a plate's own edges are not measured)
    probes = (v[surface, None, :] + (w - v)[surface, None, :] * frac[None, :, None]).reshape(-1, 2)
    err = float(np.abs(surface_deviation(cam, probes, offset)).max())
    return Outline(Contour(v), err, envelope=True)
