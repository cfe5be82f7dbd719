"""The frame's files, its report section and the machine's bill of materials (:mod:`camgen.kinds.machine.frame`).

Each plate as the laser cuts it (``<machine>-frame.dxf`` and ``-cut.svg``, ``<machine>-frame-top...`` for the top
plate: its outline on ``OUTLINE``, its holes on ``HOLES``) and as printed (``.stl``, ``.3mf``); each spacer printed
(``<machine>-spacer-<i>.stl|3mf``); the bill of materials (``<machine>-kit.csv`` with the report): the plates,
the spacers, the shafts (ground rod, ISO 286 h6), the bearings (ISO 15) and the pivot pins (a bolt of the pin's
diameter, ISO 4762 with its ISO 7089 washer and ISO 4032 nut, or a plain pin). No I/O.
"""
from __future__ import annotations

import math
from typing import Any

from camgen.core.bundle import Item, mesh_files, part_files
from camgen.core.hardware import BOLTS, bolt_length
from camgen.core.kit import BomLine, bolt_line, bom_item
from camgen.core.parts import Drawing
from camgen.kinds.machine.frame import Frame

#: a shaft stands this far below the bottom plate, to take a coupling, a pulley or a crank (mm)
SHAFT_STUB_MM = 10.0


def shaft_length(frame: Frame, design: Any, shaft: str) -> float:
    """How long (mm) shaft ``shaft`` is: from :data:`SHAFT_STUB_MM` under the bottom plate (from the bottom face of
    the part it carries behind the plate, with a linkage there) to the top of its highest cam (the bottom plate's
    top for a shaft carrying none), as the assembly draws it."""
    body = next((b for b in design.bodies if b.name == f"shafts.{shaft}"), None)
    top = frame.stack.top[body.high] if body is not None else frame.stack.thickness
    if body is not None and body.low < 0:
        return top - frame.stack.bottom[body.low]
    return SHAFT_STUB_MM + top


def pin_span(frame: Frame, design: Any, pin: str) -> tuple[float, float]:
    """A pin's bottom and top (mm): from the bottom plate's bottom face (standing on it) or the bottom of the
    lowest part it carries, up to the top of the highest (standing alone) or the top plate's top (hanging from it,
    or standing in a spacer up to it)."""
    body = next(b for b in design.bodies if b.name == pin)
    s = frame.stack
    held = next(seat for seat in frame.seats if seat.name == pin).top
    bottom = 0.0 if body.low == 0 else s.bottom[body.low]
    top = s.bottom[s.roof] + s.thickness if held else s.top[body.high]
    return bottom, top


def bom(frame: Frame, design: Any) -> tuple[BomLine, ...]:
    """The bill of materials of the frame and what it carries: plates, spacers, shafts, bearings, pins, the cams and
    the linkages' parts the machine writes (:func:`camgen.kinds.machine.coupled_kit.bom_lines`), and the
    followers' arms, rollers and axles (:func:`camgen.kinds.machine.follower_parts.bom_lines`)."""
    lines = [BomLine(p.name, 1, f"{'top' if p is frame.top else 'bottom'} frame plate, {p.thickness:g} mm, "
                     f"{len(p.holes)} holes (its own files)", "laser or fdm") for p in frame.plates]
    for part, (bottom, top) in zip(frame.spacer_parts(), frame.spacer_heights(), strict=True):
        d, bore = 2 * part.outline.arcs()[2][0], part.holes[0][1]
        lines.append(BomLine(part.name, 1, f"spacer {d:g} mm across, {bore:g} mm bore, {top - bottom:.4g} mm "
                             "high (its own files)", "fdm"))
    from camgen.kinds.machine.stem_kit import guide_screws

    screws = guide_screws(design)
    for seat in frame.seats:
        if seat.name.startswith("shafts."):
            length = shaft_length(frame, design, seat.name.removeprefix("shafts."))
            lines.append(BomLine(seat.name.replace("shafts.", "shaft "), 1, f"{seat.diameter:g} mm ground rod "
                                 f"(h6), {math.ceil(length):g} mm long", "buy", "ISO 286 h6"))
            if seat.bearing is not None:
                b = seat.bearing
                lines.append(BomLine(f"bearing {b.name}", 1, f"{b.bore:g} x {b.outside:g} x {b.width:g} mm, in the "
                                     f"frame's seat of {seat.name}", "buy", "ISO 15 (deep groove ball bearing)"))
            continue
        bottom, top = pin_span(frame, design, seat.name)
        bolt = next((b for b in BOLTS.values() if b.diameter == seat.diameter), None)
        held = screws.get(seat.name)
        what = f"guide screw {seat.name} of {held}" if held else f"pivot pin {seat.name}"
        where = f"{what} at ({seat.centre[0]:.4g}, {seat.centre[1]:.4g}) mm"
        if bolt is not None:
            lines.append(bolt_line(bolt, bolt_length(bolt, top - bottom), 1, where))
        else:
            lines.append(BomLine(f"pin {seat.diameter:g} mm", 1, f"{where}, {math.ceil(top - bottom + 2):g} mm "
                                 "long", "buy", "ISO 2338 (parallel pin)"))
    from camgen.kinds.machine import coupled_kit, follower_parts, machine_gears

    return (*lines, *coupled_kit.bom_lines(design), *follower_parts.bom_lines(design, frame.stack),
            *machine_gears.bom_lines(design))


