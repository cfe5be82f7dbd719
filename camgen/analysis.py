"""Design checks of a cam: pressure angle, curvature and undercut, and the largest roller that fits."""
from __future__ import annotations

import math
from collections.abc import Callable, Generator
from dataclasses import dataclass

import numpy as np

from camgen.cam import Ask, Cam, Maker
from camgen.followers.base import PitchGeometry
from camgen.numeric import boundary
from camgen.rig import Rig


@dataclass(frozen=True)
class CamAnalysis:
    """Extremes over the whole cycle. Angles in degrees of cam rotation, radii in mm.

    ``pitch_rho_min_mm`` is the smallest radius of curvature where the pitch curve is
    convex; the cam surface there has ``profile_rho_min_mm`` = that minus the roller
    radius. ``*_concave_*`` are the smallest concave radii (None where the curve is
    convex throughout); a cutter must be no larger than the profile's. ``undercut``
    is True where a convex pitch radius is smaller than the roller radius.
    """

    pressure_angle_max_deg: float
    pressure_angle_max_at_deg: float
    pitch_rho_min_mm: float
    pitch_rho_min_at_deg: float
    profile_rho_min_mm: float
    pitch_concave_rho_min_mm: float | None
    profile_concave_rho_min_mm: float | None
    concave_at_deg: float | None
    undercut: bool


def _peaks(cam: Cam, *quantities: Callable[[PitchGeometry], np.ndarray]) -> list[tuple[float, float]]:
    """Largest value over the cycle of each pitch-geometry quantity, and where: (value, cam angle in degrees) each,
    all from one evaluation of the pitch curve (see :meth:`camgen.program.Program.maxima`); of equal peaks (within
    1e-12 of the quantity's magnitude, an angle's at least 1 radian) the first."""
    return cam.serve([_peaks_steps(cam, *quantities)])[0]


def _peaks_steps(cam: Cam, *quantities: Callable[[PitchGeometry], np.ndarray]) -> Maker:
    """:func:`_peaks` as a maker of :meth:`Cam.serve` (its asks are the law's own variable on each segment):
    the program's search itself, asking as the cam's evaluation takes it."""
    def values(answers: list[PitchGeometry]) -> np.ndarray:
        (g,) = answers
        return np.array([q(g) for q in quantities])

    return cam.program.maxima_steps(values, [1.0 if q is _pressure else 0.0 for q in quantities],
                                    cam.steady, _ask)


def _ask(v: np.ndarray, index: np.ndarray) -> list[Ask]:
    """The search's points as :meth:`Cam.serve` takes them: one ask, its points given by segment and by the law's own
    variable (see :data:`camgen.cam.Ask`)."""
    return [(index, v, True)]


def _peak(cam: Cam, quantity: Callable[[PitchGeometry], np.ndarray]) -> tuple[float, float]:
    """Largest value of a pitch-geometry ``quantity`` over the cycle: (value, cam angle in degrees)."""
    return _peaks(cam, quantity)[0]


def _pressure(g: PitchGeometry) -> np.ndarray:
    return np.abs(g.pressure_angle)


def _kappa(g: PitchGeometry) -> np.ndarray:
    return g.kappa


def _concave(g: PitchGeometry) -> np.ndarray:
    return -g.kappa


def _cusp(g: PitchGeometry) -> np.ndarray:
    return -g.face_rho


def convex_curvature_max(cam: Cam) -> tuple[float, float]:
    """Largest convex curvature of the pitch curve (1/mm) and where (degrees)."""
    return _peak(cam, _kappa)


def convex_radius_min(cam: Cam) -> tuple[float, float]:
    """Smallest convex radius of curvature of the pitch curve (mm) and where (degrees): infinite where the curve
    is nowhere convex (a plate cam of straight ramps and dwells)."""
    return _radius(*convex_curvature_max(cam))


def _radius(kmax: float, at: float) -> tuple[float, float]:
    return (1.0 / kmax if kmax > 0 else math.inf), at


def face_extent(cam: Cam) -> tuple[float, float]:
    """Nearest and farthest contact positions along a flat face (mm; see the follower's ``face_position``)."""
    position = cam.follower.face_position
    (hi, _), (neg, _) = _peaks(cam, position, lambda g: -position(g))
    return -neg, hi


def pressure_angle_max(cam: Cam) -> float:
    """Peak |pressure angle| over the cycle (degrees)."""
    return math.degrees(_peak(cam, _pressure)[0])


