"""A start for the six-bar search from the best four-bar: the four-bar embedded as a Stephenson III (or, by
:func:`embedded_stephenson1`, nearly as a Stephenson I).

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


#: Stephenson I embedding: the short crank O2-A and the offset O4-F as multiples of the shortest link allowed, and
#: the directions tried for A (from E's), B (from O4) and F (from O4)
SHORT = (1.05, 1.5, 2.5)
TURNS = 8


def embedded_stephenson1(joints: Mapping[str, Sequence[float]], box: float, shortest: float,
                         errors: Callable[[np.ndarray], np.ndarray]) -> np.ndarray | None:
    """The Stephenson I design (10,) (A, B, E, F, G of the normalised drawing, O2 at 0 and O4 at 1) nearest to the
    four-bar drawn at ``joints`` (the task's frame: O2, O4, A, B and its coupler point P), or None.

    The four-bar becomes the loop O2-E-G-F (E its crank pin, G its rocker pin, the tracer on the rod E-G at its
    coupler point) with F a short offset from O4 on a ternary rocker (O4, B, F) that a short crank O2-A barely
    swings: F nearly still, the tracer nearly the four-bar's coupler curve. The grid (offsets SHORT times
    ``shortest``, the shortest link allowed in ground lengths; TURNS directions each for A, B and F) keeps the
    design of least error within ``box`` (the first of them where several tie), the grid's designs (10, K) given
    to ``errors`` at once (-> (K,) mm^2, infinite where a hard constraint breaks); None if every one breaks one."""
    if "P" not in joints:
        return None
    o2, o4 = complex(*joints["O2"]), complex(*joints["O4"])

    def normal(key: str) -> complex:
        return (complex(*joints[key]) - o2) / (o4 - o2)

    e, g = normal("A"), normal("B")
    grid = []
    for short in SHORT:
        r = short * shortest
        for i in range(TURNS):
            a = cmath.rect(r, cmath.phase(e) + 2.0 * math.pi * i / TURNS)
            for j in range(TURNS):
                b = 1.0 + cmath.rect(0.5, 2.0 * math.pi * j / TURNS)
                for k in range(TURNS):
                    f = 1.0 + cmath.rect(r, 2.0 * math.pi * k / TURNS)
                    x = np.array([v for z in (a, b, e, f, g) for v in (z.real, z.imag)])
                    if np.all(np.abs(x) <= box):
                        grid.append(x)
    if not grid:
        return None
    designs = np.array(grid).T
    err = np.asarray(errors(designs), dtype=float)
    best = int(np.argmin(err))
    return designs[:, best] if err[best] < math.inf else None
