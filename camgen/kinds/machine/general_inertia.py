"""A follower-driven general linkage's accelerations and inertia carried back through the chain (issue 35 item 3):
the linkage an oscillating follower's arm drives as its crank, or a translating follower's stem as its slider
(:mod:`camgen.kinds.machine.slider_coupling`). Pure numpy; no I/O.

The follower's motion s (degrees of an arm's swing, mm of a stem's lift) is the cam's program on its phased shaft;
the linkage's input is q = base + scale s (radians of the crank, mm of the slider). By the chain rule, per radian of
the main shaft phi:

    q' = scale s',  q'' = scale s''
    P' = P_q q',    P'' = P_qq q'^2 + P_q q''

with P_q and P_qq a joint's velocity and acceleration per unit input speed (linkgen's general solver, which
differentiates each dyad's closure; :class:`linkgen.kinematics.linkage.Solution`), and the same for a link's angle
(omega and alpha per unit input speed). At the machine's constant speed omega (rad/s) a rate per radian times omega
is per second, per radian^2 times omega^2 per second^2.

The linkage's own dynamics (its ``[dynamics]`` table: masses, gravity, springs, ``[[loads]]``) gives the effort
Q its input needs along that motion: linkgen's inverse dynamics
(:func:`linkgen.kinematics.kinetostatics.kinetostatics`) at input speed q' omega and acceleration q'' omega^2 in SI
(rad/s and rad/s^2 for a crank, m/s and m/s^2 for a slider). Q is a torque (N*m, counter-clockwise) on a crank, a
force (N, along the guide's direction) on a slider. Virtual work carries it back: Q dq = F dl = T_shaft dphi, with l
the follower's path (mm: ``lever`` mm per unit of s), so

    F = Q f scale / (lever * 1e-3)          (N, pressing the follower onto its cam where positive)
    T_shaft = Q f q'                        (N*m, what the main shaft puts in)

f the input's unit in SI (1 for a radian, 1e-3 for a mm: :func:`linkgen.kinematics.inertia.input_scale`). The shares
add to those of the coupling's ``output_torque`` (:func:`camgen.kinds.machine.kinematics.reflected_force`,
:func:`~camgen.kinds.machine.kinematics.shaft_torque`); a linkage without ``[dynamics]`` has none.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.kinds.machine import chain_inertia, kinematics
from linkgen.kinematics.inertia import input_scale

#: mm in a metre
MM = 1e-3


@dataclass(frozen=True)
class DrivenLoad:
    """What a follower-driven general linkage puts on its follower and the main shaft, over the poses.

    Attributes
    ----------
    effort : ndarray or None
        The input's effort its inverse dynamics gives (N*m on a crank, N on a slider; the output torque's share
        left out); None for a linkage without ``[dynamics]``.
    force : ndarray
        The whole load reflected onto the follower (N along its path, pressing it onto the cam where positive).
    torque : ndarray
        The main shaft's whole torque against it (N*m).
    """

    effort: np.ndarray | None
    force: np.ndarray
    torque: np.ndarray


def input_rates(scale: float, lift: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """q' and q'' (the input's units per radian and per radian^2 of the driving shaft) of the input q = base +
    scale s, from the follower's ``lift`` rows (s, s', s'') per radian of that shaft."""
    return scale * lift[1], scale * lift[2]


def accelerations(sol: Any, d1: np.ndarray, d2: np.ndarray) -> dict[str, np.ndarray]:
    """Every joint's d^2 P / d phi^2 (n, 2; mm/rad^2) from ``sol`` (solved at unit input speed: P_q, P_qq) and the
    input's q' = ``d1``, q'' = ``d2`` per radian of the driving shaft: P_qq q'^2 + P_q q''."""
    w2, a = (d1 * d1)[:, None], d2[:, None]
    return {p: np.asarray(acc, dtype=float) * w2 + np.asarray(sol.velocities[p], dtype=float) * a
            for p, acc in sol.accelerations.items()}


