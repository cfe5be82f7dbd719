"""A fit-test coupon: a plate with a row of holes at a range of clearances round one nominal pin, and the pin.

Cut it on the laser or print it, try the pin in each hole, and read off the clearance that gives the fit wanted
(a press fit, a sliding fit, a free turn): that clearance, added to the pin's diameter, is what a design's holes
should be drawn at on this machine (``parts.clearance``, ``output.clearance``). Hole k is drawn for a
clearance c_k = ``clearance_min`` + k ``clearance_step`` up to ``clearance_max``, with its label (c_k in mm, signed,
``+0.05``) engraved below it on the ``LABELS`` layer; the holes run from the smallest clearance on the left (-X)
to the largest on the right, and the plate's top-left corner is cut off (a printed plate has no labels: the cut
corner marks the smallest clearance's end, whichever face is up).

The process allowances are applied as for every part (:class:`~camgen.core.parts.Allowances`): the cut plate's
holes are drawn at d + c_k - kerf and the cut pin (a disc, stack several for a longer pin) at d + kerf, so that once
the laser has burnt kerf/2 either side of each path the hole is d + c_k and the pin d; the printed holes are
d + c_k + ``output.clearance``, the printed pin d (a cylinder ``pin_length`` long), each with the elephant-foot
chamfer ``output.elephant_foot``. Lengths in mm; the plate's lower-left corner is the origin.
"""
from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import Field, model_validator

from camgen.core.bundle import (
    Bundle, Item, figure_files, mesh_files, part_files, report_file, solid_files, write_bundle)
from camgen.core.parts import LAYER_LABELS, LAYER_OUTLINE, Allowances, Drawing, Part
from camgen.core.routing import add_routing
from camgen.core.shapes import Circle, Contour, Text, rounded_hull
from camgen.core.spec import CutOutputTable, Model, apply_overrides, length, name_field, parse_overrides, unit, validate

#: the most holes a coupon may have
MAX_HOLES = 50
#: the formats a coupon is written in: its cut sheet (dxf, cut-svg), the printed plate and pin (stl, 3mf), the report
#: (json), the sheet as a figure (png, svg) and the plate and pin as exact solids (step, with the step extra); a
#: page (html) does not apply: a coupon has no motion to show
COUPON_FORMATS = ("dxf", "cut-svg", "stl", "3mf", "json", "png", "svg", "step")
#: what a coupon writes unless ``output.formats`` says otherwise
COUPON_DEFAULT_FORMATS = ("dxf", "cut-svg", "stl", "3mf", "json")


def hole_count(low: float, high: float, step: float) -> int:
    """How many holes from clearance ``low`` to ``high`` by ``step`` (mm): the last at most ``high`` (to 1e-9 of a
    step)."""
    return math.floor((high - low) / step + 1e-9) + 1


class CouponTable(Model):
    """The ``[coupon]`` table: the nominal pin, the clearances to try, and the plate (mm)."""

    diameter: float = length("nominal pin diameter (3, 4, 5, 8 mm for common dowels and shafts)", 5.0, le=50.0)
    clearance_min: float = Field(-0.2, ge=-2.0, le=5.0, description="the first hole's clearance (hole less pin "
                                 "diameter; negative for an interference fit)", json_schema_extra=unit("mm"))
    clearance_max: float = Field(0.4, ge=-2.0, le=5.0, description="the last hole's clearance, at most",
                                 json_schema_extra=unit("mm"))
    clearance_step: float = length("clearance from one hole to the next", 0.05, le=5.0)
    thickness: float = length("plate thickness", 3.0, le=100.0)
    pin_length: float = length("the printed pin's length", 10.0, le=200.0)
    web: float = length("material between two holes, and round the edges", 3.0, le=50.0)
    label_height: float = length("height of the engraved labels", 2.5, le=20.0)

    @model_validator(mode="after")
    def _range(self) -> CouponTable:
        if self.clearance_max < self.clearance_min:
            raise ValueError(f"clearance_max: must be >= clearance_min {self.clearance_min:g} mm "
                             f"(got {self.clearance_max:g})")
        count = hole_count(self.clearance_min, self.clearance_max, self.clearance_step)
        if count > MAX_HOLES:
            raise ValueError(f"clearance_step: must be > {(self.clearance_max - self.clearance_min) / MAX_HOLES:g} mm, "
                             f"for at most {MAX_HOLES} holes from clearance_min to clearance_max (got "
                             f"{self.clearance_step:g}: {count} holes)")
        if self.diameter + self.clearance_min <= 0:
            raise ValueError(f"clearance_min: must be > -diameter = {-self.diameter:g} mm, or the first hole has no "
                             f"size (got {self.clearance_min:g})")
        return self


