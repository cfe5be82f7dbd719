"""A machine's ratchets (``[[ratchets]]``, :mod:`camgen.kinds.machine.ratchet_mount`) as clash bodies
(:func:`camgen.kinds.machine.clash.machine_parts`): the wheel, its teeth as linkgen draws them
(:meth:`linkgen.gears.ratchet.RatchetWheel.outline`), turning about its follower's pivot.

**Frame.** linkgen draws the wheel about its axis, tooth 0's tip on +Y, driven counter-clockwise. The machine moves
it onto the arm's pivot and turns it by the wheel's angle W in the arm's rising sense; where the arm rises clockwise
(``sense`` -1) the wheel is mirrored about its +Y axis first (its teeth then face the other way, as a clockwise drive
needs them): x_machine = R(sense W) diag(sense, 1) x_wheel + pivot.

**Plane.** Plane 2 ``layer``, else the plane over the follower's arm (the arm's pawl rides on the arm's face); the
wheel turns on the pivot's pin, which reaches up to it, and is as thick as the arm. The pawls are not bodies yet.
Lengths mm, angles radians, counter-clockwise.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.kinds.machine.clash import Body, Placement, rotation


def wheel_placement(motion: Any, pivot: np.ndarray) -> Placement:
    """The wheel's placement (phi -> (M, t)) of ratchet ``motion`` on the pivot at ``pivot`` (mm)."""
    mirror = np.diag([float(motion.sense), 1.0])

    def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        turn = rotation(motion.sense * motion.wheel_angle(phi))
        return turn @ mirror, np.broadcast_to(pivot, (len(phi), 2))

    return place


def ratchet_bodies(design: Any, arms: dict[str, tuple[Any, np.ndarray, int, Any]], bodies: list[Body],
                   pins: dict[tuple[float, float], tuple[list[str], int, float]],
                   arm_pins: dict[str, list[tuple[float, float]]]) -> None:
    """Each ratchet's wheel added to ``bodies``, on its arm's pivot pin (its holder added to ``pins``), and its arm's
    pawl's pin to ``arm_pins`` (each cam's (distance out along its arm, pin diameter) mm: the arm's holes); ``arms``:
    each cam's follower, its pivot (mm), its arm's plane and its arm's direction."""
    from camgen.kinds.machine.ratchet_parts import PIN_MM

    for motion, mount in zip(design.ratchets, design.spec.ratchets, strict=True):
        if motion.cam not in arms:
            continue
        _, pivot, arm_plane, _ = arms[motion.cam]
        plane = arm_plane + 1 if mount.layer is None else 2 * mount.layer
        outline = motion.table.wheel.outline()[0]
        name = f"ratchets.{motion.name}.wheel"
        bodies.append(Body(name, plane, plane, np.asarray(outline, float), wheel_placement(motion, pivot)))
        key = next((k for k in pins if float(np.hypot(k[0] - pivot[0], k[1] - pivot[1])) < 1e-9),
                   (float(pivot[0]), float(pivot[1])))
        entry = pins.setdefault(key, ([], 0, PIN_MM / 2))
        entry[0].append(name)
        arm_pins.setdefault(motion.cam, []).append((float(np.hypot(*motion.table.holding_pawl.pivot)), PIN_MM))


def thicknesses(design: Any, known: dict[str, float]) -> dict[str, float]:
    """Each ratchet's wheel's thickness (mm) by its clash-check name: its follower's arm's (``known``, the others'
    thicknesses), the pawls being cut from the same stock as the arm they ride on."""
    out = {}
    for motion in getattr(design, "ratchets", ()):
        arm = known.get(f"cams.{motion.cam}.arm")
        if arm is not None:
            out[f"ratchets.{motion.name}.wheel"] = arm
    return out
