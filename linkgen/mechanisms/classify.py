"""The course's classification of a mechanism by the motion it transforms (Torfason's classes), from its kinematics.

Each class is earned by a rule on what the kinematics computed, stated with the figures that earned it:

- **oscillator**: the input turns fully and an output link pivoted on the frame swings back and forth (it does
  not turn fully): its swing in degrees;
- **reciprocator**: the input turns fully and a slider on the frame moves back and forth: its stroke in mm;
- **coupling**: the input turns fully and an output turns fully with it (rotation passed on, as a drag link or a
  gear pair does);
- **reversing**: an output turns fully the other way from the input (a mean rate below zero; an external gear
  pair's negative speed ratio);
- **hesitation**: an output stands all but still (within :data:`DWELL_BAND` of its travel) over at least
  :data:`DWELL_INPUT` degrees of the turning input, then moves: a dwell;
- **clamp**: at a slider output's limit position the two links that meet at the pin driving its dyad lie in line
  (within :data:`IN_LINE` degrees), neither the input: a toggle, whose force ratio grows without bound there;
- **straight-line generator**: a traced point on a floating link (neither the input, nor pivoted on the frame, nor
  sliding on it) runs within :data:`STRAIGHT_BAND` of its chord's length of a straight line over at least
  :data:`STRAIGHT_INPUT` degrees of the input, the chord at least :data:`STRAIGHT_CHORD` of the drawing's size;
- **curve generator**: a traced point on a floating link that no straight stretch earns the class above (both
  with an input that turns fully);
- **linear actuator**: a slide input moves an output (a swing or a stroke);
- **indexing**: an output advances a step per stroke of the input and is held between strokes (a ratchet).
- **counter**: a second wheel advances one step a turn of an indexed first wheel and is held between (a counter's
  tens wheel): its strokes a step.

Classes of the list the kinematics cannot tell (fine adjustment) are not given.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkgen.kinematics import motion
from linkgen.kinematics.structure import GROUND, DyadStep, Pin
from linkgen.mechanisms.general import Analysis

#: the classes in the order a report lists them
CLASSES = ("linear actuator", "oscillator", "reciprocator", "coupling", "reversing", "hesitation", "clamp",
           "indexing", "counter", "straight-line generator", "curve generator")
#: a dwell: the output within DWELL_BAND of its travel over at least DWELL_INPUT degrees of input
DWELL_BAND, DWELL_INPUT = 0.005, 30.0
#: links this close to in line (degrees) at a slider's limit make a toggle
IN_LINE = 1.0
#: a straight stretch: within STRAIGHT_BAND of its chord of the best line over at least STRAIGHT_INPUT degrees of
#: input, the chord at least STRAIGHT_CHORD of the drawing's size
STRAIGHT_BAND, STRAIGHT_INPUT, STRAIGHT_CHORD = 0.0025, 90.0, 0.1
#: poses a turn the rules sample
SAMPLES = 720


@dataclass(frozen=True)
class Earned:
    """A class a mechanism earns and the reason, in the report's words with the figures."""

    name: str
    because: str


def report(earned: list[Earned]) -> dict[str, Any]:
    """The report's ``classification`` entry: the classes (in :data:`CLASSES` order, each once) and why."""
    order = sorted(earned, key=lambda e: CLASSES.index(e.name))
    names: list[str] = []
    for e in order:
        if e.name not in names:
            names.append(e.name)
    return {"classes": names, "rules": [{"class": e.name, "because": e.because} for e in order]}


