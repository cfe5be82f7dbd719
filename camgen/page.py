"""A cam design's interactive page: the cam turning (or a plate or developed barrel sliding) under its follower, drawn
from the design's own geometry, with S-V-A-J, pressure angle and curvature against the cam angle and the report's key
figures (see :mod:`camgen.core.page`).

Frames: one a degree of cam angle, theta = 0 ... 359 degrees. In the fixed frame a point P of the cam's frame stands
at R(sense theta) P (the cam turns by theta in its sense); a plate slides by -travel theta / 360 along x, the developed
barrel by -pitch_radius theta, under a follower that stays at x = 0.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.page import FRAMES, Body, Mover, Outline, Page, Plot, Scene, key_figures, pose_motion
from camgen.tables.followers import Face

#: the figures a cam's page shows, where its report has them: (label, dotted key, unit)
CAM_FIGURES = (
    ("largest pressure angle", "pressure_angle_max_deg", "deg"),
    ("... at cam angle", "pressure_angle_max_at_deg", "deg"),
    ("pressure angle limit", "pressure_angle_limit_deg", "deg"),
    ("pressure angle at the groove's floor", "pressure_angle_floor_deg", "deg"),
    ("smallest convex radius, pitch curve", "pitch_rho_min_mm", "mm"),
    ("smallest convex radius, cam", "profile_rho_min_mm", "mm"),
    ("... at cam angle", "pitch_rho_min_at_deg", "deg"),
    ("inner flank: smallest convex radius", "flanks.inner.flank_rho_min_mm", "mm"),
    ("outer flank: smallest concave radius", "flanks.outer.flank_rho_min_mm", "mm"),
    ("lower wall: smallest radius", "walls.lower.wall_rho_min_mm", "mm"),
    ("upper wall: smallest radius", "walls.upper.wall_rho_min_mm", "mm"),
    ("undercut", "undercut", ""),
    ("largest lift", "lift_max_mm", "mm"),
    ("largest swing", "lift_max_deg", "deg"),
    ("base radius", "cam.base_radius_mm", "mm"),
    ("prime radius", "cam.prime_radius_mm", "mm"),
    ("pitch radius", "cam.pitch_radius_mm", "mm"),
    ("arm's rest angle", "follower.rest_angle_deg", "deg"),
    ("face width", "face_width_mm", "mm"),
    ("wall round the bore", "wall_mm", "mm"),
    ("outline vertices", "outline_vertices", ""),
    ("outline error (bound)", "outline_max_error_mm", "mm"),
    ("tolerance", "tolerance_mm", "mm"),
    ("solid's volume", "mesh.volume_mm3", "mm^3"),
    ("speed", "speed.rpm", "rpm"),
    ("peak velocity", "speed.velocity_max_mm_s", "mm/s"),
    ("peak acceleration", "speed.acceleration_max_mm_s2", "mm/s^2"),
    ("peak jerk", "speed.jerk_max_mm_s3", "mm/s^3"),
    ("peak velocity", "speed.velocity_max_deg_s", "deg/s"),
    ("peak acceleration", "speed.acceleration_max_deg_s2", "deg/s^2"),
    ("lift-off speed", "speed.contact.liftoff_rpm", "rpm"),
    ("least contact force", "speed.contact.force_min_n", "N"),
)

#: what a flat face's page says instead of plotting its pressure angle
FLAT_NOTE = ("no pressure angle plotted: a flat face is pushed square to itself, so its pressure angle is 0 by "
             "definition; its profile's radius of curvature is plotted instead (it must stay positive)")


def frame_angles() -> np.ndarray:
    """The cam angles (rad) of a page's frames: :data:`~camgen.core.page.FRAMES` evenly over the turn from 0."""
    return np.radians(np.arange(FRAMES) * 360.0 / FRAMES)


def svaj_plots(cam: Any, theta: np.ndarray) -> tuple[Plot, ...]:
    """S, V, A, J against the cam angle, per radian of cam angle."""
    motion = cam.program.evaluate(theta)
    u = cam.follower.lift_unit
    names = (("displacement s", u), ("velocity s'", f"{u}/rad"), ("acceleration s''", f"{u}/rad^2"),
             ("jerk s'''", f"{u}/rad^3"))
    return tuple(Plot(title, unit, ((title, motion[k]),)) for k, (title, unit) in enumerate(names))


def check_plots(cam: Any, theta: np.ndarray, limit: float | None,
            contact: float) -> tuple[tuple[Plot, ...], tuple[str, ...]]:
    """Pressure angle (with its limit) and curvature (with the undercut limit 1/``contact``) against the cam angle;
    a flat face's profile radius instead, with a note."""
    g = cam.pitch(theta)
    if cam.follower.flat:
        return (Plot("profile's radius of curvature", "mm", (("radius", g.rho),), (("cusp at 0", 0.0),)),), (FLAT_NOTE,)
    marks = () if limit is None else (("limit", limit), ("limit", -limit))
    pressure = Plot("pressure angle", "deg", (("pressure angle", np.degrees(g.pressure_angle)),), marks)
    bend = (("undercut limit 1/roller", 1.0 / contact),) if contact > 0 else ()
    curvature = Plot("pitch curve's curvature (convex > 0)", "1/mm", (("curvature", g.kappa),), bend)
    return (pressure, curvature), ()


