"""A grooved cam as files: its cut drawing (the groove on its own layer), its printed solid, report and plots.

Names as for every cam (:mod:`camgen.outputs`): ``<name>.dxf`` and ``<name>-cut.svg`` (the plate on
``OUTLINE``, holes on ``HOLES``, both flanks on ``GROOVE``), ``<name>.stl`` and ``<name>.3mf`` (the plate
with the groove as a pocket), ``<name>.json``, ``<name>-svaj.png|svg`` and ``<name>-cam.png|svg`` (the
plate, the groove, the pitch curve, the roller and where each flank's check peaks), ``<name>.html`` (the page).
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.bundle import Bundle
from camgen.core.figures import PREVIEW_TOLERANCE_MM, figure
from camgen.core.solids import volume_check
from camgen.groove import Flank
from camgen.kinds.grooved.design import GroovedDesign, step_plate
from camgen.outputs import cam_files, printed_mesh
from camgen.kinds.grooved.page import grooved_page
from camgen.report import cam_report


def _flank(flank: Flank, outline: Any) -> dict[str, Any]:
    finite = math.isfinite(flank.pitch_rho_min_mm)
    return {"pitch_rho_min_mm": round(flank.pitch_rho_min_mm, 9) if finite else None,
            "at_deg": None if flank.at_deg is None else round(flank.at_deg, 9),
            "flank_rho_min_mm": round(flank.rho_min_mm, 9) if finite else None,
            "undercut": flank.undercut, "envelope": outline.envelope,
            "vertices": len(outline.contour.vertices), "arcs": outline.contour.n_arcs,
            "max_error_mm": float(outline.max_error_mm)}


def groove_summary(report: dict[str, Any]) -> str:
    """One line of a grooved cam's report: the groove and each flank's smallest radius of curvature."""
    flanks = report["flanks"]

    def radius(side: str) -> str:
        f = flanks[side]
        if f["flank_rho_min_mm"] is None:
            return f"none on the {side} flank (the pitch curve is nowhere {'convex' if side == 'inner' else 'concave'})"
        return f"{side} flank {f['flank_rho_min_mm']:.3f} mm at {f['at_deg']:.2f} deg"

    cam = report["cam"]
    return (f"groove: {cam['groove_width_mm']:g} mm wide, {cam['groove_depth_mm']:g} mm deep; smallest convex radius "
            f"of the {radius('inner')}, {radius('outer')}")


def grooved_report(design: GroovedDesign, mesh: Any = None, volume: dict | None = None) -> dict[str, Any]:
    """The report of a grooved cam: every figure of a disc cam's (its profile being the inner flank), the plate,
    and the checks of both flanks (``flanks``: the pitch curve's smallest convex radius for the inner flank and
    concave radius for the outer, where, the flank's own radius there, undercut)."""
    t, profile = design.spec, design.profile
    report = cam_report(profile, mesh)
    d, kerf = design.offset_mm, t.output.kerf
    report["cam"].update({"kind": "grooved", "base_radius_mm": design.base_radius_mm,
                          "groove_depth_mm": t.cam.groove_depth, "running_clearance_mm": t.cam.running_clearance,
                          "groove_width_mm": round(2 * d, 12), "rim_mm": t.cam.rim,
                          "plate_diameter_mm": round(2 * design.plate_radius_mm, 9)})
    report["follower"]["roller_radius_mm"] = t.follower.roller_radius
    inner, outer = profile.cut_outline.contour, design.cut_outer.contour
    report.update({
        "flanks": {"offset_mm": round(d, 12),
                   "inner": _flank(design.inner, profile.cut_outline), "outer": _flank(design.outer, design.cut_outer)},
        "undercut": design.inner.undercut or design.outer.undercut,
        "envelope": profile.outline.envelope or design.outer_outline.envelope,
        "outline_vertices": len(inner.vertices) + len(outer.vertices),
        "outline_arcs": inner.n_arcs + outer.n_arcs, "outline_lines": inner.n_lines + outer.n_lines,
        "outline_max_error_mm": float(design.written_error_mm),
        "outline_note": "the GROOVE layer's two flanks as written" + (
            f", each measured against its exact flank moved into the groove by half the kerf ({kerf / 2:g} mm)"
            if kerf else ""),
        "area_mm2": round(design.part.area, 6),
        "groove_area_mm2": round(design.part.pockets[0].area, 6),
        "warnings": list(design.warnings),
    })
    if mesh is not None and volume is not None:
        report["mesh"].update(volume)
    return report


def grooved_figure(design: GroovedDesign) -> Any:
    """The cam at theta = 0: the plate, the groove between its flanks, the pitch curve, the roller, and where each
    flank's radius is smallest and the pressure angle largest."""
    cam, t, a = design.cam, design.spec, design.analysis
    fig = figure(8, 9)
    ax = fig.add_subplot()
    circle = np.linspace(0, 2 * math.pi, 721)
    r = design.plate_radius_mm
    ax.fill(r * np.cos(circle), r * np.sin(circle), color="0.88", zorder=0)
    ax.plot(r * np.cos(circle), r * np.sin(circle), color="k", lw=1.2, label="plate")
    outer = design.outer_outline.contour.flatten(PREVIEW_TOLERANCE_MM)
    inner = design.outline.contour.flatten(PREVIEW_TOLERANCE_MM)
    ax.fill(outer[:, 0], outer[:, 1], color="#f3c6f3", zorder=1, label=f"groove, {t.cam.groove_depth:g} mm deep")
    ax.fill(inner[:, 0], inner[:, 1], color="0.88", zorder=1)
    for ring, colour, label in ((outer, "C4", "outer flank"), (inner, "C0", "inner flank")):
        ax.plot(*np.vstack([ring, ring[:1]]).T, color=colour, lw=1.0, label=label, zorder=2)
    pitch = cam.pitch(np.linspace(0, 2 * math.pi, 721)).point
    ax.plot(pitch[:, 0], pitch[:, 1], "--", color="0.3", lw=0.7, label="pitch curve", zorder=2)
    for hole in design.part.holes:
        ring = hole.flatten(PREVIEW_TOLERANCE_MM)
        ax.fill(ring[:, 0], ring[:, 1], color="white", ec="k", lw=0.8, zorder=2)
    centre = cam.pitch(np.array([0.0])).point[0]
    rr = t.follower.roller_radius
    ax.plot(centre[0] + rr * np.cos(circle), centre[1] + rr * np.sin(circle), color="C2", lw=1.5,
            label="roller at θ = 0", zorder=3)
    for flank, sign, marker, colour in ((design.inner, -1, "s", "C1"), (design.outer, 1, "D", "C5")):
        if flank.at_deg is None:
            continue
        g = cam.pitch(np.radians([flank.at_deg]))
        spot = g.point[0] + sign * design.offset_mm * g.normal[0]
        ax.plot(*spot, marker, color=colour, zorder=4, label=f"{flank.side} flank: min radius {flank.rho_min_mm:.2f} "
                f"mm (pitch {flank.pitch_rho_min_mm:.2f}) at θ = {flank.at_deg:.1f}°")
    pa = cam.pitch(np.radians([a.pressure_angle_max_at_deg])).point[0]
    ax.plot(*pa, "o", color="C3", zorder=4, label=f"max pressure angle {a.pressure_angle_max_deg:.1f}° at "
                                                   f"θ = {a.pressure_angle_max_at_deg:.1f}°")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.grid(alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2, fontsize=8)
    ax.set_title(f"{t.name}: grooved cam at θ = 0 ({t.cam.rotation}), {t.follower.type} follower")
    return fig


def grooved_bundle(design: GroovedDesign) -> tuple[Bundle, dict[str, Any]]:
    """The files of a grooved cam and its report (without the ``files`` map, which the bundle adds)."""
    mesh, mesh_check = printed_mesh(design.spec, design.printed)
    volume = volume_check([design.printed], mesh_check.volume_mm3) if mesh_check is not None else None
    report = grooved_report(design, mesh_check, volume)
    speed = design.profile.speed
    forces, speeds = (None, None) if speed is None else (speed.forces, speed.speeds)

    def plot(kind: str) -> Any:
        from camgen import plots
        from camgen.kinds.grooved.plots import grooved_checks_figure

        if kind == "svaj":
            return plots.svaj_figure(design.profile)
        if kind == "checks":
            return grooved_checks_figure(design)
        if kind == "speeds" and speeds is not None:
            return plots.speeds_plot(design.spec.name, speeds)
        return grooved_figure(design)

    checks = (("checks",) if forces else ()) + (("speeds",) if speeds else ())
    return cam_files(design.spec, design.cut, mesh, plot, report, lambda: grooved_page(design, report),
                     ("svaj", "cam", *checks),
                     printed=step_plate(design) if "step" in design.spec.output.formats else None), report
