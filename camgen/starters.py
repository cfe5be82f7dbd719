"""Starter templates for ``camgen new KIND``: one for each follower on a disc cam, each cam kind and the Geneva
drive, every key commented from the template's models (:mod:`camgen.core.starter`); each builds as it is."""
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
         "motion.lift": "mm (degrees of swing for an arm): the follower's travel",
         "cam.rotation": "ccw or cw, seen from the side the follower is drawn on",
         "output.formats": "leave out a format to skip its files"}


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
    what, tables = STARTERS[choose(kind, STARTERS, "KIND")]
    header = (f"{what}\nBuild it with:  camgen build {name}.toml   (files land in out/{name}/)\n"
              "Every key is explained in the README's key tables; --set KEY=VALUE changes one for a run.")
    return render(header, [("", {"name": name}), *tables], {"": None, **MODELS}, NOTES)
