"""The dynamics' figures and page plots: the driving effort and power over the cycle, the joints' forces as polar
loci, the shaking force's locus (with the counterweight's) and the shaking moment.

matplotlib's object API through :func:`camgen.core.figures.figure`, imported only when a figure is drawn. Forces in
N in the drawing's frame, torques in N*m, power in W; the input in degrees (a crank) or mm (a slide).
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.figures import figure
from linkgen.dynamics.report import speed_section, speed_words
from linkgen.dynamics.run import Dynamics

#: joints drawn in the polar figure (the most loaded first when there are more)
MOST_JOINTS = 12


def _input(dyn: Dynamics, x: np.ndarray) -> tuple[np.ndarray, str]:
    return (np.degrees(x), "input angle (degrees)") if dyn.crank else (x, "input travel (mm)")


def dynamics_figures(name: str, dyn: Dynamics) -> tuple[tuple[str, Any], ...]:
    """The figures ``(kind, draw)`` of the dynamics, each drawn only when called (``motor``: the speed from rest,
    :mod:`linkgen.dynamics.forward_plots`)."""
    figures: tuple[tuple[str, Any], ...] = (
        ("torque", lambda: torque_figure(name, dyn)), ("joint-forces", lambda: joint_force_figure(name, dyn)),
        ("shaking", lambda: shaking_figure(name, dyn)))
    motion = dyn.motion
    if motion is not None:
        from linkgen.dynamics.forward_plots import motor_figure

        figures += (("motor", lambda: motor_figure(name, motion)),)
    return figures


def torque_figure(name: str, dyn: Dynamics) -> Any:
    """The driving effort (with its mean over a turn) and the driver's power against the input."""
    r = dyn.result
    x, label = _input(dyn, r.inputs)
    fig = figure(8, 6, layout=None)
    fig.subplots_adjust(left=0.13, right=0.97, bottom=0.09, top=0.93, hspace=0.12)
    top, bottom = fig.subplots(2, 1, sharex=True)
    top.plot(x, r.effort, color="C0", lw=1.5, label="driving " + ("torque" if dyn.crank else "force"))
    if dyn.fluctuation is not None:
        top.axhline(dyn.fluctuation.mean_torque, color="C3", lw=0.9, ls="--", label="mean over a turn")
    top.axhline(0.0, color="0.5", lw=0.6)
    top.set_ylabel("torque (N·m)" if dyn.crank else "force (N)")
    top.legend(fontsize=8)
    bottom.plot(x, r.power, color="C1", lw=1.3)
    bottom.axhline(0.0, color="0.5", lw=0.6)
    bottom.set_ylabel("power (W)")
    bottom.set_xlabel(label)
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    speed = speed_words(speed_section(dyn, dyn.speed * 60 / (2 * math.pi)))
    top.set_title(f"{name}: driving {'torque' if dyn.crank else 'force'} and power at {speed}")
    return fig


def joint_force_figure(name: str, dyn: Dynamics) -> Any:
    """Each joint's force as a polar locus: the tip of the force vector (N, the drawing's frame) over the motion,
    its peak marked; up to :data:`MOST_JOINTS` joints, the most loaded first."""
    pairs = [pf for pf in dyn.result.pairs if np.isfinite(pf.force).all()]
    pairs = sorted(pairs, key=lambda pf: -float(np.hypot(*pf.force.T).max()))[:MOST_JOINTS]
    cols = min(4, max(1, len(pairs)))
    rows = max(1, math.ceil(len(pairs) / cols))
    fig = figure(2.6 * cols + 0.6, 2.7 * rows + 0.6, layout=None)
    fig.subplots_adjust(left=0.06, right=0.98, bottom=0.06, top=1 - 0.5 / (2.7 * rows + 0.6), wspace=0.35,
                        hspace=0.45)
    for k, pf in enumerate(pairs):
        ax = fig.add_subplot(rows, cols, k + 1)
        f = pf.force
        ax.plot(f[:, 0], f[:, 1], color=f"C{k % 10}", lw=1.2)
        i = int(np.argmax(np.hypot(*f.T)))
        ax.plot([0, f[i, 0]], [0, f[i, 1]], color="0.3", lw=0.8)
        ax.plot([0], [0], "+", color="0.3")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
        ax.tick_params(labelsize=7)
        ax.set_title(f"{pf.pair.slider or pf.pair.point}: {pf.pair.by} on {pf.pair.on}", fontsize=8)
    fig.suptitle(f"{name}: joint forces (N), the force's tip over the motion; line: the peak", fontsize=10)
    return fig


def shaking_figure(name: str, dyn: Dynamics) -> Any:
    """The shaking force's locus (N) with, for a crank turning fully, the locus with the counterweight; the shaking
    moment about the origin against the input."""
    r = dyn.result
    fig = figure(10, 4.8, layout=None)
    fig.subplots_adjust(left=0.09, right=0.98, bottom=0.12, top=0.9, wspace=0.3)
    locus, moment = fig.subplots(1, 2)
    f = r.shaking_force
    locus.plot(f[:, 0], f[:, 1], color="C0", lw=1.4, label="shaking force")
    cw = dyn.counterweight
    if cw is not None:
        z = f[:, 0] + 1j * f[:, 1]
        turn = np.exp(1j * r.inputs)
        forward = np.sum(z * np.conj(turn)) / len(z)
        after = z - forward * turn
        locus.plot(after.real, after.imag, color="C1", lw=1.1, ls="--", label="with the counterweight")
    locus.plot([0], [0], "+", color="0.3")
    locus.set_aspect("equal", adjustable="datalim")
    locus.set_xlabel("Fx (N)")
    locus.set_ylabel("Fy (N)")
    locus.grid(alpha=0.3)
    locus.legend(fontsize=8)
    x, label = _input(dyn, r.inputs)
    moment.plot(x, r.shaking_moment, color="C2", lw=1.3)
    moment.axhline(0.0, color="0.5", lw=0.6)
    moment.set_xlabel(label)
    moment.set_ylabel("shaking moment about the origin (N·m)")
    moment.grid(alpha=0.3)
    fig.suptitle(f"{name}: what the moving links put on the frame", fontsize=11)
    return fig


def page_plots(dyn: Dynamics, values: np.ndarray) -> tuple[Any, ...]:
    """The page's plots at its input values (k, frames) (rad or mm): the driving effort, the power, and the five
    most loaded joints' force magnitudes."""
    from camgen.core.page import Plot

    k = dyn.at(np.asarray(values, dtype=float)[0])
    effort = "torque" if dyn.crank else "force"
    plots = [Plot(f"driving {effort}", "N·m" if dyn.crank else "N", ((effort, k.effort),), (("zero", 0.0),)),
             Plot("driving power", "W", (("power", k.power),), (("zero", 0.0),))]
    loaded = sorted(k.pairs, key=lambda pf: -float(np.nanmax(np.hypot(*pf.force.T))))[:5]
    plots.append(Plot("joint forces", "N", tuple((pf.pair.name, np.hypot(*pf.force.T)) for pf in loaded)))
    return tuple(plots)
