"""A conjugate pair as files: each cam's cut drawing and printed solid, one report with both cams' checks, the
follower's motion and the pair assembled.

Names: ``<name>-1.dxf``, ``<name>-2.dxf`` and their ``-cut.svg`` (each cam on ``OUTLINE``, the common bore and
keyway on ``HOLES``, its name, the sense of rotation and the theta = 0 tick on ``ENGRAVE``; kerf applied),
``<name>-1.stl|3mf`` and ``<name>-2.stl|3mf`` (clearance applied), ``<name>.json``, ``<name>-svaj.png|svg`` (the
follower's motion, which both cams share) and ``<name>-assembly.png|svg`` (both cams, both rollers and the
follower at theta = 0, and both pressure angles over the turn), ``<name>.html`` (the interactive page: both cams
turning under their rollers). Only the formats ``output.formats`` asks for are
made; nothing is written if any file fails.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.kinds.conjugate.design import ConjugateDesign, roller_centres
from camgen.kinds.conjugate.kinematics import ArmRoller
from camgen.core.bundle import Bundle, Item, mesh_files, part_files, sheet_files, solid_files, tail
from camgen.core.figures import PREVIEW_TOLERANCE_MM, figure
from camgen.core.nesting import SheetRules, nest, sheet_kinds
from camgen.core.parts import Drawing, Placed
from camgen.core.routing import add_routing
from camgen.profile import step_part
from camgen.outputs import printed_mesh
from camgen.kinds.conjugate.page import conjugate_page
from camgen.report import cam_report, design_lines

#: the keys of a disc cam's report that each cam of the pair has of its own (the rest they share)
OWN_KEYS = ("pressure_angle_max_deg", "pressure_angle_max_at_deg", "pitch_rho_min_mm", "pitch_rho_min_at_deg",
            "profile_rho_min_mm", "pitch_concave_rho_min_mm", "profile_concave_rho_min_mm", "concave_rho_min_at_deg",
            "outline_vertices", "outline_arcs", "outline_lines", "outline_max_error_mm", "area_mm2", "wall_mm")
#: how many cam angles the pair's constraint is measured at
CONSTRAINT_ANGLES = 3600


def _r(x: float | None, digits: int = 9) -> float | None:
    return None if x is None or not math.isfinite(x) else round(float(x), digits)


def _follower(design: ConjugateDesign) -> dict[str, Any]:
    """The second roller's place and the constraint the pair keeps, measured on both pitch curves."""
    first, second = design.cam, design.second
    theta = 2 * math.pi * np.arange(CONSTRAINT_ANGLES) / CONSTRAINT_ANGLES
    p1, p2 = first.pitch(theta).point, second.pitch(theta).point
    apart = np.linalg.norm(p1 - p2, axis=1)
    f = second.follower
    if isinstance(f, ArmRoller):
        distance = float(np.linalg.norm(f.rest - (np.array([0.0, first.follower.prime_radius]) - f.pivot)))
        return {"type": "bell crank: both rollers on one arm about the pivot",
                "arm_angle_deg": _r(math.degrees(f.arm_angle)), "second_arm_length_mm": f.arm_length,
                "second_roller_rest_mm": [_r(x) for x in f.centre(np.zeros(1))[0]],
                "roller_distance_mm": _r(distance),
                "constraint": "the rollers' centres stay roller_distance_mm apart, each on its arm's circle about the "
                              "pivot",
                "constraint_error_mm": _r(float(np.abs(apart - distance).max()), 15)}
    span = f.span
    out = {"type": "yoke: both rollers on the follower's line, on either side of the shaft", "yoke_span_mm": _r(span),
           "second_roller_rest_mm": [_r(x) for x in f.centre(np.zeros(1))[0]],
           "constraint": "the rollers' centres stay yoke_span_mm apart along the follower's line"
                         + (": r1(phi) + r2(phi + 180 degrees) = yoke_span_mm, the pitch radii at opposite polar "
                            "angles" if f.first.offset == 0 else ""),
           "constraint_error_mm": _r(float(np.abs(apart - span).max()), 15)}
    if f.first.offset == 0:
        radii = np.linalg.norm(p1, axis=1) + np.linalg.norm(p2, axis=1)
        out["pitch_radius_sum_error_mm"] = _r(float(np.abs(radii - span).max()), 15)
    return out


