"""A barrel cam as files: the developed drawing, the printed solid with its groove, the report and the plots.

Names: ``<name>-developed.dxf`` and ``<name>-developed.svg`` (the pitch cylinder unrolled: a template to check
or to wrap round a turned cylinder), ``<name>.stl`` and ``<name>.3mf`` (the cylinder with its bore and groove),
``<name>.json``, ``<name>-svaj.png|svg`` and ``<name>-cam.png|svg`` (the developed drawing), ``<name>.html`` (the
interactive page: the developed drawing running under the roller).
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.kinds.barrel.design import BarrelDesign
from camgen.core import VERSION
from camgen.core.bundle import Bundle, mesh_files, sheet_files, tail
from camgen.core.errors import ExportError
from camgen.followers.barrel import Arm
from camgen.kinds.barrel.page import barrel_page
from camgen.report import design_lines
from camgen.sizing import pressure_limit


#: where the cutter's loops start, in steps round from theta = 0, tried in turn: should the cut leave two vertices
#: on one point that no edge joins, or a short edge that cannot be collapsed safely
#: (:func:`camgen.kinds.barrel.mesh.without_short_edges`), another phase moves every vertex of the cut
SOLID_PHASES = (0.0, 0.5, 0.25, 0.75)


def _r(x: float | None, digits: int = 9) -> float | None:
    return None if x is None or not math.isfinite(x) else round(float(x), digits)


def _wall(check: Any) -> dict[str, Any]:
    f = check.flank
    return {"pitch_rho_min_mm": _r(f.pitch_rho_min_mm), "at_deg": _r(f.at_deg), "at_radius_mm": _r(check.at_radius_mm),
            "wall_rho_min_mm": _r(f.rho_min_mm), "undercut": f.undercut}


def _arm(arm: Arm, rm: float) -> dict[str, Any]:
    """An arm's figures: its swing, its axial stroke against the arc, and its chordal error (``rm``: the pitch
    cylinder's radius, mm)."""
    turn = 2 * arm.mid
    half = math.radians(arm.mid)
    chordal = arm.chordal_error(turn)
    return {"arm_length_mm": arm.length, "pivot_distance_mm": arm.pivot_distance, "pivot_height_mm": _r(arm.height),
            "swing_deg": _r(turn), "rest_angle_deg": _r(-arm.mid),
            "axial_stroke_mm": _r(2 * arm.length * math.sin(half)), "arc_length_mm": _r(arm.length * 2 * half),
            "chordal_error_mm": _r(chordal),
            "pitch_cylinder_departure_mm": _r(math.hypot(rm, chordal) - rm),
            "chordal_error_least_mm": _r(arm.length * (1 - math.cos(half)) / 2),
            "pivot_distance_least_mm": _r(arm.length * (1 + math.cos(half)) / 2)}


def _cone(design: BarrelDesign) -> dict[str, Any]:
    """A conical roller's half-angle and the groove's width at the floor and at the rim."""
    walls = design.walls
    if not walls.taper:
        return {}
    inner, _, outer = design.radii
    return {"cone_half_angle_deg": _r(math.degrees(math.atan(walls.taper))),
            "groove_width_floor_mm": _r(2 * (walls.r0 + walls.taper * inner)),
            "groove_width_rim_mm": _r(2 * (walls.r0 + walls.taper * outer))}


def _rib(design: BarrelDesign) -> dict[str, Any]:
    """A rib's figures: its width where level and at its thinnest (square to the track, on the core), the rollers'
    centres' distance (mm); nothing for a groove (whose width is groove_width_mm)."""
    if design.rib is None or design.rib_thinnest is None:      # both set for a rib, neither for a groove
        return {}
    (below, above), (thinnest, at) = design.rib, design.rib_thinnest
    return {"form": "rib", "rib_width_mm": design.spec.cam.rib_width, "rib_height_mm": design.spec.cam.groove_depth,
            "roller_centres_apart_mm": _r(above.z0 - below.z0), "rib_thinnest_mm": _r(thinnest),
            "rib_thinnest_at_deg": _r(at)}


