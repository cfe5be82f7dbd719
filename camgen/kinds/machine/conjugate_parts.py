"""A conjugate (dual) cam mounted on a machine's shaft (:mod:`camgen.kinds.conjugate`): its two plates on two
adjacent layers, and its follower's clash bodies (:func:`camgen.kinds.machine.clash.machine_parts`).

A conjugate cam mounted at ``layer`` L takes layers L and L + 1 of its shaft: its first plate (the clash body
``cams.<name>``) on plane 2L, its second (``cams.<name>.second``) on plane 2L + 2; its follower between them, on
plane 2L + 1, with its first roller over planes 2L to 2L + 1 and its second over 2L + 1 to 2L + 2.

* A bell crank (oscillating rollers): one part ``cams.<name>.arm``, the two arms (bars from the pivot to each roller,
  as wide as half the roller) joined at the pivot, turned by the swing psi about it; the arm a coupled linkage's
  crank is (the first arm), as a single cam's arm is.
* A translating yoke: the first roller's stem (as a single cam's translating follower,
  :mod:`camgen.kinds.machine.stem_parts`) and the yoke ``cams.<name>.yoke``, a plate from the second roller's centre
  to the first's, :data:`YOKE_WALL_MM` wider on each side than the shaft, with a slot along its line that the shaft
  runs in (a joint: the shaft's disc is left out of their overlap).

Frames: the cam's (camgen's) fixed frame moved to the shaft's centre, the rollers placed by the conjugate kind's
own kinematics (:meth:`~camgen.kinds.conjugate.kinematics.ArmRoller.centre`,
:meth:`~camgen.kinds.conjugate.kinematics.YokeRoller.centre`).
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import shapely

from camgen.kinds.machine.clash import Body, Joint, _margin, _round_holes, bar, circle, rotation, still

#: how much wider (mm) than the shaft a yoke is on each side of its slot
YOKE_WALL_MM = 4.0


def is_conjugate(cam_design: Any) -> bool:
    """Whether a cam kind's design is a conjugate pair (two plates, :class:`~camgen.kinds.conjugate.design.
    ConjugateDesign`)."""
    return getattr(getattr(cam_design, "spec", None), "kind", None) == "conjugate"


def layers_taken(cam_spec: Any, layer: int) -> tuple[int, ...]:
    """The layers of its shaft a cam mounted at ``layer`` takes: two for a conjugate pair (its two plates), else
    one."""
    return (layer, layer + 1) if getattr(cam_spec, "kind", None) == "conjugate" else (layer,)


def check_layers(mounts: Sequence[Any], cam_specs: Sequence[Any], most: int) -> None:
    """Refuse two cams on one shaft at one layer (a conjugate pair takes its layer and the next,
    :func:`layers_taken`): a :class:`ValueError` naming the second cam's ``cams[i].layer`` (layers 0 to ``most``)."""
    seats: dict[tuple[str, int], str] = {}
    for i, (cam, cam_spec) in enumerate(zip(mounts, cam_specs, strict=True)):
        for layer in layers_taken(cam_spec.cam, cam.layer):
            other = seats.setdefault((cam.shaft, layer), cam.name)
            if other == cam.name:
                continue
            pair = [n for n, s in zip(mounts, cam_specs, strict=True) if n.name in (other, cam.name)
                    and len(layers_taken(s.cam, n.layer)) == 2]
            why = (f" (cams.{pair[0].name} is a conjugate pair: its two plates take layers {pair[0].layer} and "
                   f"{pair[0].layer + 1})" if pair else "")
            raise ValueError(f"cams[{i}].layer: cams.{other} already sits on shaft {cam.shaft} at layer "
                             f"{layer}{why}; give another layer (0 to {most})")


def plates(cam_design: Any) -> tuple[Any, ...]:
    """A cam's flat parts as cut, by its clash body's name suffix: ``("", part)`` for a single plate, and
    ``(".second", part)`` for a conjugate pair's second."""
    if is_conjugate(cam_design):
        first, second = cam_design.cams
        return (("", first.part), (".second", second.part))
    part = getattr(cam_design, "part", None)
    return (("", part),) if part is not None else ()


def bell_crank_outline(rest1: np.ndarray, rest2: np.ndarray, half1: float, half2: float,
                       tolerance: float) -> np.ndarray:
    """The bell crank's outline (m, 2) mm in its own frame (the pivot at the origin, the first arm along +x): the
    first arm a bar to (|rest1|, 0), the second a bar to ``rest2`` turned the same way, their ends rounded by
    ``half1`` and ``half2`` mm; ``rest1`` and ``rest2`` the arms at rest (pivot to roller centre, mm)."""
    turn = math.atan2(rest2[1], rest2[0]) - math.atan2(rest1[1], rest1[0])
    one = bar(float(np.hypot(*rest1)), half1, tolerance)
    two = bar(float(np.hypot(*rest2)), half2, tolerance) @ rotation(np.array([turn]))[0].T
    merged = shapely.union(shapely.Polygon(one), shapely.Polygon(two))
    coords = np.asarray(shapely.get_exterior_ring(shapely.normalize(merged)).coords)[:-1]
    return coords[::-1] if _clockwise(coords) else coords


def _clockwise(points: np.ndarray) -> bool:
    x, y = points[:, 0], points[:, 1]
    return float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)) < 0


def follower_bodies(name: str, cam_design: Any, plane: int, centre: np.ndarray,
                    theta: Callable[[np.ndarray], np.ndarray], tolerance: float, shaft: str,
                    shaft_radius: float) -> tuple[list[Body], list[Joint], Any]:
    """The conjugate pair ``cams.<name>``'s second plate and its follower's bodies and joints (the first plate is
    the caller's, as a single cam's), and, for a bell crank, its arm ``(pivot, arm)`` for a coupled linkage (None
    for a yoke: its first stem is added by the caller as a translating follower's).

    Parameters
    ----------
    plane
        The first plate's plane (2 layer).
    centre
        (2,) mm: the shaft's centre.
    theta
        phi (n,) radians -> the cam's program angles (n,) radians.
    shaft, shaft_radius
        The shaft's name and its radius (mm, the plates' bore): a yoke's slot.
    """
    first, second = cam_design.cam, cam_design.second
    f, g = first.follower, second.follower
    program = first.program
    me = f"cams.{name}"
    part = cam_design.cams[1].part
    sense = f.sense

    def place_cam(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return rotation(sense * theta(phi)), np.broadcast_to(centre, (len(phi), 2))

    bodies = [Body(f"{me}.second", plane + 2, plane + 2, part.outline.flatten(tolerance), place_cam,
                   _round_holes(part.holes))]
    joints = [Joint(f"{me}.second", f"shafts.{shaft}", still(centre), _margin(shaft_radius))]
    r2 = float(g.contact_radius)

    def swing(phi: np.ndarray) -> np.ndarray:
        return np.asarray(program.evaluate(theta(phi))[0], float)

    def roller2(phi: np.ndarray) -> np.ndarray:
        return centre + g.centre(swing(phi))

    def place_roller2(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.broadcast_to(np.eye(2), (len(phi), 2, 2)), roller2(phi)

    bodies.append(Body(f"{me}.roller2", plane + 1, plane + 2, circle(r2, tolerance), place_roller2))
    joints.append(Joint(f"{me}.second", f"{me}.roller2", roller2, _margin(r2)))
    if hasattr(g, "span"):                                   # a translating yoke
        width = 2 * (shaft_radius + YOKE_WALL_MM)
        length = float(g.span)
        h = width / 2
        outline = np.array([[-h, -length], [h, -length], [h, 0.0], [-h, 0.0]])

        def yoke_roller(phi: np.ndarray) -> np.ndarray:
            return centre + np.column_stack([np.full(len(phi), f.offset), f.d0 + swing(phi)])

        def place_yoke(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            return np.broadcast_to(np.eye(2), (len(phi), 2, 2)), yoke_roller(phi)

        bodies.append(Body(f"{me}.yoke", plane + 1, plane + 1, outline, place_yoke))
        joints += [Joint(f"{me}.yoke", f"{me}.roller2", roller2, _margin(r2)),
                   Joint(f"{me}.yoke", f"{me}.roller", yoke_roller, _margin(float(f.roller_radius))),
                   Joint(f"{me}.yoke", f"{me}.stem", yoke_roller, _margin(h)),
                   Joint(f"{me}.yoke", f"shafts.{shaft}", still(centre), _margin(shaft_radius))]
        return bodies, joints, None
    pivot = centre + f.pivot
    rest1 = np.array([0.0, f.prime_radius]) - f.pivot
    k = float(g.away)

    def arm(phi: np.ndarray) -> np.ndarray:
        psi = np.radians(swing(phi))
        c, s = np.cos(k * psi), np.sin(k * psi)
        return np.column_stack([c * rest1[0] - s * rest1[1], s * rest1[0] + c * rest1[1]])

    def place_arm(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        w = arm(phi)
        return rotation(np.arctan2(w[:, 1], w[:, 0])), np.broadcast_to(pivot, (len(phi), 2))

    def roller1(phi: np.ndarray) -> np.ndarray:
        return pivot + arm(phi)

    def place_roller1(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.broadcast_to(np.eye(2), (len(phi), 2, 2)), roller1(phi)

    r1 = float(f.roller_radius)
    outline = bell_crank_outline(rest1, np.asarray(g.rest, float), r1 / 2, r2 / 2, tolerance)
    bodies += [Body(f"{me}.arm", plane + 1, plane + 1, outline, place_arm),
               Body(f"{me}.roller", plane, plane + 1, circle(r1, tolerance), place_roller1)]
    joints += [Joint(me, f"{me}.roller", roller1, _margin(r1)),
               Joint(f"{me}.arm", f"{me}.roller", roller1, _margin(r1)),
               Joint(f"{me}.arm", f"{me}.roller2", roller2, _margin(r2))]
    return bodies, joints, (pivot, arm)