def conjugate_report(design: ConjugateDesign, meshes: tuple[Any, Any] = (None, None)) -> dict[str, Any]:
    """The report of a conjugate pair: a disc cam's figures for each cam (under ``cams``), the worst of both at
    the top, the second roller's place and the pair's constraint (``pair``), and both contacts measured over a
    turn (``contact``)."""
    t = design.spec
    own = [cam_report(d, mesh) for d, mesh in zip(design.cams, meshes, strict=True)]
    first = own[0]
    worst = max((0, 1), key=lambda i: own[i]["pressure_angle_max_deg"])
    sharpest = min((0, 1), key=lambda i: own[i]["profile_rho_min_mm"])
    report: dict[str, Any] = {key: first[key] for key in ("name", "generator", "conventions")}
    report["name"] = t.name
    report["conventions"] = {**first["conventions"], "pair": (
        "cam 1 drives the follower's own roller (on +Y at theta = 0 at rest), cam 2 the second roller; both in the "
        "same cam frame, keyway on +Y, the theta = 0 tick at the same angle on both"),
        "pressure_angle": "angle between the contact normal and the way the roller's centre moves: for cam 1 as the "
                          "follower rises, for cam 2 as it returns (the way cam 2 drives it)"}
    report["cam"] = {"kind": "conjugate", "base_radius_mm": design.cam.base_radius,
                     "second_base_radius_mm": _r(design.second.base_radius),
                     "thickness_mm": t.cam.thickness, "bore_mm": t.cam.bore, "keyway": t.hub.keyway,
                     "rotation": t.cam.rotation}
    radius = design.second.follower.radius            # the second roller's own radius, where it has one
    report["follower"] = {**first["follower"], "second_roller": {
        **_follower(design), **({} if radius is None else {"roller_radius_mm": radius})}}
    report["segments"] = first["segments"]
    lift = next(k for k in first if k.startswith("lift_max_"))
    report.update({
        lift: first[lift],
        "pressure_angle_max_deg": own[worst]["pressure_angle_max_deg"],
        "pressure_angle_max_at_deg": own[worst]["pressure_angle_max_at_deg"],
        "pressure_angle_max_cam": worst + 1,
        "pressure_angle_limit_deg": first["pressure_angle_limit_deg"],
        "profile_rho_min_mm": own[sharpest]["profile_rho_min_mm"],
        "profile_rho_min_cam": sharpest + 1,
        "undercut": False,
        "envelope": False,
        "outline_vertices": sum(r["outline_vertices"] for r in own),
        "outline_arcs": sum(r["outline_arcs"] for r in own),
        "outline_lines": sum(r["outline_lines"] for r in own),
        "outline_max_error_mm": float(design.written_error_mm),
        "outline_note": "both cams' DXF outlines as written" + (
            f", each measured against its cam's surface moved out by half the kerf ({t.output.kerf / 2:g} mm)"
            if t.output.kerf else ""),
        **{key: first[key] for key in ("tolerance_mm", "kerf_mm", "clearance_mm", "bore_cut_mm", "bore_printed_mm")},
        "cams": {str(i + 1): {"base_radius_mm": r["cam"]["base_radius_mm"],
                              "prime_radius_mm": r["cam"]["prime_radius_mm"],
                              **{key: r[key] for key in OWN_KEYS}, **({"mesh": r["mesh"]} if "mesh" in r else {})}
                 for i, r in enumerate(own)},
        "contact": {"angles": design.contact.angles,
                    **{f"cam{i + 1}_gap_{end}_mm": _r(gap[k] + 0.0, 12) for i, gap in enumerate(design.contact.gap_mm)
                       for k, end in enumerate(("min", "max"))},
                    "worst_mm": _r(design.contact.worst_mm, 12),
                    "note": "each roller placed by the follower's kinematics at every angle, its distance from its "
                            "cam's nominal outline less its radius (negative: it would cut in)"},
        "continuity": first["continuity"],
        "warnings": list(design.warnings),
    })
    if all("mesh" in r for r in own):
        report["mesh"] = {key: all(r["mesh"][key] for r in own) for key in ("watertight", "winding_consistent")}
        report["mesh"]["volume_mm3"] = _r(sum(r["mesh"]["volume_mm3"] for r in own), 6)
    for key in ("speed", "sizing"):
        if key in first:
            report[key] = first[key]
    second = design.sizing[1]
    if second is not None:
        report["sizing_second"] = {"base_radius_mm": _r(second.base_radius_mm), "decided_by": second.decided_by,
                                   "pressure_radius_mm": _r(second.pressure_radius_mm),
                                   "curvature_radius_mm": _r(second.curvature_radius_mm)}
    return report