class CouponSpec(Model):
    """A coupon template: a ``name``, the ``[coupon]`` table and the ``[output]`` table (``kerf``, ``clearance``,
    ``elephant_foot``, ``tolerance``, ``formats``, ``dxf``, ``dxf_version``, ``text``, ``tool_radius``)."""

    name: str = name_field("coupon")
    coupon: CouponTable = CouponTable()
    output: CutOutputTable = CutOutputTable()

    @model_validator(mode="before")
    @classmethod
    def _default_formats(cls, data: Any) -> Any:
        """Without ``output.formats``, a coupon's own default formats (:data:`COUPON_DEFAULT_FORMATS`), not a
        design's (which name the page)."""
        if isinstance(data, Mapping) and isinstance(data.get("output", {}), Mapping) and \
                "formats" not in data.get("output", {}):
            return {**data, "output": {**data.get("output", {}), "formats": list(COUPON_DEFAULT_FORMATS)}}
        return data

    @model_validator(mode="after")
    def _open(self) -> CouponSpec:
        others = [f for f in self.output.formats if f not in COUPON_FORMATS]
        if others:
            raise ValueError(f"output.formats: a coupon is written as {', '.join(COUPON_FORMATS)} ({', '.join(others)} "
                             f"does not apply: a coupon has no motion to show) (got {list(self.output.formats)})")
        smallest = self.coupon.diameter + self.coupon.clearance_min
        if self.output.kerf >= smallest:
            raise ValueError(f"output.kerf: must be < {smallest:g} mm (coupon.diameter + coupon.clearance_min), or "
                             f"the smallest cut hole closes (got {self.output.kerf:g})")
        return self


def coupon_spec(raw: Mapping[str, Any] | None = None, overrides: Iterable[str] = ()) -> CouponSpec:
    """The validated coupon of a raw mapping (a template's tables; defaults for what it leaves out) with
    ``key=value`` ``overrides`` merged in (``coupon.diameter=8``), or a one-line :class:`SpecError`."""
    data = apply_overrides(dict(raw or {}), parse_overrides(overrides))
    data.setdefault("name", "coupon")
    return validate(CouponSpec, data)


def _decimals(values: np.ndarray) -> int:
    """The fewest decimals (2 to 6) that write every value exactly."""
    for digits in range(2, 6):
        if np.all(np.abs(np.round(values, digits) - values) < 1e-9):
            return digits
    return 6


@dataclass(frozen=True)
class Plate:
    """The coupon plate (a :class:`~camgen.core.parts.PartMaker`): a ``width`` by ``height`` rectangle from the
    origin with its top-left corner cut off at 45 degrees by ``corner_cut`` (mm; it marks the end of the smallest
    clearance on a printed plate, which has no labels, whichever face is up), round holes of ``diameters`` at
    ``centres`` (mm), and its ``labels``."""

    name: str
    width: float
    height: float
    centres: np.ndarray
    diameters: np.ndarray
    labels: tuple[Text, ...]
    thickness: float
    tolerance: float
    corner_cut: float

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        """The plate with its outline moved out by ``outline_grow`` (corners become arcs of that radius, exactly:
        :func:`~camgen.core.shapes.rounded_hull`) and its holes' radii grown by ``hole_grow`` (mm)."""
        cut = self.corner_cut
        corners = np.array([[0.0, 0.0], [self.width, 0.0], [self.width, self.height], [cut, self.height],
                            [0.0, self.height - cut]])
        outline = rounded_hull(corners, outline_grow) if outline_grow > 0 else Contour(corners)
        holes = tuple(Circle((float(x), float(y)), d / 2 + hole_grow)
                      for (x, y), d in zip(self.centres, self.diameters, strict=True))
        return Part(self.name, outline, holes, self.thickness, self.tolerance,
                    marks=tuple((LAYER_LABELS, t) for t in self.labels))


