"""Speed and contact of a translating follower at a given cam speed (constant).

Time derivatives: v = omega s', a = omega^2 s'', j = omega^3 s''' (omega in rad/s).
The follower's axis is +Y (its rise is upward).

* Gravity return: the weight alone holds the follower down; contact is lost where
  the follower must decelerate faster than g, a < -g, so the largest speed is
  omega_max = sqrt(g / -min s'').
* Spring return (spring weight and the follower's own weight neglected): contact
  force N = preload + rate s + m a (newtons, s in mm, a in m/s^2); contact holds
  while N > 0. Reported: its smallest value and where, the preload that would hold
  contact with this rate, and the rate that would with this preload.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from camgen.cam import Cam
from camgen.speed import ContactCheck, GravityHold, HeldContact, LoadRange, Speed, Unanalysed

#: standard gravity, mm/s^2
G_MM = 9806.65


@dataclass(frozen=True)
class Peak:
    value: float     # largest value
    at_deg: float


def peak_of(cam: Cam, func: Callable[[np.ndarray], np.ndarray]) -> Peak:
    """Largest value over the cycle of ``func`` of the motion (its four rows: s and three derivatives)."""
    return peaks_at(cam, lambda t, m: func(m))[0]


def peak_at(cam: Cam, func: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> Peak:
    """Largest value over the cycle of ``func(theta, motion rows)`` (theta the cam angle, radians)."""
    return peaks_at(cam, func)[0]


def peaks_at(cam: Cam, *funcs: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> list[Peak]:
    """Largest value over the cycle of each ``func(theta, motion rows)`` (theta the cam angle, radians), all from
    one search (see :func:`stacked_peaks`)."""
    return stacked_peaks(cam, lambda t, m: np.stack([np.broadcast_to(f(t, m), t.shape) for f in funcs]))


def stacked_peaks(cam: Cam, values: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> list[Peak]:
    """Largest value over the cycle of each row of ``values(theta, motion rows)`` -> (k, n), and where: one search
    (:meth:`camgen.program.Program.maxima`) for the k of them, each row's peak found as if it were searched alone.

    The motion is the segments' own evaluation at ``theta`` (:meth:`camgen.program.Program.evaluate_on`, as
    :meth:`camgen.program.Segment.evaluate` makes it), not the one the search hands over (made from the laws'
    parameter, it differs from it in the last bits, which would move the reports' peaks by as much)."""
    def rows(theta: np.ndarray, _: np.ndarray, index: np.ndarray) -> np.ndarray:
        return values(theta, cam.program.evaluate_on(index, theta))

    return [Peak(*found) for found in cam.program.maxima(rows)]


@dataclass(frozen=True)
class LoadTable:
    """An external load (N, pressing the follower onto the cam) against cam angle: ``angles`` (radians, strictly
    increasing in [0, 2 pi)) and ``loads`` (N), interpolated linearly between rows and from the last row round to
    the first (the table is periodic: a row at 360 degrees must repeat the one at 0 and is dropped)."""

    angles: tuple[float, ...]
    loads: tuple[float, ...]

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        return np.interp(np.asarray(theta, dtype=float), self.angles, self.loads, period=2 * math.pi)


@dataclass(frozen=True)
class SegmentLoads:
    """A load (N, pressing the follower onto the cam) constant over each motion segment (``motion[i].load``):
    ``starts`` the segments' first cam angles (radians, increasing from 0), ``loads`` theirs. A boundary belongs
    to the segment it starts (:meth:`camgen.program.Program.segment_index`); the means over the turn never see it
    (their nodes lie inside the segments)."""

    starts: tuple[float, ...]
    loads: tuple[float, ...]

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        t = np.mod(np.asarray(theta, dtype=float), 2 * math.pi)
        index = np.clip(np.searchsorted(self.starts, t, side="right") - 1, 0, len(self.starts) - 1)
        return np.asarray(self.loads)[index]


def segment_loads(program: Any, motion: Any) -> SegmentLoads | None:
    """The :class:`SegmentLoads` of a spec's ``motion`` tables (their ``load``, N; a segment without one 0) on its
    built ``program``, or None when no segment has a load."""
    if program is None or all(getattr(seg, "load", None) is None for seg in motion):
        return None
    return SegmentLoads(tuple(float(seg.start) for seg in program.segments),
                        tuple(float(m.load or 0.0) for m in motion))


def load_table(rows: list[tuple[float, float]] | tuple[tuple[float, float], ...]) -> LoadTable:
    """A :class:`LoadTable` from checked (cam angle in degrees, load in N) rows (:func:`camgen.spec.load_rows`)."""
    return LoadTable(tuple(math.radians(a) for a, _ in rows), tuple(float(v) for _, v in rows))


@dataclass(frozen=True)
class Loading:
    """What presses a follower onto its cam along its path, in N: ``preload + rate s + load + table(theta) +
    weight cos(tilt + turn s) + mass a`` (s in mm, a = omega^2 s'' in m/s^2). ``mass`` kg (for an arm the roller's
    mass plus the arm's moment of inertia over L^2), ``rate`` N/mm; ``load`` an external force pressing the
    follower onto the cam (negative pulls it off), ``table`` a load against cam angle added to it; ``weight`` the
    weights' pull (N) along the path where it points straight down the path, ``tilt`` (rad) the angle of the path's
    rising direction from straight up at s = 0 and ``turn`` (rad per unit of s) how fast that direction turns with
    s (0 for a translating follower; an arm's swing turns it by its own angle); ``margin`` the least contact force
    wanted (N)."""

    mass: float
    rate: float = 0.0
    preload: float = 0.0
    load: float = 0.0
    weight: float = 0.0
    margin: float = 0.0
    #: mm of the contact's path per unit of s: 1 for a translating follower, L pi / 180 for an arm of length L
    #: (whose s is its swing in degrees: the forces then act at the roller's centre along its path)
    scale: float = 1.0
    tilt: float = 0.0
    turn: float = 0.0
    table: LoadTable | None = None
    segments: SegmentLoads | None = None

    @property
    def weight_at_rest(self) -> float:
        """The weights' pull (N) along the path at s = 0."""
        return self.weight * math.cos(self.tilt)

    def external(self, theta: np.ndarray | None) -> np.ndarray | float:
        """The external load (N) at cam angles ``theta`` (radians): the constant and the table's."""
        if theta is None:
            return self.load
        table = 0.0 if self.table is None else self.table(theta)
        return self.load + table + (0.0 if self.segments is None else self.segments(theta))

    @property
    def varies(self) -> bool:
        """Whether the external load changes with cam angle (a load table or loads per segment)."""
        return self.table is not None or self.segments is not None

    def still(self, m: np.ndarray, theta: np.ndarray | None = None) -> np.ndarray:
        """The force (N) at rest: everything but the inertia."""
        weight = self.weight_at_rest if self.turn == 0 else self.weight * np.cos(self.tilt + self.turn * m[0])
        return self.preload + self.rate * self.scale * m[0] + self.external(theta) + weight

    def force(self, m: np.ndarray, omega: float, theta: np.ndarray | None = None) -> np.ndarray:
        """The force (N) pressing the follower onto the cam at ``omega`` rad/s (``theta`` for a load table)."""
        return self.still(m, theta) + self.mass * omega ** 2 * self.scale * m[2] / 1000.0


def loading(mass: float, spring_rate: float | None, preload: float | None, load: float | None = None,
            orientation: float | None = None, margin: float | None = None, arm: float | None = None,
            table: LoadTable | None = None, arm_weight: Any = None) -> Loading:
    """The loading of a follower table's keys: with no spring (no rate, no preload) gravity holds the follower, its
    rise pointing straight up unless ``orientation`` (degrees from straight up) says otherwise; with a spring its
    weight counts only when ``orientation`` is given. For an ``arm`` (its length, mm) the mass sits at the roller's
    centre and the spring and load act there along its path; its weight (and the arm's) only through
    ``arm_weight``, an :class:`ArmWeight`."""
    gravity = spring_rate is None and preload is None and arm is None
    tilt = 0.0 if orientation is None and gravity else orientation
    scale = 1.0 if arm is None else arm * math.pi / 180.0
    if arm is not None:
        inertia = 0.0 if arm_weight is None else arm_weight.inertia / arm ** 2
        weight, tilt_rad, turn = (0.0, 0.0, 0.0) if arm_weight is None or arm_weight.tilt is None else (
            arm_weight.weight(mass, arm), arm_weight.tilt, arm_weight.turn)
        return Loading(mass + inertia, spring_rate or 0.0, preload or 0.0, load or 0.0, weight, margin or 0.0,
                       scale, tilt_rad, turn, table)
    weight = 0.0 if tilt is None else mass * G_MM / 1000.0
    return Loading(mass, spring_rate or 0.0, preload or 0.0, load or 0.0, weight, margin or 0.0, scale,
                   0.0 if tilt is None else math.radians(tilt), 0.0, table)


@dataclass(frozen=True)
class ArmWeight:
    """An oscillating roller's arm: its moment of inertia about the pivot ``inertia`` (kg*mm^2), its own mass
    ``mass`` (kg) with its centre of mass ``com`` mm from the pivot on the line to the roller's centre, and how it
    hangs: ``tilt`` (rad) the angle of the roller's rising direction at rest from straight up (None: weights
    neglected) and ``turn`` (rad per degree of swing, +-pi/180) how the swing turns it, counter-clockwise positive
    as drawn."""

    inertia: float = 0.0
    mass: float = 0.0
    com: float = 0.0
    tilt: float | None = None
    turn: float = 0.0

    def weight(self, roller_mass: float, arm: float) -> float:
        """The pull (N) along the roller's path of the roller's weight and the arm's: their moment about the pivot
        over the arm's length L (mm) where the path points straight down."""
        return (roller_mass * arm + self.mass * self.com) / arm * G_MM / 1000.0


def arm_weight(follower: Any, inertia: float | None, arm_mass: float | None, arm_com: float | None,
               orientation: float | None) -> ArmWeight:
    """The :class:`ArmWeight` of an oscillating roller follower (its pivot, rest position and arm length), the
    drawing's +Y (cam centre to the follower at theta = 0) turned ``orientation`` degrees counter-clockwise from
    straight up (None: weights neglected)."""
    if orientation is None:
        return ArmWeight(inertia or 0.0, arm_mass or 0.0, arm_com or 0.0)
    arm = np.array([0.0, follower.prime_radius]) - follower.pivot             # pivot -> roller centre at rest
    across = np.array([-arm[1], arm[0]])
    sign = 1.0 if np.array([0.0, follower.prime_radius]) @ across >= 0 else -1.0  # the swing away from the cam
    rising = sign * across                                                  # the rising direction at rest
    tilt = math.radians(orientation) + math.atan2(-rising[0], rising[1])    # from +Y, then +Y from up
    return ArmWeight(inertia or 0.0, arm_mass or 0.0, arm_com or 0.0, tilt, sign * math.pi / 180.0)


def spec_loading(table: Any, follower: Any, positive: bool = False, motion: Any = (), program: Any = None
                 ) -> Loading:
    """The :class:`Loading` of a ``[follower]`` table (one of :mod:`camgen.tables.followers`) on its built
    ``follower``: the spring, loads and load table (or the ``motion`` tables' loads per segment on the built
    ``program``), and for an oscillating roller its arm's inertia and weights. A ``positive`` drive (a groove: no
    spring) counts the weight only with ``orientation``."""
    per_segment = segment_loads(program, motion)
    if per_segment is not None:
        return replace(spec_loading(table, follower, positive), segments=per_segment)
    arm = table.arm_length if table.oscillating else None
    rows = table.load_table_rows
    weights = None if arm is None else arm_weight(follower, table.inertia, table.arm_mass, table.arm_com,
                                                  table.orientation)
    if positive and table.orientation is None:
        return loading(table.mass, None, 0.0, table.load, None, None, arm, None if rows is None else load_table(rows),
                       weights)
    return loading(table.mass, table.spring_rate, table.preload, table.load, table.orientation,
                   table.contact_margin, arm, None if rows is None else load_table(rows), weights)


def speed_report(cam: Cam, rpm: float, mass: float | None, spring_rate: float | None,
                 preload: float | None, parabolic: list[tuple[int, float]], load: float | None = None,
                 orientation: float | None = None, margin: float | None = None,
                 ld: Loading | None = None) -> Speed:
    """Peak velocity, acceleration and jerk at ``rpm``; contact with ``mass`` kg, an optional spring (N/mm, N), an
    external ``load`` (N), the follower's ``orientation`` (degrees from straight up) and a contact ``margin`` (N),
    or with the :class:`Loading` ``ld`` built from them (with a load table, an arm's inertia and weights).
    An oscillating roller's arm carries its mass, spring and load at the roller's centre, along its path."""
    omega = rpm * 2 * math.pi / 60
    unit = cam.follower.lift_unit
    v, a, j = peaks_at(cam, *(lambda t, m, k=k: np.abs(m[k]) for k in (1, 2, 3)))
    contact = None if mass is None else _check(cam, rpm, omega, mass, spring_rate, preload, load, orientation,
                                               margin, ld)
    return Speed(rpm, omega, unit, v.value * omega, v.at_deg, a.value * omega**2, a.at_deg, j.value * omega**3,
                 j.at_deg, tuple(parabolic), contact)


def _check(cam: Cam, rpm: float, omega: float, mass: float, spring_rate: float | None, preload: float | None,
           load: float | None, orientation: float | None, margin: float | None, ld: Loading | None) -> ContactCheck:
    """:func:`speed_report`'s contact check with a ``mass``."""
    unit = cam.follower.lift_unit
    arm = getattr(cam.follower, "arm_length", None) if unit != "mm" else None
    ld = ld or loading(mass, spring_rate, preload, load, orientation, margin, arm)
    held = spring_rate is not None or preload is not None or bool(load) or ld.varies or ld.weight != 0
    if unit != "mm" and (arm is None or not held):
        return Unanalysed("contact is analysed for translating followers and for an oscillating roller's arm held "
                          "by a spring, a load or its weight")
    if arm is None and spring_rate is None and preload is None and not load and orientation is None and not margin \
            and not ld.varies:
        decel = peak_of(cam, lambda m: -m[2])                      # largest -s'' (mm/rad^2)
        limit = math.inf if decel.value <= 0 else math.sqrt(G_MM / decel.value) * 60 / (2 * math.pi)
        return GravityHold(None if math.isinf(limit) else limit, decel.at_deg if decel.value > 0 else None,
                           rpm < limit)
    return _contact(cam, ld, omega, "gravity" if spring_rate is None and preload is None else "spring")


#: :func:`rate_angle`'s value where the follower is at rest with a shortfall (pi/2): only the preload can help
RATE_ONLY_PRELOAD = math.pi / 2


def rate_angle(ld: Loading, omega: float, theta: np.ndarray, m: np.ndarray) -> np.ndarray:
    """The rate (N/mm) that would keep the contact force at the margin with this preload, as an angle (radians):
    atan2(shortfall, s), the shortfall ``margin - (force - rate s)`` (N) and s the travel along the path (mm, >= 0).

    Where the follower has moved (s > 0) it is atan(shortfall / s), the rate this point asks for, increasing with
    it; where it is at rest (s = 0) it is +pi/2 with a shortfall (no rate can help there: only the preload, see
    :data:`RATE_ONLY_PRELOAD`) and -pi/2 (or 0) without. So the function is finite and continuous (but at a point
    with no shortfall at rest, where it asks for nothing), its largest value over the turn is the rate needed's
    angle, tan of it the rate (clamped at 0 by the caller), and a peak search sees no sentinel: the least rate is
    max over s > 0 of shortfall / s."""
    short = ld.margin - (ld.force(m, omega, theta) - ld.rate * ld.scale * m[0])
    return np.arctan2(short, np.maximum(ld.scale * m[0], 0.0))


def liftoff_demand(ld: Loading, theta: np.ndarray, m: np.ndarray) -> np.ndarray:
    """1 / omega^2 (s^2/rad^2) of the speed at which the follower leaves the cam here: the force at ``omega`` is
    ``still + mass omega^2 s'' / 1000``, zero at omega^2 = 1000 still / (mass * -s''), so this is
    mass * -s'' / (1000 still) (<= 0 where s'' >= 0: no speed lets it go there). Its largest value over the turn,
    if > 0, gives the lift-off speed, omega = 1 / sqrt of it. Finite and continuous where the force at rest
    ``still`` is > 0 (0 elsewhere: the caller reports lift-off at rest, 0 rpm, from the least force at rest)."""
    still = ld.still(m, theta)
    top = ld.mass * ld.scale * -np.asarray(m[2], dtype=float) / 1000.0
    return np.divide(top, still, out=np.zeros(np.broadcast(top, still).shape), where=still > 0)


def _contact(cam: Cam, ld: Loading, omega: float, mode: str) -> HeldContact:
    """The contact force's least value and where, the preload and the rate that keep it at the margin at this
    speed, and the speed at which this loading lets the follower go (see :func:`rate_angle` and
    :func:`liftoff_demand` for the two searched functions, finite and continuous over the whole turn)."""
    low, need, worst, rest, slowest = peaks_at(
        cam, lambda t, m: -ld.force(m, omega, t), lambda t, m: ld.margin - (ld.force(m, omega, t) - ld.preload),
        lambda t, m: rate_angle(ld, omega, t, m), lambda t, m: -ld.still(m, t),
        lambda t, m: liftoff_demand(ld, t, m))
    need_rate = None if worst.value >= RATE_ONLY_PRELOAD else max(0.0, math.tan(worst.value))
    held_at_rest = -rest.value > 0
    # 0 if the follower leaves at rest (the least force still at rest not above 0); None if it never decelerates
    liftoff = 0.0 if not held_at_rest else (None if slowest.value <= 0
                                            else math.sqrt(1.0 / slowest.value) * 60 / (2 * math.pi))
    return HeldContact(mode, ld.rate, ld.preload, ld.load, ld.weight_at_rest, ld.margin, -low.value, low.at_deg,
                       -low.value > ld.margin, max(0.0, need.value), need_rate, liftoff,
                       None if ld.table is None else LoadRange(float(min(ld.table.loads)), float(max(ld.table.loads)),
                                                               len(ld.table.loads)),
                       None if ld.segments is None else tuple(ld.segments.loads),
                       None if need_rate is None or need_rate == 0.0 else worst.at_deg)
