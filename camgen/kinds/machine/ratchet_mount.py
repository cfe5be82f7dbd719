"""A ratchet on a machine (``[[ratchets]]``): a ratchet wheel on a shaft at an oscillating follower's pivot, indexed
by a pawl riding on the follower's arm (the lever of :mod:`linkgen.mechanisms.ratchet`) and held by a pawl on a frame
pin. The wheel and the pawls are linkgen's (:class:`~linkgen.mechanisms.ratchet.RatchetTable`): their tooth geometry
and the holding check are not written again here. Pure numpy; no I/O.

**Motion.** The arm swings psi (camgen's swing, radians here, positive as it rises off its cam) by its cam's program,
once a cam turn from its least swing psi_lo up to its most psi_hi and back: a swing h = psi_hi - psi_lo of
n = floor(h / p) whole pitches p = 2 pi / z. The holding pawl sits where it drops behind a tooth with the wheel at
the top of each stroke, so the wheel is held there over the back stroke (its load never turns it back); the arm's
pawl, carried back with the arm, slides over n teeth and bears on a face again only after h - n p of the next forward
stroke (its lost motion). Over a forward stroke (program angles from the least swing's to the most's) the wheel has
so turned

    w = max(0, psi - (psi_hi - n p)),        n p over the back stroke,

and each cam turn adds n p: W = k n p + w, k the strokes the arm has finished, continuous. The wheel's angle is W
less its value at the machine's start (0 then), counted in the sense the arm rises in (the machine's sense of
rotation times the follower's swing sign); its rate dW/dphi = psi' |turns| where the arm's pawl drives, else 0.

**Forces.** ``load_torque`` T (N*m) resists the wheel's advance. While the arm's pawl drives, the arm carries it about
the wheel's axis (the arm's pivot), so the roller is pressed onto its cam with T / arm (virtual work: T dW = F arm
dpsi, dW = dpsi); while the holding pawl holds, the frame carries it and the arm nothing. The main shaft puts in
T dW/dphi (the wheel's power over the shaft's speed).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Annotated, Any

import numpy as np
from pydantic import Field

from camgen.core.errors import SpecError
from camgen.core.spec import NAME_PATTERN, Model, notes, unit, validate
from camgen.kinds.machine import kinematics
from linkgen.mechanisms.ratchet import PawlTable, RatchetTable

TWO_PI = 2.0 * math.pi
#: the most a ratchet's load may be (N*m)
MAX_LOAD_N_M = 1e4
#: program angles at which a ratchet's cam is sampled to find its stroke (its least and most swing)
STROKE_SAMPLES = 7200
#: a swing falling (or rising) by at most this (rad) between two samples counts as still (a dwell's round-off)
STILL_RAD = 1e-12
#: the lever table's swing (degrees) the wheel and pawl are checked with before the cam's swing is known
_ANY_SWING_DEG = 180.0
_WHEEL = RatchetTable.model_fields


class RatchetMount(Model):
    """A ratchet on a machine: a wheel at the pivot of ``cam``'s oscillating follower, indexed by a pawl on its arm
    and held by a pawl on a frame pin (the wheel's and the holding pawl's sizes as ``type = "ratchet"`` takes
    them)."""

    name: str = Field(pattern=NAME_PATTERN, description="its name: letters, digits, '.', '_', '-' (its files' names "
                      "are <machine>-<name>)")
    cam: str = Field(description="the cam whose follower's arm drives it (one of [[cams]], an oscillating roller): "
                     "the wheel's shaft is the arm's pivot, the arm the ratchet's lever")
    teeth: Annotated[int, _WHEEL["teeth"]]
    tip_diameter: Annotated[float, _WHEEL["tip_diameter"]]
    depth: Annotated[float, _WHEEL["depth"]]
    face_angle: Annotated[float, _WHEEL["face_angle"]] = _WHEEL["face_angle"].default
    friction: Annotated[float, _WHEEL["friction"]] = _WHEEL["friction"].default
    pawl: PawlTable = Field(description="the holding pawl on its frame pin, as a ratchet's [linkage.pawl]")
    load_torque: float = Field(0.0, ge=0.0, le=MAX_LOAD_N_M, description="the torque on the wheel resisting its "
                               "advance, carried by the arm while its pawl drives (onto the follower's roller and "
                               "the main shaft) and by the holding pawl while it holds", json_schema_extra=unit("N*m"))
    layer: int | None = Field(None, ge=0, le=50, description="the wheel's and the pawls' plane along the wheel's "
                              "shaft: plane 2 layer, as a cam's",
                              json_schema_extra=notes(absent="the plane over its follower's arm"))

    def table(self, swing_deg: float = _ANY_SWING_DEG, lever_mm: float = 0.0) -> RatchetTable:
        """linkgen's ratchet of this wheel and holding pawl, its lever swinging ``swing_deg`` degrees (the arm's
        stroke) and ``lever_mm`` long (the arm's length; at least its pawl's pivot and a width out); a
        :class:`SpecError` naming the field where linkgen refuses it."""
        pawl = self.pawl.model_dump()
        reach = self.tip_diameter / 2 + self.pawl.length + 2 * self.depth
        return validate(RatchetTable, {
            "type": "ratchet", "teeth": self.teeth, "tip_diameter": self.tip_diameter, "depth": self.depth,
            "face_angle": self.face_angle, "friction": self.friction, "pawl": pawl,
            "lever": {"swing": swing_deg, "length": max(lever_mm, reach)}})


def check_ratchets(spec: Any) -> None:
    """Refuse, in a :class:`ValueError` naming the field, a ratchet on a cam that does not exist, whose follower is
    not an oscillating roller (a translating one has no arm, a flat face's contact no fixed arm length), which
    another ratchet or a coupling drives already or which turns with an indexing shaft; a mount name taken; and a
    wheel whose teeth cannot be drawn or whose holding pawl does not hold (linkgen's checks)."""
    cams = {c.name: i for i, c in enumerate(spec.cams)}
    taken = {m.name for m in (*spec.cams, *spec.linkages, *spec.genevas)}
    coupled = {c.cam: i for i, c in enumerate(spec.couplings)}
    wheels = {g.wheel for g in spec.genevas}
    seen: dict[str, int] = {}
    for i, r in enumerate(spec.ratchets):
        if r.name in taken or any(r.name == o.name for o in spec.ratchets[:i]):
            raise ValueError(f"ratchets[{i}].name: {r.name!r} names another mount already (their files share the "
                             "machine's folder: give each mount a name of its own)")
        if r.cam not in cams:
            raise ValueError(f"ratchets[{i}].cam: no cam {r.cam!r}; cams: {', '.join(cams) or 'none'}")
        follower = spec.cam_specs[cams[r.cam]].follower.type
        if follower != "oscillating-roller":
            raise ValueError(f"ratchets[{i}].cam: cams.{r.cam} has a {follower} follower; a ratchet's lever is an "
                             "arm of fixed length: give an oscillating-roller follower")
        if r.cam in seen:
            raise ValueError(f"ratchets[{i}].cam: cams.{r.cam}'s arm drives ratchets[{seen[r.cam]}] already; one arm "
                             "carries one ratchet's pawl")
        if r.cam in coupled:
            raise ValueError(f"ratchets[{i}].cam: cams.{r.cam}'s arm drives couplings[{coupled[r.cam]}] already; one "
                             "arm drives one ratchet or one linkage")
        if spec.cams[cams[r.cam]].shaft in wheels:
            raise ValueError(f"ratchets[{i}].cam: cams.{r.cam} turns with an indexing shaft (a Geneva drive turns "
                             "it): a ratchet there is not supported yet")
        seen[r.cam] = i
        try:
            r.table()
        except SpecError as exc:                                   # linkgen's refusal, named under the mount
            raise ValueError(str(exc.under(f"ratchets[{i}]"))) from None


@dataclass(frozen=True)
class Stroke:
    """An arm's stroke over its cam's program: the program angles (rad) of its least and most swing and those swings
    (rad), the forward stroke running from ``start`` to ``top`` (cyclic)."""

    start: float
    top: float
    low: float
    high: float

    @property
    def swing(self) -> float:
        """h = psi_hi - psi_lo (rad)."""
        return self.high - self.low

    def teeth(self, pitch: float) -> int:
        """n = floor(h / p): the whole pitches ``pitch`` (rad) a stroke advances the wheel (a swing within 1e-9 of
        a whole number of pitches counts as that number)."""
        return math.floor(self.swing / pitch + 1e-9)

    @property
    def rise(self) -> float:
        """The forward stroke's length in program angle (rad, in (0, 2 pi))."""
        return float(np.mod(self.top - self.start, TWO_PI))


def stroke_of(program: Any, where: str, samples: int = STROKE_SAMPLES) -> Stroke:
    """The one stroke a cam turn of ``program`` (a :class:`camgen.program.Program` of swings in degrees), found on
    ``samples`` program angles and its segments' starts; a :class:`SpecError` under ``where`` for a program that
    swings forward more than once a turn (it falls on its way up or rises on its way down) or not at all."""
    theta = np.union1d(np.arange(samples) * (TWO_PI / samples), np.mod(program.starts, TWO_PI))
    psi = np.radians(program.evaluate(theta)[0])
    lo, hi = int(np.argmin(psi)), int(np.argmax(psi))
    if psi[hi] - psi[lo] <= 0:
        raise SpecError("its follower does not swing: a ratchet's arm makes one stroke a cam turn", where)
    rolled = np.roll(psi, -lo)
    up = (hi - lo) % len(psi)
    if np.any(np.diff(rolled[:up + 1]) < -STILL_RAD) or np.any(np.diff(np.append(rolled[up:], rolled[0]))
                                                                > STILL_RAD):
        raise SpecError("its follower swings forward more than once a cam turn; a ratchet's arm makes one stroke "
                        "a turn (a rise to its most swing and a return to its least)", where)
    return Stroke(float(theta[lo]), float(theta[hi]), float(psi[lo]), float(psi[hi]))


def forward(stroke: Stroke, theta: np.ndarray) -> np.ndarray:
    """Where (bool) program angles ``theta`` (rad, unwrapped) lie on the forward stroke (from its start, the least
    swing's angle, to its top, the most's, the top left to the back stroke)."""
    return np.asarray(np.mod(np.asarray(theta, float) - stroke.start, TWO_PI) < stroke.rise)


def wheel_turned(stroke: Stroke, pitch: float, theta: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """W (rad, see the module's notes) at unwrapped program angles ``theta`` (rad) where the arm's swing is ``psi``
    (rad): k n p + w, k the strokes finished since program angle 0."""
    n = stroke.teeth(pitch)
    k = np.floor((np.asarray(theta, float) - stroke.start) / TWO_PI)
    w = np.where(forward(stroke, theta), np.maximum(0.0, psi - (stroke.high - n * pitch)), n * pitch)
    return np.asarray(k * n * pitch + w)


def driving(stroke: Stroke, pitch: float, theta: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """Where (bool) the arm's pawl drives the wheel: on the forward stroke past its lost motion."""
    n = stroke.teeth(pitch)
    return np.asarray(forward(stroke, theta) & (psi > stroke.high - n * pitch))


@dataclass(frozen=True)
class RatchetMotion:
    """One ratchet over the machine's turn (arrays by its shaft angles).

    Attributes
    ----------
    name, cam, mount, table
        Its mount's name, the cam whose arm drives it, the mount (:class:`RatchetMount`) and linkgen's ratchet of
        its wheel, its holding pawl and the arm as its lever (:class:`~linkgen.mechanisms.ratchet.RatchetTable`).
    stroke : Stroke
        The arm's stroke.
    turns : float
        Strokes (the cam's shaft's turns) per main turn.
    arm : float
        The arm's length (mm), pivot to roller.
    angle, rate : ndarray
        The wheel's turn W (rad, 0 at the start, in the arm's rising sense) and dW/dphi (rad/rad).
    force : ndarray
        ``load_torque`` on the follower's roller (N, pressing it onto the cam).
    torque : ndarray
        The main shaft's torque against ``load_torque`` (N*m).
    sense : int
        The wheel's sense of rotation in the machine's frame: +1 counter-clockwise, -1 clockwise.
    """

    name: str
    cam: str
    mount: RatchetMount
    table: RatchetTable
    stroke: Stroke
    turns: float
    arm: float
    angle: np.ndarray
    rate: np.ndarray
    force: np.ndarray
    torque: np.ndarray
    sense: int = 1
    #: the arm's program (degrees of swing) and the shaft's angle (degrees) at which it starts
    program: Any = None
    phase_deg: float = 0.0

    def wheel_angle(self, phi: np.ndarray) -> np.ndarray:
        """W (rad, 0 at the start, in the arm's rising sense) at any main shaft angles ``phi`` (rad)."""
        return _turned_at(self.program, self.stroke, self.pitch, self.turns, self.phase_deg, np.asarray(phi, float))

    def driving_at(self, phi: np.ndarray) -> np.ndarray:
        """Where (bool) the arm's pawl drives the wheel at any main shaft angles ``phi`` (rad): on the forward
        stroke past its lost motion (elsewhere the holding pawl holds it)."""
        theta = self.turns * np.asarray(phi, float) - math.radians(self.phase_deg)
        return driving(self.stroke, self.pitch, theta, np.radians(self.program.evaluate(theta)[0]))

    def top_angle(self) -> float:
        """A main shaft angle (rad) at which the arm is at the top of its stroke (its most swing)."""
        return (self.stroke.top + math.radians(self.phase_deg)) / self.turns

    @property
    def pitch(self) -> float:
        """2 pi / z (rad)."""
        return TWO_PI / self.mount.teeth

    @property
    def teeth_per_stroke(self) -> int:
        return self.stroke.teeth(self.pitch)

    @property
    def teeth_per_turn(self) -> float:
        """Teeth the wheel advances a main turn."""
        return self.teeth_per_stroke * self.turns


def least_swing_deg(teeth: int) -> float:
    """A tooth's pitch, the least stroke (degrees) that advances a wheel of ``teeth``."""
    return 360.0 / teeth


def ratchet_motion(index: int, mount: RatchetMount, program: Any, arm_mm: float, turns: float, phase_deg: float,
                   phi: np.ndarray, sense: int = 1) -> RatchetMotion:
    """The ratchet ``mount`` (``ratchets[index]``) driven by an arm ``arm_mm`` long swinging by ``program`` (degrees)
    on a shaft of ``turns`` turns per main turn, its program starting at the shaft's ``phase_deg``, at main shaft
    angles ``phi`` (rad); a :class:`SpecError` naming ``ratchets[index].cam`` for a stroke under a tooth's pitch, or
    ``ratchets[index].pawl.length`` for an arm's pawl whose pin would lie beyond the arm."""
    where = f"ratchets[{index}].cam"
    stroke = stroke_of(program, where)
    pitch = TWO_PI / mount.teeth
    if stroke.teeth(pitch) < 1:
        raise SpecError(f"cams.{mount.cam}'s arm swings {math.degrees(stroke.swing):.6g} degrees, under a tooth's "
                        f"pitch: the wheel would never advance; give a swing of at least "
                        f"{least_swing_deg(mount.teeth):.6g} degrees (360 / {mount.teeth} teeth)", where)
    table = mount.table(math.degrees(stroke.swing), arm_mm)
    reach = float(np.hypot(*table.holding_pawl.pivot))
    if not reach < arm_mm:
        raise SpecError(f"the arm's pawl's pin lies {reach:.6g} mm from the wheel's axis (the tip radius and the "
                        f"pawl's length), beyond cams.{mount.cam}'s arm ({arm_mm:g} mm): give a shorter pawl or a "
                        "smaller wheel", f"ratchets[{index}].pawl.length")
    n = abs(turns)
    theta = n * np.asarray(phi, float) - math.radians(phase_deg)
    swing = program.evaluate(theta)[:2]
    psi, dpsi = np.radians(swing[0]), np.radians(swing[1]) * n
    driven = driving(stroke, pitch, theta, psi).astype(float)
    rate = driven * dpsi
    force = kinematics.reflected_force(-mount.load_torque, driven, arm_mm)
    torque = kinematics.shaft_torque(-mount.load_torque, driven, dpsi)
    turned = _turned_at(program, stroke, pitch, n, phase_deg, np.asarray(phi, float))
    return RatchetMotion(mount.name, mount.cam, mount, table, stroke, n, arm_mm, turned, rate, force, torque, sense,
                         program, phase_deg)


def _turned_at(program: Any, stroke: Stroke, pitch: float, turns: float, phase_deg: float,
               phi: np.ndarray) -> np.ndarray:
    """W (rad) at main shaft angles ``phi`` (rad) less its value at the start, the arm swinging by ``program``
    (degrees) on a shaft of ``turns`` (> 0) turns a main turn whose program starts at its angle ``phase_deg``."""
    theta = np.append(turns * phi, 0.0) - math.radians(phase_deg)
    turned = wheel_turned(stroke, pitch, theta, np.radians(program.evaluate(theta)[0]))
    return np.asarray(turned[:-1] - turned[-1])


def program_load(motion: RatchetMotion, program: Any, theta: np.ndarray) -> np.ndarray:
    """The force (N) ``load_torque`` presses the roller onto its cam with at program angles ``theta`` (rad): the
    cam's load table."""
    psi = np.radians(program.evaluate(theta)[0])
    driven = driving(motion.stroke, motion.pitch, theta, psi).astype(float)
    return np.asarray(kinematics.reflected_force(-motion.mount.load_torque, driven, motion.arm))


def report_entry(motion: RatchetMotion, phi: np.ndarray) -> dict[str, Any]:
    """The report's ``ratchets.<name>``: teeth, pitch, the arm's stroke, teeth a stroke and a main turn, the wheel's
    angle range over the turn (degrees), the runs (main shaft degrees) over which the arm's pawl drives, the load and
    what it puts on the roller and the main shaft."""
    pitch = math.degrees(motion.pitch)
    n = motion.teeth_per_stroke
    runs = kinematics.intervals(motion.rate != 0)
    return {"cam": motion.cam, "teeth": motion.mount.teeth, "pitch_deg": _num(pitch),
            "swing_deg": _num(math.degrees(motion.stroke.swing)), "teeth_per_stroke": n,
            "lost_motion_deg": _num(math.degrees(motion.stroke.swing) - n * pitch),
            "strokes_per_turn": motion.turns, "teeth_per_turn": motion.teeth_per_turn,
            "wheel_deg": [_num(math.degrees(float(motion.angle.min()))), _num(math.degrees(float(motion.angle.max())))],
            "advance_per_turn_deg": _num(motion.teeth_per_turn * pitch),
            "sense": "counter-clockwise" if motion.sense > 0 else "clockwise",
            "driving_deg": [[_num(a), _num(b)] for a, b in runs],
            "load_torque_n_m": motion.mount.load_torque,
            "reflected_force_n": [_num(float(motion.force.min())), _num(float(motion.force.max()))],
            "shaft_torque_n_m": [_num(float(motion.torque.min())), _num(float(motion.torque.max()))]}


def _num(value: float) -> float:
    """``value`` rounded to 9 decimals, without a negative zero."""
    return round(float(value), 9) + 0.0
