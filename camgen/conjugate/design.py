"""A conjugate pair from a spec: both cams built, checked and outlined, as a matched pair. No I/O.

The first cam is the disc cam of the template (the follower's own roller, prime radius base radius + roller
radius at rest); the second cam's pitch curve is the second roller's path in the same cam frame (see
:mod:`camgen.conjugate.followers`), sharing the first cam's motion program. Where the template does not place
the second roller (``cam.yoke_span``, ``cam.arm_angle``) it is placed so that the second cam's base circle (the
second roller's nearest approach less its radius) is ``cam.second_base_radius``, by default the first cam's.

Both cams are checked alike (:func:`camgen.analysis.analyze`): pressure angle (the second cam's measured from
the way it drives the follower back), convex radius of curvature against the roller (undercut, refused naming
the cam, the angle, both radii and the largest roller that fits both cams) and a bore that leaves material.
The second cam must drive the follower back everywhere: its pressure angle below 90 degrees (a second roller
placed where it would move away from its cam on a rise is refused naming the key that placed it).

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
from camgen.cam import Cam, build_cam
from camgen.conjugate.followers import ArmRoller, YokeRoller, arm_prime, arm_turn, yoke_prime, yoke_span
from camgen.core.errors import CamgenError, DesignError
from camgen.core.parts import Allowances
from camgen.profile import CamDesign, _body, _check_holes, _curves, _engraving, _Profile, _reach, _speed, known_wall
from camgen.forces import Contact, drive_speed
from camgen.followers.base import rotate
from camgen.numeric import boundary
from camgen.outline import exact_outline
from camgen.sizing import Sizing, pressure_limit, size_cam
from camgen.spec import CamSpec

#: the cam angles (per turn) at which both contacts are measured against the outlines
CONTACT_ANGLES = 720
#: how many second base radii an arm's range is scanned at for the smallest meeting the limits
SCAN = 64
#: thinnest wall between the bore and an outline before a warning (mm), as for a disc cam
THIN_WALL = 2.0


def swing_top(cam: Cam) -> float:
    """The follower's largest displacement over the turn (mm, or degrees of swing), spline overshoots included."""
    segments = cam.program.segments
    return cam.program.peak(lambda i, t: segments[i].evaluate(t)[0])[0]


def second_roller(spec: CamSpec, first: Cam) -> float:
    """The second roller's radius (mm): ``cam.second_roller_radius``, else the first's."""
    return spec.cam.second_roller_radius or first.contact_radius


def second_cam(spec: CamSpec, first: Cam, second_base: float | None) -> Cam:
    """The second cam of the pair whose first cam is ``first``: its roller placed by ``cam.yoke_span`` or
    ``cam.arm_angle`` where the template gives them, else so that its base circle is ``second_base`` mm."""
    rr, top = second_roller(spec, first), swing_top(first)
    if spec.follower.type == "translating-roller":
        span = spec.cam.yoke_span or yoke_span(first.follower, top, second_base + rr)
        follower: Any = YokeRoller(first.follower, span, radius=spec.cam.second_roller_radius)
        prime = yoke_prime(first.follower, top, span)
    else:
        arm = spec.cam.second_arm_length or spec.follower.arm_length
        turn = (math.radians(spec.cam.arm_angle) if spec.cam.arm_angle is not None
                else arm_turn(first.follower, math.radians(top), arm, second_base + rr))
        follower = ArmRoller(first.follower, turn, arm, radius=spec.cam.second_roller_radius)
        prime = arm_prime(first.follower, math.radians(top), arm, turn)
    return Cam(f"{spec.name}-2", first.program, follower, prime - rr, spec.cam.thickness, spec.cam.bore)


def build_pair(spec: CamSpec, base: float, second_base: float | None, roller: float | None = None) -> tuple[Cam, Cam]:
    """Both cams with the first cam's base radius ``base``, the second's ``second_base`` (mm; where the template
    does not place the second roller) and rollers of ``roller`` mm (the template's by default)."""
    first = build_cam(spec, roller_radius=roller, base_radius=base)
    return dataclasses.replace(first, name=f"{spec.name}-1"), second_cam(spec, first, second_base)


