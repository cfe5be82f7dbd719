"""The machine's timing diagram: every output against the main shaft's angle, each normalised to its own range
(0 at its lowest, 1 at its highest) on a row of its own, its dwells shaded and the runs where it moves together
with another output (an overlap) marked beneath (not with the four-bar a follower drives: they move together by
construction). matplotlib's object API, imported only when a plot is asked for.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.core.figures import figure, fit_equal
from camgen.kinds.machine import kinematics
from camgen.kinds.machine.design import MachineDesign


#: the timing figure's fixed margins (inches): right of the axes, above them (the title), below (the x tick labels
#: and label), between rows, and from a row's y label to its axes (the tick labels 0 and 1 and their pads)
_RIGHT, _TOP, _BOTTOM, _ROW_GAP, _LABEL_ROOM = 0.2, 0.3, 0.5, 0.13, 0.3


def timing_figure(design: MachineDesign) -> Any:
    """The timing diagram of ``design`` (see the module docstring), laid out at fixed margins (the left one as wide as
    the widest row label, measured once), which cost nothing each time the figure is written (a constrained layout
    measured every label and tick again, a fifth of the figure's time)."""
    outputs = design.outputs
    deg = np.degrees(design.phi)
    width, height = 9.0, 1.2 + 1.1 * len(outputs)
    fig = figure(width, height, layout=None)
    axes = np.atleast_1d(fig.subplots(len(outputs), 1, sharex=True))
    moving = [~o.still for o in outputs]
    for j, (ax, o) in enumerate(zip(axes, outputs, strict=True)):
        ax.plot(deg, kinematics.normalised(o.values), color=f"C{j % 10}", lw=1.4)
        for a, b in kinematics.intervals(o.still):
            for lo, hi in ((a, min(b, 360.0)), (a - 360.0, b - 360.0)):
                if hi > 0 and lo < 360:
                    ax.axvspan(max(lo, 0.0), hi, color="0.9", zorder=0)
        together = np.zeros_like(moving[j])
        for k, other in enumerate(moving):
            if k != j and not design.together(o.label, outputs[k].label):
                together |= moving[j] & other
        ax.fill_between(deg, -0.12, -0.04, where=together, color="C3", alpha=0.5, lw=0, step="mid")
        ax.set_ylim(-0.15, 1.08)
        ax.set_yticks([0, 1])
        ax.set_ylabel(f"{o.label}\n{o.values.min():.3g} to {o.values.max():.3g} {o.unit}", fontsize=8,
                      rotation=0, ha="right", va="center")
        ax.grid(alpha=0.3)
    axes[-1].set_xlim(0, 360)
    axes[-1].set_xticks(np.arange(0, 361, 30))
    axes[-1].set_xlabel("main shaft angle (deg); grey: dwell; red bar: moving while another output moves")
    axes[0].set_title(f"{design.spec.name}: timing diagram at {design.spec.machine.rpm:g} rpm", y=1.0)
    renderer = fig.canvas.get_renderer()
    left = max(ax.yaxis.label.get_window_extent(renderer).width for ax in axes) / fig.dpi + _LABEL_ROOM
    row = (height - _TOP - _BOTTOM - (len(outputs) - 1) * _ROW_GAP) / len(outputs)
    fig.subplots_adjust(left=left / width, right=1 - _RIGHT / width, top=1 - _TOP / height, bottom=_BOTTOM / height,
                        hspace=_ROW_GAP / row)
    return fig


def machine_figure(design: MachineDesign) -> Any:
    """The whole machine at each of ``machine.figure_angles``, a panel each (mm, y up, one scale and one region for
    all, laid out at fixed margins: :func:`camgen.core.figures.fit_equal`): every part
    the clash check places (:func:`camgen.kinds.machine.poses.placed_parts`, from the lowest plane up; those behind
    the frame in orange), each named point (:func:`~camgen.kinds.machine.poses.points`) as a dot, the tracers' paths
    over the turn, the gear pairs' working pitch circles (dashed, over their gears) and each slider's guide over its
    travel (dash-dotted, :mod:`camgen.kinds.machine.guides`). Each part is a patch and each point and guide a line
    whose ``gid`` is its name."""
    from matplotlib.patches import Polygon

    from camgen.kinds.machine import poses
    from camgen.kinds.machine.clash import circle
    from camgen.kinds.machine.guides import guides
    from camgen.kinds.machine.page import frame_angles, traced

    angles = design.spec.machine.figure_angles
    phi = np.radians(np.asarray(angles, dtype=float))
    parts = sorted(poses.placed_parts(design, phi), key=lambda p: (p.low, p.high))
    named = poses.points(design, phi)
    fixed = guides(design)
    turn = poses.points(design, frame_angles())
    paths = [turn[t] for t in traced(design)]
    at = {s.name: np.asarray(s.at, dtype=float) for s in design.spec.shafts}
    rings = [circle(radius, 0.05) + at[shaft] for g in design.gears
             for shaft, radius in zip(g.shafts, g.pair.working_pitch_radii, strict=True)]
    outlines = [[p.at(k) for p in parts] for k in range(len(angles))]
    cols = min(len(angles), 4)
    rows = -(-len(angles) // cols)
    fig = figure(4.2 * cols, 4.2 * rows, layout=None)
    axes = [fig.add_axes((0, 0, 1, 1)) for _ in angles]
    for k, (ax, angle) in enumerate(zip(axes, angles, strict=True)):
        for path in paths:
            ax.plot(path[:, 0], path[:, 1], color="C3", lw=0.8, alpha=0.7)
        for ring in rings:                          # the view is set below: no patch grows the axes' limits
            ax.add_artist(Polygon(ring, closed=True, fill=False, ls="--", ec="0.5", lw=0.8))
        for guide in fixed:
            ax.plot(guide.ends[:, 0], guide.ends[:, 1], color="0.35", lw=1.2, ls="-.", gid=guide.name)
        for p, xy in zip(parts, outlines[k], strict=True):
            back = p.high < 0
            pin = p.name.startswith(("pins.", "shafts."))
            face = "white" if pin else ("#fdd0a2" if back else "#d9e6f2")
            ax.add_artist(Polygon(xy, closed=True, fc=face, ec="#e6550d" if back else "#1f4e79", lw=0.8,
                                  alpha=0.85, gid=p.name))
        for name, xy in named.items():
            ax.plot([xy[k, 0]], [xy[k, 1]], "o", ms=2.5, color="C3" if name in traced(design) else "k", gid=name)
        ax.set_title(f"main shaft at {angle:g} deg", fontsize=9, y=1.0)   # at the top: no tick labels to clear
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
    fit_equal(fig, axes, cols, width=4.2 * cols, max_height=4.2 * rows + 1.0,
              box=_region([*paths, *rings, *(g.ends for g in fixed), *(xy for k in outlines for xy in k),
                           *named.values()]))
    fig.suptitle(f"{design.spec.name} at {len(angles)} main shaft angle(s) (mm)", fontsize=10,
                 y=1 - 0.08 / fig.get_size_inches()[1])
    return fig


def _region(points: list[np.ndarray]) -> tuple[float, float, float, float]:
    """The region (x0, y0, x1, y1 mm) every panel of the machine figure shows: all of ``points`` (arrays (..., 2)
    mm; a point without a pose, NaN, left out) with a margin of 4 % of its larger side."""
    xy = np.concatenate([np.asarray(p, dtype=float).reshape(-1, 2) for p in points])
    xy = xy[np.isfinite(xy).all(axis=1)]
    (x0, y0), (x1, y1) = xy.min(axis=0), xy.max(axis=0)
    pad = 0.04 * max(x1 - x0, y1 - y0, 1e-9)
    return float(x0 - pad), float(y0 - pad), float(x1 + pad), float(y1 + pad)
