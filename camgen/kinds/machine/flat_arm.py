"""An oscillating flat-faced follower's arm as a clash body of a machine
(:func:`camgen.kinds.machine.clash.machine_parts`).

The follower (:class:`~camgen.followers.oscillating_flat.OscillatingFlat`) is a straight face through its pivot
(``follower.pivot`` from the cam's centre, in the cam's fixed frame, which is the machine's moved to the cam's
shaft), touching the base circle at (0, Rb) at rest and turned by k psi about the pivot (k its ``_swing``, psi its
swing in radians). Its arm, ``cams.<cam>.arm``, lies along the face on the side away from the cam:

* in its own frame the pivot is the origin and +X runs along the face towards the contact; the arm is a rectangle
  from the pivot to the face's far end (the farthest contact, the cam's ``face_extent[1]`` mm from the pivot, plus
  ``follower.face_margin``), :data:`DEPTH_MM` deep away from the cam, its face the rectangle's edge on y = 0, with an
  ear round the pivot pin (a disc of the pin's hole radius plus :data:`EAR_WALL_MM`) and round each coupled
  four-bar's crank pin, which lies on the face's line ``crank`` mm out (:mod:`camgen.kinds.machine.arms`);
* it turns with the face: placed at the angle of the pivot-to-rest-contact line plus k psi, about the pivot;
* it fills its cam's plane (its face rides the cam) and the plane over it (as a roller fills both beside its arm),
  so that a part on either meets it;
* it meets its cam at the contact (:meth:`~camgen.followers.drawing.Pivoted.fixed`, turning with the program
  angle) in a disc of :data:`DEPTH_MM` (+ 0.05 mm), and its pivot pin (standing on the frame, plane 0 up) at the
  pivot, as an oscillating roller's arm does.

It is an :class:`~camgen.kinds.machine.clash.Arm`, as an oscillating roller's arm is: a coupled four-bar's crank,
its coupler and rocker placed from the arm's top plane with their crank pin on it.

Lengths mm, angles radians, counter-clockwise.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from camgen.kinds.machine import arms
from camgen.kinds.machine.clash import Arm, Body, Joint, rotation
from camgen.kinds.machine.flat_arm_part import FlatArmPart

#: (mm) the arm's depth away from its face; the wall round its pins' holes (its ears)
DEPTH_MM, EAR_WALL_MM = 8.0, 2.0

#: a hole: its centre (x, y) and radius, mm in the arm's frame
Hole = tuple[tuple[float, float], float]


def arm_part(name: str, far: float, side: float, holes: tuple[Hole, ...], thickness: float,
             tolerance: float) -> FlatArmPart:
    """The arm as a part maker (``name``, its own frame): the rectangle [0, ``far``] x [0, ``side``
    :data:`DEPTH_MM`] (``side`` +1 or -1: the side away from the cam) and an ear round each of ``holes`` ((centre,
    radius) mm: the pivot pin's at the origin, a crank pin's on the face's line), a disc of the hole's radius plus
    :data:`EAR_WALL_MM`; ``thickness`` and chord ``tolerance`` mm."""
    return FlatArmPart(name, far, side, DEPTH_MM, tuple((c, 2 * r) for c, r in holes),
                       tuple(r + EAR_WALL_MM for _, r in holes), thickness, tolerance)


def face_geometry(cam_design: Any, follower: Any) -> tuple[float, float]:
    """The arm's far end (mm from the pivot: the farthest contact, ``face_extent[1]``, plus
    ``follower.face_margin``) and its side (+1 or -1, away from the cam's centre) in its own frame."""
    pivot = np.asarray(follower.pivot, float)
    rest = arms.rest_vector(follower)
    normal = np.array([-rest[1], rest[0]])                  # +Y of the arm's frame at rest
    side = -1.0 if float(np.dot(-pivot, normal)) > 0 else 1.0
    return float(cam_design.face_extent[1]) + float(cam_design.spec.follower.face_margin), side


def flat_arm(cam: str, cam_design: Any, kin: Any, plane: int, centre: np.ndarray,
             theta: Callable[[np.ndarray], np.ndarray], tolerance: float) -> tuple[Arm, Joint]:
    """Cam ``cams.<cam>``'s oscillating flat face's arm (see the module docstring), whose ``made`` body (given its
    pivot pin's diameter and its crank pins) the caller adds and stands a pin under (at its ``pivot``, (2,) mm in the
    machine's frame), and its joint with the cam.

    Parameters
    ----------
    cam_design, kin
        The cam kind's design (its ``face_extent`` and ``spec.follower.face_margin``) and its cam (``follower``,
        ``program``).
    plane, centre
        The cam's plane (2 layer) and its shaft's centre (2,) mm.
    theta
        phi (n,) radians -> the cam's program angles (n,) radians.
    """
    from camgen.kinds.machine.follower_parts import arm_holes

    f = kin.follower
    pivot = np.asarray(f.pivot, float)
    rest = arms.rest_vector(f)
    base = math.atan2(rest[1], rest[0])
    far, side = face_geometry(cam_design, f)
    k = arms.swing_sign(f)
    at = centre + pivot
    name = f"cams.{cam}.arm"

    def turn(phi: np.ndarray) -> np.ndarray:
        return base + k * np.radians(np.asarray(kin.program.evaluate(theta(phi))[0], float))

    def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return rotation(turn(phi)), np.broadcast_to(at, (len(phi), 2))

    def direction(phi: np.ndarray) -> np.ndarray:
        a = turn(phi)
        return float(np.hypot(*rest)) * np.column_stack([np.cos(a), np.sin(a)])

    def contact(phi: np.ndarray) -> np.ndarray:
        t = np.asarray(theta(phi), float)
        return centre + f.fixed(t, f.pitch(t, kin.program.evaluate(t)))

    def made(pivot_pin: float, pins: tuple[tuple[float, float], ...] = ()) -> Body:
        holes = arm_holes(None, pivot_pin, pins)
        outline = arm_part(name, far, side, holes, 0.0, tolerance).outline.flatten(tolerance)
        return Body(name, plane, plane + 1, outline, place, holes)

    return Arm(f, at, plane + 1, direction, made), Joint(f"cams.{cam}", name, contact, DEPTH_MM + 0.05)
