"""The course's couplings and double sliders as named types: Oldham's coupling (``type = "oldham"``), the elliptic
trammel (``type = "trammel"``, the double slider) and Rapson's slide (``type = "rapson"``, the scotch yoke's
sibling: the slot on the turning link, the pin on the slider); their ``[linkage]`` tables, reports, figures and
parts.

Frames and closed forms: :mod:`linkgen.kinematics.couplings`; parts: :mod:`linkgen.mechanisms.couplingparts`.
Oldham's and the trammel's input turns at the table's rpm; Rapson's input is the crosshead, moved at ``speed`` mm/s
(its ``angle`` is the crosshead's height in mm, as for a slide input).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field

from camgen.core.errors import SpecError
from camgen.core.spec import MAX_LENGTH_MM, Model, unit
from linkgen.kinematics.couplings import Oldham, Rapson, Trammel
from linkgen.mechanisms.common import Figure, deg, length, num, omega, rpm, types_of
from linkgen.parts import Layout, Stock

if TYPE_CHECKING:
    from camgen.core.parts import Drawing
    from linkgen.spec import PartsTable

#: the largest helm Rapson's slide may be asked for (degrees): its leverage 1 / cos^2 grows without bound at 90
MAX_HELM_DEG = 75.0
#: the fastest crosshead (mm/s)
MAX_SPEED_MM_S = 10_000.0


class OldhamTable(Model):
    """``[linkage]`` of Oldham's coupling: the offset between its two parallel shafts (mm)."""

    type: Literal["oldham"]
    offset: float = Field(gt=0, le=MAX_LENGTH_MM, description="distance between the two shafts' axes",
                          json_schema_extra=unit("mm"))
    rpm: float = rpm()

    def closed_form(self) -> Oldham:
        return Oldham(self.offset)


class TrammelTable(Model):
    """``[linkage]`` of the elliptic trammel (double slider): the rod between the blocks' pins and the tracer on
    its line (mm)."""

    type: Literal["trammel"]
    rod: float = length("the rod between block A's pin (on the X guide) and block B's (on the Y guide)")
    point: float = Field(ge=-MAX_LENGTH_MM, le=MAX_LENGTH_MM, description="the tracer's distance from A along the "
                         "rod towards B (negative behind A, above rod beyond B): its ellipse has semi-axes "
                         "|rod - point| along X and |point| along Y", json_schema_extra=unit("mm"))
    rpm: float = rpm()

    def closed_form(self) -> Trammel:
        return Trammel(self.rod, self.point)


class RapsonTable(Model):
    """``[linkage]`` of Rapson's slide: the crosshead's guide's distance from the rudder stock, the largest helm and
    the crosshead's speed."""

    type: Literal["rapson"]
    distance: float = length("from the rudder stock to the crosshead's guide, square to the centre line")
    max_angle: float = Field(35.0, gt=0, le=MAX_HELM_DEG, description="the tiller's largest angle each side (hard "
                             "over): sets the crosshead's travel distance tan(max_angle) each side",
                             json_schema_extra=unit("degrees"))
    speed: float = Field(10.0, gt=0, le=MAX_SPEED_MM_S, description="the crosshead's speed, constant: the tiller's "
                         "rates are given at it", json_schema_extra=unit("mm/s"))

    def closed_form(self) -> Rapson:
        return Rapson(self.distance)

    @property
    def rpm(self) -> None:
        """No turning input: the report's ``rpm`` is null (the crosshead's ``speed`` sets the rates)."""
        return None


def _xy(p: np.ndarray) -> list[float | None]:
    return [num(float(p[0])), num(float(p[1]))]


def oldham_report(table: OldhamTable, o: Oldham, angle: float | None) -> dict[str, Any]:
    """The report's Oldham section (mm and degrees; speeds at the table's rpm)."""
    w = omega(table.rpm)
    report: dict[str, Any] = {
        "offset_mm": table.offset, "speed_ratio": 1.0,
        "disc_centre_circle": {"centre_mm": list(o.thales_centre), "radius_mm": o.thales_radius,
                               "turns_per_input_turn": 2},
        "slot_stroke_mm": o.stroke, "disc_centre_speed_mm_s": num(o.offset * w),
        "disc_centre_acceleration_mm_s2": num(2 * o.offset * w**2),
        "sliding_speed_max_mm_s": num(o.offset * w), "input_range_deg": None}
    if angle is not None:
        m = o.motion(np.array([math.radians(angle)]), w)
        report["positions"] = {"hub1_deg": deg(m.theta[0]), "hub2_deg": deg(m.output[0]), "disc_deg": deg(m.disc[0]),
                               "disc_centre_mm": _xy(m.centre[0]), "disc_centre_velocity_mm_s": _xy(m.velocity[0]),
                               "disc_centre_acceleration_mm_s2": _xy(m.acceleration[0]),
                               "slides_mm": _xy(m.slide[0]), "slide_speeds_mm_s": _xy(m.slide_rate[0])}
    return report


