"""A machine's report (its ``<name>.json``, in mm, degrees, N and N*m) and the lines ``camgen build`` prints.

Angles of the timing diagram are the main shaft's, in degrees from the machine's start; a dwell is a run of shaft
angles where an output's rate is at most 1e-9 of its range per radian (to the sampling's step, 360 /
``machine.samples`` degrees), an overlap a run where two outputs both move.
"""
from __future__ import annotations

import math
from itertools import combinations
from typing import Any

import numpy as np

from camgen.kinds.machine import kinematics
from camgen.kinds.machine.design import MachineDesign, Output, _cam_of
from camgen.kinds.machine.indexed_cam import indexed_cam
from camgen.kinds.machine.keeptime import timing_report
from camgen.kinds.machine.machine_gears import report_entries
from camgen.kinds.machine.poses import poses_report
from camgen.kinds.machine.ratchet_mount import report_entry as ratchet_entry
from camgen.speed import HeldContact, Speed
from camgen.tables.followers import Driven


def _num(value: float, digits: int = 9) -> float:
    """A float for the report, rounded to ``digits`` decimals."""
    return round(float(value), digits)


def _runs(runs: list[tuple[float, float]]) -> list[list[float]]:
    return [[_num(a, 6), _num(b, 6)] for a, b in runs]


def _profile(design: Any) -> Any:
    """The design holding a cam's analysis: itself, or its profile (a grooved cam's island)."""
    return design if hasattr(design, "analysis") else design.profile


def timing(design: MachineDesign) -> dict[str, Any]:
    """The timing diagram's figures: each output's range, dwells and moving runs, and each pair's overlaps (a
    follower and the linkage it drives left out: they move together by construction)."""
    outputs = design.outputs
    rows = [{"output": o.label, "unit": o.unit, "min": _num(o.values.min()), "max": _num(o.values.max()),
             "dwells_deg": _runs(kinematics.intervals(o.still)), "moving_deg": _runs(kinematics.intervals(~o.still))}
            for o in outputs]
    overlaps = [{"outputs": [a.label, b.label], "deg": _runs(kinematics.overlap(~a.still, ~b.still))}
                for a, b in combinations(outputs, 2) if not design.together(a.label, b.label)]
    return {"samples": len(design.phi), "step_deg": 360.0 / len(design.phi), "outputs": rows,
            "overlaps": [o for o in overlaps if o["deg"]]}


def _cam_entry(design: MachineDesign, index: int) -> dict[str, Any]:
    cam, mount = design.cams[index], design.spec.cams[index]
    profile = _profile(cam.design)
    speed = getattr(profile, "speed", None) or getattr(cam.design, "speed", None)
    contact = speed.contact if isinstance(speed, Speed) else None
    out = {"shaft": mount.shaft, "layer": mount.layer, "phase_deg": mount.phase, "kind": cam.design.spec.kind,
           "turns_per_main_turn": cam.turns, "rpm": cam.design.spec.cam.rpm,
           "follower": cam.design.spec.follower.type, "unit": cam.unit,
           "follower_min": _num(cam.follower[0].min()), "follower_max": _num(cam.follower[0].max()),
           "pressure_angle_max_deg": _num(profile.analysis.pressure_angle_max_deg, 6),
           "base_radius_mm": _num(_cam_of(cam.design).base_radius, 6), "files_prefix": cam.design.spec.name}
    if contact:
        out["contact"] = {k: v for k, v in contact.as_report().items() if not isinstance(v, list)}
    real = indexed_cam(cam, _cam_of(cam.design), design.omega, design.phi)
    if real is not None:
        out["indexed"] = real.as_report()
    return out


