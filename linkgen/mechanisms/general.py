"""``type = "linkage"``: any planar linkage drawn as joints, links and sliders, solved dyad by dyad.

The ``[linkage]`` table::

    type = "linkage"
    ground = ["O2", "O4"]                      # the joints fixed to the frame
    input = { link = "crank", pivot = "O2" }   # or { slider = "ram" }; a list for two inputs
    tracers = ["P"]                            # points whose paths are drawn and reported
    [linkage.joints]                           # the drawing: every joint (and tracer point) in mm
    O2 = [0, 0]
    ...
    [linkage.links]                            # each moving link and the joints it holds
    crank = ["O2", "A"]
    coupler = ["A", "B", "P"]                  # a plate: three joints
    [linkage.sliders.ram]                      # a prismatic joint: C slides along a guide of the ground at 0 deg
    point = "C"
    guide = "ground"
    angle = 0

Gears are joints too: ``[linkage.gears.NAME]`` (a gear on a link meshing with one on another) and
``[linkage.racks.NAME]`` (a rack on a slider meshing with a pinion), see :mod:`linkgen.mechanisms.gearjoints`.

The input's value is the crank's direction in degrees (counter-clockwise from +X, the
drawing's frame) or the slider's travel in mm from the drawing. The report gives every
angle in degrees, lengths in mm, speeds at the table's ``rpm`` (or ``speed`` mm/s for a
slide input); see :mod:`linkgen.kinematics.linkage` for the frames and branches.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field, field_validator, model_validator

from camgen.core.errors import SpecError
from camgen.core.parts import Drawing
from camgen.core.shapes import Polyline
from camgen.core.spec import MAX_LENGTH_MM, Model, unit
from linkgen import plots
from linkgen.kinematics import linkage_circuit, motion
from linkgen.kinematics.groups import GROUP_KINDS
from linkgen.kinematics.linkage import Linkage, Solution
from linkgen.kinematics.structure import (GROUND, DyadStep, FixedStep, GearStep, GroupStep, Input, InputStep, Slider,
                                          Structure, make_structure)
from linkgen.mechanisms import gearjoints
from linkgen.mechanisms.common import Figure, num, omega, rpm
from linkgen.mechanisms.gearjoints import GearJointTable, RackJointTable
from linkgen.parts import SWEEP, Layout, LinkPart, Placement, Stock

if TYPE_CHECKING:
    from linkgen.spec import PartsTable

NAME = r"^[A-Za-z][A-Za-z0-9_]{0,31}$"
#: transmission angles (degrees) usually kept for good force transmission
TRANSMISSION_BAND = (40.0, 140.0)
#: how closely (mm) a redundant constraint must hold over the motion for the linkage to count as paradoxical
PARADOX_TOL_MM = 1e-7
TWO_PI = 2 * math.pi

CONVENTIONS = ("the drawing's frame: x, y in mm; angles in degrees counter-clockwise from +X; a crank input's value "
               "is its direction from its pivot, a slide input's its travel (mm) from the drawing; link angles are "
               "turns from the drawing; speeds per second at the template's rpm")


class SliderTable(Model):
    """A prismatic joint: ``point`` moves along a straight guide of ``guide`` drawn through it at ``angle``."""

    point: str = Field(description="the joint that slides")
    guide: str = Field(GROUND, description="the link carrying the guide")
    angle: float = Field(ge=-360, le=360, description="the guide's direction in the drawing, counter-clockwise from "
                                                      "+X", json_schema_extra=unit("degrees"))
    link: str | None = Field(None, description="the sliding link (keeps its angle to the guide); else a block "
                                               "named after the slider pivots on the point")


class InputTable(Model):
    """An input: a link turned about a pivot (``link``, ``pivot``, ``relative_to``) or a slider moved
    (``slider``); ``range`` (degrees or mm) limits the motion analysed."""

    link: str | None = Field(None, description="the link the input turns")
    pivot: str | None = Field(None, description="the joint it turns about")
    relative_to: str = Field(GROUND, description="the link its angle is measured from")
    slider: str | None = Field(None, description="the slider the input moves")
    range: tuple[float, float] | None = Field(None, description="input values analysed: from, to (degrees or mm)")

    @model_validator(mode="after")
    def _one_kind(self) -> InputTable:
        if self.slider is None and (self.link is None or self.pivot is None):
            raise ValueError("give link and pivot (a crank) or slider (a slide input)")
        if self.slider is not None and self.link is not None:
            raise ValueError("give link and pivot, or slider, not both")
        if self.range is not None and not (all(math.isfinite(v) and abs(v) <= 1e6 for v in self.range)
                                           and self.range[0] < self.range[1]):
            raise ValueError("range: must be two finite numbers, from < to")
        return self


class LinkageTable(Model):
    """``[linkage]`` of any planar linkage: the drawing (joints), links, sliders, ground joints, input(s),
    tracers."""

    type: Literal["linkage"]
    joints: dict[str, tuple[float, float]] = Field(description="each joint's drawn position",
                                                   json_schema_extra=unit("mm"))
    links: dict[str, tuple[str, ...]] = Field(description="each moving link and the joints it holds")
    ground: tuple[str, ...] = Field(min_length=1, description="the joints fixed to the frame")
    sliders: dict[str, SliderTable] = Field(default_factory=dict, description="prismatic joints")
    input: InputTable | tuple[InputTable, ...] = Field(description="what drives the linkage")
    tracers: tuple[str, ...] = Field((), description="points whose paths are drawn and reported")
    lengths: dict[str, float] = Field(default_factory=dict, description="checks: 'A-B' = the distance the drawing "
                                                                        "must show", json_schema_extra=unit("mm"))
    gears: dict[str, GearJointTable] = Field(default_factory=dict, max_length=gearjoints.MAX_PAIRS,
                                             description="gear pairs: a gear fixed to a link about one of its joints "
                                                         "meshing with a gear on another link (at most 50)")
    racks: dict[str, RackJointTable] = Field(default_factory=dict, max_length=gearjoints.MAX_PAIRS,
                                             description="racks: a rack on a slider's sliding link meshing with a "
                                                         "pinion on a link turning about a joint of its guide (at "
                                                         "most 50)")
    rpm: float = rpm()

    @field_validator("joints")
    @classmethod
    def _joints(cls, joints: dict[str, tuple[float, float]]) -> dict[str, tuple[float, float]]:
        if len(joints) > 200:
            raise ValueError("at most 200 joints")
        for name, (x, y) in joints.items():
            _name(name, "joints")
            if not (abs(x) <= MAX_LENGTH_MM and abs(y) <= MAX_LENGTH_MM):
                raise ValueError(f"{name}: must lie within {MAX_LENGTH_MM:g} mm of the origin (got [{x:g}, {y:g}])")
        return joints

    @field_validator("links")
    @classmethod
    def _links(cls, links: dict[str, tuple[str, ...]]) -> dict[str, tuple[str, ...]]:
        if not links or len(links) > 100:
            raise ValueError("give 1 to 100 moving links")
        for name in links:
            _name(name, "links")
        return links

    @property
    def inputs(self) -> tuple[InputTable, ...]:
        return self.input if isinstance(self.input, tuple) else (self.input,)

    def lengths_mm(self) -> dict[str, dict[str, float]]:
        """Each link's joint-to-joint distances in the drawing (mm), keyed 'A-B'."""
        out = {}
        for link, pts in self.links.items():
            out[link] = {f"{a}-{b}": round(math.dist(self.joints[a], self.joints[b]), 9)
                         for i, a in enumerate(pts) for b in pts[i + 1:] if a in self.joints and b in self.joints}
        return out


