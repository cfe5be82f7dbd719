"""A translating follower's stem (and roller) as clash bodies of a machine
(:func:`camgen.kinds.machine.clash.machine_parts`).

The stem is a rectangle ``width`` mm wide centred on the follower's line x = ``axis_x`` (the cam's fixed frame,
which is the machine's, moved to the cam's shaft), from the follower's point (the roller's centre; a knife's edge; a
flat face's contact height) up ``length`` mm, moved along +Y by the follower's lift s (mm) at each main shaft angle.
It lies on the plane over its cam's (as an arm does); a roller (radius > 0) is a circle about the follower's point on
the cam's plane and the stem's, meeting the cam at its centre's disc. A knife's edge or a flat face meets its cam at
the follower's point: a joint disc of half the stem's width there.

The stem's length is twice its stroke plus its width (it stays in a guide as long as its stroke), and at least
:data:`MIN_LENGTH_MM`; its width is the coupled linkage's parts' width, else :data:`WIDTH_MM`.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from camgen.kinds.machine.clash import Body, Joint, circle

#: the width (mm) of a stem not coupled to a linkage (no parts table to take one from)
WIDTH_MM = 8.0
#: the shortest stem drawn (mm), for a follower of a small stroke
MIN_LENGTH_MM = 20.0


def stem_length(stroke: float, width: float) -> float:
    """The stem's length (mm): twice the follower's ``stroke`` (mm) plus its ``width`` (mm), at least
    :data:`MIN_LENGTH_MM`."""
    return max(2.0 * stroke + width, MIN_LENGTH_MM)


def rectangle(length: float, width: float) -> np.ndarray:
    """(4, 2) mm: a ``width`` mm wide rectangle from (0, 0) to (0, ``length``), counter-clockwise."""
    h = width / 2
    return np.array([[-h, 0.0], [h, 0.0], [h, length], [-h, length]])


def stem_bodies(cam: str, follower: object, plane: int, point: np.ndarray, lift: Callable[[np.ndarray], np.ndarray],
                width: float, tolerance: float) -> tuple[list[Body], list[Joint]]:
    """The bodies and joints of cam ``cam``'s translating follower (its clash name ``cams.<cam>``): its stem
    ``cams.<cam>.stem`` and, with a roller, ``cams.<cam>.roller``.

    Parameters
    ----------
    follower
        A :class:`~camgen.followers.translating_roller.TranslatingRoller` (a knife edge with radius 0) or a
        :class:`~camgen.followers.translating_flat.TranslatingFlat`.
    plane
        The cam's plane (2 layer); the stem lies on ``plane + 1``.
    point
        (2,) mm: the follower's point at lift 0 in the machine's frame
        (:func:`camgen.kinds.machine.slider_coupling.rest_point` moved to the shaft).
    lift
        phi (n,) radians -> the follower's lift s (n,) mm along +Y.
    width, tolerance
        The stem's width and the outlines' chordal tolerance (mm).
    """
    name = f"cams.{cam}"
    sample = lift(np.linspace(0.0, 2 * np.pi, 721))
    length = stem_length(float(np.ptp(sample)), width)

    def centre(phi: np.ndarray, point: np.ndarray = point) -> np.ndarray:
        s = lift(phi)
        return np.column_stack([np.full(len(phi), point[0]), point[1] + s])

    def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.broadcast_to(np.eye(2), (len(phi), 2, 2)), centre(phi)

    radius = float(getattr(follower, "roller_radius", 0.0))
    bodies = [Body(f"{name}.stem", plane + 1, plane + 1, rectangle(length, width), place)]
    if radius > 0:
        bodies.append(Body(f"{name}.roller", plane, plane + 1, circle(radius, tolerance), place))
        joints = [Joint(name, f"{name}.roller", centre, 1.01 * radius + 0.05),
                  Joint(f"{name}.stem", f"{name}.roller", centre, 1.01 * radius + 0.05)]
    else:
        joints = [Joint(name, f"{name}.stem", centre, 0.51 * width + 0.05)]
    return bodies, joints