def placement_range(spec: CamSpec, first: Cam, second_base: float | None) -> tuple[str, float, float, float]:
    """Where the second roller may go: (the key that places it, its least and largest value, exclusive, and its
    value), for the key the template gives or else ``cam.second_base_radius`` (mm; arm angles in degrees), whose
    value is then ``second_base``.

    A yoke's second roller must stay beyond the shaft and its cam keep a base circle: the span more than
    d0 + s_max + sqrt(Rr^2 - e^2). An arm's second roller must stay on its side of the line from the pivot to the
    cam centre over the whole swing (there it nears the cam as the follower rises) and its cam keep a base circle.
    """
    rr, top, f = second_roller(spec, first), swing_top(first), first.follower
    if spec.follower.type == "translating-roller":
        least = f.d0 + top + math.sqrt(max(rr * rr - f.offset**2, 0.0))
        if spec.cam.yoke_span is not None:
            return "yoke_span", least, math.inf, spec.cam.yoke_span
        return "second_base_radius", yoke_prime(f, top, least) - rr, math.inf, second_base
    arm, swing = spec.cam.second_arm_length or spec.follower.arm_length, math.radians(top)
    c = f.pivot_distance
    near = math.acos(max(-1.0, min(1.0, (c * c + arm * arm - rr * rr) / (2 * c * arm)))) if rr > abs(c - arm) else 0.0
    if spec.cam.arm_angle is not None:
        return ("arm_angle", math.degrees(f.rest_angle + swing + near), math.degrees(f.rest_angle + math.pi),
                spec.cam.arm_angle)
    low = arm_prime(f, swing, arm, f.rest_angle + swing + near) - rr
    high = arm_prime(f, swing, arm, f.rest_angle + math.pi) - rr
    return "second_base_radius", low, high, second_base


def check_placement(spec: CamSpec, first: Cam, second_base: float | None) -> None:
    """Refuse a second roller :func:`placement_range` does not allow, naming its key and the range."""
    key, low, high, value = placement_range(spec, first, second_base)
    if low < value < high:
        return
    unit = "degrees" if key == "arm_angle" else "mm"
    span = f"> {low:.6g} {unit}" if math.isinf(high) else f"between {low:.6g} and {high:.6g} {unit}"
    why = {"yoke_span": "so the second roller stays beyond the shaft and its cam has a base circle",
           "arm_angle": "so the second roller stays on its side of the line from the pivot to the cam centre over "
                        "the swing (nearing its cam as the follower rises) and its cam has a base circle",
           "second_base_radius": "for the second roller to reach it on its side of the cam"}[key]
    raise DesignError(f"cam.{key}: must be {span}, {why} (got {value:.6g})")


def _smallest_second(spec: CamSpec, first: Cam) -> Sizing:
    """The smallest base radius of the second cam meeting the pressure-angle limit and the curvature margin (its
    shape does not depend on the first cam's base radius, only on where the second roller goes), by bisection
    within the range :func:`placement_range` allows."""
    limit, margin = pressure_limit(spec), spec.cam.min_rho_margin
    _, low, high, _ = placement_range(spec, first, None)

    def smallest(ok: Any, what: str) -> float:
        def holds(radius: float) -> bool:
            try:
                with np.errstate(divide="raise", over="raise", invalid="raise"):
                    return bool(ok(second_cam(spec, first, radius)))
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


def size_conjugate(spec: CamSpec) -> tuple[Sizing, Sizing]:
    """Each cam's smallest base radius (:func:`camgen.sizing.size_cam` for the first; the second by bisection on
    its own base radius, its roller placed by it, whatever the template's ``cam.yoke_span`` or ``cam.arm_angle``)."""
    first = size_cam(spec)
    free = spec.model_copy(update={"cam": spec.cam.model_copy(update={"yoke_span": None, "arm_angle": None})})
    return first, _smallest_second(free, build_cam(spec, base_radius=first.base_radius_mm))