def of_report(kind: str, rep: Mapping[str, Any]) -> list[Earned]:
    """The classes of the mechanisms not drawn as general linkages, from their own kinematic figures: a gear pair
    (its speed ratio), a ratchet (its index per stroke), a counter (its index and its transfer), a gear train (its
    ratio), Oldham's coupling (its speed ratio), the elliptic trammel (its blocks' stroke and its ellipse) and
    Rapson's slide (its crosshead's stroke)."""
    out = []
    if kind == "gear-pair" and rep.get("speed_ratio") is not None:
        out += _geared(float(rep["speed_ratio"]), "the gear", "the pinion", "speed ratio")
    if kind in ("ratchet", "counter") and isinstance(rep.get("lever"), Mapping) and rep.get("holds"):
        lever = rep["lever"]
        wheel = "wheel" if kind == "ratchet" else "units wheel"
        out.append(Earned("indexing", f"each {float(lever['swing_deg']):.6g} degree stroke of the lever advances the "
                                      f"{wheel} {int(lever['teeth_per_stroke'])} tooth (tooth) of "
                                      f"{float(rep['wheel']['pitch_deg']):.6g} degrees, and the pawl holds it "
                                      "between strokes"))
    if kind == "counter" and isinstance(rep.get("count"), Mapping):
        out.append(Earned("counter", f"the tens wheel advances one step of {float(rep['transfer']['step_deg']):.6g} "
                                     f"degrees every {int(rep['count']['strokes_per_turn'])} strokes (a turn of the "
                                     "units wheel), held by its locking disc between"))
    if kind == "gear-train" and rep.get("ratio") is not None:
        out += _geared(float(rep["ratio"]), "the output", "the input", "ratio")
    if kind == "oldham" and rep.get("speed_ratio") is not None:
        ratio, offset = float(rep["speed_ratio"]), float(rep["offset_mm"])
        out.append(Earned("coupling", f"hub 2 turns fully with hub 1 at a speed ratio of {ratio:.6g}, {offset:.6g} mm "
                                      "off its axis"))
    if kind == "trammel" and isinstance(rep.get("ellipse"), Mapping):
        ellipse = rep["ellipse"]
        out.append(Earned("reciprocator", f"the crank turns fully and each block moves back and forth, a stroke of "
                                          f"{float(rep['block_stroke_mm']):.6g} mm"))
        out.append(Earned("curve generator", f"the tracer draws an ellipse of semi-axes "
                                             f"{float(ellipse['semi_axis_x_mm']):.6g} and "
                                             f"{float(ellipse['semi_axis_y_mm']):.6g} mm"))
    if kind == "rapson" and rep.get("stroke_mm"):
        out.append(Earned("linear actuator", f"the crosshead's stroke of {float(rep['stroke_mm']):.6g} mm swings the "
                                             "tiller"))
    return out


def _geared(ratio: float, driven: str, driver: str, word: str) -> list[Earned]:
    """A pair or train of gears: a coupling at its ``ratio`` (output over input speed, named ``word``), reversing
    where the ratio is negative."""
    out = [Earned("coupling", f"{driven} turns fully with {driver} at a {word} of {ratio:.6g}")]
    if ratio < 0:
        out.append(Earned("reversing", f"the {word} {ratio:.6g} is negative: {driven} turns the other way"))
    return out


def of_analysis(a: Analysis) -> list[Earned]:
    """The classes a general linkage (or a mechanism drawn as one) earns over its circuit, one input only."""
    if len(a.linkage.structure.inputs) != 1 or a.circuit is None:
        return []
    lk = a.linkage
    full_turn = a.crank and a.ranges is None
    out: list[Earned] = []
    sol = _sample(a)
    x = sol.inputs[0]
    for name, om in a.outputs.items():
        slider = name in lk.structure.slider_by_name
        if not a.crank and om.travel > 0:
            what = f"a stroke of {om.travel:.6g} mm" if slider else f"a swing of {math.degrees(om.travel):.6g} degrees"
            out.append(Earned("linear actuator", f"the slide input moves {name} through {what}"))
        if not full_turn:
            continue
        if om.turns:
            _, rate, _ = motion.values_of(lk, sol, name)
            out.append(Earned("coupling", f"the input turns fully and {name} turns fully with it"))
            if float(np.mean(rate)) < 0:
                out.append(Earned("reversing", f"{name} turns the other way from the input (mean rate "
                                               f"{float(np.mean(rate)):.6g})"))
            continue
        if slider:
            out.append(Earned("reciprocator", f"the input turns fully and the slider {name} moves back and forth, "
                                              f"a stroke of {om.travel:.6g} mm"))
        else:
            out.append(Earned("oscillator", f"the input turns fully and {name} swings back and forth through "
                                            f"{math.degrees(om.travel):.6g} degrees"))
        dwell = _dwell(lk, sol, name, om.travel)
        if dwell >= DWELL_INPUT:
            out.append(Earned("hesitation", f"{name} stays within {100 * DWELL_BAND:g}% of its travel over "
                                            f"{dwell:.4g} degrees of input (at least {DWELL_INPUT:g}), then moves"))
        if slider:
            out += _clamp(a, name, [e.value for e in om.limits])
    for point in a.table.tracers if full_turn else ():
        if not _floating(a, point):
            continue
        path = sol.points[point][np.isfinite(sol.points[point]).all(axis=1)]
        straight = _straight(path, x, lk.structure.size, full_turn)
        if straight is not None:
            span, dev, chord = straight
            out.append(Earned("straight-line generator", f"tracer {point} stays within {dev:.3g} mm of a straight line "
                                                         f"along {chord:.4g} mm over {span:.4g} degrees of input"))
        else:
            out.append(Earned("curve generator", f"tracer {point} on a floating link traces a curve (no straight "
                                                 f"stretch of {STRAIGHT_INPUT:g} degrees within "
                                                 f"{100 * STRAIGHT_BAND:g}%)"))
    return out