def _spring_entry(design: MachineDesign, m: Any) -> dict[str, Any] | None:
    """How the follower driving ``m`` stays on its cam with the linkage attached: a positive drive needs no spring;
    with the linkage's ``[dynamics]`` the least contact force (N), where (cam and main shaft degrees) and the preload
    (N) or rate (N/mm) that would keep it at the cam's margin; None otherwise (the cam's own ``contact`` says it)."""
    cam = design.cam(m.cam)
    if isinstance(cam.design.spec.follower, Driven):
        return {"positive_drive": True, "note": f"cams.{m.cam} drives its follower both ways (a positive drive): "
                                               "no spring to size, whatever the linkage's load"}
    speed = getattr(_profile(cam.design), "speed", None)
    contact = speed.contact if isinstance(speed, Speed) else None
    if m.effort is None or not isinstance(contact, HeldContact):
        return None
    shaft = (contact.force_min_at_deg + cam.phase_deg) / abs(cam.turns) % 360.0
    return {"positive_drive": False, "least_contact_force_n": _num(contact.force_min, 6),
            "at_cam_deg": _num(contact.force_min_at_deg, 6), "at_shaft_deg": _num(shaft, 6),
            "margin_n": contact.margin, "holds": contact.holds, "spring_rate_n_mm": contact.spring_rate,
            "preload_n": contact.preload, "preload_needed_n": _num(contact.preload_needed, 6),
            "rate_needed_n_mm": None if contact.rate_needed is None else _num(contact.rate_needed, 6)}


def _linkage_entry(design: MachineDesign, m: Any) -> dict[str, Any]:
    omega = design.omega
    gamma = np.degrees(m.gamma)
    extra: dict[str, Any] = {}
    if m.effort is not None:
        extra["inertia_torque_n_m"] = [_num(m.effort.min(), 6), _num(m.effort.max(), 6)]
    if (spring := _spring_entry(design, m)) is not None:
        extra["spring"] = spring
    return {"cam": m.cam, "rest_deg": m.coupling.rest, "output_torque_n_m": m.coupling.output_torque,
            "crank_deg": [_num(np.degrees(m.chain.theta2.min())), _num(np.degrees(m.chain.theta2.max()))],
            "rocker_deg": [_num(np.degrees(m.theta4.min())), _num(np.degrees(m.theta4.max()))],
            "rocker_omega_max_rad_s": _num(np.abs(m.rocker_rate).max() * omega),
            "rocker_alpha_max_rad_s2": _num(np.abs(m.rocker_acc).max() * omega ** 2),
            "transmission_deg": [_num(gamma.min(), 6), _num(gamma.max(), 6)],
            "tracer_mm": {"x": [_num(m.point[:, 0].min(), 6), _num(m.point[:, 0].max(), 6)],
                          "y": [_num(m.point[:, 1].min(), 6), _num(m.point[:, 1].max(), 6)],
                          "speed_max_mm_s": _num(np.hypot(*m.point_rate.T).max() * omega, 6)},
            "reflected_force_n": [_num(m.force.min(), 6), _num(m.force.max(), 6)],
            "shaft_torque_n_m": [_num(m.torque.min(), 6), _num(m.torque.max(), 6)],
            "files_prefix": m.design.spec.name, **extra}


def _cranked_entry(design: MachineDesign, m: Any) -> dict[str, Any]:
    """A shaft-driven linkage: its shaft, phase and planes, and its tracers' extents and speeds over the turn."""
    omega = design.omega
    tracers = {p: {"x_mm": [_num(m.points[p][:, 0].min(), 6), _num(m.points[p][:, 0].max(), 6)],
                   "y_mm": [_num(m.points[p][:, 1].min(), 6), _num(m.points[p][:, 1].max(), 6)],
                   "speed_max_mm_s": _num(np.hypot(*m.rates[p].T).max() * omega, 6)} for p in m.tracers}
    return {"shaft": m.shaft, "phase_deg": m.phase_deg, "layer": m.layer, "side": "front" if m.side > 0 else "back",
            "turns_per_main_turn": m.turns, "offset_mm": [_num(v) for v in m.offset], "tracers": tracers,
            "files_prefix": m.design.spec.name,
            **({} if m.torque is None else {"shaft_torque_n_m": [_num(m.torque.min(), 6), _num(m.torque.max(), 6)]})}


