"""The slider-crank and the scotch yoke: their ``[linkage]`` tables, reports, motion figure, and the slider-crank's
parts.

Frame (see :mod:`linkgen.kinematics.slidercrank`): crank pivot at the origin, the slider
on the line y = offset parallel to +X; crank angle counter-clockwise from +X. The
helpers here also serve the quick-return mechanisms, whose ram is a slider.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field

from camgen.core.errors import SpecError
from camgen.core.spec import Model, unit
from linkgen import plots
from linkgen.kinematics import equivalents
from linkgen.kinematics.slidercrank import ScotchYoke, SliderCrank, SliderMotion
from linkgen.mechanisms.common import Figure, deg, length, lengths_table, no_parts, num, omega, rpm, types_of
from linkgen.parts import SWEEP, Layout, LinkPart, Placement, Stock

if TYPE_CHECKING:
    from camgen.core.parts import Drawing
    from linkgen.spec import PartsTable


class SliderCrankTable(Model):
    """``[linkage]`` of a slider-crank: crank and rod (mm), the slider line's offset above the crank pivot (mm)."""

    type: Literal["slider-crank"]
    crank: float = length("crank")
    rod: float = length("connecting rod")
    offset: float = Field(0.0, description="slider line above the crank pivot", json_schema_extra=unit("mm"))
    rpm: float = rpm()


ScotchYokeTable = lengths_table("ScotchYokeTable", "``[linkage]`` of a scotch yoke: its crank (mm).", ("scotch-yoke",),
                                crank="crank")


def slider_report(mech: Any, table: Any, angle: float | None, input_range: tuple[float, float] | None = None,
                  full: bool = True, extra: dict[str, Any] | None = None,
                  at: Callable[[Any, SliderMotion, float], dict[str, Any]] | None = None) -> dict[str, Any]:
    """The report of a mechanism driving a slider (mm from its own origin): the crank's reachable ``input_range``
    (rad, None when it turns fully), the dead centres, and when it turns fully (``full``) the stroke and time
    ratio; then ``extra``; with ``angle`` (degrees) the slider's motion there, and what
    ``at(mech, motion, speed rad/s)`` adds."""
    report: dict[str, Any] = {
        "input_range_deg": None if input_range is None else [round(math.degrees(x), 9) for x in input_range]}
    dead = mech.dead_centres()
    report["dead_centres"] = [{"kind": k, "crank_deg": deg(t), "slider_mm": round(x, 9)} for k, t, x in dead]
    ends = full and len(dead) == 2
    report["stroke_mm"] = round(mech.stroke, 9) if ends else None
    report["time_ratio"] = round(mech.time_ratio, 12) if ends else None
    report.update(extra or {})
    if angle is not None:
        speed = omega(table.rpm)
        m = mech.motion(np.array([math.radians(angle)]), speed)
        pos = {"crank_deg": deg(m.theta[0]), "slider_mm": num(m.x[0]), "velocity_mm_s": num(m.v[0]),
               "acceleration_mm_s2": num(m.a[0])}
        pos.update(at(mech, m, speed) if at is not None else {})
        report["positions"] = pos
    return report


def _approximation_error(sc: SliderCrank) -> dict[str, Any]:
    """A centred slider-crank turning fully: the classic approximation's largest error over a turn, and its
    estimate r^4 / (8 L^3) (mm)."""
    if not (sc.offset == 0 and sc.turns_fully):
        return {}
    t = np.linspace(0, 2 * math.pi, 3601)
    d, _, _ = sc.approximation(t)
    exact = sc.position(0.0) - sc.position(t)
    err = np.abs(exact - d)
    return {"approximation_error_max_mm": round(float(err.max()), 12),
            "approximation_error_estimate_mm": round(sc.crank**4 / (8 * sc.rod**3), 12)}


def _rod_and_approximation(sc: SliderCrank, m: SliderMotion, speed: float) -> dict[str, Any]:
    """The rod's angle at one pose and, centred, the classic approximation there with its errors."""
    pos: dict[str, Any] = {"rod_deg": deg(m.rod[0])}
    if sc.offset == 0:
        d, d1, d2 = sc.approximation(m.theta)
        # displacement from TDC is x(0) - x, so its rates are -v and -a
        pos["approximation"] = {
            "displacement_from_tdc_mm": num(d[0]), "error_mm": num(sc.position(0.0) - m.x[0] - d[0]),
            "velocity_mm_s": num(d1[0] * speed), "velocity_error_mm_s": num(-m.v[0] - d1[0] * speed),
            "acceleration_mm_s2": num(d2[0] * speed**2),
            "acceleration_error_mm_s2": num(-m.a[0] - d2[0] * speed**2)}
    return pos


def placement(sc: SliderCrank, theta: np.ndarray) -> Placement:
    """Where the base, crank, rod and slider block sit at crank angles ``theta`` (rad)."""
    m = sc.motion(theta, 1.0)
    a = np.column_stack([sc.crank * np.cos(theta), sc.crank * np.sin(theta)])
    b = np.column_stack([m.x, np.full_like(m.x, sc.offset)])
    zero = np.zeros(len(theta))
    return Placement(
        angles={"ground": zero, "crank": theta, "rod": m.rod, "slider": zero},
        origins={"ground": np.zeros((len(theta), 2)), "crank": np.zeros((len(theta), 2)), "rod": a, "slider": b},
        joints={"O": (("ground", "crank"), np.zeros((len(theta), 2))), "A": (("crank", "rod"), a),
                "B": (("rod", "slider"), b)})


