"""What the cam kinds' starter templates share (each kind lists its own, :attr:`camgen.kinds.base.Kind.starters`): a
motion program, the output table, a sprung follower's keys, a cam table's usual keys, and the comments of rules
several kinds have."""
from __future__ import annotations

from typing import Any

#: a rise, a dwell, a return, a dwell: laws with continuous acceleration, so no jerk is infinite
MOTION = ({"type": "rise", "law": "cycloidal", "lift": 20.0, "angle": 120.0}, {"type": "dwell", "angle": 60.0},
          {"type": "return", "law": "modified-sine", "lift": 20.0, "angle": 120.0}, {"type": "dwell", "angle": 60.0})
#: an arm's lift, for the oscillating followers
SWING = {"motion.lift": "degrees: the arm's swing"}
#: the rules every disc cam under a roller has
ROLLER = {"follower.roller_radius": "mm: roller radius; below the pitch curve's least convex radius, else the cam "
                                   "undercuts (the prime radius is base_radius + roller_radius)"}
#: a base radius sized by camgen under a flat face
FLAT_AUTO = {"cam.base_radius": "\"auto\": the smallest whose profile radius (base_radius + s + s'' for a "
                                "translating face) stays above min_rho_margin and meets the pressure-angle limit",
             "cam.min_rho_margin": "mm: least radius of curvature of the profile; at 0 or below it folds into a "
                                   "cusp the face cannot follow"}
OUTPUT = ("output", {"tolerance": 0.01, "kerf": 0.0, "clearance": 0.2})
SPRUNG = {"mass": 0.2, "spring_rate": 0.5, "preload": 5.0}


def cam_table(kind: str, **keys: Any) -> tuple[str, dict[str, Any]]:
    """A ``[cam]`` table of ``kind`` (its ``kind`` key left out for a disc, the default) with the usual size, bore,
    rotation and speed, and ``keys`` over them."""
    base = {"kind": kind} if kind != "disc" else {}
    return "cam", {**base, "base_radius": 40.0, "thickness": 8.0, "bore": 10.0, "rotation": "ccw", "rpm": 60.0,
                   **keys}


def motion(lift: float = 20.0) -> tuple[tuple[str, dict[str, Any]], ...]:
    """:data:`MOTION`'s ``[[motion]]`` entries with ``lift`` (mm, or degrees of an arm's swing)."""
    return tuple(("[motion]", {k: (lift if k == "lift" else v) for k, v in seg.items()}) for seg in MOTION)
