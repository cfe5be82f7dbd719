"""One motion for every shaft of a machine: its angle Q(phi) and its rates Q' = dQ/dphi, Q'' = d^2Q/dphi^2 against
the main shaft's angle phi, whatever turns it.

Angles in radians, counter-clockwise in the machine's frame, 0 at the machine's start; rates per radian (and per
radian squared) of the main shaft, which turns steadily. Three kinds of shaft:

* a uniform one, turned from the main shaft through gear pairs alone: Q = n phi, Q' = n, Q'' = 0 (n its turns per
  main turn, :attr:`~camgen.kinds.machine.spec.MachineSpec.turns`, negative where it turns clockwise);
* a Geneva drive's wheel shaft (:class:`~camgen.kinds.machine.indexing.Indexer`): Q = s W(phi), its wheel's turn W
  counted in the wheel's own sense and s the sign of its mean turns (the wheel turns the other way from its driver);
* a shaft geared to an indexed one, through any number of pairs: Q = r Q_w, r the pairs' ratio (its mean turns
  over the wheel shaft's), so it indexes and dwells with the wheel.

For the last two Q = (n / m) W, m the wheel's mean turns in its own sense (:attr:`Indexer.mean_turns`): over a main
turn each shaft turns its mean turns n, as the uniform formula does. A shaft's angle in its own sense (a cam's
program angle runs with it) is sign(n) Q.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.kinds.machine.indexing import Indexer, wheel_of


@dataclass(frozen=True)
class ShaftMotion:
    """A shaft's angle against the main shaft's: its ``name``, its mean ``turns`` per main turn (signed) and the
    Geneva drive ``indexer`` whose wheel turns it (directly or through gears), None for a uniform shaft."""

    name: str
    turns: float
    indexer: Indexer | None = None

    @property
    def uniform(self) -> bool:
        """Whether it turns steadily with the main shaft (no Geneva drive before it)."""
        return self.indexer is None

    def angles(self, phi: np.ndarray) -> np.ndarray:
        """(3, n): Q (rad, counter-clockwise), Q' (rad/rad) and Q'' (rad/rad^2) at main shaft angles ``phi``
        (rad)."""
        phi = np.asarray(phi, dtype=float)
        if self.indexer is None:
            return np.stack([self.turns * phi, np.full(phi.shape, self.turns), np.zeros(phi.shape)])
        scale = self.turns / self.indexer.mean_turns
        return scale * np.stack(self.indexer.wheel_rates(phi))

    def own(self, phi: np.ndarray) -> np.ndarray:
        """(3, n): its angle and rates in its own sense of rotation (sign(turns) Q, ...): what a cam's program
        angle follows (|n| phi on a uniform shaft)."""
        phi = np.asarray(phi, dtype=float)
        if self.indexer is None:
            n = abs(self.turns)
            return np.stack([n * phi, np.full(phi.shape, n), np.zeros(phi.shape)])
        return math.copysign(1.0, self.turns) * self.angles(phi)


def shaft_motions(spec: Any, indexed: tuple[Indexer, ...]) -> dict[str, ShaftMotion]:
    """Every driven shaft of ``spec`` (a :class:`~camgen.kinds.machine.spec.MachineSpec`, its ``turns``) as a
    :class:`ShaftMotion`: indexed where a Geneva drive of ``indexed`` turns it, or turns a shaft geared to it."""
    driver_of = {g.driven: g.driver for g in spec.gears}
    out = {}
    for name, turns in spec.turns.items():
        shaft, seen = name, set()
        while wheel_of(indexed, shaft) is None and shaft in driver_of and shaft not in seen:
            seen.add(shaft)
            shaft = driver_of[shaft]
        out[name] = ShaftMotion(name, float(turns), wheel_of(indexed, shaft))
    return out