def slidercrank_parts(sc: SliderCrank, table: PartsTable) -> tuple[LinkPart, ...]:
    """Base plate (crank pivot and a guide slot along the slider's travel), crank, rod and slider block."""
    dead = sc.dead_centres()
    if len(dead) != 2:
        raise SpecError("parts need a crank that turns fully (rod >= crank + |offset|)", "linkage.rod")
    stock = Stock.of(table)
    x_top, x_bottom = dead[0][2], dead[1][2]
    w = table.width_of("crank") / 2
    ends = (np.array([x_bottom, sc.offset]), np.array([x_top, sc.offset]))
    # one pivot hole and the slot; the plate rounds the pivot and both ends of the slot (the slot is not a pair of
    # holes too: its ends would be cut twice)
    base = LinkPart("ground", np.array([[0.0, 0.0]]), 2 * w, stock, slots=(ends,), moving=False,
                    body=np.array([[0.0, 0.0], ends[0], ends[1]]))
    block = table.width_of("slider")
    return (base, LinkPart("crank", np.array([[0.0, 0.0], [sc.crank, 0.0]]), w, stock),
            LinkPart("rod", np.array([[0.0, 0.0], [sc.rod, 0.0]]), table.width_of("rod") / 2, stock),
            LinkPart("slider", np.array([[0.0, 0.0]]), block / 2, stock, body=np.array([[-block, 0.0], [block, 0.0]])))


@dataclass(frozen=True)
class SliderMechanism:
    """A mechanism driving a slider (or a ram): its report (:func:`slider_report`), the slider's motion figure, no
    parts, no thumbnail and no sketch.

    Its types are its table's. ``make`` builds the kinematics from the table (with ``dead_centres()``, ``stroke``,
    ``time_ratio``, ``motion(theta, omega)`` and, where the crank may not turn fully,
    ``input_range()`` and ``turns_fully``); ``extra(kinematics)`` gives report keys after the
    time ratio, ``at(kinematics, motion, speed)`` keys of a position.
    """

    table: type[Model]
    make: Callable[[Any], Any]
    extra: Callable[[Any], dict[str, Any]] | None = None
    at: Callable[[Any, SliderMotion, float], dict[str, Any]] | None = None
    #: the mechanism drawn as a general linkage (kinematics -> structure), whose parts are cut for it; and the
    #: point whose path the assembly shows
    drawn: Callable[[Any], Any] | None = None
    traced: str = ""

    @property
    def types(self) -> tuple[str, ...]:
        return types_of(self.table)

    def build(self, table: Any) -> Any:
        return self.make(table)

    def report(self, table: Any, kinematics: Any, angle: float | None, method: str) -> dict[str, Any]:
        return slider_report(kinematics, table, angle, getattr(kinematics, "input_range", lambda: None)(),
                             getattr(kinematics, "turns_fully", True),
                             self.extra(kinematics) if self.extra is not None else None, self.at)

    def figures(self, name: str, table: Any, kinematics: Any) -> tuple[Figure, ...]:
        """Slider position, velocity and acceleration over one crank turn at the table's rpm."""
        return (("motion", lambda: plots.slider_figure(name, kinematics, omega(table.rpm))),)

    def layout(self, table: Any, kinematics: Any, parts: PartsTable) -> Layout:
        """Its parts cut as those of the general linkage it draws (crank, links, blocks, the guides' slots)."""
        if self.drawn is None:
            no_parts(table.type)
        from linkgen.mechanisms.general import analysis_of, general_layout

        return general_layout(analysis_of(self.drawn(kinematics), (self.traced,)), parts)

    def family_row(self, table: Any, kinematics: Any, report: dict[str, Any]) -> dict[str, Any]:
        return {}

    def sketch(self, table: Any, kinematics: Any) -> Drawing | None:
        return None


@dataclass(frozen=True)
class SliderCrankMechanism(SliderMechanism):
    """A slider-crank: a slider mechanism with parts when the crank turns fully."""

    def layout(self, table: Any, kinematics: SliderCrank, parts: PartsTable) -> Layout:
        """The parts over a full crank turn, both dead centres, and the slider's path."""
        links = slidercrank_parts(kinematics, parts)
        dead = tuple((k, t) for k, t, _ in kinematics.dead_centres())
        sweep = placement(kinematics, np.linspace(0, 2 * math.pi, SWEEP))
        poses = tuple(placement(kinematics, np.array([t])) for _, t in dead)
        return Layout(links, sweep, dead, poses, (sweep.origins["slider"],))


REGISTER = (
    SliderCrankMechanism(SliderCrankTable, lambda t: SliderCrank(t.crank, t.rod, t.offset), _approximation_error,
                         _rod_and_approximation),
    SliderMechanism(ScotchYokeTable, lambda t: ScotchYoke(t.crank), drawn=lambda k: equivalents.scotch_yoke(k, 0.0),
                    traced="Y"),
)
