"""A candidate's figure: its curve (coupler curve, rocker or slider pin), the linkage at some poses, the targets and
the points reached; for a function, its structural error against x beside it (matplotlib's object API)."""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.core.figures import figure
from linkgen.synthesis.candidates import Sketch


def candidate_figure(title: str, sketch: Sketch) -> Any:
    """The figure of one candidate, titled ``title``; equal axes in mm."""
    fig = figure(12 if sketch.error is not None else 8, 6)
    ax = fig.add_subplot(1, 2 if sketch.error is not None else 1, 1)
    for k, (label, path) in enumerate(sketch.paths):
        ax.plot(path[:, 0], path[:, 1], "-", color=f"C{k}", lw=1.2, label=label)
    for k, (label, chain) in enumerate(sketch.poses):
        ax.plot(chain[:, 0], chain[:, 1], "-o", color="0.35" if k == 0 else f"C{(k + 2) % 10}", lw=1.5, ms=3,
                alpha=0.8, label=f"linkage {label}")
    if sketch.targets is not None:
        ax.plot(sketch.targets[:, 0], sketch.targets[:, 1], "x", color="C3", ms=9, mew=2, label="targets")
        for k, (x, y) in enumerate(sketch.targets):
            ax.annotate(str(k + 1), (x, y), textcoords="offset points", xytext=(5, 5), fontsize=8, color="C3")
    if sketch.reached is not None:
        ax.plot(sketch.reached[:, 0], sketch.reached[:, 1], "o", mfc="none", color="k", ms=7, label="reached")
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.legend(fontsize=7, loc="best")
    ax.set_title(title, fontsize=9)
    if sketch.error is not None:
        x, err, precision, label = sketch.error
        ex = fig.add_subplot(1, 2, 2)
        ex.axhline(0.0, color="0.5", lw=0.8)
        ex.plot(x, err, color="C0", lw=1.4, label="structural error")
        ex.plot(precision, np.zeros(len(precision)), "o", color="C3", label="precision points")
        ex.set_xlabel("x")
        ex.set_ylabel(label)
        ex.grid(alpha=0.3)
        ex.legend(fontsize=8)
        ex.set_title("generated minus asked, over the range", fontsize=9)
    return fig
