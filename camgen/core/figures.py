"""Figures both products draw: a blank figure, any drawing, a family's overview (matplotlib's object API).

matplotlib is imported only when a figure is made (about 0.6 s); the figures are written
by :mod:`camgen.core.writers.figure`.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.shapes import Polyline, Text

#: chord tolerance (mm) of drawings drawn as figures: finer than a screen or a 120 dpi PNG shows
PREVIEW_TOLERANCE_MM = 0.05


def figure(width: float, height: float, layout: str | None = "constrained") -> Any:
    """A blank figure ``width`` x ``height`` inches with the Agg canvas (no pyplot state) and constrained layout, or
    ``layout`` (None: the caller sets fixed margins, which cost nothing each time the figure is written)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), layout=layout)
    FigureCanvasAgg(fig)
    return fig


def drawing_figure(drawing: Any, title: str) -> Any:
    """Any drawing, one colour per layer (paths dashed), equal axes in mm."""
    fig = figure(9, 7)
    ax = fig.add_subplot()
    colours: dict[str, str] = {}
    for layer, shape in drawing.items:
        first = layer not in colours                      # label each layer once in the legend
        colour = colours.setdefault(layer, f"C{len(colours) % 10}")
        pts = shape.flatten(PREVIEW_TOLERANCE_MM)
        if not isinstance(shape, (Text, Polyline)):
            pts = np.vstack([pts, pts[:1]])            # close contours and circles
        ax.plot(pts[:, 0], pts[:, 1], "--" if layer == "PATH" else "-", color=colour, lw=1,
                label=layer if first else None)
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    fig.legend(loc="outside lower center", ncols=3, fontsize=8)
    ax.set_title(title)
    return fig


def overview_figure(rows: list[dict], title: str) -> Any:
    """A grid of the members' thumbnails (``thumbnail``: a closed outline, or with ``thumbnail_kind`` "path"
    an open path, in mm), failed members marked."""
    n = max(1, len(rows))
    cols = min(8, n)
    grid = math.ceil(n / cols)
    fig = figure(1.6 * cols, 1.7 * grid + 0.4)
    for k, row in enumerate(rows):
        ax = fig.add_subplot(grid, cols, k + 1)
        ax.set_axis_off()
        ax.set_title(row["name"], fontsize=5)
        if row.get("thumbnail"):
            ring = np.array(row["thumbnail"])
            if row.get("thumbnail_kind") == "path":
                ax.plot(ring[:, 0], ring[:, 1], color="C0", lw=0.8)
            else:
                ax.fill(ring[:, 0], ring[:, 1], color="0.85", ec="k", lw=0.5)
            ax.set_aspect("equal")
        else:
            ax.text(0.5, 0.5, "failed", color="C3", ha="center", va="center", fontsize=7, transform=ax.transAxes)
    fig.suptitle(title, fontsize=9)
    return fig