def barrel_report(design: BarrelDesign, mesh: Any = None) -> dict[str, Any]:
    """The report of a barrel cam as a JSON-ready dict (keys carry their units)."""
    t, a = design.spec, design.analysis
    inner, rm, outer = design.radii
    tube, slip = design.tube, design.slip or {}
    arm = design.walls.arm
    report: dict[str, Any] = {
        "name": t.name,
        "generator": f"camgen {VERSION}",
        "conventions": {
            "units": "mm and degrees; derivatives of s per radian of cam angle",
            "frame": "cam axis +Z, the cylinder from z = 0 to its length; the roller's axis radial, on +X at "
                     "theta = 0; in the cam's frame the roller stands at the polar angle -theta (ccw cams)",
            "developed": "x = pitch_radius theta (the way the roller travels over the cam), z along the axis",
            "pressure_angle": "atan(s' / r) on the cylinder of radius r" if arm is None else
                              "the angle between the normal at the roller's contact on the cylinder of radius r and "
                              "the path of the roller's centre, in 3D (the larger of the two walls')",
        },
        "cam": {"kind": "barrel", "pitch_radius_mm": rm, "floor_radius_mm": inner, "rim_radius_mm": outer,
                "length_mm": t.cam.length, "groove_depth_mm": t.cam.groove_depth,
                "groove_width_mm": round(2 * design.cutter, 12), "running_clearance_mm": t.cam.running_clearance,
                "rest_height_mm": _r(design.walls.z0 if arm is None else float(design.walls.centre(np.zeros(1))[0, 0])),
                "bore_mm": t.cam.bore, "rotation": t.cam.rotation, **_rib(design)},
        "follower": {"type": t.follower.type, "roller_radius_mm": t.follower.roller_radius,
                     "roller_shape": t.follower.roller_shape, **_cone(design),
                     **({} if arm is None else _arm(arm, rm))},
        "segments": [{"index": i, "type": seg.type, "law": seg.law, **seg.law_params(), "angle_deg": seg.angle,
                      "lift_mm": seg.lift} for i, seg in enumerate(t.motion)],
        "lift_max_mm": _r(design.cam.program.max_lift),
        "pressure_angle_max_deg": _r(a.pressure_angle_max_deg),
        "pressure_angle_max_at_deg": _r(a.pressure_angle_max_at_deg),
        "pressure_angle_floor_deg": _r(design.pressure_deg["floor"]),
        "pressure_angle_rim_deg": _r(design.pressure_deg["rim"]),
        "walls": {"cutter_radius_mm": round(design.cutter, 12), "lower": _wall(design.checks[0]),
                  "upper": _wall(design.checks[1]),
                  "plane_offset_gap_mm": _r(design.walls.plane_offset_gap(rm)),
                  "plane_offset_gap_floor_mm": _r(design.walls.plane_offset_gap(inner))},
        "undercut": False,
        "rolling_slip": {"floor_percent": _r(slip.get("floor")), "rim_percent": _r(slip.get("rim")),
                         "note": "the largest slip of the roller along the way it rolls, over the cycle and both "
                                 "walls, in percent of the cam's surface speed there, the roller rolling without "
                                 "slip on the pitch cylinder"},
        "developed_max_error_mm": _r(design.drawing_error_mm, 12),
        "wall_max_error_mm": None if tube is None else _r(tube.wall_error_mm, 12),
        "floor_max_error_mm": None if tube is None else _r(tube.floor_error_mm, 12),
        "outline_max_error_mm": max(design.drawing_error_mm, tube.wall_error_mm if tube else 0.0),
        "outline_note": "the larger of the developed drawing's chords' and the solid's walls' distance from the exact "
                        "curves and walls",
        "tolerance_mm": design.tolerance,
        "clearance_mm": t.output.clearance,
        "continuity": [j.as_dict() for j in design.jumps],
        "warnings": list(design.warnings),
    }
    if design.speed is not None:
        report["speed"] = design.speed.as_report()
    if mesh is not None:
        report["mesh"] = {"watertight": mesh.watertight, "winding_consistent": mesh.winding_consistent,
                          "volume_mm3": _r(mesh.volume_mm3, 6), "triangles": mesh.triangles,
                          "bodies": mesh.bodies, "loops": design.solid_tube.loops, "radii": design.solid_tube.radii + 1}
    return report


