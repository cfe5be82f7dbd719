"""The motor's figure: the crank's speed over time from rest (rpm), each turn's mean speed, the steady band or the
stall; and the last full turn's speed against the crank angle (degrees).

matplotlib's object API through :func:`camgen.core.figures.figure`, imported only when the figure is drawn.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.figures import figure
from linkgen.dynamics.forward import LAST_TURN, SETTLED, Motion

RPM = 60.0 / (2.0 * math.pi)


def motor_figure(name: str, motion: Motion) -> Any:
    """The speed over time from rest and, after a full turn, the last turn's speed against the crank angle."""
    fig = figure(8, 6.4, layout=None)
    fig.subplots_adjust(left=0.11, right=0.97, bottom=0.09, top=0.93, hspace=0.35)
    top, bottom = fig.subplots(2, 1)
    top.plot(motion.time, motion.speed * RPM, color="C0", lw=1.0, label="crank speed")
    if len(motion.turn_ends):
        top.stairs(motion.turn_means * RPM, np.concatenate([[0.0], motion.turn_ends]), baseline=None, color="C1",
                   lw=1.2, label="each turn's mean")
    last = motion.last
    if motion.outcome == "steady" and last is not None:
        top.axhspan(last.mean * RPM * (1 - SETTLED), last.mean * RPM * (1 + SETTLED), color="C2", alpha=0.15,
                    label=f"steady mean ± {100 * SETTLED:g} %")
        if last.settled is not None:
            top.axvline(last.settled, color="C2", lw=0.9, ls="--")
    if motion.stall is not None:
        top.plot([motion.stall.time], [0.0], "x", color="C3", ms=9,
                 label=f"stall at {math.degrees(motion.stall.angle) % 360:.4g}°")
    top.set_xlabel("time from rest (s)")
    top.set_ylabel("speed (rpm)")
    top.grid(alpha=0.3)
    top.legend(fontsize=8)
    sol = motion.last_turn
    if last is not None and sol is not None and len(motion.turn_ends):
        t1 = float(motion.turn_ends[-1])
        t0 = float(motion.turn_ends[-2]) if len(motion.turn_ends) > 1 else 0.0
        y = sol(np.linspace(t0, t1, LAST_TURN))
        first = motion.equation.start + 2 * math.pi * (len(motion.turn_ends) - 1)     # the turn's start
        angle = np.degrees(y[0] - first) + math.degrees(motion.equation.start) % 360.0
        bottom.plot(angle, y[1] * RPM, color="C0", lw=1.2)
        bottom.axhline(last.mean * RPM, color="C1", lw=0.9, ls="--", label="the turn's mean")
        bottom.set_title(f"the last full turn: fluctuation (max - min)/mean {last.fluctuation:.4g}", fontsize=9)
        bottom.legend(fontsize=8)
    else:
        bottom.text(0.5, 0.5, "no full turn", ha="center", va="center", transform=bottom.transAxes)
    bottom.set_xlabel("crank angle (degrees)")
    bottom.set_ylabel("speed (rpm)")
    bottom.grid(alpha=0.3)
    top.set_title(f"{name}: the motor's start from rest ({motion.outcome})")
    return fig
