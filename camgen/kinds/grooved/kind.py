"""The grooved face (track) cam: a disc whose face carries a groove the roller runs in, driving it both ways.

The groove's two flanks are the exact offsets of the pitch curve by +/-(Rr + c/2), Rr the
roller's radius and c ``cam.running_clearance``; the groove is a pocket ``cam.groove_depth``
mm deep in the face (see :mod:`camgen.kinds.grooved`). Positive drive holds the follower without a
spring, so rollers only, and no spring or preload; at ``cam.rpm`` with a mass the report gives the forces, the
flank that carries them and the torque (:func:`camgen.forces.drive_report`). The pitch curve
is the disc cam's (prime radius = base radius + roller radius).
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from camgen.kinds.base import Animator, Operations, SizeReport, Starter
from camgen.kinds.grooved.starters import STARTERS
from camgen.kinds.shared import SharedTableKind

if TYPE_CHECKING:
    from camgen.kinds.grooved.design import GroovedDesign
    from camgen.kinds.grooved.table import GroovedSpec


class GroovedKind(SharedTableKind["GroovedSpec", "GroovedDesign"]):
    """A grooved face cam (``cam.kind = "grooved"``): designed by
    :func:`camgen.kinds.grooved.design.design_grooved`, written by :func:`camgen.kinds.grooved.outputs.grooved_bundle`;
    its console lines are a disc cam's and the groove's."""

    name: str = "grooved"
    title: str = "a grooved cam"
    starters: Mapping[str, Starter] = STARTERS

    @property
    def spec(self) -> type[GroovedSpec]:
        from camgen.kinds.grooved.table import GroovedSpec

        return GroovedSpec

    def operations(self) -> Operations[GroovedSpec, GroovedDesign]:
        from camgen.kinds.grooved.design import design_grooved, size_grooved
        from camgen.kinds.grooved.outputs import groove_summary, grooved_bundle
        from camgen.outputs import cam_row
        from camgen.report import cam_summary

        return Operations(design_grooved, grooved_bundle,
                          lambda design, report: [*cam_summary(design, report), groove_summary(report)],
                          lambda design, report: cam_row(design, report, design.outline.contour.flatten),
                          lambda spec: SizeReport(size_grooved(spec)))

    def animator(self) -> Animator:
        from camgen.kinds.grooved.animation import grooved_frames

        return grooved_frames


KIND = GroovedKind()
