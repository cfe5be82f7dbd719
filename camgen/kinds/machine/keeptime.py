"""A coupling's ``keep_time``: the cam that makes its four-bar keep time, designed from the targets its tracer must
reach at given times, or from a program its rocker must follow (rise, dwell, return in degrees).

The machine template gives the cam's body and follower (``[cams.template.cam]``, ``[cams.template.follower]``) but no
motion, and the coupling no ``rest``: before the machine is validated, :func:`expand` inverts the linkage (the crank
angle that puts the tracer on each target, or the rocker at each point of its program), makes the crank's motion a
smooth periodic function of the shaft's angle through those points (:mod:`camgen.kinds.machine.timing`: quintic
pieces, continuous to the acceleration, monotone between the points) and writes it into the raw template as the
cam's ``motion`` (rise, dwell and return segments of the polynomial law), the cam mount's ``phase`` (where the
program starts: the crank's lowest angle) and the coupling's ``rest`` (that angle). The machine then designs that cam
by its kind with its own checks and drives the four-bar with it, as any other. :func:`timing_report` checks the
built machine against the targets: the linkage solved at the follower's swing from the built cam's program.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from collections.abc import Callable
from typing import Any, Literal

import numpy as np
from pydantic import Field, model_validator

from camgen.core.errors import SpecError
from camgen.core.spec import MAX_LENGTH_MM, Model, notes, unit, validate
from camgen.kinds.machine import timing
from camgen.spec import SegmentTable
from linkgen.kinematics.fourbar import Assembly, FourBar

#: the most targets a coupling's keep_time may give, and the most segments an output's program may have
MAX_TARGETS, MAX_OUTPUT_SEGMENTS = 360, 100
#: the largest swing (degrees) a follower's arm may make (camgen's limit on an arm's lift)
MAX_SWING_DEG = 90.0


class KeepTime(Model):
    """A coupling's timing: targets its linkage's tracer must reach at given shaft angles, or a program its rocker
    must follow; the machine designs the cam's motion, its phase and the coupling's rest from it."""

    targets: list[list[float]] | None = Field(
        None, min_length=2, max_length=MAX_TARGETS, description="the tracer's targets in time order, each [x, y, "
        "angle] or [x, y, angle, dwell]: a point in the linkage's frame (its crank pivot at the origin, its rocker "
        "pivot on +x; with ground_pivots, in theirs), the cam shaft's angle at which the tracer is there and how "
        "long it holds there",
        json_schema_extra=unit("mm (x, y), degrees (angle, dwell)",
                               allowed=f"|x|, |y| <= {MAX_LENGTH_MM:g}; angles increasing from 0 to below 360; a "
                               "dwell >= 0 ending before the next target's angle; each point within tolerance of the "
                               "tracer's path on the linkage's assembly", absent="give targets or output"))
    output: list[SegmentTable] | None = Field(
        None, min_length=1, max_length=MAX_OUTPUT_SEGMENTS, description="the rocker's program instead of targets: "
        "rise, dwell and return segments as a cam's [[motion]] takes them, lifts in degrees of the rocker, from the "
        "cam shaft's angle 0", json_schema_extra=notes(allowed="angles adding up to 360; the rocker kept within its "
                                                       "swing on one stroke of the crank",
                                                       absent="give targets or output"))
    ground_pivots: tuple[tuple[float, float], tuple[float, float]] | None = Field(
        None, description="targets: the linkage's crank pivot and rocker pivot in the targets' frame, as linkgen "
        "synthesize's rows give them (ground_pivots); without it the targets are in the linkage's own frame",
        json_schema_extra=unit("mm", allowed=f"|x|, |y| <= {MAX_LENGTH_MM:g}, as far apart as linkage.ground (to "
                               "1e-6 mm)", absent="the linkage's own frame: [[0, 0], [ground, 0]]"))
    start: float | None = Field(None, ge=-360, le=360, description="output: the rocker's angle (from the ground "
                                "line, counter-clockwise) where its program is 0",
                                json_schema_extra=unit("degrees", absent="required with output"))
    turn: Literal["ccw", "cw"] = Field("ccw", description="output: the way a rise turns the rocker, counter-clockwise "
                                       "or clockwise")
    step: float = Field(2.0, ge=0.5, le=30.0, description="output: the cam shaft's angle between two points of the "
                        "program the crank's motion passes through exactly", json_schema_extra=unit("degrees"))
    stroke: Literal["transmission", "swing"] = Field("transmission", description="output: which of the crank's two "
                                                     "strokes that turn the rocker so it takes: the one whose "
                                                     "transmission angle stays farthest from a toggle, or the one "
                                                     "whose crank swings least")
    tolerance: float = Field(0.5, gt=0, le=10.0, description="targets: how far a target may lie from the tracer's "
                             "path (the tracer reaches the path's nearest point at the target's time)",
                             json_schema_extra=unit("mm"))

    @model_validator(mode="after")
    def _one_way(self) -> KeepTime:
        if (self.targets is None) == (self.output is None):
            raise ValueError("targets: give targets ([[x, y, angle], ...]) or output (the rocker's program), "
                             "one of them")
        if self.output is not None:
            if self.start is None:
                raise ValueError("start: required with output: the rocker's angle (degrees) where its program is 0")
            total = sum(seg.angle for seg in self.output)
            if abs(total - 360.0) > 1e-9:
                raise ValueError(f"output: segment angles add up to {total:.6g} degrees; they must add up to 360")
            if self.ground_pivots is not None:
                raise ValueError("ground_pivots: only with targets (an output's program is the rocker's own angle)")
            return self
        if self.start is not None:
            raise ValueError("start: only with output (the rocker's program)")
        if self.ground_pivots is not None and any(abs(v) > MAX_LENGTH_MM for xy in self.ground_pivots for v in xy):
            raise ValueError(f"ground_pivots: each coordinate within +-{MAX_LENGTH_MM:g} mm")
        rows = self.targets or []
        for i, row in enumerate(rows):
            if len(row) not in (3, 4):
                raise ValueError(f"targets[{i}]: a target is [x, y, angle] or [x, y, angle, dwell] (got {len(row)} "
                                 "numbers)")
            if any(abs(v) > MAX_LENGTH_MM for v in row[:2]):
                raise ValueError(f"targets[{i}]: x and y must lie within +-{MAX_LENGTH_MM:g} mm (got {row[0]:g}, "
                                 f"{row[1]:g})")
            if not 0.0 <= row[2] < 360.0:
                raise ValueError(f"targets[{i}]: its angle must be >= 0 and < 360 degrees (got {row[2]:g})")
            if len(row) == 4 and not 0.0 <= row[3] < 360.0:
                raise ValueError(f"targets[{i}]: its dwell must be >= 0 and < 360 degrees (got {row[3]:g})")
            if i and row[2] <= rows[i - 1][2]:
                raise ValueError(f"targets[{i}]: its angle {row[2]:g} degrees must come after targets[{i - 1}]'s "
                                 f"({rows[i - 1][2]:g}): give the targets in time order")
        for i, row in enumerate(rows):
            nxt = rows[i + 1][2] if i + 1 < len(rows) else rows[0][2] + 360.0
            if (end := row[2] + _dwell(row)) >= nxt:
                raise ValueError(f"targets[{i}]: its dwell of {_dwell(row):g} degrees runs to {end:g}, not before "
                                 f"the next target's angle {nxt:g}")
        return self


def _dwell(row: list[float]) -> float:
    return row[3] if len(row) == 4 else 0.0


@dataclass(frozen=True)
class Plan:
    """A coupling's timing worked out: the cam program's ``phase`` (degrees of its shaft), the crank's ``rest``
    (degrees, its lowest angle), the ``motion`` entries, and what they came from: each target's nearest point of the
    path (targets), or the points of the rocker's program and the crank's stroke (output)."""

    phase: float
    rest: float
    motion: list[dict[str, Any]]
    reaches: tuple[timing.Reach, ...] = ()
    inverse: timing.Inverse | None = None
    theta4: np.ndarray | None = None
    stroke: str = ""


def four_bar(table: Any) -> FourBar:
    """The kinematic four-bar of a linkgen ``[linkage]`` table (a four-bar's)."""
    return FourBar(table.ground, table.crank, table.coupler, table.rocker, table.point_distance,
                   math.radians(table.point_angle))


def plan(keep: KeepTime, table: Any) -> Plan:
    """The cam program that makes the four-bar of ``table`` keep the time ``keep`` asks for.

    Raises
    ------
    SpecError
        Naming the key under ``keep_time``: a target farther than ``tolerance`` from the tracer's path (with where
        the other assembly passes it, if it does), targets on two of the crank's ranges (the crank would pass a
        toggle), a swing of 90 degrees or more, an output program the rocker cannot follow on one stroke.
    """
    fb = four_bar(table)
    if keep.targets is not None:
        return _targets(keep, fb, table.assembly)
    return _output(keep, fb, table.assembly)


def frame(keep: KeepTime, fb: FourBar) -> tuple[np.ndarray, float]:
    """Where the linkage's own frame lies in the targets' (its crank pivot, mm, and its ground line's angle,
    radians), from ``keep.ground_pivots``; a refusal naming them where they lie farther apart or nearer than the
    linkage's ground (by more than 1e-6 mm)."""
    if keep.ground_pivots is None:
        return np.zeros(2), 0.0
    o2, o4 = (np.asarray(p, dtype=float) for p in keep.ground_pivots)
    apart = float(np.hypot(*(o4 - o2)))
    if abs(apart - fb.ground) > 1e-6:
        raise SpecError(f"the pivots lie {apart:.9g} mm apart; this linkage's ground is {fb.ground:.9g} mm (they "
                        "must agree within 1e-6 mm)", "ground_pivots")
    return o2, math.atan2(*(o4 - o2)[::-1])


def to_linkage(points: np.ndarray, origin: np.ndarray, angle: float) -> np.ndarray:
    """Points (n, 2) of the targets' frame in the linkage's own (mm): turned by -angle about ``origin``."""
    c, s = math.cos(angle), math.sin(angle)
    d = np.atleast_2d(points) - origin
    return np.column_stack((c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]))


