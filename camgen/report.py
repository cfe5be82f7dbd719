"""The report of a cam design: every figure a designer checks before cutting, in mm and degrees.

Pure formatting of a finished :class:`~camgen.flat.FlatCamDesign` (and the check of its
solid, when one was made): nothing here computes a peak or reads a spec.
"""
from __future__ import annotations

import math
from typing import Any

from camgen.core import VERSION as __version__
from camgen.core.solids import MeshCheck
from camgen.flat import FlatCamDesign
from camgen.tables.followers import Face


def _r(x: float | None, digits: int = 9) -> float | None:
    """``x`` rounded for the report; None where there is no value or it is unbounded (an infinite radius)."""
    return None if x is None or not math.isfinite(x) else round(float(x), digits)


def _fit(spec: Any, seg: Any) -> dict[str, Any]:
    """A table law's fit: its rows, continuity, knots and largest residual (in the lift's unit) and where."""
    law = seg.law
    if not hasattr(law, "residual"):
        return {}
    u = law.residual_at
    at = seg.start + seg.beta * (1.0 - u if seg.kind == "return" else u)
    return {"fit": {"file": spec.file, "rows": len(law.samples), "continuity": f"C{law.continuity}",
                    "knots": len(law.knots), "residual_max": _r(law.residual * spec.lift),
                    "residual_max_at_deg": _r(math.degrees(at)), "fit_tolerance": law.tolerance * spec.lift}}


def cam_report(design: FlatCamDesign, mesh: MeshCheck | None = None) -> dict[str, Any]:
    """The report as a JSON-ready dict (keys carry their units)."""
    t, cam, a, outline = design.spec, design.cam, design.analysis, design.outline
    segments = [{
        "index": i, "type": spec.type, "law": spec.law, **{k: v for k, v in spec.law_params().items() if k != "data"},
        "start_deg": _r(math.degrees(seg.start)), "angle_deg": spec.angle, "lift_mm": spec.lift, **_fit(spec, seg),
    } for i, (spec, seg) in enumerate(zip(t.motion, cam.program.segments, strict=True))]
    report: dict[str, Any] = {
        "name": t.name,
        "generator": f"camgen {__version__}",
        "conventions": {
            "units": "mm and degrees; derivatives of s per radian of cam angle",
            "theta_zero": "follower on +Y at theta = 0; theta grows in the cam's sense of rotation",
            "rotation": t.cam.rotation,
            "offset": "positive offset puts the follower axis at +X (right of the cam centre, follower on top)",
            "pressure_angle": "angle between the contact normal and the follower's direction of travel at the "
                              "contact; for a translating roller atan((s' - sense * offset) / (d0 + s)), sense +1 "
                              "for ccw",
        },
        "cam": {"base_radius_mm": cam.base_radius, "prime_radius_mm": cam.base_radius + cam.contact_radius,
                "thickness_mm": t.cam.thickness, "bore_mm": t.cam.bore, "rotation": t.cam.rotation},
        "follower": {"type": t.follower.type, "roller_radius_mm": t.follower.roller_radius,
                     "offset_mm": t.follower.offset, "pivot_distance_mm": t.follower.pivot_distance,
                     "arm_length_mm": t.follower.arm_length},
        "segments": segments,
        f"lift_max_{'deg' if cam.follower.lift_unit == 'deg' else 'mm'}": _r(cam.program.max_lift),
        "pressure_angle_max_deg": _r(a.pressure_angle_max_deg),
        "pressure_angle_max_at_deg": _r(a.pressure_angle_max_at_deg),
        "pressure_angle_limit_deg": design.pressure_limit_deg,
        "pitch_rho_min_mm": _r(a.pitch_rho_min_mm),
        "pitch_rho_min_at_deg": _r(a.pitch_rho_min_at_deg),
        "profile_rho_min_mm": _r(a.profile_rho_min_mm),
        "pitch_concave_rho_min_mm": _r(a.pitch_concave_rho_min_mm),
        "profile_concave_rho_min_mm": _r(a.profile_concave_rho_min_mm),
        "concave_rho_min_at_deg": _r(a.concave_at_deg),
        "undercut": a.undercut,
        "envelope": outline.envelope,
        "outline_vertices": len(design.cut_outline.contour.vertices),
        "outline_arcs": design.cut_outline.contour.n_arcs,
        "outline_lines": design.cut_outline.contour.n_lines,
        "outline_max_error_mm": float(design.written_error_mm),
        "outline_note": "the DXF's outline as written" + (
            f", measured against the cam surface moved out by half the kerf ({t.output.kerf / 2:g} mm)"
            if t.output.kerf else ""),
        "tolerance_mm": design.tolerance,
        "kerf_mm": t.output.kerf,
        "clearance_mm": t.output.clearance,
        "bore_cut_mm": t.cam.bore - t.output.kerf if t.cam.bore else None,
        "bore_printed_mm": t.cam.bore + t.output.clearance if t.cam.bore else None,
        "area_mm2": _r(design.part.area, 6),
        "wall_mm": _r(design.wall_mm, 6) if t.cam.bore > 0 else None,
        "continuity": [j.as_dict() for j in design.jumps],
        "warnings": list(design.warnings),
    }
    f = cam.follower
    if design.face_extent is not None and isinstance(t.follower, Face):
        lo, hi = design.face_extent
        report["face_position_min_mm"], report["face_position_max_mm"] = _r(lo), _r(hi)
        report["face_width_mm"] = _r(hi - lo + 2 * t.follower.face_margin)
        report["face_measured_from"] = f.face_origin
    if design.face_leaves is not None:          # a flat face's folds cut off (cam.allow_undercut)
        report["face_leaves_cam"] = [leaves.as_dict() for leaves in design.face_leaves]
    report["follower"].update({key: [_r(x) for x in value] if isinstance(value, list) else _r(value)
                               for key, value in f.report_fields().items()})
    if design.speed is not None:
        report["speed"] = design.speed.as_report()
    if design.sizing is not None:
        s = design.sizing
        report["sizing"] = {"base_radius_mm": _r(s.base_radius_mm), "decided_by": s.decided_by,
                            "pressure_radius_mm": _r(s.pressure_radius_mm),
                            "curvature_radius_mm": _r(s.curvature_radius_mm),
                            "max_pressure_angle_deg": s.max_pressure_angle_deg,
                            "min_rho_margin_mm": s.min_rho_margin_mm}
    if mesh is not None:
        report["mesh"] = {"watertight": mesh.watertight, "winding_consistent": mesh.winding_consistent,
                          "volume_mm3": _r(mesh.volume_mm3, 6), "triangles": mesh.triangles,
                          "bodies": mesh.bodies}
    return report


