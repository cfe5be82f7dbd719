"""The plate (linear) cam: a plate sliding under a translating roller or knife edge, cut to a profile.

The program's 360 degrees spread over ``cam.travel`` mm of plate; ``base_radius`` is the
plate's height under the profile (see :mod:`camgen.followers.plate`).
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from camgen.kinds.base import Animator, Starter
from camgen.kinds.plate.starters import STARTERS
from camgen.kinds.shared import FlatKind

if TYPE_CHECKING:
    from camgen.kinds.plate.table import PlateSpec


class PlateKind(FlatKind["PlateSpec"]):
    """A plate (linear) cam (``cam.kind = "plate"``)."""

    name: str = "plate"
    title: str = "a plate cam"
    starters: Mapping[str, Starter] = STARTERS

    @property
    def spec(self) -> type[PlateSpec]:
        from camgen.kinds.plate.table import PlateSpec

        return PlateSpec

    def animator(self) -> Animator:
        from camgen.kinds.plate.animation import plate_frames

        return plate_frames


KIND = PlateKind()
