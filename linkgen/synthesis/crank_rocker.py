"""A Grashof crank-rocker for a rocker swing and a time ratio: the classical construction over its free choice.

The rocker pivot O4 is put at the origin and the rocker pin's limit positions B1, B2 on a circle
of the rocker's length, ``swing`` apart. The crank pivot lies on a circle through B1 and B2 where
the chord subtends alpha = 180 (Q - 1) / (Q + 1) degrees (:mod:`linkgen.synthesis.construction`);
each point of it gives crank = (|O2 B1| - |O2 B2|) / 2, coupler = (|O2 B1| + |O2 B2|) / 2 and
ground = |O2 O4|. With ``ground`` given the pivot is where that circle meets the circle of radius
ground about O4; else ``samples`` points round the circle are tried. Every linkage is then
analysed as a four-bar (its own frame: O2 at the origin, O4 on +X) and kept only if it is a
Grashof crank-rocker whose swing and time ratio are those asked for (1e-6 degrees, 1e-9 relative);
the candidates are ranked by their worst transmission angle (the smaller of the least and 180
minus the largest) over the turn, and those below ``min_transmission`` (30 degrees by default)
are left out, unless none keeps it: then the nearest are offered and a ``bound`` line names the
limit (:func:`keep`).
"""
from __future__ import annotations

import cmath
import math
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.spec import MAX_LENGTH_MM, MIN_LENGTH_MM
from linkgen.kinematics.fourbar import FourBar
from linkgen.synthesis import construction
from linkgen.synthesis.candidates import Candidate, Sketch, deg, fits_template, fourbar_table

TWO_PI = 2.0 * math.pi
LENGTHS = ("ground", "crank", "coupler", "rocker")


def swing_of(fb: FourBar) -> tuple[float, tuple[float, float]] | None:
    """The rocker's swing (rad) and the crank angles at its limit positions (extended, folded), or None."""
    ends = {d.kind: d for d in fb.dead_centres("open") if d.kind in ("extended", "folded")}
    if len(ends) != 2:
        return None
    swing = abs(math.remainder(ends["extended"].rocker - ends["folded"].rocker, TWO_PI))
    return swing, (ends["extended"].crank, ends["folded"].crank)


def worst_transmission(fb: FourBar) -> tuple[float, float, float]:
    """(worst, least, largest) transmission angle in degrees; worst = min(least, 180 - largest)."""
    (gmin, _), (gmax, _) = fb.transmission_extremes()
    least, largest = math.degrees(gmin), math.degrees(gmax)
    return min(least, 180.0 - largest), least, largest


def within(lengths: dict[str, float], link_range: tuple[float, float] | None) -> bool:
    """Whether every length lies in ``link_range`` (mm), when one is given."""
    return link_range is None or all(link_range[0] <= v <= link_range[1] for v in lengths.values())


def _checked(ground: float, crank: float, coupler: float, rocker: float, task: Any, o2: complex) -> Candidate | None:
    """The candidate of these lengths (the crank pivot at ``o2`` in the construction's frame) if it is a Grashof
    crank-rocker meeting the task, else None."""
    try:
        fb = FourBar(ground, crank, coupler, rocker)
    except SpecError:
        return None
    g = fb.grashof
    found = swing_of(fb)
    ratio = fb.time_ratio()
    if g.grashof_class != "I" or g.inversion != "crank-rocker" or found is None or ratio is None:
        return None
    swing, cranks = found
    if abs(math.degrees(swing) - task.swing) > 1e-6 or abs(ratio - task.time_ratio) > 1e-9 * task.time_ratio:
        return None
    worst, least, largest = worst_transmission(fb)
    row = {"ground_pivots": [[0.0, 0.0], [ground, 0.0]], "ground": ground, "crank": crank, "coupler": coupler,
           "rocker": rocker, "coupler_point": [0.0, 0.0], "input_angles": [deg(c) for c in cranks],
           "swing_deg": math.degrees(swing), "time_ratio": ratio, "swing_error_deg": abs(math.degrees(swing)
                                                                                          - task.swing),
           "transmission_worst_deg": worst, "transmission_min_deg": least, "transmission_max_deg": largest,
           "inversion": g.inversion,
           # the free choice: where the crank pivot sits, seen from the rocker pivot, counter-clockwise from the
           # rocker's mid-swing line
           "free_choice": {"crank_pivot_bearing_deg": math.degrees(math.remainder(cmath.phase(o2) - math.pi / 2,
                                                                                   TWO_PI))}}
    return Candidate(fourbar_table(ground, crank, coupler, rocker), row, -worst, (ground, crank, coupler, rocker),
                     _sketch(fb, cranks))