def checks_line(design: Any) -> str:
    """The console's first line of a cam cut to a profile: the peak pressure angle and the smallest convex radius
    (deg, mm). A flat face has no pitch curve apart from its profile, so only the cam's radius is given; a
    translating flat face is pushed square to its face, so its pressure angle is said to be 0 by definition rather
    than printed as a peak."""
    a, name = design.analysis, design.spec.name
    flat = design.cam.follower.flat
    where = f"at {a.pitch_rho_min_at_deg:.2f} deg"
    radius = (f"min convex radius {a.profile_rho_min_mm:.3f} mm (cam) {where}" if flat else
              f"min convex radius {a.profile_rho_min_mm:.3f} mm (cam), {a.pitch_rho_min_mm:.3f} mm (pitch) {where}")
    if flat and not design.spec.follower.oscillating:
        return f"{name}: pressure angle 0 by definition (the flat face is pushed square to its face); {radius}"
    return (f"{name}: pressure angle max {a.pressure_angle_max_deg:.2f} deg at {a.pressure_angle_max_at_deg:.2f} deg; "
            f"{radius}")


def cam_summary(design: Any, report: dict[str, Any]) -> list[str]:
    """The lines ``camgen build`` prints of a cam cut to a profile (a disc, a plate, a grooved cam's inner flank)
    whose report is ``report``: its checks (:func:`checks_line`), its outline, and :func:`design_lines`."""
    return [checks_line(design),
            f"outline: {report['outline_vertices']} vertices ({report['outline_arcs']} exact arcs), max error "
            f"{report['outline_max_error_mm']:.2e} mm (tolerance {report['tolerance_mm']:g} mm)",
            *design_lines(report)]


