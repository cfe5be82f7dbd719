"""A start for the six-bar search from the best four-bar: the four-bar embedded as a Stephenson III.

A Stephenson III whose tracer P sits on the rod's joint C (the four-bar's coupler point) traces the four-bar's
coupler curve whatever its dyad C-D-O6 does, so the best four-bar on the same targets, with a dyad added that
closes over the whole turn and keeps the transmission limit, is a six-bar design of the four-bar's error. Put
among the differential evolution's first population, it makes the search start no worse than the four-bar.
The dyad is looked for on a grid: O6 at RADII (ground lengths) from C in DIRECTIONS directions, rod and output
each |C - O6| / sqrt 2 long (a right angle at D as drawn), D on either side; the first the search's own
constraints keep.
"""
from __future__ import annotations

import cmath
import math
from collections.abc import Callable, Mapping, Sequence

import numpy as np

#: O6's distances from C (ground lengths of the normalised drawing) and directions tried
RADII, DIRECTIONS = (1.0, 1.5, 2.0, 2.5), 12


def embedded(joints: Mapping[str, Sequence[float]], name: str, box: float,
             keeps: Callable[[np.ndarray], bool]) -> np.ndarray | None:
    """The Stephenson III design (10,) (A, B, C, O6, D of the normalised drawing, O2 at 0 and O4 at 1) of the four-bar
    drawn at ``joints`` (the task's frame: O2, O4, A, B and its coupler point P), or None: a six-bar type other than
    ``stephenson3``, a coupler point on a pin, or no dyad of the grid within ``box`` that ``keeps`` accepts."""
    if name != "stephenson3" or "P" not in joints:
        return None
    o2, o4 = complex(*joints["O2"]), complex(*joints["O4"])

    def normal(key: str) -> complex:
        return (complex(*joints[key]) - o2) / (o4 - o2)

    a, b, c = normal("A"), normal("B"), normal("P")
    for radius in RADII:
        for k in range(DIRECTIONS):
            for turn in (1.0, -1.0):
                phi = 2.0 * math.pi * k / DIRECTIONS
                o6 = c + cmath.rect(radius, phi)
                d = c + cmath.rect(radius / math.sqrt(2.0), phi + turn * math.pi / 4.0)
                x = np.array([v for z in (a, b, c, o6, d) for v in (z.real, z.imag)])
                if np.all(np.abs(x) <= box) and keeps(x):
                    return x
    return None
