"""The machine's entry in the kind registry (:data:`camgen.kinds.KINDS`): chosen by its own ``[machine]`` table,
designed by :func:`camgen.kinds.machine.design.design_machine` and written by
:func:`camgen.kinds.machine.outputs.machine_bundle` (both imported when first called)."""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from camgen.kinds.base import Animator, KindBase, Operations, Starter

if TYPE_CHECKING:
    from pathlib import Path

    from camgen.kinds.machine.design import MachineDesign
    from camgen.kinds.machine.spec import MachineSpec

#: what a machine writes: its cams' and linkages' files (those of their kinds that these name; html their own
#: pages), the timing diagram and the report
MACHINE_FORMATS = frozenset(("dxf", "cut-svg", "stl", "3mf", "json", "png", "svg", "html", "step", "gif"))

def _leg(side: str, phase: float) -> tuple[tuple[str, dict[str, Any]], ...]:
    """A walking toy's leg on the legs' shaft: a crank-rocker (ground 60, crank 15, coupler 50, rocker 50 mm) whose
    coupler point P, 110 mm from the crank pin at -70 degrees to the coupler, is the foot; its drawing turned 330
    degrees so that the foot's flat run is at the bottom."""
    return (("[linkages]", {"name": f"{side}-leg", "shaft": "legs", "phase": phase, "side": side}),
            ("linkages.template.linkage", {"type": "linkage", "ground": ["O", "Q"],
                                           "input": {"link": "crank", "pivot": "O"}, "tracers": ["P"]}),
            ("linkages.template.linkage.joints", {"O": [0.0, 0.0], "Q": [51.961524227, -30.0],
                                                  "A": [7.5, 12.990381057], "B": [57.042168229, 19.741200795],
                                                  "P": [58.733852935, -84.349704794]}),
            ("linkages.template.linkage.links", {"crank": ["O", "A"], "coupler": ["A", "B", "P"],
                                                 "rocker": ["Q", "B"]}),
            ("linkages.template.parts", {"width": 8.0, "thickness": 3.0, "pin_diameter": 3.0}))


#: ``camgen new machine``: one cam whose follower's arm is a four-bar's crank; ``walking-toy``: two legs on a shaft
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
    "walking-toy": Starter(
        "A walking toy: a hand crank turns two four-bar legs in antiphase through a gear pair, a foot on each coupler.",
        (("machine", {"main": "crank", "rpm": 30.0}),
         ("[shafts]", {"name": "crank", "at": [40.5, 0.0]}),
         ("[shafts]", {"name": "legs", "at": [0.0, 0.0]}),
         ("[gears]", {"driver": "crank", "driven": "legs", "driver_teeth": 36, "driven_teeth": 18, "module": 1.5}),
         ("output", {"formats": ["dxf", "json", "png", "svg"]}),
         *(table for side, phase in (("front", 0.0), ("back", 180.0)) for table in _leg(side, phase))),
        {"gears": "the hand crank's 36 teeth turn the legs' 18: the legs' shaft turns twice (the other way) a turn",
         "linkages": "a leg turned by the legs' shaft; its template is a linkgen template (or a path to one)",
         "linkages.template.linkage.joints": "mm: the leg drawn with its crank at 60 degrees (O its pivot on the "
                                             "shaft, Q the rocker's pivot on the frame, P the foot); a crank-rocker "
                                             "whose transmission angle stays within 53-98 degrees"}),
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

    def beside(self, raw: dict[str, Any], folder: Path) -> dict[str, Any]:
        """Each mount's template path read from the machine template's folder
        (:func:`camgen.kinds.machine.mounts.beside`)."""
        from camgen.kinds.machine.mounts import beside

        return beside(raw, folder)

    def animator(self) -> Animator:
        from camgen.kinds.machine.animation import machine_frames

        return machine_frames


KIND = MachineKind()
