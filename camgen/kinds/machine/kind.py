"""The machine's entry in the kind registry (:data:`camgen.kinds.KINDS`): chosen by its own ``[machine]`` table,
designed by :func:`camgen.kinds.machine.design.design_machine` and written by
:func:`camgen.kinds.machine.outputs.machine_bundle` (both imported when first called)."""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from camgen.kinds.base import Animator, KindBase, Operations, Starter

if TYPE_CHECKING:
    from camgen.kinds.machine.design import MachineDesign
    from camgen.kinds.machine.spec import MachineSpec

#: what a machine writes: its cams' and linkages' files (those of their kinds that these name; html their own
#: pages), the timing diagram and the report
MACHINE_FORMATS = frozenset(("dxf", "cut-svg", "stl", "3mf", "json", "png", "svg", "html", "step", "gif"))

#: ``camgen new machine``: one cam whose follower's arm is a four-bar's crank
STARTERS = {
    "machine": Starter(
        "A machine: a cam on a camshaft swings its follower's arm, the crank of a four-bar whose rocker is the output.",
        (("machine", {"main": "camshaft", "rpm": 20.0}),
         ("[shafts]", {"name": "camshaft", "at": [0.0, 0.0]}),
         ("output", {"formats": ["dxf", "json", "png", "svg"]}),
         ("[cams]", {"name": "lever", "shaft": "camshaft", "layer": 0, "phase": 0.0}),
         ("cams.template.cam", {"base_radius": 40.0, "thickness": 6.0, "bore": 8.0}),
         ("cams.template.follower", {"type": "oscillating-roller", "roller_radius": 8.0, "pivot_distance": 110.0,
                                     "arm_length": 90.0, "mass": 0.1, "spring_rate": 0.5, "preload": 8.0}),
         ("[cams.template.motion]", {"type": "rise", "law": "cycloidal", "lift": 20.0, "angle": 120.0}),
         ("[cams.template.motion]", {"type": "dwell", "angle": 60.0}),
         ("[cams.template.motion]", {"type": "return", "law": "cycloidal", "lift": 20.0, "angle": 120.0}),
         ("[cams.template.motion]", {"type": "dwell", "angle": 60.0}),
         ("[linkages]", {"name": "output"}),
         ("linkages.template.linkage", {"type": "four-bar", "ground": 80.0, "crank": 30.0, "coupler": 90.0,
                                        "rocker": 60.0}),
         ("[couplings]", {"cam": "lever", "linkage": "output", "link": "crank", "rest": 60.0,
                          "output_torque": 0.0})),
        {"cams": "a cam on a shaft; its template is a cam template in its own terms (or template = \"path.toml\")",
         "cams.template.motion.lift": "degrees of the follower arm's swing",
         "linkages": "a linkage the machine drives; its template is a linkgen template (or a path to one)",
         "linkages.template.linkage.crank": "mm: the four-bar's input link, the follower's arm",
         "couplings": "the follower of cams.lever is the crank of linkages.output: crank angle = rest + swing"}),
}


class MachineKind(KindBase["MachineSpec", "MachineDesign"]):
    """A machine (a ``[machine]`` table): cams on phased shafts driving four-bars through their followers' arms.
    Its modules are imported when first asked for, so the registry stays light."""

    name: str = "machine"
    starters: Mapping[str, Starter] = STARTERS
    formats: frozenset[str] = MACHINE_FORMATS
    title: str = "a machine"
    table_key: str = "machine"
    unsized: str = "a machine has no base radius of its own to size; size each cam's template"

    @property
    def spec(self) -> type[MachineSpec]:
        from camgen.kinds.machine import spec

        return spec.MachineSpec

    def operations(self) -> Operations[MachineSpec, MachineDesign]:
        from camgen.kinds.machine import design, outputs, report

        return Operations(design.design_machine, outputs.machine_bundle, report.summary, outputs.machine_row)

    def sheet_refusal(self, spec: Any) -> str | None:
        return "a machine's cams and linkages write their own cut files; a family's [sheet] nests single cams"

    def animator(self) -> Animator:
        from camgen.kinds.machine.animation import machine_frames

        return machine_frames


KIND = MachineKind()
