"""Sizing a cam: the cam-factor table (quick method) and the smallest base radius (exact method).

Quick method: prime radius Rp = f h / beta, with the cam factor f = Cv cot(phi_max)
from the law's peak slope Cv (h = beta = 1) for a centred translating roller; for
the drafted modified uniform law f follows from its arcs: the straight stretch's
slope angle alpha equals the pressure angle, so f = k = (2 - cos alpha) / sin alpha.

Exact method: bisection on the base radius for the smallest one meeting the
pressure-angle limit, and for the smallest meeting the curvature margin (the cam's
smallest convex radius at least ``min_rho_margin`` mm; for a flat face its radius of
curvature everywhere); the larger decides, and the result says which. Both search a
:class:`~camgen.rig.Rig`'s cams (its motion and follower, without a size) against
:class:`Limits`.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.analysis import pressure_angle_max, profile_rho_min
from camgen.cam import Cam
from camgen.core.errors import CamgenError, DesignError
from camgen.laws import make_law
from camgen.numeric import boundary
from camgen.rig import Rig

FACTOR_LAWS = ("uniform", "modified-uniform", "harmonic", "parabolic", "cycloidal")
FACTOR_ANGLES = tuple(range(10, 50, 5))


def cam_factor(law: str, pressure_angle_deg: float) -> float:
    """f such that Rp = f h / beta keeps a centred translating roller's pressure angle within the limit."""
    phi = math.radians(pressure_angle_deg)
    if law == "modified-uniform":                 # drafted: the line's slope angle is the pressure angle
        return (2 - math.cos(phi)) / math.sin(phi)
    cv = float(make_law(law).peaks()[0])
    return cv / math.tan(phi)


def factor_table() -> dict[str, dict[str, float]]:
    """``{law: {angle: f}}`` for pressure-angle limits 10 to 45 degrees."""
    return {law: {str(a): cam_factor(law, a) for a in FACTOR_ANGLES} for law in FACTOR_LAWS}


@dataclass(frozen=True)
class Sizing:
    """The smallest base radius (mm), which constraint decided it and each constraint's own smallest radius."""

    base_radius_mm: float
    decided_by: str
    pressure_radius_mm: float
    curvature_radius_mm: float
    max_pressure_angle_deg: float
    min_rho_margin_mm: float


@dataclass(frozen=True)
class Limits:
    """What sizing keeps: the pressure angle at most ``pressure_deg`` (degrees) and the cam surface's convex radii
    above ``min_rho_margin`` (mm; a flat face's profile radius everywhere)."""

    pressure_deg: float
    min_rho_margin: float = 0.0


def pressure_limit(spec: Any) -> float:
    """The template's pressure-angle limit (``cam.max_pressure_angle``), or the usual 30 degrees (translating) / 40
    (oscillating)."""
    if spec.cam.max_pressure_angle is not None:
        return spec.cam.max_pressure_angle
    return 40.0 if spec.follower.oscillating else 30.0


def limits_of(spec: Any) -> Limits:
    """The :class:`Limits` a template sets: its pressure-angle limit and ``cam.min_rho_margin``."""
    return Limits(pressure_limit(spec), spec.cam.min_rho_margin)


def _domain(rig: Rig) -> tuple[float, float]:
    """Base radii (mm) for which the follower can be assembled and follow the program's levels at all: (lowest,
    highest), exclusive (a law's overshoot above its levels is checked as each cam is built)."""
    return rig.mount.base_range(rig.roller_radius, rig.level_top)


#: the narrowest bracket of the base-radius search, as a fraction of the radius it starts from
FLOOR = 1e-12


