"""Plots of a Geneva drive: the wheel's motion over a driver turn, and the drive assembled at three angles.

matplotlib's object API (no pyplot state), imported only when a plot is asked for.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.figures import PREVIEW_TOLERANCE_MM, figure
from camgen.kinds.geneva.design import GenevaDesign, sample_turn


def motion_figure(design: GenevaDesign) -> Any:
    """The wheel's angle, velocity, acceleration and jerk against the driver's angle (per radian of it), the
    acceleration's jumps at entry and exit marked."""
    law, m = design.law, design.motion
    alpha, values = sample_turn(law)
    deg = np.degrees(alpha)
    fig = figure(8, 9)
    axes = fig.subplots(4, 1, sharex=True)
    labels = ["wheel angle β (deg)", "β' (× ω)", "β'' (× ω²)", "β''' (× ω³)"]
    e = math.degrees(law.engagement)
    for k, ax in enumerate(axes):
        ax.plot(deg, np.degrees(values[0]) if k == 0 else values[k], color="C0", lw=1.2)
        ax.axhline(0, color="0.6", lw=0.6)
        for at in (-e, e):
            ax.axvline(at, color="0.85", lw=0.6, zorder=0)
        ax.set_ylabel(labels[k])
        ax.grid(alpha=0.3)
    jump = law.acceleration_jump
    for at, sign in ((-e, 1), (e, -1)):
        axes[2].annotate(f"jump {jump:.3f}", (at, sign * jump), color="C3", ha="center",
                         va="bottom" if sign > 0 else "top", fontsize=8)
        axes[3].annotate("∞", (at, 0), color="C3", ha="center", va="bottom", fontsize=12)
    peak, at = m["acceleration_ratio_max"], m["acceleration_ratio_max_at_deg"]
    axes[2].plot(at, [peak, -peak], "o", color="C1", ms=4, label=f"peak {peak:.4f} at ±{at[1]:.2f}°")
    axes[2].legend(fontsize=8, loc="upper right")
    axes[-1].set_xlabel("driver angle α (degrees, from the centre line)")
    axes[-1].set_xlim(-180, 180)
    axes[-1].set_xticks(range(-180, 181, 30))
    axes[0].set_title(f"{design.spec.name}: {law.slots}-slot Geneva, the wheel's motion over a driver turn "
                      "(∞ marks infinite jerk)")
    return fig


def _placed(ring: np.ndarray, angle: float, shift: tuple[float, float]) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.column_stack([c * ring[:, 0] - s * ring[:, 1] + shift[0], s * ring[:, 0] + c * ring[:, 1] + shift[1]])


def assembly_figure(design: GenevaDesign) -> Any:
    """The drive at the pin's entry, at the wheel's peak acceleration and in the middle of the dwell: the wheel, the
    locking disc, the crank and pin, the pin's circle."""
    g, check = design.geometry, design.assembly
    e, peak = g.law.engagement, g.law.acceleration_peak()[1]
    fig = figure(14, 5.2)
    axes = fig.subplots(1, 3)
    circle = np.linspace(0, 2 * math.pi, 361)
    shapes = {k: p.outline.flatten(PREVIEW_TOLERANCE_MM) for k, p in design.parts.items()}
    for ax, (alpha, what) in zip(axes, ((-e, "entry"), (-peak, "peak acceleration"), (math.pi, "dwell")), strict=True):
        beta = float(g.law.motion(np.array([alpha]))[0, 0])
        wheel = _placed(shapes["wheel"], math.pi - beta, (g.centre_distance, 0.0))
        ax.fill(*wheel.T, color="#9ecae1", ec="C0", lw=0.8, label="wheel")
        ax.fill(*_placed(shapes["lock"], alpha, (0.0, 0.0)).T, color="#fdd0a2", ec="C1", lw=0.8,
                label="locking disc")
        ax.plot(*np.vstack([c := _placed(shapes["crank"], alpha, (0.0, 0.0)), c[:1]]).T, color="0.4", lw=0.8,
                ls="--", label="crank (below)")
        pin = g.crank_radius * np.array([math.cos(alpha), math.sin(alpha)])
        ax.fill(pin[0] + g.pin_diameter / 2 * np.cos(circle), pin[1] + g.pin_diameter / 2 * np.sin(circle),
                color="C3", label="pin")
        ax.plot(g.crank_radius * np.cos(circle), g.crank_radius * np.sin(circle), ":", color="0.5", lw=0.7,
                label="pin circle")
        ax.plot([0, g.centre_distance], [0, 0], "+", color="k", ms=8)
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.set_title(f"{what}: α = {math.degrees(alpha):.2f}°, β = {math.degrees(beta):.2f}°", fontsize=10)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=5, fontsize=8)
    fig.suptitle(f"{design.spec.name}: least gap locking disc to wheel {check.lock_clearance_min_mm:.4f} mm, pin to "
                 f"wheel {check.pin_clearance_min_mm:.4f} mm over a turn", fontsize=10)
    return fig
