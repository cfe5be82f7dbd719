"""Measured convergence of a cam's outline: tolerance -> entities -> measured max error -> time.

The error is measured on the contour as it would be written, independently of the
outline code: points along every piece (arcs included) are projected onto the exact
pitch curve (:func:`camgen.surface.surface_deviation`).
"""
from __future__ import annotations

import statistics
import time
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from camgen.cam import Cam
from camgen.outline import exact_outline
from camgen.core.shapes import Contour
from camgen.surface import surface_deviation


@dataclass(frozen=True)
class ConvergenceRow:
    """One tolerance: entities written (lines plus arcs), measured max error (mm), median seconds to build."""

    tolerance_mm: float
    curves: str
    entities: int
    max_error_mm: float
    seconds: float


def contour_error(cam: Cam, contour: Contour, tolerance: float) -> float:
    """Largest distance (mm) of points on ``contour`` from the exact cam surface.

    The points lie on the geometry as written: every vertex, the midpoint of every
    line (where a chord strays most) and points along every arc, close enough that
    the arc between them departs from their chords by under 10 % of ``tolerance``.
    """
    on_arcs = contour.flatten(0.1 * tolerance)
    v, w = contour.vertices, np.roll(contour.vertices, -1, axis=0)
    lines = contour.bulges == 0
    probes = np.vstack([on_arcs, 0.5 * (v[lines] + w[lines])])
    return float(np.abs(surface_deviation(cam, probes)).max())


def convergence(cam: Cam, tolerances: Iterable[float], curves: str = "polylines",
                repeats: int = 3) -> list[ConvergenceRow]:
    """Build the outline at each tolerance ``repeats`` times; measure what it costs and how close it is.

    Parameters
    ----------
    cam : Cam
        A built cam (:meth:`camgen.rig.Rig.cam`, :func:`camgen.flat.build_cam`).
    tolerances : iterable of float
        The outline's tolerances to build at (mm).
    curves : str, optional
        ``"polylines"`` (chords and the exact arcs) or ``"biarcs"``, as ``output.curves`` takes them.
    repeats : int, optional
        How many times each outline is built; its time is the median.

    Returns
    -------
    list of ConvergenceRow
        One row a tolerance, in the order given: the entities written, the largest distance of the written
        contour from the exact cam surface measured independently of the outline code (mm), and the median
        seconds to build it.
    """
    rows = []
    for tol in tolerances:
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            outline = exact_outline(cam, tol, curves)
            times.append(time.perf_counter() - start)
        rows.append(ConvergenceRow(tol, curves, len(outline.contour.vertices),
                                   contour_error(cam, outline.contour, tol), statistics.median(times)))
    return rows


def error_order(rows: list[ConvergenceRow]) -> float:
    """p in error ~ entities^-p, fitted by least squares in log-log."""
    x = np.log([r.entities for r in rows])
    y = np.log([r.max_error_mm for r in rows])
    return float(-np.polyfit(x, y, 1)[0])
