"""A Geneva drive's interactive page: the driver turning at constant speed, the wheel indexing and dwelling, the
wheel's angle, velocity, acceleration and jerk against the driver's angle, the report's key figures (see
:mod:`camgen.core.page`).

Frames: one a degree of driver angle alpha, -180 ... 179 degrees (the pin's direction from the centre line, the
driver's axis at the origin, the wheel's at (C, 0)). The wheel's outline is turned by pi - beta about its axis,
the locking disc and the crank by alpha about the driver's, as in :mod:`camgen.kinds.geneva.plots`.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.page import FRAMES, Body, Mover, Outline, Page, Plot, Scene, key_figures, pose_motion

#: the figures a Geneva drive's page shows: (label, dotted key, unit)
GENEVA_FIGURES = (
    ("slots", "geneva.slots", ""),
    ("centre distance", "geneva.centre_distance_mm", "mm"),
    ("crank radius", "geneva.crank_radius_mm", "mm"),
    ("index (wheel turns)", "motion.index_deg", "deg"),
    ("driver turns while it indexes", "motion.motion_deg", "deg"),
    ("dwell", "motion.dwell_deg", "deg"),
    ("peak wheel velocity (x the driver's)", "motion.velocity_ratio_max", ""),
    ("peak wheel acceleration (x omega^2)", "motion.acceleration_ratio_max", ""),
    ("least gap, locking disc to wheel", "assembly.lock_clearance_min_mm", "mm"),
    ("least gap, pin to wheel", "assembly.pin_clearance_min_mm", "mm"),
    ("pin's entry angle to the slot", "assembly.entry_angle_deg", "deg"),
    ("lock overlap at the dwell's ends", "assembly.lock_overlap_deg", "deg"),
)


def _outlines(part: Any, style: str, tol: float) -> tuple[Outline, ...]:
    return (Outline(part.outline.flatten(tol), style),
            *(Outline(h.flatten(tol), "hole") for h in part.holes))


def geneva_page(design: Any, report: dict[str, Any]) -> Page:
    """The page of a Geneva drive ``design`` whose report is ``report`` (the JSON report's dict)."""
    g, spec = design.geometry, design.spec
    alpha = np.radians(np.arange(FRAMES) * 360.0 / FRAMES - 180.0)
    law = g.law.motion(alpha)
    tol = max(design.tolerance, g.centre_distance / 1000.0)
    wheel = Body("wheel", _outlines(design.parts["wheel"], "wheel", tol),
                 pose_motion(np.degrees(math.pi - law[0]), np.tile([g.centre_distance, 0.0], (FRAMES, 1))))
    turn = pose_motion(np.degrees(alpha))
    crank = Body("crank", (Outline(design.parts["crank"].outline.flatten(tol), "crank"),), turn)
    lock = Body("locking disc", _outlines(design.parts["lock"], "lock", tol), turn)
    pin = g.crank_radius * np.column_stack([np.cos(alpha), np.sin(alpha)])
    circle = np.linspace(0, 2 * math.pi, 181)
    still = Body("pin circle", (Outline(g.crank_radius * np.column_stack([np.cos(circle), np.sin(circle)]), "pitch"),))
    names = (("wheel angle β", "deg", np.degrees(law[0])), ("wheel velocity β'", "x omega", law[1]),
             ("wheel acceleration β''", "x omega^2", law[2]), ("wheel jerk β'''", "x omega^3", law[3]))
    plots = tuple(Plot(title, unit, ((title, values),)) for title, unit, values in names)
    return Page(spec.name, f"{spec.name}: Geneva drive, {g.slots} slots",
                f"the driver turns at constant speed (counter-clockwise); the wheel indexes {360 / g.slots:g} deg "
                f"while the driver turns {180 - 360 / g.slots:g} deg, then dwells", "driver angle α", "deg",
                np.degrees(alpha), Scene((still, crank, lock, wheel), (Mover("pin", pin[:, None, :], "pin",
                                                                              g.pin_diameter / 2),)),
                plots, key_figures(report, GENEVA_FIGURES), tuple(report.get("warnings", ())),
                ("the wheel's rates are per radian of driver angle; the acceleration jumps at entry and exit "
                 "(infinite jerk), drawn here between two frames",))