def trammel_report(table: TrammelTable, t: Trammel, angle: float | None) -> dict[str, Any]:
    """The report's trammel section (mm and degrees; speeds at the table's rpm)."""
    w = omega(table.rpm)
    ax, ay = t.semi_axes
    report: dict[str, Any] = {
        "ellipse": {"centre_mm": [0.0, 0.0], "semi_axis_x_mm": ax, "semi_axis_y_mm": ay},
        "block_stroke_mm": 2 * t.rod, "midpoint_crank_mm": t.rod / 2,
        "tracer_speed_max_mm_s": num(max(ax, ay) * w), "tracer_speed_min_mm_s": num(min(ax, ay) * w),
        "input_range_deg": None}
    if angle is not None:
        m = t.motion(np.array([math.radians(angle)]), w)
        report["positions"] = {"input_deg": deg(m.phi[0]), "block_a_mm": num(m.a[0]), "block_b_mm": num(m.b[0]),
                               "block_a_speed_mm_s": num(m.a_rate[0]), "block_b_speed_mm_s": num(m.b_rate[0]),
                               "rod_deg": deg(m.rod_angle[0]), "tracer_mm": _xy(m.point[0]),
                               "tracer_velocity_mm_s": _xy(m.velocity[0]),
                               "tracer_acceleration_mm_s2": _xy(m.acceleration[0])}
    return report


def rapson_report(table: RapsonTable, r: Rapson, angle: float | None) -> dict[str, Any]:
    """The report's Rapson section (mm and degrees; rates at the crosshead's speed); ``angle`` is the crosshead's
    height (mm), a SpecError on ``angle`` outside its travel."""
    helm = math.radians(table.max_angle)
    travel = r.travel(helm)
    report: dict[str, Any] = {
        "input_range_mm": [num(-travel), num(travel)], "stroke_mm": num(2 * travel), "speed_mm_s": table.speed,
        "leverage_amidships_mm": num(r.distance), "leverage_hard_over_mm": num(r.distance / math.cos(helm) ** 2),
        "leverage_gain_hard_over": num(1 / math.cos(helm) ** 2),
        "tiller_rate_amidships_deg_s": num(math.degrees(table.speed / r.distance)),
        "tiller_rate_hard_over_deg_s": num(math.degrees(table.speed * math.cos(helm) ** 2 / r.distance))}
    if angle is not None:
        if not -travel - 1e-9 <= angle <= travel + 1e-9:
            raise SpecError(f"the crosshead travels from {-travel:.6g} to {travel:.6g} mm (the input is its height; "
                            f"got {angle:g})", "angle")
        m = r.motion(np.array([angle]), table.speed)
        report["positions"] = {"crosshead_mm": num(m.y[0]), "tiller_deg": num(math.degrees(m.angle[0])),
                               "tiller_rate_deg_s": num(math.degrees(m.rate[0])),
                               "tiller_acceleration_deg_s2": num(math.degrees(m.acceleration[0])),
                               "block_radius_mm": num(m.radius[0]), "leverage_mm": num(m.leverage[0])}
    return report


def _line(points: Any) -> Any:
    from camgen.core.shapes import Polyline

    xy = np.asarray(points, dtype=float)
    return Polyline(xy, np.zeros(len(xy) - 1))


def oldham_sketch(o: Oldham) -> Drawing:
    """The hubs' slots at input angle 30 degrees, the line of centres, and the disc centre's circle."""
    from camgen.core.parts import Drawing

    d, t = o.offset, math.radians(30.0)
    m = o.motion(np.array([t]), 1.0)
    u1, u2 = np.array([math.cos(t), math.sin(t)]), np.array([-math.sin(t), math.cos(t)])
    o2 = np.array([d, 0.0])
    path = o.motion(np.linspace(0.0, math.pi, 181), 1.0).centre
    items = (("LINKS", _line([-d * u1, d * u1])), ("LINKS", _line([o2 - d * u2, o2 + d * u2])),
             ("LINKS", _line([(0.0, 0.0), o2])), ("LINKS", _line([(0.0, 0.0), m.centre[0], o2])),
             ("PATH", _line(path)))
    return Drawing(items, 0.01)


