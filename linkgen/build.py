"""``linkgen build``: a linkage's parts, their layers, a cut sheet and the assembly at the dead centres. No I/O."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import DesignError, SpecError
from camgen.core.parts import LAYER_HOLES, LAYER_OUTLINE, Drawing, Part
from camgen.core.shapes import Contour, Polyline
from linkgen.analyze import build_linkage
from linkgen.bars import (LinkPart, Placement, PartsSpec, check_spec, fourbar_parts, fourbar_placement,
                          layer_order, slidercrank_parts, slidercrank_placement)
from linkgen.fourbar import FourBar
from linkgen.slidercrank import SliderCrank

#: poses over the motion at which collisions are checked
SWEEP = 181


@dataclass(frozen=True)
class LinkageBuild:
    parts: tuple[LinkPart, ...]
    spec: PartsSpec
    layers: dict[str, int]
    cut: tuple[Part, ...]
    printed: tuple[Part, ...]
    sheet: Drawing
    assembly: Drawing
    positions: tuple[tuple[str, float], ...]      # (dead-centre kind, input angle rad) drawn in the assembly


def parts_spec(table: Any) -> PartsSpec:
    widths = tuple((k, getattr(table, k).width) for k in ("ground", "crank", "coupler", "rocker", "rod", "slider")
                   if getattr(table, k) is not None)
    spec = PartsSpec(table.width, table.thickness, table.pin_diameter, table.clearance, table.kerf, widths)
    check_spec(spec)
    return spec


def _mechanism(template: Any, spec: PartsSpec) -> tuple[Any, tuple[LinkPart, ...], Placement, list, str]:
    """The linkage, its parts, their placement over the motion, the dead centres to draw, the assembly."""
    mech = build_linkage(template.linkage)
    if hasattr(mech, "straightness"):
        mech = mech.linkage
    if isinstance(mech, FourBar):
        assembly = getattr(template.linkage, "assembly", "open")
        ranges = mech.input_ranges()
        lo, hi = (0.0, 2 * math.pi) if ranges is None else ranges[0]
        sweep = fourbar_placement(mech, np.linspace(lo, hi, SWEEP), assembly)
        dead = [(d.kind, d.crank) for d in mech.dead_centres(assembly)
                if ranges is None or lo <= d.crank <= hi or lo <= d.crank + 2 * math.pi <= hi]
        return mech, fourbar_parts(mech, spec), sweep, dead, assembly
    if isinstance(mech, SliderCrank):
        dead = [(k, t) for k, t, _ in mech.dead_centres()]
        return mech, slidercrank_parts(mech, spec), slidercrank_placement(mech, np.linspace(0, 2 * math.pi, SWEEP)), \
            dead, "open"
    raise SpecError(f"parts are made for four-bars, straight-line linkages and slider-cranks, "
                    f"not {template.linkage.type}", "linkage.type")


def _placement_at(mech: Any, angle: float, assembly: str) -> Placement:
    if isinstance(mech, FourBar):
        return fourbar_placement(mech, np.array([angle]), assembly)
    return slidercrank_placement(mech, np.array([angle]))


def _place(part: Part, angle: float, shift: np.ndarray) -> tuple[Contour, list]:
    """The part's outline and holes turned by ``angle`` (rad) and moved by ``shift`` (mm)."""
    return part.outline.moved(angle, shift), [hole.moved(angle, shift) for hole in part.holes]


def _sheet(cut: tuple[Part, ...], size: tuple[float, float], gap: float, tolerance: float) -> Drawing:
    """Shelf packing, left to right in rows, each part shifted so its box starts at the cursor."""
    width, height = size
    x = y = row = 0.0
    items: list = []
    for part in sorted(cut, key=lambda p: p.outline.bounds()[1] - p.outline.bounds()[3]):
        x0, y0, x1, y1 = part.outline.bounds()
        lo, span = np.array([x0, y0]), np.array([x1 - x0, y1 - y0])
        if x > 0 and x + span[0] > width:
            x, y, row = 0.0, y + row + gap, 0.0
        if x + span[0] > width or y + span[1] > height:
            raise DesignError(f"parts.sheet: the parts do not fit a {width:g} x {height:g} mm sheet with gaps of "
                              f"{gap:g} mm; give a larger sheet")
        outline, holes = _place(part, 0.0, np.array([x, y]) - lo)
        items += [(LAYER_OUTLINE, outline), *((LAYER_HOLES, h) for h in holes)]
        x, row = x + span[0] + gap, max(row, span[1])
    return Drawing(tuple(items), tolerance)


def build_parts(template: Any) -> LinkageBuild:
    """Parts, layers, cut sheet and assembly drawing for a template with a ``[parts]`` table."""
    if template.parts is None:
        raise SpecError("missing: give a [parts] table (width, thickness, pin_diameter, ...)", "parts")
    table = template.parts
    spec = parts_spec(table)
    mech, parts, sweep, dead, assembly = _mechanism(template, spec)
    layers = layer_order(parts, sweep, (spec.pin_diameter) / 2)
    cut = tuple(p.part(spec, True, table.tolerance) for p in parts)
    printed = tuple(p.part(spec, False, table.tolerance) for p in parts)
    sheet = _sheet(cut, table.sheet, spec.kerf + table.margin, table.tolerance)
    items: list = []
    for i, (kind, angle) in enumerate(dead):
        place = _placement_at(mech, angle, assembly)
        layer = f"DC{i + 1}-{kind}"
        for part in printed:
            outline, holes = _place(part, float(place.angles[part.name][0]), place.origins[part.name][0])
            items += [(layer, outline), *((layer, h) for h in holes)]
    points = _path(mech, sweep, assembly)
    items.append(("PATH", Polyline(points, np.zeros(len(points) - 1))))
    return LinkageBuild(parts, spec, layers, cut, printed, sheet, Drawing(tuple(items), table.tolerance), tuple(dead))


def _path(mech: Any, sweep: Placement, assembly: str) -> np.ndarray:
    """The coupler point's path (the coupler-rocker pin's without one), or the slider's."""
    if isinstance(mech, FourBar):
        theta = sweep.angles["crank"]
        return mech.sweep(theta, assembly).point if mech.point_distance > 0 else sweep.joints["B"][1]
    return sweep.origins["slider"]
