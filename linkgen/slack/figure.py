"""The slack's figure and the band on the interactive page (matplotlib imported only when the figure is drawn).

A band a few tenths of a millimetre wide round a path a hundred millimetres across is thinner than the path's line,
so both draw it (and the Monte Carlo samples' paths) magnified about the nominal path by :func:`magnification`,
the figure's title and the page's note saying by how much; the band's width against the input is drawn to
scale.
"""
from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from camgen.core.page import Page
    from linkgen.slack import Slack
    from linkgen.slack.band import SlackBand, TracerBand

#: the band is magnified until its widest place is about this fraction of the paths' extent
SHOWN_WIDTH = 0.04
#: the magnifications used: 1, 2, 5 and their powers of ten
STEPS = (1.0, 2.0, 5.0)


def magnification(band: SlackBand) -> float:
    """How much the band is magnified when drawn: 1, 2, 5, 10, 20, ... so that its widest place (outside the
    ranges where the linkage binds) is at most :data:`SHOWN_WIDTH` of the tracers' extent; 1 when it is already
    that wide."""
    keep = ~band.binds
    widths = [2 * t.half_width[keep & np.isfinite(t.half_width)] for t in band.tracers]
    widest = max((float(w.max()) for w in widths if len(w)), default=0.0)
    paths = [t.path[np.isfinite(t.path).all(axis=1)] for t in band.tracers]
    extent = max((float(np.ptp(p, axis=0).max()) for p in paths if len(p)), default=0.0)
    if widest <= 0 or extent <= 0 or widest >= SHOWN_WIDTH * extent:
        return 1.0
    wanted = SHOWN_WIDTH * extent / widest
    decade = 10.0 ** math.floor(math.log10(wanted))
    return max(step * decade for step in STEPS if step * decade <= wanted)


def edges(t: TracerBand, scale: float, keep: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The band's two edges round the tracer's path (n, 2) mm, magnified ``scale`` times: the path moved by the
    half-width along its normal either way; NaN where the band is unbounded or not kept."""
    shown = np.where(keep & np.isfinite(t.half_width), scale * t.half_width, np.nan)[:, None] * t.normal
    return t.path + shown, t.path - shown


def _input_axis(slack: Slack) -> tuple[np.ndarray, str]:
    a = slack.band.analysis
    x = slack.band.inputs
    return (np.degrees(x), "input angle (degrees)") if a.crank else (x, "input travel (mm)")


def slack_figure(name: str, slack: Slack) -> Any:
    """The tracers' paths with their bands and the Monte Carlo samples' paths (magnified about the path), and the
    bands' widths against the input, the ranges where the linkage binds shaded."""
    from camgen.core.figures import figure

    band = slack.band
    keep = ~band.binds
    scale = magnification(band)
    fig = figure(12, 5.5, layout=None)
    fig.subplots_adjust(left=0.06, right=0.97, bottom=0.11, top=0.9, wspace=0.25, hspace=0.35)
    paths = fig.add_subplot(1, 2, 1)
    shown = "" if scale == 1 else f" (band and samples drawn {scale:g} x)"
    paths.set(title=f"{name}: slack band{shown}", xlabel="x (mm)", ylabel="y (mm)", aspect="equal")
    mc = slack.monte_carlo
    for k, t in enumerate(band.tracers):
        colour = f"C{k % 10}"
        if mc is not None:
            for sampled in mc.paths.get(t.name, ()):
                moved = t.path + scale * (sampled - t.path)
                paths.plot(moved[:, 0], moved[:, 1], color="0.75", lw=0.5)
        paths.plot(t.path[:, 0], t.path[:, 1], color=colour, lw=1.2, label=t.name)
        for edge in edges(t, scale, keep):
            paths.plot(edge[:, 0], edge[:, 1], color=colour, lw=0.8, ls="--")
    if band.tracers:
        paths.legend(fontsize=8)
    paths.grid(alpha=0.3)
    x, label = _input_axis(slack)
    widths = fig.add_subplot(2, 2, 2)
    widths.set(title="band width across each tracer's path", ylabel="width (mm)")
    for k, t in enumerate(band.tracers):
        widths.plot(x, np.where(keep, 2 * t.half_width, np.nan), color=f"C{k % 10}", lw=1.2, label=t.name)
    outputs = fig.add_subplot(2, 2, 4, sharex=widths)
    outputs.set(title="band width of each output", xlabel=label, ylabel="width (degrees or mm)")
    for k, o in enumerate(band.outputs):
        width = 2 * (np.degrees(o.half_width) if o.rocker else o.half_width)
        outputs.plot(x, np.where(keep, width, np.nan), color=f"C{k % 10}", lw=1.2,
                     label=f"{o.name} ({'deg' if o.rocker else 'mm'})")
    for ax in (widths, outputs):
        _shade(ax, x, band.binds)
        if ax.get_lines():
            ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    return fig


def _shade(ax: Any, x: np.ndarray, binds: np.ndarray) -> None:
    """Shade the input ranges where the linkage binds."""
    from linkgen.slack.band import runs

    for k, (first, last) in enumerate(runs(binds, False)):
        ax.axvspan(x[first], x[last], color="C3", alpha=0.15, lw=0, label="binds" if k == 0 else None)


def with_slack(page: Page, slack: Slack) -> Page:
    """The linkage's page with the band's edges round each tracer's path (dashed, magnified as in the figure) and
    a plot of the band's width across each tracer's path against the input."""
    from camgen.core.page import Body, Outline, Plot

    band = slack.band
    keep = ~band.binds
    scale = magnification(band)
    outlines = []
    for t in band.tracers:
        for edge in edges(t, scale, keep):
            for first, last in _finite_runs(edge):
                outlines.append(Outline(edge[first:last + 1], "pitch", False))
    a = band.analysis
    frames = np.radians(page.inputs) if a.crank else np.asarray(page.inputs)
    series = tuple((t.name, np.interp(frames, band.inputs, np.where(keep & np.isfinite(t.half_width),
                                                                  2 * t.half_width, np.nan)))
                   for t in band.tracers)
    note = "the slack band round the tracers' paths (dashed)" + ("" if scale == 1 else f" is drawn {scale:g} x")
    scene = replace(page.scene, bodies=(*page.scene.bodies, Body("slack band", tuple(outlines))))
    plots = (*page.plots, Plot("slack band width", "mm", series)) if series else page.plots
    return replace(page, scene=scene, plots=plots, notes=(*page.notes, note))


def _finite_runs(points: np.ndarray) -> list[tuple[int, int]]:
    """The runs of finite points (n, 2) with at least two points, (first, last) each."""
    from linkgen.slack.band import runs

    return [(f, t) for f, t in runs(np.isfinite(points).all(axis=1), False) if t > f]
