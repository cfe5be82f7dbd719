"""The Geneva drive: a driver's pin indexes a slotted wheel, then a locking disc holds it; chosen by its own
``[geneva]`` table (no follower and no motion program: its motion is the Geneva law). See :mod:`camgen.kinds.geneva`,
which is imported only when a drive is validated, designed or written."""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from camgen.kinds.base import NESTED, KindBase, Operations, Starter

if TYPE_CHECKING:
    from camgen.kinds.geneva.design import GenevaDesign
    from camgen.kinds.geneva.table import GenevaSpec

STARTERS = {
    "geneva": Starter(
        "A Geneva drive: the wheel indexes a quarter turn while the driver turns 90 degrees.",
        (("geneva", {"slots": 4, "centre_distance": 80.0, "pin_diameter": 6.0, "slot_clearance": 0.2,
                     "lock_clearance": 0.2, "thickness": 6.0, "driver_bore": 8.0, "wheel_bore": 8.0, "rpm": 30.0}),
         ("output", {"tolerance": 0.01})),
        {"geneva": "the wheel indexes 360 / slots degrees while the driver turns 180 - 360 / slots, then dwells; the "
                   "pin runs at centre_distance sin(180 / slots) from the driver's axis (a radial entry)",
         "geneva.slots": "number of slots in the wheel, 3 to 36",
         "geneva.pin_diameter": "mm: diameter of the driver's pin; the slots are pin_diameter + slot_clearance wide"}),
}


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


KIND = GenevaKind()