@dataclass(frozen=True)
class Pin:
    """The matching pin (a :class:`~camgen.core.parts.PartMaker`): a disc of ``diameter`` (mm) centred at
    ``centre``, ``length`` mm thick (printed: a cylinder standing on the bed)."""

    name: str
    centre: tuple[float, float]
    diameter: float
    length: float
    tolerance: float

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        """The disc with its radius grown by ``outline_grow`` (mm)."""
        r = self.diameter / 2 + outline_grow
        x, y = self.centre
        return Part(self.name, Contour(np.array([[x + r, y], [x - r, y]]), np.array([1.0, 1.0])), (), self.length,
                    self.tolerance)


@dataclass(frozen=True)
class CouponDesign:
    """A coupon ready to write: its spec, the ``clearances`` (mm) and ``labels`` of its holes in order, the plate
    and pin as cut and as printed, and the allowances that made them."""

    spec: CouponSpec
    clearances: np.ndarray
    labels: tuple[str, ...]
    plate: Plate
    pin: Pin
    allowances: Allowances
    cut: tuple[Part, Part]
    printed: tuple[Part, Part]


def design_coupon(spec: CouponSpec) -> CouponDesign:
    """The coupon ``spec`` describes: holes from the smallest clearance (left) to the largest, labels below them,
    the pin to the plate's right on the cut sheet. No I/O."""
    c, out = spec.coupon, spec.output
    n = hole_count(c.clearance_min, c.clearance_max, c.clearance_step)
    clearances = np.round(c.clearance_min + c.clearance_step * np.arange(n), 9)
    digits = _decimals(clearances)
    labels = tuple(f"{v:+.{digits}f}" for v in clearances)
    widest = c.diameter + max(clearances[-1], 0.0) + max(out.clearance, 0.0)
    label_width = max(Text(s, (0.0, 0.0), c.label_height).box_width for s in labels)
    pitch = max(widest + c.web, label_width + c.label_height)
    gap = c.label_height / 2
    width = 2 * c.web + max(widest, label_width) + (n - 1) * pitch
    height = c.web + c.label_height + gap + widest + c.web + c.label_height + gap
    y_hole = c.web + c.label_height + gap + widest / 2
    x = width / 2 + pitch * (np.arange(n) - (n - 1) / 2)
    texts = [Text(s, (float(xk) - Text(s, (0.0, 0.0), c.label_height).box_width / 2, c.web), c.label_height)
             for s, xk in zip(labels, x, strict=True)]
    title = f"pin {c.diameter:g} mm, kerf {out.kerf:g}, print {out.clearance:g}"
    texts.append(Text(title, (c.web, height - c.web / 2 - c.label_height), c.label_height))
    plate = Plate(spec.name, width, height, np.column_stack([x, np.full(n, y_hole)]), c.diameter + clearances,
                  tuple(texts), c.thickness, out.tolerance, c.web)
    pin = Pin(f"{spec.name}-pin", (width + c.web + c.diameter / 2 + out.kerf, height / 2), c.diameter,
              c.pin_length, out.tolerance)
    allowances = Allowances(out.kerf, out.clearance, "output.kerf", out.elephant_foot)
    cut = (allowances.cut(plate), allowances.cut(pin))
    printed = (allowances.printed(plate), allowances.printed(pin))
    return CouponDesign(spec, clearances, labels, plate, pin, allowances, cut, printed)


def coupon_drawing(design: CouponDesign) -> Drawing:
    """The cut sheet: the plate (outline, holes, labels) and the pin's disc beside it."""
    plate, pin = design.cut
    sheet = Drawing.of_part(plate)
    return Drawing((*sheet.items, (LAYER_OUTLINE, pin.outline)), plate.tolerance)


