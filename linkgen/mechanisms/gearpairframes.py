"""A gear pair's animation (``type = "gear-pair"``, external or internal): the pinion and the gear (or ring) drawn
with their teeth, turning at their ratio, the pinion's tooth 0 marked by a radius; one cycle is one pinion turn, in
which the other member turns z1 of its pitches and so shows the same picture again. A rack and pinion is not
animated (its rack runs a limited travel; refused naming ``linkage.kind``)."""
from __future__ import annotations


import numpy as np

from camgen.core.errors import SpecError
from camgen.core.frames import cycle
from camgen.core.shapes import Contour
from linkgen.gears.pair import GearPair
from linkgen.mechanisms.gearframes import Wheel, cycle_turns, wheel_frames
from linkgen.mechanisms.gearparts import outlines

#: the outlines are flattened within this share of the module (mm)
RESOLUTION = 0.02


def pair_inputs(pair: GearPair, n: int) -> np.ndarray:
    """The ``n`` pinion angles (rad) of one cycle from the mesh phase, counter-clockwise: a whole number of pinion
    turns (:func:`linkgen.mechanisms.gearframes.cycle_turns`, one for every external or internal pair)."""
    if pair.kind == "rack":
        raise SpecError("linkgen animates external and internal gear pairs, not a rack and pinion", "linkage.kind")
    assert pair.gear_teeth is not None
    turns = cycle_turns([(1.0, True), (pair.speed_ratio, False)], [pair.pinion_teeth, pair.gear_teeth])
    return pair.mesh_phases[0] + turns * (cycle(n, True, 0.0, 0.0))


def pair_frames(pair: GearPair, values: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    """The pair at pinion angles ``values`` (rad), ``size`` (width, height) pixels: the pinion about the origin at
    its angle, the other member about (c, 0) at :meth:`GearPair.gear_angle`. Returns (n, height, width, 3) uint8."""
    theta = np.asarray(values, dtype=float)
    res = RESOLUTION * pair.module
    shapes = outlines(pair, res)
    r1, r2 = pair.working_pitch_radii
    n = len(theta)
    pinion = Wheel(Contour(*shapes.pinion).flatten(res), r1, theta, np.zeros((n, 2)), marked=True)
    other = Wheel(Contour(*shapes.other).flatten(res), r2, pair.gear_angle(theta),
                  np.tile([pair.centre_distance, 0.0], (n, 1)), internal=pair.kind == "internal", colour="C2")
    return wheel_frames([pinion, other], [], [], size)
