"""The kinematic report of a linkage template (what ``linkgen analyze`` prints), in mm and degrees."""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from linkgen.fourbar import ASSEMBLIES, FourBar, Poses
from linkgen.quickreturn import CrankShaper, Whitworth
from linkgen.slidercrank import ScotchYoke, SliderCrank
from linkgen.straightline import straight_line

#: transmission angles (degrees) usually kept for good force transmission
TRANSMISSION_BAND = (40.0, 140.0)
CONVENTIONS = ("input pivot at the origin, output pivot on +X; angles counter-clockwise from the ground line (+X) "
               "in degrees; lengths in mm; speeds per second at the template's rpm")


def _deg(x: float) -> float:
    """Degrees in [0, 360), rounded to 1e-9."""
    return round(math.degrees(x) % 360.0, 9) % 360.0


def _num(x: float) -> float | None:
    """A JSON number, or None where the value is unbounded (at a toggle)."""
    return round(float(x), 9) if math.isfinite(x) else None


def build_linkage(spec: Any) -> Any:
    """The kinematic object a validated ``[linkage]`` table describes."""
    kind = spec.type
    if kind == "four-bar":
        return FourBar(spec.ground, spec.crank, spec.coupler, spec.rocker, spec.point_distance,
                       math.radians(spec.point_angle))
    if kind == "slider-crank":
        return SliderCrank(spec.crank, spec.rod, spec.offset)
    if kind == "scotch-yoke":
        return ScotchYoke(spec.crank)
    if kind == "whitworth":
        return Whitworth(spec.crank, spec.ground, spec.arm, spec.rod)
    if kind == "crank-shaper":
        return CrankShaper(spec.crank, spec.ground, spec.lever)
    return straight_line(kind, spec.size)


def _fourbar_position(fb: FourBar, pose: Poses, omega: float) -> dict[str, Any]:
    w3, w4 = fb.velocities(pose, omega)
    a3, a4 = fb.accelerations(pose, omega)
    ma = fb.mechanical_advantage(pose)
    return {"crank_deg": _deg(pose.theta2[0]), "coupler_deg": _deg(pose.theta3[0]), "rocker_deg": _deg(pose.theta4[0]),
            "transmission_deg": _num(math.degrees(pose.gamma[0])),
            "coupler_omega_rad_s": _num(w3[0]), "rocker_omega_rad_s": _num(w4[0]),
            "coupler_alpha_rad_s2": _num(a3[0]), "rocker_alpha_rad_s2": _num(a4[0]),
            "mechanical_advantage": _num(ma[0]),
            "crank_pin_mm": [_num(v) for v in pose.a[0]], "rocker_pin_mm": [_num(v) for v in pose.b[0]],
            "coupler_point_mm": [_num(v) for v in pose.point[0]]}


def _ranges_deg(ranges: tuple[tuple[float, float], ...] | None) -> Any:
    if ranges is None:
        return None
    out = [[round(math.degrees(lo), 9), round(math.degrees(hi), 9)] for lo, hi in ranges]
    return out[0] if len(out) == 1 else out


