"""A linkage's kit (a ``[kit]`` table beside ``[parts]``): the base plate with mounting holes, the pins as bolts of
the catalogue, the spacers, a bill of materials and every part in its assembled place. No I/O.

The base plate is the ground part: its pivot holes where the design's ground pivots are, and four corner mounting
holes (ISO 273 medium clearance holes for ``kit.bolt``, :mod:`camgen.core.hardware`) at the corners of the pivots'
box widened until the bolts' heads (ISO 4762) clear every moving part over the whole motion (they stand on the
plate, where the moving parts sweep). The pins are ``kit.bolt`` bolts (``parts.pin_diameter`` is their diameter):
one a pivot point, through every part that holds it, with a washer and a nut; their length is the shortest of
ISO 4762's preferred lengths that takes the stack. The parts go into the same build (cut sheet, assembly, meshes)
as any linkage's parts.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from camgen.core.errors import DesignError
from camgen.core.hardware import Bolt, bolt_length
from camgen.core.kit import BomLine, KitTable, Solid, bolt_line, bought, check_clear, disc, fixed
from linkgen.parts import COLLISION_TOLERANCE_MM, Layout, LinkageBuild

#: how many times the corner holes may step outwards (each a hole's width) to clear the moving parts
CORNER_STEPS = 200


@dataclass(frozen=True)
class LinkageKit:
    """A linkage's kit: its build (the base plate with its mounting holes among the parts), the mounting holes'
    centres (mm, the ground's frame), the pins (each pivot point: its position at the first pose, the parts it
    passes, its layers' span), the bill of materials, the report's ``kit`` section and the pose it is shown at."""

    build: LinkageBuild
    mounts: tuple[tuple[float, float], ...]
    pins: tuple[dict[str, Any], ...]
    bom: tuple[BomLine, ...]
    report: dict[str, Any]
    #: the bolt the pins and the mounting holes are sized for
    bolt: Bolt
    #: the placement of the first pose the assembly drawing shows (the kit's 3MF shows the parts there)
    pose: Any = None


def base_plate(layout: Layout, kit: KitTable) -> tuple[Layout, tuple[tuple[float, float], ...]]:
    """The layout with its ground part made a base plate with four corner mounting holes, and their centres (mm).

    The corners start a wall and a hole's width outside the ground pivots' box and step out, a clearance hole's
    width at a time, until no bolt head meets a moving part at any pose; a :class:`DesignError` naming ``kit.bolt``
    when none within :data:`CORNER_STEPS` steps does."""
    import shapely

    bolt = kit.hardware
    ground = next(p for p in layout.parts if not p.moving)
    lo, hi = ground.centres.min(axis=0), ground.centres.max(axis=0)
    sweep = layout.sweep
    n = len(next(iter(sweep.angles.values())))
    swept = shapely.union_all([shapely.Polygon(p.outline().moved(float(sweep.angles[p.name][k]),
                                                                  sweep.origins[p.name][k])
                                               .flatten(COLLISION_TOLERANCE_MM))
                               for p in layout.parts if p.moving for k in range(n)])
    start = ground.half_width + kit.wall + bolt.clearance_hole
    for step in range(CORNER_STEPS):
        m = start + step * bolt.clearance_hole
        corners = ((lo[0] - m, lo[1] - m), (hi[0] + m, lo[1] - m), (hi[0] + m, hi[1] + m), (lo[0] - m, hi[1] + m))
        heads = shapely.buffer(shapely.points(np.array(corners)), bolt.head_diameter / 2 + 0.5)
        if not shapely.intersects(heads, swept).any():
            break
    else:
        raise DesignError(f"kit.bolt: no corner of the base plate within {CORNER_STEPS} steps keeps the {bolt.name} "
                          "mounting bolts' heads clear of the moving parts")
    body = np.vstack([ground.centres if ground.body is None else ground.body, corners])
    mounts = tuple((float(x), float(y)) for x, y in corners)
    plate = replace(ground, body=body, mounts=tuple((c, bolt.clearance_hole) for c in mounts),
                    half_width=max(ground.half_width, bolt.clearance_hole / 2 + kit.wall))
    parts = tuple(plate if p is ground else p for p in layout.parts)
    return replace(layout, parts=parts), mounts


def pins_of(build: LinkageBuild, layout: Layout) -> tuple[dict[str, Any], ...]:
    """Each pivot point (:attr:`LinkageBuild.pivots`) at the first pose of the motion: where it is (mm), the parts
    it passes through and the lowest and highest of their layers (one bolt passes them all)."""
    out = []
    for p in build.pivots:
        at = layout.sweep.joints[p.joints[0]][1][0]
        out.append({"joints": list(p.joints), "parts": list(p.parts), "x_mm": round(float(at[0]), 9),
                    "y_mm": round(float(at[1]), 9), "low_layer": p.low, "high_layer": p.high})
    return tuple(out)


def linkage_kit(spec: Any, layout: Layout, mounts: tuple[tuple[float, float], ...],
                build: LinkageBuild) -> LinkageKit:
    """The kit of a linkage ``spec`` (its ``[kit]`` table) from the ``layout`` whose ground :func:`base_plate` made
    the base plate with ``mounts``, and the ``build`` of that layout (:func:`linkgen.linkage_design.design_linkage`
    makes both, once). The parts, pins, spacers and mounting heads are placed over the motion's sweep, and two that
    share some height and meet in plan at any pose are refused (:class:`DesignError` naming ``parts.width``)."""
    kit, table = spec.kit, spec.parts
    pins = pins_of(build, layout)
    bolt = kit.hardware
    bom = [BomLine(p.name, 1, f"{'base plate' if not p.moving else 'link'}, {table.thickness:g} mm",
                   "laser or fdm") for p in build.parts]
    lengths: dict[float, int] = {}
    for pin in pins:
        grip = (pin["high_layer"] - pin["low_layer"] + 1) * table.thickness
        length = bolt_length(bolt, grip)
        if math.isinf(length):
            raise DesignError(f"kit.bolt: a pin through {grip:g} mm of parts is longer than the {bolt.name} bolts "
                              "of ISO 4762's table (100 mm)")
        pin["bolt_length_mm"] = length
        lengths[length] = lengths.get(length, 0) + 1
    bom += [bolt_line(bolt, length, count, "pins (one a pivot point)") for length, count in sorted(lengths.items())]
    inner, outer = build.spacer_diameters
    runs: dict[int, int] = {}
    for _, _, run, _ in build.spacers:
        runs[run] = runs.get(run, 0) + 1
    bom += [BomLine(f"spacer-{run}", count, f"tube {inner:g} x {outer:g} mm, {run * table.thickness:g} mm high",
                    "fdm") for run, count in sorted(runs.items())]
    bom.append(bolt_line(bolt, bolt_length(bolt, table.thickness), len(mounts),
                         "mounting the base plate (add your base's thickness to the length)"))
    report = {"bolt": kit.bolt, "pin_diameter_mm": bolt.diameter,
              "mounting_holes": [{"x_mm": round(x, 9), "y_mm": round(y, 9), "diameter_mm": bolt.clearance_hole,
                                  "cut_diameter_mm": build.allowances.cut_diameter(bolt.clearance_hole)}
                                 for x, y in mounts],
              "pins": list(pins), "bom": [line.row() for line in bom]}
    made = LinkageKit(build, mounts, pins, tuple(bom), report, bolt, layout.poses[0])
    sweep = layout.sweep
    check_clear(placed_solids(made, sweep), len(next(iter(sweep.angles.values()))), COLLISION_TOLERANCE_MM,
                frozenset(), "parts.width")
    report["stack"] = [{"name": s.name, "z_mm": round(s.z, 9), "top_mm": round(s.top, 9), "made": s.made,
                        "bought": s.bought} for s in placed_solids(made, made.pose)]
    return made


def placed_solids(kit: LinkageKit, placement: Any) -> tuple[Solid, ...]:
    """The kit placed at every pose of ``placement`` (a :class:`~linkgen.parts.Placement`): each printed part (one
    the placement does not move, a top plate, stays where it is drawn) standing at its layer times the plate
    thickness; each pin (``pin-<joint>``, the bolt's shank) from its lowest part's bottom to its highest part's top;
    a spacer (``spacer-<joint>-<layer>``) on each layer a pin crosses that no part it passes is on; the mounting
    bolts' heads (``mount-head-<k>``) on the base plate."""
    build, bolt = kit.build, kit.bolt
    table = build.table
    t = table.thickness
    n = len(next(iter(placement.angles.values())))
    out = []
    for part in build.printed:
        angles = placement.angles.get(part.name, np.zeros(n))
        origins = placement.origins.get(part.name, np.zeros((n, 2)))
        out.append(Solid(part, build.layers[part.name] * t, np.asarray(angles, dtype=float),
                         np.asarray(origins, dtype=float)))
    inner, outer = build.spacer_diameters
    for pin in kit.pins:
        joint = pin["joints"][0]
        where = np.asarray(placement.joints[joint][1], dtype=float)
        low, high = pin["low_layer"], pin["high_layer"]
        shank = disc(f"pin-{joint}", bolt.diameter, 0.0, (high - low + 1) * t, table.tolerance).part(0.0, 0.0)
        out.append(bought(shank, low * t, np.zeros(n), where))
        held = {build.layers[name] for name in pin["parts"]}
        for layer in sorted(set(range(low + 1, high)) - held):
            ring = disc(f"spacer-{joint}-{layer}", outer, inner, t, table.tolerance).part(0.0, 0.0)
            out.append(Solid(ring, layer * t, np.zeros(n), where))
    for k, at in enumerate(kit.mounts):
        head = disc(f"mount-head-{k + 1}", bolt.head_diameter, 0.0, bolt.head_height, table.tolerance)
        out.append(fixed(head.part(0.0, 0.0), t, at, made=False, bought=True))
    return tuple(out)