def angular_acceleration(sol: Any, body: str, d1: np.ndarray, d2: np.ndarray) -> np.ndarray:
    """d^2 theta / d phi^2 (rad/rad^2) of link ``body``: its alpha q'^2 + omega q'' (alpha, omega per unit input
    speed from ``sol``)."""
    return np.asarray(sol.alphas[body], dtype=float) * d1 * d1 + np.asarray(sol.omegas[body], dtype=float) * d2


def dynamic_effort(design: Any, inputs: np.ndarray, d1: np.ndarray, d2: np.ndarray,
                   omega: float) -> np.ndarray | None:
    """The effort (N*m on a crank, N on a slider) linkgen's inverse dynamics gives the linkage ``design`` at input
    values ``inputs`` (radians or mm, its drawing's frame), the input moving q' = ``d1`` and q'' = ``d2`` (its
    units per radian and radian^2 of a shaft turning at ``omega`` rad/s); None without ``[dynamics]``."""
    if design.dynamics is None:
        return None
    f = input_scale(design.dynamics.analysis.linkage.structure)
    return chain_inertia.dynamic_effort(design, inputs, np.asarray(d1) * f, np.asarray(d2) * f, omega)


def carried(effort: np.ndarray, f: float, scale: float, lever: float,
            d1: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The follower's force (N) and the driving shaft's torque (N*m) of an input effort ``effort`` (SI: N*m or N),
    the input's unit ``f`` in SI, q = base + ``scale`` s, the follower's path ``lever`` mm per unit of s and the
    input's q' = ``d1`` per radian of the shaft: Q f scale / (lever 1e-3) and Q f q' (virtual work)."""
    return effort * (f * scale / (lever * MM)), effort * f * d1


def driven_load(design: Any, inputs: np.ndarray, lift: np.ndarray, mapping: tuple[float, float, float],
                output_torque: float, per_unit: np.ndarray, omega: float) -> DrivenLoad:
    """The load a general linkage (``design``) puts back on its follower and shaft at inputs ``inputs`` (radians
    or mm): the output torque's share (``output_torque`` N*m on a link turning ``per_unit`` rad per unit of s) and,
    with ``[dynamics]``, its inverse dynamics along the motion the follower's ``lift`` rows (s, s', s'' per radian
    of a shaft at ``omega`` rad/s) give through ``mapping`` = (base, scale, lever). Without ``[dynamics]`` the
    figures are exactly the output torque's."""
    _, scale, lever = mapping
    force = kinematics.reflected_force(output_torque, per_unit, lever)
    torque = kinematics.shaft_torque(output_torque, per_unit, lift[1])
    d1, d2 = input_rates(scale, lift)
    effort = dynamic_effort(design, inputs, d1, d2, omega)
    if effort is None:
        return DrivenLoad(None, force, torque)
    more_force, more_torque = carried(effort, input_scale(design.dynamics.analysis.linkage.structure), scale, lever,
                                      d1)
    return DrivenLoad(effort, force + more_force, torque + more_torque)


def program_load(driven: Any, theta: np.ndarray, omega: float) -> np.ndarray:
    """The force (N, pressing the follower onto its cam) a follower-driven linkage ``driven``
    (:class:`camgen.kinds.machine.slider_coupling.SliderMotion`) puts on its follower at its cam's program angles
    ``theta`` (radians), the cam turning at ``omega`` rad/s: what the cam is designed again with."""
    lift = driven.program.evaluate(theta)[:3]
    inputs = driven.base + driven.scale * lift[0]
    sol = driven.analysis.linkage.solve(inputs[None, :])
    output = driven.coupling.output
    per_unit = np.zeros_like(theta) if output is None else driven.scale * np.asarray(sol.omegas[output], dtype=float)
    load = driven_load(driven.design, inputs, lift, (driven.base, driven.scale, driven.lever),
                       driven.coupling.output_torque, per_unit, omega)
    return load.force
