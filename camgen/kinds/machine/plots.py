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
