"""The machine's timing diagram: every output against the main shaft's angle, each normalised to its own range
(0 at its lowest, 1 at its highest) on a row of its own, its dwells shaded and the runs where it moves together
with another output (an overlap) marked beneath (not with the four-bar a follower drives: they move together by
construction). matplotlib's object API, imported only when a plot is asked for.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.core.figures import figure
from camgen.kinds.machine import kinematics
from camgen.kinds.machine.design import MachineDesign


def timing_figure(design: MachineDesign) -> Any:
    """The timing diagram of ``design`` (see the module docstring)."""
    outputs = design.outputs
    deg = np.degrees(design.phi)
    fig = figure(9, 1.2 + 1.1 * len(outputs))
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
    axes[0].set_title(f"{design.spec.name}: timing diagram at {design.spec.machine.rpm:g} rpm")
    return fig


def machine_figure(design: MachineDesign) -> Any:
    """The whole machine at each of ``machine.figure_angles``, a panel each (mm, y up, one scale for all): every part
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
    cols = min(len(angles), 4)
    rows = -(-len(angles) // cols)
    fig = figure(4.2 * cols, 4.2 * rows)
    axes = np.atleast_1d(fig.subplots(rows, cols, squeeze=False)).ravel()
    for k, (ax, angle) in enumerate(zip(axes, angles, strict=False)):
        for path in paths:
            ax.plot(path[:, 0], path[:, 1], color="C3", lw=0.8, alpha=0.7)
        for g in design.gears:
            for shaft, radius in zip(g.shafts, g.pair.working_pitch_radii, strict=True):
                ring = circle(radius, 0.05) + at[shaft]
                ax.add_patch(Polygon(ring, closed=True, fill=False, ls="--", ec="0.5", lw=0.8))
        for guide in fixed:
            ax.plot(guide.ends[:, 0], guide.ends[:, 1], color="0.35", lw=1.2, ls="-.", gid=guide.name)
        for p in parts:
            back = p.high < 0
            pin = p.name.startswith(("pins.", "shafts."))
            face = "white" if pin else ("#fdd0a2" if back else "#d9e6f2")
            ax.add_patch(Polygon(p.at(k), closed=True, fc=face, ec="#e6550d" if back else "#1f4e79", lw=0.8,
                                 alpha=0.85, gid=p.name))
        for name, xy in named.items():
            ax.plot([xy[k, 0]], [xy[k, 1]], "o", ms=2.5, color="C3" if name in traced(design) else "k", gid=name)
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_title(f"main shaft at {angle:g} deg", fontsize=9)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
    for ax in axes[len(angles):]:
        ax.set_axis_off()
    fig.suptitle(f"{design.spec.name} at {len(angles)} main shaft angle(s) (mm)", fontsize=10)
    return fig
