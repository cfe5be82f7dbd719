"""A barrel cam mounted on a machine's shaft (:mod:`camgen.kinds.barrel`): its drum as a clash body, and why its
follower drives no planar linkage.

A machine's frame lies across its shafts, and its parts move in planes across them. A barrel's follower moves along
its shaft (a translating roller, ``mm`` along the axis) or swings about an axis across it (an oscillating roller,
degrees): out of the frame's plane either way. So its motion is an output of the machine (its timing, its report),
but a coupling from it to a planar linkage is refused in one line, and its follower is not a clash body (the
report's ``clash_check.not_checked`` names it with the reason).

The drum is rotationally symmetric about its shaft: in the frame's plane it is a disc of its rim's radius (the
groove's or rib's outermost, ``BarrelDesign.radii[2]``) about the shaft, with its bore, on its layer's plane, as
high as the drum is long (``cam.length``).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.kinds.machine.clash import Body, circle, fixed

#: why a barrel's follower is neither a coupling's driver nor a clash body
OUT_OF_PLANE = "moves along the shaft (or swings across it), out of the frame's plane"


def is_barrel(cam_design: Any) -> bool:
    """Whether a cam kind's design is a barrel cam's."""
    return getattr(getattr(cam_design, "spec", None), "kind", None) == "barrel"


def drum(name: str, cam_design: Any, plane: int, centre: np.ndarray, tolerance: float) -> Body:
    """The barrel ``cams.<name>``'s drum: a disc of its rim's radius (mm) about the shaft's ``centre`` with its bore,
    on ``plane``."""
    rim = float(max(cam_design.radii))
    bore = float(cam_design.spec.cam.bore) / 2
    return Body(f"cams.{name}", plane, plane, circle(rim, tolerance), fixed(centre), (((0.0, 0.0), bore),))


def thicknesses(design: Any) -> dict[str, float]:
    """Each barrel drum's height along its shaft (mm) by its clash body's name: its ``cam.length``."""
    return {f"cams.{c.name}": float(c.design.spec.cam.length) for c in design.cams if is_barrel(c.design)}


def check_coupling(cam_spec: Any, index: int, cam: str) -> None:
    """Refuse coupling ``couplings[index]`` from the barrel ``cams.<cam>`` to a planar linkage (a
    :class:`ValueError` naming ``couplings[i].cam``); nothing for another kind's cam."""
    if getattr(cam_spec.cam, "kind", None) == "barrel":
        raise ValueError(f"couplings[{index}].cam: cams.{cam} is a barrel cam: its follower {OUT_OF_PLANE}, so it "
                         "drives no planar linkage; couple a disc, plate, grooved or conjugate cam's follower")