def _name(name: str, where: str) -> None:
    import re

    if not re.match(NAME, name):
        raise ValueError(f"{name!r}: a name is a letter then letters, digits or _ (at most 32)")


def table_of(s: Structure, tracers: tuple[str, ...] = ()) -> LinkageTable:
    """The ``[linkage]`` table that draws structure ``s`` (for mechanisms cut through the general parts layer)."""
    blocks = {sl.name for sl in s.sliders if sl.link is None}
    links = {b: pts for b, pts in s.bodies.items() if b != GROUND and b not in blocks}
    sliders = {sl.name: {"point": sl.point, "guide": sl.guide, "angle": math.degrees(sl.angle),
                         **({"link": sl.link} if sl.link else {})} for sl in s.sliders}
    inputs = [{"slider": i.slider} if i.kind == "slide" else
              {"link": i.link, "pivot": i.pivot, "relative_to": i.relative_to} for i in s.inputs]
    return LinkageTable.model_validate({"type": "linkage", "joints": dict(s.points), "links": links,
                                        "ground": s.bodies[GROUND], "sliders": sliders,
                                        "input": inputs[0] if len(inputs) == 1 else inputs, "tracers": tracers})


def analysis_of(s: Structure, tracers: tuple[str, ...] = ()) -> Analysis:
    """The analysis of a structure drawn by another mechanism."""
    return Analysis(table_of(s, tracers), Linkage.of(s))


def _input(table: InputTable) -> Input:
    """The kinematic input an ``[[linkage.inputs]]`` table gives: a slide of its slider, else a crank (its
    validator has made sure a crank names its link and pivot)."""
    if table.slider is not None:
        return Input("slide", slider=table.slider)
    if table.link is None or table.pivot is None:
        raise SpecError("give link and pivot (a crank) or slider (a slide input)", "linkage.inputs")
    return Input("crank", table.link, table.pivot, table.relative_to)


