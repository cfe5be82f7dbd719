"""Plots of a linkage: transmission angle over the cycle, the linkage at its dead centres, slider motion.

matplotlib's object API through :func:`camgen.core.figures.figure`; imported only when a plot is asked for.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.figures import figure
from linkgen.kinematics.fourbar import FourBar, Poses


def _input_grid(fb: FourBar, n: int = 721) -> list[np.ndarray]:
    ranges = fb.input_ranges()
    if ranges is None:
        return [np.linspace(0, 2 * math.pi, n)]
    return [np.linspace(lo, hi, n) for lo, hi in ranges]


def transmission_figure(name: str, fb: FourBar, assembly: str) -> Any:
    """Transmission angle against crank angle, the 40-140 degree band shaded, extremes marked."""
    fig = figure(8, 4.5)
    ax = fig.add_subplot()
    ax.axhspan(40, 140, color="C2", alpha=0.12, label="40-140° (good force transmission)")
    for t in _input_grid(fb):
        p = fb.sweep(t, assembly)
        ax.plot(np.degrees(t), np.degrees(p.gamma), color="C0", lw=1.4)
    (gmin, at_min), (gmax, at_max) = fb.transmission_extremes()
    ax.plot([math.degrees(at_min)], [math.degrees(gmin)], "v", color="C3", label=f"min {math.degrees(gmin):.2f}°")
    ax.plot([math.degrees(at_max)], [math.degrees(gmax)], "^", color="C1", label=f"max {math.degrees(gmax):.2f}°")
    ax.set_xlabel("crank angle θ2 (degrees)")
    ax.set_ylabel("transmission angle γ (degrees)")
    ax.set_ylim(0, 180)
    ax.set_yticks(range(0, 181, 20))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(f"{name}: transmission angle ({assembly} assembly)")
    return fig


def _draw(ax: Any, fb: FourBar, pose: Poses, colour: str, label: str) -> None:
    o2, o4 = np.zeros(2), np.array([fb.ground, 0.0])
    chain = np.array([o2, pose.a[0], pose.b[0], o4])
    ax.plot(chain[:, 0], chain[:, 1], "-o", color=colour, lw=2, ms=4, label=label)
    if fb.point_distance > 0:
        tri = np.array([pose.a[0], pose.point[0], pose.b[0]])
        ax.fill(tri[:, 0], tri[:, 1], color=colour, alpha=0.15)
        ax.plot(*pose.point[0], "*", color=colour, ms=8)


def dead_centre_figure(name: str, fb: FourBar, assembly: str) -> Any:
    """The linkage drawn at each dead-centre and toggle position, with the coupler-point path."""
    fig = figure(8, 6.5)
    ax = fig.add_subplot()
    ax.plot([0, fb.ground], [0, 0], color="0.3", lw=3, solid_capstyle="round", label="ground")
    for t in _input_grid(fb):
        p = fb.sweep(t, assembly)
        ax.plot(p.point[:, 0], p.point[:, 1], ":", color="0.4", lw=1)
        ax.plot(p.b[:, 0], p.b[:, 1], "--", color="0.75", lw=0.8)
    for k, d in enumerate(fb.dead_centres(assembly)):
        pose = fb.positions(np.array([d.crank]), assembly)
        _draw(ax, fb, pose, f"C{k % 10}", f"{d.kind}: crank {math.degrees(d.crank) % 360:.1f}°, "
                                          f"rocker {math.degrees(d.rocker) % 360:.1f}°")
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    fig.legend(loc="outside lower center", ncols=2, fontsize=8)
    ax.set_title(f"{name}: dead-centre positions ({assembly}); dotted: coupler-point path")
    return fig


def slider_figure(name: str, mech: Any, omega: float) -> Any:
    """Slider (ram) position, velocity and acceleration over one crank turn, dead centres marked."""
    rng = getattr(mech, "input_range", lambda: None)()
    t = np.linspace(*(rng if rng else (0.0, 2 * math.pi)), 721)
    m = mech.motion(t, omega)
    fig = figure(8, 7)
    axes = fig.subplots(3, 1, sharex=True)
    for ax, y, label in zip(axes, (m.x, m.v, m.a), ("position (mm)", "velocity (mm/s)", "acceleration (mm/s²)"),
                            strict=True):
        ax.plot(np.degrees(t), y, color="C0", lw=1.3)
        for _, crank, _ in mech.dead_centres():
            ax.axvline(math.degrees(crank) % 360, color="C3", lw=0.8, ls="--")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("crank angle (degrees); dashed: dead centres")
    axes[0].set_title(f"{name}: slider motion at {omega * 60 / (2 * math.pi):g} rpm")
    return fig
