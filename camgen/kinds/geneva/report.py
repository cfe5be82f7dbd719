"""The report of a Geneva drive: the law's figures, the parts' dimensions, the assembly's checks and the solids'.

Pure formatting of a finished :class:`~camgen.kinds.geneva.design.GenevaDesign` and the checks of its solids; nothing
here computes a figure. Keys carry their units; rates are per radian of driver angle (multiply by omega,
omega^2 of the driver) unless they say otherwise.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any

from camgen.core import VERSION
from camgen.core.shapes import Circle, Contour
from camgen.kinds.geneva.design import PARTS, GenevaDesign


def _r(x: Any) -> Any:
    """Floats rounded to 12 significant digits for the report (lists and dicts through), the rest as it is."""
    if isinstance(x, float):
        return float(f"{x:.12g}") if math.isfinite(x) else None
    if isinstance(x, dict):
        return {k: _r(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_r(v) for v in x]
    return x


def _diameters(holes: tuple[Contour | Circle, ...]) -> list[float]:
    """The diameters (mm) of a Geneva part's holes, every one a circle (the bore, the crank's pin hole)."""
    return [2 * h.radius for h in holes if isinstance(h, Circle)]


def geneva_report(design: GenevaDesign, solids: dict[str, dict[str, Any]] | None = None) -> dict[str, Any]:
    """The report as a JSON-ready dict. ``solids``: each printed solid's checks (watertight, winding, volume and its
    check), by name, when solids were made."""
    t, g = design.spec, design.geometry
    parts = {}
    for name in PARTS:
        cut = design.cut[name]
        parts[name] = {"area_mm2": design.parts[name].area, "vertices": len(cut.outline.vertices),
                       "arcs": cut.outline.n_arcs, "lines": cut.outline.n_lines,
                       "holes_cut_mm": _diameters(cut.holes),
                       "holes_printed_mm": _diameters(design.printed[name].holes)}
    report: dict[str, Any] = {
        "name": t.name,
        "generator": f"camgen {VERSION}",
        "conventions": {
            "units": "mm and degrees; rates per radian of driver angle (x omega, omega^2, omega^3 of the driver)",
            "frame": "driver's axis at the origin, wheel's axis at (centre distance, 0); the driver turns "
                     "counter-clockwise, the wheel clockwise",
            "driver_angle": "the pin's direction, counter-clockwise from the centre line, in (-180, 180]",
            "wheel_angle": "beta, from the centre line to the engaged slot in the wheel's sense of rotation: "
                           "tan(beta) = sin(alpha) / (C/a - cos(alpha)) while engaged, -180/n before entry, "
                           "180/n after exit",
        },
        "geneva": {"slots": t.geneva.slots, "centre_distance_mm": g.centre_distance, "crank_radius_mm": g.crank_radius,
                   "entry_radius_mm": g.law.entry_radius, "pin_diameter_mm": g.pin_diameter,
                   "slot_width_mm": 2 * g.half_width, "slot_clearance_mm": g.slot_clearance,
                   "slot_bottom_mm": g.bottom - g.half_width, "wheel_radius_mm": g.wheel_radius,
                   "lock_radius_mm": g.lock_radius, "lock_arc_radius_mm": g.lock_arc_radius,
                   "lock_clearance_mm": g.lock_clearance, "cutout_radius_mm": g.cutout_radius,
                   "cutout_centre_mm": [g.centre_distance, 0.0], "crank_width_mm": g.crank_width,
                   "tip_width_mm": g.tip_width(), "thickness_mm": t.geneva.thickness,
                   "driver_bore_mm": t.geneva.driver_bore, "wheel_bore_mm": t.geneva.wheel_bore},
        "motion": design.motion,
        "assembly": dataclasses.asdict(design.assembly),
        "parts": parts,
        "outline_max_error_mm": design.written_error_mm,
        "outline_note": "every piece of the cut files is an exact line or arc" + (
            "; the segments flavour writes the arcs as chords" if t.output.dxf == "segments" else ""),
        "tolerance_mm": design.tolerance,
        "kerf_mm": t.output.kerf,
        "clearance_mm": t.output.clearance,
        "warnings": list(design.warnings),
    }
    if design.speed is not None:
        report["speed"] = design.speed
    if solids:
        report["mesh"] = {"watertight": all(s["watertight"] for s in solids.values()),
                          "winding_consistent": all(s["winding_consistent"] for s in solids.values()),
                          "triangles": sum(s["triangles"] for s in solids.values()), "solids": solids}
    return _r(report)


def summary_lines(report: dict[str, Any]) -> list[str]:
    """The key figures of a Geneva report, a few lines for the command to print."""
    g, m, a = report["geneva"], report["motion"], report["assembly"]
    at = m["acceleration_ratio_max_at_deg"][1]
    jump = m["jumps"][0]
    return [f"{report['name']}: {g['slots']} slots, centre distance {g['centre_distance_mm']:g} mm, crank radius "
            f"{g['crank_radius_mm']:.4f} mm; the wheel turns {m['index_deg']:g} deg while the driver turns "
            f"{m['motion_deg']:g} deg, then dwells {m['dwell_deg']:g} deg",
            f"wheel velocity max {m['velocity_ratio_max']:.4f} x the driver's at 0 deg; acceleration max "
            f"{m['acceleration_ratio_max']:.4f} x omega^2 at +/-{at:.2f} deg; it jumps by {jump['size']:.4f} x "
            f"omega^2 at entry ({jump['at_deg']:g} deg) and exit ({-jump['at_deg']:g} deg): infinite jerk",
            f"assembly: the locking disc clears the wheel by {a['lock_clearance_min_mm']:.4f} mm at least (at "
            f"{a['lock_clearance_at_deg']:.2f} deg), the pin by {a['pin_clearance_min_mm']:.4f} mm; the pin enters at "
            f"{a['entry_angle_deg']:.4f} deg to the slot (tangential)"]