def structure_of(table: LinkageTable) -> Any:
    """The kinematic structure a ``[linkage]`` table draws (a :class:`SpecError` naming the field otherwise)."""
    sliders = tuple(Slider(name, t.point, t.guide, math.radians(t.angle), t.link) for name, t in table.sliders.items())
    inputs = tuple(_input(i) for i in table.inputs)
    s = make_structure(dict(table.joints), dict(table.links), tuple(table.ground), sliders, inputs,
                       gearjoints.gears_of(table.gears), gearjoints.racks_of(table.racks, table.joints, table.sliders))
    for key, want in table.lengths.items():
        a, sep, b = key.partition("-")
        if not sep or a not in s.points or b not in s.points:
            raise SpecError("a check names two joints as 'A-B'", f"linkage.lengths.{key}")
        got = math.dist(s.points[a], s.points[b])
        if abs(got - want) > 1e-6 * max(1.0, want):
            raise SpecError(f"the drawing puts {a} and {b} {got:.6f} mm apart, not {want:g} mm",
                            f"linkage.lengths.{key}")
    for t in table.tracers:
        if t not in s.points:
            raise SpecError(f"no joint {t!r}", "linkage.tracers")
    return s


@dataclass(frozen=True)
class Analysis:
    """A general linkage with what its report and parts read: the solved linkage, its sweep over the motion
    analysed on the drawing's branches (input values in the input's unit: rad or mm), the reachable ranges, the
    circuit the drawing lies on, toggles, and each output's motion over the circuit."""

    table: LinkageTable
    linkage: Linkage

    @property
    def crank(self) -> bool:
        return self.linkage.structure.inputs[0].kind == "crank"

    @cached_property
    def ranges(self) -> tuple[tuple[float, float], ...] | None:
        return self.linkage.ranges if len(self.table.inputs) == 1 else None

    @cached_property
    def span(self) -> np.ndarray:
        """The input values analysed (k, SWEEP): the table's range, else the reachable range holding the drawing,
        else a full turn from the drawing. A range that ends where a dyad of two slides runs away (its guides
        parallel, its joint at infinity) is refused unless the table gives one."""
        rows = []
        for i, inp in enumerate(self.table.inputs):
            if inp.range is not None:
                lo, hi = (math.radians(v) for v in inp.range) if inp.slider is None else inp.range
            elif len(self.table.inputs) > 1:
                raise SpecError("with more than one input, give each input its range = [from, to]",
                                f"linkage.input[{i}].range")
            elif self.ranges is None:
                lo, hi = motion.span(self.linkage)
            else:
                lo, hi = self.ranges[0]
                _refuse_runaway(self, lo, hi)
            rows.append(np.linspace(lo, hi, SWEEP))
        return np.array(rows)

    @cached_property
    def sweep(self) -> Solution:
        return self.linkage.solve(self.span)

    @cached_property
    def toggles(self) -> tuple[motion.Toggle, ...]:
        return motion.toggles(self.linkage) if len(self.table.inputs) == 1 else ()

    @cached_property
    def circuit(self) -> linkage_circuit.Circuit | None:
        """The circuit the motion analysed runs on (one input): the drawing's (see
        :mod:`linkgen.kinematics.linkage_circuit`), or the table's range on the drawing's branches; None with more
        inputs."""
        if len(self.table.inputs) != 1:
            return None
        lo, hi = float(self.span[0, 0]), float(self.span[0, -1])
        if self.table.inputs[0].range is not None:
            return linkage_circuit.Circuit((linkage_circuit.Piece(self.linkage, lo, hi, True, ()),), False, False, ())
        return linkage_circuit.circuit(self.linkage)

    @cached_property
    def travel(self) -> Solution:
        """The linkage over the whole circuit, piece after piece (the parts' slots and layers are made for it): the
        sweep itself where the circuit is that one piece."""
        if self.circuit is None or len(self.circuit.pieces) == 1:
            return self.sweep
        return linkage_circuit.sweep_over(self.circuit, SWEEP)

    @cached_property
    def outputs(self) -> dict[str, linkage_circuit.OutputMotion]:
        """The motion of each rocker and ground slider over the circuit (one input; none with more)."""
        if self.circuit is None:
            return {}
        outputs = motion.rockers(self.linkage) + motion.ground_sliders(self.linkage)
        return linkage_circuit.outputs_over(self.circuit, outputs)

    def shown(self, value: float) -> float:
        """An input value in the report's unit (degrees in [0, 360) or mm)."""
        return round(math.degrees(value) % 360.0, 9) % 360.0 if self.crank else round(value, 9)