def design_lines(report: dict[str, Any]) -> list[str]:
    """The figures a designer decides on, as lines for the console: a base radius sized by ``auto``, each table
    law's fit and, at a speed, the peak rates, the contact check with its lift-off speed, the camshaft torque and
    power, the contact pressure."""
    lines, lift = [], "deg" if "lift_max_deg" in report else "mm"
    for seg in report.get("segments", []):
        if "fit" in seg:
            f = seg["fit"]
            lines.append(f"motion[{seg['index']}]: {f['rows']} rows fitted by a {f['continuity']} spline of "
                         f"{f['knots']} knots, within {f['residual_max']:.3g} {lift} "
                         f"(largest at {f['residual_max_at_deg']:.4g} deg)")
    if "sizing" in report:
        s = report["sizing"]
        lines.append(f"base radius {s['base_radius_mm']:.4g} mm (auto, decided by the {s['decided_by']})")
    speed = report.get("speed")
    if not speed:
        return lines
    unit = "deg" if "velocity_max_deg_s" in speed else "mm"
    v, a = speed[f"velocity_max_{unit}_s"], speed[f"acceleration_max_{unit}_s2"]
    j = speed[f"jerk_max_{unit}_s3"]
    rates = (f"velocity max {v:.4g} deg/s, acceleration {a:.4g} deg/s^2, jerk {j:.4g} deg/s^3" if unit == "deg"
             else f"velocity max {v / 1000:.4g} m/s, acceleration {a / 1000:.4g} m/s^2, jerk {j / 1000:.4g} m/s^3")
    lines.append(f"at {speed['rpm']:g} rpm: {rates}")
    contact = speed.get("contact")
    if contact and contact.get("mode") == "gravity" and "force_min_n" not in contact:
        off = contact["liftoff_rpm"]
        lines.append("contact: gravity holds the follower at any speed" if off is None else
                     f"contact: gravity holds the follower up to {off:.4g} rpm")
    elif contact and contact.get("mode"):
        off = contact["liftoff_rpm"]
        lines.append(f"contact: least force {contact['force_min_n']:.4g} N at {contact['force_min_at_deg']:.4g} deg; "
                     + ("held at any speed" if off is None else f"lets go above {off:.4g} rpm")
                     + f"; preload for a {contact['margin_n']:g} N margin {contact['preload_needed_n']:.4g} N")
    forces = speed.get("forces")
    if forces:
        lines.append(f"camshaft torque {forces['torque_min_N_m']:.4g} to {forces['torque_max_N_m']:.4g} N*m (RMS "
                     f"{forces['torque_rms_N_m']:.4g}), peak power {forces['power_max_W']:.4g} W, contact force "
                     f"max {forces['contact_force_max_N']:.4g} N")
        if "side_changes" in forces:
            sides, changes = forces["carried_by"], forces["side_changes"]
            lines.append(f"positive drive: {sides['force_positive']} carries the force where it presses the "
                         f"follower against its rise, {sides['force_negative']} where it pulls; "
                         + ("the contact changes side at " + ", ".join(f"{c['at_deg']:.4g}" for c in changes) + " deg"
                            if changes else "the contact never changes side"))
        stress = forces.get("stress", {})
        if "pressure_max_MPa" in stress:
            on = f", {stress['on']}" if "on" in stress else ""
            lines.append(f"contact pressure max {stress['pressure_max_MPa']:.4g} MPa at "
                         f"{stress['pressure_max_at_deg']:.4g} deg{on} ({stress['cam_material']} cam, "
                         f"{stress['follower_material']} follower; allowable {stress['allowable_MPa']:g} MPa)")
    if "speeds" in speed:
        lines.append(speeds_line(speed["speeds"]))
    return lines


def speeds_line(speeds: dict[str, Any]) -> str:
    """The console's line of the ``speeds`` table: its range, the largest torque and pressure over it, where the
    contact is lost (the first speed that loses it, and the lift-off speed) and where the pressure passes its
    allowable."""
    rows = speeds["rows"]
    top = max(rows, key=lambda r: max(abs(r["torque_max_N_m"]), abs(r["torque_min_N_m"])))
    peak = max(abs(top["torque_max_N_m"]), abs(top["torque_min_N_m"]))
    text = (f"over {rows[0]['rpm']:g} to {rows[-1]['rpm']:g} rpm ({len(rows)} speeds): torque up to {peak:.4g} N*m "
            f"(at {top['rpm']:.4g} rpm), peak power up to {max(r['power_max_W'] for r in rows):.4g} W")
    if "holds" in rows[0]:
        lost = [r["rpm"] for r in rows if not r["holds"]]
        off = speeds.get("liftoff_rpm")
        text += ("; contact held at every speed" if not lost else f"; contact lost from {lost[0]:.4g} rpm") + (
            "" if off is None else f" (lift-off {off:.4g} rpm)")
    if "pressure_max_MPa" in rows[0]:
        over = [r["rpm"] for r in rows if r["pressure_max_MPa"] > speeds["allowable_MPa"]]
        text += (f"; contact pressure up to {max(r['pressure_max_MPa'] for r in rows):.4g} MPa"
                 + (f", over the allowable {speeds['allowable_MPa']:g} MPa from {over[0]:.4g} rpm" if over else
                    f", within the allowable {speeds['allowable_MPa']:g} MPa"))
    return text