def _sketch(fb: FourBar, cranks: tuple[float, float]) -> Sketch:
    """The rocker pin's arc over a crank turn and the linkage at both limit positions."""
    arc = fb.sweep(np.linspace(0.0, TWO_PI, 361), "open").b
    at = fb.positions(np.array(cranks), "open")
    o4 = [fb.ground, 0.0]
    poses = tuple((kind, np.array([[0.0, 0.0], at.a[k], at.b[k], o4])) for k, kind in enumerate(("extended",
                                                                                               "folded")))
    return Sketch(paths=(("rocker pin", arc),), poses=poses, reached=at.b)


def solve(task: Any) -> tuple[list[Candidate], dict[str, Any]]:
    """The crank-rockers of a validated crank-rocker task (unranked) and how they were found."""
    c, psi = task.rocker, math.radians(task.swing)
    alpha = construction.alpha_of(task.time_ratio)
    b1, b2 = c * complex(math.cos(math.pi / 2 + psi / 2), math.sin(math.pi / 2 + psi / 2)), \
        c * complex(math.cos(math.pi / 2 - psi / 2), math.sin(math.pi / 2 - psi / 2))
    if task.ground is not None and alpha > 0:
        o2 = np.concatenate([construction.circle_meets_circle(m, r, 0j, task.ground)
                             for m, r in construction.circles(b1, b2, alpha)])
    elif task.ground is not None:
        o2 = construction.line_meets_circle(b1, (b2 - b1) / abs(b2 - b1), 0j, task.ground)
    else:
        reach = task.link_range[1] if task.link_range is not None else min(10.0 * c, MAX_LENGTH_MM)
        o2 = construction.pivots(b1, b2, alpha, task.samples, reach)
    cranks, couplers = construction.limit_lengths(o2, b1, b2)
    found = [x for x in (_checked(float(abs(o)), float(a), float(b), c, task, o) for o, a, b in
                         zip(o2, cranks, couplers, strict=True)) if x is not None]
    wanted = (f"swings its rocker {task.swing:g} degrees with time ratio {task.time_ratio:g}"
              + (f" on a ground of {task.ground:g} mm" if task.ground else ""))
    kept, bound = keep(found, task, LENGTHS, "Grashof crank-rocker", wanted,
                       "task.ground" if task.ground is not None else "task.time_ratio", "task.rocker",
                       "ask for a smaller swing or time ratio" + (", or another ground" if task.ground else ""))
    return kept, construction.info("rocker pin's limit positions", alpha, len(o2), len(found)) | {"bound": bound}


def keep(found: list[Candidate], task: Any, lengths: tuple[str, ...], what: str, wanted: str, field: str,
         scale: str, hint: str) -> tuple[list[Candidate], list[str]]:
    """The candidates ``found`` whose ``lengths`` (row keys) lie within ``link_range`` and what a template holds, and
    whose worst transmission angle is at least ``task.min_transmission``; and a line naming that limit when it left
    fewer than were asked for. A one-line error on ``field`` if none was found, on ``task.link_range`` if none lies
    within it, on ``task.link_range`` (or, without one, the field ``scale`` that sizes them) if none fits a template,
    and, if none keeps the transmission limit, all of them (the nearest: ranked by their worst transmission angle)
    with a line naming ``task.min_transmission`` (and ``hint``)."""
    if not found:
        raise SpecError(f"no {what} {wanted}", field)
    kept = [x for x in found if within({k: x.row[k] for k in lengths}, task.link_range)]
    if not kept:
        raise SpecError(f"none of the {len(found)} linkages found has its {', '.join(lengths)} within "
                        f"{list(task.link_range or ())} mm", "task.link_range")
    kept = [x for x in kept if fits_template(x.row[k] for k in (*lengths, "offset") if k in x.row)]
    if not kept:
        raise SpecError(f"none of the {len(found)} linkages found has its {', '.join(lengths)} within "
                        f"[{MIN_LENGTH_MM:g}, {MAX_LENGTH_MM:g}] mm, what a template holds: "
                        + ("give a link_range within it" if task.link_range is not None else
                           f"give a smaller or larger {scale[5:]}"), "task.link_range" if task.link_range else scale)
    mu = task.min_transmission
    good = [x for x in kept if x.row["transmission_worst_deg"] >= mu]
    if not good:
        best = max(x.row["transmission_worst_deg"] for x in kept)
        return kept, [f"task.min_transmission: none of the {len(kept)} linkages found keeps its transmission angle at "
                      f"least {mu:g} degrees over its turn; the nearest are offered (the best reaches {best:.4g}): "
                      f"lower min_transmission, or {hint}"]
    bound = [] if len(good) >= task.candidates or len(good) == len(kept) else [
        f"task.min_transmission: {len(good)} of the {len(kept)} linkages found keep the transmission angle at least "
        f"{mu:g} degrees over their turn; the others are left out"]
    return good, bound
