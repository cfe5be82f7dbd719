"""A machine's ratchets (``[[ratchets]]``, :mod:`camgen.kinds.machine.ratchet_mount`) as clash bodies
(:func:`camgen.kinds.machine.clash.machine_parts`): the wheel, its teeth as linkgen draws them
(:meth:`linkgen.gears.ratchet.RatchetWheel.outline`), turning about its follower's pivot, and its two pawls, linkgen's
pawl figure (:func:`linkgen.mechanisms.ratchet.pawl_shape`) each on its pin: the holding pawl on a frame pin, the
arm's pawl on a pin in the arm that swings with it.

**Frame.** linkgen draws the wheel about its axis, tooth 0's tip on +Y, driven counter-clockwise, the holding pawl
bearing on tooth 0's face at its tip C = (0, R), its pivot at P. Call that the wheel's frame. The machine moves it
onto the arm's pivot, mirrored about its +Y axis where the arm rises clockwise (``sense`` -1: its teeth then face
the other way, as a clockwise drive needs them): x_machine = S x_wheel + pivot, S = diag(sense, 1). In the wheel's
frame the arm then rises counter-clockwise: its direction is a(phi), at angle a0 + psi.

**Poses.** The wheel is turned by W + w0 (W its angle, :meth:`~camgen.kinds.machine.ratchet_mount.RatchetMotion
.wheel_angle`): w0 in [0, p) (p the pitch) puts a tooth's tip at the arm's pawl's contact while it drives. The arm's
pawl is linkgen's figure turned about the axis by beta = a(phi) - angle(P), so its pivot lies on the arm's line
|P| out (the arm's hole); while it drives, beta - W - w0 is a whole number of pitches, so its tip bears on a face.
The holding pawl is the figure turned by a fixed alpha = W_top + w0 + m p (W_top the wheel's angle where it is
held, from the top of a stroke), the whole number m putting its pin nearest the side of the wheel away from the
arm at mid-stroke: while the wheel is held its nose sits on the face it holds. A pawl bearing (the arm's while it
drives the wheel, the holding pawl while the wheel is still) is linkgen's pose; elsewhere it is turned about its
pin by the least lift that keeps it its drawn nose gap (:data:`~linkgen.mechanisms.ratchet.NOSE_GAP_MM`, 0.05 mm)
off the teeth, as its spring holds it down on them (:meth:`PawlPoses.lift`): riding up a tooth's back or over its
tip, or dropped into a tooth space. That lift has no closed form here: it is bisected on every angle at once to
1e-12 rad (rather than drawn at the highest it rides, resting on the tip circle: the pawl follows the teeth, its
nose 0.05 mm off them at every angle).

**Plane.** Plane 2 ``layer``, else the plane over the follower's arm (the arm's pawl rides on the arm's face); the
wheel turns on the pivot's pin, which reaches up to it, and is as thick as the arm, and so are its pawls, on its
plane. Each pawl meets the wheel in a joint (a disc of the teeth's depth about its contact, as a roller meets its
cam) and its pin; the arm's pin is its hole in the arm (no body: the arm lies on the plane under it).
Lengths mm, angles radians, counter-clockwise.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.kinds.machine.clash import Arm, Body, Joint, Placement, rotation

#: the lift (rad) to which :func:`lift_angle` bisects
LIFT_TOL_RAD = 1e-12


def lift_angle(points: np.ndarray, pivot: np.ndarray, tip_radius: float) -> float:
    """The least turn (rad, >= 0) of the pawl ``points`` (its outline in the wheel's frame at rest, mm) about its
    ``pivot`` away from the wheel (clockwise in the wheel's frame: its nose, on the pivot's counter-clockwise side,
    rises) that puts all of it outside the tip circle of ``tip_radius`` mm: the pawl resting on the tips. Bisected
    to :data:`LIFT_TOL_RAD` on shapely's distance from the axis, the clear end kept."""
    import shapely

    def clear(delta: float) -> bool:
        turned = (points - pivot) @ rotation(np.array([-delta]))[0].T + pivot
        return bool(shapely.Polygon(turned).distance(shapely.Point(0.0, 0.0)) >= tip_radius)

    lo, hi = 0.0, math.pi / 2
    if clear(lo):
        return 0.0
    while hi - lo > LIFT_TOL_RAD:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if clear(mid) else (mid, hi)
    return hi


def _placed(points: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """(n, m, 2): ``points`` (m, 2) turned counter-clockwise by each of ``angle`` (n,) rad about the origin."""
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    x, y = points[:, 0], points[:, 1]
    return np.stack([c * x - s * y, s * x + c * y], -1)


@dataclass(frozen=True)
class PawlPoses:
    """Where a ratchet's wheel and pawls sit in its wheel's frame (see the module's notes): the ``motion``, its arm's
    direction ``arm`` (phi -> (n, 2), the machine's frame), the wheel's offset ``w0`` (rad), the holding pawl's turn
    ``alpha`` (rad) about the axis, the pawl's outline ``points`` and linkgen's ``pivot`` and ``contact`` (mm, the
    wheel's frame at rest), the most lift ``highest`` (rad) and ``mirror`` S."""

    motion: Any
    arm: Callable[[np.ndarray], np.ndarray]
    w0: float
    alpha: float
    points: np.ndarray
    pivot: np.ndarray
    contact: np.ndarray
    highest: float
    mirror: np.ndarray

    def arm_angle(self, phi: np.ndarray) -> np.ndarray:
        """a(phi): the arm's direction's angle in the wheel's frame (rad)."""
        w = self.arm(np.asarray(phi, float)) @ self.mirror.T
        return np.arctan2(w[:, 1], w[:, 0])

    def beta(self, phi: np.ndarray) -> np.ndarray:
        """The arm's pawl's turn about the axis (rad): a(phi) - angle(P)."""
        return self.arm_angle(phi) - math.atan2(self.pivot[1], self.pivot[0])

    def lift(self, turn: np.ndarray, phi: np.ndarray, bears: np.ndarray) -> np.ndarray:
        """The pawl's lift (rad, clockwise about its pin in the wheel's frame: its nose rising; 0 as linkgen draws
        it bearing on a face at the tooth's tip) where it is turned ``turn`` (n,) about the axis at main shaft
        angles ``phi`` (n,): 0 where it ``bears``, elsewhere the least, down to -``highest``, that keeps it
        :data:`~linkgen.mechanisms.ratchet.NOSE_GAP_MM` (its drawn gap, less 1e-9 mm) off the wheel's teeth, as its
        spring holds it down on them: riding on a tooth (above 0) or dropped into a tooth space. Bisected on every
        angle at once to :data:`LIFT_TOL_RAD` on shapely's distance, the clear end kept."""
        import shapely

        from linkgen.mechanisms.ratchet import NOSE_GAP_MM

        out = np.zeros(len(phi))
        free = ~np.asarray(bears, bool)
        if not free.any():
            return out
        wheel = self.motion.table.wheel.outline()[0]
        teeth = shapely.polygons(_placed(wheel, self.motion.wheel_angle(phi[free]) + self.w0 - turn[free]))
        shapely.prepare(teeth)
        local = self.points - self.pivot

        def clear(delta: np.ndarray) -> np.ndarray:
            pawls = shapely.polygons(_placed(local, -delta) + self.pivot)
            return np.asarray(shapely.distance(pawls, teeth) >= NOSE_GAP_MM - 1e-9)

        lo, hi = np.full(len(teeth), -self.highest), np.full(len(teeth), self.highest)
        down = clear(lo)
        hi[down] = lo[down]
        while np.any(hi - lo > LIFT_TOL_RAD):
            mid = 0.5 * (lo + hi)
            ok = clear(mid)
            hi, lo = np.where(ok, mid, hi), np.where(ok, lo, mid)
        out[free] = hi
        return out

    def turns(self, which: str, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pawl ``which`` ("pawl", the holding pawl, or "lever-pawl", the arm's): its turn about the axis and its
        turn about its pin (rad, counter-clockwise in the wheel's frame: minus its lift) at main shaft angles
        ``phi``; the arm's pawl bears where it drives the wheel, the holding pawl elsewhere."""
        phi = np.asarray(phi, float)
        drives = self.motion.driving_at(phi)
        if which == "pawl":
            turn = np.full(len(phi), self.alpha)
            return turn, -self.lift(turn, phi, ~drives)
        turn = self.beta(phi)
        return turn, -self.lift(turn, phi, drives)

    def placement(self, which: str, centre: np.ndarray) -> Placement:
        """Pawl ``which``'s placement (phi -> (M, t)), its frame's origin at its pin, the wheel on ``centre`` (mm);
        the last angles' poses kept, as the clash check places a body at the same angles for each pair."""
        last: list[tuple[bytes, tuple[np.ndarray, np.ndarray]]] = []

        def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            key = np.asarray(phi, float).tobytes()
            if not last or last[0][0] != key:
                turn, lift = self.turns(which, phi)
                pin = np.einsum("nij,j->ni", rotation(turn), self.pivot) @ self.mirror.T + centre
                last[:] = [(key, (self.mirror @ rotation(turn + lift), pin))]
            return last[0][1]
        return place

    def contact_at(self, which: str, centre: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
        """Pawl ``which``'s contact C (its nose's point at a tooth's tip when it bears) over the angles (mm)."""
        local = self.contact - self.pivot
        place = self.placement(which, centre)

        def at(phi: np.ndarray) -> np.ndarray:
            m, t = place(np.asarray(phi, float))
            return np.einsum("nij,j->ni", m, local) + t
        return at


def pawl_poses(motion: Any, arm: Callable[[np.ndarray], np.ndarray], points: np.ndarray) -> PawlPoses:
    """The poses of ratchet ``motion``'s pawls, its arm's direction ``arm`` (phi -> (n, 2), the machine's frame),
    linkgen's pawl outline ``points`` (mm, the wheel's frame at rest)."""
    pawl = motion.table.holding_pawl
    pitch, mirror = motion.pitch, np.diag([float(motion.sense), 1.0])
    pivot, contact = np.asarray(pawl.pivot, float), np.asarray(pawl.contact, float)
    from linkgen.mechanisms.ratchet import NOSE_GAP_MM

    highest = lift_angle(points, pivot, motion.table.wheel.tip_radius + 2 * NOSE_GAP_MM)
    poses = PawlPoses(motion, arm, 0.0, 0.0, points, pivot, contact, highest, mirror)
    top = np.array([motion.top_angle()])
    held = float(motion.wheel_angle(top)[0])
    w0 = float(np.mod(poses.beta(top)[0] - held, pitch))
    lo, hi = motion.stroke.start, motion.stroke.top
    mid = np.array([(0.5 * (lo + hi + (2 * math.pi if hi < lo else 0.0)) + math.radians(motion.phase_deg))
                    / motion.turns])
    away = float(poses.arm_angle(mid)[0]) + math.pi - math.atan2(pivot[1], pivot[0])
    base = held + w0
    alpha = base + round((away - base) / pitch) * pitch
    return PawlPoses(motion, arm, w0, float(alpha), points, pivot, contact, highest, mirror)


def wheel_placement(motion: Any, pivot: np.ndarray, offset: float = 0.0) -> Placement:
    """The wheel's placement (phi -> (M, t)) of ratchet ``motion`` on the pivot at ``pivot`` (mm), turned on by
    ``offset`` (rad, w0) in its frame."""
    mirror = np.diag([float(motion.sense), 1.0])

    def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        turn = rotation(motion.sense * (motion.wheel_angle(phi) + offset))
        return turn @ mirror, np.broadcast_to(pivot, (len(phi), 2))

    return place


def ratchet_bodies(design: Any, arms: dict[str, Arm], bodies: list[Body],
                   joints: list[Joint], pins: dict[tuple[float, float], tuple[list[str], int, float]],
                   arm_pins: dict[str, list[tuple[float, float]]]) -> None:
    """Each ratchet's wheel and pawls added to ``bodies`` (their joints to ``joints``), the wheel on its arm's pivot
    pin and the holding pawl on its frame pin (both added to ``pins``), and its arm's pawl's pin to ``arm_pins``
    (each cam's (distance out along its arm, pin diameter) mm: the arm's holes); ``arms``: each cam's follower's arm
    (:class:`~camgen.kinds.machine.clash.Arm`: its follower, pivot (mm), plane and direction)."""
    from camgen.kinds.machine.clash import _margin
    from camgen.kinds.machine.frame import pin_hole
    from camgen.kinds.machine.ratchet_parts import PIN_MM, pawl_points

    for i, (motion, mount) in enumerate(zip(design.ratchets, design.spec.ratchets, strict=True)):
        if motion.cam not in arms:
            continue
        follower, pivot, arm_plane, arm = (arms[motion.cam].follower, arms[motion.cam].pivot, arms[motion.cam].plane,
                                           arms[motion.cam].direction)
        plane = arm_plane + 1 if mount.layer is None else 2 * mount.layer
        points = pawl_points(design, i, motion, float(follower.roller_radius))
        poses = pawl_poses(motion, arm, points)
        outline = motion.table.wheel.outline()[0]
        name = f"ratchets.{motion.name}.wheel"
        bodies.append(Body(name, plane, plane, np.asarray(outline, float), wheel_placement(motion, pivot, poses.w0)))
        key = next((k for k in pins if float(np.hypot(k[0] - pivot[0], k[1] - pivot[1])) < 1e-9),
                   (float(pivot[0]), float(pivot[1])))
        entry = pins.setdefault(key, ([], 0, PIN_MM / 2))
        entry[0].append(name)
        arm_pins.setdefault(motion.cam, []).append((float(np.hypot(*poses.pivot)), PIN_MM))
        local = np.asarray(points, float) - poses.pivot
        holes = (((0.0, 0.0), pin_hole(PIN_MM) / 2),)
        for which in ("pawl", "lever-pawl"):
            pawl = f"ratchets.{motion.name}.{which}"
            bodies.append(Body(pawl, plane, plane, local, poses.placement(which, pivot), holes))
            joints.append(Joint(pawl, name, poses.contact_at(which, pivot), _margin(float(mount.depth))))
        pin = poses.placement("pawl", pivot)(np.zeros(1))[1][0]
        pins.setdefault((float(pin[0]), float(pin[1])), ([], 0, PIN_MM / 2))[0].append(f"ratchets.{motion.name}.pawl")


def thicknesses(design: Any, known: dict[str, float]) -> dict[str, float]:
    """Each ratchet's wheel's and pawls' thickness (mm) by their clash-check names: its follower's arm's
    (``known``, the others' thicknesses), the pawls being cut from the same stock as the arm they ride on."""
    out = {}
    for motion in getattr(design, "ratchets", ()):
        arm = known.get(f"cams.{motion.cam}.arm")
        if arm is not None:
            for part in ("wheel", "pawl", "lever-pawl"):
                out[f"ratchets.{motion.name}.{part}"] = arm
    return out