def _sized(spec: CamSpec) -> tuple[CamSpec, float | None, tuple[Sizing | None, Sizing | None]]:
    """The spec at its base radius (sized where ``"auto"``), the second cam's base radius (None where the template
    places the second roller itself), and each cam's sizing where one was made."""
    base, second = spec.cam.base_radius, spec.cam.second_base_radius
    sizes: list[Sizing | None] = [None, None]
    if base == "auto":
        sizes[0] = size_cam(spec)
        base = sizes[0].base_radius_mm
    if second == "auto" or (second is None and spec.cam.base_radius == "auto"):
        sizes[1] = _smallest_second(spec, build_cam(spec, base_radius=base))
        second = sizes[1].base_radius_mm
        if spec.cam.second_base_radius is None:          # equal base circles: the larger of both
            base = second = max(base, second)
    cam = spec.cam.model_copy(update={"base_radius": base})
    if spec.cam.yoke_span is not None or spec.cam.arm_angle is not None:
        second = None
    elif second is None:
        second = base
    return spec.model_copy(update={"cam": cam}), second, (sizes[0], sizes[1])


def largest_pair_roller(spec: CamSpec, second_base: float | None) -> float | None:
    """The largest roller radius (mm) with which neither cam undercuts, both rollers alike, the base circles as
    the template sets them (the pitch curves grow with the roller); None when even a vanishing one undercuts."""
    def margin(rr: float) -> float:
        try:
            cams = build_pair(spec, spec.cam.base_radius, second_base, rr)
        except (CamgenError, ValueError, ArithmeticError):
            return -math.inf
        return min(analyze(cam).pitch_rho_min_mm - cam.contact_radius for cam in cams)

    return largest_fitting(spec, margin)


