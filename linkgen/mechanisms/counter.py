"""The counter (``type = "counter"``): a ratchet's units wheel, indexed by its lever a stroke at a time, that once a
turn steps a tens wheel by one slot through a Geneva pin; its ``[linkage]`` table, the checks, the report with the
count over the strokes, the figures and the parts.

Stage 1 is :mod:`linkgen.mechanisms.ratchet`'s wheel, holding pawl and lever (the same keys and checks). Stage 2 is
:mod:`linkgen.gears.counter`'s Geneva step: the transfer pin on the units wheel at a = C sin(180 / slots) from its
axis, the tens wheel's axis C from it at ``transfer.angle``; the tens wheel turns one slot clockwise while the units
wheel turns through the window, 180 - 360 / slots degrees, and is held the rest of the turn by the locking disc
fixed to the units wheel in the tens wheel's concave locking arcs. At rest the pin stands half a stroke's index past
its exit, so the transfer ends half a stroke before the units wheel's turn does and the locking disc holds the tens
wheel both ways between transfers.

Parts (pins from the base plate up): the base plate (layer 0) with the units wheel's axle, the tens wheel's, the
pawl's pivot and its spring's post; the locking disc and the tens wheel (layer 1, the Geneva's plane); the units
wheel, its holding pawl and the lever's pawl (layer 2); the lever (layer 3). The transfer pin stands in the units
wheel and reaches down into the tens wheel's slots; a dowel pins the locking disc to the units wheel. The slots are
the pin's hole wide (pin + clearance); the locking disc's radius is a less the slot's width.

Checks, each refused in one line naming the key, beyond the ratchet's: a lever whose index does not divide the
wheel's teeth (the transfer would come at another stroke each turn), a transfer pin off the units wheel or a tens
wheel's axis inside it (the transfer cannot engage), a tens wheel that cannot be drawn or locked, and a tens wheel
that reaches the pawl's pins.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field, model_validator

from camgen.core.errors import DesignError
from camgen.core.spec import MAX_LENGTH_MM, Model, unit
from linkgen.gears.counter import Transfer, driven, stroke_turns
from linkgen.gears.geneva import GenevaStep
from linkgen.gears.ratchet import teeth_per_stroke
from linkgen.mechanisms.common import Figure, num, types_of
from linkgen.mechanisms.ratchet import Ratchet, RatchetTable, ratchet_drawing, ratchet_report
from linkgen.parts import Layout, LinkPart, Placement, Stock

if TYPE_CHECKING:
    from camgen.core.parts import Drawing
    from linkgen.spec import PartsTable

#: the fewest and most slots of the tens wheel
MIN_SLOTS, MAX_SLOTS = 3, 36
#: the most strokes the report counts
MAX_STROKES = 10_000
#: the most samples the count's figure draws (200 a stroke up to 500 strokes)
FIGURE_SAMPLES = 100_000
#: the gap (mm) kept between the units wheel's holes (its axle, the transfer pin, the dowel) and its root circle
#: or each other
WALL_MM = 1.0


class TransferTable(Model):
    """The transfer (``[linkage.transfer]``): the tens wheel's slots and where its axis stands."""

    slots: int = Field(ge=MIN_SLOTS, le=MAX_SLOTS, description="slots of the tens wheel: the steps of its turn")
    centre_distance: float = Field(gt=0, le=MAX_LENGTH_MM, description="from the units wheel's axis to the tens "
                                   "wheel's; the transfer pin stands centre_distance x sin(180 / slots) from the "
                                   "units wheel's axis", json_schema_extra=unit(
                                       "mm", allowed="beyond the units wheel's tip radius, with the pin's circle "
                                       "inside its root circle"))
    angle: float = Field(-90.0, ge=-180.0, le=180.0, description="the direction of the tens wheel's axis from the "
                         "units wheel's, counter-clockwise from +X", json_schema_extra=unit("degrees"))
    clearance: float = Field(0.2, ge=0.0, le=5.0, description="the gap between the locking disc and the tens "
                             "wheel's locking arcs", json_schema_extra=unit("mm"))