def from_linkage(points: np.ndarray, origin: np.ndarray, angle: float) -> np.ndarray:
    """Points (n, 2) of the linkage's own frame in the targets' (mm): turned by angle, then moved to ``origin``."""
    c, s = math.cos(angle), math.sin(angle)
    p = np.atleast_2d(points)
    return np.column_stack((c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1])) + origin


def _targets(keep: KeepTime, fb: FourBar, assembly: Assembly) -> Plan:
    rows = keep.targets or []
    local = to_linkage(np.array([r[:2] for r in rows]), *frame(keep, fb))
    reaches: list[timing.Reach] = []
    other: Assembly = "crossed" if assembly == "open" else "open"
    for i, row in enumerate(rows):
        reach = timing.nearest(fb, assembly, local[i])
        if reach.distance > keep.tolerance:
            there = timing.nearest(fb, other, local[i])
            hint = (f"; only the {other} assembly passes it (crank at {there.crank_deg:.6g} degrees): reaching it "
                    "would need the crank to reverse through a toggle" if there.distance <= keep.tolerance else "")
            raise SpecError(f"the tracer comes no nearer than {reach.distance:.4g} mm to ({row[0]:g}, {row[1]:g}) on "
                            f"the {assembly} assembly (keep_time.tolerance {keep.tolerance:g} mm){hint}",
                            f"targets[{i}]")
        if reach.range_index != reaches[0].range_index if reaches else False:
            raise SpecError(f"the tracer passes it at crank angle {reach.crank_deg:.6g} degrees, in another range of "
                            f"the crank than targets[0] ({reaches[0].crank_deg:.6g} degrees): getting there would need "
                            "the crank to reverse through a toggle", f"targets[{i}]")
        reaches.append(reach)
    crank = timing.unwrapped([r.crank_deg for r in reaches], fb.input_ranges() is None)
    span = float(np.ptp(crank))
    if span >= MAX_SWING_DEG:
        raise SpecError(f"the crank must swing through {span:.4g} degrees (from {crank.min():.6g} to "
                        f"{crank.max():.6g}) to reach them all; a follower's arm swings less than 90: choose targets "
                        "nearer together on the tracer's path", "targets")
    if span <= timing.SAME_DEG:
        raise SpecError("every target is the same point of the tracer's path: the cam would not move", "targets")
    pieces = timing.through_targets([r[2] for r in rows], crank.tolist(), [_dwell(r) for r in rows])
    phase, rest, motion = timing.program(pieces)
    return Plan(phase, rest, motion, reaches=tuple(reaches))


