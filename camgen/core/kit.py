"""Kits: the parts and the hardware that mount a mechanism, shared by cams and linkages. No I/O.

A kit is a stack of flat solids (:class:`Solid`): a part as made (its process allowance applied) standing on its
bottom face at a height z (mm, up from the frame's or base plate's bottom face), placed at each pose of the motion by
a turn (rad, counter-clockwise seen from +Z) about its own origin and a shift (mm). Two solids whose heights overlap
must never overlap in plan (:func:`interferences`). The bill of materials lists what is made and what is bought
(:class:`BomLine`, sizes from :mod:`camgen.core.hardware`). The ``[kit]`` tables (:class:`KitTable`,
:class:`CamKitTable`) choose the hardware and the process.
"""
from __future__ import annotations

import itertools
from collections.abc import Iterable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field, field_validator, model_validator

from camgen.core.errors import DesignError
from camgen.core.hardware import BEARINGS, BOLTS, SHAFTS, Bearing, BearingName, Bolt, BoltName
from camgen.core.parts import Allowances, Drawing, Part, PartMaker, preview_stroke
from camgen.core.shapes import Circle, Contour, rounded_hull
from camgen.core.spec import Model, length, unit

if TYPE_CHECKING:
    from camgen.core.bundle import Item

#: the bearings a ``[kit]`` may name, and ``"none"`` for a plain hole the shaft runs in
BearingChoice = Literal[BearingName, "none"]
#: a kit's moving parts clear the fixed ones by at least this much in plan (mm)
RUNNING_GAP = 1.0


class KitTable(Model):
    """A ``[kit]`` table: the hardware a mechanism is mounted with (linkages: bolts as pins and mounting bolts)."""

    bolt: BoltName = Field("M4", description="bolt size: pins, guides and mounting holes")
    wall: float = length("material left round every hole of a kit part", 4.0, le=100.0)

    @property
    def hardware(self) -> Bolt:
        """The bolt the table names."""
        return BOLTS[self.bolt]


class CamKitTable(KitTable):
    """A cam's ``[kit]`` table: the camshaft, its bearing, the bolts, the process the frame and follower are made
    by and its allowance, their thickness."""

    shaft: float = Field(8.0, description="camshaft diameter", json_schema_extra=unit("mm"))
    bearing: BearingChoice = Field("none", description="bearing seated in the frame, or a plain hole")
    process: Literal["laser", "fdm"] = Field("laser", description="how the frame, follower and roller are made")
    thickness: float = length("frame and follower plate thickness", 5.0, le=100.0)
    kerf: float = Field(0.15, ge=0, le=5, description="laser kerf (process laser)", json_schema_extra=unit("mm"))
    clearance: float = Field(0.3, ge=0, le=5, description="printing clearance on holes (process fdm)",
                             json_schema_extra=unit("mm"))

    @field_validator("bearing", mode="before")
    @classmethod
    def _bearing_name(cls, value: Any) -> Any:
        return str(value) if isinstance(value, int) and not isinstance(value, bool) else value

    @field_validator("shaft")
    @classmethod
    def _standard_shaft(cls, value: float) -> float:
        if value not in SHAFTS:
            raise ValueError(f"must be one of {', '.join(f'{s:g}' for s in SHAFTS)} mm (got {value:g})")
        return value

    @model_validator(mode="after")
    def _bearing_fits_shaft(self) -> CamKitTable:
        if self.bearing != "none" and BEARINGS[self.bearing].bore != self.shaft:
            fits = [b.name for b in BEARINGS.values() if b.bore == self.shaft] + ["none"]
            raise ValueError(f"bearing: a {self.bearing} has a {BEARINGS[self.bearing].bore:g} mm bore, not the "
                             f"kit.shaft of {self.shaft:g} mm; for that shaft: {', '.join(fits)}")
        return self

    @property
    def seat(self) -> Bearing | None:
        """The bearing seated in the frame (None: a plain hole)."""
        return None if self.bearing == "none" else BEARINGS[self.bearing]

    @property
    def allowances(self) -> Allowances:
        """The process's allowances: a laser's kerf, or a printer's clearance."""
        laser = self.process == "laser"
        return Allowances(self.kerf if laser else 0.0, 0.0 if laser else self.clearance, "kit.kerf")

    def made(self, maker: PartMaker) -> Part:
        """The part as the process makes it (cut, or printed)."""
        return self.allowances.cut(maker) if self.process == "laser" else self.allowances.printed(maker)


