"""The energy cross-checks' own kinetic energy: links' centres and angles at shaft angles a step either side, their
velocities by central differences, sum 1/2 m v^2 + 1/2 I w^2 (no solver rates)."""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

#: a link's pose over the samples: its centre (n, 2) mm and its angle (n,) rad
Pose = tuple[np.ndarray, np.ndarray]


def kinetic_energy(ahead: Mapping[str, Pose], behind: Mapping[str, Pose], links: Mapping[str, Mapping],
                   h: float, omega: float) -> np.ndarray:
    """The kinetic energy (J) of ``links`` (each its ``mass`` kg and ``inertia`` kg*mm^2 about its centre) from
    their poses at shaft angles phi + h (``ahead``) and phi - h (``behind``), the shaft turning at ``omega``
    rad/s: v = (G(phi + h) - G(phi - h)) / 2h * omega (mm to m), w likewise from the angles (their difference
    wrapped to (-pi, pi])."""
    energy = np.zeros(len(next(iter(ahead.values()))[1]))
    for link, values in links.items():
        v = (ahead[link][0] - behind[link][0]) / (2 * h) * omega / 1000.0                        # m/s
        w = np.angle(np.exp(1j * (ahead[link][1] - behind[link][1]))) / (2 * h) * omega          # rad/s
        energy += 0.5 * values["mass"] * np.sum(v ** 2, axis=1) + 0.5 * values["inertia"] * 1e-6 * w ** 2
    return energy