def largest_second_roller(spec: CamSpec, second_base: float | None) -> float | None:
    """The largest own radius (mm), up to the template's ``cam.second_roller_radius``, with which the second cam
    does not undercut, the first cam and the base circles as the template sets them; None when even a vanishing
    one undercuts."""
    first = build_cam(spec)

    def fits(radius: float) -> bool:
        own = spec.model_copy(update={"cam": spec.cam.model_copy(update={"second_roller_radius": radius})})
        try:
            cam = second_cam(own, first, second_base)
        except (CamgenError, ValueError, ArithmeticError):
            return False
        return analyze(cam).pitch_rho_min_mm - radius >= 0

    top = spec.cam.second_roller_radius
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

    ``spec`` is the template's (base radii sized where ``"auto"``); ``cams`` the first and the second cam, each a
    complete :class:`~camgen.profile.CamDesign` (named ``<name>-1`` and ``<name>-2``); ``sizing`` each cam's where
    a base radius was ``"auto"``; ``contact`` both contacts measured over a turn.
    """

    spec: CamSpec
    cams: tuple[CamDesign, CamDesign]
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
        from camgen.conjugate.outputs import conjugate_bundle
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


def _undercut_message(spec: CamSpec, cams: tuple[Cam, Cam], which: int, a: CamAnalysis,
                      second_base: float | None) -> str:
    cam = cams[which]
    where = f"undercut of cam {which + 1} at {a.pitch_rho_min_at_deg:.2f} degrees: "
    if a.pitch_rho_min_mm == 0.0:
        jump = next(i for i, turn in cam.corners() if turn > 0)
        other = 2 - which
        return (f"motion[{spec.moving_segment(jump)}]: " + where + "the follower velocity jumps there, a convex corner "
                f"of its pitch curve that no roller can follow (the same jump is a concave corner on cam {other}); "
                "a conjugate pair needs a law with continuous velocity (e.g. modified-uniform)")
    own = which == 1 and spec.cam.second_roller_radius is not None
    best = largest_second_roller(spec, second_base) if own else largest_pair_roller(spec, second_base)
    fits = ((f"the largest second roller that fits cam 2 is {best:.4g} mm" if own else
             f"the largest roller that fits both cams is {best:.4g} mm") if best is not None
            else "no roller fits these base circles")
    larger = _enlarge(spec, which)
    key = "cam.second_roller_radius" if own else "follower.roller_radius"
    return (where + f"its pitch curve's radius of curvature is {a.pitch_rho_min_mm:.4g} mm, smaller than "
            f"{key} {cam.contact_radius:.4g} mm; {fits} (or {larger})")


def _enlarge(spec: CamSpec, which: int) -> str:
    """How to enlarge cam ``which``'s base circle, in the template's terms."""
    if which == 0:
        return "enlarge cam.base_radius"
    if spec.cam.yoke_span is not None:
        return "lengthen cam.yoke_span"
    if spec.cam.arm_angle is not None:
        return "widen cam.arm_angle"
    return "enlarge cam.second_base_radius"


def _drives_back(spec: CamSpec, first: Cam, a: CamAnalysis) -> None:
    """Refuse a second cam that cannot drive the follower back somewhere (its pressure angle 90 degrees or more)."""
    if a.pressure_angle_max_deg < 90.0:
        return
    key = placement_range(spec, first, None)[0]
    raise DesignError(f"cam.{key}: the second cam cannot drive the follower back near "
                      f"{a.pressure_angle_max_at_deg:.2f} degrees (its pressure angle reaches "
                      f"{a.pressure_angle_max_deg:.4g} degrees): the second roller moves along its cam there; place it "
                      "elsewhere")


def _outline_body(spec: CamSpec, cam: Cam, which: int) -> tuple[Any, Any, float]:
    """A cam's nominal outline, its shapely polygon and its wall round the bore (mm); refused where the bore leaves
    no material."""
    import shapely

    tol = spec.output.tolerance
    outline = exact_outline(cam, tol, _curves(spec))
    body = _body(outline, tol)
    near = _reach(body)
    if spec.cam.bore > 0 and not (body.contains(shapely.Point(0.0, 0.0)) and near > spec.cam.bore / 2):
        raise DesignError(f"cam.bore: {spec.cam.bore:.4g} mm leaves no material in cam {which + 1}; its outline comes "
                          f"within {near:.4g} mm of the centre, so the bore must be < {2 * near:.4g} mm")
    return outline, body, near - spec.cam.bore / 2


@dataclass(frozen=True)
class _Shared:
    """What both cams' designs share: the follower's motion (its jumps, its speed at ``cam.rpm``), the
    pressure-angle limit, the first cam (whose roller the theta = 0 tick points at) and each cam's sizing."""

    jumps: tuple
    speed: dict[str, Any] | None
    limit: float
    timing: Cam
    sizing: tuple[Sizing | None, Sizing | None]


def _member(spec: CamSpec, cam: Cam, analysis: CamAnalysis, which: int, shared: _Shared) -> CamDesign:
    """One cam of the pair as a complete disc cam's design (its spec the template's as a disc, so whatever takes a
    disc cam's design takes it): its part named ``<name>-<1|2>``, engraved with the theta = 0 tick towards the first
    roller, at the same angle on both."""
    own = spec.model_copy(update={"name": cam.name, "cam": spec.cam.model_copy(
        update={"kind": "disc", "base_radius": cam.base_radius})})         # a disc cam's design, as far as it goes
    outline, body, wall = _outline_body(own, cam, which)
    _check_holes(own, body, own.output.tolerance)
    engrave = own.hub.engrave or "engrave" not in own.hub.model_fields_set
    near = wall + own.cam.bore / 2
    maker = _Profile(own, cam, False, _engraving(own, shared.timing, body, near) if engrave else (), outline)
    allow = Allowances(own.output.kerf, own.output.clearance, "output.kerf", own.output.elephant_foot)
    return known_wall(CamDesign(own, cam, analysis, shared.jumps, outline, maker.part(0.0, 0.0),
                                maker.outline(allow.kerf / 2), allow.cut(maker), allow.printed(maker), allow, (),
                                shared.limit, None, shared.speed, shared.sizing[which]), wall)