class CounterTable(RatchetTable):
    """``[linkage]`` of a counter: the units wheel's ratchet (as ``type = "ratchet"``), the transfer to the tens
    wheel and the strokes the report counts."""

    type: Literal["counter"]  # type: ignore[assignment]
    transfer: TransferTable = Field(description="the Geneva step to the tens wheel: [linkage.transfer]")
    strokes: int | None = Field(None, ge=1, le=MAX_STROKES, description="strokes the report counts (three turns of "
                                "the units wheel unless given)")

    @model_validator(mode="after")
    def _engages(self) -> CounterTable:
        n = teeth_per_stroke(self.teeth, math.radians(self.lever.swing))
        if self.teeth % n:
            raise ValueError(f"lever.swing: it indexes {n} teeth a stroke, which does not divide the wheel's "
                             f"{self.teeth}: the transfer would come at another stroke each turn")
        t = self.transfer
        pin = self.geneva.pin_radius
        root, tip = self.tip_diameter / 2 - self.depth, self.tip_diameter / 2
        if not pin < root:
            raise ValueError(f"transfer.centre_distance: the transfer pin's circle, {t.centre_distance:g} x "
                             f"sin(180 / {t.slots}) = {pin:.6g} mm, must lie inside the units wheel's root circle "
                             f"({root:.6g} mm): at most {root / math.sin(math.pi / t.slots):.6g} mm, so the "
                             "transfer cannot engage")
        if not t.centre_distance > tip:
            raise ValueError(f"transfer.centre_distance: must be > the units wheel's tip radius, {tip:g} mm, to "
                             f"stand the tens wheel's axis off it (got {t.centre_distance:g})")
        return self

    @property
    def geneva(self) -> Transfer:
        """The Geneva step, the pin half a stroke's index past its exit at rest."""
        n = teeth_per_stroke(self.teeth, math.radians(self.lever.swing))
        return Transfer(self.transfer.slots, self.transfer.centre_distance, math.pi * n / self.teeth)

    def lengths_mm(self) -> dict[str, float]:
        """The report's lengths (mm)."""
        return {**super().lengths_mm(), "centre_distance": self.transfer.centre_distance}


