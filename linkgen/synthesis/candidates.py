"""Candidates: what each method offers, how they are ranked, and each written as a linkgen template.

A method returns :class:`Candidate` s: the ``[linkage]`` table of the linkage (a ``four-bar`` or
``slider-crank`` in its own frame, or a ``linkage`` drawn in the task's frame when the ground is
placed and turned by the task), the summary row (mm and degrees) and what its figure shows.
:func:`offer` ranks them, names them ``<name>-<rank>``, and re-analyses each template exactly as
``linkgen analyze`` would read it, so the report offered is the report of the file written.
"""
from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from camgen.core.spec import MAX_LENGTH_MM, MIN_LENGTH_MM
from linkgen.synthesis.geometry import place_design

TWO_PI = 2.0 * math.pi
#: a path candidate's error counts for more as its worst transmission angle falls below this (degrees): the lower
#: end of the usual design band (40 to 140 degrees)
GOOD_TRANSMISSION_DEG = 40.0


@dataclass(frozen=True)
class Sketch:
    """What a candidate's figure shows, in mm: paths (label, (n, 2)), the linkage at some poses (label, joints in
    order, drawn as a chain), the targets and the points reached; for a function, its structural error against x
    (x, error, the precision points' x, the axis label)."""

    paths: tuple[tuple[str, np.ndarray], ...] = ()
    poses: tuple[tuple[str, np.ndarray], ...] = ()
    targets: np.ndarray | None = None
    reached: np.ndarray | None = None
    error: tuple[np.ndarray, np.ndarray, np.ndarray, str] | None = None


@dataclass(frozen=True)
class Candidate:
    """One linkage a method offers: its ``[linkage]`` table, its summary row and its figure; ``score`` ranks it
    (lower first) and ``signature`` tells near-copies apart (numbers in mm and radians)."""

    linkage: dict[str, Any]
    row: dict[str, Any]
    score: float
    signature: tuple[float, ...]
    sketch: Sketch = field(default_factory=Sketch)


@dataclass(frozen=True)
class Offered:
    """A ranked candidate as written: its name, its template (a raw mapping), its summary row and the report of
    ``linkgen analyze`` on that template."""

    name: str
    template: dict[str, Any]
    row: dict[str, Any]
    report: dict[str, Any]
    sketch: Sketch


def ranked(candidates: Iterable[Candidate], count: int, tol: float = 1e-3) -> list[Candidate]:
    """The ``count`` best candidates, best first, leaving out any whose signature is within ``tol`` (relative to
    its size) of a better one's."""
    out: list[Candidate] = []
    for c in sorted(candidates, key=lambda c: c.score):
        sig = np.asarray(c.signature)
        if all(np.max(np.abs(sig - np.asarray(o.signature))) > tol * max(1.0, np.max(np.abs(sig))) for o in out):
            out.append(c)
            if len(out) == count:
                break
    return out


def weighed(c: Candidate) -> Candidate:
    """A path candidate ranked by its error weighed against its transmission: ``rank_score`` = ``error_mm2`` x
    max(1, sin 40 degrees / sin gamma), gamma its worst transmission angle over the motion (degrees in the row).
    A linkage at 40 degrees or better is ranked by its error alone; at 30 degrees its error counts 1.29 times, at
    20 degrees 1.88 times, so a linkage that binds must be that much closer to rank above one that does not."""
    gamma = math.radians(c.row["transmission_worst_deg"])
    weight = max(1.0, math.sin(math.radians(GOOD_TRANSMISSION_DEG)) / max(math.sin(gamma), 1e-12))
    score = c.row["error_mm2"] * weight
    return dataclasses.replace(c, score=score, row={**c.row, "rank_score": score})


def fits_template(lengths: Iterable[float]) -> bool:
    """Whether every length (mm) is one a linkage template holds: 0, or between MIN_LENGTH_MM and MAX_LENGTH_MM in
    size."""
    return all(v == 0 or MIN_LENGTH_MM <= abs(v) <= MAX_LENGTH_MM for v in lengths)


def table_fits(linkage: dict[str, Any]) -> bool:
    """Whether a candidate's ``[linkage]`` table is one a template holds: its lengths (:func:`fits_template`) and,
    drawn in the task's frame, every joint within MAX_LENGTH_MM of the origin in x and y."""
    joints = linkage.get("joints", {})
    numbers = [v for k, v in linkage.items() if isinstance(v, float) and k != "point_angle"]
    return fits_template(numbers) and all(abs(c) <= MAX_LENGTH_MM for xy in joints.values() for c in xy)


# ---------------------------------------------------------------------- rows and tables of four-bars


def deg(x: float) -> float:
    """Radians as degrees in [0, 360), rounded to 1e-9."""
    return round(math.degrees(x) % 360.0, 9) % 360.0


def fourbar_table(r1: float, r2: float, r3: float, r4: float, cx: float = 0.0, cy: float = 0.0,
                  assembly: str = "open") -> dict[str, Any]:
    """The ``[linkage]`` table of a four-bar in its own frame (O2 at the origin, O4 on +X)."""
    table: dict[str, Any] = {"type": "four-bar", "ground": r1, "crank": r2, "coupler": r3, "rocker": r4}
    if math.hypot(cx, cy) > 0:
        table |= {"point_distance": math.hypot(cx, cy), "point_angle": math.degrees(math.atan2(cy, cx))}
    return table | {"assembly": assembly}


