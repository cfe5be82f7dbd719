"""A machine's translating followers as parts of their own (issue 35 item 4): each stem, its roller or flat face
and its guide's two rails, cut and printed as the followers' arms are (``<machine>-<cam>-stem.dxf|-cut.svg|.stl|
.3mf``, ``-roller``, ``-face``, ``-guide-left``, ``-guide-right``), listed in the machine's kit with the roller's
axle and the guide's screws bought, each at its place in the assembly. No I/O.

The parts are the clash check's bodies (:func:`camgen.kinds.machine.stem_parts.stem_bodies`), their outlines exact:

* the stem: ``width`` mm wide from the follower's point up its length, with the roller's axle hole at its foot (the
  follower's point) and the hole of a coupled linkage's slider joint where it sits (one hole where they fall
  together), as thick as its cam, on the plane over its cam's;
* the roller: a disc of ``follower.roller_radius`` with the axle's hole, as thick as its cam, on the cam's plane;
  its axle a bolt of :data:`~camgen.kinds.machine.follower_parts.AXLE_MM` (bought) from the roller's bottom face up
  through the stem;
* a flat face: its strip along the contact line (:func:`camgen.kinds.machine.stem_guide.face_slab`), as thick as
  its cam, on the cam's plane, under the stem's foot (glued or screwed to it: no hole is drawn);
* the guide's rails: printed blocks standing on the frame's plate (its top face) up to the top of the stem's plane,
  each with its lugs and their screws' holes (:func:`camgen.kinds.machine.stem_guide.rail_slabs`); the screws are
  pins of the frame (the plate's holes, the kit's bolts).
"""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from camgen.kinds.machine.follower_parts import Axle, FollowerPart
from camgen.kinds.machine.stem_guide import face_slab, rail_slabs
from camgen.kinds.machine.stem_parts import Hole, stem_slab


def slider_joint(m: Any, point: np.ndarray) -> Hole | None:
    """Where the slider joint of the linkage ``m`` (a :class:`~camgen.kinds.machine.slider_coupling.SliderMotion`)
    sits on its stem: (centre mm in the stem's frame, the linkage's pin diameter mm), the stem's frame at the
    follower's point ``point`` (mm, the machine's frame, at lift 0) moving with the lift; None where the slider
    slides on a link (not the stem)."""
    slider = next((x for x in m.analysis.linkage.structure.sliders if x.name == m.coupling.link), None)
    if slider is None or slider.link is not None:
        return None
    at = np.asarray(m.points[slider.point][0], float) - np.asarray(point, float) - np.array([0.0, m.lift[0][0]])
    return (float(at[0]), float(at[1])), float(m.design.spec.parts.pin_diameter)


def _stems(design: Any) -> list[tuple[Any, dict[str, Any]]]:
    """Each cam with a translating follower's stem among the clash check's bodies: (cam, its bodies by suffix:
    ``stem`` and, as it has them, ``roller``, ``face``, ``guide.left``, ``guide.right``)."""
    bodies = {b.name: b for b in design.bodies}
    out = []
    for cam in design.cams:
        name = f"cams.{cam.name}"
        if f"{name}.stem" in bodies:
            out.append((cam, {k: bodies[f"{name}.{k}"] for k in ("stem", "roller", "face", "guide.left",
                                                                   "guide.right") if f"{name}.{k}" in bodies}))
    return out


def _stack(design: Any) -> Any:
    """The heights of the machine's planes (:class:`camgen.kinds.machine.frame.Stack`), as the assembly takes them."""
    from camgen.kinds.machine import frame as frames

    return design.frame.stack if design.frame is not None else frames.stack(design.spec, design, design.bodies)


def rail_span(stack: Any, body: Any) -> tuple[float, float]:
    """A guide rail's bottom and top (mm, up from the bottom plate's bottom face): from the plate's top face to the
    top of the stem's plane."""
    return float(stack.thickness), float(stack.top[body.high])


def stem_parts(design: Any) -> tuple[FollowerPart, ...]:
    """Each translating follower's parts (see the module's docstring), in the cams' order: the stem, the roller or
    the flat face, the two rails; nominal (holes at their nominal sizes), as thick as the assembly makes them."""
    from camgen.kinds.machine.design import _cam_of
    from camgen.kinds.machine.follower_parts import made_radius, roller_hole, roller_outline
    from camgen.kinds.machine.frame import thicknesses
    from camgen.core.kit import Plate

    thick, stack = thicknesses(design), _stack(design)
    out: list[FollowerPart] = []
    for cam, parts in _stems(design):
        tol, name = float(cam.design.tolerance), f"cams.{cam.name}"
        stem = parts["stem"]
        x0, x1 = float(stem.outline[:, 0].min()), float(stem.outline[:, 0].max())
        length = float(stem.outline[:, 1].max())
        holes = tuple((c, 2 * r) for c, r in stem.holes)
        out.append(FollowerPart(stem.name, "stem", stem_slab(cam.name, x1 - x0, length, holes, thick[stem.name], tol)))
        if "roller" in parts:
            r = made_radius(cam.design, float(_cam_of(cam.design).follower.roller_radius))
            (c, hr), = (roller_hole(),)
            out.append(FollowerPart(parts["roller"].name, "roller", Plate(
                f"{cam.name}-roller", roller_outline(r), ((c, 2 * hr),), thick[name], tol)))
        if "face" in parts:
            face = parts["face"].outline
            slab = face_slab(cam.name, (float(face[:, 0].min()), float(face[:, 0].max())), thick[name], tol)
            out.append(FollowerPart(parts["face"].name, "flat face", slab))
        rails = [parts[k] for k in ("guide.left", "guide.right") if k in parts]
        if rails:
            ys = np.concatenate([b.outline[:, 1] for b in rails])
            bottom, top = rail_span(stack, rails[0])
            for (side, slab), body in zip(rail_slabs(cam.name, x1 - x0, (float(ys.min()), float(ys.max()))), rails,
                                          strict=True):
                out.append(FollowerPart(body.name, f"guide rail ({side})", replace(slab, thickness=top - bottom,
                                                                                   tolerance=tol)))
    return tuple(out)


def stem_axles(design: Any, stack: Any) -> tuple[Axle, ...]:
    """Each translating roller's axle placed at ``machine.assembly_angle``: from the roller's bottom face up through
    the stem to its top face."""
    from camgen.kinds.machine.frame import thicknesses

    thick = thicknesses(design)
    phi = np.array([math.radians(design.spec.machine.assembly_angle)])
    out = []
    for cam, parts in _stems(design):
        if "roller" not in parts:
            continue
        roller, stem = parts["roller"], parts["stem"]
        centre = roller.place(phi)[1][0]
        out.append(Axle(f"cams.{cam.name}.axle", (float(centre[0]), float(centre[1])), stack.bottom[roller.low],
                        stack.bottom[stem.low] + thick[stem.name]))
    return tuple(out)


def guide_screws(design: Any) -> dict[str, str]:
    """The frame's pins that are stem guides' screws: pin name -> the rail it holds (``cams.<cam>.guide.<side>``),
    a pin at a rail's lug hole (to 1e-9 mm)."""
    from camgen.kinds.machine.stem_guide import guide_screws as screws

    at = [(c, b.name) for b in design.bodies for c, _ in screws(b)]
    out = {}
    for b in design.bodies:
        if b.name.startswith("pins."):
            centre = b.place(np.zeros(1))[1][0]
            rail = next((r for c, r in at if math.dist(c, centre) <= 1e-9), None)
            if rail is not None:
                out[b.name] = rail
    return out