def _refuse_runaway(a: Analysis, lo: float, hi: float) -> None:
    """Refuse a range on the drawing's branches that ends where a dyad of two slides runs away: its joint goes to
    infinity there, so no stroke or swing is finite; name the input and the range to give instead."""
    stops = motion.stopping_dyad(a.linkage, np.array([lo, hi]))
    ends = [(v, d) for v, (kind, d) in zip((lo, hi), stops, strict=True)
            if kind == "runaway" and not motion.bounded(a.linkage, v)]
    if not ends:
        return
    value, d = ends[0]
    step = [s for s in a.linkage.plan.steps if isinstance(s, DyadStep)][d]      # the d-th dyad, in solve order
    unit = "degrees" if a.crank else "mm"
    shown = [a.shown(v) for v in (lo, hi)]
    raise SpecError(f"at input {a.shown(value):.6g} {unit} the guides of the {step.kind} dyad of {step.bodies[0]} and "
                    f"{step.bodies[1]} turn parallel, so {step.joint} runs to infinity; give range = [from, to] "
                    f"strictly between {shown[0]:.6g} and {shown[1]:.6g} {unit}", "linkage.input")


def _paradoxes(a: Analysis) -> list[str]:
    """What the redundant constraints say: each held over the whole motion (the solver refuses the linkage
    otherwise), so the linkage is paradoxical."""
    notes = []
    for r in a.linkage.plan.redundant:
        if r.slider:
            notes.append(f"paradoxical: Gruebler gives mobility {a.linkage.plan.mobility}, yet slider {r.name} keeps "
                         f"{a.linkage.structure.slider_by_name[r.name].point} on its guide over the whole motion, so "
                         "it moves")
        else:
            notes.append(f"paradoxical: Gruebler gives mobility {a.linkage.plan.mobility}, yet links {r.bodies[0]} "
                         f"and {r.bodies[1]} keep joint {r.name} together over the whole motion (parallel or equal "
                         "links), so it moves")
    return notes


