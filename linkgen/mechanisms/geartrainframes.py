"""A gear train's animation (``type = "gear-train"``: simple, compound, planetary): every gear drawn with its teeth at
the angle and centre :meth:`~linkgen.mechanisms.geartrain.Train.poses` gives it, the input gear's tooth 0 marked by a
radius; a planetary train's carrier as arms from the centre to its planets, the path of its first planet's centre and
of the point of its pitch circle on its tooth 0 (an epicycloid or hypocycloid) traced.

One cycle is the fewest whole turns of the input after which every gear and the carrier look as they did
(:func:`linkgen.mechanisms.gearframes.cycle_turns`): one turn for a train on fixed axes (each gear turns z_input of
its pitches), more for most planetary trains (the carrier must also come back by a whole number of planet spacings:
6 turns of the sun for templates/planetary-train.toml).
"""
from __future__ import annotations

import numpy as np

from camgen.core.frames import cycle
from camgen.core.shapes import Contour
from linkgen.mechanisms.gearframes import Wheel, cycle_turns, wheel_frames
from linkgen.mechanisms.geartrain import Train, _outline

#: the outlines are flattened within this share of the module (mm)
RESOLUTION = 0.02
#: the traced paths' points per input turn
TRACE_STEPS = 360


def input_name(train: Train) -> str:
    """The name of the input member: the first gear of a train on fixed axes, a planetary train's ``input``."""
    return train.table.input if train.table.kind == "planetary" else train.gears[0].name


def _colour(train: Train, k: int) -> str:
    """The fill of gear ``k``: every planet the same (they change places over a cycle), the others in turn."""
    g = train.gears[k]
    if g.carrier:
        return "C2"
    return ("C0", "C4", "C6", "C8", "C9")[k % 5] if k else "C0"


def train_turns(train: Train) -> int:
    """The input turns of one cycle (see the module docstring)."""
    marked = input_name(train)
    rates = [(g.speed, g.name == marked) for g in train.gears]
    teeth = [g.teeth for g in train.gears]
    if train.table.kind == "planetary":
        rates.append((train.carrier_speed, marked == "carrier"))
        teeth.append(train.table.planets)
    return cycle_turns(rates, teeth)


def train_inputs(train: Train, n: int) -> np.ndarray:
    """The ``n`` input angles (rad) of one cycle from 0, counter-clockwise (:func:`train_turns` turns)."""
    return train_turns(train) * cycle(n, True, 0.0, 0.0)


def train_frames(train: Train, values: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    """The train at input angles ``values`` (rad), ``size`` (width, height) pixels. Returns (n, height, width, 3)
    uint8."""
    theta = np.asarray(values, dtype=float)
    res = RESOLUTION * train.table.module
    turned, centres = train.poses(theta)
    marked = input_name(train)
    wheels = [Wheel(Contour(*_outline(g, res)).flatten(res), g.tooth.pitch_radius, turned[g.name], centres[g.name],
                    marked=g.name == marked, internal=g.internal, colour=_colour(train, k))
              for k, g in enumerate(train.gears)]
    planets = [g for g in train.gears if g.carrier]
    arms = [np.stack([centres["carrier"], centres[g.name]], axis=1) for g in planets]
    paths: list[np.ndarray] = []
    if planets:
        first = planets[0]
        dense = np.linspace(0.0, 2 * np.pi * train_turns(train), TRACE_STEPS * train_turns(train) + 1)
        a, c = train.poses(dense)
        angle = a[first.name]
        rim = c[first.name] + first.tooth.pitch_radius * np.column_stack([np.cos(angle), np.sin(angle)])
        paths = [c[first.name], rim]
    return wheel_frames(wheels, arms, paths, size)
