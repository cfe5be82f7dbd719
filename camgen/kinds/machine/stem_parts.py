"""A translating follower's stem (and roller) as clash bodies of a machine
(:func:`camgen.kinds.machine.clash.machine_parts`).

The stem is a rectangle ``width`` mm wide centred on the follower's line x = ``axis_x`` (the cam's fixed frame,
which is the machine's, moved to the cam's shaft), from the follower's point (the roller's centre; a knife's edge; a
flat face's contact height) up ``length`` mm, moved along +Y by the follower's lift s (mm) at each main shaft angle.
It lies on the plane over its cam's (as an arm does); a roller (radius > 0) is a circle about the follower's point on
the cam's plane and the stem's, meeting the cam at its centre's disc, with its axle's hole. The stem is a part of
its own (:mod:`camgen.kinds.machine.stem_kit`): its outline is this body's (:func:`stem_slab`), with the roller's
axle hole at its foot and the hole of a coupled linkage's slider joint where that sits (:func:`stem_holes`); a hole
at its foot gives it a round foot of half its width about the hole. A knife's edge or a flat face meets its cam at
the follower's point: a joint disc of half the stem's width there.

The stem's length is twice its stroke plus its width (it stays in a guide as long as its stroke), and at least
:data:`MIN_LENGTH_MM` and its stroke, its foot's height (a roller's radius, a face's depth), the guide's gap and its
width (so that a width of it stays in the guide); its width is the coupled linkage's parts' width, else
:data:`WIDTH_MM`. A flat face and the guide are bodies too (:mod:`camgen.kinds.machine.stem_guide`).
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from camgen.kinds.machine.clash import Body, Joint
from camgen.kinds.machine.slabs import Slab
from camgen.kinds.machine.stem_guide import FACE_DEPTH_MM, GUIDE_GAP_MM, face_bodies, guide_bodies, guide_span

#: a hole of a stem: (centre (x, y) mm in its frame, nominal diameter mm)
Hole = tuple[tuple[float, float], float]

#: a flat face: its ends along it (mm from the follower's axis, +X) and its contact (phi -> (n, 2) mm)
Face = tuple[tuple[float, float], Callable[[np.ndarray], np.ndarray]]

#: the width (mm) of a stem not coupled to a linkage (no parts table to take one from)
WIDTH_MM = 8.0
#: the shortest stem drawn (mm), for a follower of a small stroke
MIN_LENGTH_MM = 20.0


def stem_length(stroke: float, width: float, foot: float = 0.0) -> float:
    """The stem's length (mm): twice the follower's ``stroke`` (mm) plus its ``width`` (mm), at least
    :data:`MIN_LENGTH_MM` and the ``stroke``, the ``foot`` (mm over the follower's point), the guide's gap and the
    ``width`` together."""
    return max(2.0 * stroke + width, MIN_LENGTH_MM, stroke + foot + GUIDE_GAP_MM + width)


def stem_holes(roller: bool, slider: Hole | None) -> tuple[Hole, ...]:
    """A stem's holes (centre mm in its frame, nominal diameter mm): a roller's axle at its foot (the follower's
    point, the origin: :data:`~camgen.kinds.machine.follower_parts.AXLE_MM`'s ISO 273 clearance hole) and the pin of
    a linkage's ``slider`` joint ((centre, pin diameter) mm) where it sits; one hole where the two fall together (to
    1e-9 mm: the larger kept)."""
    from camgen.kinds.machine.follower_parts import AXLE_MM
    from camgen.kinds.machine.frame import pin_hole

    holes: list[Hole] = [((0.0, 0.0), pin_hole(AXLE_MM))] if roller else []
    if slider is not None:
        (x, y), d = slider
        same = next((i for i, (c, _) in enumerate(holes) if np.hypot(c[0] - x, c[1] - y) <= 1e-9), None)
        if same is None:
            holes.append(((x, y), pin_hole(d)))
        else:
            holes[same] = (holes[same][0], max(holes[same][1], pin_hole(d)))
    return tuple(holes)


def stem_slab(cam: str, width: float, length: float, holes: tuple[Hole, ...], thickness: float = 0.0,
              tolerance: float = 0.01) -> Slab:
    """Cam ``cam``'s stem as a part maker (``<cam>-stem``, its frame's origin the follower's point, +Y up the
    stem): ``width`` mm wide, from its foot up ``length`` mm, with ``holes``; a hole at its foot (a roller's axle, a
    slider's pin at the follower's point) gets a round foot of half its width about it, so that the hole has a wall
    all round."""
    foot = width / 2 if any(np.hypot(*c) <= 1e-9 for c, _ in holes) else 0.0
    return Slab(f"{cam}-stem", ((-width / 2, 0.0, width / 2, length),), holes, thickness, tolerance, foot)


def stem_bodies(cam: str, follower: object, plane: int, point: np.ndarray, lift: Callable[[np.ndarray], np.ndarray],
                width: float, tolerance: float, face: Face | None = None,
                slider: Hole | None = None) -> tuple[list[Body], list[Joint]]:
    """The bodies and joints of cam ``cam``'s translating follower (its clash name ``cams.<cam>``): its stem
    ``cams.<cam>.stem``, with a roller ``cams.<cam>.roller``, with a flat face ``cams.<cam>.face``, and the stem's
    guide (:func:`camgen.kinds.machine.stem_guide.guide_bodies`).

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
    face
        A flat face's ends along it (mm from the axis, +X) and its contact (phi -> (n, 2) mm, the machine's
        frame); None for a roller or a knife edge.
    slider
        The coupled linkage's slider joint on the stem: (centre mm in the stem's frame, pin diameter mm), or None.
    """
    name = f"cams.{cam}"
    sample = lift(np.linspace(0.0, 2 * np.pi, 721))
    radius = float(getattr(follower, "roller_radius", 0.0))
    foot = FACE_DEPTH_MM if face is not None else radius
    length = stem_length(float(np.ptp(sample)), width, foot)
    rails = guide_bodies(cam, plane + 1, float(point[0]), width,
                         guide_span(float(point[1]), float(sample.min()), float(sample.max()), length, foot))

    def centre(phi: np.ndarray, point: np.ndarray = point) -> np.ndarray:
        s = lift(phi)
        return np.column_stack([np.full(len(phi), point[0]), point[1] + s])

    def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.broadcast_to(np.eye(2), (len(phi), 2, 2)), centre(phi)

    from camgen.kinds.machine.follower_parts import roller_hole, roller_outline

    slab = stem_slab(cam, width, length, stem_holes(radius > 0, slider))
    bodies = [Body(f"{name}.stem", plane + 1, plane + 1, slab.outline.flatten(tolerance), place,
                   tuple((c, d / 2) for c, d in slab.holes))]
    if radius > 0:
        bodies.append(Body(f"{name}.roller", plane, plane + 1, roller_outline(radius).flatten(tolerance), place,
                           (roller_hole(),)))
        joints = [Joint(name, f"{name}.roller", centre, 1.01 * radius + 0.05),
                  Joint(f"{name}.stem", f"{name}.roller", centre, 1.01 * radius + 0.05)]
    elif face is not None:
        faced, joints = face_bodies(cam, plane, point, face[0], width, lift, face[1])
        bodies += faced
    else:
        joints = [Joint(name, f"{name}.stem", centre, 0.51 * width + 0.05)]
    return [*bodies, *rails], joints

