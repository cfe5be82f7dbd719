"""Ratchet and pawl (``type = "ratchet"``): a saw-toothed wheel held by a pawl on the ground and indexed by a lever
swinging about the wheel's axis with a pawl of its own; their ``[linkage]`` table, the holding check, the report,
the figure and the parts.

The geometry and the statics are :mod:`linkgen.gears.ratchet` (tooth 0 on +Y, the wheel driven counter-clockwise,
held against turning clockwise). The lever's pawl is the holding pawl's figure turned half a turn about the wheel's
axis: at rest it bears on the tooth on -Y (``teeth`` even) or the nearest one to it.

Parts (all pins from the base plate up): the base plate (layer 0) with the wheel's axle, the pawl's pivot and the
post its spring pulls to; the wheel, the pawl and the lever's pawl (layer 1, the wheel's plane); the lever (layer
2) on the wheel's axle, with its pawl's pivot, the post that pawl's spring pulls to and a handle hole. Each pawl's
spring seat is a hole in its tail, beyond its pivot, ``pawl.spring`` mm from its post across the pawl's line, so
the spring turns the pawl's nose into the wheel.

Checks, each refused in one line naming the key: a wheel whose teeth cannot be drawn, a pawl that does not hold (its
engagement angle under the friction angle), a lever that swings less than a tooth's pitch, parts that do not fit.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field, model_validator

from camgen.core.errors import DesignError, SpecError
from camgen.core.shapes import merged_pieces
from camgen.core.spec import MAX_LENGTH_MM, Model, unit
from linkgen.gears.ratchet import Pawl, RatchetWheel, teeth_per_stroke
from linkgen.mechanisms.common import Figure, num, types_of
from linkgen.parts import Layout, LinkPart, Placement, Stock

if TYPE_CHECKING:
    from camgen.core.parts import Drawing
    from linkgen.spec import PartsTable

#: the fewest and most teeth a wheel may have
MIN_TEETH, MAX_TEETH = 6, 360
#: an engagement angle within this (degrees) of the friction angle is warned of
MARGIN_WARNING_DEG = 3.0
#: the gap (mm) between a pawl's nose and the tooth it bears on, as drawn
NOSE_GAP_MM = 0.05
#: the gap (mm) between a pawl's bar and the wheel's tip circle
BAR_CLEARANCE_MM = 0.5
#: a pawl's outline has no piece shorter than this (mm)
SHORTEST_PIECE_MM = 0.05


class PawlTable(Model):
    """The pawl (``[linkage.pawl]``): where its pivot sits from the contact at the tooth's tip, and its spring."""

    length: float = Field(gt=0, le=MAX_LENGTH_MM, description="from the pawl's contact at the tooth's tip to its "
                          "pivot", json_schema_extra=unit("mm"))
    angle: float = Field(0.0, ge=-45.0, le=45.0, description="the pivot's line from the contact, above the wheel's "
                         "tangent there (positive away from the wheel); adds to the engagement angle",
                         json_schema_extra=unit("degrees"))
    spring: float = Field(12.0, gt=0, le=1000.0, description="the spring's length at rest, from the seat in the "
                          "pawl's tail to its post, across the pawl's line", json_schema_extra=unit("mm"))


class LeverTable(Model):
    """The driving lever (``[linkage.lever]``): it swings about the wheel's axis and its pawl indexes the wheel."""

    swing: float = Field(gt=0, le=180.0, description="the lever's stroke about the wheel's axis",
                         json_schema_extra=unit("degrees", allowed=">= a tooth's pitch, 360 / teeth"))
    length: float = Field(gt=0, le=MAX_LENGTH_MM, description="from the wheel's axis to the lever's handle hole",
                          json_schema_extra=unit("mm", allowed="beyond its pawl's pivot by the parts' width"))