def summary_lines(report: dict[str, Any]) -> list[str]:
    """The key figures of a conjugate pair's report, as ``camgen build`` prints them."""
    follower = report["follower"]
    place = follower["second_roller"]
    where = (f"a yoke of span {place['yoke_span_mm']:.3f} mm" if "yoke_span_mm" in place
             else f"a bell crank, arms {place['arm_angle_deg']:.2f} deg apart")
    lines = [f"{report['name']}: conjugate pair, {follower['type']} follower on {where}"]
    for key, cam in report["cams"].items():
        lines.append(f"cam {key}: base radius {cam['base_radius_mm']:.3f} mm; pressure angle max "
                     f"{cam['pressure_angle_max_deg']:.2f} deg at {cam['pressure_angle_max_at_deg']:.2f} deg; min "
                     f"convex radius {cam['profile_rho_min_mm']:.3f} mm (cam), {cam['pitch_rho_min_mm']:.3f} mm "
                     f"(pitch) at {cam['pitch_rho_min_at_deg']:.2f} deg")
    contact = report["contact"]
    lines.append(f"outline: {report['outline_vertices']} vertices ({report['outline_arcs']} exact arcs), max error "
                 f"{report['outline_max_error_mm']:.2e} mm (tolerance {report['tolerance_mm']:g} mm)")
    lines.append(f"contact: both rollers within {contact['worst_mm']:.2e} mm of their cams over {contact['angles']} "
                 "angles")
    if (report.get("speed") or {}).get("forces"):        # the forces of its positive drive at cam.rpm
        lines += design_lines({"speed": report["speed"]})
    return lines


def assembly_figure(design: ConjugateDesign) -> Any:
    """Both cams, both rollers and the follower at theta = 0 (above), and both pressure angles over the turn."""
    t = design.spec
    fig = figure(8, 11)
    ax, pa = fig.subplots(2, 1, height_ratios=[3, 1])
    circle = np.linspace(0, 2 * math.pi, 361)
    colours = ("C0", "C1")
    for which, d in enumerate(design.cams):
        ring = d.outline.contour.flatten(PREVIEW_TOLERANCE_MM)
        ax.fill(ring[:, 0], ring[:, 1], color=colours[which], alpha=0.18, zorder=0)
        ax.plot(*np.vstack([ring, ring[:1]]).T, color=colours[which], lw=1.2, label=f"cam {which + 1}")
        pitch = d.cam.pitch(np.linspace(0, 2 * math.pi, 721)).point
        ax.plot(pitch[:, 0], pitch[:, 1], "--", color=colours[which], lw=0.6)
    for hole in design.cams[0].part.holes:
        ring = hole.flatten(PREVIEW_TOLERANCE_MM)
        ax.fill(ring[:, 0], ring[:, 1], color="white", ec="k", lw=0.8, zorder=2)
    pair = (design.cam, design.second)
    centres = [c[0] for c in roller_centres(pair, np.zeros(1))]
    radii = [cam.contact_radius for cam in pair]
    for which, (centre, rr) in enumerate(zip(centres, radii, strict=True)):
        ax.plot(centre[0] + rr * np.cos(circle), centre[1] + rr * np.sin(circle), color="C2", lw=1.5,
                label="rollers at θ = 0" if which == 0 else None)
    follower = design.second.follower
    if isinstance(follower, ArmRoller):
        pivot = follower.pivot
        ax.plot(*pivot, "^", color="C2", ms=9)
        for centre in centres:
            ax.plot([pivot[0], centre[0]], [pivot[1], centre[1]], color="C2", lw=2)
    else:
        ax.plot([centres[0][0], centres[1][0]], [centres[0][1] + radii[0], centres[1][1] - radii[1]], color="C2", lw=2,
                label="yoke")
    for which, d in enumerate(design.cams):
        a = d.analysis
        at = d.cam.pitch(np.radians([a.pressure_angle_max_at_deg])).point[0]
        ax.plot(*at, "o", color=colours[which], label=f"cam {which + 1}: max pressure angle "
                f"{a.pressure_angle_max_deg:.1f}° at θ = {a.pressure_angle_max_at_deg:.1f}°")
    ax.set(aspect="equal", xlabel="x (mm)", ylabel="y (mm)",
           title=f"{t.name}: conjugate pair at θ = 0 ({t.cam.rotation}), {t.follower.type} follower")
    ax.grid(alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2, fontsize=8)
    theta = np.linspace(0, 2 * math.pi, 1441)
    for which, d in enumerate(design.cams):
        pa.plot(np.degrees(theta), np.degrees(np.abs(d.cam.pitch(theta).pressure_angle)), color=colours[which],
                label=f"cam {which + 1}")
    pa.axhline(design.cams[0].pressure_limit_deg, color="C3", ls=":", lw=0.8, label="limit")
    pa.set(xlim=(0, 360), xticks=range(0, 361, 30), xlabel="cam angle θ (degrees)", ylabel="|pressure angle| (°)")
    pa.grid(alpha=0.3)
    pa.legend(fontsize=7)
    return fig


