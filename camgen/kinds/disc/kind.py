"""The disc cam: a plate turning about its centre, cut to a profile; every follower type drives it."""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from camgen.kinds.base import Starter
from camgen.kinds.disc.starters import STARTERS
from camgen.kinds.shared import FlatKind
from camgen.rig import Mount, disc_mount

if TYPE_CHECKING:
    from camgen.spec import DiscSpec
    from camgen.core.bundle import Item
    from camgen.flat import FlatCamDesign


def _check(spec: Any) -> None:
    """Nothing beyond its tables: a disc cam's follower tables are the spring-held ones
    (:mod:`camgen.tables.followers`)."""


class DiscKind(FlatKind["DiscSpec"]):
    """A disc cam (``cam.kind = "disc"``, the default); the one kind with a graphical construction."""

    name: str = "disc"
    title: str = "a disc cam"
    check: Callable[[DiscSpec], None] = staticmethod(_check)
    starters: Mapping[str, Starter] = STARTERS

    @property
    def spec(self) -> type[DiscSpec]:
        from camgen.spec import DiscSpec

        return DiscSpec

    def mount(self, spec: DiscSpec) -> Mount:
        return disc_mount(spec.follower, spec.cam.rotation)

    def construction(self, design: FlatCamDesign) -> tuple[Item, ...]:
        from camgen.construction.figure import construction_files

        return construction_files(design)


KIND = DiscKind()
