"""The disc cam: a plate turning about its centre, cut to a profile; every follower type drives it."""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from camgen.kinds.base import Starter
from camgen.kinds.disc.starters import STARTERS
from camgen.kinds.shared import FlatKind

if TYPE_CHECKING:
    from camgen.core.bundle import Item
    from camgen.flat import FlatCamDesign
    from camgen.kinds.disc.table import DiscSpec
    from camgen.spec import FlatSpec


class DiscKind(FlatKind["DiscSpec"]):
    """A disc cam (``cam.kind = "disc"``, the default); the one kind with a graphical construction and a kit."""

    name: str = "disc"
    title: str = "a disc cam"
    starters: Mapping[str, Starter] = STARTERS

    @property
    def spec(self) -> type[DiscSpec]:
        from camgen.kinds.disc.table import DiscSpec

        return DiscSpec

    def with_kit(self, spec: FlatSpec) -> bool:
        from camgen.kinds.disc.table import DiscSpec

        return isinstance(spec, DiscSpec) and spec.kit is not None

    def animation(self, design: FlatCamDesign, n: int, size: tuple[int, int],
                  report: dict[str, Any] | None = None) -> Any:
        from camgen.animation import cam_frames                 # drawn from the design alone: no report needed

        return cam_frames(design, n, size)

    def construction(self, design: FlatCamDesign) -> tuple[Item, ...]:
        from camgen.construction.figure import construction_files

        return construction_files(design)


KIND = DiscKind()
