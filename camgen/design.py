"""A cam design from a template: the cam, its checks, its outline and its part. No I/O."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from camgen.analysis import CamAnalysis, analyse, face_extent, largest_roller
from camgen.cam import Cam, build_cam
from camgen.dynamics import speed_report
from camgen.core.errors import DesignError
from camgen.outline import Outline, envelope_outline, exact_outline
from camgen.core.parts import LAYER_ENGRAVE, Part
from camgen.core.shapes import Circle, Contour, Polyline, Text
from camgen.core.features import bolt_holes, key_for, keyed_bore
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
    pressure_limit_deg: float
    face_extent: tuple[float, float] | None       # flat faces: nearest and farthest contact along the face (mm)
    speed: dict[str, Any] | None                  # with cam.rpm: peak rates and the contact check
    sizing: Sizing | None = None

    @property
    def tolerance(self) -> float:
        """The chord tolerance (mm) every curve of this design was made to."""
        return self.template.output.tolerance

    def _repr_svg_(self) -> str:
        """Jupyter shows the cam as it will be cut."""
        return self.cut[1]._repr_svg_()


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
    kerf, clearance = template.output.kerf, template.output.clearance
    _check_holes(template, body)
    marks = _engraving(template, cam, reach) if template.hub.engrave else ()
    hub = template.hub
    boss = (hub.boss_diameter, hub.boss_height) if hub.boss_diameter else None

    def plate(contour: Contour, grow: float) -> Part:
        return Part(template.name, contour, _holes(template, grow), template.cam.thickness, tol, marks, boss,
                    hub.set_screw)

    part = plate(outline.contour, 0.0)
    cut = outline
    if kerf > 0:
        grown = replace(cam, surface_offset=kerf / 2)
        cut = envelope_outline(grown, tol) if a.undercut else exact_outline(grown, tol, template.output.curves)
    cut_part, printed = plate(cut.contour, -kerf / 2), plate(outline.contour, clearance / 2)
    jumps = tuple(cam.program.jumps())
    speed = _speed(template, cam)
    warnings = _warnings(template, a, jumps, wall, cam.program.segments) + _contact_warnings(speed)
    extent = face_extent(cam) if cam.follower.flat else None
    return CamDesign(template, cam, a, jumps, outline, part, (cut, cut_part), printed, wall, warnings,
                     pressure_limit(template), extent, speed, sizing)


def _speed(template: CamTemplate, cam: Cam) -> dict[str, Any] | None:
    """Peak rates and the contact check at ``cam.rpm`` (None without a speed)."""
    t = template
    if t.cam.rpm is None:
        return None
    parabolic = [(i, seg.ratio or 1.0) for i, seg in enumerate(t.motion) if seg.law == "parabolic"]
    return speed_report(cam, t.cam.rpm, t.follower.mass, t.follower.spring_rate, t.follower.preload, parabolic)


def _contact_warnings(speed: dict[str, Any] | None) -> tuple[str, ...]:
    contact = speed and speed["contact"]
    if not contact or contact.get("holds") is not False:
        return ()
    if contact["mode"] == "gravity":
        return (f"the follower leaves the cam near {contact['liftoff_at_deg']:.1f} degrees: "
                f"gravity holds it only up to {contact['liftoff_rpm']:.4g} rpm",)
    return (f"the spring loses contact near {contact['force_min_at_deg']:.1f} degrees (force "
            f"{contact['force_min_n']:.3g} N): a preload of {contact['preload_needed_n']:.4g} N would hold it",)


def _holes(template: CamTemplate, grow: float) -> tuple:
    """The bore (keyed or round) and the mounting holes, their edges moved out by ``grow`` mm."""
    hub, bore = template.hub, template.cam.bore
    out: list = []
    if bore > 0:
        out.append(keyed_bore(bore, grow) if hub.keyway else Circle((0.0, 0.0), bore / 2 + grow))
    if hub.bolt_holes:
        out.extend(bolt_holes(hub.bolt_circle, hub.bolt_holes, hub.bolt_hole_diameter, grow))
    return tuple(out)


def _check_holes(template: CamTemplate, body: Any) -> None:
    """Every hole must lie inside the cam with material round it."""
    import shapely

    for hole in _holes(template, 0.0):
        ring = shapely.Polygon(hole.flatten(template.output.tolerance))
        if not body.contains(ring) or body.exterior.distance(ring) <= 0:
            field = "hub.bolt_circle" if isinstance(hole, Circle) and hole.centre != (0.0, 0.0) else "cam.bore"
            raise DesignError(f"{field}: a hole reaches the cam's outline (it comes within "
                              f"{body.exterior.distance(ring):.3g} mm); make it smaller or move it in")


def _engraving(template: CamTemplate, cam: Cam, reach: float) -> tuple:
    """ENGRAVE marks, in the band between the outermost hole and the outline: the part's name, an arrow
    in the sense of rotation and a tick towards the follower at theta = 0."""
    hub = template.hub
    inner = template.cam.bore / 2 + (key_for(template.cam.bore)[1] if hub.keyway else 0.0)
    if hub.bolt_holes:
        inner = max(inner, hub.bolt_circle / 2 + hub.bolt_hole_diameter / 2)
    mid = inner + 0.5 * (reach - inner)
    height = max(1.0, min(5.0, 0.3 * (reach - inner)))
    name = Text(template.name, (-0.3 * height * len(template.name), -mid - 0.5 * height), height)
    sense = 1 if template.cam.rotation == "ccw" else -1

    def at(radius: float, degrees: float) -> np.ndarray:
        return radius * np.array([math.cos(math.radians(degrees)), math.sin(math.radians(degrees))])

    start, end = 200.0, 200.0 + sense * 60.0
    shaft = Polyline(np.array([at(mid, start), at(mid, end)]), np.array([math.tan(sense * math.radians(60) / 4)]))
    back = end - sense * 8.0
    head = Polyline(np.array([at(mid + height / 2, back), at(mid, end), at(mid - height / 2, back)]), np.zeros(2))
    contact = cam.pitch(np.array([0.0])).point[0]
    direction = contact / np.linalg.norm(contact)
    tick = Polyline(np.array([direction * (reach - 2 * height), direction * (reach - height)]), np.zeros(1))
    return tuple((LAYER_ENGRAVE, mark) for mark in (name, shaft, head, tick))


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

