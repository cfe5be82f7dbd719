"""Starter templates for ``camgen new KIND``: one for each follower on a disc cam, each cam kind and the Geneva
drive, every key commented from the template's models (:mod:`camgen.core.starter`), and where a kind has rules of
its own (what limits its sizes, what it leaves out) by :data:`RULES`, so that a comment names only keys that kind
takes; each builds as it is."""
from __future__ import annotations

from typing import Any

from camgen.core.options import choose
from camgen.core.spec import CutOutputTable
from camgen.core.starter import render
from camgen.geneva.spec import GenevaTable
from camgen.spec import CamTable, FollowerTable, HubTable, SegmentTable

MODELS = {"cam": CamTable, "follower": FollowerTable, "motion": SegmentTable, "hub": HubTable,
          "output": CutOutputTable, "geneva": GenevaTable}
#: a rise, a dwell, a return, a dwell: laws with continuous acceleration, so no jerk is infinite
MOTION = ({"type": "rise", "law": "cycloidal", "lift": 20.0, "angle": 120.0}, {"type": "dwell", "angle": 60.0},
          {"type": "return", "law": "modified-sine", "lift": 20.0, "angle": 120.0}, {"type": "dwell", "angle": 60.0})
NOTES = {"motion.type": "rise, dwell or return; the angles add up to 360",
         "motion.law": "see `camgen laws` for the laws and their peak factors",
         "motion.lift": "mm: the follower's travel",
         "cam.rotation": "ccw or cw, seen from the side the follower is drawn on",
         "output.formats": "leave out a format to skip its files"}
#: an arm's lift, for the oscillating followers
SWING = {"motion.lift": "degrees: the arm's swing"}
#: the rules every disc cam under a roller has
_ROLLER = {"follower.roller_radius": "mm: roller radius; below the pitch curve's least convex radius, else the cam "
                                    "undercuts (the prime radius is base_radius + roller_radius)"}
#: a base radius sized by camgen under a flat face
_FLAT_AUTO = {"cam.base_radius": "\"auto\": the smallest whose profile radius (base_radius + s + s'' for a "
                                 "translating face) stays above min_rho_margin and meets the pressure-angle limit",
              "cam.min_rho_margin": "mm: least radius of curvature of the profile; at 0 or below it folds into a "
                                    "cusp the face cannot follow"}

