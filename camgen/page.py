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
from camgen.followers.base import rotate
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


def _theta() -> np.ndarray:
    return np.radians(np.arange(FRAMES) * 360.0 / FRAMES)


def _svaj(cam: Any, theta: np.ndarray) -> tuple[Plot, ...]:
    """S, V, A, J against the cam angle, per radian of cam angle."""
    motion = cam.program.evaluate(theta)
    u = cam.follower.lift_unit
    names = (("displacement s", u), ("velocity s'", f"{u}/rad"), ("acceleration s''", f"{u}/rad^2"),
             ("jerk s'''", f"{u}/rad^3"))
    return tuple(Plot(title, unit, ((title, motion[k]),)) for k, (title, unit) in enumerate(names))


def _checks(cam: Any, theta: np.ndarray, limit: float | None,
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


def _ring(points: np.ndarray) -> np.ndarray:
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


def _holes(part: Any, tol: float) -> tuple[Outline, ...]:
    return tuple(Outline(_ring(h.flatten(tol)), "hole") for h in part.holes)


def _title(spec: Any, what: str) -> tuple[str, str]:
    return (f"{spec.name}: {what}",
            f"{spec.follower.type} follower, {spec.cam.rotation} rotation; {len(spec.motion)} segments over 360 deg")


def cam_page(design: Any, report: dict[str, Any]) -> Page:
    """The page of a disc or plate cam's design whose report is ``report`` (the JSON report's dict, its figures shown
    as they are there)."""
    return _profile_page(design, design, report, grooved=False)


def grooved_page(design: Any, report: dict[str, Any]) -> Page:
    """The page of a grooved cam's design (its groove round the island, the disc cam whose surface is the inner
    flank), whose report is ``report``."""
    return _profile_page(design, design.profile, report, grooved=True)


def _profile_page(design: Any, profile: Any, report: dict[str, Any], grooved: bool) -> Page:
    """The page of a cam cut to a profile: ``profile`` the design of that profile (``design`` itself, or a grooved
    cam's island)."""
    spec, cam = design.spec, profile.cam
    theta = _theta()
    reach = float(np.abs(cam.pitch(np.linspace(0, 2 * math.pi, 361)).point).max()) + cam.contact_radius
    tol = max(design.tolerance, reach / 1000.0)
    roller = float(spec.follower.roller_radius or 0.0)
    pitch = Outline(cam.pitch(np.linspace(0, 2 * math.pi, 721)).point, "pitch")
    if grooved:
        outlines = (Outline(_ring(design.part.outline.flatten(tol)), "part"),
                    Outline(_ring(design.outer_outline.contour.flatten(tol)), "groove"),
                    Outline(_ring(design.outline.contour.flatten(tol)), "island"), pitch, *_holes(design.part, tol))
        what = "grooved face cam"
    else:
        outlines = (Outline(_ring(design.outline.contour.flatten(tol)), "part"), *_holes(design.part, tol))
        outlines += () if cam.follower.flat else (pitch,)
        what = "plate cam" if cam.is_plate else "disc cam"
    movers, still = _follower(spec, cam, theta, report, roller, reach)
    if cam.is_plate:
        shift = np.column_stack([-cam.follower.travel * theta / (2 * math.pi), np.zeros_like(theta)])
        body = Body("plate", outlines, pose_motion(np.zeros_like(theta), shift))
    else:                                       # a turning cam: its centre marked
        body = Body("cam", outlines, pose_motion(np.degrees(cam.follower.sense * theta)))
        still += (Outline(np.array([[-0.06 * reach, 0], [0.06 * reach, 0]]), "guide", False),
                  Outline(np.array([[0, -0.06 * reach], [0, 0.06 * reach]]), "guide", False))
    limit = report.get("pressure_angle_limit_deg")
    contact = roller + float(getattr(spec.cam, "running_clearance", 0.0) or 0.0) / 2 if grooved else cam.contact_radius
    checks, notes = _checks(cam, theta, limit, contact)
    title, subtitle = _title(spec, what)
    figures = key_figures(report, CAM_FIGURES)
    if cam.follower.flat:
        figures = tuple(f for f in figures if not f.key.startswith("pressure_angle"))
    return Page(spec.name, title, subtitle, "cam angle θ", "deg", np.degrees(theta),
                Scene((Body("frame", still), body), movers), (*_svaj(cam, theta), *checks), figures,
                tuple(report.get("warnings", ())), notes)


#: a conjugate pair's own figures, before every cam's (:data:`CAM_FIGURES`)
CONJUGATE_FIGURES = (
    ("... on cam", "pressure_angle_max_cam", ""),
    ("cam 1: largest pressure angle", "cams.1.pressure_angle_max_deg", "deg"),
    ("cam 2: largest pressure angle", "cams.2.pressure_angle_max_deg", "deg"),
    ("cam 1: smallest convex radius", "cams.1.profile_rho_min_mm", "mm"),
    ("cam 2: smallest convex radius", "cams.2.profile_rho_min_mm", "mm"),
    ("second cam's base radius", "cam.second_base_radius_mm", "mm"),
    ("yoke span (roller to roller)", "follower.second_roller.yoke_span_mm", "mm"),
    ("rollers' distance", "follower.second_roller.roller_distance_mm", "mm"),
    ("constraint error", "follower.second_roller.constraint_error_mm", "mm"),
)


def conjugate_page(design: Any, report: dict[str, Any]) -> Page:
    """A conjugate pair's page: both cams turning together on their shaft, each under its roller, the two rollers
    joined by the yoke (or by the bell crank through its pivot); the follower's S-V-A-J (the pair shares it), both
    pressure angles and both pitch curves' curvature."""
    spec, (one, two) = design.spec, design.cams
    theta = _theta()
    sense = one.cam.follower.sense
    reach = max(float(np.abs(d.cam.pitch(np.linspace(0, 2 * math.pi, 361)).point).max()) for d in design.cams)
    tol = max(design.tolerance, reach / 1000.0)
    turn = pose_motion(np.degrees(sense * theta))
    cams = (Body("cam 2 (below)", (Outline(_ring(two.outline.contour.flatten(tol)), "second"),), turn),
            Body("cam 1", (Outline(_ring(one.outline.contour.flatten(tol)), "part"), *_holes(one.part, tol)), turn))
    g1, g2 = one.cam.pitch(theta), two.cam.pitch(theta)
    c1, c2 = rotate(g1.point, sense * theta), rotate(g2.point, sense * theta)
    pivot = getattr(two.cam.follower, "pivot", None)
    joined = np.stack([c1, c2], axis=1) if pivot is None else np.stack(
        [c1, np.broadcast_to(np.asarray(pivot, dtype=float), c1.shape), c2], axis=1)
    movers = (Mover("yoke" if pivot is None else "bell crank", joined, "follower"),
              Mover("roller 1", c1[:, None, :], "roller", one.cam.contact_radius),
              Mover("roller 2", c2[:, None, :], "roller", two.cam.contact_radius))
    limit = report.get("pressure_angle_limit_deg")
    marks = () if limit is None else (("limit", limit), ("limit", -limit))
    checks = (Plot("pressure angle", "deg", (("cam 1", np.degrees(g1.pressure_angle)),
                                             ("cam 2", np.degrees(g2.pressure_angle))), marks),
              Plot("pitch curves' curvature (convex > 0)", "1/mm", (("cam 1", g1.kappa), ("cam 2", g2.kappa)),
                   (("undercut limit 1/roller", 1.0 / one.cam.contact_radius),)))
    return Page(spec.name, f"{spec.name}: conjugate cams", f"{spec.follower.type} follower held both ways by two cams "
                f"on one shaft, {spec.cam.rotation} rotation", "cam angle θ", "deg", np.degrees(theta),
                Scene(cams, movers), (*_svaj(one.cam, theta), *checks),
                key_figures(report, (*CAM_FIGURES[:1], *CONJUGATE_FIGURES, *CAM_FIGURES[1:])),
                tuple(report.get("warnings", ())))


def barrel_page(design: Any, report: dict[str, Any]) -> Page:
    """A barrel cam's page: its developed drawing (the pitch cylinder unrolled, x = Rm theta) sliding under the
    roller, which stands at x = 0 (an arm's roller where its axis pierces the pitch cylinder, Rm asin(e / Rm)) and
    rides at its height zc (z0 + s for a translating roller); three copies of the drawing keep the groove in view."""
    spec, cam = design.spec, design.cam
    theta = _theta()
    rm = design.radii[1]
    length = 2 * math.pi * rm
    tol = max(design.tolerance, length / 2000.0)
    styles = {"OUTLINE": "part", "GROOVE": "wall", "PITCH": "pitch"}
    outlines = []
    for layer, shape in design.drawing.items:
        if not hasattr(shape, "flatten"):
            continue
        ring = _ring(shape.flatten(tol))
        closed = layer == "OUTLINE"
        for k in (-1, 0, 1):
            outlines.append(Outline(ring + np.array([k * length, 0.0]), styles.get(layer, "path"), closed))
    x = rm * theta
    shift = np.column_stack([-x, np.zeros_like(x)])
    body = Body("developed cylinder", tuple(outlines), pose_motion(np.zeros_like(x), shift))
    pose = design.walls.pose(theta)              # the roller axis's height zc and tangential offset e (an arm's)
    centre = np.column_stack([rm * np.arcsin(np.clip(pose[3] / rm, -1.0, 1.0)), pose[0]])
    roller = float(spec.follower.roller_radius)
    movers = (Mover("roller", centre[:, None, :], "roller", roller),)
    top = float(spec.cam.length)
    view = (-0.5 * length, -0.05 * top, 0.5 * length, 1.05 * top)
    g_pressure = np.degrees(np.arctan2(cam.program.evaluate(theta)[1], rm))
    limit = report.get("pressure_angle_limit_deg")
    marks = () if limit is None else (("limit", limit), ("limit", -limit))
    checks = (Plot("pressure angle on the pitch cylinder", "deg", (("atan(s'/Rm)", g_pressure),), marks),)
    return Page(spec.name, f"{spec.name}: barrel cam, the pitch cylinder unrolled",
                f"radius {rm:g} mm developed over {length:.6g} mm; the roller stays, the groove runs under it",
                "cam angle θ", "deg", np.degrees(theta), Scene((body,), movers, view), (*_svaj(cam, theta), *checks),
                key_figures(report, CAM_FIGURES), tuple(report.get("warnings", ())))
