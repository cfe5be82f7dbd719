"""Approximate straight-line four-bars from their canonical proportions, scaled by one size.

Proportions in units of ``size`` (u), tracing point P on the coupler:

* Chebyshev: ground 2, crank 2.5, coupler 1, rocker 2.5, crossed; P at mid-coupler.
* Hoekens (its cognate): ground 2, crank 1, coupler 2.5, rocker 2.5, open; P on
  the coupler line at 5 from the crank pin.
* Roberts: pivots 2 apart (2b, b = 1), rockers and coupler-triangle sides a = 2,
  triangle base b = 1, open; P at the triangle's apex, between the pivots.
* Watt: rockers 1, coupler 1, pivots offset by (2, 1) so the rockers lie parallel
  and opposite at mid-stroke, crossed; P at mid-coupler.

The useful stroke is the stretch of P's path whose chord is ``stroke`` long
(Chebyshev, Hoekens and Roberts 2 u, Watt 0.5 u) that lies closest to a straight
line; the straightness error is the largest distance of the path from that chord.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics.fourbar import Assembly, FourBar

#: (ground, crank, coupler, rocker, point distance, point angle rad, assembly, stroke), in units of size
CANONICAL: dict[str, tuple[float, float, float, float, float, float, Assembly, float]] = {
    "chebyshev": (2.0, 2.5, 1.0, 2.5, 0.5, 0.0, "crossed", 2.0),
    "hoekens": (2.0, 1.0, 2.5, 2.5, 5.0, 0.0, "open", 2.0),
    "roberts": (2.0, 2.0, 1.0, 2.0, 2.0, -math.acos(0.25), "open", 2.0),
    "watt": (math.sqrt(5.0), 1.0, 1.0, 1.0, 0.5, 0.0, "crossed", 0.5),
}


@dataclass(frozen=True)
class Straightness:
    """The useful stroke: its chord length (mm), largest deviation of the path from it (mm),
    the input angles (rad) where it starts and ends, and its end points (mm)."""

    stroke_mm: float
    error_mm: float
    input_from: float
    input_to: float
    start: tuple[float, float]
    end: tuple[float, float]


#: crank-angle samples over a reachable range (or a turn) that find the neighbourhoods of the straightest stretches
COARSE = 721
#: neighbourhoods (the coarse deviation's lowest local minima) searched to convergence
CANDIDATES = 4
#: starts tried per round of that search, which narrows each neighbourhood 16-fold a round
TRIES = 33
#: samples of the path across a stretch; of their local maxima the PEAKS highest are refined, each by PARABOLAS
#: parabolic steps (:func:`_peak_max`)
ACROSS, PEAKS, PARABOLAS = 65, 4, 10


@dataclass(frozen=True)
class StraightLine:
    """A straight-line linkage: its four-bar (with the tracing point), assembly and nominal stroke (mm)."""

    kind: str
    linkage: FourBar
    assembly: Assembly
    stroke: float

    def trace(self, theta2: np.ndarray) -> np.ndarray:
        """The tracing point (mm, shape (n, 2)) at crank angles ``theta2`` (rad, any shape flattened). The canonical
        linkages have no change point, so every angle's pose lies on the one branch of the assembly."""
        return self.linkage.positions(np.ravel(theta2), self.assembly).point

    def straightness(self) -> Straightness:
        """The straightest stretch of the tracing point's path with a chord of ``stroke`` mm, converged.

        A coarse pass (:data:`COARSE` crank angles) finds the starts whose stretches deviate least
        from their chords; around each of the best few the start is narrowed 16-fold a round until it
        is fixed to rounding (the deviation, a maximum of two or more peaks, is least where they are
        equal: a kink, which a narrowing search finds where derivatives would not), each stretch's end
        found by regula falsi (:func:`_bisect`) to where the chord is ``stroke`` long and its largest deviation by
        parabolic interpolation (:func:`_peak_max`) on each of its highest peaks. The deviation so found is converged to
        about 1e-12 relative (the 2001-angle grid it replaces read 0.3 to 1.7 % high). Of stretches
        equally straight (a symmetric path has two) the one starting first.
        """
        ranges = self.linkage.input_ranges()
        best: Straightness | None = None
        for lo, hi in [(0.0, 2 * math.pi)] if ranges is None else ranges:
            found = self._straightest(lo, hi, cyclic=ranges is None)
            if found is not None and (best is None or not _least(np.array([best.error_mm, found.error_mm]))[0]):
                best = found
        if best is None:
            raise SpecError(f"the tracing point never travels {self.stroke:.6g} mm", "linkage.size")
        return best

    def _straightest(self, lo: float, hi: float, cyclic: bool) -> Straightness | None:
        """The straightest stretch starting in [lo, hi] (rad) and, unless ``cyclic`` (the crank turns, and a stretch
        may run on past hi = lo + 2 pi), ending there."""
        t = np.linspace(lo, hi, COARSE)
        starts = len(t)
        if cyclic:
            t = np.concatenate([t, t[1:] + 2 * math.pi])
        ends, dev = _coarse(self.trace(t), self.stroke, starts)
        picks = _candidates(dev)
        if len(picks) == 0:
            return None
        # brackets: the start within a coarse step of the candidate's; the end between the neighbours' coarse ends
        nb = np.clip(picks[:, None] + np.array([-1, 0, 1]), 0, starts - 1)
        valid = np.where(ends[nb] >= 0, ends[nb], ends[picks][:, None])
        a_lo, a_hi = t[nb[:, 0]], t[nb[:, 2]]
        b_lo, b_hi = t[np.maximum(valid.min(axis=1) - 1, 0)], t[valid.max(axis=1)]
        for _ in range(64):                             # 16-fold a round: some 12 rounds to rounding
            if np.all(a_hi - a_lo <= 4 * np.finfo(float).eps * (abs(hi) + 2 * math.pi)):
                break
            a = a_lo[:, None] + (a_hi - a_lo)[:, None] * np.linspace(0.0, 1.0, TRIES)
            d, _ = self._deviation(a.ravel(), np.repeat(b_lo, TRIES), np.repeat(b_hi, TRIES))
            k = np.argmin(d.reshape(a.shape), axis=1)
            rows = np.arange(len(a))
            a_lo, a_hi = a[rows, np.maximum(k - 1, 0)], a[rows, np.minimum(k + 1, TRIES - 1)]
        a = (a_lo + a_hi) / 2
        d, b = self._deviation(a, b_lo, b_hi)
        if not np.isfinite(d).any():
            return None
        i = int(np.flatnonzero(_least(d))[np.argmin(a[_least(d)])])      # of equals, the earliest
        p, q = self.trace(np.array([a[i], b[i]]))
        return Straightness(self.stroke, float(d[i]), float(a[i]), float(b[i]), tuple(p), tuple(q))

    def _deviation(self, a: np.ndarray, b_lo: np.ndarray, b_hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """For stretches starting at crank angles ``a`` (rad): their largest distance (mm) from their chords, and
        their ends (rad), where the chord is ``stroke`` long, looked for between ``b_lo`` and ``b_hi``
        (inf, and nan, where it is not there)."""
        pa = self.trace(a)

        def reach(t: np.ndarray) -> np.ndarray:          # chord from each start to t, less the stroke (mm)
            return np.hypot(*(self.trace(t) - pa).T) - self.stroke

        there = (reach(b_lo) < 0) & (reach(b_hi) >= 0)
        b = _bisect(reach, b_lo, b_hi)
        chord = self.trace(b) - pa
        u = chord / np.hypot(*chord.T)[:, None]

        def off(t: np.ndarray) -> np.ndarray:             # |distance| of the path at t (n, m) from each chord
            d = self.trace(t).reshape(*t.shape, 2) - pa[:, None, :]
            return np.abs(d[..., 0] * u[:, None, 1] - d[..., 1] * u[:, None, 0])

        s = a[:, None] + (b - a)[:, None] * np.linspace(0.0, 1.0, ACROSS)
        h = off(s)
        peak = np.zeros(h.shape, dtype=bool)
        peak[:, 1:-1] = (h[:, 1:-1] >= h[:, :-2]) & (h[:, 1:-1] >= h[:, 2:])
        top = np.argsort(np.where(peak, h, -1.0), axis=1)[:, -PEAKS:]      # the highest local maxima
        rows = np.arange(len(a))[:, None]
        near = np.stack([np.maximum(top - 1, 0), top, np.minimum(top + 1, ACROSS - 1)])
        dev = _peak_max(off, s[rows, near], h[rows, near]).max(axis=1)
        return np.where(there, dev, np.inf), np.where(there, b, np.nan)


def _coarse(pts: np.ndarray, chord: float, starts: int) -> tuple[np.ndarray, np.ndarray]:
    """For each of the first ``starts`` points: the index of the first later point at least ``chord`` away (-1 if
    none) and the largest distance of the points between from the line through the two (inf if none)."""
    d = pts[None, :, :] - pts[:starts, None, :]                       # (starts, n, 2): from each start
    dist = np.hypot(d[..., 0], d[..., 1])
    later = np.arange(len(pts))[None, :] > np.arange(starts)[:, None]
    far = later & (dist >= chord)
    ends = np.where(far.any(axis=1), np.argmax(far, axis=1), -1)
    rows = np.arange(starts)
    u = d[rows, ends] / np.where(ends >= 0, dist[rows, ends], 1.0)[:, None]
    inside = later & (np.arange(len(pts))[None, :] <= ends[:, None])
    off = np.abs(d[..., 0] * u[:, None, 1] - d[..., 1] * u[:, None, 0])
    dev = np.where(ends >= 0, np.where(inside, off, 0.0).max(axis=1), np.inf)
    return ends, dev


def _candidates(dev: np.ndarray) -> np.ndarray:
    """Indices of the :data:`CANDIDATES` lowest local minima of the coarse deviations (finite ones only)."""
    padded = np.concatenate([[np.inf], dev, [np.inf]])
    low = np.isfinite(dev) & (dev <= padded[:-2]) & (dev <= padded[2:])
    picks = np.flatnonzero(low)
    return picks[np.argsort(dev[picks])][:CANDIDATES]


def _least(d: np.ndarray) -> np.ndarray:
    """Which of the deviations ``d`` are the least, to rounding (1e-9 relative): a symmetric path has two equal
    stretches, and which of them is picked must not follow the last bit."""
    return d <= np.min(d) * (1.0 + 1e-9)


def _bisect(f: Callable[[np.ndarray], np.ndarray], lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Where f (negative at ``lo``, not at ``hi``) changes sign, to rounding, elementwise: regula falsi with the
    Illinois modification, each secant point kept a little inside the bracket (so that a root found at one end
    closes it, as in Brent's zeroin) and a bisection wherever the bracket has not halved in two steps (so it never
    lags bisection by much), until every bracket is a few units in the last place wide. Some 8 to 12 calls of f
    where bisection to rounding takes 52."""
    lo, hi = lo.copy(), hi.copy()
    flo, fhi = f(lo), f(hi)
    kept = np.zeros(lo.shape)                           # +1: lo was kept by the last step, -1: hi was
    last = before = np.full(lo.shape, np.inf)           # the brackets' widths one and two steps ago
    for _ in range(4 * 64):
        width = hi - lo
        ulps = 4 * np.finfo(float).eps * np.maximum(abs(lo), abs(hi))
        done = ~(width > ulps)
        if done.all():
            break
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            x = np.clip(lo - flo * (width / (fhi - flo)), lo + ulps / 4, hi - ulps / 4)
        secant = np.isfinite(x) & (width <= before / 2)
        x = np.where(done, lo, np.where(secant, x, lo + width / 2))
        fx = f(x)
        low, zero = fx < 0, fx == 0                     # a root hit exactly closes the bracket on it
        new = (np.where(low | zero, x, lo), np.where(low, hi, x),
               np.where(low, fx, np.where(kept == 1, flo / 2, flo)),     # Illinois: an end kept twice counts half
               np.where(low, np.where(kept == -1, fhi / 2, fhi), fx))
        lo, hi, flo, fhi = (np.where(done, old, value) for old, value in zip((lo, hi, flo, fhi), new, strict=True))
        kept = np.where(low, -1.0, 1.0)
        last, before = width, last
    return (lo + hi) / 2


def _peak_max(f: Callable[[np.ndarray], np.ndarray], x: np.ndarray, fx: np.ndarray) -> np.ndarray:
    """The maxima of f near the peaks bracketed by the triples ``x`` (shape (3, ...), ascending along the first axis;
    ``fx`` f there, the middle the highest): by successive parabolic interpolation (the vertex of the parabola
    through the three, kept strictly inside them, else the middle of the wider side), each step keeping the highest
    point and its two neighbours. The highest value f took: on a smooth peak the vertex converges superlinearly, and
    the value, flat there, reaches rounding within :data:`PARABOLAS` steps (golden-section search needs some 40)."""
    best = fx.max(axis=0)
    for _ in range(PARABOLAS):
        (a, b, c), (fa, fb, fc) = x, fx
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            p, q = (b - a) * (fb - fc), (b - c) * (fb - fa)
            u = b - ((b - a) * p - (b - c) * q) / (2 * (p - q))
        u = np.where((u > a) & (u < c) & (u != b), u, np.where(c - b > b - a, (b + c) / 2, (a + b) / 2))
        fu = f(u)
        best = np.maximum(best, fu)
        xs, fs = np.concatenate([x, u[None]]), np.concatenate([fx, fu[None]])
        order = np.argsort(xs, axis=0, kind="stable")
        xs, fs = np.take_along_axis(xs, order, axis=0), np.take_along_axis(fs, order, axis=0)
        m = np.clip(np.argmax(fs, axis=0), 1, 2)[None] + np.arange(-1, 2).reshape(3, *[1] * u.ndim)
        x, fx = np.take_along_axis(xs, m, axis=0), np.take_along_axis(fs, m, axis=0)
    return best


def straight_line(kind: str, size: float) -> StraightLine:
    """The ``kind`` linkage (chebyshev, hoekens, roberts, watt) with unit length ``size`` mm.

    Parameters
    ----------
    kind : str
        ``"chebyshev"``, ``"hoekens"``, ``"roberts"`` or ``"watt"``.
    size : float
        The unit of the canonical proportions (mm): Hoekens' ground is 2 of it, its crank 1, ...

    Returns
    -------
    StraightLine
        Its four-bar with the tracing point as the coupler point, its assembly and its nominal stroke (mm).

    Raises
    ------
    SpecError
        An unknown ``kind`` (naming ``linkage.type``) or a size that is not a finite length > 0 (naming
        ``linkage.size``).
    """
    if kind not in CANONICAL:
        raise SpecError(f"must be one of {', '.join(CANONICAL)} (got {kind!r})", "linkage.type")
    if not (size > 0 and math.isfinite(size)):
        raise SpecError(f"must be a finite length > 0 mm (got {size})", "linkage.size")
    g, c, cp, r, pd, pa, assembly, stroke = CANONICAL[kind]
    return StraightLine(kind, FourBar(g * size, c * size, cp * size, r * size, pd * size, pa), assembly,
                        stroke * size)