def output_program(keep: KeepTime) -> Any:
    """The rocker's program (a camgen :class:`~camgen.program.Program`, in degrees of the rocker) of ``keep.output``;
    a law's error named under ``output[i]``."""
    from camgen.laws import make_law
    from camgen.program import build_program

    steps = []
    for i, seg in enumerate(keep.output or []):
        law = None
        if seg.type != "dwell":
            params = seg.law_params()
            if params.get("form") == "drafted":
                raise SpecError("the drafted form needs a cam's prime radius; give the blended form",
                                f"output[{i}].form")
            if seg.law == "table":
                params.update(beta_deg=seg.angle, lift=seg.lift, falling=seg.type == "return")
            try:
                law = make_law(str(seg.law), **params)
            except SpecError as exc:
                raise exc.under(f"output[{i}]") from None
        steps.append((seg.type, seg.angle, seg.lift or 0.0, law))
    try:
        return build_program(steps)
    except SpecError as exc:
        raise SpecError(exc.detail, (exc.field or "motion").replace("motion", "output", 1)) from None


def _output(keep: KeepTime, fb: FourBar, assembly: Assembly) -> Plan:
    prog = output_program(keep)
    times, before, after = [], [], []
    for i, seg in enumerate(prog.segments):
        count = 1 if seg.kind == "dwell" else max(1, math.ceil(math.degrees(seg.beta) / keep.step - 1e-9))
        for j in range(count):
            times.append(seg.start + seg.beta * j / count)
            before.append(i if j else (i - 1) % len(prog.segments))
            after.append(i)
    times.append(2 * math.pi)
    before.append(len(prog.segments) - 1)
    after.append(0)
    t = np.array(times)
    left = np.stack([prog.segments[k].evaluate(np.array([x]))[:, 0] for k, x in zip(before, t, strict=True)], 1)
    right = np.stack([prog.segments[k].evaluate(np.array([x % (2 * math.pi)]))[:, 0]
                      for k, x in zip(after, t, strict=True)], 1)
    sign = 1.0 if keep.turn == "ccw" else -1.0
    per = math.pi / 180.0                                  # per radian of shaft -> per degree
    start = float(keep.start or 0.0)
    theta4 = start + sign * right[0]
    rates = (sign * left[1] * per, sign * left[2] * per ** 2, sign * right[1] * per, sign * right[2] * per ** 2)
    try:
        inverse, stroke = timing.rocker_inverse(fb, assembly, np.degrees(t), theta4, rates, keep.stroke)
    except SpecError as exc:
        raise SpecError(f"the rocker's program (start {start:g} + its lifts) cannot be followed: {exc.detail}",
                        "start") from None
    pieces = inverse.pieces()
    span = float(np.ptp(inverse.crank))
    if span >= MAX_SWING_DEG:
        raise SpecError(f"the crank must swing through {span:.4g} degrees for this program; a follower's arm swings "
                        "less than 90: give the rocker a smaller swing or the linkage a longer crank", "output")
    for p in pieces:
        if not p.monotone():
            raise SpecError(f"between shaft angles {p.t0:.6g} and {p.t1:.6g} degrees the crank's quintic through the "
                            "points turns back (the points are too far apart for this motion): give a smaller step",
                            "step")
    phase, rest, motion = timing.program(pieces)
    return Plan(phase, rest, motion, inverse=inverse, theta4=theta4, stroke=stroke)


