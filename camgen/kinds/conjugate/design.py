"""A conjugate pair from a spec: both cams built, checked and outlined, as a matched pair. No I/O.

The first cam is the disc cam of the template (the follower's own roller, prime radius base radius + roller
radius at rest); the second cam's pitch curve is the second roller's path in the same cam frame (see
:mod:`camgen.kinds.conjugate.kinematics`), sharing the first cam's motion program. Where the template does not place
the second roller (``cam.yoke_span``, ``cam.arm_angle``) it is placed so that the second cam's base circle (the
second roller's nearest approach less its radius) is ``cam.second_base_radius``, by default the first cam's.

Both cams are checked alike (:func:`camgen.analysis.analyze`): pressure angle (the second cam's measured from
the way it drives the follower back), convex radius of curvature against the roller (undercut, refused naming
the cam, the angle, both radii and the largest roller that fits both cams) and a bore that leaves material.
The second cam must drive the follower back everywhere: its pressure angle below 90 degrees (a second roller
placed where it would move away from its cam on a rise is refused naming the key that placed it).

Designs take domain objects: the template's :class:`~camgen.rig.Rig` (the disc's mount: the first cam's), a
:class:`Placement` of the second roller, each cam's :class:`~camgen.profile.Body` and the template's
:class:`~camgen.profile.Finish`; the template itself is read once, and never copied or validated again.

Each cam is a part of its own (``<name>-1``, ``<name>-2``), with the same bore, keyway (on +Y), holes and boss,
and engraved (unless ``hub.engrave = false``) with its name, the sense of rotation and a tick at the same angle
on both: towards the first roller at theta = 0, so the ticks line up when the pair is stacked on its key, and
the names read from the top face of each (a cam turned over shows its name mirrored). Both contacts are
measured over a turn: each roller, placed by the follower's kinematics, against its cam's outline.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.analysis import CamAnalysis, analyze, largest_fitting, pressure_angle_max, profile_rho_min
from camgen.cam import Cam
from camgen.kinds.conjugate.kinematics import ArmRoller, YokeRoller, arm_prime, arm_turn, yoke_prime, yoke_span
from camgen.core.errors import CamgenError, DesignError
from camgen.flat import FlatCamDesign, flat_rig, parabolic_ratios, rates
from camgen.forces import Contact, drive_speed
from camgen.speed import Speed
from camgen.followers.base import rotate
from camgen.numeric import boundary
from camgen.outline import exact_outline
from camgen.profile import (Body, Finish, Profile, ProfileMaker, check_holes, check_opened_holes, engraving,
                            outline_body, reach)
from camgen.rig import Rig, disc_mount
from camgen.sizing import Limits, Sizing, limits_of, pressure_limit, size_cam
from camgen.kinds.conjugate.table import ConjugateSpec

#: the cam angles (per turn) at which both contacts are measured against the outlines
CONTACT_ANGLES = 720
#: how many second base radii an arm's range is scanned at for the smallest meeting the limits
SCAN = 64
#: thinnest wall between the bore and an outline before a warning (mm), as for a disc cam
THIN_WALL = 2.0


@dataclass(frozen=True)
class Placement:
    """Where the second roller goes, and what it is: ``yoke_span`` (mm: a yoke's rollers' centres apart) or
    ``arm_angle`` (degrees: a bell crank's arms apart at the pivot) where the template fixes them (None: the second
    roller is placed by its cam's base circle instead), the second arm's length ``arm_length`` (mm; None: the
    first arm's) and the second roller's own ``roller_radius`` (mm; None: the first roller's). From the template's
    ``cam.yoke_span``, ``cam.arm_angle``, ``cam.second_arm_length`` and ``cam.second_roller_radius``."""

    yoke_span: float | None = None
    arm_angle: float | None = None
    arm_length: float | None = None
    roller_radius: float | None = None

    @classmethod
    def of(cls, cam: Any) -> Placement:
        """The placement a conjugate template's ``[cam]`` table gives."""
        return cls(cam.yoke_span, cam.arm_angle, cam.second_arm_length, cam.second_roller_radius)

    @property
    def fixed(self) -> bool:
        """Whether the template fixes the second roller (by its yoke span or arm angle), not its base circle."""
        return self.yoke_span is not None or self.arm_angle is not None

    def free(self) -> Placement:
        """The same rollers placed by the second cam's base circle, whatever span or angle this one fixes."""
        return dataclasses.replace(self, yoke_span=None, arm_angle=None)

    def with_roller(self, radius: float) -> Placement:
        """The same placement with a second roller of its own ``radius`` mm."""
        return dataclasses.replace(self, roller_radius=radius)


def pair_rig(spec: ConjugateSpec) -> Rig:
    """The rig of a conjugate pair's first cam: the disc cam's, the template's follower and roller."""
    return flat_rig(spec, disc_mount(spec.follower, spec.cam.rotation))


def _yoke(rig: Rig) -> bool:
    """Whether the rig's follower is a translating yoke (else an arm, a bell crank)."""
    return rig.mount.table.type == "translating-roller"


def swing_top(cam: Cam) -> float:
    """The follower's largest displacement over the turn (mm, or degrees of swing), spline overshoots included."""
    return cam.program.top()


def second_roller(placement: Placement, first: Cam) -> float:
    """The second roller's radius (mm): the placement's own, else the first's."""
    return placement.roller_radius or first.contact_radius


def second_arm(rig: Rig, placement: Placement) -> float:
    """The second arm's length (mm): the placement's own, else the first arm's."""
    return placement.arm_length or rig.mount.table.arm_length


def _needed(second_base: float | None) -> float:
    """The second cam's base radius (mm), which places the second roller where the placement does not fix it
    (a ValueError where it is not given then)."""
    if second_base is None:
        raise ValueError("the second cam's base radius places its roller where no yoke span or arm angle does")
    return second_base


def second_cam(rig: Rig, first: Cam, placement: Placement, second_base: float | None) -> Cam:
    """The second cam of the pair whose first cam is ``first``: its roller placed by the ``placement``'s yoke span
    or arm angle where it fixes one, else so that its base circle is ``second_base`` mm."""
    rr, top = second_roller(placement, first), swing_top(first)
    if _yoke(rig):
        span = placement.yoke_span or yoke_span(first.follower, top, _needed(second_base) + rr)
        follower: Any = YokeRoller(first.follower, span, radius=placement.roller_radius)
        prime = yoke_prime(first.follower, top, span)
    else:
        arm = second_arm(rig, placement)
        turn = (math.radians(placement.arm_angle) if placement.arm_angle is not None
                else arm_turn(first.follower, math.radians(top), arm, _needed(second_base) + rr))
        follower = ArmRoller(first.follower, turn, arm, radius=placement.roller_radius)
        prime = arm_prime(first.follower, math.radians(top), arm, turn)
    return Cam(f"{rig.name}-2", first.program, follower, prime - rr)


def build_pair(rig: Rig, base: float, placement: Placement, second_base: float | None,
               roller: float | None = None) -> tuple[Cam, Cam]:
    """Both cams with the first cam's base radius ``base``, the second's ``second_base`` (mm; where the placement
    does not fix the second roller) and rollers of ``roller`` mm (the rig's by default)."""
    first = rig.cam(base, roller)
    return dataclasses.replace(first, name=f"{rig.name}-1"), second_cam(rig, first, placement, second_base)


def placement_range(rig: Rig, first: Cam, placement: Placement,
                    second_base: float | None) -> tuple[str, float, float, float | None]:
    """Where the second roller may go: (the key that places it, its least and largest value, exclusive, and its
    value), for the key the placement fixes or else ``cam.second_base_radius`` (mm; arm angles in degrees), whose
    value is then ``second_base`` (None where not given).

    A yoke's second roller must stay beyond the shaft and its cam keep a base circle: the span more than
    d0 + s_max + sqrt(Rr^2 - e^2). An arm's second roller must stay on its side of the line from the pivot to the
    cam centre over the whole swing (there it nears the cam as the follower rises) and its cam keep a base circle.
    """
    rr, top, f = second_roller(placement, first), swing_top(first), first.follower
    if _yoke(rig):
        least = f.d0 + top + math.sqrt(max(rr * rr - f.offset**2, 0.0))
        if placement.yoke_span is not None:
            return "yoke_span", least, math.inf, placement.yoke_span
        return "second_base_radius", yoke_prime(f, top, least) - rr, math.inf, second_base
    arm, swing = second_arm(rig, placement), math.radians(top)
    c = f.pivot_distance
    near = math.acos(max(-1.0, min(1.0, (c * c + arm * arm - rr * rr) / (2 * c * arm)))) if rr > abs(c - arm) else 0.0
    if placement.arm_angle is not None:
        return ("arm_angle", math.degrees(f.rest_angle + swing + near), math.degrees(f.rest_angle + math.pi),
                placement.arm_angle)
    low = arm_prime(f, swing, arm, f.rest_angle + swing + near) - rr
    high = arm_prime(f, swing, arm, f.rest_angle + math.pi) - rr
    return "second_base_radius", low, high, second_base


def check_placement(rig: Rig, first: Cam, placement: Placement, second_base: float | None) -> None:
    """Refuse a second roller :func:`placement_range` does not allow, naming its key and the range."""
    key, low, high, given = placement_range(rig, first, placement, second_base)
    value = _needed(given)
    if low < value < high:
        return
    unit = "degrees" if key == "arm_angle" else "mm"
    span = f"> {low:.6g} {unit}" if math.isinf(high) else f"between {low:.6g} and {high:.6g} {unit}"
    why = {"yoke_span": "so the second roller stays beyond the shaft and its cam has a base circle",
           "arm_angle": "so the second roller stays on its side of the line from the pivot to the cam centre over "
                        "the swing (nearing its cam as the follower rises) and its cam has a base circle",
           "second_base_radius": "for the second roller to reach it on its side of the cam"}[key]
    raise DesignError(f"cam.{key}: must be {span}, {why} (got {value:.6g})")


def _smallest_second(rig: Rig, first: Cam, placement: Placement, limits: Limits) -> Sizing:
    """The smallest base radius of the second cam meeting the ``limits`` (its shape does not depend on the first
    cam's base radius, only on where the second roller goes, which its base circle sets here: the placement is
    taken free), by bisection within the range :func:`placement_range` allows."""
    limit, margin = limits.pressure_deg, limits.min_rho_margin
    free = placement.free()
    _, low, high, _ = placement_range(rig, first, free, None)

    def smallest(ok: Any, what: str) -> float:
        def holds(radius: float) -> bool:
            try:
                with np.errstate(divide="raise", over="raise", invalid="raise"):
                    return bool(ok(second_cam(rig, first, free, radius)))
            except (CamgenError, ValueError, ArithmeticError):
                return False

        # a yoke's second cam only grows gentler with its base circle: double until it holds; an arm's second roller
        # nears the line from the pivot at both ends of its range, so scan the range from below
        tries = (max(1.0, 2 * low) * 2.0 ** np.arange(24) if math.isinf(high)
                 else low + (high - low) * np.arange(1, SCAN) / SCAN)
        below = max(low, 0.0)
        for radius in tries:
            if holds(radius):
                return boundary(holds, radius, below)
            below = radius
        raise DesignError(f"{what}: no second base radius meets it (searched up to {below:.6g} mm)")

    pressure = smallest(lambda cam: pressure_angle_max(cam) <= limit,
                        f"cam.max_pressure_angle: the second cam's pressure-angle limit of {limit:g} degrees")
    curvature = smallest(lambda cam: profile_rho_min(cam) > margin,
                         f"cam.min_rho_margin: the second cam's curvature margin of {margin:g} mm")
    decided = "pressure angle" if pressure >= curvature else "curvature"
    return Sizing(max(pressure, curvature), decided, pressure, curvature, limit, margin)


def size_conjugate(spec: ConjugateSpec) -> tuple[Sizing, Sizing]:
    """Each cam's smallest base radius (:func:`camgen.sizing.size_cam` for the first; the second by bisection on
    its own base radius, its roller placed by it, whatever the template's ``cam.yoke_span`` or ``cam.arm_angle``)."""
    rig, limits, base = pair_rig(spec), limits_of(spec), spec.cam.base_radius
    first = size_cam(rig, limits, base if isinstance(base, float) else None)
    return first, _smallest_second(rig, rig.cam(first.base_radius_mm), Placement.of(spec.cam), limits)


def _sized(spec: ConjugateSpec, rig: Rig, placement: Placement
           ) -> tuple[float, float | None, tuple[Sizing | None, Sizing | None]]:
    """The first cam's base radius (sized where ``"auto"``), the second cam's (None where the placement fixes the
    second roller itself), and each cam's sizing where one was made."""
    base, second = spec.cam.base_radius, spec.cam.second_base_radius
    limits = limits_of(spec)
    sizes: list[Sizing | None] = [None, None]
    if base == "auto":
        sizes[0] = sized = size_cam(rig, limits)
        base = sized.base_radius_mm
    if second == "auto" or (second is None and spec.cam.base_radius == "auto"):
        sizes[1] = sized = _smallest_second(rig, rig.cam(base), placement, limits)
        second = sized.base_radius_mm
        if spec.cam.second_base_radius is None:          # equal base circles: the larger of both
            base = second = max(base, second)
    if placement.fixed:
        second = None
    elif second is None:
        second = base
    return base, second, (sizes[0], sizes[1])


def largest_pair_roller(rig: Rig, base: float, placement: Placement, second_base: float | None) -> float | None:
    """The largest roller radius (mm) with which neither cam undercuts, both rollers alike, the base circles as
    the template sets them (the pitch curves grow with the roller); None when even a vanishing one undercuts."""
    def margin(rr: float) -> float:
        try:
            cams = build_pair(rig, base, placement, second_base, rr)
        except (CamgenError, ValueError, ArithmeticError):
            return -math.inf
        return min(analyze(cam).pitch_rho_min_mm - cam.contact_radius for cam in cams)

    return largest_fitting(rig, base, margin)


def largest_second_roller(rig: Rig, base: float, placement: Placement, second_base: float | None) -> float | None:
    """The largest own radius (mm), up to the placement's second roller's, with which the second cam does not
    undercut, the first cam and the base circles as the template sets them; None when even a vanishing one
    undercuts."""
    first = rig.cam(base)

    def fits(radius: float) -> bool:
        try:
            cam = second_cam(rig, first, placement.with_roller(radius), second_base)
        except (CamgenError, ValueError, ArithmeticError):
            return False
        return analyze(cam).pitch_rho_min_mm - radius >= 0

    top = placement.roller_radius
    if top is None:
        raise ValueError("the placement's second roller has no radius of its own: see largest_pair_roller")
    if not fits(1e-6 * top):
        return None
    return top if fits(top) else boundary(fits, 1e-6 * top, top)


@dataclass(frozen=True)
class ContactCheck:
    """Both contacts over a turn: at ``angles`` cam angles each roller, placed by the follower's kinematics, against
    its cam's nominal outline (chords within a tenth of the tolerance). ``gap_mm``: per cam, the smallest and
    largest distance of the roller's circle from the outline, negative where it would cut in (mm)."""

    angles: int
    gap_mm: tuple[tuple[float, float], tuple[float, float]]

    @property
    def worst_mm(self) -> float:
        """The largest |gap| of either roller (mm): how far a contact strays from touching."""
        return max(abs(g) for pair in self.gap_mm for g in pair)


def roller_centres(pair: tuple[Cam, Cam], theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Both rollers' centres (n, 2; mm) in the cam frame at cam angles ``theta`` (rad): placed on the follower at
    its displacement s(theta) in the fixed frame, then turned back by the cam's rotation."""
    first, second = pair
    s = first.program.evaluate(theta)[0]
    f = first.follower
    if isinstance(second.follower, YokeRoller):
        one = np.column_stack([np.full_like(s, f.offset), f.d0 + s])
    else:
        arm = np.array([0.0, f.prime_radius]) - f.pivot
        one = f.pivot + rotate(np.tile(arm, (len(s), 1)), second.follower.away * np.radians(s))
    back = -f.sense * theta
    return rotate(one, back), rotate(second.follower.centre(s), back)


def contact_check(pair: tuple[Cam, Cam], outlines: tuple[Any, Any], tolerance: float) -> ContactCheck:
    """The :class:`ContactCheck` of ``pair`` against its ``outlines`` at :data:`CONTACT_ANGLES` angles."""
    import shapely

    theta = 2 * math.pi * np.arange(CONTACT_ANGLES) / CONTACT_ANGLES
    gaps = []
    for cam, centre, outline in zip(pair, roller_centres(pair, theta), outlines, strict=True):
        ring = shapely.LinearRing(outline.contour.flatten(tolerance / 10))
        inside = shapely.contains_xy(shapely.Polygon(ring), centre[:, 0], centre[:, 1])
        gap = np.where(inside, -1.0, 1.0) * shapely.distance(ring, shapely.points(centre)) - cam.contact_radius
        gaps.append((float(gap.min()), float(gap.max())))
    return ContactCheck(CONTACT_ANGLES, (gaps[0], gaps[1]))


@dataclass(frozen=True)
class ConjugateDesign:
    """Everything known about a conjugate pair before anything is written (mm, degrees).

    ``spec`` is the template's (its base radii ``"auto"`` where they were); ``cams`` the first and the second cam,
    each a complete :class:`~camgen.flat.FlatCamDesign` of the template (their parts named ``<name>-1`` and
    ``<name>-2``); ``sizing`` each cam's where a base radius was ``"auto"``; ``contact`` both contacts measured over
    a turn.
    """

    spec: ConjugateSpec
    cams: tuple[FlatCamDesign, FlatCamDesign]
    contact: ContactCheck
    sizing: tuple[Sizing | None, Sizing | None]
    warnings: tuple[str, ...]

    @property
    def cam(self) -> Cam:
        """The first cam (the follower's own roller)."""
        return self.cams[0].cam

    @property
    def second(self) -> Cam:
        return self.cams[1].cam

    def _repr_html_(self) -> str | None:
        """Jupyter shows the interactive page, as :meth:`camgen.profile.CamDesign._repr_html_` does."""
        from camgen.kinds.conjugate.outputs import conjugate_bundle
        from camgen.core.page import bundle_frame

        return bundle_frame(conjugate_bundle(self)[0])

    @property
    def analysis(self) -> CamAnalysis:
        return self.cams[0].analysis

    @property
    def tolerance(self) -> float:
        return self.spec.output.tolerance

    @property
    def written_error_mm(self) -> float:
        """A bound (mm) on the distance of either cut outline, as written, from its exact surface."""
        return max(d.written_error_mm for d in self.cams)

    def thumbnail(self, tolerance: float) -> np.ndarray:
        """The first cam's outline (mm, points within about ``tolerance``), for a family's overview."""
        return self.cams[0].outline.contour.flatten(tolerance)

    def _repr_svg_(self) -> str:
        return self.cams[0].cut._repr_svg_()


def _undercut_message(rig: Rig, base: float, placement: Placement, cams: tuple[Cam, Cam], which: int,
                      a: CamAnalysis, second_base: float | None) -> str:
    cam = cams[which]
    where = f"undercut of cam {which + 1} at {a.pitch_rho_min_at_deg:.2f} degrees: "
    if a.pitch_rho_min_mm == 0.0:
        jump = next(i for i, turn in cam.corners() if turn > 0)
        other = 2 - which
        return (f"motion[{rig.moving_segment(jump)}]: " + where + "the follower velocity jumps there, a convex corner "
                f"of its pitch curve that no roller can follow (the same jump is a concave corner on cam {other}); "
                "a conjugate pair needs a law with continuous velocity (e.g. modified-uniform)")
    own = which == 1 and placement.roller_radius is not None
    best = (largest_second_roller(rig, base, placement, second_base) if own
            else largest_pair_roller(rig, base, placement, second_base))
    fits = ((f"the largest second roller that fits cam 2 is {best:.4g} mm" if own else
             f"the largest roller that fits both cams is {best:.4g} mm") if best is not None
            else "no roller fits these base circles")
    larger = _enlarge(placement, which)
    key = "cam.second_roller_radius" if own else "follower.roller_radius"
    return (where + f"its pitch curve's radius of curvature is {a.pitch_rho_min_mm:.4g} mm, smaller than "
            f"{key} {cam.contact_radius:.4g} mm; {fits} (or {larger})")


def _enlarge(placement: Placement, which: int) -> str:
    """How to enlarge cam ``which``'s base circle, in the template's terms."""
    if which == 0:
        return "enlarge cam.base_radius"
    if placement.yoke_span is not None:
        return "lengthen cam.yoke_span"
    if placement.arm_angle is not None:
        return "widen cam.arm_angle"
    return "enlarge cam.second_base_radius"


def _drives_back(rig: Rig, first: Cam, placement: Placement, a: CamAnalysis) -> None:
    """Refuse a second cam that cannot drive the follower back somewhere (its pressure angle 90 degrees or more)."""
    if a.pressure_angle_max_deg < 90.0:
        return
    key = placement_range(rig, first, placement, None)[0]
    raise DesignError(f"cam.{key}: the second cam cannot drive the follower back near "
                      f"{a.pressure_angle_max_at_deg:.2f} degrees (its pressure angle reaches "
                      f"{a.pressure_angle_max_deg:.4g} degrees): the second roller moves along its cam there; place it "
                      "elsewhere")


def _outline_body(body: Body, finish: Finish, cam: Cam, which: int) -> tuple[Any, Any, float]:
    """A cam's nominal outline, its shapely polygon and its wall round the bore (mm); refused where the bore leaves
    no material."""
    import shapely

    tol = finish.tolerance
    outline = exact_outline(cam, tol, finish.outline_curves)
    polygon = outline_body(outline, tol)
    near = reach(polygon)
    if body.bore > 0 and not (polygon.contains(shapely.Point(0.0, 0.0)) and near > body.bore / 2):
        raise DesignError(f"cam.bore: {body.bore:.4g} mm leaves no material in cam {which + 1}; its outline comes "
                          f"within {near:.4g} mm of the centre, so the bore must be < {2 * near:.4g} mm")
    return outline, polygon, near - body.bore / 2


@dataclass(frozen=True)
class _Shared:
    """What both cams' designs share: the follower's motion (its jumps, its speed at ``cam.rpm``), the
    pressure-angle limit, the first cam (whose roller the theta = 0 tick points at), each cam's sizing and how
    both are made."""

    jumps: tuple
    speed: Speed | None
    limit: float
    timing: Cam
    sizing: tuple[Sizing | None, Sizing | None]
    finish: Finish


def _member(spec: ConjugateSpec, cam: Cam, analysis: CamAnalysis, which: int, shared: _Shared) -> FlatCamDesign:
    """One cam of the pair as a complete disc cam's design of the pair's template (whatever takes a disc cam's
    design takes it): its part named ``<name>-<1|2>`` (the cam's name), engraved (unless ``hub.engrave = false``)
    with the theta = 0 tick towards the first roller, at the same angle on both. Its holes are checked as a disc
    cam's are, drawn and as the printing clearance opens them (:func:`~camgen.profile.check_opened_holes`, naming
    the cam)."""
    hub = spec.hub
    body = Body(cam.name, spec.cam.thickness, spec.cam.bore, hub, hub.engrave or "engrave" not in hub.model_fields_set)
    finish = shared.finish
    outline, polygon, wall = _outline_body(body, finish, cam, which)
    check_holes(body, polygon, finish.tolerance)
    check_opened_holes(body, finish.allowances.clearance, outline, finish.tolerance, f"cam {which + 1}")
    marks = engraving(body, shared.timing, polygon, wall + body.bore / 2) if body.engraved else ()
    maker = ProfileMaker(body, finish, cam, False, marks, outline)
    allow = finish.allowances
    profile = Profile(body, finish, cam, analysis, shared.jumps, outline, maker.part(0.0, 0.0),
                      maker.outline(allow.kerf / 2), allow.cut(maker), allow.printed(maker), (), shared.limit, None,
                      measured_wall_mm=wall)
    return FlatCamDesign.of(profile, spec, shared.speed, shared.sizing[which])


def _warnings(spec: ConjugateSpec, placement: Placement, designs: tuple[FlatCamDesign, FlatCamDesign],
              limit: float) -> tuple[str, ...]:
    out = []
    for which, d in enumerate(designs):
        a, key = d.analysis, _enlarge(placement, which)
        if a.pressure_angle_max_deg > limit:
            out.append(f"cam {which + 1}: pressure angle peaks at {a.pressure_angle_max_deg:.2f} degrees (at "
                       f"{a.pressure_angle_max_at_deg:.2f} degrees), above the {limit:g} degree limit: {key} "
                       "or lengthen the segment")
        if spec.cam.bore > 0 and d.wall_mm < THIN_WALL:
            out.append(f"cam {which + 1}: only {d.wall_mm:.3g} mm of material between the bore and the outline")
        extent = float(np.linalg.norm(d.outline.contour.vertices, axis=1).max())
        if spec.follower.pivot_distance is not None and extent >= spec.follower.pivot_distance:
            out.append(f"cam {which + 1} reaches {extent:.4g} mm from the shaft, past the crank's pivot "
                       f"({spec.follower.pivot_distance:g} mm away): the pivot's shaft cannot pass its plane")
        concave = a.profile_concave_rho_min_mm
        if concave is not None and concave < 1.0:
            out.append(f"cam {which + 1}: concave radius of {concave:.3g} mm at {a.concave_at_deg:.2f} degrees: the "
                       "cutting tool or laser kerf must be smaller")
    for j in designs[0].jumps:
        if j.order < 3:
            out.append(f"{j.quantity} jumps at {j.at_deg:.4g} degrees: {j.consequence}")
    for i, seg in enumerate(designs[0].cam.program.segments):
        law = seg.law                                   # None on a dwell
        over = law.overshoot() if law is not None and hasattr(law, "overshoot") else 0.0
        if over > 1e-9:
            out.append(f"motion[{i}]: the spline through the points overshoots by {100 * over:.3g} % of the lift "
                       "between them; add points where it bulges")
    return tuple(out)


def _pair_speed(spec: ConjugateSpec, pair: tuple[Cam, Cam]) -> Speed | None:
    """The follower's rates at ``cam.rpm`` and, with a mass, the pair's forces (:func:`camgen.forces.pair_report`):
    no spring, so no contact check."""
    speed = rates(pair[0], spec.cam.rpm, parabolic_ratios(spec.motion))
    if speed is not None and spec.follower.mass is not None:
        f = spec.follower
        contact = None if spec.cam.material is None else Contact(
            spec.cam.material, f.material, min(spec.cam.thickness, f.roller_width or spec.cam.thickness))
        forces, speeds = drive_speed(spec, pair[0], pair=pair, contact=contact)
        speed = dataclasses.replace(speed, forces=forces, speeds=speeds)
    return speed


def design_conjugate(spec: ConjugateSpec) -> ConjugateDesign:
    """Build, check and outline the conjugate pair ``spec`` describes (sized first where its base radii are
    ``"auto"``: the spec keeps them so, the sizes are ``design.cam.base_radius`` and ``design.second.base_radius``).

    Raises :class:`DesignError` for a second roller out of its range (naming ``cam.yoke_span``, ``cam.arm_angle``
    or ``cam.second_base_radius``), a second cam that cannot drive the follower back, an undercut of either cam
    (naming the cam, the angle, both radii and the largest roller that fits both), and for a bore or holes that
    leave no material in either cam.
    """
    rig, placement = pair_rig(spec), Placement.of(spec.cam)
    base, second_base, sizing = _sized(spec, rig, placement)
    first = rig.cam(base)
    check_placement(rig, first, placement, second_base)
    pair = (dataclasses.replace(first, name=f"{spec.name}-1"), second_cam(rig, first, placement, second_base))
    analyses = (analyze(pair[0]), analyze(pair[1]))
    _drives_back(rig, first, placement, analyses[1])
    for which, a in enumerate(analyses):
        if a.undercut:
            raise DesignError(_undercut_message(rig, base, placement, pair, which, a, second_base))
    shared = _Shared(tuple(first.program.jumps()), _pair_speed(spec, pair), pressure_limit(spec), pair[0], sizing,
                     Finish.of(spec.output))
    made = (_member(spec, pair[0], analyses[0], 0, shared), _member(spec, pair[1], analyses[1], 1, shared))
    warnings = _warnings(spec, placement, made, shared.limit)
    designs = (dataclasses.replace(made[0], warnings=warnings), dataclasses.replace(made[1], warnings=warnings))
    contact = contact_check(pair, (designs[0].outline, designs[1].outline), spec.output.tolerance)
    return ConjugateDesign(spec, designs, contact, sizing, designs[0].warnings)
