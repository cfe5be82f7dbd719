"""A machine's ratchets' parts (``[[ratchets]]``): each wheel, its holding pawl and the pawl its follower's arm
carries, cut and printed as the followers' parts are (``<machine>-<ratchet>-wheel.dxf|-cut.svg|.stl|.3mf``,
``-pawl...``, ``-lever-pawl...``) and listed in the kit with them (:func:`camgen.kinds.machine.follower_parts
.follower_parts`). No I/O.

The outlines are linkgen's (:mod:`linkgen.mechanisms.ratchet`): the wheel's saw teeth about its axle's hole, and the
pawl (:func:`~linkgen.mechanisms.ratchet.pawl_shape`) as wide as the follower's arm, in its own frame with its pivot
at the origin and its pin's hole there. The arm's pawl is the holding pawl's figure (linkgen's lever pawl is the same
outline turned to the tooth it drives), its pin in the arm's hole at its pivot's distance from the wheel's axis
(:func:`camgen.kinds.machine.ratchet_bodies.ratchet_bodies`). Each hole is the pin's ISO 273 medium clearance hole.
The pawls' springs are not drawn yet. Lengths mm.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.core.errors import DesignError, SpecError
from camgen.core.kit import Plate
from camgen.core.shapes import Contour
from camgen.kinds.machine.follower_parts import FollowerPart
from linkgen.mechanisms.ratchet import RatchetMechanism, pawl_shape

#: the pawls' pins and the wheel's axle (mm): as a follower's pivot pin
PIN_MM = 4.0


def pawl_width(design: Any, motion: Any) -> float:
    """A ratchet's pawls' width (mm): its follower's arm's, the roller's radius."""
    from camgen.kinds.machine.design import _cam_of

    return float(_cam_of(design.cam(motion.cam).design).follower.roller_radius)


def ratchet_parts(design: Any) -> tuple[FollowerPart, ...]:
    """Each ratchet's wheel, holding pawl and arm's pawl of ``design`` (a
    :class:`~camgen.kinds.machine.design.MachineDesign`) whose wheel the clash check placed, as thick as the arm.

    Raises
    ------
    SpecError
        Naming ``ratchets[i].pawl``: a pawl of the arm's width that does not fit the wheel's teeth (linkgen's check).
    """
    from camgen.kinds.machine.frame import pin_hole, thicknesses

    thick = thicknesses(design)
    hole = pin_hole(PIN_MM)
    out = []
    for i, motion in enumerate(design.ratchets):
        body = f"ratchets.{motion.name}.wheel"
        if body not in thick:
            continue
        tol = float(design.cam(motion.cam).design.tolerance)
        ratchet = RatchetMechanism().build(motion.table)
        try:
            points, bulges = pawl_shape(ratchet, pawl_width(design, motion), tol)
        except DesignError as exc:
            raise SpecError(str(exc).partition(": ")[2] or str(exc), f"ratchets[{i}].pawl") from None
        pawl = Contour(np.asarray(points) - ratchet.pawl.pivot, bulges)
        t = thick[body]
        out.append(FollowerPart(body, "ratchet wheel", Plate(f"{motion.name}-wheel", Contour(*ratchet.wheel.outline()),
                                                             (((0.0, 0.0), hole),), t, tol)))
        for suffix, what in (("pawl", "holding pawl"), ("lever-pawl", "arm's pawl")):
            out.append(FollowerPart(f"ratchets.{motion.name}.{suffix}", what,
                                    Plate(f"{motion.name}-{suffix}", pawl, (((0.0, 0.0), hole),), t, tol)))
    return tuple(out)
