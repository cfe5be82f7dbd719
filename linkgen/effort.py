"""What holding a linkage's loads asks of its input: the effort over the motion, its peaks, and the mechanical
advantage (``[[loads]]``; the virtual work itself is :mod:`linkgen.kinematics.statics`).

Every mechanism linkgen draws as a general linkage takes loads by its joints' and links' names (a four-bar's
O2, A, B, O4, P and crank, coupler, rocker; see docs/guides/loads.md). The effort is sampled over the motion
analysed and its extremes refined to 1e-9 of the input's range; the mechanical advantage, for one force, is that
force over the force the input gives at its lever's radius (a crank's torque over the input link's longest reach
from its pivot; a slide's force itself).
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics.statics import LinkTorque, PointForce, input_effort
from linkgen.kinematics.structure import GROUND
from linkgen.mechanisms.general import Analysis

#: how finely the extremes are found: a fraction of the input's range
REFINE_TO = 1e-9


@dataclass(frozen=True)
class Statics:
    """The effort holding the loads over the motion: inputs (rad or mm, as analysed), effort (N*m or N), the
    lever radius (mm; 1 for a slide) and the loads."""

    analysis: Analysis
    forces: tuple[PointForce, ...]
    torques: tuple[LinkTorque, ...]
    inputs: np.ndarray
    effort: np.ndarray
    lever_mm: float

    @property
    def crank(self) -> bool:
        return self.analysis.crank

    def effort_at(self, x: np.ndarray) -> np.ndarray:
        """The effort at input values ``x`` (rad or mm)."""
        sol = self.analysis.linkage.solve(np.atleast_1d(x), strict=False)
        return np.where(sol.ok, input_effort(sol, self.forces, self.torques, self.crank), np.nan)

    def advantage(self, effort: np.ndarray) -> np.ndarray | None:
        """Mechanical advantage for one force: |F| over the input's force at its lever, |Q| / lever (None else);
        infinite where the input gives no force (a dead centre, a force across its point's path, a zero force),
        NaN where the effort is."""
        if len(self.forces) != 1 or self.torques:
            return None
        held = math.hypot(*self.forces[0].force)
        given = np.abs(effort) * (1000.0 / self.lever_mm if self.crank else 1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(np.isnan(given), np.nan, np.where(given > 0, held / given, np.inf))


def statics_of(loads: Sequence[Any], analysis: Analysis) -> Statics:
    """The effort that holds ``loads`` (``[[loads]]`` tables) on the linkage ``analysis`` draws; a
    :class:`SpecError` naming the load for a joint or link the linkage has not, or for a linkage of more than one
    input."""
    s = analysis.linkage.structure
    if len(s.inputs) != 1:
        raise SpecError("a linkage of one input holds loads (with two, one effort cannot be said)", "loads")
    forces, torques = [], []
    moving_points = [p for p in s.points if p not in s.bodies[GROUND]]
    for i, load in enumerate(loads):
        if load.point is not None:
            if load.point not in s.points:
                raise SpecError(f"no joint {load.point!r}; joints: {', '.join(s.points)}", f"loads[{i}].point")
            if load.point not in moving_points:
                raise SpecError(f"{load.point} is fixed to the ground, which holds a force there by itself (it asks "
                                f"nothing of the input); give a moving joint: {', '.join(moving_points)}",
                                f"loads[{i}].point")
            forces.append(PointForce(load.point, tuple(load.force)))
        else:
            moving = [b for b in s.bodies if b != "ground"]
            if load.link not in moving:
                raise SpecError(f"no moving link {load.link!r}; links: {', '.join(moving)}", f"loads[{i}].link")
            torques.append(LinkTorque(load.link, float(load.torque)))
    sol = analysis.sweep
    effort = input_effort(sol, forces, torques, analysis.crank)
    effort = np.where(sol.ok, effort, np.nan)
    inp = s.inputs[0]
    lever = 1.0
    if inp.kind == "crank":
        pivot = np.asarray(s.points[inp.pivot])
        lever = max(float(np.hypot(*(np.asarray(s.points[p]) - pivot))) for p in s.bodies[inp.link])
    return Statics(analysis, tuple(forces), tuple(torques), analysis.span[0], effort, lever)


def _refine(f: Callable[[np.ndarray], np.ndarray], x: np.ndarray, i: int, sign: float) -> tuple[float, float]:
    """The extreme of ``sign * f`` near sample ``i`` of the grid ``x``: a few rounds of a fine grid across the
    samples either side, to :data:`REFINE_TO` of the range."""
    lo, hi = x[max(i - 1, 0)], x[min(i + 1, len(x) - 1)]
    best_x, best = float(x[i]), float(f(x[i:i + 1])[0])
    while hi - lo > REFINE_TO * (x[-1] - x[0]):
        grid = np.linspace(lo, hi, 41)
        values = sign * f(grid)
        values = np.where(np.isfinite(values), values, -np.inf)
        k = int(np.argmax(values))
        if values[k] > sign * best:
            best_x, best = float(grid[k]), float(sign * values[k])
        step = grid[1] - grid[0]
        lo, hi = max(grid[k] - step, x[0]), min(grid[k] + step, x[-1])
    return best_x, best


def statics_report(st: Statics, rpm: float) -> dict[str, Any]:
    """The report's ``statics`` section: the effort's extremes (refined) and RMS over the motion, the peak power at
    ``rpm``, the least mechanical advantage for one force, and where the input cannot hold the loads."""
    a = st.analysis
    unit = "N_m" if st.crank else "N"
    finite = np.isfinite(st.effort)
    out: dict[str, Any] = {"effort": "torque on the input, N*m counter-clockwise" if st.crank
                           else "force on the input slide, N along its travel",
                           "loads": [{"point": f.point, "force_N": list(f.force)} for f in st.forces]
                           + [{"link": t.link, "torque_N_m": t.torque} for t in st.torques]}
    if not finite.any():
        out["warnings"] = ["the input cannot hold these loads anywhere in its motion"]
        return out
    key = "input_deg" if st.crank else "input_mm"
    for name, sign in (("max", 1.0), ("min", -1.0)):
        i = int(np.nanargmax(sign * st.effort))
        x, value = _refine(st.effort_at, st.inputs, i, sign)
        out[f"{name}_{unit}"] = value
        out[f"{name}_at_{key}"] = a.shown(x)
    out[f"rms_{unit}"] = float(np.sqrt(np.trapezoid(st.effort[finite] ** 2, st.inputs[finite])
                                       / (st.inputs[finite][-1] - st.inputs[finite][0])))
    peak = max(abs(out[f"max_{unit}"]), abs(out[f"min_{unit}"]))
    speed = rpm * 2 * math.pi / 60 if st.crank else None
    if speed is not None:
        out["peak_power_W"] = peak * speed
    warnings = []
    advantage = st.advantage(st.effort)
    if advantage is not None and np.isfinite(advantage).any():
        i = int(np.nanargmin(np.where(np.isfinite(advantage), advantage, np.nan)))
        x, _ = _refine(st.effort_at, st.inputs, i, 1.0 if st.effort[i] >= 0 else -1.0)
        there = st.advantage(st.effort_at(np.array([x])))      # not None: one force, as at the samples
        refined = math.nan if there is None else float(there[0])
        if not math.isfinite(refined):                     # the refinement met a dead centre: keep the sample
            x, refined = float(st.inputs[i]), float(advantage[i])
        out["mechanical_advantage_min"] = refined
        out[f"mechanical_advantage_min_at_{key}"] = a.shown(x)
        out["lever_mm"] = st.lever_mm
    elif advantage is not None:
        force = st.forces[0]
        why = "the force is zero" if not any(force.force) else \
            f"the force at {force.point} lies across its path everywhere, so it asks no effort of the input"
        warnings.append(f"no mechanical advantage: {why}")
    if not finite.all():
        bad = st.inputs[~finite]
        warnings.append(f"the input cannot hold the loads near {a.shown(float(bad[0])):.4g} "
                        f"{'degrees' if st.crank else 'mm'}: a dead centre of the input")
    if warnings:
        out["warnings"] = warnings
    return out