def _same(given: Any, made: float) -> bool:
    """Whether a value the template gives is the one keep_time makes (a spec validated again gives it back)."""
    return isinstance(given, (int, float)) and not isinstance(given, bool) and abs(given - made) <= 1e-9


def _names(mounts: Any) -> list[Any]:
    return [m.get("name") if isinstance(m, dict) else None for m in mounts] if isinstance(mounts, list) else []


def expand(data: Any, read: Callable[[Any, str, str], dict[str, Any]]) -> Any:
    """The raw machine template ``data`` with every coupling's ``keep_time`` worked in (see the module): its cam's
    ``motion``, its cam mount's ``phase`` and its own ``rest`` set; ``data`` itself when no coupling has one or the
    tables are not yet the lists and tables they must be (validation then says so). ``read(given, where,
    product)`` reads a mount's ``template`` (inline or a file's path) as the machine does.

    Raises
    ------
    SpecError
        Naming the key: a bad ``keep_time`` (under ``couplings[i].keep_time``), a cam or linkage that does not exist,
        a linkage that is not a four-bar driven by its crank, or a ``rest``, ``phase`` or cam ``motion`` the template
        gives that is not the one keep_time makes.
    """
    couplings = data.get("couplings") if isinstance(data, dict) else None
    if not isinstance(couplings, list) or not any(isinstance(c, dict) and c.get("keep_time") is not None
                                                  for c in couplings):
        return data
    cams, linkages = data.get("cams"), data.get("linkages")
    cam_names, link_names = _names(cams), _names(linkages)
    out = {**data, "couplings": list(couplings), "cams": list(cams) if isinstance(cams, list) else cams}
    for i, c in enumerate(couplings):
        if not isinstance(c, dict) or c.get("keep_time") is None:
            continue
        where = f"couplings[{i}]"
        try:
            keep = validate(KeepTime, c["keep_time"])
        except SpecError as exc:
            raise exc.under(f"{where}.keep_time") from None
        if c.get("cam") not in cam_names:
            raise SpecError(f"no cam {c.get('cam')!r}; cams: {', '.join(map(str, cam_names))}", f"{where}.cam")
        if c.get("linkage") not in link_names:
            raise SpecError(f"no linkage {c.get('linkage')!r}; linkages: {', '.join(map(str, link_names)) or 'none'}",
                            f"{where}.linkage")
        ci, li = cam_names.index(c["cam"]), link_names.index(c["linkage"])
        made = plan_for(keep, _linkage_table(read, linkages[li], li), where)
        if "rest" in c and not _same(c["rest"], made.rest):
            raise SpecError(f"keep_time sets the crank's rest (to {made.rest:.9g} degrees here); leave rest out",
                            f"{where}.rest")
        mount = out["cams"][ci]
        template = read(mount.get("template", {}), f"cams[{ci}].template", "camgen")
        if "motion" in template and template["motion"] != made.motion:
            raise SpecError(f"{where}.keep_time makes this cam's motion; leave motion out",
                            f"cams[{ci}].template.motion")
        if "phase" in mount and not _same(mount["phase"], made.phase):
            raise SpecError(f"{where}.keep_time sets this cam's phase (to {made.phase:.9g} degrees here); leave "
                            "phase out", f"cams[{ci}].phase")
        out["couplings"][i] = {**c, "rest": made.rest}
        out["cams"][ci] = {**mount, "phase": made.phase, "template": {**template, "motion": made.motion}}
    return out


