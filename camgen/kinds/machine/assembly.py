"""The machine assembled at one angle of the main shaft (``machine.assembly_angle``): every part the clash check
places (:func:`camgen.kinds.machine.clash.machine_parts`: the cams, the followers' arms and rollers, the four-bars'
couplers and rockers, the pins and shafts, a frame's spacers), put where the kinematics puts it at that angle, on
the height of its plane (:class:`camgen.kinds.machine.frame.Stack`), with the frame's plates and the bearings in
their seats. No I/O.

A piece is a flat :class:`~camgen.core.parts.Part` already in the machine's frame (its outline and round holes
turned, mirrored where the kinematics mirrors a four-bar, and moved: x, y in mm as the frame's plate has them) and
its height ``z`` (mm, up from the bottom plate's bottom face). The outlines are the clash check's (chords within the
cams' tolerance, 0.01 mm for the links). ``bought`` marks the hardware (pins, shafts, bearings): the 3MF holds it
as one object of its own (:data:`BOUGHT_GROUP`), its build item marked not printable (a slicer shows it and slices
only the printed parts); the STEP file holds every piece as a solid of its own.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from camgen.core.parts import Part, Placed
from camgen.core.shapes import Circle, Contour
from camgen.kinds.machine import frame as frames
from camgen.kinds.machine.clash import Body

#: the 3MF group that holds the bought parts
BOUGHT_GROUP = "bought parts (not printed)"


@dataclass(frozen=True)
class Piece:
    """A part of the assembly: a flat ``part`` in the machine's frame (mm), standing at height ``z`` (mm), and
    whether it is ``bought`` (hardware: not printed)."""

    part: Part
    z: float
    bought: bool


def _placed_part(body: Body, phi: float, thickness: float, tolerance: float) -> Part:
    """``body``'s outline and round holes placed at main shaft angle ``phi`` (rad): a flat part ``thickness`` mm
    thick in the machine's frame (counter-clockwise, the order reversed where its placement mirrors)."""
    m, t = body.place(np.array([phi]))
    m, t = np.asarray(m[0]), np.asarray(t[0])
    points = body.outline @ m.T + t
    if np.linalg.det(m) < 0:
        points = points[::-1]
    holes = tuple(Circle((float(c[0]), float(c[1])), r)
                  for c, r in ((m @ np.asarray(centre) + t, radius) for centre, radius in body.holes))
    return Part(body.name, Contour(points), holes, thickness, tolerance)


def _span(body: Body, design: Any, stack: frames.Stack, thick: dict[str, float]) -> tuple[float, float]:
    """A body's bottom and top (mm): a flat moving part on its plane, as thick as it is made; an arm's roller on
    its cam's plane, as thick as the cam, as a translating follower's roller and flat face; a stem guide's rail from
    the plate's top face to the top of its stem's plane; a pin from under the
    bottom plate or its lowest part to its highest part or the top plate's top; a shaft from its stub under the
    bottom plate (or from the bottom face of its part behind the frame: a stub there would cross the back
    linkage's rods) to its highest cam; a spacer between its neighbours."""
    from camgen.kinds.machine.framekit import SHAFT_STUB_MM, pin_span

    name = body.name
    if name.startswith("spacers.") and design.frame is not None:
        index = [s.name for s in design.frame.spacers].index(name)
        return design.frame.spacer_heights()[index]
    if name.startswith("pins."):
        if design.frame is not None:
            return pin_span(design.frame, design, name)
        return (0.0 if body.low == 0 else stack.bottom[body.low]), stack.top[body.high]
    if name.startswith("shafts."):
        if body.low < 0:           # reaching a linkage behind the frame: to its crank's face (its rods cross below)
            return stack.bottom[body.low], stack.top[body.high]
        return -SHAFT_STUB_MM, stack.top[body.high]
    cam = name.removesuffix(".roller").removesuffix(".face")
    if name.endswith((".roller", ".face")) and f"{cam}.arm" in thick:    # a roller, a flat face: as its cam
        return stack.bottom[body.low], stack.bottom[body.low] + thick[cam]
    if ".guide." in name:                                   # a stem's guide rail: standing on the frame's plate
        from camgen.kinds.machine.stem_kit import rail_span

        return rail_span(stack, body)
    if name in thick and body.low == body.high:
        return stack.bottom[body.low], stack.bottom[body.low] + thick[name]
    return stack.bottom[body.low], stack.top[body.high]