class RatchetTable(Model):
    """``[linkage]`` of a ratchet and pawl: the wheel's teeth, the pawl, the driving lever, the friction."""

    type: Literal["ratchet"]
    teeth: int = Field(ge=MIN_TEETH, le=MAX_TEETH, description="teeth of the wheel")
    tip_diameter: float = Field(gt=0, le=MAX_LENGTH_MM, description="the wheel's diameter over its tips",
                                json_schema_extra=unit("mm"))
    depth: float = Field(gt=0, le=MAX_LENGTH_MM, description="the teeth's depth, tip circle to root circle",
                         json_schema_extra=unit("mm", allowed="< the tip radius"))
    face_angle: float = Field(10.0, ge=-30.0, le=45.0, description="the tooth face's lean from the radial line "
                              "through its tip, positive hooked (the tip overhanging the face)",
                              json_schema_extra=unit("degrees"))
    friction: float = Field(0.15, ge=0.0, le=1.0, description="friction coefficient mu between the pawl and the "
                            "face: the pawl must hold with the face's normal atan(mu) inside its pivot")
    pawl: PawlTable = Field(description="the holding pawl: [linkage.pawl]")
    lever: LeverTable = Field(description="the driving lever: [linkage.lever]")
    rpm: float = Field(30.0, gt=0, le=10000.0, description="strokes of the lever a minute",
                       json_schema_extra=unit("1/min"))

    @model_validator(mode="after")
    def _consistent(self) -> RatchetTable:
        wheel = self.wheel
        if not self.depth < self.tip_diameter / 2:
            raise ValueError(f"depth: must be < the tip radius, {self.tip_diameter / 2:g} mm (got {self.depth:g})")
        try:
            wheel.check()
        except DesignError as exc:
            raise ValueError(f"face_angle: {exc}") from None
        pawl = self.holding_pawl
        friction = math.degrees(math.atan(self.friction))
        psi = math.degrees(pawl.engagement_angle)
        if not pawl.holds(self.friction):
            raise ValueError(f"face_angle: the pawl does not hold: its engagement angle (face_angle + pawl.angle) is "
                             f"{psi:.6g} degrees, under the friction angle atan({self.friction:g}) = {friction:.6g}; "
                             f"lean the faces {friction - psi:.4g} degrees more or raise pawl.angle")
        pitch = 360.0 / self.teeth
        if teeth_per_stroke(self.teeth, math.radians(self.lever.swing)) < 1:
            raise ValueError(f"lever.swing: must be at least a tooth's pitch, 360 / {self.teeth} = {pitch:.6g} "
                             f"degrees (got {self.lever.swing:g})")
        return self

    @property
    def wheel(self) -> RatchetWheel:
        return RatchetWheel(self.teeth, self.tip_diameter / 2, self.depth, math.radians(self.face_angle))

    @property
    def holding_pawl(self) -> Pawl:
        return Pawl(self.wheel, self.pawl.length, math.radians(self.pawl.angle))

    def lengths_mm(self) -> dict[str, float]:
        """The report's lengths (mm)."""
        return {"tip_diameter": self.tip_diameter, "depth": self.depth, "pawl": self.pawl.length,
                "lever": self.lever.length}


@dataclass(frozen=True)
class Ratchet:
    """The built ratchet: its pawl (and through it the wheel), the friction, the lever's swing (rad) and length
    (mm), and the tooth its pawl bears on at rest."""

    pawl: Pawl
    friction: float
    swing: float
    lever_length: float

    @property
    def wheel(self) -> RatchetWheel:
        return self.pawl.wheel

    @property
    def teeth_per_stroke(self) -> int:
        return teeth_per_stroke(self.wheel.teeth, self.swing)

    @property
    def drive_tooth(self) -> int:
        """The tooth nearest -Y, on which the lever's pawl bears at rest."""
        return round(self.wheel.teeth / 2)

    @property
    def drive_turn(self) -> float:
        """The turn (rad) that takes the holding pawl's figure to the lever's: that tooth's angle from tooth 0."""
        return self.drive_tooth * self.wheel.pitch