def _turned(d: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Vector(s) d turned counter-clockwise by ``angle`` (rad, (n,)): (n, 2)."""
    c, s = np.cos(angle), np.sin(angle)
    d = np.broadcast_to(d, (len(angle), 2))
    return np.column_stack([c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]])


def steps_report(a: Analysis) -> list[dict[str, Any]]:
    out: list[dict[str, Any]] = []
    for step in a.linkage.plan.steps:
        if isinstance(step, InputStep):
            out.append({"step": "input", "link": step.body})
        elif isinstance(step, DyadStep):
            out.append({"step": step.kind, "links": list(step.bodies), "joint": step.joint})
        elif isinstance(step, FixedStep):
            out.append({"step": "fixed", "link": step.body})
        elif isinstance(step, GroupStep):
            out.append({"step": step.kind, "links": list(step.bodies), "joints": list(step.joints),
                        "method": "Newton's method continued along the input from the drawing"})
        elif isinstance(step, GearStep):
            out.append({"step": step.kind, "link": step.body, "from": step.partner, "pair": step.pair})
    return out


def general_report(table: LinkageTable, a: Analysis, angle: float | None) -> dict[str, Any]:
    """Mobility, solve order, reachable input, toggles, transmission angles, outputs' limit positions and time
    ratios, tracer paths; with ``angle`` (the input's, degrees or mm) every joint's position there."""
    notes = _paradoxes(a)
    unit_name = "deg" if a.crank else "mm"
    ranges = a.ranges
    sweep = a.sweep
    report: dict[str, Any] = {
        "conventions": CONVENTIONS,
        "mobility": a.linkage.plan.mobility, "inputs": [_input_report(i) for i in table.inputs],
        "solve_order": steps_report(a),
        **({"higher_pairs": gearjoints.pairs_report(a.linkage)} if a.linkage.structure.pairs else {}),
        f"input_range_{unit_name}": None if ranges is None else [[a.shown(lo) if a.crank else lo, a.shown(hi)]
                                                                   for lo, hi in ranges],
        f"analysed_{unit_name}": [round(math.degrees(v), 9) if a.crank else round(v, 9)
                                  for v in (float(a.span[0, 0]), float(a.span[0, -1]))],
        "toggles": [{"kind": t.kind, f"input_{unit_name}": a.shown(t.value), "links": list(t.bodies),
                     "joint": t.joint} for t in a.toggles],
    }
    circuit = a.circuit
    if circuit is not None and (ranges is not None or len(circuit.pieces) > 1) and table.inputs[0].range is None:
        report["circuit"] = _circuit_report(a, circuit)
    dyads = []
    if circuit is not None:
        extremes = [row[:4] for row in linkage_circuit.transmission_over(circuit)]
    else:
        extremes = [(float(np.min(d.transmission)), float(sweep.inputs[0, np.argmin(d.transmission)]),
                     float(np.max(d.transmission)), float(sweep.inputs[0, np.argmax(d.transmission)]))
                    for d in sweep.dyads]
    for d, (gmin, at_min, gmax, at_max) in zip(sweep.dyads, extremes, strict=True):
        if d.kind in GROUP_KINDS:
            # a group has no one transmission angle: its Jacobian's conditioning (sine of the angle given), 0 at a
            # toggle; where its flat extremes lie is left out (rounding moves them)
            dyads.append({"kind": d.kind, "links": list(d.bodies), "joint": d.joint,
                          "conditioning_min": num(math.sin(gmin)), "conditioning_max": num(math.sin(gmax))})
            continue
        dyads.append({"kind": d.kind, "links": list(d.bodies), "joint": d.joint,
                      "transmission_min_deg": num(math.degrees(gmin)),
                      f"transmission_min_at_{unit_name}": a.shown(at_min),
                      "transmission_max_deg": num(math.degrees(gmax)),
                      f"transmission_max_at_{unit_name}": a.shown(at_max)})
    report["dyads"] = dyads
    outputs = {name: _output_report(a, name, om) for name, om in a.outputs.items()}
    for name, sl in a.linkage.structure.slider_by_name.items():
        if sl.guide == GROUND and name not in outputs:
            # an input's slider travels its range over the circuit; with more inputs, over the sweep
            if circuit is not None:
                ends = [min(p.lo for p in circuit.pieces), max(p.hi for p in circuit.pieces)]
            else:
                travel = _travel(a, sl)
                ends = [float(travel.min()), float(travel.max())]
            outputs[name] = {"travel_mm": [num(ends[0]), num(ends[1])], "stroke_mm": num(ends[1] - ends[0])}
    report["outputs"] = outputs
    report["tracers"] = {t: dict(zip(("x_mm", "y_mm"), ([num(v) for v in axis] for axis in extent),
                                     strict=True)) for t, extent in _extents(a, table.tracers).items()}
    warnings = list(notes)
    for d in report["dyads"]:
        if d["kind"] in GROUP_KINDS:
            continue
        lo_t, hi_t = d["transmission_min_deg"], d["transmission_max_deg"]
        if d["kind"] == "RRR" and (lo_t < TRANSMISSION_BAND[0] or hi_t > TRANSMISSION_BAND[1]):
            warnings.append(f"dyad {'-'.join(d['links'])} (joint {d['joint']}): transmission angle spans "
                            f"{lo_t:.2f} to {hi_t:.2f} degrees, outside the usual {TRANSMISSION_BAND[0]:g}-"
                            f"{TRANSMISSION_BAND[1]:g} degree band")
        elif d["kind"] != "RRR" and lo_t < TRANSMISSION_BAND[0]:
            warnings.append(f"dyad {'-'.join(d['links'])} (joint {d['joint']}): transmission angle falls to "
                            f"{lo_t:.2f} degrees (below 40)")
    if any(t.kind == "change point" for t in a.toggles):
        warnings.append("change point: a dyad folds flat and can switch branch; guide it through")
    bound = _slide_bound(a)
    if bound is not None:
        report["input_bound_mm"] = num(bound)
        warnings.append(f"no toggle ends the slide's range within {bound:.6g} mm of the drawing "
                        f"({motion.SLIDE_REACH:g} times the drawing's size, {a.linkage.structure.size:.6g} mm): the "
                        "motion is analysed to there; give range = [from, to] for another stretch")
    report["warnings"] = warnings
    if angle is not None:
        report["positions"] = positions(table, a, angle)
    return report


def _extents(a: Analysis, points: tuple[str, ...]) -> dict[str, tuple[tuple[float, float], tuple[float, float]]]:
    """The tracers' x and y ranges (mm): refined over the circuit with one input, sampled with more."""
    if a.circuit is not None:
        return linkage_circuit.extents_over(a.circuit, points) if points else {}
    out = {}
    for point in points:
        p = a.sweep.points[point]
        out[point] = (float(p[:, 0].min()), float(p[:, 0].max())), (float(p[:, 1].min()), float(p[:, 1].max()))
    return out


def _slide_bound(a: Analysis) -> float | None:
    """The searched bound (mm either way of the drawing) where a slide input's range analysed ends without a toggle;
    None where toggles end it (or the table gives the range)."""
    if a.crank or a.circuit is None or a.table.inputs[0].range is not None:
        return None
    ends = [v for p in a.circuit.pieces for v in (p.lo, p.hi)]
    return motion.reach(a.linkage) if any(motion.bounded(a.linkage, v) for v in ends) else None


def _branch(circuit: linkage_circuit.Circuit, piece: int) -> str:
    other = circuit.pieces[piece].other
    return "as drawn" if not other else "other branch at " + ", ".join(other)


def _circuit_report(a: Analysis, circuit: linkage_circuit.Circuit) -> dict[str, Any]:
    """The circuit's pieces (input range and branches; a full turn from its start to its end, unreduced), whether
    it closes, and the ranges of separate circuits."""
    unit = "deg" if a.crank else "mm"

    def shown(v: float) -> float:
        return round(math.degrees(v), 9) if circuit.turns else a.shown(v)

    return {"pieces": [{f"input_{unit}": [shown(p.lo), shown(p.hi)], "branches": _branch(circuit, k)}
                       for k, p in enumerate(circuit.pieces)],
            "closed": circuit.closed,
            f"separate_{unit}": [[a.shown(lo), a.shown(hi)] for lo, hi in circuit.separate]}


def _output_report(a: Analysis, name: str, om: linkage_circuit.OutputMotion) -> dict[str, Any]:
    """A rocker's limit positions, swing and time ratio; a ground slider's limit positions, travel and stroke:
    over the circuit (the branches named where it has more than one piece)."""
    unit = "deg" if a.crank else "mm"
    rocker = name not in a.linkage.structure.slider_by_name
    circuit = a.circuit
    several = circuit is not None and len(circuit.pieces) > 1
    at = []
    for e, k in zip(om.limits, om.pieces, strict=True):
        entry: dict[str, Any] = {f"input_{unit}": a.shown(e.value),
                                 **({"angle_from_drawing_deg": num(math.degrees(e.position))} if rocker else
                                    {"travel_mm": num(e.position)})}
        if several and circuit is not None:
            entry["branches"] = _branch(circuit, k)
        at.append(entry)
    out: dict[str, Any] = {"limit_positions": at}
    if rocker:
        if om.turns:
            out["turns_fully"] = True
        elif om.limits:
            out["swing_deg"] = num(math.degrees(om.travel))
            if several:
                out["swing_between_deg"] = [num(math.degrees(om.least[0])), num(math.degrees(om.greatest[0]))]
    else:
        travel = {"travel_mm": [num(om.least[0]), num(om.greatest[0])], "stroke_mm": num(om.travel)}
    one_turn = circuit is not None and circuit.turns and len(circuit.pieces) == 1
    ratio = motion.time_ratio(a.linkage, om.limits) if one_turn else None
    out["time_ratio"] = None if ratio is None else round(ratio, 12)
    return out if rocker else {**out, **travel}


def _travel(a: Analysis, sl: Slider) -> np.ndarray:
    """A ground slider's travel from the drawing along its guide (mm) over the sweep."""
    u = np.array([math.cos(sl.angle), math.sin(sl.angle)])
    return (a.sweep.points[sl.point] - np.asarray(a.linkage.structure.points[sl.point])) @ u


def _input_report(i: InputTable) -> dict[str, Any]:
    if i.slider is not None:
        return {"slider": i.slider}
    return {"link": i.link, "pivot": i.pivot, "relative_to": i.relative_to}


def positions(table: LinkageTable, a: Analysis, angle: float) -> dict[str, Any]:
    """Every joint's position (mm), velocity (mm/s) and acceleration (mm/s^2) at input ``angle`` (degrees or mm),
    the input turning at the table's rpm; every link's angle, angular velocity and acceleration."""
    if len(table.inputs) != 1:
        raise SpecError("--angle is for linkages with one input", "--angle")
    value = math.radians(angle) if a.crank else angle
    speed = omega(table.rpm) if a.crank else 1.0
    sol = a.linkage.solve(np.array([value]))
    joints = {p: {"x_mm": num(sol.points[p][0, 0]), "y_mm": num(sol.points[p][0, 1]),
                  "v_mm_s": [num(speed * v) for v in sol.velocities[p][0]],
                  "a_mm_s2": [num(speed**2 * v) for v in sol.accelerations[p][0]]} for p in sol.points}
    links = {b: {"angle_from_drawing_deg": num(math.degrees(sol.angles[b][0])),
                 "omega_rad_s": num(speed * sol.omegas[b][0]), "alpha_rad_s2": num(speed**2 * sol.alphas[b][0])}
             for b in sol.angles if b != GROUND}
    return {"input": angle, "joints": joints, "links": links,
            "transmission_deg": [num(math.degrees(d.transmission[0])) for d in sol.dyads],
            "speed": "per second at the input's rpm" if a.crank else "per second at 1 mm/s of the input"}


# ---------------------------------------------------------------------- parts


def _frame(a: Analysis, body: str) -> tuple[np.ndarray, float]:
    """A body's part frame: its first point and the drawn direction (rad) to its second (a block's: the guide's)."""
    s = a.linkage.structure
    pts = s.bodies[body]
    p0 = np.asarray(s.points[pts[0]], dtype=float)
    if len(pts) >= 2:
        d = np.asarray(s.points[pts[1]], dtype=float) - p0
        return p0, math.atan2(d[1], d[0])
    slider = next((sl for sl in s.sliders if sl.body == body), None)
    return p0, 0.0 if slider is None else slider.angle


def _local(points: np.ndarray, p0: np.ndarray, beta: float) -> np.ndarray:
    c, s = math.cos(beta), math.sin(beta)
    d = points - p0
    return np.column_stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]])


