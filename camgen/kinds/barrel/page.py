"""A barrel cam's page: its developed drawing sliding under the roller, which rides at its height."""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.page import Body, Mover, Outline, Page, Plot, Scene, key_figures, pose_motion
from camgen.page import CAM_FIGURES, frame_angles, ring, svaj_plots


def barrel_page(design: Any, report: dict[str, Any]) -> Page:
    """A barrel cam's page: its developed drawing (the pitch cylinder unrolled, x = Rm theta) sliding under the
    roller, which stands at x = 0 (an arm's roller where its axis pierces the pitch cylinder, Rm asin(e / Rm)) and
    rides at its height zc (z0 + s for a translating roller); three copies of the drawing keep the groove in view."""
    spec, cam = design.spec, design.cam
    theta = frame_angles()
    rm = design.radii[1]
    length = 2 * math.pi * rm
    tol = max(design.tolerance, length / 2000.0)
    styles = {"OUTLINE": "part", "GROOVE": "wall", "PITCH": "pitch"}
    outlines = []
    for layer, shape in design.drawing.items:
        if not hasattr(shape, "flatten"):
            continue
        points = ring(shape.flatten(tol))
        closed = layer == "OUTLINE"
        for k in (-1, 0, 1):
            outlines.append(Outline(points + np.array([k * length, 0.0]), styles.get(layer, "path"), closed))
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
                "cam angle θ", "deg", np.degrees(theta), Scene((body,), movers, view),
                (*svaj_plots(cam, theta), *checks),
                key_figures(report, CAM_FIGURES), tuple(report.get("warnings", ())))
