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
from dataclasses import dataclass

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics.fourbar import FourBar

#: (ground, crank, coupler, rocker, point distance, point angle rad, assembly, stroke), in units of size
CANONICAL = {
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


@dataclass(frozen=True)
class StraightLine:
    """A straight-line linkage: its four-bar (with the tracing point), assembly and nominal stroke (mm)."""

    kind: str
    linkage: FourBar
    assembly: str
    stroke: float

    def straightness(self, samples: int = 2001) -> Straightness:
        """The straightest stretch of the tracing point's path with a chord of ``stroke`` mm."""
        ranges = self.linkage.input_ranges()
        intervals = [(0.0, 2 * math.pi)] if ranges is None else list(ranges)
        best: tuple[float, Straightness] | None = None
        for lo, hi in intervals:
            t = np.linspace(lo, hi, samples)
            pts = self.linkage.sweep(t, self.assembly).point
            cyclic = ranges is None
            if cyclic:
                t, pts = np.concatenate([t, t[1:] + 2 * math.pi]), np.vstack([pts, pts[1:]])
            found = _straightest(pts, self.stroke, samples)
            if found is not None and (best is None or found[0] < best[0]):
                dev, i, j = found
                best = (dev, Straightness(self.stroke, dev, float(t[i]), float(t[j]),
                                          tuple(pts[i]), tuple(pts[j])))
        if best is None:
            raise SpecError(f"the tracing point never travels {self.stroke:.6g} mm", "linkage.size")
        return best[1]


def _straightest(pts: np.ndarray, chord: float, starts: int) -> tuple[float, int, int] | None:
    """(deviation, i, j): the window pts[i..j] with |pts[j] - pts[i]| >= chord deviating least from its chord."""
    best = None
    for i in range(min(starts, len(pts))):
        d = np.linalg.norm(pts[i:] - pts[i], axis=1)
        k = int(np.argmax(d >= chord))
        if d[k] < chord:
            continue
        seg = pts[i:i + k + 1]
        u = (pts[i + k] - pts[i]) / d[k]
        dev = float(np.abs((seg[:, 0] - pts[i, 0]) * u[1] - (seg[:, 1] - pts[i, 1]) * u[0]).max())
        if best is None or dev < best[0]:
            best = (dev, i, i + k)
    return best


def straight_line(kind: str, size: float) -> StraightLine:
    """The ``kind`` linkage (chebyshev, hoekens, roberts, watt) with unit length ``size`` mm."""
    if kind not in CANONICAL:
        raise SpecError(f"must be one of {', '.join(CANONICAL)} (got {kind!r})", "linkage.type")
    if not (size > 0 and math.isfinite(size)):
        raise SpecError(f"must be a finite length > 0 mm (got {size})", "linkage.size")
    g, c, cp, r, pd, pa, assembly, stroke = CANONICAL[kind]
    return StraightLine(kind, FourBar(g * size, c * size, cp * size, r * size, pd * size, pa), assembly,
                        stroke * size)
