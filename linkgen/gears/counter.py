"""A counter's second stage: a Geneva step that turns a tens wheel one slot a turn of the units wheel, and the
units wheel's turn over the strokes of its ratchet's lever (pure numpy).

Frame: the units wheel's axis O1 at the origin, the tens wheel's axis O2 at C (cos psi, sin psi), psi the
transfer's ``angle``. The units wheel turns counter-clockwise; it carries the transfer pin on the circle of radius
a = C sin(pi / n) about O1 (n slots on the tens wheel; radial entry: the slot's line is tangent to the pin's circle
where the pin enters and leaves, so the wheel starts and stops without a jerk of speed). With alpha the pin's angle
from the line O1 -> O2 (counter-clockwise), the pin is in a slot while |alpha| <= w / 2, w = pi - 2 pi / n (the
**window**), and the tens wheel turns **clockwise** by

    beta(alpha) + pi / n,   tan(beta) = sin(alpha) / (C / a - cos(alpha))

from pi / n before the pin's entry to pi / n past it: one step, 2 pi / n, a window. Through the rest of the units
wheel's turn the tens wheel dwells, held by the locking disc on the units wheel in its concave locking arc.

At rest (units turn 0) the pin has left a slot by the ``lead`` lambda (alpha = w / 2 + lambda; the counter takes
half a stroke's index, so that the locking disc holds the wheel both ways at rest): the next transfer runs over the
units turn [2 pi - w - lambda, 2 pi - lambda] of each turn, so it ends before the units wheel completes a turn, and
after k strokes of a lever that indexes the units wheel 2 pi / N a stroke (N strokes a turn, lambda below a stroke's
index) the tens wheel has made floor(k / N) steps.

The lever's stroke (:func:`stroke_turns`): its angle from rest is swing (1 - cos 2 pi u) / 2 over a stroke's
fraction u (out for u < 1/2, back after); going out its pawl meets the tooth's face after the lost motion
(swing - index) and drives the wheel through the index; coming back it rides over the teeth and the wheel is
held. Lengths mm, angles rad.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: grace (a fraction of a turn) for a units turn given as an exact multiple of a turn
TURN_GRACE = 1e-12


@dataclass(frozen=True)
class Transfer:
    """The Geneva step: ``slots`` n on the tens wheel, ``centre_distance`` C (mm) between the axes, the pin's
    ``lead`` lambda (rad) past its exit at rest."""

    slots: int
    centre_distance: float
    lead: float = 0.0

    @property
    def step(self) -> float:
        """The tens wheel's step, 2 pi / n (rad)."""
        return 2 * math.pi / self.slots

    @property
    def pin_radius(self) -> float:
        """a = C sin(pi / n) (mm): the transfer pin's circle about the units wheel's axis."""
        return self.centre_distance * math.sin(math.pi / self.slots)

    @property
    def window(self) -> float:
        """w = pi - 2 pi / n (rad): the units wheel's turn while the pin is in a slot."""
        return math.pi - 2 * math.pi / self.slots

    @property
    def entry_radius(self) -> float:
        """b = C cos(pi / n) (mm): how far from the tens wheel's axis the pin's centre enters a slot."""
        return self.centre_distance * math.cos(math.pi / self.slots)

    @property
    def deepest(self) -> float:
        """C - a (mm): the pin's centre nearest the tens wheel's axis (alpha = 0)."""
        return self.centre_distance - self.pin_radius

    def in_slot(self, alpha: np.ndarray) -> np.ndarray:
        """The tens wheel's clockwise turn (rad) from its dwell before the pin's entry, at the pin's angles
        ``alpha`` (rad, in [-w/2, w/2]): beta(alpha) + pi / n, 0 at entry and 2 pi / n at exit."""
        alpha = np.asarray(alpha, dtype=float)
        ratio = self.centre_distance / self.pin_radius
        return np.arctan2(np.sin(alpha), ratio - np.cos(alpha)) + math.pi / self.slots

    def tens_turn(self, units_turn: np.ndarray) -> np.ndarray:
        """The tens wheel's clockwise turn (rad) from rest at the units wheel's counter-clockwise turns
        ``units_turn`` (rad, >= 0) from rest: its completed steps, plus its motion in the window."""
        whole, alpha = self._alpha(units_turn)
        moving = alpha >= -self.window / 2
        step = np.where(moving, self.in_slot(np.clip(alpha, -self.window / 2, self.window / 2)), 0.0)
        return whole * self.step + step

    def _alpha(self, units_turn: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The transfers completed and the pin's angle alpha from the centre line (rad, in [w/2 - 2 pi, w/2): past
        the last exit and round to the next) at the units turns ``units_turn`` (rad)."""
        turns = (np.asarray(units_turn, dtype=float) + self.lead) / (2 * math.pi)
        whole = np.floor(turns + TURN_GRACE)
        part = np.clip(turns - whole, 0.0, 1.0) * 2 * math.pi          # the units wheel's turn past the last exit
        return whole, part - (2 * math.pi - self.window / 2)

    def tens_rate(self, units_turn: np.ndarray) -> np.ndarray:
        """d(tens turn) / d(units turn) at ``units_turn`` (rad): 0 in the dwell, in the window
        (C/a cos(alpha) - 1) / (C^2/a^2 - 2 C/a cos(alpha) + 1), 0 at entry and exit (radial)."""
        _, alpha = self._alpha(units_turn)
        ratio = self.centre_distance / self.pin_radius
        c = np.cos(alpha)
        rate = (ratio * c - 1) / (ratio * ratio - 2 * ratio * c + 1)
        return np.where(np.abs(alpha) <= self.window / 2, rate, 0.0)

    def pin(self, units_turn: np.ndarray, angle: float) -> np.ndarray:
        """The transfer pin's centre (n, 2) mm at the units turns ``units_turn`` (rad), the tens wheel's axis at
        ``angle`` psi (rad) from O1: at rest on the pin's circle at psi + w / 2 + lambda."""
        phi = angle + self.window / 2 + self.lead + np.asarray(units_turn, dtype=float)
        return self.pin_radius * np.stack([np.cos(phi), np.sin(phi)], axis=-1)


def stroke_turns(strokes: np.ndarray, index: float, swing: float) -> tuple[np.ndarray, np.ndarray]:
    """The lever's angle and the units wheel's counter-clockwise turn from rest (rad, each shaped like
    ``strokes``) at ``strokes`` (a number of strokes, >= 0, its fraction a stroke's progress) of a lever swinging
    ``swing`` that indexes the wheel ``index`` (rad, <= swing) a stroke (see the module's notes)."""
    t = np.asarray(strokes, dtype=float)
    whole = np.floor(t)
    u = t - whole
    lever = swing * (1 - np.cos(2 * math.pi * u)) / 2
    return lever, whole * index + np.where(u < 0.5, driven(lever, index, swing), index)


def driven(lever: np.ndarray, index: float, swing: float) -> np.ndarray:
    """The units wheel's turn (rad) on a stroke going out, the lever at ``lever`` (rad from rest): nothing over the
    lost motion swing - index, then with the lever up to the index."""
    return np.clip(np.asarray(lever, dtype=float) - (swing - index), 0.0, index)