def _smallest(rig: Rig, ok: Callable[[Cam], bool], what: str, near: float | None = None) -> float:
    """Smallest base radius (to 1e-9 relative, or to :data:`FLOOR` of the radius the search starts from: a limit
    that every base circle meets, as a flat face's pressure angle, is met down to 0, which halving reached only
    after 200 cams) at which ``ok(cam)`` holds, by bisection from the first radius found
    to hold, starting from ``near`` (mm: a template's own base radius, where it gives one): doubling where the
    follower assembles on any base circle, else stepping up through the range it assembles on by 1/64 of it (an
    arm's pressure angle grows again towards the top of that range, where the arm turns radial, so halving towards
    the top can step over every radius that holds)."""
    lo, top = _domain(rig)

    def holds(rb: float) -> bool:
        try:
            with np.errstate(divide="raise", over="raise", invalid="raise"):
                return ok(rig.cam(rb))
        except (CamgenError, ArithmeticError):         # a radius so small its geometry degenerates fails too
            return False

    hi = max(near or 0.0, lo + rig.lift_max, 1.0)
    if hi >= top:                                       # a short range (an arm's): start from its bottom step
        hi = lo + (top - lo) / 64
    while not holds(hi):
        nxt = hi * 2 if math.isinf(top) else hi + (top - lo) / 64
        if nxt > 1e7 or nxt >= top:
            raise DesignError(f"{what}: no base radius meets it (searched up to {hi:.6g} mm)")
        hi = nxt
    return boundary(holds, hi, lo, floor=FLOOR * hi)


def size_cam(rig: Rig, limits: Limits, near: float | None = None) -> Sizing:
    """The smallest base radius of ``rig``'s cams meeting ``limits``: the pressure-angle limit and the curvature
    margin.

    Parameters
    ----------
    rig : Rig
        A disc or plate cam's set-up without its size (:mod:`camgen.rig`): its motion, follower and roller.
    limits : Limits
        The pressure-angle limit (degrees; a template's ``cam.max_pressure_angle``, 30 degrees by default, 40 for
        an oscillating follower, :func:`limits_of`) and the curvature margin (mm, ``cam.min_rho_margin``).
    near : float, optional
        Where to start the search (mm): a template's own base radius, where it gives one.

    Returns
    -------
    Sizing
        The smallest base radius (mm) meeting the pressure-angle limit and keeping the cam surface's convex radii
        above the margin, which of the two decided it, and each one's own smallest radius.

    Raises
    ------
    DesignError
        A velocity jump no roller can follow at any size (naming its moving segment), or a limit no base radius
        meets (naming ``cam.max_pressure_angle`` or ``cam.min_rho_margin``).
    """
    jumps = [i for i, turn in rig.cam(_probe(rig)).corners() if turn > 0]
    if jumps and rig.roller_radius > 0:
        raise DesignError(f"motion[{rig.moving_segment(jumps[0])}]: the follower velocity jumps (a convex pitch "
                          "corner): no base radius gives the roller a path it can follow; use a law with continuous "
                          "velocity")
    limit, margin = limits.pressure_deg, limits.min_rho_margin
    pressure = _smallest(rig, lambda cam: pressure_angle_max(cam) <= limit,
                         f"cam.max_pressure_angle: the pressure-angle limit of {limit:g} degrees", near)
    curvature = smallest_for_curvature(rig, margin, near)
    decided = "pressure angle" if pressure >= curvature else "curvature"
    return Sizing(max(pressure, curvature), decided, pressure, curvature, limit, margin)


def _probe(rig: Rig) -> float:
    lo, hi = _domain(rig)
    middle = 0.5 * (lo + hi) if hi < math.inf else math.inf
    return min(lo + rig.lift_max + 1.0, middle)


def smallest_for_curvature(rig: Rig, margin: float = 0.0, near: float | None = None) -> float:
    """Smallest base radius (mm) whose cam surface keeps every convex radius above ``margin`` mm (searched from
    ``near`` mm, where given)."""
    return _smallest(rig, lambda cam: profile_rho_min(cam) > margin,
                     f"cam.min_rho_margin: the curvature margin of {margin:g} mm", near)
