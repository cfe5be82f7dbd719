"""The grooved face cam's template: its ``[cam]`` table (:class:`GroovedTable`, ``kind = "grooved"``) and its spec
(:class:`GroovedSpec`: a roller driven both ways, no spring), with the rules its tables cannot check alone."""
from __future__ import annotations

from typing import ClassVar, Literal

from pydantic import ConfigDict, Field

from camgen.spec import FlatSpec
from camgen.tables import FlatBody, GrooveBody, Speeds
from camgen.tables.followers import DrivenFollower


class GroovedTable(Speeds, GrooveBody, FlatBody):
    """A grooved face cam: a disc whose face carries a groove the roller runs in, driving it both ways."""

    model_config = ConfigDict(title="a grooved cam")

    kind: Literal["grooved"] = Field(description="cam kind")


class GroovedSpec(FlatSpec):
    """A grooved face cam's template (``cam.kind = "grooved"``), validated."""

    cam: GroovedTable
    follower: DrivenFollower

    noun: ClassVar[str] = "a grooved cam"  # its table's title

    def kind_rules(self) -> None:
        """The groove shallower than the plate; no boss on the grooved face."""
        cam = self.cam
        if not cam.groove_depth < cam.thickness:
            raise ValueError(f"cam.groove_depth: must be < cam.thickness {cam.thickness:g} mm (got "
                             f"{cam.groove_depth:g})")
        if self.hub.boss_diameter:
            raise ValueError("hub.boss_diameter: a boss would stand on the grooved face, where the follower runs; "
                             "mount a grooved cam by its bore (hub.keyway) or hub.bolt_circle holes")
