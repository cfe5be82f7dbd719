"""Toothed wheels as the frames of an animation, shared by the gear pair (:mod:`linkgen.mechanisms.gearpairframes`)
and the gear trains (:mod:`linkgen.mechanisms.geartrainframes`): each wheel's outline turned and placed frame by frame,
its pitch circle dashed, a driver's tooth 0 marked by a radius, arms (a carrier's) and traced paths. Pure: returns the
frames (:func:`camgen.core.frames.render`).

A cycle is the fewest whole turns of the input after which every wheel shows the same picture again
(:func:`cycle_turns`): a wheel without a mark looks the same after a whole number of its tooth pitches, a marked one
after a whole number of turns.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.frames import bounds, fill, render

#: the most input turns an animation's cycle may take (a ratio of large coprime numbers would need more)
MAX_TURNS = 60
#: the colour a marked wheel's tooth-0 radius is drawn in (matplotlib's C3, red)
MARK = "C3"


@dataclass(frozen=True)
class Wheel:
    """One wheel over the frames: its outline (m, 2) mm about its own centre at angle 0 (tooth 0 on +X), its pitch
    radius (mm), its angle (n,) rad counter-clockwise and centre (n, 2) mm at each frame, whether its tooth 0 is
    marked, whether it is a ring (its outline a toothed hole, drawn as a line), and its fill colour (wheels that
    stand for one another, a train's planets, share one so that the picture repeats when they change places)."""

    outline: np.ndarray
    pitch_radius: float
    angles: np.ndarray
    centres: np.ndarray
    marked: bool = False
    internal: bool = False
    colour: str = "C0"

    def drawn(self, k: int) -> np.ndarray:
        """The outline (m, 2) mm at frame ``k``."""
        a = float(self.angles[k])
        c, s = math.cos(a), math.sin(a)
        return self.outline @ np.array([[c, s], [-s, c]]) + self.centres[k]


def cycle_turns(rates: list[tuple[float, bool]], teeth: list[int]) -> int:
    """The fewest whole input turns after which every wheel looks as it did: ``rates`` each wheel's (turns per input
    turn, marked), ``teeth`` its teeth. A marked wheel must turn a whole number of turns, an unmarked one a whole
    number of its pitches (r z teeth an input turn); rates are ratios of teeth (read to 1e-9). A :class:`SpecError`
    naming ``linkage`` where that is more than :data:`MAX_TURNS`."""
    turns = 1
    for (rate, marked), z in zip(rates, teeth, strict=True):
        per_turn = Fraction(rate * (1 if marked else z)).limit_denominator(10**6)
        if per_turn == 0:
            continue
        # T per_turn must be whole: T a multiple of the denominator of per_turn
        q = per_turn.denominator
        turns = turns * q // math.gcd(turns, q)
    if turns > MAX_TURNS:
        raise SpecError(f"its wheels come back to where they started only after {turns} turns of the input: "
                        f"linkgen animates a cycle of at most {MAX_TURNS}", "linkage")
    return turns


def wheel_frames(wheels: list[Wheel], arms: list[np.ndarray], paths: list[np.ndarray],
                 size: tuple[int, int]) -> np.ndarray:
    """The ``wheels`` drawn at each of their frames, ``size`` (width, height) pixels: the ``paths`` ((m, 2) mm) whole,
    then each wheel filled (a ring outlined) with its pitch circle dashed and a marked wheel's tooth-0 radius, then the
    ``arms`` ((n, 2, 2) mm: a line per frame). The view holds every wheel at every frame. Returns (n, height, width, 3)
    uint8."""
    n = len(wheels[0].angles)
    reach = [w.centres + sign * float(np.hypot(*w.outline.T).max()) for w in wheels for sign in (-1, 1)]
    box = bounds(*reach, *paths)
    circle = np.linspace(0, 2 * math.pi, 181)
    unit = np.column_stack([np.cos(circle), np.sin(circle)])

    def draw(ax: Any, k: int) -> None:
        for path in paths:
            ax.plot(path[:, 0], path[:, 1], "-", color="C1", lw=1.0, alpha=0.8)
        for w in wheels:
            xy = w.drawn(k)
            if w.internal:
                fill(ax, np.vstack([xy, xy[:1]]), fill=False, ec="k", lw=1.0)
            else:
                fill(ax, xy, color=w.colour, alpha=0.45, lw=0)
                ax.plot(*np.vstack([xy, xy[:1]]).T, "-", color="k", lw=0.6)
            centre = w.centres[k]
            pitch = centre + w.pitch_radius * unit
            ax.plot(pitch[:, 0], pitch[:, 1], "--", color="0.4", lw=0.6)
            if w.marked:
                a = float(w.angles[k])
                tip = centre + w.pitch_radius * np.array([math.cos(a), math.sin(a)])
                ax.plot([centre[0], tip[0]], [centre[1], tip[1]], "-", color=MARK, lw=2.0)
            ax.plot([centre[0]], [centre[1]], "o", color="k", ms=3)
        for arm in arms:
            ax.plot(arm[k, :, 0], arm[k, :, 1], "-", color="0.2", lw=2.5)

    return render(draw, n, size, box)
