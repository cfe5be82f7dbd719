"""The plate (linear) cam's template: its ``[cam]`` table (:class:`PlateTable`, ``kind = "plate"``) and its spec
(:class:`PlateSpec`: a translating roller or a knife edge over the sliding plate)."""
from __future__ import annotations

from typing import ClassVar, Literal

from pydantic import ConfigDict, Field

from camgen.core.spec import length
from camgen.rig import Mount, plate_mount
from camgen.spec import FlatSpec
from camgen.tables import FlatSize, Limits, Speeds
from camgen.tables.followers import PlateFollower


class PlateTable(Speeds, Limits, FlatSize):
    """A plate (linear) cam: a plate sliding along +X as the program runs, cut to a profile; ``base_radius`` is its
    height under the profile. It does not turn, so it has no bore and no sense of rotation."""

    model_config = ConfigDict(title="a plate cam")

    kind: Literal["plate"] = Field(description="cam kind")
    travel: float = length("the distance the plate slides over the program's 360 degrees")

    @property
    def bore(self) -> float:
        """A plate has no bore (mm)."""
        return 0.0

    @property
    def rotation(self) -> Literal["ccw"]:
        """A plate does not turn; its program runs as it slides along +X, as a counter-clockwise disc's does."""
        return "ccw"


class PlateSpec(FlatSpec):
    """A plate (linear) cam's template (``cam.kind = "plate"``), validated: the program's 360 degrees spread over
    ``cam.travel`` mm of plate, ``base_radius`` the plate's height under the profile (see
    :mod:`camgen.followers.plate`)."""

    cam: PlateTable
    follower: PlateFollower

    noun: ClassVar[str] = "a plate cam"  # its table's title

    def mount(self) -> Mount:
        return plate_mount(self.follower, self.cam.travel)