def general_parts(a: Analysis, table: PartsTable) -> tuple[LinkPart, ...]:
    """Every body as a part: the ground plate (pivots and guide slots), bars and plates (rounded hulls of their
    joints), sliding links, and blocks (a bar along the guide round their pin)."""
    s = a.linkage.structure
    for name in table.links:
        if name not in s.bodies:
            raise SpecError(f"no link {name!r} in this linkage (links: {', '.join(s.bodies)})", f"parts.links.{name}")
    stock = Stock.of(table)
    sweep = a.travel
    slots: dict[str, list[tuple[np.ndarray, np.ndarray]]] = {b: [] for b in s.bodies}
    for sl in s.sliders:
        # the guide's slot spans the sliding point's travel, seen from the guide (in the drawing's frame)
        first = s.bodies[sl.guide][0]
        drawn = np.asarray(s.points[first]) + _turned(sweep.points[sl.point] - sweep.points[first],
                                                      -sweep.angles[sl.guide])
        u = np.array([math.cos(sl.angle), math.sin(sl.angle)])
        along = (drawn - np.asarray(s.points[sl.point])) @ u
        ends = np.asarray(s.points[sl.point]) + np.outer([along.min(), along.max()], u)
        if along.max() - along.min() > 1e-9:
            p0, beta = _frame(a, sl.guide)
            local = ends if sl.guide == GROUND else _local(ends, p0, beta)
            slots[sl.guide].append((local[0], local[1]))
    parts = []
    for body, pts in s.bodies.items():
        where = np.array([s.points[p] for p in pts], dtype=float)
        if body == GROUND:
            body_pts = [where] + [np.array(e) for e in slots[body]]
            extra = np.vstack(body_pts) if slots[body] else where
            holes = np.array([w for p, w in zip(pts, where, strict=True)
                              if not any(sl.guide == GROUND and sl.point == p for sl in s.sliders)])
            parts.append(LinkPart(GROUND, holes if len(holes) else where[:1], table.width_of(GROUND), stock,
                                  slots=tuple(slots[body]), moving=False, body=extra))
            continue
        p0, beta = _frame(a, body)
        local = _local(where, p0, beta)
        half = table.width_of(body) / 2
        rounded = [np.array([[-2 * half, 0.0], [2 * half, 0.0]])] if len(pts) == 1 else [local]
        outline = np.vstack(rounded + [np.array(e) for e in slots[body]]) if slots[body] or len(pts) == 1 else None
        parts.append(LinkPart(body, local, half, stock, slots=tuple(slots[body]), body=outline))
    return tuple(parts)


