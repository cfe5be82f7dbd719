"""An oscillating flat-faced follower's arm as a clash body of a machine
(:func:`camgen.kinds.machine.clash.machine_parts`).

The follower (:class:`~camgen.followers.oscillating_flat.OscillatingFlat`) is a straight face through its pivot
(``follower.pivot`` from the cam's centre, in the cam's fixed frame, which is the machine's moved to the cam's
shaft), touching the base circle at (0, Rb) at rest and turned by k psi about the pivot (k its ``_swing``, psi its
swing in radians). Its arm, ``cams.<cam>.arm``, lies along the face on the side away from the cam:

* in its own frame the pivot is the origin and +X runs along the face towards the contact; the arm is a rectangle
  from the pivot to the face's far end (the farthest contact, the cam's ``face_extent[1]`` mm from the pivot, plus
  ``follower.face_margin``), :data:`DEPTH_MM` deep away from the cam, its face the rectangle's edge on y = 0, with an
  ear round the pivot pin (a disc of the pin's hole radius plus :data:`EAR_WALL_MM`);
* it turns with the face: placed at the angle of the pivot-to-rest-contact line plus k psi, about the pivot;
* it fills its cam's plane (its face rides the cam) and the plane over it (as a roller fills both beside its arm),
  so that a part on either meets it;
* it meets its cam at the contact (:meth:`~camgen.followers.drawing.Pivoted.fixed`, turning with the program
  angle) in a disc of :data:`DEPTH_MM` (+ 0.05 mm), and its pivot pin (standing on the frame, plane 0 up) at the
  pivot, as an oscillating roller's arm does.

Lengths mm, angles radians, counter-clockwise.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import shapely

from camgen.kinds.machine.clash import Body, Joint, PIVOT_PIN_MM, rotation
from camgen.kinds.machine.stem_guide import box

#: (mm) the arm's depth away from its face; the wall round its pivot pin's hole (its ear)
DEPTH_MM, EAR_WALL_MM = 8.0, 2.0


def arm_outline(far: float, side: float, pin_hole: float, tolerance: float) -> np.ndarray:
    """The arm's outline (m, 2) mm in its own frame, counter-clockwise: the rectangle [0, ``far``] x [0, ``side``
    :data:`DEPTH_MM`] (``side`` +1 or -1: the side away from the cam) and the ear, a disc of ``pin_hole`` / 2 +
    :data:`EAR_WALL_MM` about the pivot (chords within ``tolerance``)."""
    from camgen.kinds.machine.clash import circle

    lo, hi = sorted((0.0, side * DEPTH_MM))
    body = shapely.union(shapely.Polygon(box(0.0, lo, far, hi)),
                         shapely.Polygon(circle(pin_hole / 2 + EAR_WALL_MM, tolerance)))
    ring = shapely.geometry.polygon.orient(body, 1.0)
    return np.asarray(ring.exterior.coords)[:-1]


def flat_arm(cam: str, cam_design: Any, kin: Any, plane: int, centre: np.ndarray,
             theta: Callable[[np.ndarray], np.ndarray], tolerance: float) -> tuple[Body, Joint, np.ndarray]:
    """Cam ``cams.<cam>``'s oscillating flat face's arm (see the module docstring), its joint with the cam, and its
    pivot (2,) mm in the machine's frame (the caller stands a pin there).

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
    from camgen.kinds.machine.frame import pin_hole

    f = kin.follower
    pivot = np.asarray(f.pivot, float)
    rest = np.array([0.0, float(f.base_radius)]) - pivot
    base = math.atan2(rest[1], rest[0])
    normal = np.array([-rest[1], rest[0]])                  # +Y of the arm's frame at rest
    side = -1.0 if float(np.dot(-pivot, normal)) > 0 else 1.0      # away from the cam's centre
    far = float(cam_design.face_extent[1]) + float(cam_design.spec.follower.face_margin)
    k = float(f._swing)
    at = centre + pivot

    def place(phi: np.ndarray, theta: Callable = theta, program: Any = kin.program) -> tuple[np.ndarray, np.ndarray]:
        psi = np.radians(np.asarray(program.evaluate(theta(phi))[0], float))
        return rotation(base + k * psi), np.broadcast_to(at, (len(phi), 2))

    def contact(phi: np.ndarray, theta: Callable = theta) -> np.ndarray:
        t = np.asarray(theta(phi), float)
        return centre + f.fixed(t, f.pitch(t, kin.program.evaluate(t)))

    hole = pin_hole(PIVOT_PIN_MM) / 2
    body = Body(f"cams.{cam}.arm", plane, plane + 1, arm_outline(far, side, 2 * hole, tolerance), place,
                (((0.0, 0.0), hole),))
    return body, Joint(f"cams.{cam}", body.name, contact, DEPTH_MM + 0.05), at