def _warnings(spec: CamSpec, designs: tuple[CamDesign, CamDesign], limit: float) -> tuple[str, ...]:
    out = []
    for which, d in enumerate(designs):
        a, key = d.analysis, _enlarge(spec, which)
        if a.pressure_angle_max_deg > limit:
            out.append(f"cam {which + 1}: pressure angle peaks at {a.pressure_angle_max_deg:.2f} degrees (at "
                       f"{a.pressure_angle_max_at_deg:.2f} degrees), above the {limit:g} degree limit: {key} "
                       "or lengthen the segment")
        if spec.cam.bore > 0 and d.wall_mm < THIN_WALL:
            out.append(f"cam {which + 1}: only {d.wall_mm:.3g} mm of material between the bore and the outline")
        reach = float(np.linalg.norm(d.outline.contour.vertices, axis=1).max())
        if spec.follower.pivot_distance is not None and reach >= spec.follower.pivot_distance:
            out.append(f"cam {which + 1} reaches {reach:.4g} mm from the shaft, past the crank's pivot "
                       f"({spec.follower.pivot_distance:g} mm away): the pivot's shaft cannot pass its plane")
        concave = a.profile_concave_rho_min_mm
        if concave is not None and concave < 1.0:
            out.append(f"cam {which + 1}: concave radius of {concave:.3g} mm at {a.concave_at_deg:.2f} degrees: the "
                       "cutting tool or laser kerf must be smaller")
    for j in designs[0].jumps:
        if j.order < 3:
            out.append(f"{j.quantity} jumps at {j.at_deg:.4g} degrees: {j.consequence}")
    for i, seg in enumerate(designs[0].cam.program.segments):
        over = seg.law.overshoot() if hasattr(seg.law, "overshoot") else 0.0
        if over > 1e-9:
            out.append(f"motion[{i}]: the spline through the points overshoots by {100 * over:.3g} % of the lift "
                       "between them; add points where it bulges")
    return tuple(out)


def _pair_speed(spec: CamSpec, pair: tuple[Cam, Cam]) -> dict[str, Any] | None:
    """The follower's rates at ``cam.rpm`` and, with a mass, the pair's forces (:func:`camgen.forces.pair_report`):
    no spring, so no contact check."""
    speed = _speed(spec, pair[0], rates_only=True)
    if speed is not None and spec.follower.mass is not None:
        f = spec.follower
        contact = None if spec.cam.material is None else Contact(
            spec.cam.material, f.material, min(spec.cam.thickness, f.roller_width or spec.cam.thickness))
        speed = {**speed, **drive_speed(spec, pair[0], pair=pair, contact=contact)}
    return speed


def design_conjugate(spec: CamSpec) -> ConjugateDesign:
    """Build, check and outline the conjugate pair ``spec`` describes.

    Raises :class:`DesignError` for a second roller out of its range (naming ``cam.yoke_span``, ``cam.arm_angle``
    or ``cam.second_base_radius``), a second cam that cannot drive the follower back, an undercut of either cam
    (naming the cam, the angle, both radii and the largest roller that fits both), and for a bore or holes that
    leave no material in either cam.
    """
    spec, second_base, sizing = _sized(spec)
    first = build_cam(spec)
    check_placement(spec, first, second_base)
    pair = (dataclasses.replace(first, name=f"{spec.name}-1"), second_cam(spec, first, second_base))
    analyses = (analyze(pair[0]), analyze(pair[1]))
    _drives_back(spec, first, analyses[1])
    for which, a in enumerate(analyses):
        if a.undercut:
            raise DesignError(_undercut_message(spec, pair, which, a, second_base))
    shared = _Shared(tuple(first.program.jumps()), _pair_speed(spec, pair), pressure_limit(spec), pair[0], sizing)
    designs = tuple(_member(spec, cam, a, which, shared)
                    for which, (cam, a) in enumerate(zip(pair, analyses, strict=True)))
    designs = tuple(known_wall(dataclasses.replace(d, warnings=_warnings(spec, designs, shared.limit)), d.wall_mm)
                    for d in designs)
    contact = contact_check(pair, (designs[0].outline, designs[1].outline), spec.output.tolerance)
    return ConjugateDesign(spec, designs, contact, sizing, designs[0].warnings)
