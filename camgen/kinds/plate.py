"""The plate (linear) cam: a plate sliding under a translating roller or knife edge, cut to a profile.

The program's 360 degrees spread over ``cam.travel`` mm of plate; ``base_radius`` is the
plate's height under the profile (see :mod:`camgen.followers.plate`).
"""
from __future__ import annotations

from typing import Any

from camgen.kinds.base import GROOVE_KEYS, GROOVED, CamKind, flat_body, refuse_keys
from camgen.rig import plate_mount

FOLLOWERS = ("translating-roller", "knife-edge")


def _check(spec: Any) -> None:
    flat_body(spec)
    if spec.cam.travel is None:
        raise ValueError("cam.travel: required for a plate cam (mm)")
    if spec.follower.type not in FOLLOWERS:
        raise ValueError(f"follower.type: a plate cam takes a translating-roller or knife-edge follower "
                         f"(got {spec.follower.type!r})")
    if spec.follower.offset != 0 or spec.cam.bore != 0:
        raise ValueError(f"{'cam.bore' if spec.cam.bore else 'follower.offset'}: not used by a plate cam")
    if spec.cam.rotation != "ccw":
        raise ValueError("cam.rotation: not used by a plate cam (the plate slides along +X as the program runs)")
    refuse_keys(spec, GROOVE_KEYS, GROOVED)


def _follower(spec: Any, base_radius: float, roller_radius: float) -> Any:
    """The roller over a plate ``base_radius`` mm high (the plate's mount's)."""
    return plate_mount(spec.follower, spec.cam.travel).at(base_radius, roller_radius)


KIND = CamKind("plate", FOLLOWERS, _check, _follower, "camgen.flat:design_plate", "camgen.outputs:cam_bundle")
