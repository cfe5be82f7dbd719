"""What the cam kinds chosen by ``cam.kind`` have in common: :class:`SharedTableKind` (disc, plate, grooved, barrel
and conjugate cams: a spec of :class:`~camgen.spec.CamSpec`'s shape with the kind's own ``[cam]`` table, a check of
the values its table cannot check alone, the follower on the cam) and :class:`FlatKind` (disc and plate cams: a flat
plate cut to a profile, one design and one bundle).

The kinds' ``check`` and ``follower`` (the follower on a spec's cam, for :func:`camgen.flat.build_cam`) stay until the
kinds are packages (step S6 of issue 31). A flat kind's design and size take its :meth:`FlatKind.mount`
(:mod:`camgen.rig`), not the spec's kind.
"""
from __future__ import annotations

from abc import abstractmethod
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

from camgen.kinds.base import KindBase, Operations, SizeReport
from camgen.rig import Mount, disc_mount

if TYPE_CHECKING:
    from camgen.flat import FlatCamDesign
    from camgen.spec import CamSpec, FlatSpec

D = TypeVar("D")
#: a cam kind's spec, and a flat cam kind's
S = TypeVar("S", bound="CamSpec")
F = TypeVar("F", bound="FlatSpec")


def disc_follower(spec: Any, base_radius: float, roller_radius: float) -> Any:
    """The follower ``spec`` describes on a disc turning in ``cam.rotation``'s sense (a disc cam's, a grooved cam's
    and a conjugate pair's first cam's): the disc's mount's (:func:`camgen.rig.disc_mount`)."""
    return disc_mount(spec.follower, spec.cam.rotation).at(base_radius, roller_radius)


class SharedTableKind(KindBase[S, D]):
    """A cam kind chosen by ``cam.kind``: its :attr:`spec` is a :class:`~camgen.spec.CamSpec` holding the kind's own
    ``[cam]`` table (:mod:`camgen.tables`, which refuses another kind's keys), whose validation calls :attr:`check`
    (``ValueError("field: why")`` for values this kind cannot take: a rule across tables, or one of geometry); the
    cam builder asks :attr:`follower` for the follower on a cam of base radius ``base_radius`` (mm) under a roller of
    ``roller_radius`` (mm; 0 for a knife edge or a flat face): by default :func:`disc_follower`. Its cut part is
    nested on a family's ``[sheet]`` where it writes one (a DXF)."""

    check: Callable[[S], None]
    follower: Callable[[S, float, float], Any] = staticmethod(disc_follower)

    def thumbnail_bore(self, spec: S) -> float:
        return float(spec.cam.bore)

    def sheet_refusal(self, spec: S) -> str | None:
        if "dxf" not in spec.output.formats:
            return 'it writes no cut file to nest: add "dxf" to output.formats'
        return None


class FlatKind(SharedTableKind[F, "FlatCamDesign"]):
    """A cam cut to a profile from a flat plate, a disc or a plate (linear) cam: its follower on the kind's
    :meth:`mount`, designed by :func:`camgen.flat.design_flat`, written by :func:`camgen.outputs.cam_bundle`, sized
    by :func:`camgen.flat.size_flat`."""

    @abstractmethod
    def mount(self, spec: F) -> Mount:
        """How the kind carries the follower ``spec`` describes (:mod:`camgen.rig`)."""

    def operations(self) -> Operations[F, FlatCamDesign]:
        from camgen.flat import design_flat, size_flat
        from camgen.outputs import cam_bundle, cam_row
        from camgen.report import cam_summary

        return Operations(lambda spec: design_flat(spec, self.mount(spec)), cam_bundle, cam_summary,
                          lambda design, report: cam_row(design, report, design.outline.contour.flatten),
                          lambda spec: SizeReport(size_flat(spec, self.mount(spec))))