def _turn(points: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.asarray(points, dtype=float) @ np.array([[c, s], [-s, c]])


def ratchet_report(table: RatchetTable, ratchet: Ratchet, angle: float | None) -> dict[str, Any]:
    """The report's ratchet section (mm and degrees)."""
    wheel, pawl = ratchet.wheel, ratchet.pawl
    psi, friction = math.degrees(pawl.engagement_angle), math.degrees(math.atan(ratchet.friction))
    n = ratchet.teeth_per_stroke
    pitch = 360.0 / wheel.teeth
    report: dict[str, Any] = {
        "wheel": {"teeth": wheel.teeth, "pitch_deg": num(pitch), "tip_radius_mm": num(wheel.tip_radius),
                  "root_radius_mm": num(wheel.root_radius), "face_angle_deg": table.face_angle,
                  "face_length_mm": num(wheel.face_length)},
        "pawl": {"pivot_mm": [num(float(v)) for v in pawl.pivot], "length_mm": pawl.length,
                 "angle_deg": table.pawl.angle, "spring_mm": table.pawl.spring},
        "engagement_angle_deg": num(psi), "friction_angle_deg": num(friction), "holds": True,
        "holding_margin_deg": num(psi - friction),
        "lever": {"swing_deg": table.lever.swing, "length_mm": table.lever.length, "teeth_per_stroke": n,
                  "index_deg": num(n * pitch), "lost_motion_deg": num(table.lever.swing - n * pitch)},
        "wheel_rpm": num(table.rpm * n / wheel.teeth),
        "input_range_deg": [0.0, table.lever.swing],
        "warnings": [f"the engagement angle {psi:.4g} degrees is within {MARGIN_WARNING_DEG:g} of the friction angle "
                     f"{friction:.4g}: a little more friction and the pawl slips out"]
        if psi - friction < MARGIN_WARNING_DEG else [],
    }
    if angle is not None:
        if not 0.0 <= angle <= table.lever.swing:
            raise SpecError(f"the lever swings from 0 to {table.lever.swing:g} degrees (got {angle:g})", "angle")
        report["positions"] = {"lever_deg": num(angle), "wheel_deg": num(angle),
                               "teeth_passed": math.floor(angle / pitch + 1e-9)}
    return report


def pawl_shape(ratchet: Ratchet, width: float, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """The holding pawl's outline in the wheel's frame at rest (counter-clockwise, mm; lines, within ``tolerance``
    of its round ends): a nose whose face lies :data:`NOSE_GAP_MM` off the tooth's face, down 60 % of it, reaching
    along the pawl's line; and a bar ``width`` wide from the nose over the pivot to the tail, kept
    :data:`BAR_CLEARANCE_MM` outside the tip circle."""
    import shapely
    from shapely.geometry.polygon import orient

    pawl, wheel = ratchet.pawl, ratchet.wheel
    c, p = pawl.contact, pawl.pivot
    u = (p - c) / pawl.length
    half = width / 2
    segments = max(2, math.ceil(math.pi / (4 * math.acos(1 - min(tolerance / half, 1.0)))))
    down = np.array([-math.sin(wheel.face_angle), -math.cos(wheel.face_angle)])      # along the face, inwards
    top = c + NOSE_GAP_MM * pawl.normal
    foot = top + 0.6 * wheel.face_length * down
    # the nose reaches along the pawl's line 60 % of a pitch, or to half the bar's clearance outside the tip circle
    # (so that the bar's clearance arc crosses the nose's end, not its corner)
    b = float(top @ u)
    out = -b + math.sqrt(b * b + (wheel.tip_radius + BAR_CLEARANCE_MM / 2) ** 2 - float(top @ top))
    reach = top + min(0.6 * wheel.tip_radius * wheel.pitch, out) * u
    nose = shapely.MultiPoint([top, foot, reach, top - half * down, reach - half * down]).convex_hull
    teeth = shapely.Polygon(wheel.outline()[0])
    if nose.intersects(teeth):
        raise DesignError("linkage.depth: the pawl's nose does not fit the tooth space: give the teeth more depth, "
                          "or the wheel more teeth' pitch")
    bar = shapely.LineString([reach, p, p + _tail(width) * u]).buffer(half, quad_segs=segments)
    clear = shapely.Point(0.0, 0.0).buffer(wheel.tip_radius + BAR_CLEARANCE_MM, quad_segs=4 * segments)
    shape = shapely.union(nose, bar.difference(clear)).simplify(tolerance / 2)
    if not isinstance(shape, shapely.Polygon) or not shape.is_valid or shape.intersects(teeth):
        raise DesignError("linkage.pawl: the pawl's bar does not clear the wheel: give the pawl a larger angle or "
                          "the parts less width")
    ring = np.asarray(orient(shape, 1.0).exterior.coords)[:-1]
    # the union and simplification may leave a sliver of an edge where the nose meets the bar's clearance arc, which
    # a kerf's offset would close: merged into its neighbours (each end moves by half of it at most)
    return merged_pieces(ring, np.zeros(len(ring)), SHORTEST_PIECE_MM)


def _tail(width: float) -> float:
    """How far (mm) beyond its pivot a pawl's spring seat sits: two widths."""
    return 2 * width


def ratchet_layout(ratchet: Ratchet, spring: float, stock: Stock, width: float) -> Layout:
    """The parts (see the module's notes) at rest and at the end of a stroke's index."""
    from linkgen.mechanisms.shaped import ShapedPart

    pawl, wheel = ratchet.pawl, ratchet.wheel
    half = width / 2
    if stock.hole / 2 + 1.0 > wheel.root_radius:
        raise DesignError(f"parts.pin_diameter: the wheel's hole ({stock.hole:g} mm: pin + clearance) leaves less "
                          f"than 1 mm inside its root circle ({2 * wheel.root_radius:.4g} mm across)")
    p = pawl.pivot
    u = (p - pawl.contact) / pawl.length
    seat = p + _tail(width) * u
    post = seat + spring * np.array([-u[1], u[0]])
    if spring < stock.hole + 1.0:
        raise DesignError(f"linkage.pawl.spring: its seat and post ({stock.hole:g} mm holes) need at least "
                          f"{stock.hole + 1.0:g} mm between them (got {spring:g})")
    shape = pawl_shape(ratchet, width, stock.tolerance)
    turn = ratchet.drive_turn
    drive_pivot, drive_post = _turn(p, turn), _turn(post, turn)
    handle = ratchet.lever_length * drive_pivot / float(np.hypot(*drive_pivot))
    if not ratchet.lever_length >= float(np.hypot(*drive_pivot)) + width:
        raise DesignError(f"linkage.lever.length: the handle must lie at least the parts' width beyond the lever's "
                          f"pawl pivot, {float(np.hypot(*drive_pivot)) + width:.6g} mm from the axis (got "
                          f"{ratchet.lever_length:g})")
    outline = wheel.outline()
    parts: tuple[LinkPart, ...] = (
        LinkPart("ground", np.array([[0.0, 0.0], p, post]), half, stock, moving=False),
        ShapedPart("wheel", np.zeros((1, 2)), half, stock, shape=outline),
        ShapedPart("pawl", np.array([p, seat]), half, stock, shape=shape),
        LinkPart("lever", np.array([[0.0, 0.0], drive_pivot, drive_post, handle]), half, stock),
        ShapedPart("lever-pawl", np.array([drive_pivot, _turn(seat, turn)]), half, stock,
                   shape=(_turn(shape[0], turn), shape[1])))
    layers = {"ground": 0, "wheel": 1, "pawl": 1, "lever-pawl": 1, "lever": 2}
    index = ratchet.teeth_per_stroke * wheel.pitch
    positions = (("rest", 0.0), ("indexed", index))
    sweep = _placement(np.array([0.0, index]), p, drive_pivot)
    poses = tuple(_placement(np.array([t]), p, drive_pivot) for _, t in positions)
    return Layout(parts, sweep, positions, poses, (), layers)


def _placement(theta: np.ndarray, pivot: np.ndarray, drive_pivot: np.ndarray) -> Placement:
    """The parts with the wheel, the lever and its pawl turned by ``theta`` (rad) about the axis, the rest still
    (each part drawn in the wheel's frame)."""
    n = len(theta)
    zero, origin = np.zeros(n), np.zeros((n, 2))
    turned = {"wheel": theta, "lever": theta, "lever-pawl": theta}
    angles = {"ground": zero, "pawl": zero, **turned}
    origins = {name: origin for name in angles}
    c, s = np.cos(theta), np.sin(theta)
    moved = np.column_stack([c * drive_pivot[0] - s * drive_pivot[1], s * drive_pivot[0] + c * drive_pivot[1]])
    joints: dict[str, tuple[tuple[str, str], np.ndarray]] = {
        "O": (("ground", "wheel"), origin), "OL": (("wheel", "lever"), origin.copy()),
        "P": (("ground", "pawl"), np.tile(pivot, (n, 1))), "D": (("lever", "lever-pawl"), moved)}
    return Placement(angles, origins, joints)


def ratchet_drawing(ratchet: Ratchet, width: float) -> Drawing:
    """The wheel and the holding pawl at rest, the face's normal at the contact, the friction cone's edges about it
    and the line from the contact to the pawl's pivot."""
    from camgen.core.parts import Drawing, preview_stroke
    from camgen.core.shapes import Circle, Contour, Polyline

    pawl, wheel = ratchet.pawl, ratchet.wheel
    tolerance = 0.01 * wheel.depth
    c, p = pawl.contact, pawl.pivot
    reach = 2 * wheel.depth
    items: list = [("wheel", Contour(*wheel.outline())), ("pawl", Contour(*pawl_shape(ratchet, width, tolerance))),
                   ("pivots", Circle((0.0, 0.0), width / 4)), ("pivots", Circle((float(p[0]), float(p[1])),
                                                                                  width / 4)),
                   ("pawl line", Polyline(np.array([c, p]), np.zeros(1)))]
    friction = math.atan(ratchet.friction)
    for turn, layer in ((0.0, "face normal"), (friction, "friction cone"), (-friction, "friction cone")):
        items.append((layer, Polyline(np.array([c, c + reach * _turn(pawl.normal, turn)]), np.zeros(1))))
    return Drawing(tuple(items), tolerance, stroke=preview_stroke(items))


@dataclass(frozen=True)
class RatchetMechanism:
    """The ratchet-and-pawl mechanism (:class:`linkgen.mechanisms.Mechanism`)."""

    table: type[Model] = RatchetTable

    @property
    def types(self) -> tuple[str, ...]:
        return types_of(self.table)

    def build(self, table: RatchetTable) -> Ratchet:
        return Ratchet(table.holding_pawl, table.friction, math.radians(table.lever.swing), table.lever.length)

    def report(self, table: RatchetTable, kinematics: Ratchet, angle: float | None, method: str) -> dict[str, Any]:
        return ratchet_report(table, kinematics, angle)

    def figures(self, name: str, table: RatchetTable, kinematics: Ratchet) -> tuple[Figure, ...]:
        """The wheel and the pawl with the face's normal and the friction cone at the contact."""
        def draw() -> Any:
            from camgen.core.figures import drawing_figure

            return drawing_figure(ratchet_drawing(kinematics, _width(table)),
                                  f"{name}: the pawl at rest, the face's normal and the friction cone")

        return (("pawl", draw),)

    def layout(self, table: RatchetTable, kinematics: Ratchet, parts: PartsTable) -> Layout:
        return ratchet_layout(kinematics, table.pawl.spring, Stock.of(parts), parts.width)

    def family_row(self, table: RatchetTable, kinematics: Ratchet, report: dict[str, Any]) -> dict[str, Any]:
        return {"engagement_angle_deg": report["engagement_angle_deg"],
                "teeth_per_stroke": report["lever"]["teeth_per_stroke"]}

    def sketch(self, table: RatchetTable, kinematics: Ratchet) -> Drawing | None:
        return ratchet_drawing(kinematics, _width(table))

    def animation_inputs(self, table: RatchetTable, kinematics: Ratchet, n: int) -> np.ndarray:
        from linkgen.mechanisms.ratchetframes import stroke_inputs

        return stroke_inputs(n)

    def animation_frames(self, table: RatchetTable, kinematics: Ratchet, values: np.ndarray,
                         size: tuple[int, int]) -> np.ndarray:
        from linkgen.mechanisms.ratchetframes import ratchet_frames

        return ratchet_frames(kinematics, _width(table), values, size)


def _width(table: RatchetTable) -> float:
    """The pawl's width in a drawing without parts: a third of the teeth's depth's worth more than the depth."""
    return 1.5 * table.depth


REGISTER = (RatchetMechanism(),)
