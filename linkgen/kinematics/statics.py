"""The effort that holds a linkage against loads, by virtual work (pure numpy).

A linkage of one input q (a crank's angle in rad, or a slide's travel in mm) is in static
equilibrium under its loads when their virtual work and the driver's add up to nothing:

    Q dq + sum_i F_i . dr_i + sum_j M_j dphi_j = 0

so the effort the driver must supply is Q = -(sum_i F_i . v_i + sum_j M_j omega_j) / qdot, with
v_i and omega_j the velocities of the loaded points and links at input speed qdot. The general
solver gives them per unit input speed (mm/rad or mm/mm, rad/rad or rad/mm), so qdot = 1 here.

Units and signs: forces in N in the drawing's frame (x, y), torques on links in N*m counter-clockwise;
the effort is a torque in N*m counter-clockwise on the crank (the direction its angle grows), or a
force in N along the slide's positive direction. Friction, weights and inertia are not loads here
(the links are massless and the joints frictionless).
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from linkgen.kinematics.linkage import Solution

#: N*mm in a N*m
MM_PER_M = 1000.0
#: a finite effort within this fraction of the loads' own power scale (sum |F| |v| + |M| |omega|) at a pose is
#: rounding: the loads' terms cancel there (a force across its point's path), and the effort is 0
CANCELLED = 1e-12


@dataclass(frozen=True)
class PointForce:
    """A force (N, in the drawing's frame) acting on the linkage at joint ``point``."""

    point: str
    force: tuple[float, float]


@dataclass(frozen=True)
class LinkTorque:
    """A torque (N*m, counter-clockwise) acting on link ``link``."""

    link: str
    torque: float


def load_power(sol: Solution, forces: Sequence[PointForce], torques: Sequence[LinkTorque]) -> np.ndarray:
    """The loads' power per unit input speed over the poses of ``sol`` (N*mm per rad of a crank, or N*mm per mm of
    a slide, i.e. N): sum F . v + 1000 M omega, exactly 0 where that is within :data:`CANCELLED` of the terms'
    sizes (the rounding of terms that cancel)."""
    n = sol.inputs.shape[-1]
    power, size = np.zeros(n), np.zeros(n)
    for f in forces:
        force = np.asarray(f.force, dtype=float)
        power += sol.velocities[f.point] @ force
        size += np.hypot(*sol.velocities[f.point].T) * math.hypot(*force)
    for t in torques:
        power += MM_PER_M * t.torque * sol.omegas[t.link]
        size += MM_PER_M * abs(t.torque) * np.abs(sol.omegas[t.link])
    return np.where(np.isfinite(power) & (np.abs(power) <= CANCELLED * size), 0.0, power)


def input_effort(sol: Solution, forces: Sequence[PointForce], torques: Sequence[LinkTorque],
                 crank: bool) -> np.ndarray:
    """The driver's effort that holds the loads at each pose of ``sol`` (solved with unit input speed): a torque
    in N*m (``crank``) or a force in N (a slide). Non-finite where the input cannot move the loads' points
    (their velocity per unit input grows without bound near a dead centre of the input)."""
    power = load_power(sol, forces, torques)
    effort = np.where(power == 0, 0.0, -power)          # no effort is 0, not -0
    return effort / MM_PER_M if crank else effort
