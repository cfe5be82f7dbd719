"""The machine's entry in the kind registry (:data:`camgen.kinds.KINDS`): chosen by its own ``[machine]`` table,
designed by :func:`camgen.machine.design.design_machine` and written by :func:`camgen.machine.outputs.machine_bundle`
(both imported when first called)."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

from camgen.kinds.base import KindBase, Operations

if TYPE_CHECKING:
    from camgen.machine.design import MachineDesign
    from camgen.machine.spec import MachineSpec

#: what a machine writes: its cams' and linkages' files (those of their kinds that these name), the timing diagram
#: and the report
MACHINE_FORMATS = frozenset(("dxf", "cut-svg", "stl", "3mf", "json", "png", "svg"))


class MachineKind(KindBase["MachineSpec", "MachineDesign"]):
    """A machine (a ``[machine]`` table): cams on phased shafts driving four-bars through their followers' arms."""

    name: str = "machine"
    title: str = "a machine"
    table_key: str = "machine"
    formats: frozenset[str] = MACHINE_FORMATS
    unsized: str = "a machine has no base radius of its own to size; size each cam's template"

    @property
    def spec(self) -> type[MachineSpec]:
        from camgen.machine.spec import MachineSpec

        return MachineSpec

    def operations(self) -> Operations[MachineSpec, MachineDesign]:
        from camgen.machine.design import design_machine
        from camgen.machine.outputs import machine_bundle, machine_row
        from camgen.machine.report import summary_lines

        return Operations(design_machine, machine_bundle, lambda design, report: summary_lines(report), machine_row)

    def sheet_refusal(self, spec: Any) -> str | None:
        return "a machine's cams and linkages write their own cut files; a family's [sheet] nests single cams"


KIND = MachineKind()
