"""The four-bar: its ``[linkage]`` table, report, figures, parts and thumbnail.

Frame (see :mod:`linkgen.kinematics.fourbar`): crank pivot O2 at the origin, rocker pivot
O4 at (ground, 0); angles counter-clockwise from +X. The parts are a ground plate holding
both pivots, the crank, the coupler (a plate when it carries a coupler point) and the
rocker. The helpers here also serve the straight-line linkages, which are four-bars.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field

from camgen.core.errors import SpecError
from camgen.core.parts import Drawing
from camgen.core.shapes import Polyline
from camgen.core.spec import Model, unit
from linkgen import plots
from linkgen.kinematics.circuits import input_grid, input_span
from linkgen.kinematics.fourbar import ASSEMBLIES, Assembly, FourBar, Poses
from linkgen.mechanisms.circuits import circuits_report, split_warning
from linkgen.mechanisms.common import Figure, deg, length, num, omega, rpm, types_of
from linkgen.parts import SWEEP, Layout, LinkPart, Placement, Stock

if TYPE_CHECKING:
    from linkgen.spec import PartsTable

#: transmission angles (degrees) usually kept for good force transmission
TRANSMISSION_BAND = (40.0, 140.0)
TWO_PI = 2 * math.pi


class FourBarTable(Model):
    """``[linkage]`` of a four-bar: link lengths (mm), an optional coupler point, the assembly and the driven link."""

    type: Literal["four-bar"]
    ground: float = length("ground link: input pivot to output pivot")
    crank: float = length("input link")
    coupler: float = length("coupler")
    rocker: float = length("output link")
    point_distance: float = Field(0.0, ge=0, description="coupler point: distance from the crank pin",
                                  json_schema_extra=unit("mm"))
    point_angle: float = Field(0.0, description="coupler point: angle from the coupler line, counter-clockwise",
                               json_schema_extra=unit("degrees"))
    assembly: Assembly = Field("open", description="assembly branch")
    input: Literal["crank", "rocker"] = Field("crank", description="driven link")
    rpm: float = rpm()


def position(fb: FourBar, pose: Poses, speed: float) -> dict[str, Any]:
    """The report's entry for one pose: angles (degrees), rates at ``speed`` rad/s of the input, pins (mm)."""
    w3, w4 = fb.velocities(pose, speed)
    a3, a4 = fb.accelerations(pose, speed)
    ma = fb.mechanical_advantage(pose)
    return {"crank_deg": deg(pose.theta2[0]), "coupler_deg": deg(pose.theta3[0]), "rocker_deg": deg(pose.theta4[0]),
            "transmission_deg": num(math.degrees(pose.gamma[0])),
            "coupler_omega_rad_s": num(w3[0]), "rocker_omega_rad_s": num(w4[0]),
            "coupler_alpha_rad_s2": num(a3[0]), "rocker_alpha_rad_s2": num(a4[0]),
            "mechanical_advantage": num(ma[0]),
            "crank_pin_mm": [num(v) for v in pose.a[0]], "rocker_pin_mm": [num(v) for v in pose.b[0]],
            "coupler_point_mm": [num(v) for v in pose.point[0]]}


def _ranges_deg(ranges: tuple[tuple[float, float], ...] | None) -> Any:
    if ranges is None:
        return None
    out = [[round(math.degrees(lo), 9), round(math.degrees(hi), 9)] for lo, hi in ranges]
    return out[0] if len(out) == 1 else out


