"""The conjugate (dual) cam: two discs on one shaft, each driving one of two rollers of one follower.

Positive drive without a spring: the first cam drives the follower's own roller (the disc cam's: its pitch curve
has the prime radius base radius + roller radius at rest), the second cam a second roller on the same follower,
so each cam holds the follower against the other. A translating follower is a yoke carrying the second roller
``cam.yoke_span`` mm from the first along its line of travel, on the far side of the shaft; an oscillating
follower is a bell crank carrying the second roller on an arm ``cam.second_arm_length`` long at
``cam.arm_angle`` degrees from the first, on the same pivot. Either is set by the second cam's base circle
(``cam.second_base_radius``, by default ``cam.base_radius``) instead. Both rollers are ``follower.roller_radius``.
See :mod:`camgen.kinds.conjugate`.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from camgen.kinds.base import Animator, NESTED, Operations, SizeReport, Starter
from camgen.kinds.conjugate.starters import STARTERS
from camgen.kinds.shared import SharedTableKind

if TYPE_CHECKING:
    from camgen.kinds.conjugate.design import ConjugateDesign
    from camgen.kinds.conjugate.table import ConjugateSpec


class ConjugateKind(SharedTableKind["ConjugateSpec", "ConjugateDesign"]):
    """A conjugate pair (``cam.kind = "conjugate"``): designed by
    :func:`camgen.kinds.conjugate.design.design_conjugate`, written by
    :func:`camgen.kinds.conjugate.outputs.conjugate_bundle`; sized cam by cam, the pair at the larger."""

    name: str = "conjugate"
    title: str = "a conjugate cam"
    starters: Mapping[str, Starter] = STARTERS

    @property
    def spec(self) -> type[ConjugateSpec]:
        from camgen.kinds.conjugate.table import ConjugateSpec


        return ConjugateSpec

    def operations(self) -> Operations[ConjugateSpec, ConjugateDesign]:
        from camgen.kinds.conjugate.design import design_conjugate
        from camgen.kinds.conjugate.outputs import conjugate_bundle, summary_lines
        from camgen.outputs import cam_row

        return Operations(design_conjugate, conjugate_bundle, lambda design, report: summary_lines(report),
                          lambda design, report: cam_row(design, report, design.thumbnail),
                          _size)

    def sheet_refusal(self, spec: ConjugateSpec) -> str | None:
        return f"a conjugate pair's two cams are nested on its own <name>-sheet.dxf; {NESTED}"

    def animator(self) -> Animator:
        from camgen.kinds.conjugate.animation import conjugate_frames

        return conjugate_frames


def _size(spec: ConjugateSpec) -> SizeReport:
    """Each cam sized alone (:func:`camgen.kinds.conjugate.design.size_conjugate`), the pair at the larger."""
    from camgen.kinds.conjugate.design import size_conjugate

    alone = size_conjugate(spec)
    note = (f"each cam alone: cam 1 needs {alone[0].base_radius_mm:.4f} mm (cam.base_radius), cam 2 "
            f"{alone[1].base_radius_mm:.4f} mm (cam.second_base_radius); a pair of equal cams, the larger")
    return SizeReport(max(alone, key=lambda one: one.base_radius_mm),
                      {"each_cam_base_radius_mm": [one.base_radius_mm for one in alone]}, (note,))


KIND = ConjugateKind()