#: main shaft angles over the turn at which the moving parts' sweep is taken (every 5 degrees)
SWEEP_SAMPLES = 72


def swept_outside(frame: Frame, design: Any) -> float:
    """The plan area (mm^2) the moving parts sweep over the turn (placed at :data:`SWEEP_SAMPLES` angles) outside
    the plate's outline: 0 when the plate covers every moving part at every angle."""
    import numpy as np
    import shapely

    from camgen.kinds.machine.clash import outlines

    phi = np.arange(SWEEP_SAMPLES) * (2 * math.pi / SWEEP_SAMPLES)
    moving = [b for b in design.bodies if not b.name.startswith(("pins.", "shafts.", "spacers."))]
    if not moving:
        return 0.0
    swept = shapely.union_all(np.concatenate([outlines(b, phi) for b in moving]))
    plate = shapely.Polygon(frame.plate.outline.flatten(frame.plate.tolerance))
    return float(swept.difference(plate).area)


def frame_report(frame: Frame, design: Any) -> dict[str, Any]:
    """The report's ``frame`` section: the plates, every seat (where, what it carries, its hole nominal, as cut and
    as printed, and which plates hold it), the spacers, the planes' heights, the area the moving parts sweep
    outside the plate (:func:`swept_outside`) and the bill of materials."""
    allow = frame.allowances
    seats = [{"name": s.name, "x_mm": round(s.centre[0], 9), "y_mm": round(s.centre[1], 9),
              "carries_mm": s.diameter, "nominal_mm": round(s.hole, 9),
              "cut_mm": round(allow.cut_diameter(s.hole), 9), "printed_mm": round(allow.printed_diameter(s.hole), 9),
              "bearing": s.bearing.name if s.bearing else "none",
              "plates": [p for p, held in (("frame", s.bottom), ("frame-top", s.top)) if held]}
             for s in frame.seats]
    spacers = [{"name": p.name, "pin": sp.pin, "x_mm": round(sp.centre[0], 9), "y_mm": round(sp.centre[1], 9),
                "z_mm": round(bottom, 9), "height_mm": round(top - bottom, 9), "outside_mm": sp.outside,
                "bore_mm": round(sp.bore, 9)}
               for p, sp, (bottom, top) in zip(frame.spacer_parts(), frame.spacers, frame.spacer_heights(),
                                               strict=True)]
    s = frame.stack
    return {"plates": [p.name for p in frame.plates], "thickness_mm": s.thickness, "margin_mm": frame.margin,
            "allowances": {"kerf_mm": allow.kerf, "clearance_mm": allow.clearance},
            "seats": seats, "spacers": spacers,
            "planes": [{"plane": p, "bottom_mm": round(s.bottom[p], 9), "top_mm": round(s.top[p], 9)}
                       for p in s.bottom],
            "top_plate_mm": round(s.bottom[s.roof], 9) if frame.top is not None else None,
            "swept_outside_mm2": round(swept_outside(frame, design), 3),
            "bom": [line.row() for line in bom(frame, design)]}


def frame_items(frame: Frame, design: Any, formats: tuple[str, ...]) -> list[Item | None]:
    """The frame's files of ``formats``: each plate cut and printed, each spacer printed, the bill of materials."""
    from camgen.core.solids import checked_mesh

    name = design.spec.name
    meshes = bool({"stl", "3mf"} & set(formats))
    items: list[Item | None] = []
    for plate in frame.plates:
        items.append(part_files(Drawing.of_part(frame.cut(plate)), f"{name}-{plate.name}", plate.name))
        items.append(mesh_files(checked_mesh(frame.printed(plate), f"{name}-{plate.name}")[0] if meshes else None,
                                f"{name}-{plate.name}", plate.name))
    for part in frame.spacer_parts():
        made = frame.allowances.printed(part)
        items.append(mesh_files(checked_mesh(made, f"{name}-{part.name}")[0] if meshes else None,
                                f"{name}-{part.name}", part.name.replace("-", "_")))
    items.append(bom_item(name, bom(frame, design)))
    return [i.only(formats) if i is not None else None for i in items]
