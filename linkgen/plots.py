"""Plots of a linkage: transmission angle over the cycle, the linkage at its dead centres, slider motion.

matplotlib's object API through :func:`camgen.core.figures.figure`; imported only when a plot is asked for. Fixed
margins (charts) and figures sized to their drawings (:func:`camgen.core.figures.fit_equal`), no constrained layout.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.figures import figure, fit_equal
from linkgen.kinematics.circuits import input_grid, input_spans
from linkgen.kinematics.fourbar import Assembly, FourBar, Poses
from linkgen.kinematics.groups import GROUP_KINDS


def _chart(width: float, height: float) -> tuple[Any, Any]:
    """A figure of one chart with fixed margins: a constrained layout re-measures every label each time a figure is
    written (PNG and SVG), and took most of what linkgen's figures cost."""
    fig = figure(width, height, layout=None)
    fig.subplots_adjust(left=0.09, right=0.97, bottom=0.12, top=0.92)
    return fig, fig.add_subplot()


def _input_grid(fb: FourBar, n: int = 721) -> list[np.ndarray]:
    """The crank angles (rad) each curve is drawn at: ``n`` over the full turn or over each reachable range, off a
    deltoid's undetermined fold (see :func:`linkgen.kinematics.circuits.input_grid`)."""
    return [input_grid(fb, n, span) for span in input_spans(fb)]


def transmission_figure(name: str, fb: FourBar, assembly: Assembly) -> Any:
    """Transmission angle against crank angle, the 40-140 degree band shaded, extremes marked."""
    fig, ax = _chart(8, 4.5)
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


def dead_centre_figure(name: str, fb: FourBar, assembly: Assembly) -> Any:
    """The linkage drawn at each dead-centre and toggle position, with the rocker pin's arc and, with a coupler
    point, its path."""
    fig = figure(8, 6.5, layout=None)
    ax = fig.add_subplot()
    ax.plot([0, fb.ground], [0, 0], color="0.3", lw=3, solid_capstyle="round", label="ground")
    for t in _input_grid(fb):
        p = fb.sweep(t, assembly)
        if fb.point_distance > 0:
            ax.plot(p.point[:, 0], p.point[:, 1], ":", color="0.4", lw=1)
        ax.plot(p.b[:, 0], p.b[:, 1], "--", color="0.75", lw=0.8)
    for k, d in enumerate(fb.dead_centres(assembly)):
        pose = fb.positions(np.array([d.crank]), assembly)
        _draw(ax, fb, pose, f"C{k % 10}", f"{d.kind}: crank {math.degrees(d.crank) % 360:.1f}°, "
                                          f"rocker {math.degrees(d.rocker) % 360:.1f}°")
    ax.grid(alpha=0.3)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    fit_equal(fig, [ax], width=8.0, legend_rows=math.ceil(len(ax.get_legend_handles_labels()[1]) / 2), top=0.1)
    fig.legend(loc="lower center", ncols=2, fontsize=8)
    paths = "dotted: coupler-point path; dashed: rocker pin" if fb.point_distance > 0 else "dashed: rocker pin's arc"
    ax.set_title(f"{name}: dead-centre positions ({assembly}); {paths}")
    return fig


def slider_figure(name: str, mech: Any, omega: float) -> Any:
    """Slider (ram) position, velocity and acceleration over one crank turn, dead centres marked."""
    rng = getattr(mech, "input_range", lambda: None)()
    lo, hi = rng if rng else (0.0, 2 * math.pi)
    t = np.linspace(lo, hi, 721)
    m = mech.motion(t, omega)
    fig = figure(8, 7, layout=None)
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.08, top=0.95, hspace=0.12)
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


def _input_axis(a: Any) -> tuple[np.ndarray, str]:
    """The analysed input values in the report's unit and the axis label (the span, not the solution's inputs, which
    a crank's full turn wraps back to its start)."""
    x = a.span[0]
    return (np.degrees(x), "input angle (degrees)") if a.crank else (x, "input travel (mm)")