#: the followers a cam's kit mounts
KIT_FOLLOWERS = ("translating-roller", "oscillating-roller")


def check_cam_kit(kit: CamKitTable, follower: str, bore: float) -> None:
    """A ValueError naming the field when a disc cam's ``[kit]`` cannot mount it: a kit is for a roller follower
    (only a disc cam's spec takes a kit), and the shaft must pass through the cam's bore."""
    if follower not in KIT_FOLLOWERS:
        raise ValueError(f"kit: a kit mounts a disc cam with a {' or '.join(KIT_FOLLOWERS)} follower (got a "
                         f"{follower} follower)")
    if kit.shaft > bore:
        fits = [f"{s:g}" for s in SHAFTS if s <= bore]
        raise ValueError(f"kit.shaft: a {kit.shaft:g} mm shaft does not pass through the cam's bore of {bore:.15g} mm "
                         f"(cam.bore); allowed: {', '.join(fits) + ' mm' if fits else 'none (enlarge cam.bore)'}")


@dataclass(frozen=True)
class Plate:
    """A kit part (a :class:`~camgen.core.parts.PartMaker`): an outline, round holes ((x, y), nominal diameter)
    and slots ((two end centres), width), all mm in its own frame, and a thickness."""

    name: str
    outline: Contour
    holes: tuple[tuple[tuple[float, float], float], ...]
    thickness: float
    tolerance: float
    slots: tuple[tuple[tuple[tuple[float, float], tuple[float, float]], float], ...] = ()

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        """The part with its outline moved out by ``outline_grow`` and its holes' edges by ``hole_grow`` (mm)."""
        outline = self.outline if outline_grow == 0 else _grown(self.outline, outline_grow)
        holes: list = [Circle(c, d / 2 + hole_grow) for c, d in self.holes]
        holes += [rounded_hull(np.array(ends), w / 2 + hole_grow) for ends, w in self.slots]
        return Part(self.name, outline, tuple(holes), self.thickness, self.tolerance)


def _grown(outline: Contour, grow: float) -> Contour:
    """A rounded hull or a circle moved outwards by ``grow`` mm: its arcs' centres kept, their radii grown."""
    _, centres, radii, _ = outline.arcs()
    return rounded_hull(np.asarray(centres), float(radii[0]) + grow)


def disc(name: str, diameter: float, hole: float, thickness: float, tolerance: float) -> Plate:
    """A round part (a roller, a spacer, a standoff) of ``diameter`` with a central hole (mm; 0 for none)."""
    return Plate(name, rounded_hull(np.zeros((1, 2)), diameter / 2), ((((0.0, 0.0)), hole),) if hole else (),
                 thickness, tolerance)


@dataclass(frozen=True)
class Solid:
    """A part standing at height ``z`` (mm) and placed at each pose: ``angles`` (n,) rad counter-clockwise about its
    own origin, then ``origins`` (n, 2) mm (one pose for a fixed part). ``made`` says whether the kit writes its
    files; ``bought`` that it is hardware (a bolt, a nut, the shaft, a bearing: drawn, checked and listed in the bill
    of materials, never in a file to print). A cam in its own kit is neither: its own build writes its files."""

    part: Part
    z: float
    angles: np.ndarray
    origins: np.ndarray
    made: bool = True
    bought: bool = False

    @property
    def name(self) -> str:
        return self.part.name

    @property
    def top(self) -> float:
        """Its top (mm): its top face, or its hub boss's."""
        return self.z + self.part.thickness + (self.part.boss[1] if self.part.boss else 0.0)

    def pose(self, k: int) -> tuple[float, np.ndarray]:
        """(angle rad, shift mm) at pose ``k`` (a fixed part has one)."""
        k = k if len(self.angles) > 1 else 0
        return float(self.angles[k]), np.asarray(self.origins[k], dtype=float)


def fixed(part: Part, z: float, at: tuple[float, float] = (0.0, 0.0), made: bool = True,
          bought: bool = False) -> Solid:
    """A part that does not move, its origin at ``at`` (mm), standing at ``z``."""
    return Solid(part, z, np.zeros(1), np.array([at], dtype=float), made, bought)


