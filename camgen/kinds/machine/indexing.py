"""A Geneva drive between two of a machine's shafts (``[[genevas]]``, :mod:`camgen.kinds.geneva`): its driver on one
shaft, its wheel on the other, and the wheel shaft's angle as an intermittent function of the main shaft's.

Angles in radians. The driver turns ``driver_turns`` = |n_d| times a main turn (its shaft's turns, through gears);
its pin's angle from the centre line (the driver's shaft towards the wheel's) is alpha(phi) = n_d phi + alpha_0,
alpha_0 the mount's ``phase``. The Geneva law (the Geneva kind's ``GenevaDesign.law``) gives the wheel's
angle beta in (-pi/n, pi/n] over one driver turn (alpha in (-pi, pi]); over many, with alpha = 2 pi k + a, a in
(-pi, pi], the wheel has turned

    W(alpha) = k 2 pi / n + beta(a) + pi / n

(continuous: each driver turn adds one index of 2 pi / n). The wheel shaft's angle is W(alpha(phi)) - W(alpha_0),
0 at the machine's start, counted in the wheel's own sense (it turns the other way from the driver); its rate
dW/dphi = beta'(a) n_d. A cam on the wheel shaft takes its program angle from it, so it moves only while the wheel
indexes. The mean ratio, -1/n times the driver's turns, is the wheel shaft's ``turns``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Indexer:
    """A Geneva drive of the machine: its mount's ``name``, its ``driver`` and ``wheel`` shafts, its ``law`` (the
    Geneva kind's ``GenevaLaw``), the
    driver shaft's turns per main turn ``driver_turns`` (> 0), the pin's angle ``start`` (rad) at the machine's start
    and its ``design`` (the Geneva kind's)."""

    name: str
    driver: str
    wheel: str
    law: Any
    driver_turns: float
    start: float
    design: Any = None

    def driver_angle(self, phi: np.ndarray) -> np.ndarray:
        """alpha (rad, not wrapped) at main shaft angles ``phi`` (rad)."""
        return self.driver_turns * np.asarray(phi, dtype=float) + self.start

    def _turned(self, alpha: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """W (rad), dW/dalpha and d^2W/dalpha^2 at driver angles ``alpha`` (rad, not wrapped)."""
        k = np.ceil((alpha - math.pi) / TWO_PI)
        a = alpha - TWO_PI * k                                  # in (-pi, pi]
        beta = self.law.motion(a)
        return k * self.law.index + beta[0] + math.pi / self.law.slots, beta[1], beta[2]

    def wheel_motion(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The wheel shaft's angle (rad, 0 at the machine's start, in the wheel's sense) and its rate (rad per rad of
        the main shaft) at main shaft angles ``phi`` (rad)."""
        turned, rate, _ = self.wheel_rates(phi)
        return turned, rate

    def wheel_rates(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The wheel shaft's angle W (rad, as :meth:`wheel_motion`) and its rates dW/dphi (rad/rad) and
        d^2W/dphi^2 (rad/rad^2) at main shaft angles ``phi`` (rad): beta' n_d and beta'' n_d^2 (the driver turning
        steadily). W'' jumps at the pin's entry and exit (by tan(pi/n) n_d^2), as the Geneva's own law does."""
        turned, rate, acc = self._turned(self.driver_angle(phi))
        start = self._turned(np.array([self.start]))[0][0]
        return turned - start, rate * self.driver_turns, acc * self.driver_turns ** 2

    @property
    def mean_turns(self) -> float:
        """The wheel shaft's turns per main turn, in its own sense (> 0): the driver's over the slots."""
        return self.driver_turns / self.law.slots

    def indexing(self, phi: np.ndarray) -> np.ndarray:
        """Where (bool) the wheel indexes at main shaft angles ``phi``: its pin in a slot, |a| < alpha_e."""
        alpha = self.driver_angle(phi)
        a = alpha - TWO_PI * np.ceil((alpha - math.pi) / TWO_PI)
        return np.abs(a) < self.law.engagement


def indexers(spec: Any, designs: tuple[Any, ...]) -> tuple[Indexer, ...]:
    """Each of ``spec.genevas`` as an :class:`Indexer`, with its Geneva design from ``designs`` (in order)."""
    out = []
    for mount, made in zip(spec.genevas, designs, strict=True):
        out.append(Indexer(mount.name, mount.driver, mount.wheel, made.law, abs(spec.turns[mount.driver]),
                           math.radians(mount.phase), made))
    return tuple(out)


def wheel_of(indexed: tuple[Indexer, ...], shaft: str) -> Indexer | None:
    """The Geneva drive whose wheel turns ``shaft``, if any."""
    return next((g for g in indexed if g.wheel == shaft), None)


#: how far apart (mm) a Geneva drive's shafts may lie from its centre distance
DISTANCE_TOL_MM = 0.01


def check_genevas(spec: Any, shafts: list[str]) -> None:
    """Refuse, in a :class:`ValueError` naming the field, a Geneva drive whose shafts do not exist, lie at another
    distance than its ``centre_distance``, or whose wheel shaft is the main one or turned by anything else (a
    coupling loop); a Geneva driven by an indexing shaft (another's wheel, or a shaft geared to one). Gear pairs,
    shaft-driven linkages and coupled followers on an indexing shaft are allowed: they follow its angle
    (:mod:`camgen.kinds.machine.shaft_motion`)."""
    at = {s.name: s.at for s in spec.shafts}
    others = {m.name for m in (*spec.cams, *spec.linkages)}
    wheels: dict[str, int] = {}
    for i, g in enumerate(spec.genevas):
        if g.name in others or g.name in (x.name for x in spec.genevas[:i]):
            raise ValueError(f"genevas[{i}].name: {g.name!r} names another mount already (their files share the "
                             "machine's folder: give each mount a name of its own)")
        for key in ("driver", "wheel"):
            if getattr(g, key) not in at:
                raise ValueError(f"genevas[{i}].{key}: no shaft {getattr(g, key)!r}; shafts: {', '.join(shafts)}")
        if g.wheel in (spec.machine.main, g.driver):
            raise ValueError(f"genevas[{i}].wheel: a coupling loop: shaft {g.wheel} is the "
                             + ("main shaft, the machine's input" if g.wheel == spec.machine.main else "driver"))
        driven = [j for j, gear in enumerate(spec.gears) if gear.driven == g.wheel]
        if driven or g.wheel in wheels:
            what = f"gears[{driven[0]}]" if driven else f"genevas[{wheels[g.wheel]}]"
            raise ValueError(f"genevas[{i}].wheel: a coupling loop: shaft {g.wheel} is driven by {what} already")
        wheels[g.wheel] = i
    for i, g in enumerate(spec.genevas):
        if g.driver in wheels:
            raise ValueError(f"genevas[{i}].driver: shaft {g.driver} indexes (genevas[{wheels[g.driver]}] turns it); "
                             "a Geneva drive is driven by a shaft turning steadily (the main shaft or a geared one)")
        gspec = spec.geneva_specs[i]
        need, apart = float(gspec.geneva.centre_distance), math.dist(at[g.driver], at[g.wheel])
        if abs(apart - need) > DISTANCE_TOL_MM:
            raise ValueError(f"genevas[{i}].wheel: the shafts {g.driver} and {g.wheel} lie {apart:.6g} mm apart; "
                             f"this Geneva drive's centre_distance is {need:.6g} mm (within {DISTANCE_TOL_MM:g} mm)")
        if g.driver not in spec.turns:
            raise ValueError(f"genevas[{i}].driver: shaft {g.driver} is not driven: no gear pair connects it to "
                             f"the main shaft {spec.machine.main}")
    indexed = indexing_shafts(spec)
    for i, g in enumerate(spec.genevas):
        if g.driver in indexed and g.driver not in wheels:
            raise ValueError(f"genevas[{i}].driver: shaft {g.driver} indexes (geared to a Geneva drive's wheel); a "
                             "Geneva drive is driven by a shaft turning steadily (the main shaft or a geared one)")


def indexing_shafts(spec: Any) -> set[str]:
    """The shafts that index: each Geneva drive's wheel shaft and every shaft geared to one (through any number of
    gear pairs)."""
    out = {g.wheel for g in spec.genevas}
    grown = True
    while grown:
        more = {gear.driven for gear in spec.gears if gear.driver in out} - out
        out |= more
        grown = bool(more)
    return out