def general_placement(a: Analysis, sol: Solution) -> Placement:
    """Where each part sits at each pose of ``sol``, and each pin (joint) with the parts it joins (a slider's pin
    also runs in its guide's slot)."""
    s = a.linkage.structure
    n = sol.inputs.shape[1]
    angles, origins = {}, {}
    for body, pts in s.bodies.items():
        if body == GROUND:
            angles[body], origins[body] = np.zeros(n), np.zeros((n, 2))
            continue
        _, beta = _frame(a, body)
        angles[body] = sol.angles[body] + beta
        origins[body] = sol.points[pts[0]]
    joints = {}
    for point, holders in s.revolutes.items():
        for k in range(1, len(holders)):
            joints[f"{point}#{k}" if k > 1 else point] = ((holders[0], holders[k]), sol.points[point])
    for sl in s.sliders:
        joints[f"{sl.name}-slot"] = ((sl.body, sl.guide), sol.points[sl.point])
    return Placement(angles, origins, joints)


def general_layout(a: Analysis, table: PartsTable) -> Layout:
    """The parts over the motion analysed; the assembly drawn at every toggle and limit position inside it (at
    the drawing when there is none), with the tracers' paths (every moving joint's when there are no tracers)."""
    positions: list[tuple[str, float, Linkage]] = []
    lo, hi = float(a.span[0, 0]), float(a.span[0, -1])

    def inside(v: float) -> bool:
        return any(lo - 1e-9 <= v + k * TWO_PI <= hi + 1e-9 for k in ((-1, 0, 1) if a.crank else (0,)))

    for t in a.toggles:
        if inside(t.value):
            positions.append(("toggle" if t.kind == "limit" else "change-point", t.value, a.linkage))
    pieces = a.circuit.pieces if a.circuit is not None else ()
    for body, om in a.outputs.items():
        positions += [(f"limit-{body}", e.value, pieces[k].linkage) for e, k in zip(om.limits, om.pieces, strict=True)]
    if not positions or len(a.table.inputs) > 1:
        positions = [("drawn", float(a.linkage.drawn_inputs[0]), a.linkage)]
    # in order of the input; positions at the same input to 1e-9 (two limits at one crank angle) by name, so that
    # their order does not hang on the last bits of where each was refined to
    positions.sort(key=lambda p: (round(p[1] * 1e9), p[0]))
    if len(a.table.inputs) > 1:
        poses: tuple[Placement, ...] = (general_placement(a, a.linkage.solve(a.linkage.drawn_inputs[:, None])),)
    else:
        poses = tuple(general_placement(a, linkage.solve(np.array([[v]]))) for _, v, linkage in positions)
    traced = a.table.tracers or tuple(p for p in a.linkage.structure.points
                                      if p not in a.linkage.structure.bodies[GROUND])
    sweep = a.travel
    layout = Layout(general_parts(a, table), general_placement(a, sweep), tuple((k, v) for k, v, _ in positions),
                    poses, tuple(sweep.points[t] for t in traced))
    if a.linkage.structure.pairs:
        from linkgen.mechanisms.gearjointparts import with_gears

        return with_gears(a, table, layout)
    return layout


