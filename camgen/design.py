"""A cam design from a template: the cam, its checks, its outline and its part. No I/O."""
from __future__ import annotations

from dataclasses import dataclass, replace

from camgen.analysis import CamAnalysis, analyse, largest_roller
from camgen.cam import Cam, build_cam
from camgen.errors import DesignError
from camgen.outline import Outline, envelope_outline, exact_outline
from camgen.parts.drawing import Circle, Contour, Part
from camgen.program import Jump
from camgen.sizing import Sizing, pressure_limit, size_cam, smallest_for_curvature
from camgen.spec import CamTemplate, with_base_radius

#: thinnest wall between the bore and the outline before a warning (mm)
THIN_WALL = 2.0


@dataclass(frozen=True)
class CamDesign:
    """Everything known about one cam before anything is written."""

    template: CamTemplate
    cam: Cam
    analysis: CamAnalysis
    jumps: tuple[Jump, ...]
    outline: Outline           # the nominal outline
    part: Part                 # the nominal part
    cut: tuple[Outline, Part]  # what the cut files carry: outline grown and holes shrunk by half the kerf
    printed: Part              # what the printed files carry: holes opened by the clearance
    wall_mm: float
    warnings: tuple[str, ...]
    sizing: Sizing | None = None


def _undercut_message(template: CamTemplate, cam: Cam, a: CamAnalysis) -> str:
    if cam.follower.flat:
        smallest = smallest_for_curvature(template)
        return (f"cusp at {a.pitch_rho_min_at_deg:.2f} degrees: the profile's radius of curvature falls to "
                f"{a.profile_rho_min_mm:.4g} mm, so the flat face cannot follow the law there; the smallest "
                f"cam.base_radius that works is {smallest:.4g} mm")
    rr = cam.contact_radius
    corner = a.pitch_rho_min_mm == 0.0
    where = f"undercut at {a.pitch_rho_min_at_deg:.2f} degrees: "
    if corner:
        return (where + "the follower velocity jumps there, so the pitch curve has a convex corner that no roller "
                "can follow; use a law with continuous velocity (e.g. modified-uniform) or set "
                "cam.allow_undercut = true")
    best = largest_roller(template)
    fits = (f"the largest roller that fits is {best:.4g} mm" if best is not None
            else "no roller fits this base radius")
    return (where + f"the pitch curve's radius of curvature is {a.pitch_rho_min_mm:.4g} mm, smaller than "
            f"follower.roller_radius {rr:.4g} mm; {fits} (or enlarge cam.base_radius, or set "
            "cam.allow_undercut = true)")


def design_cam(template: CamTemplate) -> CamDesign:
    """Build, check and outline the cam a template describes.

    Raises :class:`DesignError` for an undercut (unless ``cam.allow_undercut``; never
    for a flat face's cusp) and for a bore that leaves no material. ``base_radius =
    "auto"`` is first replaced by the smallest that meets the limits (see
    :mod:`camgen.sizing`).
    """
    sizing = None
    if template.cam.base_radius == "auto":
        sizing = size_cam(template)
        template = with_base_radius(template, sizing.base_radius_mm)
    cam = build_cam(template)
    a = analyse(cam)
    if a.undercut and (cam.follower.flat or not template.cam.allow_undercut):
        raise DesignError(_undercut_message(template, cam, a))
    tol = template.output.tolerance
    outline = envelope_outline(cam, tol) if a.undercut else exact_outline(cam, tol, template.output.curves)

    import shapely

    body = shapely.Polygon(outline.contour.flatten(tol))
    reach = float(body.exterior.distance(shapely.Point(0.0, 0.0)))
    wall = reach - template.cam.bore / 2.0
    if template.cam.bore > 0 and not (body.contains(shapely.Point(0.0, 0.0)) and wall > 0):
        raise DesignError(f"cam.bore: {template.cam.bore:.4g} mm leaves no material; the outline comes within "
                          f"{reach:.4g} mm of the centre, so the bore must be < {2 * reach:.4g} mm")
    bore = template.cam.bore / 2.0
    kerf, clearance = template.output.kerf, template.output.clearance

    def plate(contour: Contour, hole_radius: float) -> Part:
        holes = (Circle((0.0, 0.0), hole_radius),) if template.cam.bore > 0 else ()
        return Part(template.name, contour, holes, template.cam.thickness, tol)

    part = plate(outline.contour, bore)
    cut = outline
    if kerf > 0:
        grown = replace(cam, surface_offset=kerf / 2)
        cut = envelope_outline(grown, tol) if a.undercut else exact_outline(grown, tol, template.output.curves)
    cut_part, printed = plate(cut.contour, bore - kerf / 2), plate(outline.contour, bore + clearance / 2)
    jumps = tuple(cam.program.jumps())
    warnings = _warnings(template, a, jumps, wall, cam.program.segments)
    return CamDesign(template, cam, a, jumps, outline, part, (cut, cut_part), printed, wall, warnings, sizing)


def _warnings(template: CamTemplate, a: CamAnalysis, jumps: tuple[Jump, ...], wall: float,
              segments: tuple) -> tuple[str, ...]:
    out = []
    limit = pressure_limit(template)
    if a.pressure_angle_max_deg > limit:
        out.append(f"pressure angle peaks at {a.pressure_angle_max_deg:.2f} degrees (at "
                   f"{a.pressure_angle_max_at_deg:.2f} degrees), above the {limit:g} degree limit: enlarge the "
                   "base radius, lengthen the segment or add an offset")
    for j in jumps:
        if j.order < 3:
            out.append(f"{j.quantity} jumps at {j.at_deg:.4g} degrees: {j.consequence}")
    if a.undercut:
        out.append(f"undercut allowed: the outline is the cutter's envelope, and near {a.pitch_rho_min_at_deg:.2f} "
                   "degrees the follower does not follow the motion law")
    if template.cam.bore > 0 and wall < THIN_WALL:
        out.append(f"only {wall:.3g} mm of material between the bore and the outline")
    for i, seg in enumerate(segments):
        over = seg.law.overshoot() if hasattr(seg.law, "overshoot") else 0.0
        if over > 1e-9:
            out.append(f"motion[{i}]: the spline through the points overshoots by {100 * over:.3g} % of the lift "
                       "between them; add points where it bulges")
    if a.profile_concave_rho_min_mm is not None and a.profile_concave_rho_min_mm < 1.0:
        out.append(f"concave radius of {a.profile_concave_rho_min_mm:.3g} mm at {a.concave_at_deg:.2f} degrees: "
                   "the cutting tool or laser kerf must be smaller")
    return tuple(out)

