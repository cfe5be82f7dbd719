"""The defects that make a four-bar that meets every target at its own pose useless for the task.

* ``grashof``: the task asks for a crank that turns fully and the crank is not the shortest link of
  a Grashof chain (S + L < P + Q);
* ``order``: turning one way, the crank does not meet the targets in the order given;
* ``branch``: the targets are met on different assembly branches (B on either side of the line
  from A to O4), or the crank, not turning fully, would have to pass a toggle between two targets:
  the linkage cannot move from one to the next without being taken apart.

Crank angles are measured counter-clockwise from the ground line (O2 -> O4), in radians.
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from linkgen.kinematics.fourbar import FourBar
from linkgen.kinematics.grashof import classify

TWO_PI = 2.0 * math.pi
#: crank angles closer than this (rad) count as the same
ANGLE_TOL = 1e-9


def sense(theta2: ArrayLike) -> int:
    """+1 if turning counter-clockwise from the first angle meets the others in order, -1 if clockwise does,
    0 if neither (an order defect)."""
    t = np.asarray(theta2, dtype=float)
    for s in (1, -1):
        travel = np.mod(s * (t[1:] - t[0]), TWO_PI)
        if np.all(travel > ANGLE_TOL) and np.all(np.diff(travel) > ANGLE_TOL):
            return s
    return 0


def _within_reach(fb: FourBar, theta2: ArrayLike, turn: int) -> bool:
    """Whether the crank turns from the first angle through the others (in sense ``turn``) without a toggle."""
    ranges = fb.input_ranges()
    if ranges is None:
        return True
    t = np.asarray(theta2, dtype=float)
    travel = np.mod((turn or 1) * (t - t[0]), TWO_PI) * (turn or 1)
    lo, hi = t[0] + min(travel.min(), 0.0), t[0] + max(travel.max(), 0.0)
    for a, b in ranges:
        for k in (-2, -1, 0, 1, 2):
            if a - 1e-12 <= lo + k * TWO_PI and hi + k * TWO_PI <= b + 1e-12:
                return True
    return False


def defects(lengths: tuple[float, float, float, float], theta2: ArrayLike, branches: ArrayLike,
            crank: bool) -> list[str]:
    """The defects (see the module) of the four-bar of ``lengths`` (ground, crank, coupler, rocker; mm) meeting
    the targets at crank angles ``theta2`` (rad, from the ground line) on ``branches`` (+1 open, -1 crossed,
    one a target); ``crank``: the task asks for a crank that turns fully."""
    found = []
    g = classify(*lengths)
    if crank and not (g.grashof_class == "I" and g.input_turns_fully):
        found.append("grashof")
    turn = sense(theta2)
    if turn == 0:
        found.append("order")
    signs = set(np.sign(np.asarray(branches, dtype=float)).tolist())
    try:
        reach = _within_reach(FourBar(*lengths), theta2, turn)
    except SpecError:                                   # the chain cannot close: no motion at all
        reach = False
    if len(signs) > 1 or not reach:
        found.append("branch")
    return found