def _linkage_table(read: Callable[[Any, str, str], dict[str, Any]], mount: Any, index: int) -> Any:
    """The validated ``[linkage]`` table of ``linkages[index]``'s template."""
    from linkgen.spec import validate_spec

    where = f"linkages[{index}].template"
    raw = read(mount.get("template", {}) if isinstance(mount, dict) else {}, where, "linkgen")
    try:
        return validate_spec({**raw, "name": "keep-time"}).linkage
    except SpecError as exc:
        raise exc.under(where) from None


def plan_for(keep: KeepTime, table: Any, where: str) -> Plan:
    """:func:`plan` of coupling ``where``'s four-bar ``table``, its errors named under ``where``."""
    if table.type != "four-bar" or getattr(table, "input", "crank") != "crank":
        raise SpecError(f"keep_time drives a four-bar by its crank (linkage.input = \"crank\"), not a {table.type} "
                        f"by its {getattr(table, 'input', 'input')}", f"{where}.keep_time")
    try:
        return plan(keep, table)
    except SpecError as exc:
        raise exc.under(f"{where}.keep_time") from None


#: shaft angles over a turn at which an output program's reproduction is checked between its points
CHECK_SAMPLES = 3600


def timing_report(design: Any) -> dict[str, Any]:
    """Each timed coupling's check against the built machine (``couplings[i]`` -> :func:`coupling_check`); empty
    without a timed coupling."""
    return {f"couplings[{i}]": coupling_check(design, c) for i, c in enumerate(design.spec.couplings)
            if c.keep_time is not None}