#: kind -> comments of its own: under a table's heading (``"cam"``) the kind's rule, and for a ``table.key`` what
#: that key means for this kind; they name only keys the kind takes (tests)
RULES: dict[str, dict[str, str]] = {
    "translating-roller": {
        "cam": "a disc cam under a translating roller: its pressure angle is held to 30 degrees (max_pressure_angle "
               "sets another limit)",
        **_ROLLER,
        "follower.offset": "mm: the axis's offset, + to the right (+X); |offset| < base_radius + roller_radius; on "
                           "a ccw cam + lowers the rise's pressure angle and raises the return's"},
    "knife-edge": {
        "cam": "a disc cam under a point: the profile is the pitch curve itself (prime radius = base_radius)",
        "follower.offset": "mm: the axis's offset, + to the right (+X); |offset| < base_radius"},
    "translating-flat": {
        "follower": "a flat face square to its motion: pressure angle 0; it touches the cam s' mm from its axis",
        **_FLAT_AUTO,
        "follower.face_margin": "mm: face beyond the contact's travel (from least to most s'), each side"},
    "oscillating-roller": {
        "follower": "the arm puts the roller on the prime circle: |pivot_distance - arm_length| < base_radius + "
                    "roller_radius < pivot_distance + arm_length; the pressure-angle limit is 40 degrees",
        **_ROLLER, **SWING,
        "follower.pivot_distance": "mm: cam centre to the arm's pivot (to the right of the roller at rest)",
        "follower.arm_length": "mm: pivot to the roller's centre"},
    "oscillating-flat": {
        "follower": "a flat face through the pivot, touching the base circle at rest: pivot_distance > "
                    "base_radius / cos(the largest swing), so that the face touches the cam between the pivot and "
                    "the rest contact; the pressure-angle limit is 40 degrees",
        **_FLAT_AUTO, **SWING,
        "cam.base_radius": "\"auto\": the smallest whose profile radius stays above min_rho_margin and that meets "
                           "the pressure-angle limit; below pivot_distance * cos(the largest swing)",
        "follower.pivot_distance": "mm: cam centre to the pivot the face turns about; > base_radius / cos(the "
                                   "largest swing)",
        "follower.face_margin": "mm: face beyond the contact's travel along it, each side"},
    "plate": {
        "cam": "a plate cam slides along +X as the program runs: it does not turn and has no bore",
        "cam.travel": "mm: how far the plate slides over the program's 360 degrees: a segment of a degrees "
                      "takes a / 360 of it",
        "cam.base_radius": "mm: the plate's height under the profile; the roller's centre runs at base_radius + "
                           "roller_radius + s",
        "follower.roller_radius": "mm: roller radius; below the pitch curve's least convex radius, else the plate "
                                  "undercuts"},
    "grooved": {
        "cam": "a grooved face cam: flanks roller_radius + running_clearance / 2 either side of the pitch curve; "
               "the inner flank undercuts where the pitch curve's convex radius falls below that, the outer where "
               "its concave radius does",
        "follower": "positive drive: the groove drives the roller both ways, no return spring",
        "cam.groove_depth": "mm: depth of the groove's pocket in the face; < thickness (it is no slot)",
        "cam.thickness": "mm: plate thickness (STL extrusion); > groove_depth",
        "cam.rim": "mm: wall outside the groove's outer flank"},
    "barrel": {
        "cam": "a barrel cam, sized by pitch_radius, length and groove_depth; the pressure angle is "
               "atan(s' / pitch_radius)",
        "follower": "a roller moving along the cam's axis, driven both ways by the groove (no return spring)",
        "cam.pitch_radius": "mm: radius of the pitch cylinder, the groove's mid-depth",
        "cam.length": "mm: the cylinder's axial length; more than the follower's stroke and the groove's width, "
                      "2 roller_radius + running_clearance",
        "cam.groove_depth": "mm: depth of the groove about pitch_radius; its floor, at pitch_radius - "
                            "groove_depth / 2, must lie outside the bore as printed (bore / 2 + "
                            "output.clearance / 2) and outside roller_radius + running_clearance / 2",
        "cam.bore": "mm: bore diameter, 0 for none; within the groove's floor"},
    "conjugate": {
        "cam": "a conjugate pair: a second disc drives a second roller on the far end of the yoke; its base circle "
               "is cam.second_base_radius (default: base_radius); both cams are checked for pressure angle and "
               "undercut",
        "follower": "positive drive: the two cams drive the yoke both ways, no return spring",
        **_ROLLER},
    "geneva": {
        "geneva": "the wheel indexes 360 / slots degrees while the driver turns 180 - 360 / slots, then dwells; the "
                  "pin runs at centre_distance sin(180 / slots) from the driver's axis (a radial entry)",
        "geneva.slots": "number of slots in the wheel, 3 to 36",
        "geneva.pin_diameter": "mm: diameter of the driver's pin; the slots are pin_diameter + slot_clearance wide"},
}


def _cam(kind: str, **keys: Any) -> dict[str, Any]:
    base = {"kind": kind} if kind != "disc" else {}
    return {**base, "base_radius": 40.0, "thickness": 8.0, "bore": 10.0, "rotation": "ccw", "rpm": 60.0, **keys}


def _motion(lift: float = 20.0) -> list[tuple[str, dict[str, Any]]]:
    return [("[motion]", {k: (lift if k == "lift" else v) for k, v in seg.items()}) for seg in MOTION]


OUTPUT = ("output", {"tolerance": 0.01, "kerf": 0.0, "clearance": 0.2})
SPRUNG = {"mass": 0.2, "spring_rate": 0.5, "preload": 5.0}

