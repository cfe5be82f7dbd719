"""The plate (linear) cam: a plate sliding under a translating roller or knife edge, cut to a profile.

The program's 360 degrees spread over ``cam.travel`` mm of plate; ``base_radius`` is the
plate's height under the profile (see :mod:`camgen.followers.plate`).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from camgen.kinds.base import Starter
from camgen.kinds.shared import FlatKind
from camgen.kinds.starting import OUTPUT, motion
from camgen.rig import Mount, plate_mount

if TYPE_CHECKING:
    from camgen.spec import PlateSpec



def _check(spec: Any) -> None:
    """Nothing beyond its tables: a plate cam's follower table has no offset (:mod:`camgen.tables.followers`)."""


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


class PlateKind(FlatKind["PlateSpec"]):
    """A plate (linear) cam (``cam.kind = "plate"``)."""

    name: str = "plate"
    title: str = "a plate cam"
    check: Callable[[PlateSpec], None] = staticmethod(_check)
    follower: Callable[[PlateSpec, float, float], Any] = staticmethod(_follower)
    starters: Mapping[str, Starter] = STARTERS

    @property
    def spec(self) -> type[PlateSpec]:
        from camgen.spec import PlateSpec

        return PlateSpec

    def mount(self, spec: PlateSpec) -> Mount:
        return plate_mount(spec.follower, spec.cam.travel)


KIND = PlateKind()
