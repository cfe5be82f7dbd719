"""The plate (linear) cam: a plate sliding under a translating roller or knife edge, cut to a profile.

The program's 360 degrees spread over ``cam.travel`` mm of plate; ``base_radius`` is the
plate's height under the profile (see :mod:`camgen.followers.plate`).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from camgen.kinds.base import GROOVE_KEYS, GROOVED, Starter, flat_body, refuse_keys
from camgen.kinds.shared import FlatKind
from camgen.kinds.starting import OUTPUT, motion
from camgen.rig import Mount, plate_mount

if TYPE_CHECKING:
    from camgen.spec import CamSpec

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


STARTERS = {
    "plate": Starter(
        "A plate (linear) cam: the profile along a plate that slides, lifting a roller.",
        (("cam", {"kind": "plate", "travel": 200.0, "base_radius": 20.0, "thickness": 6.0}),
         ("follower", {"type": "translating-roller", "roller_radius": 8.0}), *motion(15.0), OUTPUT),
        {"cam": "a plate cam slides along +X as the program runs: it does not turn and has no bore",
         "cam.travel": "mm: how far the plate slides over the program's 360 degrees: a segment of a degrees "
                       "takes a / 360 of it",
         "cam.base_radius": "mm: the plate's height under the profile; the roller's centre runs at base_radius + "
                            "roller_radius + s",
         "follower.roller_radius": "mm: roller radius; below the pitch curve's least convex radius, else the plate "
                                   "undercuts"}),
}


class PlateKind(FlatKind):
    """A plate (linear) cam (``cam.kind = "plate"``)."""

    name: str = "plate"
    title: str = "a plate cam"
    followers: tuple[str, ...] = FOLLOWERS
    check: Callable[[CamSpec], None] = staticmethod(_check)
    follower: Callable[[CamSpec, float, float], Any] = staticmethod(_follower)
    starters: Mapping[str, Starter] = STARTERS

    def mount(self, spec: CamSpec) -> Mount:
        return plate_mount(spec.follower, spec.cam.travel)


KIND = PlateKind()
