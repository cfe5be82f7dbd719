"""A slider-crank for a stroke and a time ratio: the same construction as the crank-rocker's, on a straight line.

The slider pin's dead-centre positions C1 and C2 lie ``stroke`` apart on the slider line; the
crank pivot sees them under alpha = 180 (Q - 1) / (Q + 1) degrees (:mod:`linkgen.synthesis.construction`),
so it lies on a circle through them, below the line (the offset is the line's height above the
pivot); each point gives crank = (|O2 C1| - |O2 C2|) / 2 and rod = (|O2 C1| + |O2 C2|) / 2. A time
ratio of 1 needs a centred slider: the pivot is on the line and the free choice is the rod, out to
the longest of ``link_range`` (four strokes without one). With ``offset`` given, the pivot is where
the circle meets the line at that depth. Each linkage is analysed as a slider-crank and kept if its
stroke and time ratio are those asked for; candidates are ranked by their worst transmission angle,
90 degrees less the rod's largest angle to the slider line, and those below ``min_transmission``
(30 degrees by default) are left out, unless none keeps it (the nearest are offered then, with a
``bound`` line naming the limit).
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.spec import MAX_LENGTH_MM
from linkgen.kinematics.slidercrank import SliderCrank
from linkgen.synthesis import construction
from linkgen.synthesis.candidates import Candidate, Sketch, deg
from linkgen.synthesis.crank_rocker import keep


def _checked(crank: float, rod: float, offset: float, task: Any) -> Candidate | None:
    """The candidate of these lengths if its crank turns fully and it meets the stroke and time ratio, else None."""
    try:
        sc = SliderCrank(crank, rod, offset)
        if not sc.turns_fully or rod <= crank + abs(offset):
            return None
        stroke, ratio = sc.stroke, sc.time_ratio
    except SpecError:
        return None
    if abs(stroke - task.stroke) > 1e-9 * task.stroke or abs(ratio - task.time_ratio) > 1e-9 * task.time_ratio:
        return None
    transmission = 90.0 - math.degrees(math.asin(min(1.0, (crank + abs(offset)) / rod)))
    dead = sc.dead_centres()
    row = {"ground_pivots": [[0.0, 0.0]], "crank": crank, "rod": rod, "offset": offset,
           "input_angles": [deg(t) for _, t, _ in dead], "stroke_mm": stroke, "time_ratio": ratio,
           "stroke_error_mm": abs(stroke - task.stroke), "transmission_worst_deg": transmission}
    table = {"type": "slider-crank", "crank": crank, "rod": rod, "offset": offset}
    return Candidate(table, row, -transmission, (crank, rod, offset), _sketch(sc))


def _sketch(sc: SliderCrank) -> Sketch:
    """The slider line over the stroke and the linkage at both dead centres."""
    dead = sc.dead_centres()
    xs = [x for _, _, x in dead]
    line = np.array([[min(xs), sc.offset], [max(xs), sc.offset]])
    poses = tuple((kind, np.array([[0.0, 0.0], [sc.crank * math.cos(t), sc.crank * math.sin(t)], [x, sc.offset]]))
                  for kind, t, x in dead)
    return Sketch(paths=(("slider pin", line),), poses=poses, reached=np.array([[x, sc.offset] for x in xs]))


def solve(task: Any) -> tuple[list[Candidate], dict[str, Any]]:
    """The slider-cranks of a validated slider-crank task (unranked) and how they were found."""
    c1, c2 = complex(task.stroke, 0.0), 0j
    alpha = construction.alpha_of(task.time_ratio)
    if alpha > 0 and task.offset is not None:
        o2 = np.concatenate([construction.line_meets_circle(complex(0.0, -task.offset), 1 + 0j, m, r)
                             for m, r in construction.circles(c1, c2, alpha)])
    else:
        reach = task.link_range[1] if task.link_range is not None else min(4.0 * task.stroke, MAX_LENGTH_MM)
        o2 = construction.pivots(c1, c2, alpha, task.samples, reach)
    o2 = o2[o2.imag <= 1e-12 * task.stroke] if alpha > 0 else o2[o2.real < 0]   # below the line; one mirror image
    cranks, rods = construction.limit_lengths(o2, c1, c2)
    found = [x for x in (_checked(float(a), float(b), float(max(0.0, -o.imag)), task)
                         for o, a, b in zip(o2, cranks, rods, strict=True)) if x is not None]
    wanted = (f"whose crank turns fully makes a stroke of {task.stroke:g} mm with time ratio {task.time_ratio:g}"
              + (f" at offset {task.offset:g} mm" if task.offset else ""))
    kept, bound = keep(found, task, ("crank", "rod"), "slider-crank", wanted,
                       "task.offset" if task.offset is not None else "task.time_ratio", "task.stroke",
                       "ask for a smaller time ratio" + (", or another offset" if task.offset is not None else
                                                         ", or allow a longer rod (link_range)"))
    return kept, construction.info("slider pin's dead-centre positions", alpha, len(o2), len(found)) | {"bound": bound}