#: kind -> (what it is, its tables); a follower's name is that follower on a disc cam
STARTERS: dict[str, tuple[str, list[tuple[str, dict[str, Any]]]]] = {
    "translating-roller": ("A disc cam driving a translating roller follower, held on by a spring.", [
        ("cam", _cam("disc")), ("follower", {"type": "translating-roller", "roller_radius": 10.0, "offset": 0.0,
                                             **SPRUNG}), *_motion(), ("hub", {"keyway": True}), OUTPUT]),
    "knife-edge": ("A disc cam driving a knife-edge follower (a point: the profile is the pitch curve).", [
        ("cam", _cam("disc")), ("follower", {"type": "knife-edge", "offset": 0.0, **SPRUNG}), *_motion(), OUTPUT]),
    "translating-flat": ("A disc cam driving a translating flat-faced follower; its base radius sized by camgen.", [
        ("cam", _cam("disc", base_radius="auto", min_rho_margin=5.0)),
        ("follower", {"type": "translating-flat", "face_margin": 3.0, **SPRUNG}), *_motion(), OUTPUT]),
    "oscillating-roller": ("A disc cam swinging an arm with a roller; the lifts are the arm's swing in degrees.", [
        ("cam", _cam("disc")), ("follower", {"type": "oscillating-roller", "roller_radius": 8.0,
                                             "pivot_distance": 110.0, "arm_length": 90.0, **SPRUNG}),
        *_motion(20.0), OUTPUT]),
    "oscillating-flat": ("A disc cam swinging a flat-faced arm; the lifts are the arm's swing in degrees.", [
        ("cam", _cam("disc", base_radius="auto", min_rho_margin=5.0)),
        ("follower", {"type": "oscillating-flat", "pivot_distance": 120.0, "face_margin": 3.0}),
        *_motion(15.0), OUTPUT]),
    "plate": ("A plate (linear) cam: the profile along a plate that slides, lifting a roller.", [
        ("cam", {"kind": "plate", "travel": 200.0, "base_radius": 20.0, "thickness": 6.0}),
        ("follower", {"type": "translating-roller", "roller_radius": 8.0}), *_motion(15.0), OUTPUT]),
    "grooved": ("A grooved face cam: the roller runs in a groove that drives it both ways, no spring.", [
        ("cam", _cam("grooved", thickness=12.0, groove_depth=6.0, running_clearance=0.2, rim=5.0)),
        ("follower", {"type": "translating-roller", "roller_radius": 6.0}), *_motion(), OUTPUT]),
    "barrel": ("A barrel (cylindrical) cam: a groove round a cylinder moves the roller along the axis.", [
        ("cam", {"kind": "barrel", "pitch_radius": 30.0, "length": 50.0, "groove_depth": 6.0, "bore": 10.0,
                 "rpm": 60.0}),
        ("follower", {"type": "translating-roller", "roller_radius": 5.0}),
        *[("[motion]", seg) for seg in ({"type": "rise", "law": "cycloidal", "lift": 20.0, "angle": 150.0},
                                        {"type": "dwell", "angle": 30.0},
                                        {"type": "return", "law": "modified-sine", "lift": 20.0, "angle": 150.0},
                                        {"type": "dwell", "angle": 30.0})], OUTPUT]),
    "conjugate": ("A conjugate pair: two discs on one shaft drive a yoke's two rollers, both ways, no spring.", [
        ("cam", _cam("conjugate", bore=12.0)), ("follower", {"type": "translating-roller", "roller_radius": 8.0}),
        *_motion(), ("hub", {"keyway": True}), OUTPUT]),
    "geneva": ("A Geneva drive: the wheel indexes a quarter turn while the driver turns 90 degrees.", [
        ("geneva", {"slots": 4, "centre_distance": 80.0, "pin_diameter": 6.0, "slot_clearance": 0.2,
                    "lock_clearance": 0.2, "thickness": 6.0, "driver_bore": 8.0, "wheel_bore": 8.0, "rpm": 30.0}),
        ("output", {"tolerance": 0.01})]),
}


def starter(kind: str, name: str) -> str:
    """The starter template of ``kind`` (one of :data:`STARTERS`) named ``name``, as TOML text; a one-line
    :class:`~camgen.core.errors.SpecError` naming ``KIND`` for another."""
    kind = choose(kind, STARTERS, "KIND")
    what, tables = STARTERS[kind]
    header = (f"{what}\nBuild it with:  camgen build {name}.toml   (files land in out/{name}/)\n"
              "Every key is explained in the documentation's template reference; --set KEY=VALUE changes one for a "
              "run.")
    return render(header, [("", {"name": name}), *tables], {"": None, **MODELS}, {**NOTES, **RULES[kind]})