def _sample(a: Analysis) -> Any:
    """The linkage at :data:`SAMPLES` poses over its circuit's first piece (a crank's turn)."""
    piece = a.circuit.pieces[0] if a.circuit is not None else None
    if piece is None:
        return a.sweep
    return piece.linkage.solve(piece.inputs(SAMPLES)[None, :], strict=False)


def _dwell(lk: Any, sol: Any, name: str, travel: float) -> float:
    """The longest stretch of input (degrees, cyclic over the turn) over which the output stays within
    :data:`DWELL_BAND` of its travel."""
    value, _, _ = motion.values_of(lk, sol, name)
    value = np.unwrap(value) if name not in lk.structure.slider_by_name else value
    n = len(value)
    step = 360.0 / n
    band = DWELL_BAND * travel
    best = 0
    doubled = np.concatenate([value, value])
    for start in range(n):
        lo = hi = doubled[start]
        k = start + 1
        while k < start + n:
            lo, hi = min(lo, doubled[k]), max(hi, doubled[k])
            if hi - lo > band:
                break
            k += 1
        best = max(best, k - start - 1)
        if best >= n - 1:
            break
    return best * step


def _clamp(a: Analysis, name: str, limits: list[float]) -> list[Earned]:
    """A toggle at a slider output's limit: the pin driving its dyad joins two links in line there (the dyad's
    other link and a link holding the pin, neither the input)."""
    lk = a.linkage
    s = lk.structure
    body = s.slider_by_name[name].body
    driven = {inp.link for inp in s.inputs} | {GROUND}
    if not limits:
        return []
    sol = lk.solve(np.array(limits)[None, :], strict=False)
    for step in lk.plan.steps:
        if not isinstance(step, DyadStep) or body not in step.bodies:
            continue
        other = step.bodies[1 - step.bodies.index(body)]
        for att in step.attachments:
            if not isinstance(att, Pin):
                continue
            knee = att.point
            far_2 = next((p for p in s.bodies[other] if p != knee), None)
            for holder in s.holders(knee):
                far_1 = next((p for p in s.bodies[holder] if p != knee), None)
                if holder in driven or holder in step.bodies or far_1 is None or far_2 is None:
                    continue
                u, v = sol.points[far_1] - sol.points[knee], sol.points[far_2] - sol.points[knee]
                angle = np.degrees(np.arctan2(np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]), np.sum(u * v, axis=1)))
                off = np.minimum(angle, 180.0 - angle)
                if off.min() <= IN_LINE:
                    return [Earned("clamp", f"at {name}'s limit position {far_1}, {knee} and {far_2} lie in line "
                                            f"(within {off.min():.3g} degrees): a toggle")]
    return []


def _floating(a: Analysis, point: str) -> bool:
    """Whether a tracer rides only on floating links: none the input, pivoted on the frame or sliding on it."""
    s = a.linkage.structure
    ground_pts = set(s.bodies[GROUND])
    inputs = {inp.link for inp in s.inputs}
    on_guides = {sl.body for sl in s.sliders if sl.guide == GROUND}
    for body in s.holders(point):
        if body == GROUND or body in inputs or body in on_guides or ground_pts & set(s.bodies[body]):
            return False
    return True


def _straight(path: np.ndarray, x: np.ndarray, size: float, cyclic: bool) -> tuple[float, float, float] | None:
    """The longest window of the path (input degrees, deviation mm, chord mm) within :data:`STRAIGHT_BAND` of its
    chord of its best line (total least squares), over at least :data:`STRAIGHT_INPUT` degrees; None if none."""
    n = len(path)
    if n < 8:
        return None
    step = float(np.median(np.abs(np.diff(x))))         # the samples' spacing (rad or mm)
    best = None
    for w in range(math.ceil(math.radians(STRAIGHT_INPUT) / max(step, 1e-300)), n + 1, max(1, n // 24)):
        starts = range(0, n if cyclic else n - w + 1, max(1, n // 72))
        found = None
        for start in starts:
            idx = np.arange(start, start + w) % n
            pts = path[idx]
            centred = pts - pts.mean(axis=0)
            _, sv, vt = np.linalg.svd(centred, full_matrices=False)
            along = centred @ vt[0]
            chord = float(along.max() - along.min())
            dev = float(np.abs(centred @ vt[1]).max()) if len(sv) > 1 else 0.0
            if chord >= STRAIGHT_CHORD * size and dev <= STRAIGHT_BAND * chord:
                found = (math.degrees(w * step), dev, chord)
                break
        if found is None:
            break
        best = found
    return best