def step_solids(design: ConjugateDesign) -> tuple[Placed, ...]:
    """The STEP file's cams (``<name>-1``, ``<name>-2``, their biarc outlines: :func:`camgen.profile.step_part`) as
    assembled: on one shaft in the pair's cam frame (both turned alike, so their keyways line up), the second
    standing on the first's top face (on its hub boss, if it has one)."""
    out, z = [], 0.0
    for which, member in enumerate(design.cams):
        part = step_part(member)[0]
        out.append(Placed(f"{design.spec.name}-{which + 1}", (part,), 0.0, (0.0, 0.0, z)))
        z += part.thickness + (part.boss[1] if part.boss else 0.0)
    return tuple(out)


def conjugate_bundle(design: ConjugateDesign) -> tuple[Bundle, dict[str, Any]]:
    """The files of a conjugate pair and its report (without the ``files`` map, which the bundle adds)."""
    out = design.spec.output
    formats, name = out.formats, design.spec.name
    meshes = [printed_mesh(design.spec, d.printed, d.printed.name) for d in design.cams]
    report = conjugate_report(design, (meshes[0][1], meshes[1][1]))
    add_routing(report, [d.cut for d in design.cams], out.tool_radius)
    nested = nest(tuple(d.cut for d in design.cams), SheetRules.of(out, out.kerf, "output.sheet"))
    report["sheet"] = nested.report

    speed = design.cams[0].speed
    forces, speeds = (None, None) if speed is None else (speed.forces, speed.speeds)

    def plot(kind: str) -> Any:
        from camgen import plots
        from camgen.kinds.conjugate.plots import pair_checks_figure

        if kind == "svaj":
            return plots.svaj_figure(design.cams[0])
        if kind == "checks":
            return pair_checks_figure(design)
        if kind == "speeds" and speeds is not None:
            return plots.speeds_plot(name, speeds)
        return assembly_figure(design)

    items: list[Item | None] = []
    for which, (d, (mesh, _)) in enumerate(zip(design.cams, meshes, strict=True)):
        items += [part_files(Drawing.of_part(d.cut), f"{name}-{which + 1}", f"cam{which + 1}"),
                  mesh_files(mesh, f"{name}-{which + 1}", f"cam{which + 1}")]
    items += [sheet_files(drawing, f"{name}-{kind}", kind) for kind, drawing in sheet_kinds(nested.drawings(
        out.tolerance))]
    items.append(solid_files(step_solids(design) if "step" in formats else None, name))
    checks: tuple[str, ...] = ("checks",) if forces else ()   # at a speed with a mass
    checks += ("speeds",) if speeds else ()
    items += tail(name, plot, ("svaj", "assembly", *checks), report, lambda: conjugate_page(design, report))
    return Bundle.of(items, out.write_options, formats), report