def trammel_sketch(t: Trammel) -> Drawing:
    """The guides, the rod at input angle 30 degrees and the tracer's ellipse."""
    from camgen.core.parts import Drawing

    m = t.motion(np.array([math.radians(30.0)]), 1.0)
    reach = max(t.rod, *t.semi_axes)
    ends = [(m.a[0], 0.0), (0.0, m.b[0]), tuple(m.point[0])]
    ends.sort(key=lambda p: math.hypot(p[0] - m.a[0], p[1]))
    path = t.motion(np.linspace(0.0, 2 * math.pi, 361), 1.0).point
    items = (("LINKS", _line([(-reach, 0.0), (reach, 0.0)])), ("LINKS", _line([(0.0, -reach), (0.0, reach)])),
             ("LINKS", _line([ends[0], ends[-1]])), ("PATH", _line(path)))
    return Drawing(items, 0.01)


def rapson_sketch(r: Rapson, max_angle: float) -> Drawing:
    """The crosshead's guide, the tiller amidships and hard over each side, and the block's path."""
    from camgen.core.parts import Drawing

    travel = r.travel(max_angle)
    far = r.distance / math.cos(max_angle)
    items: list[tuple[str, Any]] = [("PATH", _line([(r.distance, -travel), (r.distance, travel)]))]
    for a in (-max_angle, 0.0, max_angle):
        items.append(("LINKS", _line([(0.0, 0.0), (far * math.cos(a), far * math.sin(a))])))
    return Drawing(tuple(items), 0.01)


@dataclass(frozen=True)
class CouplingMechanism:
    """One of the couplings (:class:`linkgen.mechanisms.Mechanism`): its table (whose ``closed_form()`` is its
    kinematics), and its report, sketch and layout as functions of the table and the kinematics."""

    table: type[Model]
    reporter: Callable[[Any, Any, float | None], dict[str, Any]]
    sketcher: Callable[[Any, Any], Drawing]
    layouter: Callable[[Any, Any, Stock, float], Layout]
    what: str

    @property
    def types(self) -> tuple[str, ...]:
        """Its table's ``type`` value."""
        return types_of(self.table)

    def build(self, table: Any) -> Any:
        """The closed form (:mod:`linkgen.kinematics.couplings`) the table describes."""
        return table.closed_form()

    def report(self, table: Any, kinematics: Any, angle: float | None, method: str) -> dict[str, Any]:
        if method == "newton":
            raise SpecError(f"the Newton-Raphson table is for four-bars; a {table.type} is solved in closed form",
                            "--method")
        return self.reporter(table, kinematics, angle)

    def figures(self, name: str, table: Any, kinematics: Any) -> tuple[Figure, ...]:
        """The sketch: the mechanism at one pose with its path."""
        def draw() -> Any:
            from camgen.core.figures import drawing_figure

            return drawing_figure(self.sketcher(table, kinematics), f"{name}: {self.what}")

        return (("sketch", draw),)

    def layout(self, table: Any, kinematics: Any, parts: PartsTable) -> Layout:
        return self.layouter(table, kinematics, Stock.of(parts), parts.width)

    def family_row(self, table: Any, kinematics: Any, report: dict[str, Any]) -> dict[str, Any]:
        return {}

    def sketch(self, table: Any, kinematics: Any) -> Drawing | None:
        return self.sketcher(table, kinematics)


def _oldham_layout(table: OldhamTable, o: Oldham, stock: Stock, width: float) -> Layout:
    from linkgen.mechanisms.couplingparts import oldham_layout

    return oldham_layout(o, stock, width)


def _trammel_layout(table: TrammelTable, t: Trammel, stock: Stock, width: float) -> Layout:
    from linkgen.mechanisms.couplingparts import trammel_layout

    return trammel_layout(t, stock, width)


def _rapson_layout(table: RapsonTable, r: Rapson, stock: Stock, width: float) -> Layout:
    from linkgen.mechanisms.couplingparts import rapson_layout

    return rapson_layout(r, math.radians(table.max_angle), stock, width)


REGISTER = (
    CouplingMechanism(OldhamTable, oldham_report, lambda t, k: oldham_sketch(k),
                      _oldham_layout, "the hubs' slots and the disc centre's circle"),
    CouplingMechanism(TrammelTable, trammel_report,
                      lambda t, k: trammel_sketch(k), _trammel_layout, "the guides, the rod and the tracer's ellipse"),
    CouplingMechanism(RapsonTable, rapson_report,
                      lambda t, k: rapson_sketch(k, math.radians(t.max_angle)), _rapson_layout,
                      "the tiller amidships and hard over, and the crosshead's guide"),
)
