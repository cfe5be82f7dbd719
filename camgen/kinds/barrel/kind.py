"""The barrel (cylindrical) cam: a groove round a cylinder drives a translating roller along the cam's axis.

The cylinder is ``cam.length`` long with the groove ``cam.groove_depth`` deep about the pitch cylinder of
radius ``cam.pitch_radius`` (the groove's mid-depth); the roller's centre runs on the pitch cylinder at
z = z0 + s, z0 putting the groove in the middle of the length. Developed (x = Rm theta) the pitch curve is
a plate cam's of travel 2 pi Rm, so the pressure angle is atan(s' / Rm); see :mod:`camgen.kinds.barrel`.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from camgen.kinds.base import Animator, ALL_FORMATS, NESTED, Operations, Starter
from camgen.kinds.barrel.starters import STARTERS
from camgen.kinds.shared import SharedTableKind

if TYPE_CHECKING:
    from camgen.kinds.barrel.design import BarrelDesign
    from camgen.kinds.barrel.table import BarrelSpec


class BarrelKind(SharedTableKind["BarrelSpec", "BarrelDesign"]):
    """A barrel cam (``cam.kind = "barrel"``): designed by :func:`camgen.kinds.barrel.design.design_barrel`, written by
    :func:`camgen.kinds.barrel.outputs.barrel_bundle`; printed round its axis, so no STEP solid and nothing to size."""

    name: str = "barrel"
    title: str = "a barrel cam"
    formats: frozenset[str] = ALL_FORMATS - {"step"}
    unsized: str = ("a barrel cam has no base radius to size: its pitch_radius is the designer's choice (the report "
               "gives the pressure angle at it)")
    starters: Mapping[str, Starter] = STARTERS

    @property
    def spec(self) -> type[BarrelSpec]:
        from camgen.kinds.barrel.table import BarrelSpec

        return BarrelSpec

    def operations(self) -> Operations[BarrelSpec, BarrelDesign]:
        from camgen.kinds.barrel.design import design_barrel
        from camgen.kinds.barrel.outputs import barrel_bundle, summary_lines
        from camgen.outputs import cam_row

        return Operations(design_barrel, barrel_bundle, lambda design, report: summary_lines(report),
                          lambda design, report: cam_row(design, report, design.thumbnail))

    def thumbnail_bore(self, spec: BarrelSpec) -> float:
        return 0.0                                      # its thumbnail is the groove drawn unrolled

    def sheet_refusal(self, spec: BarrelSpec) -> str | None:
        return f"a barrel cam is printed: its DXF is a developed template, not a part to cut; {NESTED}"

    def format_refusal(self, fmt: str) -> str:
        if fmt == "step":
            return ("a barrel cam has no flat part to write as an exact STEP solid (its groove is cut round a "
                    "cylinder); leave 'step' out and use 'stl' or '3mf'")
        return super().format_refusal(fmt)

    def animator(self) -> Animator:
        from camgen.kinds.barrel.animation import barrel_frames

        return barrel_frames


KIND = BarrelKind()