def analyze_fourbar(spec: Any, fb: FourBar, angle: float | None, method: str) -> dict[str, Any]:
    rocker_in = spec.input == "rocker"
    mirror = FourBar(fb.ground, fb.rocker, fb.coupler, fb.crank)
    g = mirror.grashof if rocker_in else fb.grashof
    (gmin, gmin_at), (gmax, gmax_at) = fb.transmission_extremes()
    meaning = {"extended": "dead point: the rocker cannot drive the crank through it" if rocker_in
               else "rocker limit position (crank and coupler in line, extended)",
               "folded": "dead point: the rocker cannot drive the crank through it" if rocker_in
               else "rocker limit position (crank and coupler in line, folded)",
               "toggle-extended": "crank input stops: coupler and rocker in line, extended",
               "toggle-folded": "crank input stops: coupler and rocker in line, folded"}
    dead = [{"kind": d.kind, "crank_deg": _deg(d.crank), "rocker_deg": _deg(d.rocker), "meaning": meaning[d.kind]}
            for d in fb.dead_centres(spec.assembly)
            if not (rocker_in and d.kind.startswith("toggle"))]
    ranges = fb.input_ranges()
    if rocker_in:
        mr = mirror.input_ranges()
        ranges = None if mr is None else tuple((math.pi - hi, math.pi - lo) for lo, hi in mr)
    swing = None
    limits = [d for d in fb.dead_centres(spec.assembly) if d.kind in ("extended", "folded")]
    if len(limits) == 2 and not rocker_in:
        swing = abs(math.degrees(math.remainder(limits[0].rocker - limits[1].rocker, 2 * math.pi)))
    ratio = None if rocker_in else fb.time_ratio(spec.assembly)
    report: dict[str, Any] = {
        "grashof_class": g.grashof_class, "inversion": g.inversion, "form": g.form,
        "grashof_margin_mm": round(g.margin, 9), "input": spec.input, "assembly": spec.assembly,
        "input_range_deg": _ranges_deg(ranges),
        "transmission_min_deg": round(math.degrees(gmin), 9), "transmission_min_at_crank_deg": _deg(gmin_at),
        "transmission_max_deg": round(math.degrees(gmax), 9), "transmission_max_at_crank_deg": _deg(gmax_at),
        "dead_centres": dead, "time_ratio": None if ratio is None else round(ratio, 12),
        "rocker_swing_deg": None if swing is None else round(swing, 9),
        "change_points_crank_deg": [_deg(c) for c in fb.change_points()],
    }
    warnings = []
    if report["transmission_min_deg"] < TRANSMISSION_BAND[0] or report["transmission_max_deg"] > TRANSMISSION_BAND[1]:
        warnings.append(f"transmission angle spans {report['transmission_min_deg']:.2f} to "
                        f"{report['transmission_max_deg']:.2f} degrees, outside the usual {TRANSMISSION_BAND[0]:g}-"
                        f"{TRANSMISSION_BAND[1]:g} degree band for good force transmission")
    if g.grashof_class == "III":
        warnings.append("change point: the linkage can fold flat and switch assembly at crank angles "
                        f"{report['change_points_crank_deg']}; guide it through them")
    report["warnings"] = warnings
    if angle is not None:
        omega = spec.rpm * 2 * math.pi / 60
        t = np.array([math.radians(angle)])
        if rocker_in:
            poses = {a: fb.rocker_positions(t, a) for a in ASSEMBLIES}
        else:
            poses = {a: fb.positions(t, a) for a in ASSEMBLIES}
        report["positions"] = {a: _fourbar_position(fb, p, omega) for a, p in poses.items()}
        if method == "newton":
            if rocker_in:
                raise SpecError("the Newton-Raphson table is for crank input", "--method")
            exact = poses[spec.assembly]
            guess = (float(exact.theta3[0]) + math.radians(10), float(exact.theta4[0]) - math.radians(10))
            result = fb.newton(float(t[0]), guess)
            report["newton"] = {
                "start": "closed-form answer moved by +10 degrees (coupler) and -10 degrees (rocker)",
                "tolerance_mm": 1e-12 * fb.longest,
                "iterations": [{"iteration": s.iteration, "coupler_deg": math.degrees(s.theta3),
                                "rocker_deg": math.degrees(s.theta4), "f1_mm": s.f1, "f2_mm": s.f2,
                                "residual_mm": s.residual} for s in result.steps],
                "agrees_with_closed_form_deg": max(
                    abs(math.degrees(math.remainder(result.theta3 - exact.theta3[0], 2 * math.pi))),
                    abs(math.degrees(math.remainder(result.theta4 - exact.theta4[0], 2 * math.pi))))}
    return report


