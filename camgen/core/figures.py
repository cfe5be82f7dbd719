"""Figures both products draw: a blank figure, any drawing, a family's overview (matplotlib's object API).

matplotlib is imported only when a figure is made (about 0.6 s); the figures are written
by :mod:`camgen.core.writers.figure`.
"""
from __future__ import annotations

import math
import os
import re
from typing import Any, Literal

import numpy as np

from camgen.core.parts import layer_colour
from camgen.core.shapes import Polyline, Text

#: chord tolerance (mm) of drawings drawn as figures: finer than a screen or a 120 dpi PNG shows
PREVIEW_TOLERANCE_MM = 0.05


def figure(width: float, height: float, layout: Literal["constrained", "compressed", "tight"] | None = "constrained"
           ) -> Any:
    """A blank figure ``width`` x ``height`` inches with the Agg canvas (no pyplot state) and constrained layout, or
    ``layout`` (None: the caller sets fixed margins, which cost nothing each time the figure is written)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), layout=layout)
    FigureCanvasAgg(fig)
    return fig


#: margins of a drawing laid out by :func:`fit_equal` (inches): left (y tick labels and label), right, top (the
#: title), a column's gap, above each panel (its title), below each panel (its x tick labels), the x label
_LEFT, _RIGHT, _TOP, _GAP, _ABOVE, _BELOW, _XLABEL = 0.8, 0.25, 0.45, 0.55, 0.3, 0.3, 0.25
#: a legend's row and its padding at the figure's foot (inches)
_LEGEND_ROW, _LEGEND_PAD = 0.21, 0.2


def fit_equal(fig: Any, axes: list[Any], cols: int = 1, width: float = 9.0, legend_rows: int = 0,
              max_height: float = 11.0, box: tuple[float, float, float, float] | None = None,
              top: float = _TOP) -> None:
    """Lay out ``axes`` (drawings in mm, equal aspect), ``cols`` to a row, all at one scale and showing one region,
    and size ``fig`` to them, so that no band of the figure stays empty: ``width`` inches wide (narrower if
    ``max_height`` would be passed), each panel as tall as the drawing's proportions ask, with room for the title,
    each panel's title and tick labels, and ``legend_rows`` rows of a legend at the foot (``fig.legend(loc="lower
    center")``). The region is ``box`` (x0, y0, x1, y1 mm) or every panel's data with a margin of 4 %; ``top``
    inches are kept above the panels for the figure's title (none needed when the one panel's title is it). Fixed
    margins cost nothing when the figure is written (a constrained layout re-measures every label each time)."""
    if box is None:
        lim = np.array([ax.dataLim.extents for ax in axes])
        x0, y0, x1, y1 = lim[:, 0].min(), lim[:, 1].min(), lim[:, 2].max(), lim[:, 3].max()
        pad = 0.04 * max(x1 - x0, y1 - y0, 1e-9)
        box = (x0 - pad, y0 - pad, x1 + pad, y1 + pad)
    x0, y0, x1, y1 = box
    rows = math.ceil(len(axes) / cols)
    foot = _XLABEL + (legend_rows * _LEGEND_ROW + _LEGEND_PAD if legend_rows else 0.1)
    fixed = top + rows * (_ABOVE + _BELOW) + foot
    panel_w = (width - _LEFT - _RIGHT - (cols - 1) * _GAP) / cols
    panel_h = panel_w * (y1 - y0) / (x1 - x0)
    if fixed + rows * panel_h > max_height:                   # a tall drawing: narrower panels
        panel_h = (max_height - fixed) / rows
        panel_w = panel_h * (x1 - x0) / (y1 - y0)
        width = _LEFT + _RIGHT + cols * panel_w + (cols - 1) * _GAP
    height = fixed + rows * panel_h
    fig.set_size_inches(width, height)
    for k, ax in enumerate(axes):
        r, c = divmod(k, cols)
        bottom = height - top - r * (_ABOVE + panel_h + _BELOW) - _ABOVE - panel_h
        ax.set_position([(_LEFT + c * (panel_w + _GAP)) / width, bottom / height, panel_w / width, panel_h / height])
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.set_aspect("equal")


def _pose(layer: str) -> bool:
    """An assembly's pose layer (``DC1-...``, ``DC2-...``), drawn in its colour in the cut files too
    (:func:`camgen.core.parts.layer_colour`)."""
    return layer.startswith("DC") and layer[2:].partition("-")[0].isdigit()


#: a layer's colour in a drawing's figure: matplotlib's ten, then ten more dark ones, so a kit's parts differ
_PALETTE = (*(f"C{i}" for i in range(10)), "black", "darkgoldenrod", "teal", "indigo", "olive", "maroon", "navy",
            "darkslategray", "saddlebrown", "darkviolet")


def _legend_key(layer: str) -> str:
    """What a layer is listed as in a figure's legend: a kit's part at a pose (``KIT-<degrees>-<part>``) by the
    part's name alone, so each part has one colour and one entry over all the panels; any other layer by its name."""
    head, _, rest = layer.partition("-")
    pose, _, part = rest.partition("-")
    return part if head == "KIT" and part and pose.lstrip("-").replace(".", "").isdigit() else layer