def ring(points: np.ndarray) -> np.ndarray:
    """A flattened outline (n, 2) as floats."""
    return np.asarray(points, dtype=float)


def _follower(spec: Any, cam: Any, theta: np.ndarray, report: dict[str, Any], roller: float,
              reach: float) -> tuple[tuple[Mover, ...], tuple[Outline, ...]]:
    """The follower frame by frame (a turning cam's in the fixed frame, a plate's at x = 0), and what of it stands
    still (guide, pivot): as it sketches itself (:class:`~camgen.followers.drawing.Follower`), a flat face as wide as
    the report's face positions and its margins."""
    f, g = cam.follower, cam.pitch(theta)
    face = None
    if "face_position_min_mm" in report and isinstance(spec.follower, Face):
        margin = spec.follower.face_margin
        face = (report["face_position_min_mm"] - margin, report["face_position_max_mm"] + margin)
    movers = tuple(Mover(s.name, s.points, s.style, s.radius) for s in f.sketch(theta, g, reach, face, roller))
    return movers, tuple(Outline(s.points, s.style, s.closed) for s in f.still(theta, g, reach))


def hole_outlines(part: Any, tol: float) -> tuple[Outline, ...]:
    """The holes of ``part`` (a :class:`~camgen.core.parts.Part`) flattened to ``tol`` mm, as a page draws them."""
    return tuple(Outline(ring(h.flatten(tol)), "hole") for h in part.holes)


def _title(spec: Any, what: str) -> tuple[str, str]:
    return (f"{spec.name}: {what}",
            f"{spec.follower.type} follower, {spec.cam.rotation} rotation; {len(spec.motion)} segments over 360 deg")


def cam_page(design: Any, report: dict[str, Any]) -> Page:
    """The page of a disc or plate cam's design whose report is ``report`` (the JSON report's dict, its figures shown
    as they are there)."""
    cam = design.cam
    tol = page_tolerance(design, cam)
    outlines = (Outline(ring(design.outline.contour.flatten(tol)), "part"), *hole_outlines(design.part, tol))
    outlines += () if cam.follower.flat else (pitch_outline(cam),)
    return profile_page(design, cam, report, outlines, "plate cam" if cam.is_plate else "disc cam", cam.contact_radius)


def _reach(cam: Any) -> float:
    """How far from the cam's centre the follower's contact reaches (mm): the page's scale."""
    return float(np.abs(cam.pitch(np.linspace(0, 2 * math.pi, 361)).point).max()) + cam.contact_radius


def page_tolerance(design: Any, cam: Any) -> float:
    """The tolerance (mm) a page flattens ``design``'s outlines to: its own, or a thousandth of ``cam``'s reach."""
    return max(design.tolerance, _reach(cam) / 1000.0)


def pitch_outline(cam: Any) -> Outline:
    """``cam``'s pitch curve, as a page draws it."""
    return Outline(cam.pitch(np.linspace(0, 2 * math.pi, 721)).point, "pitch")


def profile_page(design: Any, cam: Any, report: dict[str, Any], outlines: tuple[Outline, ...], what: str,
                 contact: float) -> Page:
    """The page of a cam cut to a profile (a disc, a plate, a grooved cam's island): ``cam`` the cam of that profile,
    ``outlines`` what its body draws, ``what`` the title's name of it and ``contact`` (mm) the radius whose inverse is
    the curvature's undercut limit (the roller's; a groove's cutter's)."""
    spec = design.spec
    theta = frame_angles()
    reach = _reach(cam)
    roller = float(spec.follower.roller_radius or 0.0)
    movers, still = _follower(spec, cam, theta, report, roller, reach)
    if cam.is_plate:
        shift = np.column_stack([-cam.follower.travel * theta / (2 * math.pi), np.zeros_like(theta)])
        body = Body("plate", outlines, pose_motion(np.zeros_like(theta), shift))
    else:                                       # a turning cam: its centre marked
        body = Body("cam", outlines, pose_motion(np.degrees(cam.follower.sense * theta)))
        still += (Outline(np.array([[-0.06 * reach, 0], [0.06 * reach, 0]]), "guide", False),
                  Outline(np.array([[0, -0.06 * reach], [0, 0.06 * reach]]), "guide", False))
    limit = report.get("pressure_angle_limit_deg")
    checks, notes = check_plots(cam, theta, limit, contact)
    title, subtitle = _title(spec, what)
    figures = key_figures(report, CAM_FIGURES)
    if cam.follower.flat:
        figures = tuple(f for f in figures if not f.key.startswith("pressure_angle"))
    return Page(spec.name, title, subtitle, "cam angle θ", "deg", np.degrees(theta),
                Scene((Body("frame", still), body), movers), (*svaj_plots(cam, theta), *checks), figures,
                tuple(report.get("warnings", ())), notes)
