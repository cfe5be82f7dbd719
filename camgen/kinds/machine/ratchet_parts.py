"""A machine's ratchets' parts (``[[ratchets]]``): each wheel, its holding pawl and the pawl its follower's arm
carries, cut and printed as the followers' parts are (``<machine>-<ratchet>-wheel.dxf|-cut.svg|.stl|.3mf``,
``-pawl...``, ``-lever-pawl...``) and listed in the kit with them (:func:`camgen.kinds.machine.follower_parts
.follower_parts`). No I/O.

The outlines are linkgen's (:mod:`linkgen.mechanisms.ratchet`): the wheel's saw teeth about its axle's hole, and the
pawl (:func:`~linkgen.mechanisms.ratchet.pawl_shape`) as wide as the follower's arm, in its own frame with its pivot
at the origin and its pin's hole there. The arm's pawl is the holding pawl's figure (linkgen's lever pawl is the same
outline turned to the tooth it drives), its pin in the arm's hole at its pivot's distance from the wheel's axis
(:func:`camgen.kinds.machine.ratchet_bodies.ratchet_bodies`). Each hole is the pin's ISO 273 medium clearance hole.
The pawls' springs are not drawn yet. The arm's pawl's pin is a bolt in the kit and the assembly
(:func:`pawl_pins`); the holding pawl's frame pin is the frame's (a seat of its plate). Lengths mm.
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


def pawl_points(design: Any, index: int, motion: Any, width: float) -> np.ndarray:
    """Ratchet ``motion``'s (``ratchets[index]``) pawl outline, ``width`` mm wide, in linkgen's wheel frame at rest
    (mm, counter-clockwise, lines); a :class:`SpecError` naming ``ratchets[index].pawl`` for one that does not fit
    the wheel's teeth (linkgen's check)."""
    tol = float(design.cam(motion.cam).design.tolerance)
    try:
        points, _ = pawl_shape(RatchetMechanism().build(motion.table), width, tol)
    except DesignError as exc:
        raise SpecError(str(exc).partition(": ")[2] or str(exc), f"ratchets[{index}].pawl") from None
    return np.asarray(points, float)


def pawl_pins(design: Any, stack: Any) -> tuple[Any, ...]:
    """Each ratchet's arm's pawl's pin (``ratchets.<name>.pin``, an
    :class:`~camgen.kinds.machine.follower_parts.Axle` of :data:`PIN_MM`, bought as a bolt) placed at
    ``machine.assembly_angle``: through the arm's hole and the pawl, from the arm's bottom to the pawl's top
    (``stack``, the planes' heights)."""
    import math

    from camgen.kinds.machine.follower_parts import Axle
    from camgen.kinds.machine.frame import thicknesses

    thick = thicknesses(design)
    bodies = {b.name: b for b in design.bodies}
    phi = np.array([math.radians(design.spec.machine.assembly_angle)])
    out = []
    for motion in design.ratchets:
        pawl, arm = bodies.get(f"ratchets.{motion.name}.lever-pawl"), bodies.get(f"cams.{motion.cam}.arm")
        if pawl is None or arm is None:
            continue
        centre = pawl.place(phi)[1][0]
        out.append(Axle(f"ratchets.{motion.name}.pin", (float(centre[0]), float(centre[1])), stack.bottom[arm.low],
                        stack.bottom[pawl.low] + thick[pawl.name]))
    return tuple(out)


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
        points = pawl_points(design, i, motion, pawl_width(design, motion))
        pawl = Contour(points - ratchet.pawl.pivot, np.zeros(len(points)))
        t = thick[body]
        out.append(FollowerPart(body, "ratchet wheel", Plate(f"{motion.name}-wheel", Contour(*ratchet.wheel.outline()),
                                                             (((0.0, 0.0), hole),), t, tol)))
        for suffix, what in (("pawl", "holding pawl"), ("lever-pawl", "arm's pawl")):
            out.append(FollowerPart(f"ratchets.{motion.name}.{suffix}", what,
                                    Plate(f"{motion.name}-{suffix}", pawl, (((0.0, 0.0), hole),), t, tol)))
    return tuple(out)