def bought(part: Part, z: float, angles: np.ndarray, origins: np.ndarray) -> Solid:
    """A piece of hardware placed at each pose (see :class:`Solid`): neither made nor printed."""
    return Solid(part, z, angles, origins, made=False, bought=True)


def footprint(part: Part, angle: float, shift: np.ndarray, tolerance: float) -> Any:
    """The part's plan (outline less holes) as a shapely polygon, turned by ``angle`` and moved by ``shift``."""
    import shapely

    outer = shapely.Polygon(part.outline.moved(angle, shift).flatten(tolerance))
    holes = [shapely.Polygon(h.moved(angle, shift).flatten(tolerance)) for h in part.holes]
    return outer.difference(shapely.union_all(holes)) if holes else outer


def interferences(solids: tuple[Solid, ...], poses: int, tolerance: float,
                  allowed: frozenset[frozenset[str]] = frozenset()) -> list[dict[str, Any]]:
    """Every pair of solids sharing some height (more than 1e-9 mm) whose plans overlap at some pose, less the
    pairs ``allowed`` (a roller on its cam): (names, largest overlap mm^2, the pose it is at). Outlines as chords
    within ``tolerance`` mm; overlaps below tolerance x the shorter perimeter are the chords', not the parts'."""
    import shapely

    pairs = [(a, b) for a, b in itertools.combinations(solids, 2)
             if frozenset((a.name, b.name)) not in allowed and min(a.top, b.top) - max(a.z, b.z) > 1e-9]
    # the plans of the solids some pair checks only, each at every pose once
    plans = {s.name: _plans(s, poses if len(s.angles) > 1 else 1, tolerance)
             for s in solids if any(s is a or s is b for a, b in pairs)}
    out = []
    for a, b in pairs:
        area = shapely.area(shapely.intersection(plans[a.name], plans[b.name]))
        limit = tolerance * min(shapely.length(plans[a.name]).min(), shapely.length(plans[b.name]).min())
        if area.max() > limit:
            out.append({"parts": [a.name, b.name], "overlap_mm2": float(area.max()), "pose": int(area.argmax())})
    return out


def _plans(solid: Solid, poses: int, tolerance: float) -> np.ndarray:
    """The solid's plan (outline less holes, as :func:`footprint` makes it) at each of its first ``poses`` poses,
    shapely polygons: each contour made chords within ``tolerance`` mm once, then turned and moved to every pose at
    once (its chords' ends turned with it: within 1e-12 mm of those made from the turned arcs); a round hole's
    chords from its moved centre as :meth:`Circle.flatten` makes them (the same numbers)."""
    import shapely

    places = [solid.pose(k) for k in range(poses)]
    angles = np.array([a for a, _ in places])
    shifts = np.array([shift for _, shift in places], dtype=float).reshape(poses, 2)
    c, s = np.cos(angles)[:, None], np.sin(angles)[:, None]

    def turned(shape: Any) -> np.ndarray:
        if isinstance(shape, Circle):
            ring = Circle((0.0, 0.0), shape.radius).flatten(tolerance)
            centres = np.array([shape.moved(a, shift).centre for a, shift in places], dtype=float)
            return shapely.polygons(np.stack([centres[:, :1] + ring[:, 0], centres[:, 1:] + ring[:, 1]], axis=-1))
        ring = shape.flatten(tolerance)
        x, y = ring[:, 0][None, :], ring[:, 1][None, :]
        return shapely.polygons(np.stack([x * c - y * s + shifts[:, :1], x * s + y * c + shifts[:, 1:]], axis=-1))

    outer = turned(solid.part.outline)
    if not solid.part.holes:
        return outer
    holes = np.stack([turned(h) for h in solid.part.holes], axis=1)
    return shapely.difference(outer, shapely.union_all(holes, axis=1))


def check_clear(solids: tuple[Solid, ...], poses: int, tolerance: float, allowed: frozenset[frozenset[str]],
                field: str) -> None:
    """A :class:`DesignError` naming ``field`` when two solids meet (see :func:`interferences`)."""
    hits = interferences(solids, poses, tolerance, allowed)
    if hits:
        first = hits[0]
        raise DesignError(f"{field}: the kit's {first['parts'][0]} and {first['parts'][1]} meet "
                          f"({first['overlap_mm2']:.3g} mm^2 overlap at pose {first['pose']}); change that size or "
                          "the design's distances")


