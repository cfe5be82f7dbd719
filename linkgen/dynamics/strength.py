"""Will it hold: the force each hole and slot carries over the motion, its bearing pressure against the plate's
allowable, and each pin's shear stress against the pin's.

A part's hole at a joint carries the vector sum of the forces the pin puts on that part there (a joint of three
parts puts two pairs' forces on the one between). A slot carries a slide's force across the guide. The bearing
pressure on a hole of diameter d (the pin's, ``parts.pin_diameter``) in a plate t thick (``parts.thickness``) is
p = F / (d t) (N/mm^2 = MPa); the pin's shear stress, in single shear at its most loaded part, tau = F / (pi d^2 / 4)
(exact for a pin through two or three parts; a plane between two pairs of parts may carry more). Allowables: the
material's (:mod:`linkgen.dynamics.materials`) unless ``dynamics.allowable_bearing`` and ``allowable_shear`` give
them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

from linkgen.dynamics.materials import PINS, Material
from linkgen.kinematics.kinetostatics import Kinetostatics

if TYPE_CHECKING:
    from linkgen.dynamics.table import DynamicsTable
    from linkgen.spec import PartsTable


@dataclass(frozen=True)
class HoleLoad:
    """The force (n, 2) N on part ``part``'s hole (or slot) at ``joint`` over the poses (a slot's: at its slider's
    point), with the allowables (MPa) and, with ``[parts]``, the pin's diameter and the plate's thickness (mm)."""

    joint: str
    part: str
    kind: Literal["hole", "slot"]
    force: np.ndarray
    allowable_bearing: float
    allowable_shear: float
    pin_diameter: float | None
    thickness: float | None

    def pressure(self, force: float) -> float | None:
        """The bearing pressure (MPa) of a force (N) on the hole: F / (d t); None without parts."""
        if self.pin_diameter is None or self.thickness is None:
            return None
        return force / (self.pin_diameter * self.thickness)

    def shear(self, force: float) -> float | None:
        """The pin's shear stress (MPa) for that force, in single shear: F / (pi d^2 / 4); None without parts."""
        if self.pin_diameter is None:
            return None
        return force / (math.pi * self.pin_diameter**2 / 4)


def hole_force(k: Kinetostatics, part: str, joint: str, kind: str) -> np.ndarray:
    """The force (n, 2) N on ``part`` at ``joint`` of the kinetostatics ``k``: the sum of its pins' pairs there, or a
    slide's force across the slot of the guide ``part`` (``joint`` the slider's name)."""
    n = len(k.inputs)
    total = np.zeros((n, 2))
    for pf in k.pairs:
        pair = pf.pair
        if kind == "slot":
            if pair.kind == "slide" and pair.slider == joint and pair.by == part:
                total -= pf.force
        elif pair.kind == "pin" and pair.point == joint and part in (pair.on, pair.by):
            total += pf.force if pair.on == part else -pf.force
    return total


def hole_loads(k: Kinetostatics, parts: PartsTable | None, material: Material, table: DynamicsTable,
               bolts: bool = False) -> tuple[HoleLoad, ...]:
    """Every hole and slot of the moving parts and the frame, in the order of the pairs' joints; the pins are
    ``dynamics.pins``, or with ``bolts`` (a ``[kit]``) its steel bolts."""
    bearing = table.allowable_bearing if table.allowable_bearing is not None else material.allowable_bearing
    pin = PINS["steel"] if bolts else PINS[table.pins]
    shear = table.allowable_shear if table.allowable_shear is not None else pin.allowable_shear
    d = None if parts is None else parts.pin_diameter
    t = None if parts is None else parts.thickness
    seen: set[tuple[str, str, str]] = set()
    out = []
    for pf in k.pairs:
        pair = pf.pair
        holes: list[tuple[str, str, Literal["hole", "slot"]]]
        if pair.kind == "pin":
            holes = [(part, pair.point, "hole") for part in (pair.by, pair.on)]
        else:
            holes = [(pair.by, pair.slider, "slot")]
        for part, joint, kind in holes:
            if (part, joint, kind) in seen:
                continue
            seen.add((part, joint, kind))
            out.append(HoleLoad(joint, part, kind, hole_force(k, part, joint, kind), bearing, shear, d, t))
    return tuple(out)