def general_sketch(a: Analysis) -> Drawing:
    """The linkage as drawn, each link as a closed polygon of its joints, with the tracers' paths."""
    s = a.linkage.structure
    items = []
    for pts in s.bodies.values():
        if len(pts) >= 2:
            xy = np.array([s.points[p] for p in pts] + ([s.points[pts[0]]] if len(pts) > 2 else []), dtype=float)
            items.append(("LINKS", Polyline(xy, np.zeros(len(xy) - 1))))
    for t in a.table.tracers:
        path = a.sweep.points[t]
        items.append(("PATH", Polyline(path, np.zeros(len(path) - 1))))
    return Drawing(tuple(items), 0.01)


def analysis_of_table(table: LinkageTable) -> Analysis:
    """The analysis of a ``[linkage]`` table; its gears' turns per input turn and, where no link carries a pair,
    its centres' distance over the motion checked (a :class:`SpecError` naming the pair otherwise)."""
    s = structure_of(table)
    if s.pairs:
        gearjoints.check_turns(s, table.inputs[0].range)
    analysis = Analysis(table, Linkage.of(s))
    if s.gears:
        gearjoints.check_meshes(analysis.linkage, analysis.travel)
    return analysis


@dataclass(frozen=True)
class GeneralMechanism:
    """``linkage``: any planar linkage of dyads (bars, plates, sliders), one or more inputs."""

    types: tuple[str, ...] = ("linkage",)
    table: type[Model] = LinkageTable

    def build(self, table: LinkageTable) -> Analysis:
        return analysis_of_table(table)

    def report(self, table: LinkageTable, kinematics: Analysis, angle: float | None, method: str) -> dict[str, Any]:
        if method == "newton":
            raise SpecError("the Newton-Raphson table is for four-bars; a general linkage is solved in closed form",
                            "--method")
        return general_report(table, kinematics, angle)

    def figures(self, name: str, table: LinkageTable, kinematics: Analysis) -> tuple[Figure, ...]:
        return (("motion", lambda: plots.linkage_motion_figure(name, kinematics)),
                ("transmission", lambda: plots.linkage_transmission_figure(name, kinematics)))

    def layout(self, table: LinkageTable, kinematics: Analysis, parts: PartsTable) -> Layout:
        return general_layout(kinematics, parts)

    def family_row(self, table: LinkageTable, kinematics: Analysis, report: dict[str, Any]) -> dict[str, Any]:
        traced = table.tracers[0] if table.tracers else next(iter(kinematics.sweep.points))
        return {"thumbnail": kinematics.sweep.points[traced].round(3).tolist(), "thumbnail_kind": "path"}

    def sketch(self, table: LinkageTable, kinematics: Analysis) -> Drawing:
        return general_sketch(kinematics)


REGISTER = (GeneralMechanism(),)
