"""A machine's Geneva drives (``[[genevas]]``, :mod:`camgen.kinds.machine.indexing`) as clash bodies
(:func:`camgen.kinds.machine.clash.machine_parts`): the driver's crank and locking disc, its pin, and the wheel, placed
by the drive's law at every main shaft angle.

**Frames.** The Geneva kind draws each part about its own axis (:mod:`camgen.kinds.geneva.geometry`): in the
drive's frame the driver's axis is the origin and the wheel's (C, 0); at driver angle alpha the driver's parts are
turned by alpha and the wheel by pi + pi/n - W(alpha) (W the wheel's turn, continuous over many driver turns,
:meth:`~camgen.kinds.machine.indexing.Indexer._turned`: pi - beta within the first turn). The machine turns that
frame by gamma, the direction from the driver's shaft to the wheel's, and moves it onto the driver's shaft; where the
driver's shaft turns clockwise (its ``turns`` per main turn negative) the drive is mirrored about its centre line
(the pin then advances clockwise, as the law needs it to advance), so that a part's placement is

    x_machine = R(gamma) diag(1, s) R(angle) x_part + shaft,     s = sign of the driver shaft's turns.

The parts' outlines are symmetric about their own x axes, so the mirror changes no outline, only the sense.

**Planes.** The crank on plane p, the locking disc and the wheel on p + 1 (the Geneva kind's stack: the disc on the
crank, the pin reaching up into the wheel's slots), the pin (``genevas.<name>.pin``, a dowel in the crank's hole)
on both; p is 2 ``layer`` (:class:`~camgen.kinds.machine.spec.GenevaMount`), else the lowest plane from 0 up with
p and p + 1 free of every other part over the drive's discs (the driver's swept circle, the wheel's rim) and no
part under p crossing either shaft (:func:`camgen.kinds.machine.machine_gears.free_plane`).

**Joints.** The pin meets the crank at its centre (its hole) and the wheel there too (in a slot: a contact, as a
roller meets its cam; out of the slots the assembly check keeps it clear of the wheel), each within the pin's disc;
the crank and the disc meet the driver's shaft in their bore, the wheel its shaft in its bore. The locking disc and
the wheel meet in no joint: the lock clearance keeps them apart. Lengths mm, angles radians, counter-clockwise.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from camgen.kinds.machine.clash import Body, Joint, Placement, _margin, _round_holes, circle, rotation, still


def frame_matrix(gamma: float, sense: float) -> np.ndarray:
    """(2, 2) the drive's frame in the machine's: R(``gamma``) diag(1, ``sense``)."""
    return rotation(np.array([gamma]))[0] @ np.diag([1.0, sense])


def placements(g: Any, driver_at: np.ndarray, wheel_at: np.ndarray, sense: float) -> tuple[Placement, Placement,
                                                                                         Callable]:
    """The driver's and the wheel's placements (phi -> (M, t)) and the pin's centre (phi -> (n, 2) mm) of Geneva
    drive ``g`` (an :class:`~camgen.kinds.machine.indexing.Indexer`) between shafts at ``driver_at`` and
    ``wheel_at`` (mm), its driver's shaft turning counter-clockwise (``sense`` +1) or clockwise (-1)."""
    line = np.asarray(wheel_at, float) - np.asarray(driver_at, float)
    frame = frame_matrix(math.atan2(line[1], line[0]), sense)
    slots = g.law.slots
    crank = g.design.geometry.crank_radius

    def driver(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return frame @ rotation(g.driver_angle(phi)), np.broadcast_to(driver_at, (len(phi), 2))

    def wheel(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        turned = g._turned(g.driver_angle(phi))[0]
        return frame @ rotation(math.pi + math.pi / slots - turned), np.broadcast_to(wheel_at, (len(phi), 2))

    def pin(phi: np.ndarray) -> np.ndarray:
        alpha = g.driver_angle(phi)
        return driver_at + (crank * np.column_stack([np.cos(alpha), np.sin(alpha)])) @ frame.T

    return driver, wheel, pin


def _reach(geometry: Any) -> tuple[float, float]:
    """The radii (mm) the driver's parts sweep about its axis and the wheel fills about its own."""
    return (max(geometry.lock_radius, geometry.crank_radius + geometry.crank_width / 2),
            geometry.wheel_radius)


def geneva_bodies(design: Any, bodies: list[Body], joints: list[Joint],
                  shafts: dict[str, list[tuple[int, float]]]) -> None:
    """Add every Geneva drive of ``design`` (a :class:`~camgen.kinds.machine.design.MachineDesign`) to the clash
    check's ``bodies`` and ``joints`` (see the module docstring), and its bores to ``shafts`` (plane, radius mm)."""
    from camgen.kinds.machine.machine_gears import free_plane

    spec = design.spec
    at = {s.name: np.asarray(s.at, float) for s in spec.shafts}
    for g, mount in zip(getattr(design, "indexed", ()), spec.genevas, strict=True):
        geometry, parts = g.design.geometry, g.design.parts
        driver_at, wheel_at = at[g.driver], at[g.wheel]
        if mount.layer is not None:
            plane = 2 * mount.layer
        else:
            driven, filled = _reach(geometry)
            plane = free_plane(bodies, joints, [(driver_at, driven), (wheel_at, filled)],
                               [(driver_at, geometry.driver_bore / 2), (wheel_at, geometry.wheel_bore / 2)],
                               (g.driver, g.wheel), height=2)
        sense = -1.0 if spec.turns[g.driver] < 0 else 1.0
        driver, wheel, pin = placements(g, driver_at, wheel_at, sense)
        tol = float(g.design.tolerance)
        name = f"genevas.{g.name}"
        made = {"crank": (plane, driver), "lock": (plane + 1, driver), "wheel": (plane + 1, wheel)}
        for which, (on, place) in made.items():
            part = parts[which]
            bodies.append(Body(f"{name}.{which}", on, on, part.outline.flatten(tol), place, _round_holes(part.holes)))
        r = geometry.pin_diameter / 2
        bodies.append(Body(f"{name}.pin", plane, plane + 1, circle(r, tol), _at(pin)))
        joints += [Joint(f"{name}.crank", f"{name}.pin", pin, _margin(r)),
                   Joint(f"{name}.wheel", f"{name}.pin", pin, _margin(r))]
        for which, shaft, bore, on in (("crank", g.driver, geometry.driver_bore, plane),
                                       ("lock", g.driver, geometry.driver_bore, plane + 1),
                                       ("wheel", g.wheel, geometry.wheel_bore, plane + 1)):
            if bore > 0:
                joints.append(Joint(f"{name}.{which}", f"shafts.{shaft}", still(at[shaft]), _margin(bore / 2)))
                shafts.setdefault(shaft, []).append((on, bore / 2))


def _at(centre: Callable[[np.ndarray], np.ndarray]) -> Placement:
    """The placement of a round part that does not turn, its centre at ``centre(phi)`` (mm)."""
    def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.broadcast_to(np.eye(2), (len(phi), 2, 2)), centre(phi)
    return place


def thicknesses(design: Any) -> dict[str, float]:
    """Each Geneva part's thickness (mm) by its clash body's name: the drive's ``geneva.thickness``."""
    return {f"genevas.{g.name}.{which}": float(g.design.spec.geneva.thickness)
            for g in getattr(design, "indexed", ()) for which in ("crank", "lock", "wheel")}