def _placed(solids: tuple[Solid, ...], k: int, prefix: str, at: np.ndarray) -> list:
    """The solids at pose ``k`` in plan moved by ``at`` (mm), lowest first, each on its layer ``<prefix><name>``."""
    items: list = []
    for solid in sorted(solids, key=lambda s: s.z):
        angle, shift = solid.pose(k)
        layer, shift = f"{prefix}{solid.name}", shift + at
        items += [(layer, solid.part.outline.moved(angle, shift)), *((layer, h.moved(angle, shift))
                                                                    for h in solid.part.holes)]
    return items


def assembly_drawing(solids: tuple[Solid, ...], k: int, tolerance: float) -> Drawing:
    """The solids at pose ``k`` in plan, lowest first, each on its own layer ``KIT-<name>``."""
    items = _placed(solids, k, "KIT-", np.zeros(2))
    return Drawing(tuple(items), tolerance, stroke=preview_stroke(items))


#: the gap between two panels of :func:`assembly_panels`, and the labels' height, as fractions of a panel's width
PANEL_GAP, LABEL_HEIGHT = 0.15, 0.05


def assembly_panels(solids: tuple[Solid, ...], poses: tuple[tuple[int, str], ...], tolerance: float) -> Drawing:
    """The solids in plan at each of ``poses`` ((pose index, label) pairs), one panel a pose from left to right:
    panel ``i``'s origin (the shaft, or the base plate's origin) at x = ``i`` x (the widest panel's width x (1 +
    :data:`PANEL_GAP`)), y = 0; each solid on layer ``KIT-<label>-<name>``, and the label under its panel on
    ``KIT-LABELS``."""
    from camgen.core.shapes import Text

    panels = [_placed(solids, k, "", np.zeros(2)) for k, _ in poses]
    boxes = [np.array([shape.bounds() for _, shape in panel if isinstance(shape, Contour)]) for panel in panels]
    lo = np.array([min(b[:, 0].min() for b in boxes), min(b[:, 1].min() for b in boxes)])
    width = max(float(b[:, 2].max() - b[:, 0].min()) for b in boxes)
    step, height = width * (1 + PANEL_GAP), width * LABEL_HEIGHT
    items: list = []
    for i, (k, label) in enumerate(poses):
        items += _placed(solids, k, f"KIT-{label}-", np.array([i * step, 0.0]))
        items.append(("KIT-LABELS", Text(f"{label} deg", (i * step + lo[0], lo[1] - 2 * height), height)))
    return Drawing(tuple(items), tolerance, stroke=preview_stroke(items))


def placed_meshes(solids: tuple[Solid, ...], k: int) -> tuple[Any, ...]:
    """Each solid the user makes (cut, printed, or a cam with its own files) as a mesh in its assembled place at pose
    ``k``, named after it: the kit's 3MF. The bought ones are left out: a slicer puts every object of a 3MF on its
    plate to be printed (PrusaSlicer refuses a whole file whose build holds an object of 3MF's non-printing type
    "other"), so hardware there would be printed or deleted by hand; the bill of materials lists it and the assembly
    drawing shows it in place."""
    from camgen.core.solids import extrude

    out = []
    for solid in (s for s in solids if not s.bought):
        mesh = extrude(solid.part)
        angle, shift = solid.pose(k)
        c, s = np.cos(angle), np.sin(angle)
        xy = mesh.vertices[:, :2] @ np.array([[c, s], [-s, c]]) + shift
        out.append(replace(mesh, vertices=np.column_stack([xy, mesh.vertices[:, 2] + solid.z])))
    return tuple(out)


@dataclass(frozen=True)
class BomLine:
    """A line of the bill of materials: what, how many, its size in words, how it is got (``laser``, ``fdm``
    or ``buy``) and the standards a bought item is ordered by ("" for a made part)."""

    item: str
    quantity: int
    size: str
    source: str
    standard: str = ""

    def row(self) -> dict[str, Any]:
        """The report's line."""
        return {"item": self.item, "quantity": self.quantity, "standard": self.standard, "size": self.size,
                "source": self.source}

    def csv_row(self) -> dict[str, Any]:
        """The line of ``<name>-kit.csv``: the report's, its columns named part, quantity, standard, size, process."""
        return {"part": self.item, "quantity": self.quantity, "standard": self.standard, "size": self.size,
                "process": self.source}