def linkage_motion_figure(name: str, a: Any) -> Any:
    """A general linkage as drawn (links as lines and plates), a few poses over its motion in grey, and the paths
    of its tracers (of every moving joint when there are none)."""
    s = a.linkage.structure
    sol = a.sweep
    fig = figure(8, 6.5, layout=None)
    ax = fig.add_subplot()
    traced = a.table.tracers or tuple(p for p in s.points if p not in s.bodies["ground"])
    for k, point in enumerate(traced):
        path = sol.points[point]
        ax.plot(path[:, 0], path[:, 1], ":" if not a.table.tracers else "-", lw=1 if not a.table.tracers else 1.6,
                color=f"C{k % 10}", label=f"path of {point}" if a.table.tracers else None)
    n = sol.inputs.shape[1]
    for idx, alpha in [(i, 0.25) for i in np.linspace(0, n - 1, 7).astype(int)[1:-1]] + [(None, 1.0)]:
        where = {p: (np.asarray(xy) if idx is None else sol.points[p][idx]) for p, xy in s.points.items()}
        for body, pts in s.bodies.items():
            xy = np.array([where[p] for p in pts])
            colour = "0.3" if body == "ground" else ("C0" if idx is None else "0.6")
            if body == "ground":
                ax.plot(xy[:, 0], xy[:, 1], "^", color=colour, ms=9)
            elif len(pts) > 2:
                ax.fill(xy[:, 0], xy[:, 1], color=colour, alpha=0.2 * alpha, lw=0)
                ring = np.vstack([xy, xy[:1]])
                ax.plot(ring[:, 0], ring[:, 1], "-", color=colour, lw=1.5, alpha=alpha)
            else:
                ax.plot(xy[:, 0], xy[:, 1], "-o", color=colour, lw=2, ms=3, alpha=alpha)
    for p, xy in s.points.items():
        ax.annotate(p, xy, textcoords="offset points", xytext=(4, 4), fontsize=8)
    ax.grid(alpha=0.3)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    fit_equal(fig, [ax], width=8.0, top=0.1)
    if a.table.tracers:
        ax.legend(fontsize=8)
    ax.set_title(f"{name}: as drawn (blue), poses over the motion (grey) and paths")
    return fig


def linkage_transmission_figure(name: str, a: Any) -> Any:
    """Each dyad's transmission angle against the input, the 40-140 degree band shaded, toggles marked."""
    fig, ax = _chart(8, 4.5)
    ax.axhspan(40, 140, color="C2", alpha=0.12, label="40-140°")
    x, label = _input_axis(a)
    for k, d in enumerate(d for d in a.sweep.dyads if d.kind not in GROUP_KINDS):   # a group has no such angle
        ax.plot(x, np.degrees(d.transmission), color=f"C{k % 10}", lw=1.3,
                label=f"{d.kind} {'-'.join(d.bodies)} at {d.joint}")
    ax.set_xlabel(label)
    ax.set_ylabel("transmission angle (degrees)")
    ax.set_ylim(0, 180)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(f"{name}: transmission angle of each dyad")
    return fig


def effort_figure(name: str, st: Any) -> Any:
    """The input's effort holding the loads (N*m or N) against the input, and the mechanical advantage for a single
    force on a second (logarithmic) axis."""
    x, label = _input_axis(st.analysis)
    fig = figure(8, 4.5, layout=None)
    fig.subplots_adjust(left=0.1, right=0.88, bottom=0.12, top=0.92)
    ax = fig.add_subplot(title=f"{name}: effort that holds the loads", xlabel=label,
                         ylabel="input torque (N·m)" if st.crank else "input force (N)")
    ax.plot(x, st.effort, color="C0", lw=1.6)
    ax.axhline(0.0, color="0.5", lw=0.8)
    advantage = st.advantage(st.effort)
    if advantage is not None and np.isfinite(advantage).any():        # none for a force that asks no effort
        ax2 = ax.twinx()
        ax2.plot(x, np.where(np.isfinite(advantage), advantage, np.nan), color="C1", lw=1, ls="--")
        ax2.set(ylabel="mechanical advantage", yscale="log")
    ax.grid(alpha=0.3)
    return fig


def linkage_pose_figure(name: str, a: Any, value: float) -> Any:
    """The linkage at input ``value`` (rad for a crank, mm for a slide), every joint labelled, the paths of its
    tracers (of every moving joint when there are none) over the motion analysed in grey."""
    s = a.linkage.structure
    pose = a.linkage.solve(np.array([value])).points
    fig = figure(8, 6.5, layout=None)
    ax = fig.add_subplot()
    for point in s.points:
        if point not in s.bodies["ground"]:
            path = a.sweep.points[point]
            strong = point in a.table.tracers
            ax.plot(path[:, 0], path[:, 1], "-", color="0.45" if strong else "0.8", lw=1.4 if strong else 0.8)
    for k, (body, pts) in enumerate(s.bodies.items()):
        xy = np.array([pose[p][0] for p in pts])
        if body == "ground":
            ax.plot(xy[:, 0], xy[:, 1], "^", color="0.3", ms=9)
            continue
        colour = f"C{k % 10}"
        ring = np.vstack([xy, xy[:1]]) if len(pts) > 2 else xy
        if len(pts) > 2:
            ax.fill(xy[:, 0], xy[:, 1], color=colour, alpha=0.2, lw=0)
        ax.plot(ring[:, 0], ring[:, 1], "-o", color=colour, lw=2, ms=4, label=body)
    for p, xy in pose.items():
        ax.annotate(p, xy[0], textcoords="offset points", xytext=(4, 4), fontsize=8)
    shown = f"{np.degrees(value) % 360:.2f}°" if a.crank else f"{value:.3f} mm"
    ax.grid(alpha=0.3)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    fit_equal(fig, [ax], width=8.0, top=0.1)
    ax.legend(fontsize=8, loc="best")
    ax.set_title(f"{name}: the linkage at input {shown}; grey: the joints' paths (darker: tracers)")
    return fig