def _slider_report(spec: Any, mech: Any, angle: float | None) -> dict[str, Any]:
    report: dict[str, Any] = {}
    if isinstance(mech, SliderCrank):
        rng = mech.input_range()
        report["input_range_deg"] = None if rng is None else [round(math.degrees(x), 9) for x in rng]
    else:
        report["input_range_deg"] = None
    dead = mech.dead_centres()
    report["dead_centres"] = [{"kind": k, "crank_deg": _deg(t), "slider_mm": round(x, 9)} for k, t, x in dead]
    full = not isinstance(mech, SliderCrank) or mech.turns_fully
    report["stroke_mm"] = round(mech.stroke, 9) if full and len(dead) == 2 else None
    report["time_ratio"] = round(mech.time_ratio, 12) if full and len(dead) == 2 else None
    if isinstance(mech, SliderCrank) and mech.offset == 0 and mech.turns_fully:
        t = np.linspace(0, 2 * math.pi, 3601)
        d, _, _ = mech.approximation(t)
        exact = mech.position(0.0) - mech.position(t)
        err = np.abs(exact - d)
        report["approximation_error_max_mm"] = round(float(err.max()), 12)
        report["approximation_error_estimate_mm"] = round(mech.crank**4 / (8 * mech.rod**3), 12)
    if isinstance(mech, CrankShaper):
        report["lever_swing_deg"] = round(math.degrees(mech.swing), 9)
    if angle is not None:
        omega = spec.rpm * 2 * math.pi / 60
        m = mech.motion(np.array([math.radians(angle)]), omega)
        pos = {"crank_deg": _deg(m.theta[0]), "slider_mm": _num(m.x[0]), "velocity_mm_s": _num(m.v[0]),
               "acceleration_mm_s2": _num(m.a[0])}
        if isinstance(mech, SliderCrank):
            pos["rod_deg"] = _deg(m.rod[0])
            if mech.offset == 0:
                d, d1, d2 = mech.approximation(m.theta)
                # displacement from TDC is x(0) - x, so its rates are -v and -a
                pos["approximation"] = {
                    "displacement_from_tdc_mm": _num(d[0]), "error_mm": _num(mech.position(0.0) - m.x[0] - d[0]),
                    "velocity_mm_s": _num(d1[0] * omega), "velocity_error_mm_s": _num(-m.v[0] - d1[0] * omega),
                    "acceleration_mm_s2": _num(d2[0] * omega**2),
                    "acceleration_error_mm_s2": _num(-m.a[0] - d2[0] * omega**2)}
        elif isinstance(mech, (CrankShaper, Whitworth)):
            pos["link_deg"] = round(math.degrees(m.rod[0]), 9)
        report["positions"] = pos
    return report


def analyze(template: Any, angle: float | None = None, method: str = "closed") -> dict[str, Any]:
    """The report for a validated linkage template; ``angle`` (degrees) adds the positions there."""
    spec = template.linkage
    if angle is not None and not math.isfinite(angle):
        raise SpecError(f"must be a finite number of degrees (got {angle})", "--angle")
    mech = build_linkage(spec)
    report: dict[str, Any] = {"name": template.name, "type": spec.type, "conventions": CONVENTIONS,
                              "lengths_mm": {k: v for k, v in spec.model_dump().items()
                                             if k not in ("type", "assembly", "input", "rpm", "point_angle")},
                              "rpm": spec.rpm}
    if isinstance(mech, FourBar):
        report.update(analyze_fourbar(spec, mech, angle, method))
    elif hasattr(mech, "straightness"):
        s = mech.straightness()
        fb = mech.linkage
        report["proportions"] = {"ground": fb.ground, "crank": fb.crank, "coupler": fb.coupler, "rocker": fb.rocker,
                                 "point_distance": fb.point_distance,
                                 "point_angle_deg": round(math.degrees(fb.point_angle), 9),
                                 "assembly": mech.assembly}
        report["grashof_class"], report["inversion"] = fb.grashof.grashof_class, fb.grashof.inversion
        report["straightness"] = {"stroke_mm": s.stroke_mm, "error_mm": round(s.error_mm, 12),
                                  "error_ratio": round(s.error_mm / s.stroke_mm, 12),
                                  "input_from_deg": round(math.degrees(s.input_from), 6),
                                  "input_to_deg": round(math.degrees(s.input_to), 6),
                                  "start_mm": [round(v, 9) for v in s.start], "end_mm": [round(v, 9) for v in s.end]}
        if angle is not None:
            t = np.array([math.radians(angle)])
            pose = fb.positions(t, mech.assembly)
            report["positions"] = {mech.assembly: _fourbar_position(fb, pose, spec.rpm * 2 * math.pi / 60)}
    else:
        report.update(_slider_report(spec, mech, angle))
    return report
