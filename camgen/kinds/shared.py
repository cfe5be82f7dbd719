"""What the cam kinds chosen by ``cam.kind`` have in common: :class:`SharedTableKind` (disc, plate, grooved, barrel
and conjugate cams: a spec of :class:`~camgen.spec.CamSpec`'s shape with the kind's own ``[cam]`` table, in its
package's ``table.py``) and :class:`FlatKind` (disc and plate cams: a flat plate cut to a profile, one design and one
bundle).

A kind's rules across its tables, and how its cam carries the follower (its :meth:`~camgen.spec.CamSpec.mount`), are
its spec's: a flat kind's design and size take the spec's mount (:mod:`camgen.rig`), not the spec's kind.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, TypeVar

from camgen.kinds.base import KindBase, Operations, SizeReport

if TYPE_CHECKING:
    from camgen.flat import FlatCamDesign
    from camgen.spec import CamSpec, FlatSpec

D = TypeVar("D")
#: a cam kind's spec, and a flat cam kind's
S = TypeVar("S", bound="CamSpec")
F = TypeVar("F", bound="FlatSpec")


class SharedTableKind(KindBase[S, D]):
    """A cam kind chosen by ``cam.kind``: its :attr:`spec` is a :class:`~camgen.spec.CamSpec` holding the kind's own
    ``[cam]`` table (which refuses another kind's keys) and its own rules (:meth:`~camgen.spec.CamSpec.kind_rules`).
    Its cut part is nested on a family's ``[sheet]`` where it writes one (a DXF)."""

    def thumbnail_bore(self, spec: S) -> float:
        return float(spec.cam.bore)

    def sheet_refusal(self, spec: S) -> str | None:
        if "dxf" not in spec.output.formats:
            return 'it writes no cut file to nest: add "dxf" to output.formats'
        return None


class FlatKind(SharedTableKind[F, "FlatCamDesign"]):
    """A cam cut to a profile from a flat plate, a disc or a plate (linear) cam: its follower on its spec's
    :meth:`~camgen.spec.CamSpec.mount`, designed by :func:`camgen.flat.design_flat`, written by
    :func:`camgen.outputs.cam_bundle` (with the kit of a disc cam's ``[kit]``, :meth:`with_kit`), sized by
    :func:`camgen.flat.size_flat`."""

    def with_kit(self, spec: FlatSpec) -> bool:
        """Whether its bundle holds a kit round the cam (a disc cam's ``[kit]``): not by default."""
        return False

    def operations(self) -> Operations[F, FlatCamDesign]:
        from camgen.flat import design_flat, size_flat
        from camgen.outputs import cam_bundle, cam_row
        from camgen.report import cam_summary

        return Operations(lambda spec: design_flat(spec, spec.mount(), self.bundle),
                          lambda design: cam_bundle(design, self.with_kit(design.spec)), cam_summary,
                          lambda design, report: cam_row(design, report, design.outline.contour.flatten),
                          lambda spec: SizeReport(size_flat(spec, spec.mount())))