def summary_lines(report: dict[str, Any]) -> list[str]:
    """The key figures of a barrel cam's report, a few lines for the command to print."""
    cam, walls = report["cam"], report["walls"]
    foot = "rib's foot" if "form" in cam else "groove's floor"

    def wall(side: str) -> str:
        w = walls[side]
        return (f"{side} {w['wall_rho_min_mm']:.3f} mm at {w['at_deg']:.2f} deg (r {w['at_radius_mm']:g} mm)"
                if w["wall_rho_min_mm"] is not None else f"{side} never bent that way")

    follower = report["follower"]
    arm = ([] if "chordal_error_mm" not in follower else
           [f"arm: swing {follower['swing_deg']:g} deg, axial stroke {follower['axial_stroke_mm']:.4f} mm (arc "
            f"{follower['arc_length_mm']:.4f}), chordal error {follower['chordal_error_mm']:.4f} mm (least "
            f"{follower['chordal_error_least_mm']:.4f} at pivot_distance {follower['pivot_distance_least_mm']:.4f})"])
    lines = [f"{report['name']}: pressure angle max {report['pressure_angle_max_deg']:.2f} deg at "
             f"{report['pressure_angle_max_at_deg']:.2f} deg on the pitch cylinder (r {cam['pitch_radius_mm']:g} mm), "
             f"{report['pressure_angle_floor_deg']:.2f} deg at the {foot} (r {cam['floor_radius_mm']:g} mm)",
             (f"groove: {cam['groove_width_mm']:g} mm wide, {cam['groove_depth_mm']:g} mm deep" if "form" not in cam
              else f"rib: {cam['rib_width_mm']:g} mm wide where level, {cam['rib_thinnest_mm']:.4g} mm at its thinnest "
                   f"({cam['rib_thinnest_at_deg']:.2f} deg), {cam['rib_height_mm']:g} mm high, between rollers "
                   f"{cam['roller_centres_apart_mm']:.4g} mm apart")
             + f"; smallest radius of the walls: {wall('lower')}, {wall('upper')}",
             *arm,
             f"rolling slip ({follower['roller_shape']} roller): {report['rolling_slip']['floor_percent']:.2f} % at "
             f"the floor, {report['rolling_slip']['rim_percent']:.2f} % at the rim",
             f"developed drawing within {report['developed_max_error_mm']:.2e} mm of the exact curves (tolerance "
             f"{report['tolerance_mm']:g} mm)"]
    if report["wall_max_error_mm"] is not None:
        lines.append(f"solid: walls within {report['wall_max_error_mm']:.2e} mm of the exact walls, floor within "
                     f"{report['floor_max_error_mm']:.2e} mm ({report['mesh']['triangles']} triangles)")
    if (report.get("speed") or {}).get("forces"):        # the forces of its positive drive at cam.rpm
        lines += design_lines({"speed": report["speed"]})
    return lines


def barrel_bundle(design: BarrelDesign) -> tuple[Bundle, dict[str, Any]]:
    """The files of a barrel cam and its report (without the ``files`` map, which the bundle adds)."""
    out = design.spec.output
    formats, name = out.formats, design.spec.name
    mesh = check = None
    if {"stl", "3mf"} & set(formats):
        from camgen.kinds.barrel.mesh import SHORTEST_STEPS, without_short_edges
        from camgen.core.solids import carve, check_mesh

        plain, shortest = design, SHORTEST_STEPS * design.single_step
        for phase in SOLID_PHASES:            # the first whose cut is a closed solid in single precision
            design = plain.with_solid(phase)
            carved = carve(design.blank, design.solid_tube.vertices, design.solid_tube.faces, name)
            mesh = without_short_edges(carved, shortest)
            check = check_mesh(carved if mesh is None else mesh)
            if mesh is not None and check.ok:
                break
        else:
            raise ExportError(f"{name}: the mesh is not a closed outward solid in single precision with no edge "
                              f"shorter than {shortest:.3g} mm ({check}); try another output.tolerance")
    report = barrel_report(design, check)
    forces, speeds = (None, None) if design.speed is None else (design.speed.forces, design.speed.speeds)

    def plot(kind: str) -> Any:
        from camgen import plots
        from camgen.core.figures import drawing_figure

        if kind == "svaj":
            return plots.svaj_figure(design)
        if kind == "speeds" and speeds is not None:
            return plots.speeds_plot(name, speeds)
        if kind == "checks" and forces is not None:
            w = design.walls            # the developed walls at Rm, the cutter's radius there off the pitch curve
            return plots.groove_checks_plot(design.spec, design.cam, forces,
                                            pressure_limit(design.spec), w.r0 + w.taper * design.radii[1],
                                            design.spec.follower.roller_radius, ("lower wall", "upper wall"))
        what = ("the groove's walls and the pitch curve" if design.rib is None
                else "the rib's walls and the rollers' paths")
        return drawing_figure(design.drawing, f"{name}: the pitch cylinder (radius {design.radii[1]:g} mm) unrolled, "
                                              + what)

    checks: tuple[str, ...] = ("checks",) if forces and design.rib is None else ()   # with a mass
    checks += ("speeds",) if speeds else ()
    items = [sheet_files(design.drawing, f"{name}-developed"), mesh_files(mesh, name),
             *tail(name, plot, ("svaj", "cam", *checks), report, lambda: barrel_page(design, report))]
    return Bundle.of(items, out.write_options, formats), report
