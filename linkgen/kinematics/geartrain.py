"""Gear trains by their teeth: simple, compound and planetary (epicyclic); each member's speed per unit input speed
and its angle, vectorised over input angles.

Angles are counter-clockwise in radians, each gear's about its own centre; speeds are signed (counter-clockwise
positive). Gears that mesh externally turn opposite ways at the inverse ratio of their teeth; an internal gear (a
ring) turns the same way as the planet inside it.

* **Simple**: gears 0, 1, ..., n-1, each meshing with the next; gear k turns at (-1)^k z_0 / z_k of gear 0 (the
  idlers between set only the sense).
* **Compound**: stages of (driver, driven) pairs; each stage's driven gear shares its shaft with the next stage's
  driver, so shaft k+1 turns at -z_driver / z_driven of shaft k; the train's ratio is the product.
* **Planetary**: sun s, planets p on the carrier c, ring r (z_r = z_s + 2 z_p). Willis' formula: relative to the
  carrier the train is a simple one, (w_s - w_c) / (w_r - w_c) = -z_r / z_s, and the planet about its own centre
  turns at w_p = w_c - (w_s - w_c) z_s / z_p. One member fixed, one driven: the third follows.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

Member = Literal["sun", "carrier", "ring"]
MEMBERS: tuple[Member, ...] = ("sun", "carrier", "ring")


@dataclass(frozen=True)
class SimpleTrain:
    """Gears of ``teeth`` (in mesh order), on fixed axes; gear 0 is the input."""

    teeth: tuple[int, ...]

    @property
    def speeds(self) -> tuple[float, ...]:
        """Each gear's speed per unit speed of gear 0."""
        z0 = self.teeth[0]
        return tuple((-1.0) ** k * z0 / z for k, z in enumerate(self.teeth))

    @property
    def ratio(self) -> float:
        """The last gear's speed per unit input speed."""
        return self.speeds[-1]


@dataclass(frozen=True)
class CompoundTrain:
    """``stages`` of (driver teeth, driven teeth); shaft 0 carries the first driver (the input), shaft k (k >= 1) the
    driven gear of stage k-1 and the driver of stage k."""

    stages: tuple[tuple[int, int], ...]

    @property
    def speeds(self) -> tuple[float, ...]:
        """Each shaft's speed per unit speed of shaft 0 (one more shaft than stages)."""
        out = [1.0]
        for driver, driven in self.stages:
            out.append(-out[-1] * driver / driven)
        return tuple(out)

    @property
    def ratio(self) -> float:
        """The last shaft's speed per unit input speed."""
        return self.speeds[-1]


@dataclass(frozen=True)
class PlanetaryTrain:
    """Sun, planet and ring teeth; the ``fixed`` member and the ``driven`` one (the input)."""

    sun: int
    planet: int
    ring: int
    fixed: Member
    driven: Member

    @property
    def output(self) -> Member:
        """The member neither fixed nor driven."""
        return next(m for m in MEMBERS if m not in (self.fixed, self.driven))

    @property
    def speeds(self) -> dict[str, float]:
        """The sun's, carrier's, ring's and each planet's (about its own centre) speeds per unit input speed: the
        fixed member 0, the input 1, Willis' relation z_s (w_s - w_c) + z_r (w_r - w_c) = 0 for the third (solved
        for it directly: the fixed member stays exactly still)."""
        # z_s w_s + z_r w_r - (z_s + z_r) w_c = 0 with the fixed member's w = 0 and the input's 1
        coefficient = {"sun": float(self.sun), "ring": float(self.ring), "carrier": -float(self.sun + self.ring)}
        w = {self.fixed: 0.0, self.driven: 1.0, self.output: -coefficient[self.driven] / coefficient[self.output]}
        ws, wc = w["sun"], w["carrier"]
        return {"sun": ws, "carrier": wc, "ring": w["ring"], "planet": wc - (ws - wc) * self.sun / self.planet}

    @property
    def ratio(self) -> float:
        """The output member's speed per unit input speed."""
        return self.speeds[self.output]


def angles(speeds: ArrayLike, theta: ArrayLike, phases: ArrayLike | None = None) -> np.ndarray:
    """Each member's angle (k, n) rad at input angles ``theta`` (n,) rad: phase + speed x theta (each member's speed
    per unit input speed, ``speeds`` (k,); phases 0 unless given)."""
    s = np.asarray(speeds, dtype=float)[:, None]
    p = np.zeros_like(s) if phases is None else np.asarray(phases, dtype=float)[:, None]
    return p + s * np.atleast_1d(np.asarray(theta, dtype=float))[None, :]