@dataclass(frozen=True)
class Counter:
    """The built counter: its ratchet (the units wheel's stage), the transfer, the tens wheel's axis direction
    ``angle`` (rad) and the strokes the report counts."""

    ratchet: Ratchet
    transfer: Transfer
    angle: float
    strokes: int

    @property
    def index(self) -> float:
        """The units wheel's turn a stroke (rad)."""
        return self.ratchet.teeth_per_stroke * self.ratchet.wheel.pitch

    @property
    def strokes_per_turn(self) -> int:
        """N = teeth / teeth a stroke."""
        return self.ratchet.wheel.teeth // self.ratchet.teeth_per_stroke

    def count(self, strokes: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The lever's angle, the units wheel's counter-clockwise turn and the tens wheel's clockwise turn (rad) at
        ``strokes`` (strokes from rest, the fraction a stroke's progress)."""
        lever, units = stroke_turns(strokes, self.index, self.ratchet.swing)
        return lever, units, self.transfer.tens_turn(units)

    def window(self) -> tuple[float, float]:
        """The units wheel's turn (rad, within its turn) over which the tens wheel turns: [2 pi - w - lead,
        2 pi - lead]."""
        t = self.transfer
        return 2 * math.pi - t.window - t.lead, 2 * math.pi - t.lead


def counter_report(table: CounterTable, counter: Counter, angle: float | None) -> dict[str, Any]:
    """The report's section (mm and degrees): the ratchet's, the transfer and the count over the strokes."""
    report = ratchet_report(table, counter.ratchet, angle)
    t = counter.transfer
    n = counter.strokes_per_turn
    k = np.arange(counter.strokes + 1, dtype=float)
    _, units, tens = counter.count(k)
    start, end = counter.window()
    index = counter.index
    moving = [s + 1 for s in range(n) if s * index < end and (s + 1) * index > start]
    report["transfer"] = {
        "slots": t.slots, "centre_distance_mm": t.centre_distance, "pin_radius_mm": num(t.pin_radius),
        "step_deg": num(math.degrees(t.step)), "window_deg": num(math.degrees(t.window)),
        "units_window_deg": [num(math.degrees(start)), num(math.degrees(end))], "lead_deg": num(math.degrees(t.lead)),
        "strokes_turning_tens": moving, "angle_deg": table.transfer.angle}
    report["count"] = {
        "strokes_per_turn": n, "strokes": counter.strokes,
        "units_index": [round(float(u) / index) % n for u in units],
        "tens_index": [math.floor(float(v) / t.step + 1e-9) % t.slots for v in tens],
        "units_deg": [num(math.degrees(u)) for u in units], "tens_deg": [num(math.degrees(v)) for v in tens]}
    report["tens_rpm"] = num(table.rpm / (n * t.slots))
    if angle is not None:                       # the lever's angle on the first stroke going out (checked above)
        turned = float(driven(np.array(math.radians(angle)), index, counter.ratchet.swing))
        report["positions"] = {"lever_deg": num(angle), "wheel_deg": num(math.degrees(turned)),
                               "teeth_passed": math.floor(turned / counter.ratchet.wheel.pitch + 1e-9),
                               "tens_deg": num(math.degrees(float(t.tens_turn(np.array([turned]))[0])))}
    return report


def count_figure(name: str, counter: Counter) -> Any:
    """Both wheels' turns (degrees) over the strokes the report counts, the tens wheel's window shaded."""
    from camgen.core.figures import figure

    k = np.linspace(0.0, counter.strokes, min(200 * counter.strokes, FIGURE_SAMPLES) + 1)
    _, units, tens = counter.count(k)
    fig = figure(9, 4.5)
    ax = fig.subplots()
    ax.plot(k, np.degrees(units), label="units wheel (counter-clockwise)")
    ax.plot(k, np.degrees(tens) * counter.strokes_per_turn, label="tens wheel x strokes a turn (clockwise)")
    moving = np.flatnonzero(np.diff(tens) > 0)
    if len(moving):
        ax.scatter(k[moving], np.degrees(tens[moving]) * counter.strokes_per_turn, s=2, color="C3",
                   label="tens wheel turning")
    ax.set_xlabel("strokes of the lever")
    ax.set_ylabel("turn from rest (degrees)")
    ax.set_title(f"{name}: the units and tens wheels over {counter.strokes} strokes")
    ax.legend(loc="upper left")
    ax.grid(True, alpha=0.3)
    return fig


def geneva_step(counter: Counter, stock: Stock, clearance: float) -> GenevaStep:
    """The Geneva step's parts for the stock's pin: slots the hole wide, the disc a less the slot's width."""
    h = stock.hole / 2
    return GenevaStep(counter.transfer, h, counter.transfer.pin_radius - 2 * h, clearance)


def _check_geneva(counter: Counter, step: GenevaStep, stock: Stock) -> tuple[float, float]:
    """Refuse a Geneva step that cannot be drawn, pinned or locked; its cutout's radius and half-angle (mm, rad)."""
    t, wheel = counter.transfer, counter.ratchet.wheel
    hole = stock.hole
    if not t.pin_radius + hole / 2 + WALL_MM <= wheel.root_radius:
        raise DesignError(f"linkage.transfer.centre_distance: the transfer pin's hole ({hole:g} mm) at "
                          f"{t.pin_radius:.6g} mm leaves less than {WALL_MM:g} mm inside the units wheel's root "
                          f"circle ({wheel.root_radius:.6g} mm)")
    if not step.lock_radius >= 2 * hole + 2 * WALL_MM:
        raise DesignError(f"linkage.transfer.centre_distance: the locking disc ({step.lock_radius:.4g} mm: the pin's "
                          f"circle less the slot's width) needs at least {2 * hole + 2 * WALL_MM:g} mm for its axle "
                          "and dowel; give the tens wheel a larger centre distance")
    if not step.land > 0:
        raise DesignError("linkage.transfer.slots: the locking arcs leave no rim between the slots; give fewer slots "
                          "or a larger centre distance")
    cutout = step.cutout_radius()
    c, rl = t.centre_distance, step.lock_radius
    eta = math.acos(min(1.0, (rl * rl + c * c - cutout * cutout) / (2 * rl * c)))
    if not eta < t.window / 2 + t.lead:
        raise DesignError(f"linkage.lever.swing: the locking disc's cutout ({math.degrees(eta):.4g} degrees either "
                          "side of the pin) still faces the tens wheel at rest: it would not hold it; give the "
                          "lever a larger index")
    return cutout, eta


def counter_layout(counter: Counter, table: CounterTable, stock: Stock, width: float) -> Layout:
    """The parts (see the module's notes) over a turn of the units wheel and at rest, in the transfer and carried."""
    from linkgen.mechanisms.ratchet import ratchet_layout
    from linkgen.mechanisms.shaped import ShapedPart

    base = ratchet_layout(counter.ratchet, table.pawl.spring, stock, width)
    step = geneva_step(counter, stock, table.transfer.clearance)
    cutout, _ = _check_geneva(counter, step, stock)
    t = counter.transfer
    half = width / 2
    o2 = t.centre_distance * np.array([math.cos(counter.angle), math.sin(counter.angle)])
    parts = {p.name: p for p in base.parts}
    ground = parts["ground"]
    pivot, post = ground.centres[1], ground.centres[2]
    for name, point in (("pivot", pivot), ("spring post", post)):
        gap = float(np.hypot(*(point - o2))) - step.rim_radius - stock.hole / 2
        if gap < table.transfer.clearance:
            raise DesignError(f"linkage.transfer.angle: the tens wheel ({step.rim_radius:.4g} mm over its slots) "
                              f"reaches the pawl's {name}, whose pin passes its layer; turn it away from the pawl")
    pin = t.pin(np.zeros(1), counter.angle)[0]
    # at mid-transfer the tens wheel's axis stands on the pin's line: in the units wheel's frame, the pin's direction
    direction = math.atan2(pin[1], pin[0])
    dowel = 0.5 * step.lock_radius * np.array([math.cos(direction + math.pi), math.sin(direction + math.pi)])
    wheel = parts["wheel"]
    assert isinstance(wheel, ShapedPart) and wheel.shape is not None
    new = (
        LinkPart("ground", np.vstack([ground.centres, o2]), half, stock, moving=False),
        ShapedPart("wheel", np.array([[0.0, 0.0], pin, dowel]), half, stock, shape=wheel.shape),
        *(parts[name] for name in ("pawl", "lever", "lever-pawl")),
        ShapedPart("lock-disc", np.array([[0.0, 0.0], dowel]), half, stock, shape=step.disc(cutout, direction)),
        ShapedPart("tens-wheel", np.zeros((1, 2)), half, stock, shape=step.wheel()))
    layers = {"ground": 0, "lock-disc": 1, "tens-wheel": 1, "wheel": 2, "pawl": 2, "lever-pawl": 2, "lever": 3}
    start, end = counter.window()
    n = counter.strokes_per_turn
    sweep_strokes = np.linspace(0.0, n, 24 * n + 1)
    positions = (("rest", 0.0), ("transfer", (start + end) / 2), ("carried", 2 * math.pi))
    drive_pivot = parts["lever"].centres[1]

    def placed(strokes: np.ndarray | None, units_turns: np.ndarray | None = None) -> Placement:
        if strokes is not None:
            lever, units, tens = counter.count(strokes)
        else:
            assert units_turns is not None
            units, tens = units_turns, t.tens_turn(units_turns)
            driven = units - counter.index * np.floor(units / counter.index + 1e-9)     # into its stroke's index
            lever = np.where(driven > 0, driven + counter.ratchet.swing - counter.index, 0.0)
        return _placement(lever, units, tens, pivot, drive_pivot, o2, counter, dowel)

    poses = tuple(placed(None, np.array([u])) for _, u in positions)
    return Layout(new, placed(sweep_strokes), positions, poses, (), layers)


def _placement(lever: np.ndarray, units: np.ndarray, tens: np.ndarray, pivot: np.ndarray, drive_pivot: np.ndarray,
               o2: np.ndarray, counter: Counter, dowel: np.ndarray) -> Placement:
    """The parts at the lever's angles, the units wheel's and the tens wheel's turns (rad; each part drawn in its
    own frame: the units wheel's about its axis at rest, the tens wheel's about its own axis, +X to the units
    wheel's axis between two slots)."""
    n = len(units)
    zero, origin = np.zeros(n), np.zeros((n, 2))
    angles = {"ground": zero, "pawl": zero, "wheel": units, "lock-disc": units, "lever": lever, "lever-pawl": lever,
              "tens-wheel": counter.angle + math.pi - tens}
    origins = {name: origin for name in angles} | {"tens-wheel": np.tile(o2, (n, 1))}

    def turned(point: np.ndarray, by: np.ndarray) -> np.ndarray:
        c, s = np.cos(by), np.sin(by)
        return np.column_stack([c * point[0] - s * point[1], s * point[0] + c * point[1]])

    joints: dict[str, tuple[tuple[str, str], np.ndarray]] = {
        "O": (("ground", "wheel"), origin), "OD": (("lock-disc", "wheel"), origin.copy()),
        "OL": (("wheel", "lever"), origin.copy()), "P": (("ground", "pawl"), np.tile(pivot, (n, 1))),
        "D": (("lever", "lever-pawl"), turned(drive_pivot, lever)),
        "Q": (("ground", "tens-wheel"), np.tile(o2, (n, 1))),
        "K": (("lock-disc", "wheel"), turned(dowel, units)),
        "T": (("tens-wheel", "wheel"), counter.transfer.pin(units, counter.angle))}
    return Placement(angles, origins, joints)


def counter_drawing(counter: Counter, table: CounterTable, width: float) -> Drawing:
    """The ratchet's drawing (the wheel, the pawl, the face's normal and the friction cone) with the transfer's
    pin circle, the tens wheel and the locking disc at rest, their parts' slots the pawl's width wide."""
    from camgen.core.parts import Drawing, preview_stroke
    from camgen.core.shapes import Circle, Contour

    base = ratchet_drawing(counter.ratchet, width)
    t = counter.transfer
    pin = t.pin(np.zeros(1), counter.angle)[0]
    direction = math.atan2(pin[1], pin[0])
    o2 = t.centre_distance * np.array([math.cos(counter.angle), math.sin(counter.angle)])
    items = [*base.items, ("pin circle", Circle((0.0, 0.0), t.pin_radius)),
             ("pivots", Circle((float(o2[0]), float(o2[1])), width / 4)),
             ("pin", Circle((float(pin[0]), float(pin[1])), width / 4))]
    # without [parts], slots half the drawing's width wide, or as wide as the wheel leaves room for
    root = counter.ratchet.wheel.root_radius
    hole = min(width / 2, (t.pin_radius - 2 * WALL_MM) / 3, 2 * (root - t.pin_radius - WALL_MM))
    stock = Stock(hole, 1.0, base.tolerance)
    step = geneva_step(counter, stock, table.transfer.clearance)
    try:
        if not hole > 0:
            raise DesignError("no room for the slots")
        cutout, _ = _check_geneva(counter, step, stock)
    except DesignError:             # no room for drawn slots: the pin's circle and the axes only
        return Drawing(tuple(items), base.tolerance, stroke=preview_stroke(items))
    vertices, bulges = step.wheel()
    spin = counter.angle + math.pi
    c, s = math.cos(spin), math.sin(spin)
    wheel = vertices @ np.array([[c, s], [-s, c]]) + o2
    items += [("tens wheel", Contour(wheel, bulges)), ("locking disc", Contour(*step.disc(cutout, direction)))]
    return Drawing(tuple(items), base.tolerance, stroke=preview_stroke(items))


@dataclass(frozen=True)
class CounterMechanism:
    """The counter (:class:`linkgen.mechanisms.Mechanism`)."""

    table: type[Model] = CounterTable

    @property
    def types(self) -> tuple[str, ...]:
        return types_of(self.table)

    def build(self, table: CounterTable) -> Counter:
        ratchet = Ratchet(table.holding_pawl, table.friction, math.radians(table.lever.swing), table.lever.length)
        strokes = table.strokes if table.strokes is not None else 3 * (table.teeth // ratchet.teeth_per_stroke)
        return Counter(ratchet, table.geneva, math.radians(table.transfer.angle), strokes)

    def report(self, table: CounterTable, kinematics: Counter, angle: float | None, method: str) -> dict[str, Any]:
        return counter_report(table, kinematics, angle)

    def figures(self, name: str, table: CounterTable, kinematics: Counter) -> tuple[Figure, ...]:
        """The two wheels over the strokes, and the wheels at rest with the pawl's friction cone."""
        def draw() -> Any:
            from camgen.core.figures import drawing_figure

            return drawing_figure(counter_drawing(kinematics, table, _width(table)),
                                  f"{name}: the counter at rest, the pawl's face normal and friction cone")

        return (("count", lambda: count_figure(name, kinematics)), ("counter", draw))

    def layout(self, table: CounterTable, kinematics: Counter, parts: PartsTable) -> Layout:
        return counter_layout(kinematics, table, Stock.of(parts), parts.width)

    def family_row(self, table: CounterTable, kinematics: Counter, report: dict[str, Any]) -> dict[str, Any]:
        return {"strokes_per_turn": report["count"]["strokes_per_turn"], "slots": report["transfer"]["slots"]}

    def sketch(self, table: CounterTable, kinematics: Counter) -> Drawing | None:
        return counter_drawing(kinematics, table, _width(table))


def _width(table: CounterTable) -> float:
    """The parts' width in a drawing without parts: as the ratchet's."""
    return 1.5 * table.depth


REGISTER = (CounterMechanism(),)
