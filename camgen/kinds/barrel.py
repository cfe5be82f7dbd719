"""The barrel (cylindrical) cam: a groove round a cylinder drives a translating roller along the cam's axis.

The cylinder is ``cam.length`` long with the groove ``cam.groove_depth`` deep about the pitch cylinder of
radius ``cam.pitch_radius`` (the groove's mid-depth); the roller's centre runs on the pitch cylinder at
z = z0 + s, z0 putting the groove in the middle of the length. Developed (x = Rm theta) the pitch curve is
a plate cam's of travel 2 pi Rm, so the pressure angle is atan(s' / Rm); see :mod:`camgen.barrel`.
"""
from __future__ import annotations

import itertools
import math
from typing import Any

from camgen.followers.plate import PlateRoller
from camgen.kinds.base import BARREL_KEYS, CamKind

FOLLOWERS = ("translating-roller",)
#: ``[cam]`` keys a barrel does not use, with what it takes instead
_NOT_USED = {"base_radius": "pitch_radius", "thickness": "length", "travel": "length", "rim": "length"}


def rest_height(spec: Any) -> float:
    """z0 (mm): the roller centre's height at s = 0, putting the program's travel mid-length."""
    steps = [seg.lift if seg.type == "rise" else -seg.lift if seg.type == "return" else 0.0 for seg in spec.motion]
    heights = [0.0, *itertools.accumulate(steps)]
    return (spec.cam.length - max(heights) - min(heights)) / 2


def _check(spec: Any) -> None:
    cam, follower = spec.cam, spec.follower
    for key, instead in _NOT_USED.items():
        if key in cam.model_fields_set:
            raise ValueError(f"cam.{key}: not used by a barrel cam (its size is cam.pitch_radius, cam.length and "
                             f"cam.groove_depth; see cam.{instead})")
    for key in (*BARREL_KEYS, "groove_depth"):
        if getattr(cam, key) is None:
            raise ValueError(f"cam.{key}: required for a barrel cam (mm, > 0)")
    if follower.type not in FOLLOWERS:
        raise ValueError(f"follower.type: a barrel cam takes a translating-roller follower, moving along the cam's "
                         f"axis (got {follower.type!r})")
    for key in ("offset", "spring_rate", "preload", "mass"):
        if key in follower.model_fields_set:
            raise ValueError(f"follower.{key}: not used by a barrel cam (the roller's axis is radial and the groove "
                             "drives it both ways)")
    for key in ("allow_undercut", "min_rho_margin"):
        if key in cam.model_fields_set:
            raise ValueError(f"cam.{key}: not used by a barrel cam: its groove's walls are refused where they undercut")
    for key in sorted(spec.hub.model_fields_set - {"keyway"}):
        raise ValueError(f"hub.{key}: not used by a barrel cam (it takes cam.bore and hub.keyway)")
    if spec.output.kerf:
        raise ValueError("output.kerf: a barrel cam is printed; its drawing is a developed template, not a cut file")
    rw = follower.roller_radius + cam.running_clearance / 2
    floor = cam.pitch_radius - cam.groove_depth / 2
    if not floor > max(cam.bore / 2, rw):
        raise ValueError(f"cam.groove_depth: must be < {2 * (cam.pitch_radius - max(cam.bore / 2, rw)):.6g} mm, so the "
                         f"groove's floor stays outside the bore and wider than the roller (got {cam.groove_depth:g})")
    if not rest_height(spec) > rw:
        travel = cam.length - 2 * rest_height(spec)
        raise ValueError(f"cam.length: must be > {travel + 2 * rw:.6g} mm, the follower's travel and the groove's "
                         f"width (got {cam.length:g})")


def _follower(spec: Any, base_radius: Any, roller_radius: float) -> PlateRoller:
    """The developed pitch curve: a plate cam of travel 2 pi Rm whose roller centre runs at z0 + s."""
    return PlateRoller(rest_height(spec) - roller_radius, roller_radius, 2 * math.pi * spec.cam.pitch_radius)


KIND = CamKind("barrel", FOLLOWERS, _check, _follower, "camgen.barrel.design:design_barrel",
               "camgen.barrel.outputs:barrel_bundle")
