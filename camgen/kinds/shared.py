"""What the cam kinds of the shared ``[cam]`` table have in common: :class:`SharedTableKind` (disc, plate, grooved,
barrel and conjugate cams: one spec, a check of its keys, the follower on the cam) and :class:`FlatKind` (disc and
plate cams: a flat plate cut to a profile, one design and one bundle).

The shared table, the kinds' ``check`` and ``follower`` stay until each kind owns its table (step S5b of issue 31)
and the cam's set-up is built without a spec (step S3).
"""
from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

from camgen.followers import FOLLOWERS
from camgen.kinds.base import KindBase, Operations, SizeReport

if TYPE_CHECKING:
    from camgen.design import CamDesign
    from camgen.spec import CamSpec

D = TypeVar("D")


def disc_follower(spec: Any, base_radius: float, roller_radius: float) -> Any:
    """The follower ``spec`` describes on a disc turning in ``cam.rotation``'s sense (a disc cam's, a grooved cam's
    and a conjugate pair's first cam's)."""
    sense = 1 if spec.cam.rotation == "ccw" else -1
    return FOLLOWERS[spec.follower.type].make(spec.follower, base_radius, roller_radius, sense)


class SharedTableKind(KindBase["CamSpec", D]):
    """A cam kind whose ``[cam]`` keys are the shared :class:`~camgen.spec.CamTable`'s: its spec is
    :class:`~camgen.spec.CamSpec`, whose validation calls :attr:`check` (``ValueError("field: why")`` for a spec this
    kind cannot take); the cam builder asks :attr:`follower` for the follower on a cam of base radius
    ``base_radius`` (mm) under a roller of ``roller_radius`` (mm; 0 for a knife edge or a flat face): by default
    :func:`disc_follower`. Its cut part is nested on a family's ``[sheet]`` where it writes one (a DXF)."""

    check: Callable[[CamSpec], None]
    follower: Callable[[CamSpec, float, float], Any] = staticmethod(disc_follower)

    @property
    def spec(self) -> type[CamSpec]:
        from camgen.spec import CamSpec

        return CamSpec

    def sheet_refusal(self, spec: CamSpec) -> str | None:
        if "dxf" not in spec.output.formats:
            return 'it writes no cut file to nest: add "dxf" to output.formats'
        return None


class FlatKind(SharedTableKind["CamDesign"]):
    """A cam cut to a profile from a flat plate, a disc or a plate (linear) cam: designed by
    :func:`camgen.design.design_profile`, written by :func:`camgen.outputs.cam_bundle`, sized by
    :func:`camgen.sizing.size_cam`."""

    def operations(self) -> Operations[CamSpec, CamDesign]:
        from camgen.design import design_profile
        from camgen.outputs import cam_bundle, cam_row
        from camgen.report import cam_summary
        from camgen.sizing import size_cam

        return Operations(design_profile, cam_bundle, cam_summary,
                          lambda design, report: cam_row(design, report, design.outline.contour.flatten,
                                                         design.spec.cam.bore),
                          lambda spec: SizeReport(size_cam(spec)))