def coupon_report(design: CouponDesign) -> dict[str, Any]:
    """The report: each hole's label, clearance, nominal and drawn diameters (cut and printed) and centre, the pin's,
    and the allowances (mm)."""
    spec, allow = design.spec, design.allowances
    d = spec.coupon.diameter
    holes = [{"label": label, "clearance_mm": float(c), "nominal_mm": d,
              "cut_diameter_mm": round(allow.cut_diameter(d + float(c)), 9),
              "printed_diameter_mm": round(allow.printed_diameter(d + float(c)), 9),
              "x_mm": round(float(x), 6), "y_mm": round(float(y), 6)}
             for label, c, (x, y) in zip(design.labels, design.clearances, design.plate.centres, strict=True)]
    return {"name": spec.name, "kind": "coupon",
            "use": "try the pin in each hole; the clearance of the fit you want is what to add to a pin's diameter "
                   "for a hole on this machine (parts.clearance, output.clearance)",
            "nominal_mm": d, "thickness_mm": spec.coupon.thickness,
            "allowances": {"kerf_mm": allow.kerf, "clearance_mm": allow.clearance,
                           "elephant_foot_mm": allow.elephant_foot,
                           "cut_holes": "nominal + clearance - kerf", "printed_holes": "nominal + clearance + "
                           "output.clearance", "cut_pin": "nominal + kerf", "printed_pin": "nominal"},
            "plate_mm": [round(design.plate.width, 6), round(design.plate.height, 6)],
            "holes": holes,
            "pin": {"nominal_mm": d, "cut_diameter_mm": round(d + allow.kerf, 9), "printed_diameter_mm": d,
                    "length_mm": spec.coupon.pin_length},
            "warnings": []}


def coupon_bundle(design: CouponDesign) -> tuple[Bundle, dict[str, Any]]:
    """The coupon's files (those of :data:`COUPON_FORMATS` that ``output.formats`` asks for) and its report. The
    STEP file holds the printed plate and pin (``<name>`` and ``<name>-pin``) where the cut sheet has them: the pin
    beside the plate."""
    spec = design.spec
    out, name = spec.output, spec.name
    formats = list(out.formats)
    report = coupon_report(design)
    add_routing(report, design.cut, out.tool_radius)
    items: list[Item | None] = [part_files(coupon_drawing(design), name)]
    if {"stl", "3mf"} & set(formats):
        from camgen.core.solids import checked_mesh, volume_check

        checks = {}
        for key, part in zip(("plate", "pin"), design.printed, strict=True):
            mesh, check = checked_mesh(part)
            checks[key] = {"watertight": check.watertight, "volume_mm3": round(check.volume_mm3, 6),
                           "triangles": check.triangles, **volume_check([part], check.volume_mm3)}
            items.append(mesh_files(mesh, name if key == "plate" else f"{name}-pin", key))
        report["mesh"] = checks
    items.append(solid_files(tuple((part.name, (part,)) for part in design.printed), name))

    def figure() -> Any:
        from camgen.core.figures import drawing_figure

        return drawing_figure(coupon_drawing(design), f"{name}: the cut sheet, holes from the smallest clearance")

    items += [figure_files(figure, name), report_file(report, name)]
    return Bundle.of(items, out.write_options, formats), report


def write_coupon(design: CouponDesign, directory: str | Path) -> dict[str, Any]:
    """Write the coupon's files into ``directory``, all or nothing; return the report with its ``files``."""
    bundle, report = coupon_bundle(design)
    return {**report, "files": write_bundle(bundle, directory)}


def coupon(directory: str | Path, raw: Mapping[str, Any] | None = None, overrides: Iterable[str] = ()
           ) -> dict[str, Any]:
    """Design and write a coupon in one call (``coupon("out/coupon", {"coupon": {"diameter": 8}})``); the report
    with its ``files``."""
    return write_coupon(design_coupon(coupon_spec(raw, overrides)), directory)