def drawn_table(d: dict[str, float], theta2: float) -> dict[str, Any]:
    """The ``[linkage]`` table (``type = "linkage"``) that draws design ``d`` (see
    :mod:`linkgen.synthesis.geometry`) in the task's frame at crank angle ``theta2`` (rad, from the ground line),
    the coupler point traced as P (A or B where it sits on a pin)."""
    p = place_design([d[k] for k in ("x0", "y0", "theta0", "r1", "r2", "r3", "r4", "cx", "cy", "branch")], theta2)
    o4 = (d["x0"] + d["r1"] * math.cos(d["theta0"]), d["y0"] + d["r1"] * math.sin(d["theta0"]))
    joints = {"O2": [d["x0"], d["y0"]], "O4": list(o4), "A": [float(p.ax), float(p.ay)],
              "B": [float(p.bx), float(p.by)]}
    point = [float(p.px), float(p.py)]
    on_pin = next((k for k in ("A", "B") if math.dist(joints[k], point) <= 1e-9 * max(1.0, d["r1"])), None)
    coupler = ["A", "B"] if on_pin else ["A", "B", "P"]
    if on_pin is None:
        joints["P"] = point
    return {"type": "linkage", "ground": ["O2", "O4"], "input": {"link": "crank", "pivot": "O2"},
            "tracers": [on_pin or "P"], "joints": joints,
            "links": {"crank": ["O2", "A"], "coupler": coupler, "rocker": ["O4", "B"]}}


def fourbar_row(d: dict[str, float], theta2: Sequence[float]) -> dict[str, Any]:
    """What a user needs to draw design ``d`` by hand: ground pivots (crank pivot first), lengths, the coupler
    point (distance from the crank pin, angle from the coupler line A -> B, degrees counter-clockwise), the crank
    angles at the targets from the ground line, and the crank's directions in the drawing there (what
    ``linkgen analyze --angle`` takes for the drawn template)."""
    o2 = [d["x0"], d["y0"]]
    o4 = [d["x0"] + d["r1"] * math.cos(d["theta0"]), d["y0"] + d["r1"] * math.sin(d["theta0"])]
    return {"ground_pivots": [o2, o4], "ground": d["r1"], "crank": d["r2"], "coupler": d["r3"], "rocker": d["r4"],
            "coupler_point": [math.hypot(d["cx"], d["cy"]), math.degrees(math.atan2(d["cy"], d["cx"]))],
            "input_angles": [deg(t) for t in theta2],
            "input_directions": [math.degrees(d["theta0"] + t) % 360.0 for t in theta2],
            "assembly": "open" if d["branch"] >= 0 else "crossed"}


def coupler_sketch(d: dict[str, float], theta2: Sequence[float], targets: np.ndarray | None,
                   sweep: np.ndarray) -> Sketch:
    """The coupler curve over crank angles ``sweep`` (rad), the linkage at the first target, the targets and the
    points reached at ``theta2``."""
    args = [d[k] for k in ("x0", "y0", "theta0", "r1", "r2", "r3", "r4", "cx", "cy", "branch")]
    curve = place_design(args, sweep)
    hit = place_design(args, np.asarray(theta2, dtype=float))
    first = place_design(args, float(theta2[0]))
    o4 = (d["x0"] + d["r1"] * math.cos(d["theta0"]), d["y0"] + d["r1"] * math.sin(d["theta0"]))
    chain = np.array([[d["x0"], d["y0"]], [first.ax, first.ay], [first.px, first.py], [first.bx, first.by],
                      [first.ax, first.ay], [first.bx, first.by], list(o4)], dtype=float)
    return Sketch(paths=(("coupler curve", np.column_stack([curve.px, curve.py])),),
                  poses=(("at the first target", chain),), targets=targets,
                  reached=np.column_stack([hit.px, hit.py]))


# ---------------------------------------------------------------------- templates


def default_parts(lengths: Iterable[float]) -> dict[str, Any]:
    """A ``[parts]`` table sized to the shortest link, so that ``linkgen build`` takes the template as it is:
    bars 0.3 of the shortest link wide (3 to 20 mm), pins 0.4 of the width, 3 mm plates."""
    width = round(min(20.0, max(3.0, 0.3 * min(lengths))), 1)
    return {"width": width, "thickness": 3.0, "pin_diameter": round(0.4 * width, 2)}


def template_of(name: str, linkage: dict[str, Any], parts: dict[str, Any]) -> dict[str, Any]:
    return {"name": name, "linkage": linkage, "parts": parts}


def offer(name: str, candidates: Sequence[Candidate], parts: dict[str, Any] | None,
          lengths: Callable[[Candidate], Iterable[float]]) -> tuple[Offered, ...]:
    """Name the ranked ``candidates`` ``<name>-<rank>``, give each its template (``parts``, else parts sized by
    ``lengths(candidate)``) and the report ``linkgen analyze`` makes of it."""
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import validate_spec

    out = []
    for rank, c in enumerate(candidates, 1):
        cname = f"{name}-{rank}"
        raw = template_of(cname, c.linkage, parts if parts is not None else default_parts(lengths(c)))
        report = design_linkage(validate_spec(raw)).report
        row = {"rank": rank, "template": f"{cname}.toml", "report": f"{cname}.json", **c.row}
        out.append(Offered(cname, raw, row, report, c.sketch))
    return tuple(out)


