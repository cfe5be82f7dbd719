"""Frames of an animation: one figure redrawn per step of a cycle, returned as pixel arrays (matplotlib's Agg
canvas). Pure: nothing is written here (the encoders are :mod:`camgen.core.writers.animation`)."""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from camgen.core.figures import figure

#: the figure's resolution (dots per inch): a frame of W x H pixels is a figure of W/DPI x H/DPI inches
DPI = 100


def cycle(n: int, full_turn: bool, lo: float, hi: float) -> np.ndarray:
    """The ``n`` input values of one cycle, the last one step before the first comes again: a full turn from
    ``lo`` (rad, ``hi`` ignored) in steps of 2 pi / n, or forth and back between ``lo`` and ``hi`` (rad or mm) as
    lo + (hi - lo) (1 - cos(2 pi k / n)) / 2, which slows to a stop at both ends as a rocker or a ram does."""
    k = np.arange(n) / n
    if full_turn:
        return lo + 2 * math.pi * k
    return lo + (hi - lo) * (1 - np.cos(2 * math.pi * k)) / 2


def render(draw: Callable[[Any, int], None], n: int, size: tuple[int, int],
           box: tuple[float, float, float, float], clear: bool = True) -> np.ndarray:
    """Frames ``0 .. n-1`` as an array (n, height, width, 3) of uint8 RGB: each frame ``draw(ax, k)`` draws frame
    ``k`` in mm on axes emptied of the last frame's artists (its property cycle started again, as a cleared axes'),
    and the view is the fixed region ``box`` (x0, y0, x1, y1 mm, equal scale, centred), so that frames line up. One
    figure of ``size`` pixels and one axes are reused for every frame: clearing the axes, which builds its ticks and
    spines anew, cost a third of a frame, and the pixels are the same. With ``clear`` False the artists are kept
    from frame to frame: ``draw`` makes them at frame 0 and moves them after (the same pixels at a fraction of the
    cost: making and adding artists is most of a frame's time)."""
    width, height = size
    fig = figure(width / DPI, height / DPI, layout=None)
    fig.set_dpi(DPI)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
    ax.set_axis_off()
    x0, y0, x1, y1 = _fitted(box, width / height)
    out = np.empty((n, height, width, 3), dtype=np.uint8)
    for k in range(n):
        if clear:
            for artist in [*ax.lines, *ax.patches, *ax.collections, *ax.texts, *ax.images, *ax.artists, *ax.tables]:
                artist.remove()
            ax.set_prop_cycle(None)
        draw(ax, k)
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.set_axis_off()
        fig.canvas.draw()
        rgba = np.asarray(fig.canvas.buffer_rgba())
        for channel in range(3):                 # a channel at a time: numpy copies the 3 of 4 bytes of a
            out[k, :, :, channel] = rgba[:height, :width, channel]    # pixel 5 times slower in one copy
    return out


def fill(ax: Any, xy: np.ndarray, **style: Any) -> None:
    """The polygon ``xy`` (k, 2) mm filled on a frame's ``ax`` as ``ax.fill(x, y, **style)`` fills it (the same
    patch, drawn in the same order), without growing the axes' data limits: :func:`render` fixes the view, and
    matplotlib's limit update walks the outline's every vertex in Python (most of a gear wheel's frame time)."""
    from matplotlib.patches import Polygon

    ax.add_artist(Polygon(np.asarray(xy, dtype=float), closed=True, **style))


def _fitted(box: tuple[float, float, float, float], aspect: float) -> tuple[float, float, float, float]:
    """``box`` widened (or heightened) about its centre to the proportions ``aspect`` (width / height) of the
    frame, so that one mm is as many pixels across as up."""
    x0, y0, x1, y1 = box
    w, h = x1 - x0, y1 - y0
    w, h = max(w, h * aspect), max(h, w / aspect)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    return cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2


def bounds(*points: np.ndarray, margin: float = 0.06) -> tuple[float, float, float, float]:
    """The region (x0, y0, x1, y1 mm) holding every point of ``points`` (arrays (..., 2) mm) with ``margin`` of its
    larger side round it."""
    xy = np.concatenate([np.asarray(p, dtype=float).reshape(-1, 2) for p in points])
    xy = xy[np.isfinite(xy).all(axis=1)]
    (x0, y0), (x1, y1) = xy.min(axis=0), xy.max(axis=0)
    pad = margin * max(x1 - x0, y1 - y0, 1.0)
    return float(x0 - pad), float(y0 - pad), float(x1 + pad), float(y1 + pad)
