"""The disc cam: a plate turning about its centre, cut to a profile; every follower type drives it."""
from __future__ import annotations

from typing import Any

from camgen.followers import FOLLOWERS
from camgen.kinds.base import GROOVE_KEYS, GROOVED, CamKind, flat_body, refuse_keys


def _check(spec: Any) -> None:
    flat_body(spec)
    if spec.cam.travel is not None:
        raise ValueError("cam.travel: only for a plate cam (cam.kind = \"plate\")")
    refuse_keys(spec, GROOVE_KEYS, GROOVED)


def _follower(spec: Any, base_radius: float, roller_radius: float) -> Any:
    sense = 1 if spec.cam.rotation == "ccw" else -1
    return FOLLOWERS[spec.follower.type].make(spec.follower, base_radius, roller_radius, sense)


KIND = CamKind("disc", tuple(FOLLOWERS), _check, _follower, "camgen.profile:design_profile",
               "camgen.outputs:cam_bundle")
