"""A conjugate pair's page: both cams turning together on their shaft, each under its roller, the two rollers joined
by the yoke (or the bell crank)."""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.page import Body, Mover, Outline, Page, Plot, Scene, key_figures, pose_motion
from camgen.followers.base import rotate
from camgen.page import CAM_FIGURES, frame_angles, hole_outlines, ring, svaj_plots


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
    theta = frame_angles()
    sense = one.cam.follower.sense
    reach = max(float(np.abs(d.cam.pitch(np.linspace(0, 2 * math.pi, 361)).point).max()) for d in design.cams)
    tol = max(design.tolerance, reach / 1000.0)
    turn = pose_motion(np.degrees(sense * theta))
    cams = (Body("cam 2 (below)", (Outline(ring(two.outline.contour.flatten(tol)), "second"),), turn),
            Body("cam 1", (Outline(ring(one.outline.contour.flatten(tol)), "part"), *hole_outlines(one.part, tol)),
                 turn))
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
                Scene(cams, movers), (*svaj_plots(one.cam, theta), *checks),
                key_figures(report, (*CAM_FIGURES[:1], *CONJUGATE_FIGURES, *CAM_FIGURES[1:])),
                tuple(report.get("warnings", ())))