def pieces(design: Any) -> tuple[Piece, ...]:
    """Every part of ``design`` (a :class:`~camgen.kinds.machine.design.MachineDesign`) placed at
    ``machine.assembly_angle``: the frame's plates (as printed), the moving parts, the spacers, then the bought
    parts (pins, the rollers' axles, shafts, bearings)."""
    spec = design.spec
    phi = math.radians(spec.machine.assembly_angle)
    tol = min((*(float(c.design.tolerance) for c in design.cams),
               *(float(m.design.spec.parts.tolerance) for m in getattr(design, "cranked", ())
                 if m.design.spec.parts is not None)), default=0.01)
    frame = design.frame
    stack = frame.stack if frame is not None else frames.stack(spec, design, design.bodies)
    thick = frames.thicknesses(design)
    made: list[Piece] = []
    bought: list[Piece] = []
    if frame is not None:
        made.append(Piece(frame.printed(frame.plate), 0.0, False))
        if frame.top is not None:
            made.append(Piece(frame.printed(frame.top), stack.bottom[stack.roof], False))
    for body in design.bodies:
        bottom, top = _span(body, design, stack, thick)
        part = _placed_part(body, phi, top - bottom, tol)
        if body.name.startswith("spacers."):
            part = Part(part.name, part.outline, (Circle(*_centre_hole(body, frame)),), part.thickness, tol)
        hardware = body.name.startswith(("pins.", "shafts."))
        (bought if hardware else made).append(Piece(part, bottom, hardware))
    from camgen.kinds.machine.follower_parts import axles

    bought += [Piece(axle.part(tol), axle.bottom, True) for axle in axles(design, stack)]
    if frame is not None:
        bought += _bare_shafts(design, frame, tol)
        for seat in frame.seats:
            if seat.bearing is not None:
                b = seat.bearing
                ring = Part(f"bearing {b.name} of {seat.name}", _circle(seat.centre, b.outside / 2),
                            (Circle(seat.centre, b.bore / 2),), b.width, tol)
                bought.append(Piece(ring, 0.0, True))
    return (*made, *bought)


def _bare_shafts(design: Any, frame: Any, tolerance: float) -> list[Piece]:
    """The shafts in the frame that carry no part the clash check places (a hand crank's, turning gears only): each
    a rod of its seat's diameter (mm) from its stub under the bottom plate up to the plate's top, as long as the kit
    buys it (:func:`camgen.kinds.machine.framekit.shaft_length`)."""
    from camgen.kinds.machine.framekit import SHAFT_STUB_MM, shaft_length

    placed = {body.name for body in design.bodies}
    out = []
    for seat in frame.seats:
        if seat.name.startswith("shafts.") and seat.name not in placed:
            length = shaft_length(frame, design, seat.name.removeprefix("shafts."))
            rod = Part(seat.name, _circle(seat.centre, seat.diameter / 2), (), length, tolerance)
            out.append(Piece(rod, -SHAFT_STUB_MM, True))
    return out


def _centre_hole(body: Body, frame: Any) -> tuple[tuple[float, float], float]:
    """A spacer's bore: (centre, radius) mm."""
    spacer = next(s for s in frame.spacers if s.name == body.name)
    return spacer.centre, spacer.bore / 2


def _circle(centre: tuple[float, float], radius: float) -> Contour:
    """A circle of ``radius`` mm about ``centre`` as a contour of two exact half arcs."""
    from camgen.core.shapes import rounded_hull

    return rounded_hull(np.array([centre]), radius)


def meshes(design: Any) -> tuple[Any, ...]:
    """The assembly's 3MF payload: each made piece's mesh in place, then the bought ones together as one mesh named
    :data:`BOUGHT_GROUP`, not printable (one object of several closed shells: a slicer splits a 3MF object of
    components into its components, but keeps one mesh one object, which it shows and does not slice)."""
    from camgen.core.solids import Mesh, checked_mesh

    made: list[Mesh] = []
    bought: list[Mesh] = []
    for piece in pieces(design):
        mesh = checked_mesh(piece.part)[0]
        mesh = replace(mesh, vertices=mesh.vertices + np.array([0.0, 0.0, piece.z]), name=piece.part.name)
        (bought if piece.bought else made).append(mesh)
    if not bought:
        return tuple(made)
    offsets = np.cumsum(np.array([0, *(len(m.vertices) for m in bought[:-1])], dtype=np.int64))
    group = replace(bought[0], vertices=np.concatenate([m.vertices for m in bought]),
                    faces=np.concatenate([m.faces + k for m, k in zip(bought, offsets, strict=True)]),
                    name=BOUGHT_GROUP, printable=False)
    return (*made, group)


def solids(design: Any) -> tuple[Placed, ...]:
    """The assembly's STEP payload: every piece a solid of its own, raised to its height."""
    return tuple(Placed(p.part.name, (p.part,), 0.0, (0.0, 0.0, p.z)) for p in pieces(design))


def assembly_report(design: Any) -> dict[str, Any]:
    """The report's ``assembly``: the angle and each piece's name, height, thickness, plan bounds (mm) and whether
    it is bought."""
    out = []
    for p in pieces(design):
        x0, y0, x1, y1 = p.part.outline.bounds()
        out.append({"name": p.part.name, "z_mm": round(p.z, 9), "thickness_mm": round(p.part.thickness, 9),
                    "bounds_mm": [round(v, 9) for v in (x0, y0, x1, y1)], "bought": p.bought})
    return {"angle_deg": design.spec.machine.assembly_angle, "pieces": out}