def coupling_check(design: Any, coupling: Any) -> dict[str, Any]:
    """A timed coupling checked against the built machine ``design``: the law, and the linkage solved at the
    follower's swing from the built cam's program at each target's time (and its dwell's end), its distance from the
    target and from the path's nearest point; or, for an output program, the rocker's largest departure from it at
    its points and over :data:`CHECK_SAMPLES` shaft angles."""
    from camgen.kinds.machine.design import _cam_of

    spec, keep = design.spec, coupling.keep_time
    index = next(j for j, m in enumerate(spec.linkages) if m.name == coupling.linkage)
    table = spec.linkage_specs[index].linkage
    made, fb = plan(keep, table), four_bar(table)
    phase = next(m.phase for m in spec.cams if m.name == coupling.cam)
    swing = _cam_of(design.cam(coupling.cam).design).program

    def built(times: np.ndarray) -> Any:
        crank = coupling.rest + swing.evaluate(np.radians(np.asarray(times) - phase))[0]
        return fb.positions(np.radians(crank), table.assembly)

    entry: dict[str, Any] = {"cam": coupling.cam, "linkage": coupling.linkage, "law": LAW, "phase_deg": phase,
                             "rest_deg": coupling.rest, "segments": len(made.motion)}
    if keep.targets is not None:
        rows, placed = [], frame(keep, fb)
        for row, reach in zip(keep.targets, made.reaches, strict=True):
            for at in (row[2], row[2] + _dwell(row)) if _dwell(row) else (row[2],):
                point = built(np.array([at])).point[0]
                world = from_linkage(point, *placed)[0]
                rows.append({"target_mm": row[:2], "angle_deg": at, "crank_deg": _round(reach.crank_deg),
                             "tracer_mm": [_round(v) for v in world],
                             "from_target_mm": _round(float(np.hypot(*(world - row[:2])))),
                             "from_path_point_mm": float(np.hypot(*(point - reach.point))),
                             "target_off_path_mm": _round(reach.distance)})
        return {**entry, "targets": rows, "worst_from_path_point_mm": max(r["from_path_point_mm"] for r in rows)}
    assert made.inverse is not None and made.theta4 is not None
    points, want = made.inverse.times[:-1], made.theta4[:-1]
    grid = np.arange(CHECK_SAMPLES) * (360.0 / CHECK_SAMPLES)
    sign = 1.0 if keep.turn == "ccw" else -1.0
    between = float(keep.start or 0.0) + sign * output_program(keep).evaluate(np.radians(grid))[0]
    return {**entry, "points": len(points), "step_deg": keep.step, "stroke": made.stroke,
            "at_points_max_deg": _gap(built(points).theta4, want),
            "between_points_max_deg": _gap(built(grid).theta4, between), "between_samples": CHECK_SAMPLES}


#: the law the crank's motion is made by (see :mod:`camgen.kinds.machine.timing`)
LAW = ("quintic pieces between the points (the polynomial law, one segment a piece) meeting the crank's angle, rate "
       "and acceleration at both ends: continuous to the acceleration, finite jerk, monotone between points")


def _round(value: float) -> float:
    return round(float(value), 9)


def _gap(theta4: np.ndarray, want_deg: np.ndarray) -> float:
    """The largest difference (degrees) between rocker angles ``theta4`` (radians) and ``want_deg``."""
    return float(np.abs(np.degrees(np.angle(np.exp(1j * (theta4 - np.radians(want_deg)))))).max())
