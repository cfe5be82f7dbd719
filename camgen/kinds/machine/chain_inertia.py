"""A linkage's own dynamics carried back through the chain: the torque its input (a follower's arm, or a crank on a
shaft) needs to move it along the motion the machine gives it, from linkgen's inverse dynamics
(:func:`linkgen.kinematics.kinetostatics.kinetostatics`, on the masses, gravity, springs and ``[[loads]]`` of its
own ``[dynamics]`` table), plus an external torque on its output link held by virtual work. Pure numpy; no I/O.

Units and signs: angles in radians, the input's angle counter-clockwise; rates per radian of a driving shaft
(``d1`` = d theta / d phi, ``d2`` = d^2 theta / d phi^2) at that shaft's constant speed ``omega`` (rad/s), so the
input turns at d1 omega rad/s and d2 omega^2 rad/s^2; a torque in N*m on the input, counter-clockwise positive, is
what the driver must put in (positive where it works against the linkage as the input's angle grows). A linkage
without ``[dynamics]`` needs only the output torque's share, exactly as :mod:`camgen.kinds.machine.kinematics`
gives it.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.kinds.machine import kinematics
from linkgen.kinematics.kinetostatics import kinetostatics


@dataclass(frozen=True)
class InputTorque:
    """The torque (N*m) a linkage's input needs at each pose, in its two shares.

    Attributes
    ----------
    dynamic : ndarray or None
        The inverse dynamics' effort (its links' inertia, gravity, springs and ``[[loads]]``); None for a linkage
        without ``[dynamics]`` (nothing but the output torque).
    output : ndarray
        The share that holds the external output torque T: -T k (k = d theta_out / d theta_in, virtual work).
    """

    dynamic: np.ndarray | None
    output: np.ndarray

    @property
    def total(self) -> np.ndarray:
        """The whole input torque (N*m): the output's share, plus the dynamic one where there is one."""
        return self.output if self.dynamic is None else self.dynamic + self.output


def dynamic_effort(design: Any, inputs: np.ndarray, d1: np.ndarray | float, d2: np.ndarray | float,
                   omega: float) -> np.ndarray | None:
    """The input torque (N*m) linkgen's inverse dynamics gives for the linkage ``design`` (a
    :class:`linkgen.linkage_design.LinkageDesign`) at input angles ``inputs`` (radians, its general drawing's
    frame: for a four-bar the crank's angle from its ground line), its input turning d1 omega rad/s and
    accelerating d2 omega^2 rad/s^2; None where its template has no ``[dynamics]``."""
    dyn = design.dynamics
    if dyn is None:
        return None
    linkage = dyn.analysis.linkage
    x = np.asarray(inputs, dtype=float)
    speed = np.broadcast_to(np.asarray(d1, dtype=float) * omega, x.shape)
    acceleration = np.broadcast_to(np.asarray(d2, dtype=float) * omega ** 2, x.shape)
    result = kinetostatics(linkage, linkage.solve(x), dyn.masses.drawn, speed, acceleration, dyn.loads)
    return np.asarray(result.effort, dtype=float)


def coupled_input_torque(design: Any, theta2: np.ndarray, d1: np.ndarray, d2: np.ndarray, omega: float,
                         output_torque: float, k4: np.ndarray) -> InputTorque:
    """The torque a coupled four-bar's crank (the follower's arm) needs: its inverse dynamics at crank angles
    ``theta2`` (radians) with rates ``d1``, ``d2`` per radian of a shaft turning at ``omega`` rad/s
    (:func:`dynamic_effort`), and the share holding ``output_torque`` (N*m on the rocker) through ``k4`` =
    d theta4 / d theta2."""
    return InputTorque(dynamic_effort(design, theta2, d1, d2, omega), -output_torque * k4)


def arm_force(torque: np.ndarray, arm: float) -> np.ndarray:
    """The force (N) an input torque ``torque`` (N*m, the arm's angle growing as it rises off the cam) presses the
    follower's roller onto its cam with, along its path at ``arm`` mm from the pivot: torque / arm (virtual work)."""
    return torque * 1000.0 / arm


def cranked_shaft_torque(design: Any, inputs: np.ndarray, rate: float | np.ndarray, omega: float,
                         acceleration: float | np.ndarray = 0.0) -> np.ndarray | None:
    """The main shaft's torque (N*m) that turns a shaft-driven linkage's crank at ``inputs`` (radians), the crank
    turning ``rate`` = Q' rad per radian of the main shaft (a uniform shaft's signed turns per main turn; an indexing
    shaft's Q'(phi), :mod:`camgen.kinds.machine.shaft_motion`) and accelerating ``acceleration`` = Q'' rad/rad^2
    (0 on a uniform shaft), at the main shaft's constant ``omega`` (rad/s): its effort times d input / d phi = Q'
    (its power over the main shaft's speed); None without ``[dynamics]``."""
    effort = dynamic_effort(design, inputs, rate, acceleration, omega)
    return None if effort is None else effort * rate


def carried(load: InputTorque, output_torque: float, k4: np.ndarray, arm: float,
            chain: kinematics.Chain) -> tuple[np.ndarray, np.ndarray]:
    """The reflected force on the follower's roller (N, pressing it onto the cam) and the driving shaft's torque
    (N*m) of an input torque ``load``, the crank's angle and rates per radian of that shaft ``chain``: without
    dynamics exactly :func:`~camgen.kinds.machine.kinematics.reflected_force` and
    :func:`~camgen.kinds.machine.kinematics.shaft_torque` of the output torque; with them the whole torque over the
    arm and times d theta2 / d phi."""
    if load.dynamic is None:
        return kinematics.reflected_force(output_torque, k4, arm), kinematics.shaft_torque(output_torque, k4, chain.d1)
    total = load.total
    return arm_force(total, arm), total * chain.d1