def newton_table(fb: FourBar, angle: float, assembly: Assembly, start: tuple[float, float] | None = None,
                 tolerance: float | None = None) -> dict[str, Any]:
    """The Newton-Raphson table at crank angle ``angle`` (degrees): started from ``start`` (theta3, theta4 in
    degrees) or 10 degrees off the closed-form answer of ``assembly``, and stopped where the residual norm is at
    most ``tolerance`` mm (the course's test) or, without one, below 1e-12 of the longest link with a step as
    small. Says which assembly the answer is and how near the closed form's it is (degrees). Raises
    :class:`SolverError` where the iteration fails (a singular Jacobian, a stall, no convergence)."""
    least = 1e-12 * fb.longest
    if tolerance is not None and not tolerance >= least:
        raise SpecError(f"must be at least {least:.3g} mm here, 1e-12 of the longest link: the loop closes no "
                        f"nearer than rounding lets it (got {tolerance:g})", "tolerance")
    theta = math.radians(angle)
    exact = {a: fb.positions([theta], a) for a in ASSEMBLIES}
    if start is None:
        closed = exact[assembly]
        guess = (float(closed.theta3[0]) + math.radians(10), float(closed.theta4[0]) - math.radians(10))
        said = "closed-form answer moved by +10 degrees (coupler) and -10 degrees (rocker)"
    else:
        guess = (math.radians(start[0]), math.radians(start[1]))
        said = f"given: coupler {start[0]:g} degrees, rocker {start[1]:g} degrees"
    result = fb.newton(theta, guess, tolerance_mm=tolerance)

    def off(a: Assembly) -> float:
        return max(abs(math.degrees(math.remainder(result.theta3 - exact[a].theta3[0], TWO_PI))),
                   abs(math.degrees(math.remainder(result.theta4 - exact[a].theta4[0], TWO_PI))))

    found = assembly if start is None else min(ASSEMBLIES, key=off)
    return {
        "start": said, "start_deg": [math.degrees(g) for g in guess] if start is None else list(start),
        "tolerance_mm": 1e-12 * fb.longest if tolerance is None else tolerance,
        "test": ("residual norm at most the tolerance (the course's test)" if tolerance is not None
                 else "residual below the tolerance and the next step below 1e-9 rad"),
        "stopped": ("at a toggle's least-squares pose: no step lowers the residual, which is within the tolerance "
                    "the closed form reaches past a toggle with" if result.least_squares
                    else "residual below the tolerance"),
        "iterations": [{"iteration": s.iteration, "coupler_deg": math.degrees(s.theta3),
                        "rocker_deg": math.degrees(s.theta4), "f1_mm": s.f1, "f2_mm": s.f2,
                        "residual_mm": s.residual} for s in result.steps],
        "coupler_deg": deg(result.theta3), "rocker_deg": deg(result.theta4), "assembly": found,
        "agrees_with_closed_form_deg": off(found)}


def _warnings(report: dict[str, Any], grashof_class: str) -> list[str]:
    warnings = []
    if report["transmission_min_deg"] < TRANSMISSION_BAND[0] or report["transmission_max_deg"] > TRANSMISSION_BAND[1]:
        warnings.append(f"transmission angle spans {report['transmission_min_deg']:.2f} to "
                        f"{report['transmission_max_deg']:.2f} degrees, outside the usual {TRANSMISSION_BAND[0]:g}-"
                        f"{TRANSMISSION_BAND[1]:g} degree band for good force transmission")
    if grashof_class == "III":
        warnings.append("change point: the linkage can fold flat and switch assembly at crank angles "
                        f"{report['change_points_crank_deg']}; guide it through them")
    return warnings