#: the standards a bolt line is ordered by: the screw, its washer, its nut
BOLT_STANDARDS = "ISO 4762; ISO 7089; ISO 4032"


def bolt_line(bolt: Bolt, length: float, quantity: int, use: str) -> BomLine:
    """Bolts of ``length`` (mm) with a washer and a nut each, for ``use``."""
    return BomLine(f"{bolt.name} x {length:g} socket head cap screw, ISO 7089 washer, ISO 4032 nut", quantity,
                   use, "buy", BOLT_STANDARDS)


def part_entry(solid: Solid, allowances: Allowances, catalogue: dict[str, float]) -> dict[str, Any]:
    """A made part's report entry: its name, height in the stack, thickness, and each hole's centre and diameter
    as drawn in its file (``catalogue``: the nominal size each hole comes from, by hole index, for the reader)."""
    holes = []
    for i, hole in enumerate(solid.part.holes):
        if isinstance(hole, Circle):
            holes.append({"x_mm": round(hole.centre[0], 9), "y_mm": round(hole.centre[1], 9),
                          "diameter_mm": round(2 * hole.radius, 9),
                          **({"nominal_mm": catalogue[str(i)]} if str(i) in catalogue else {})})
    return {"name": solid.name, "z_mm": round(solid.z, 9), "thickness_mm": solid.part.thickness, "holes": holes,
            "allowances": {"kerf_mm": allowances.kerf, "clearance_mm": allowances.clearance}}


def kit_items(name: str, made: tuple[tuple[Part, str], ...], drawing: Drawing, meshes: Any, formats: Any,
              title: str, bom: tuple[BomLine, ...] = (), placed: Any = None) -> list[Item | None]:
    """The kit's files: each part as its process makes it (a laser's as ``<name>-<part>.dxf`` and
    ``<name>-<part>-cut.svg``, a printer's as ``<name>-<part>.stl`` and ``.3mf``), the assembly drawing
    (``<name>-kit-assembly.dxf|svg|png``), every made part in its assembled place (``<name>-kit.3mf``; ``meshes()``
    makes them, only if written) and, when asked, the kit's parts as exact solids (``<name>-kit.step``, one named
    product a part: ``placed``, :class:`~camgen.core.parts.Placed` solids or a function making them, as
    assembled; without it each part in its own frame); with the report (``json``), the bill of materials ``bom``
    as ``<name>-kit.csv`` (:meth:`BomLine.csv_row`'s columns), when it has lines. Every file the kit offers: the
    bundle keeps those ``formats`` asks for (:meth:`~camgen.core.bundle.Bundle.of`); ``formats`` decides which
    meshes are made."""
    from camgen.core.bundle import figure_files, mesh_files, part_files, sheet_files, solid_files
    from camgen.core.solids import checked_mesh

    items: list[Item | None] = []
    for part, source in made:
        if source == "laser":
            items.append(part_files(Drawing.of_part(part), f"{name}-{part.name}", part.name))
            continue
        mesh = checked_mesh(part, f"{name}-{part.name}")[0] if {"stl", "3mf"} & set(formats) else None
        items.append(mesh_files(mesh, f"{name}-{part.name}", part.name))

    def figure() -> Any:
        from camgen.core.figures import drawing_figure

        return drawing_figure(drawing, title)

    items += [sheet_files(drawing, f"{name}-kit-assembly", "kit_assembly"),
              figure_files(figure, f"{name}-kit-assembly", "kit_assembly", only=("png",)),
              mesh_files(meshes, f"{name}-kit", "kit", only=("3mf",)),
              solid_files(placed if placed is not None else tuple((part.name, (part,)) for part, _ in made),
                          f"{name}-kit", "kit"),
              bom_item(name, bom)]
    return items


def bom_item(name: str, bom: tuple[BomLine, ...], formats: Iterable[str] | None = None) -> Item | None:
    """The bill of materials ``bom`` as ``<name>-kit.csv`` (:meth:`BomLine.csv_row`'s columns), written with the
    report (``json``), when it has lines; else None. Only when ``formats`` asks for the report, when given."""
    from camgen.core.bundle import rows_file

    got = rows_file(tuple(line.csv_row() for line in bom), f"{name}-kit", "kit")
    return got.only(formats) if got is not None and formats is not None else got
