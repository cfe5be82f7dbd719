"""The Geneva drive: a driver's pin indexes a slotted wheel, then a locking disc holds it; chosen by its own
``[geneva]`` table (no follower and no motion program: its motion is the Geneva law). See :mod:`camgen.kinds.geneva`,
which is imported only when a drive is validated, designed or written."""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from camgen.kinds.base import Animator, NESTED, KindBase, Operations, Starter
from camgen.kinds.geneva.starters import STARTERS

if TYPE_CHECKING:
    from camgen.kinds.geneva.design import GenevaDesign
    from camgen.kinds.geneva.table import GenevaSpec


class GenevaKind(KindBase["GenevaSpec", "GenevaDesign"]):
    """A Geneva drive (a ``[geneva]`` table): designed by :func:`camgen.kinds.geneva.design.design_geneva`, written by
    :func:`camgen.kinds.geneva.outputs.geneva_bundle`, its parts nested on a sheet of its own."""

    name: str = "geneva"
    title: str = "a Geneva drive"
    table_key: str = "geneva"
    unsized: str = "a Geneva drive has no base radius to size; `camgen build` it"
    starters: Mapping[str, Starter] = STARTERS

    @property
    def spec(self) -> type[GenevaSpec]:
        from camgen.kinds.geneva.table import GenevaSpec

        return GenevaSpec

    def operations(self) -> Operations[GenevaSpec, GenevaDesign]:
        from camgen.kinds.geneva.design import design_geneva
        from camgen.kinds.geneva.outputs import geneva_bundle, geneva_row
        from camgen.kinds.geneva.report import summary_lines

        return Operations(design_geneva, geneva_bundle, lambda design, report: summary_lines(report), geneva_row)

    def sheet_refusal(self, spec: GenevaSpec) -> str | None:
        return f"a Geneva drive's wheel, lock and crank are nested on its own <name>-sheet.dxf; {NESTED}"

    def animator(self) -> Animator:
        from camgen.kinds.geneva.animation import geneva_frames

        return geneva_frames


KIND = GenevaKind()