def profile_rho_min(cam: Cam) -> float:
    """Smallest convex radius of the cam surface (mm); for a flat face the profile's smallest radius."""
    if cam.follower.flat:
        return -math.inf if any(step < 0 for _, step in cam.steps()) else -_peak(cam, _cusp)[0]
    return convex_radius_min(cam)[0] - cam.contact_radius


def analyze(cam: Cam) -> CamAnalysis:
    """:func:`analysis_maker` run on its own.

    Parameters
    ----------
    cam : Cam
        A built cam (:meth:`camgen.rig.Rig.cam`, :func:`camgen.flat.build_cam`).

    Returns
    -------
    CamAnalysis
        The peak |pressure angle| (degrees) and where, the least convex radii of the pitch curve and of the cam
        surface (mm; signed: positive convex) and where, the least concave ones, and whether the cam undercuts
        (for a flat face: whether its profile folds), each located to about 1e-9 degrees of cam angle.
    """
    return cam.serve([analysis_maker(cam)])[0]


def analysis_maker(cam: Cam) -> Generator[list[Ask], list[PitchGeometry], CamAnalysis]:
    """Pressure angle, curvature and undercut of ``cam``, each located to ~1e-9 degrees, all from one evaluation
    of the pitch curve on every smooth piece of the motion and one refinement round.

    For a flat face the profile itself is analysed: its radius of curvature must
    stay positive, and ``undercut`` means it does not (the profile folds into a cusp; where
    the velocity drops at a segment end it folds at once, a radius of -infinity).
    """
    if cam.follower.flat:
        (pa, pa_at), (neg, at) = yield from _peaks_steps(cam, _pressure, _cusp)
        folds = [i for i, step in cam.steps() if step < 0]
        if folds:  # the velocity drops at a segment end: the profile folds back, a radius of curvature of -infinity
            neg, at = math.inf, math.degrees(cam.program.segments[folds[0]].end) % 360.0
        return CamAnalysis(
            pressure_angle_max_deg=math.degrees(pa), pressure_angle_max_at_deg=pa_at,
            pitch_rho_min_mm=-neg, pitch_rho_min_at_deg=at, profile_rho_min_mm=-neg,
            pitch_concave_rho_min_mm=None, profile_concave_rho_min_mm=None, concave_at_deg=None, undercut=-neg <= 0)
    (pa, pa_at), convex, (kmin, kmin_at) = yield from _peaks_steps(cam, _pressure, _kappa, _concave)
    rho, kmax_at = _radius(*convex)
    rr = cam.contact_radius
    convex_corners = [i for i, turn in cam.corners() if turn > 0]
    if convex_corners:  # a convex corner of the pitch curve is a zero radius of curvature
        rho, kmax_at = 0.0, math.degrees(cam.program.segments[convex_corners[0]].end) % 360.0
    concave = 1.0 / kmin if kmin > 0 else None
    return CamAnalysis(
        pressure_angle_max_deg=math.degrees(pa), pressure_angle_max_at_deg=pa_at,
        pitch_rho_min_mm=rho, pitch_rho_min_at_deg=kmax_at, profile_rho_min_mm=rho - rr,
        pitch_concave_rho_min_mm=concave, profile_concave_rho_min_mm=None if concave is None else concave + rr,
        concave_at_deg=kmin_at if concave is not None else None, undercut=rho < rr)


def largest_roller(rig: Rig, base_radius: float) -> float | None:
    """The largest roller radius (mm), up to the rig's, that does not undercut on a base circle of ``base_radius``.

    The pitch curve depends on the roller (prime radius = base + roller), so this
    bisects on the roller radius for min convex pitch radius = roller radius.
    Returns None when no roller fits: the pitch curve has a convex corner (a
    velocity jump), or even a vanishing roller undercuts, or the follower has no roller.
    """
    if rig.mount.roller_radius is None:
        return None
    def margin(rr: float) -> float:
        return convex_radius_min(rig.cam(base_radius, rr))[0] - rr

    if any(turn > 0 for _, turn in rig.cam(base_radius).corners()):
        return None
    return largest_fitting(rig, base_radius, margin)


def largest_fitting(rig: Rig, base_radius: float, margin: Callable[[float], float]) -> float | None:
    """The largest roller radius (mm), up to the rig's, for which ``margin(roller radius)`` >= 0, by bisection
    from the least roller that assembles on a base circle of ``base_radius`` mm; None when even that one fails."""
    lo = rig.mount.roller_floor(base_radius) + 1e-9
    hi = rig.roller_radius
    if margin(lo) <= 0:
        return None
    if margin(hi) >= 0:
        return hi
    return boundary(lambda rr: margin(rr) >= 0, lo, hi)