def slid_entry(design: MachineDesign, m: Any) -> dict[str, Any]:
    """A linkage a follower drives (a stem as its slider, an arm as its crank): its input's travel, its output's turn
    and its largest angular acceleration, its tracers (with their largest speed and acceleration), the reflected force
    and the shaft torque over the turn; with ``[dynamics]`` the inverse dynamics' effort on its input and how the
    follower's spring holds it on its cam."""
    omega = design.omega
    tracers = {p: {"x_mm": [_num(m.points[p][:, 0].min(), 6), _num(m.points[p][:, 0].max(), 6)],
                   "y_mm": [_num(m.points[p][:, 1].min(), 6), _num(m.points[p][:, 1].max(), 6)],
                   "speed_max_mm_s": _num(np.hypot(*m.rates[p].T).max() * omega, 6),
                   "acceleration_max_mm_s2": _num(np.hypot(*m.accelerations[p].T).max() * omega ** 2, 6)}
               for p in m.tracers}
    extra: dict[str, Any] = {}
    if m.coupling.output is not None and m.output_acc is not None:
        extra["output_alpha_max_rad_s2"] = _num(np.abs(m.output_acc).max() * omega ** 2, 6)
    if m.effort is not None:
        unit = "n_m" if m.analysis.crank else "n"
        extra[f"inertia_effort_{unit}"] = [_num(m.effort.min(), 6), _num(m.effort.max(), 6)]
    if (spring := _spring_entry(design, m)) is not None:
        extra["spring"] = spring
    return {"cam": m.cam, "slider": m.coupling.link, "rest_mm": m.coupling.rest,
            "travel_mm": [_num(m.inputs.min(), 6), _num(m.inputs.max(), 6)], "output": m.coupling.output,
            "output_torque_n_m": m.coupling.output_torque,
            "output_deg": [_num(np.degrees(m.output_angle.min()), 6), _num(np.degrees(m.output_angle.max()), 6)],
            "offset_mm": [_num(v) for v in m.offset], "tracers": tracers,
            "reflected_force_n": [_num(m.force.min(), 6), _num(m.force.max(), 6)],
            "shaft_torque_n_m": [_num(m.torque.min(), 6), _num(m.torque.max(), 6)],
            "files_prefix": m.design.spec.name, **extra}


def machine_report(design: MachineDesign) -> dict[str, Any]:
    """The report of ``design`` without its ``files`` map (which the bundle adds)."""
    spec = design.spec
    torque = design.shaft_torque
    return {
        "name": spec.name, "kind": "machine",
        "conventions": "main shaft angles in degrees from the machine's start; a follower's swing in degrees (away "
                       "from its cam), a lift in mm; four-bar angles counter-clockwise from its ground line; torques "
                       "in N*m, counter-clockwise positive; per-second rates at machine.rpm",
        "machine": {"main": spec.machine.main, "rpm": spec.machine.rpm, "omega_rad_s": _num(design.omega),
                    "samples": spec.machine.samples},
        "shafts": [{"name": s.name, "at_mm": list(s.at), "turns_per_main_turn": spec.turns.get(s.name)}
                   for s in spec.shafts],
        "gears": report_entries(design),
        "cams": {c.name: _cam_entry(design, i) for i, c in enumerate(design.cams)},
        "linkages": {m.name: _linkage_entry(design, m) for m in design.linkages},
        **({"cranked": {m.name: _cranked_entry(design, m) for m in design.cranked}} if design.cranked else {}),
        **({"slid": {m.name: slid_entry(design, m) for m in design.slid}} if design.slid else {}),
        **({"genevas": {g.name: _geneva_entry(design, g) for g in design.indexed}} if design.indexed else {}),
        **({"ratchets": {r.name: ratchet_entry(r, design.phi) for r in design.ratchets}} if design.ratchets else {}),
        "timing": timing(design),
        "poses": poses_report(design),
        "shaft_torque_n_m": {"min": _num(torque.min(), 6), "max": _num(torque.max(), 6),
                             "mean": _num(torque.mean(), 9),
                             "note": _torque_note(design)},
        "clashes": [{"parts": [c.a, c.b], "first_deg": c.angle_deg} for c in design.clashes],
        "clash_check": {"samples": spec.machine.clash_samples, "refined_deg": 0.1, "mode": spec.machine.clash,
                        "not_checked": list(design.unchecked)},
        "warnings": list(design.warnings),
        **({"keep_time": timed} if (timed := timing_report(design)) else {}),
    }


def _geneva_entry(design: MachineDesign, g: Any) -> dict[str, Any]:
    """A Geneva drive's entry: its shafts, slots, centre distance (mm), driver turns per main turn, the pin's angle
    at the start (degrees) and the main shaft's runs (degrees) over which the wheel indexes."""
    return {"driver": g.driver, "wheel": g.wheel, "slots": g.law.slots, "centre_distance_mm": g.law.centre_distance,
            "driver_turns_per_main_turn": g.driver_turns, "start_deg": _num(math.degrees(g.start), 9),
            "indexing_deg": _runs(kinematics.intervals(g.indexing(design.phi))), "files_prefix": g.design.spec.name}


