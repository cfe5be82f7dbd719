"""The plate (linear) cam: a plate sliding under a translating roller or knife edge, cut to a profile.

The program's 360 degrees spread over ``cam.travel`` mm of plate; ``base_radius`` is the
plate's height under the profile (see :mod:`camgen.followers.plate`).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from camgen.kinds.base import Starter
from camgen.kinds.plate.starters import STARTERS
from camgen.kinds.shared import FlatKind
from camgen.rig import Mount, plate_mount

if TYPE_CHECKING:
    from camgen.spec import PlateSpec



def _check(spec: Any) -> None:
    """Nothing beyond its tables: a plate cam's follower table has no offset (:mod:`camgen.tables.followers`)."""


def _follower(spec: Any, base_radius: float, roller_radius: float) -> Any:
    """The roller over a plate ``base_radius`` mm high (the plate's mount's)."""
    return plate_mount(spec.follower, spec.cam.travel).at(base_radius, roller_radius)


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