def drawing_figure(drawing: Any, title: str) -> Any:
    """Any drawing, one colour per layer (a pose's as in the cut files, paths dashed), equal axes in mm, the figure
    sized to the drawing. An
    assembly drawn at several poses (layers ``DC1-...``, ``DC2-...``) gets a panel per pose, each with the other
    layers (the paths), all at one scale: at a slider-crank's dead centres the poses lie on one line and would hide
    each other."""
    poses = list(dict.fromkeys(layer for layer, _ in drawing.items if _pose(layer)))
    groups = [[p] for p in poses] if len(poses) > 1 else [[None]]
    fig = figure(9, 7, layout=None)
    colours: dict[str, str] = {}
    labelled: set[str] = set()
    axes = []
    for group in groups:
        ax = fig.add_axes((0, 0, 1, 1))
        for layer, shape in drawing.items:
            if group != [None] and _pose(layer) and layer not in group:
                continue
            if isinstance(shape, Text):                   # engraved words as words, not in the legend
                ax.text(*shape.position, shape.text, rotation=shape.angle, fontsize=8, va="bottom")
                continue
            key = _legend_key(layer)
            colour = colours.setdefault(key, layer_colour(layer)[1] if _pose(layer)
                                        else _PALETTE[len(colours) % len(_PALETTE)])
            pts = shape.flatten(PREVIEW_TOLERANCE_MM)
            if not isinstance(shape, (Text, Polyline)):
                pts = np.vstack([pts, pts[:1]])            # close contours and circles
            ax.plot(pts[:, 0], pts[:, 1], "--" if layer == "PATH" else "-", color=colour, lw=1,
                    label=None if key in labelled else key)
            labelled.add(key)                              # label each part or layer once in the legend
        ax.grid(alpha=0.3)
        if group != [None]:
            ax.set_title(group[0], fontsize=9)
        axes.append(ax)
    box = np.array([ax.dataLim.extents for ax in axes])
    wide = (box[:, 2].max() - box[:, 0].min()) >= 1.5 * (box[:, 3].max() - box[:, 1].min())
    cols = 1 if wide or len(axes) == 1 else 2
    for ax in axes[(len(axes) - 1) // cols * cols:]:       # the bottom row names the x axis, the first column y
        ax.set_xlabel("x (mm)")
    for ax in axes[::cols]:
        ax.set_ylabel("y (mm)")
    ncols = min(3, max(1, len(colours)))
    fit_equal(fig, axes, cols, legend_rows=math.ceil(len(colours) / ncols))
    fig.legend(loc="lower center", ncols=ncols, fontsize=8)
    fig.suptitle(title, fontsize=11, y=1 - 0.08 / fig.get_size_inches()[1])
    return fig


def natural_key(name: str) -> list:
    """A sort key that reads the numbers in ``name`` as numbers: ``lift5`` before ``lift30``."""
    return [(0, float(part), "") if part[:1].isdigit() else (1, 0.0, part)
            for part in re.findall(r"\d+(?:\.\d+)?|\D+", name)]


def _short_names(names: list[str], width: int = 24) -> list[str]:
    """The members' names without what they all begin with (the family's name) and wrapped at their dashes into
    lines of about ``width`` characters, so that titles in a row of thumbnails do not run into each other."""
    common = os.path.commonprefix(names) if len(names) > 1 else ""   # noqa: RUF071 - names, not paths: by character
    common = common[:common.rfind("-") + 1]               # whole words only
    out = []
    for name in names:
        lines, line = [], ""
        for word in re.findall(r"[^-]+-?", name[len(common):] or name):
            if line and len(line) + len(word) > width:
                lines.append(line)
                line = ""
            line += word
        out.append("\n".join([*lines, line]))
    return out


def overview_figure(rows: list[dict], title: str) -> Any:
    """A grid of the members' thumbnails (``thumbnail``: a closed outline, or with ``thumbnail_kind`` "path"
    an open path, in mm), in the order of the numbers in their names (``lift5`` before ``lift30``), all at one scale
    (a cam of 5 mm lift looks smaller than one of 30 mm): cams about their centres with their bores
    (``thumbnail_bore``, mm), paths in their mechanism's frame, the same region in every panel; titled by what
    tells the members apart; failed members marked."""
    rows = sorted(rows, key=lambda r: natural_key(str(r["name"])))
    titles = _short_names([str(r["name"]) for r in rows])
    n = max(1, len(rows))
    cols = min(6, n)
    grid = math.ceil(n / cols)
    shapes = [np.array(r["thumbnail"]) for r in rows if r.get("thumbnail")]
    reach = np.array([1.0, 1.0])                         # half the region's width and height, mm
    middle, tall = np.zeros(2), 1.0
    if shapes and any(r.get("thumbnail_kind") == "path" for r in rows):   # paths: the region they all lie in
        every = np.vstack(shapes)
        low, high = every.min(axis=0), every.max(axis=0)
        middle, reach = (low + high) / 2, np.maximum((high - low) / 2, 0.02 * float((high - low).max())) * 1.08
        tall = float(np.clip(reach[1] / reach[0], 0.3, 1.2))  # panels shaped like the region (a wide one low)
        reach = np.maximum(reach, reach[::-1] * [1.0 / 1.2, 0.3])   # the region widened to the panel's shape
    elif shapes:                                         # cams: about their centres, the farthest point for all
        reach = np.full(2, max(float(np.abs(s).max()) for s in shapes) * 1.05)
    lines = max((t.count("\n") + 1 for t in titles), default=1)
    title_h = 0.12 * lines + 0.08                               # inches a row's titles take
    cell = 1.5 * tall + title_h
    height = cell * grid + 0.45
    fig = figure(1.7 * cols, height, layout=None)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=1 - 0.45 / height, wspace=0.08,
                        hspace=title_h / (1.5 * tall))
    for k, row in enumerate(rows):
        ax = fig.add_subplot(grid, cols, k + 1)
        ax.set_axis_off()
        ax.set_title(titles[k], fontsize=6)
        if row.get("thumbnail"):
            ring = np.array(row["thumbnail"])
            if row.get("thumbnail_kind") == "path":
                ax.plot(ring[:, 0], ring[:, 1], color="C0", lw=0.8)
            else:
                ax.fill(ring[:, 0], ring[:, 1], color="0.85", ec="k", lw=0.5)
                bore = row.get("thumbnail_bore") or 0.0
                if bore > 0:
                    turn = np.linspace(0, 2 * math.pi, 61)
                    ax.fill(bore / 2 * np.cos(turn), bore / 2 * np.sin(turn), color="white", ec="k", lw=0.5)
            ax.set_xlim(middle[0] - reach[0], middle[0] + reach[0])
            ax.set_ylim(middle[1] - reach[1], middle[1] + reach[1])
            ax.set_aspect("equal")
        else:
            ax.text(0.5, 0.5, "failed", color="C3", ha="center", va="center", fontsize=7, transform=ax.transAxes)
    fig.suptitle(f"{title}, at one scale: {2 * reach[0]:.4g} mm across each" if shapes else title, fontsize=9)
    return fig