def fourbar_report(table: FourBarTable, fb: FourBar, angle: float | None, method: str) -> dict[str, Any]:
    """Grashof class, reach, transmission angle, dead centres, time ratio and rocker swing; with ``angle`` (degrees)
    the positions of both assemblies there, and with ``method = "newton"`` the Newton-Raphson table."""
    rocker_in = table.input == "rocker"
    mirror = FourBar(fb.ground, fb.rocker, fb.coupler, fb.crank)
    g = mirror.grashof if rocker_in else fb.grashof
    (gmin, gmin_at), (gmax, gmax_at) = fb.transmission_extremes()
    limit = ("dead point: the rocker cannot drive the crank through it" if rocker_in
             else "rocker limit position (crank and coupler in line, {})")
    meaning = {"extended": limit.format("extended"), "folded": limit.format("folded"),
               "toggle-extended": "crank input stops: coupler and rocker in line, extended",
               "toggle-folded": "crank input stops: coupler and rocker in line, folded"}
    dead = [{"kind": d.kind, "crank_deg": deg(d.crank), "rocker_deg": deg(d.rocker), "meaning": meaning[d.kind]}
            for d in fb.dead_centres(table.assembly)
            if not (rocker_in and d.kind.startswith("toggle"))]
    ranges = fb.input_ranges()
    if rocker_in:
        mr = mirror.input_ranges()
        ranges = None if mr is None else tuple((math.pi - hi, math.pi - lo) for lo, hi in mr)
    by_circuit = circuits_report(fb, table.assembly, rocker_in)
    ratio = None if rocker_in else fb.time_ratio(table.assembly)
    report: dict[str, Any] = {
        "grashof_class": g.grashof_class, "inversion": g.inversion, "form": g.form,
        "grashof_margin_mm": round(g.margin, 9), "input": table.input, "assembly": table.assembly,
        "input_range_deg": _ranges_deg(ranges),
        "transmission_min_deg": round(math.degrees(gmin), 9), "transmission_min_at_crank_deg": deg(gmin_at),
        "transmission_max_deg": round(math.degrees(gmax), 9), "transmission_max_at_crank_deg": deg(gmax_at),
        "dead_centres": dead, "time_ratio": None if ratio is None else round(ratio, 12),
        "rocker_swing_deg": by_circuit["rocker_swing_deg"],
        "change_points_crank_deg": [deg(c) for c in fb.change_points()],
        "motion": by_circuit["motion"], "circuits": by_circuit["circuits"],
    }
    report["warnings"] = _warnings(report, g.grashof_class)
    split = split_warning(report, table.input)
    if split is not None:
        report["warnings"].append(split)
    if angle is not None:
        t = np.array([math.radians(angle)])
        solve = fb.rocker_positions if rocker_in else fb.positions
        poses = {a: solve(t, a) for a in ASSEMBLIES}
        report["positions"] = {a: position(fb, p, omega(table.rpm)) for a, p in poses.items()}
        if method == "newton":
            if rocker_in:
                raise SpecError("the Newton-Raphson table is for crank input", "--method")
            report["newton"] = newton_table(fb, angle, table.assembly)
    return report


def fourbar_figures(name: str, fb: FourBar, assembly: Assembly) -> tuple[Figure, ...]:
    """The transmission angle over the cycle, and the linkage at its dead centres with the coupler point's path."""
    return (("transmission", lambda: plots.transmission_figure(name, fb, assembly)),
            ("dead-centres", lambda: plots.dead_centre_figure(name, fb, assembly)))


def placement(fb: FourBar, theta2: np.ndarray, assembly: Assembly) -> Placement:
    """Where the ground, crank, coupler and rocker sit at crank angles ``theta2`` (rad), following one branch."""
    p = fb.sweep(theta2, assembly)
    o4 = np.tile([fb.ground, 0.0], (len(theta2), 1))
    return Placement(
        angles={"ground": np.zeros(len(theta2)), "crank": p.theta2, "coupler": p.theta3, "rocker": p.theta4},
        origins={"ground": np.zeros((len(theta2), 2)), "crank": np.zeros((len(theta2), 2)), "coupler": p.a,
                 "rocker": o4},
        joints={"O2": (("ground", "crank"), np.zeros((len(theta2), 2))), "A": (("crank", "coupler"), p.a),
                "B": (("coupler", "rocker"), p.b), "O4": (("ground", "rocker"), o4)})