def _torque_note(design: MachineDesign) -> str:
    """What the report's main shaft torque counts."""
    dynamic = any(m.effort is not None for m in design.linkages) or any(m.effort is not None for m in design.slid) \
        or any(m.torque is not None for m in design.cranked)
    return ("the main shaft's torque against the linkages' output torques"
            + (" and their own inertia, weight, springs and loads ([dynamics])" if dynamic else "")
            + (" and the ratchets' load torques" if design.ratchets else "")
            + " (virtual work: their power over the shaft's speed); each cam's own follower forces are in its own "
            "report")


def timing_rows(design: MachineDesign) -> list[dict[str, Any]]:
    """The timing diagram as CSV rows: the main shaft's angle (degrees), then each output's value and its
    normalised value (0 to 1 over its range)."""
    outputs: tuple[Output, ...] = design.outputs
    columns = {"shaft_deg": np.degrees(design.phi)}
    for o in outputs:
        columns[f"{o.label}_{o.unit}"] = o.values
        columns[f"{o.label}_normalised"] = kinematics.normalised(o.values)
    return [{k: _num(v[j]) for k, v in columns.items()} for j in range(len(design.phi))]


def summary(design: MachineDesign, report: dict[str, Any]) -> list[str]:
    """What ``camgen build`` prints of ``design``, whose written report is ``report`` (:func:`summary_lines`)."""
    return summary_lines(report)


def summary_lines(report: dict[str, Any]) -> list[str]:
    """What ``camgen build`` prints of a machine's report."""
    linkages = len(report["linkages"]) + len(report.get("cranked", {}))
    lines = [f"{report['name']}: a machine of {len(report['cams'])} cam(s) and {linkages} "
             f"linkage(s) at {report['machine']['rpm']:g} rpm"]
    for name, cam in report["cams"].items():
        held = cam.get("contact", {}).get("holds")
        lines.append(f"  cams.{name}: {cam['kind']} on {cam['shaft']} (layer {cam['layer']}, phase "
                     f"{cam['phase_deg']:g} deg), follower {cam['follower_min']:.4g} to {cam['follower_max']:.4g} "
                     f"{cam['unit']}, pressure angle <= {cam['pressure_angle_max_deg']:.2f} deg"
                     + ("" if held is None else f", contact {'holds' if held else 'LOST'}"))
    for name, m in report["linkages"].items():
        lines.append(f"  linkages.{name}: driven by cams.{m['cam']}, rocker {m['rocker_deg'][0]:.2f} to "
                     f"{m['rocker_deg'][1]:.2f} deg, transmission {m['transmission_deg'][0]:.1f} to "
                     f"{m['transmission_deg'][1]:.1f} deg")
    for name, m in report.get("cranked", {}).items():
        feet = ", ".join(f"{p} {t['x_mm'][1] - t['x_mm'][0]:.4g} x {t['y_mm'][1] - t['y_mm'][0]:.4g} mm"
                         for p, t in m["tracers"].items())
        lines.append(f"  linkages.{name}: turned by shaft {m['shaft']} ({m['turns_per_main_turn']:g} turns a main "
                     f"turn, phase {m['phase_deg']:g} deg, {m['side']})" + (f", tracing {feet}" if feet else ""))
    for where, timed in report.get("keep_time", {}).items():
        worst = timed.get("worst_from_path_point_mm", timed.get("at_points_max_deg"))
        lines.append(f"  {where} keeps time: cams.{timed['cam']} drives linkages.{timed['linkage']} through "
                     f"{len(timed.get('targets', ())) or timed.get('points')} point(s), each within {worst:.2g} "
                     f"{'mm' if 'targets' in timed else 'deg'} of its time")
    for name, r in report.get("ratchets", {}).items():
        lines.append(f"  ratchets.{name}: indexed by cams.{r['cam']}'s arm ({r['swing_deg']:.4g} deg a stroke), "
                     f"{r['teeth']} teeth, {r['teeth_per_turn']:g} tooth(teeth) a turn")
    t = report["shaft_torque_n_m"]
    if t["min"] or t["max"]:
        lines.append(f"  main shaft torque against the linkages' loads: {t['min']:.4g} to {t['max']:.4g} N*m")
    return lines

