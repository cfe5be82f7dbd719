"""The disc cam's template: its ``[cam]`` table (:class:`DiscTable`, ``kind = "disc"``, the default) and its spec
(:class:`DiscSpec`: the spring-held followers, and a kit round the cam)."""
from __future__ import annotations

from typing import ClassVar, Literal

from pydantic import ConfigDict, Field, model_validator

from camgen.core.kit import CamKitTable, check_cam_kit
from camgen.spec import FlatSpec
from camgen.tables import FlatBody, Speeds
from camgen.tables.followers import SprungFollower


class DiscTable(Speeds, FlatBody):
    """A disc cam: a plate turning about its centre, cut to a profile."""

    model_config = ConfigDict(title="a disc cam")

    kind: Literal["disc"] = Field("disc", description="cam kind")


class DiscSpec(FlatSpec):
    """A disc cam's template (``cam.kind = "disc"``, the default), validated."""

    cam: DiscTable
    follower: SprungFollower
    kit: CamKitTable | None = None

    noun: ClassVar[str] = "a disc cam"  # its table's title

    @model_validator(mode="after")
    def _kit(self) -> DiscSpec:
        if self.kit is not None:
            check_cam_kit(self.kit, self.follower.type, self.cam.bore)
        return self