def fourbar_parts(fb: FourBar, table: PartsTable) -> tuple[LinkPart, ...]:
    """Ground plate (twice the ground's width), crank, coupler (a plate when it carries a coupler point) and rocker."""
    stock = Stock.of(table)
    half = {k: table.width_of(k) / 2 for k in ("ground", "crank", "coupler", "rocker")}
    coupler = [[0.0, 0.0], [fb.coupler, 0.0]]
    if fb.point_distance > 0:
        coupler.append([fb.point_distance * math.cos(fb.point_angle), fb.point_distance * math.sin(fb.point_angle)])
    return (LinkPart("ground", np.array([[0.0, 0.0], [fb.ground, 0.0]]), 2 * half["ground"], stock, moving=False),
            LinkPart("crank", np.array([[0.0, 0.0], [fb.crank, 0.0]]), half["crank"], stock),
            LinkPart("coupler", np.array(coupler), half["coupler"], stock),
            LinkPart("rocker", np.array([[0.0, 0.0], [fb.rocker, 0.0]]), half["rocker"], stock))


def fourbar_layout(fb: FourBar, assembly: Assembly, table: PartsTable) -> Layout:
    """The parts over the first reachable crank range, the dead centres inside it, and the coupler point's path
    (the coupler-rocker pin's without one)."""
    ranges = fb.input_ranges()
    lo, hi = input_span(fb)
    sweep = placement(fb, input_grid(fb, SWEEP), assembly)
    dead = tuple((d.kind, d.crank) for d in fb.dead_centres(assembly)
                 if ranges is None or lo <= d.crank <= hi or lo <= d.crank + TWO_PI <= hi)
    poses = tuple(placement(fb, np.array([angle]), assembly) for _, angle in dead)
    theta = sweep.angles["crank"]
    path = fb.sweep(theta, assembly).point if fb.point_distance > 0 else sweep.joints["B"][1]
    return Layout(fourbar_parts(fb, table), sweep, dead, poses, (path,))


def fourbar_thumbnail(fb: FourBar, assembly: Assembly) -> dict[str, Any]:
    """The path the coupler point (or the rocker pin) traces, for a family's overview picture."""
    poses = fb.sweep(input_grid(fb, 121), assembly)
    path = poses.point if fb.point_distance > 0 else poses.b
    return {"thumbnail": path.round(3).tolist(), "thumbnail_kind": "path"}


def fourbar_sketch(fb: FourBar, assembly: Assembly) -> Drawing:
    """The linkage a tenth into its first reachable range (at 30 degrees when the crank turns fully), with the
    coupler point's path."""
    lo, hi = input_span(fb)
    start = lo + 0.1 * (hi - lo) if fb.input_ranges() else math.radians(30)
    p = fb.positions([start], assembly)
    links = np.array([[0.0, 0.0], p.a[0], p.b[0], [fb.ground, 0.0], [0.0, 0.0]])
    path = fb.sweep(input_grid(fb, 181), assembly).point
    items = [("LINKS", Polyline(links, np.zeros(4))), ("PATH", Polyline(path, np.zeros(len(path) - 1)))]
    return Drawing(tuple(items), 0.01)


@dataclass(frozen=True)
class FourBarMechanism:
    """``four-bar``: any four-bar, crank- or rocker-driven, with an optional coupler point."""

    types: tuple[str, ...] = types_of(FourBarTable)
    table: type[Model] = FourBarTable

    def build(self, table: FourBarTable) -> FourBar:
        return FourBar(table.ground, table.crank, table.coupler, table.rocker, table.point_distance,
                       math.radians(table.point_angle))

    def report(self, table: FourBarTable, kinematics: FourBar, angle: float | None, method: str) -> dict[str, Any]:
        return fourbar_report(table, kinematics, angle, method)

    def figures(self, name: str, table: FourBarTable, kinematics: FourBar) -> tuple[Figure, ...]:
        return fourbar_figures(name, kinematics, table.assembly)

    def layout(self, table: FourBarTable, kinematics: FourBar, parts: PartsTable) -> Layout:
        return fourbar_layout(kinematics, table.assembly, parts)

    def family_row(self, table: FourBarTable, kinematics: FourBar, report: dict[str, Any]) -> dict[str, Any]:
        return fourbar_thumbnail(kinematics, table.assembly)

    def sketch(self, table: FourBarTable, kinematics: FourBar) -> Drawing:
        return fourbar_sketch(kinematics, table.assembly)


REGISTER = (FourBarMechanism(),)
