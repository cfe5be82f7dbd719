"""A linkage's dynamics from its ``[dynamics]`` table: the mass model, Newton-Euler over the motion at the table's
speed, the flywheel and the counterweight of a crank that turns fully, and what the holes and pins carry. No I/O.

The linkage is its general-linkage drawing (:func:`linkgen.linkage_design.pose_of`: the dedicated mechanisms drawn as
one), solved at ``dynamics.poses`` input values: a crank's full turn from the drawing (uniform, its end left out, so
that sums over the poses are a turn's integrals), or the input's range (its ends included). Speeds: a crank at
``linkage.rpm``, a slide at ``dynamics.speed``; both at ``dynamics.input_acceleration``; or the speed and acceleration
of ``dynamics.speed_profile`` at each pose (:mod:`linkgen.dynamics.profile`: rows, or the motor's steady turn).

The flywheel is sized at a constant speed (I = dE / (Cs w^2), dE from the driving torque at that speed): the
profile's mean speed, or with ``speed_profile = "motor"`` ``linkage.rpm`` (the motor's run turns the flywheel, so it
is sized before it); the counterweight at the mean speed.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from camgen.core.errors import SpecError
from linkgen.dynamics.flywheel import FlywheelSize, flywheel_size, with_flywheel
from linkgen.dynamics.forward import Motion, motion_of
from linkgen.dynamics.masses import MassModel, Stack, mass_model
from linkgen.dynamics.profile import SpeedProfile, constant, motor_profile, rows_profile
from linkgen.dynamics.strength import HoleLoad, hole_loads
from linkgen.kinematics.balance import Counterweight, Fluctuation, counterweight, fluctuation
from linkgen.kinematics.inertia import MM, generalised_inertia
from linkgen.kinematics.kinetostatics import G0, Kinetostatics, Loads, Spring, kinetostatics
from linkgen.kinematics.statics import LinkTorque, PointForce
from linkgen.kinematics.structure import GROUND
from linkgen.mechanisms.general import Analysis

if TYPE_CHECKING:
    from camgen.core.kit import KitTable
    from linkgen.parts import LinkageBuild
    from linkgen.dynamics.table import DynamicsTable
    from linkgen.spec import PartsTable

TWO_PI = 2.0 * math.pi
#: a range that ends at a toggle (a dyad in line, its margin within this of 0) is analysed from this fraction of the
#: range inside it: at constant input speed the links' rates, and so their inertia's forces, grow without bound there
TOGGLE_CUT = 0.01
TOGGLE_MARGIN = 1e-6


@dataclass(frozen=True)
class Dynamics:
    """A linkage's dynamics (see the module's note): the table, the analysis it runs on, the masses, the loads, the
    input's speed and acceleration (SI: rad/s, rad/s^2 or m/s, m/s^2: the constant ones, or with a profile its mean
    speed and 0) and the profile the poses run at (:mod:`linkgen.dynamics.profile`), the kinetostatics over the
    poses, the generalised inertia J and J' there (:func:`linkgen.kinematics.inertia.generalised_inertia`), and for a
    crank that turns fully the energy fluctuation, the flywheel and the counterweight; the holes' and pins' loads."""

    table: DynamicsTable
    analysis: Analysis
    masses: MassModel
    loads: Loads
    speed: float
    acceleration: float
    result: Kinetostatics
    inertia: np.ndarray
    inertia_rate: np.ndarray
    turns: bool
    fluctuation: Fluctuation | None
    flywheel: FlywheelSize | None
    counterweight: Counterweight | None
    holes: tuple[HoleLoad, ...]
    #: the ends of the input's range at toggles, left out by :data:`TOGGLE_CUT` of the range (rad or mm)
    toggles: tuple[float, ...] = ()
    #: the motion from rest under ``[dynamics.motor]`` (:mod:`linkgen.dynamics.forward`)
    motion: Motion | None = None
    #: the input's speed and acceleration at each pose (None: ``speed`` and ``acceleration`` at every pose)
    profile: SpeedProfile | None = None

    @property
    def crank(self) -> bool:
        return self.analysis.crank

    def at(self, values: np.ndarray) -> Kinetostatics:
        """The kinetostatics at other input values (rad or mm), at the same speed (the profile's there) and loads."""
        x = np.atleast_1d(np.asarray(values, dtype=float))
        sol = self.analysis.linkage.solve(x)
        speed, acceleration = (self.speed, self.acceleration) if self.profile is None else self.profile.at(x)
        return kinetostatics(self.analysis.linkage, sol, self.masses.drawn, speed, acceleration, self.loads)


def poses(analysis: Analysis, count: int) -> tuple[np.ndarray, bool, tuple[float, ...]]:
    """The input values the dynamics is computed at (rad or mm), whether they are a full, periodic turn, and the
    ends of the range that are toggles (the values start and stop :data:`TOGGLE_CUT` of the range inside them)."""
    lo, hi = float(analysis.span[0, 0]), float(analysis.span[0, -1])
    linkage = analysis.linkage
    turns = analysis.crank and abs(hi - lo - TWO_PI) < 1e-9 and all(len(f) % 2 == 0 for f in linkage.flips)
    if turns:
        return lo + TWO_PI * np.arange(count) / count, True, ()
    ends = linkage.solve(np.array([lo, hi]), strict=False, derivatives=False)
    margin = np.min([np.abs(d.margin) for d in ends.dyads], axis=0) if ends.dyads else np.ones(2)
    toggles = tuple(v for v, m in zip((lo, hi), margin, strict=True) if m < TOGGLE_MARGIN)
    cut = TOGGLE_CUT * (hi - lo)
    return np.linspace(lo + (cut if lo in toggles else 0.0), hi - (cut if hi in toggles else 0.0), count), False, \
        toggles


def _springs(table: DynamicsTable, analysis: Analysis) -> tuple[Spring, ...]:
    """The table's springs with their ends' links, each checked against the drawing."""
    s = analysis.linkage.structure
    out = []
    for i, sp in enumerate(table.springs):
        where = f"dynamics.springs[{i}]"
        ends = []
        for k, point in enumerate(sp.between):
            if point not in s.points:
                raise SpecError(f"no joint {point!r} (joints: {', '.join(s.points)})", f"{where}.between")
            holders = s.holders(point)
            if sp.links is not None:
                link = sp.links[k]
                if link not in s.bodies or (link != GROUND and point not in s.bodies[link]) or \
                        (link == GROUND and GROUND not in holders):
                    raise SpecError(f"{link!r} does not hold {point} (it is on {', '.join(holders)})",
                                    f"{where}.links")
            else:
                link = GROUND if GROUND in holders else holders[0]
            ends.append(link)
        if sp.between[0] == sp.between[1] and ends[0] == ends[1]:
            raise SpecError("a spring joins two different points or links", f"{where}.between")
        out.append(Spring(sp.between[0], ends[0], sp.between[1], ends[1], sp.stiffness, sp.free_length))
    return tuple(out)


def dynamics_of(table: DynamicsTable, analysis: Analysis, parts: PartsTable | None, rpm: float,
                forces: Sequence[PointForce] = (), torques: Sequence[LinkTorque] = (),
                kit: KitTable | None = None, stack: Stack | None = None) -> Dynamics:
    """The dynamics of the linkage ``analysis`` draws, for its ``[dynamics]`` ``table``, ``[parts]``, ``[kit]``,
    speed ``rpm`` (a crank) and its loads (``[[loads]]`` as :mod:`linkgen.effort` reads them), its pins and
    spacers as ``stack`` has them (:class:`linkgen.dynamics.masses.Stack`; none without).

    Raises
    ------
    SpecError
        One line naming the key: a link or joint the linkage has not, a link whose mass nothing gives, a linkage of
        two inputs or with a redundant constraint, a flywheel on a linkage that is not a crank turning fully.
    """
    s = analysis.linkage.structure
    if len(s.inputs) != 1:
        raise SpecError("a linkage of one input has one effort; with two, the forces cannot be shared out",
                        "dynamics")
    masses = mass_model(table, analysis, parts, stack, kit)
    angle = math.radians(table.gravity_angle)
    g = G0 * math.sin(math.radians(table.incline))
    loads = Loads((g * math.cos(angle), g * math.sin(angle)), tuple(forces), tuple(torques), _springs(table, analysis))
    x, turns, toggles = poses(analysis, table.poses)
    if table.flywheel is not None and not turns:
        raise SpecError("a flywheel is sized over a crank's full turn; this input does not turn fully",
                        "dynamics.flywheel")
    if analysis.crank:
        speed, acceleration = rpm * TWO_PI / 60.0, table.input_acceleration
    else:
        speed, acceleration = table.speed * MM, table.input_acceleration * MM
    profile = constant(speed, acceleration, analysis.crank)
    if isinstance(table.speed_profile, tuple):
        profile = rows_profile(table.speed_profile, analysis.crank, float(x[0]), float(x[-1]))
    sol = analysis.linkage.solve(x)
    j, dj = generalised_inertia(s, sol, masses.drawn)
    size = None
    if table.speed_profile == "motor":
        if table.flywheel is not None:         # sized at linkage.rpm, before the run that turns it
            size = _flywheel(table, x, kinetostatics(analysis.linkage, sol, masses.drawn, speed, 0.0, loads).effort,
                             speed, j, masses, parts)
        motion = motion_of(table, analysis.linkage, masses.drawn, loads, float(x[0]), turns, size)
        profile = motor_profile(table, motion)
    rates = profile.at(x)
    result = kinetostatics(analysis.linkage, sol, masses.drawn, *rates, loads, check=True)
    fl = cw = None
    if turns and np.isfinite(result.effort).all():
        fl = fluctuation(x, result.effort)
        if table.flywheel is not None and table.speed_profile != "motor":
            effort = result.effort if not profile.varies else \
                kinetostatics(analysis.linkage, sol, masses.drawn, profile.mean, 0.0, loads).effort
            size = _flywheel(table, x, effort, profile.mean, j, masses, parts)
        cw = counterweight(x, result.shaking_force, profile.mean)
    holes = hole_loads(result, parts, masses.material, table, kit is not None)
    if table.speed_profile != "motor":
        motion = motion_of(table, analysis.linkage, masses.drawn, loads, float(x[0]), turns, size)
    if profile.varies:
        speed, acceleration = profile.mean, 0.0
    return Dynamics(table, analysis, masses, loads, speed, acceleration, result, j, dj, turns, fl, size, cw, holes,
                    toggles, motion, profile if profile.varies else None)


def _flywheel(table: DynamicsTable, x: np.ndarray, effort: np.ndarray, speed: float, j: np.ndarray,
              masses: MassModel, parts: PartsTable | None) -> FlywheelSize | None:
    """The flywheel of ``table.flywheel`` for the driving torque ``effort`` (N*m) over the turn ``x`` (rad) at the
    constant ``speed`` (rad/s); None where the torque is not finite (a dead centre)."""
    assert table.flywheel is not None
    if not np.isfinite(effort).all():
        return None
    return flywheel_size(table.flywheel, fluctuation(x, effort).energy, speed, float(np.mean(j)), masses, parts)


def flywheel_build(build: LinkageBuild, dyn: Dynamics) -> LinkageBuild:
    """``build`` with the flywheel's plates of ``dyn`` (when it sized some) on the crank's pivot
    (:func:`linkgen.dynamics.flywheel.with_flywheel`)."""
    if dyn.flywheel is None:
        return build
    inp = dyn.analysis.linkage.structure.inputs[0]
    x, y = dyn.analysis.linkage.structure.points[inp.pivot]
    return with_flywheel(build, dyn.flywheel, (float(x), float(y)), inp.link)
