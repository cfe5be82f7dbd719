"""The disc cam: a plate turning about its centre, cut to a profile; every follower type drives it."""
from __future__ import annotations

from typing import Any

from camgen.followers import FOLLOWERS
from camgen.kinds.base import GROOVE_KEYS, GROOVED, CamKind, flat_body, refuse_keys
from camgen.rig import disc_mount


def _check(spec: Any) -> None:
    flat_body(spec)
    if spec.cam.travel is not None:
        raise ValueError("cam.travel: only for a plate cam (cam.kind = \"plate\")")
    refuse_keys(spec, GROOVE_KEYS, GROOVED)


def _follower(spec: Any, base_radius: float, roller_radius: float) -> Any:
    """The follower on a disc of ``base_radius`` with a roller of ``roller_radius`` (mm): the disc's mount's."""
    return disc_mount(spec.follower, spec.cam.rotation).at(base_radius, roller_radius)


KIND = CamKind("disc", tuple(FOLLOWERS), _check, _follower, "camgen.flat:design_disc", "camgen.outputs:cam_bundle")
