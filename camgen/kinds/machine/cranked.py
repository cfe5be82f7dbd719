"""A linkage driven by a crank on a shaft (``linkages[i].shaft``): its drawing moved so that its crank's pivot lies
on the shaft's centre, its crank turning with the shaft from its drawn angle plus the mount's ``phase``.

The crank's input at main shaft angle phi (radians) is ``drawn + phase + Q(phi)`` (:func:`~camgen.kinds.machine.
kinematics.crank_inputs`), Q the shaft's angle (:mod:`camgen.kinds.machine.shaft_motion`): n phi on a shaft turning
steadily, n its turns per main turn, negative where it turns the other way (through an odd number of gear pairs),
the main shaft's crank turning counter-clockwise; on an indexing shaft (a Geneva drive's wheel's, or geared to it)
the wheel's intermittent turn, so the linkage indexes and dwells with it, its rates by the chain rule (velocities
times Q', the crank accelerating by Q''). Every joint is solved in closed form, dyad by
dyad, on the drawing's branches (:mod:`linkgen.kinematics.linkage`); positions in the machine's frame (mm), rates
per radian of the main shaft (mm/rad).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.kinds.machine import chain_inertia, kinematics
from camgen.kinds.machine.shaft_motion import ShaftMotion


class GeneralMotion:
    """What a machine's general linkage (``type = "linkage"``) reads of its design, shaft- or follower-driven: its
    mount's name, its design, and every joint (n, 2) in the machine's frame (mm) with its rate (mm/rad)."""

    name: str
    design: Any
    points: dict[str, np.ndarray]
    rates: dict[str, np.ndarray]

    @property
    def analysis(self) -> Any:
        """Its general-linkage analysis (:class:`linkgen.mechanisms.general.Analysis`)."""
        return self.design.kinematics

    @property
    def tracers(self) -> tuple[str, ...]:
        """The joints its template traces (``linkage.tracers``)."""
        return tuple(self.analysis.table.tracers)


@dataclass(frozen=True)
class CrankedMotion(GeneralMotion):
    """A shaft-driven linkage over one turn of the main shaft (arrays by the machine's shaft angles).

    Attributes
    ----------
    name, shaft : str
        Its mount's name and its shaft's.
    turns : float
        Its shaft's turns per main turn (negative: the other way).
    phase_deg : float
        Its crank's lead over its drawing at the machine's start (degrees).
    layer : int
        Its mount's layer (its parts fill planes 2 layer + their own layers, behind the frame on its back side).
    side : int
        1 for a linkage on the frame's front, -1 on its back (its planes' sign).
    design : LinkageDesign
        Its linkgen design (its own report and parts).
    offset : ndarray
        (2,) mm added to the drawing's coordinates: the shaft's centre less the crank's drawn pivot.
    inputs : ndarray
        The crank's input (radians, the drawing's frame) at each shaft angle.
    points, rates : dict of str to ndarray
        Every joint (n, 2) in the machine's frame (mm) and its rate d P / d phi (mm/rad).
    torque : ndarray or None
        With its template's ``[dynamics]``: the main shaft's torque (N*m) that turns it at the machine's speed
        (:func:`camgen.kinds.machine.chain_inertia.cranked_shaft_torque`); None without.
    """

    name: str
    shaft: str
    turns: float
    phase_deg: float
    layer: int
    side: int
    design: Any
    offset: np.ndarray
    inputs: np.ndarray
    points: dict[str, np.ndarray]
    rates: dict[str, np.ndarray]
    torque: np.ndarray | None = None
    #: its shaft's motion (:class:`~camgen.kinds.machine.shaft_motion.ShaftMotion`), None: uniform at ``turns``
    shaft_motion: ShaftMotion | None = None

    @property
    def motion(self) -> ShaftMotion:
        """Its shaft's motion (uniform at ``turns`` where none was given)."""
        return self.shaft_motion if self.shaft_motion is not None else ShaftMotion(self.shaft, self.turns)

    def solve(self, phi: np.ndarray) -> Any:
        """Its linkage solved at main shaft angles ``phi`` (radians), in its drawing's frame
        (:class:`linkgen.kinematics.linkage.Solution`; velocities per radian of the crank on an indexing shaft, per
        radian of the main shaft on a uniform one)."""
        rate = self.turns if self.motion.uniform else 1.0
        return self.analysis.linkage.solve(self.inputs_at(phi)[None, :], rates=[rate])

    def inputs_at(self, phi: np.ndarray) -> np.ndarray:
        """The crank's input (radians) at main shaft angles ``phi``."""
        drawn = float(self.analysis.linkage.drawn_inputs[0])
        return kinematics.crank_inputs(drawn, self.phase_deg, self.motion.angles(phi)[0])


def cranked_motion(spec: Any, index: int, phi: np.ndarray, design: Any,
                   shaft: ShaftMotion | None = None) -> CrankedMotion:
    """The linkage of ``spec.linkages[index]`` (designed as ``design``) turned by its shaft (its motion ``shaft``,
    else uniform at its turns) at main shaft angles ``phi``; a :class:`SpecError` naming ``linkages[i].template``
    for a crank that does not turn fully."""
    mount = spec.linkages[index]
    a = design.kinematics
    if a.ranges is not None:
        reach = " or ".join(f"[{math.degrees(lo):.4g}, {math.degrees(hi):.4g}]" for lo, hi in a.ranges)
        raise SpecError(f"its crank reaches only {reach} degrees; a shaft turns it fully: give a linkage whose crank "
                        "turns round", f"linkages[{index}].template")
    pivot = np.asarray(a.linkage.structure.points[a.table.inputs[0].pivot], dtype=float)
    at = next(np.asarray(s.at, dtype=float) for s in spec.shafts if s.name == mount.shaft)
    turns = spec.turns[mount.shaft]
    side = 1 if mount.side == "front" else -1
    motion = None if shaft is None or shaft.uniform else shaft
    made = CrankedMotion(mount.name, mount.shaft, turns, mount.phase, mount.layer, side, design, at - pivot,
                         np.empty(0), {}, {}, None, motion)
    sol = made.solve(phi)
    q = made.motion.angles(phi)
    points = {p: np.asarray(xy, dtype=float) + made.offset for p, xy in sol.points.items()}
    per = 1.0 if made.motion.uniform else q[1][:, None]        # per radian of the crank, times Q'
    rates = {p: np.asarray(v, dtype=float) * per for p, v in sol.velocities.items()}
    inputs = made.inputs_at(phi)
    rate, acc = (turns, 0.0) if made.motion.uniform else (q[1], q[2])
    torque = chain_inertia.cranked_shaft_torque(design, inputs, rate, spec.machine.rpm * math.pi / 30.0, acc)
    return CrankedMotion(mount.name, mount.shaft, turns, mount.phase, mount.layer, side, design, made.offset,
                         inputs, points, rates, torque, motion)
