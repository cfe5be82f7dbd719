"""The motion of a general linkage over its input: change points, reachable ranges, toggles and limit positions.

Searched on the motion that starts at the drawing: a crank's revolution theta0 .. theta0 + 2 pi,
or a slide's travel of up to ``SLIDE_REACH`` times the drawing's size either way. Every
search samples :data:`GRID` poses in one vectorised solve and then refines each event to
rounding: golden sections for the change points (where a dyad's margin touches 0 and comes
back), bisection for the ends of the reachable ranges (where it goes below 0), Newton's
method on the angular velocity for the limit positions of the rockers and sliders (where
their speed is 0). Only single-input linkages are searched; with more inputs the drawing's
branches are kept and the ranges are the caller's.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, NoReturn

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics.fourbar import digits_apart
from linkgen.kinematics.structure import GROUND, DyadStep, Pin

if TYPE_CHECKING:
    from linkgen.kinematics.linkage import Linkage, Solution

#: poses sampled over the revolution or the travel
GRID = 4096
#: a dyad whose smallest margin (a sine) comes within this of 0 and returns passes a change point
CHANGE_TOL = 1e-7
#: a slide input is searched this many times the drawing's size either way
SLIDE_REACH = 4.0
TWO_PI = 2.0 * math.pi
BRANCHED = ("RRR", "RRP", "PRR", "RPR")


def span(linkage: Linkage) -> tuple[float, float]:
    """The input values searched: the crank's revolution from the drawing, or the slide's travel."""
    x0 = float(linkage.drawn_inputs[0])
    if linkage.is_crank():
        return x0, x0 + TWO_PI
    reach = SLIDE_REACH * linkage.structure.scale
    return -reach, reach


def _margins(linkage: Linkage, x: np.ndarray, upto: int | None, signs: list[np.ndarray] | None) -> np.ndarray:
    """Each dyad's margin (rows) at input values x (one input), the branches given by ``signs``."""
    sol = linkage.solve(x[None, :], strict=False, derivatives=False, upto=upto, signs=signs)
    return np.array([d.margin for d in sol.dyads]).reshape(len(sol.dyads), len(x))


def find_flips(linkage: Linkage) -> tuple[np.ndarray, ...]:
    """Per step, the input values where its branch swaps at a change point (sorted), found dyad by dyad over the
    searched span with the earlier dyads' swaps applied."""
    steps = linkage.plan.steps
    if len(linkage.structure.inputs) != 1:
        return ()
    lo, hi = span(linkage)
    grid = np.linspace(lo, hi, GRID + 1)
    flips: list[np.ndarray] = [np.empty(0) for _ in steps]
    dyad_index = -1
    for index, step in enumerate(steps):
        if not isinstance(step, DyadStep):
            continue
        dyad_index += 1
        if step.kind not in BRANCHED:
            continue
        current = type(linkage)(linkage.structure, linkage.plan, tuple(flips))

        def at(x: np.ndarray, current: Linkage = current, index: int = index, d: int = dyad_index) -> object:
            return current.solve(x[None, :], strict=False, upto=index + 1).dyads[d]

        m = at(grid).margin
        k = np.flatnonzero((m[1:-1] <= m[:-2]) & (m[1:-1] <= m[2:]) & (m[:-2] > 0) & (m[2:] > 0)
                           & (m[1:-1] < 1e-2)) + 1
        if len(k) == 0:
            continue
        # the outer joints stop moving apart (or together) at the change point: a simple zero of their spread rate
        found = _root(lambda x, at=at: at(x).spread, grid[k - 1], grid[k + 1])
        keep = (at(found).margin <= CHANGE_TOL) & (found > lo) & (found < hi)
        flips[index] = np.unique(found[keep])
    return tuple(flips)


def _root(f, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """A zero of f in each [a, b] (vectorised bisection to rounding), or the end where |f| is smaller when f keeps
    its sign there."""
    fa, fb = f(a), f(b)
    keeps = np.sign(fa) == np.sign(fb)
    for _ in range(64):
        mid = 0.5 * (a + b)
        fm = f(mid)
        left = np.sign(fm) == np.sign(fa)
        a, fa = np.where(left, mid, a), np.where(left, fm, fa)
        b = np.where(left, b, mid)
    return np.where(keeps, np.where(np.abs(fa) <= np.abs(fb), a, b), 0.5 * (a + b))


def transmission_extremes(linkage: Linkage, lo: float, hi: float) -> list[tuple[float, float, float, float]]:
    """Each dyad's smallest and largest transmission angle (rad) over the inputs lo..hi, and where: (min, at,
    max, at), found on :data:`GRID` poses and refined by golden sections."""
    grid = np.linspace(lo, hi, GRID + 1)
    sol = linkage.solve(grid[None, :], strict=False, derivatives=False)
    out = []
    for d, dyad in enumerate(sol.dyads):
        gamma = np.where(sol.ok, dyad.transmission, np.nan)
        found = []
        for sign in (1.0, -1.0):
            k = int(np.nanargmin(sign * gamma))
            a, b = grid[max(k - 1, 0)], grid[min(k + 1, GRID)]

            def f(x: np.ndarray, d: int = d, sign: float = sign) -> np.ndarray:
                s = linkage.solve(x[None, :], strict=False, derivatives=False)
                return np.where(s.ok, sign * s.dyads[d].transmission, np.inf)

            x, value = _golden(f, np.array([a]), np.array([b]))
            refined = value[0] < sign * gamma[k]            # golden sections keep the grid's best if they lose it
            found += [float(sign * value[0]), float(x[0])] if refined else [float(gamma[k]), float(grid[k])]
        out.append(tuple(found))
    return out


def _golden(f, a: np.ndarray, b: np.ndarray, iterations: int = 80) -> tuple[np.ndarray, np.ndarray]:
    """Minimisers of f on the brackets [a, b] (vectorised golden sections) and f there."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(iterations):
        left = fc < fd
        b, a = np.where(left, d, b), np.where(left, a, c)
        c, d = b - g * (b - a), a + g * (b - a)
        fc, fd = f(c), f(d)
    return np.where(fc < fd, c, d), np.minimum(fc, fd)


@dataclass(frozen=True)
class Toggle:
    """A dyad in line: ``kind`` 'limit' (the input stops there: an end of a reachable range) or 'change point'
    (the branches meet and the motion goes on); the input value, the dyad's bodies and middle joint."""

    kind: str
    value: float
    bodies: tuple[str, str]
    joint: str


def _feasible(linkage: Linkage, x: np.ndarray) -> np.ndarray:
    """Where every dyad closes (margins >= 0: the ranges' ends are the exact toggles)."""
    m = _margins(linkage, x, None, None)
    return np.all(m >= 0.0, axis=0) if len(m) else np.ones(len(x), dtype=bool)


def input_ranges(linkage: Linkage) -> tuple[tuple[float, float], ...] | None:
    """The input values (rad or mm) over which the linkage assembles on the drawing's branches: None when a crank
    turns fully; else closed intervals, the one holding the drawing first."""
    if len(linkage.structure.inputs) != 1:
        return None
    lo, hi = span(linkage)
    grid = np.linspace(lo, hi, GRID + 1)
    ok = _feasible(linkage, grid)
    if ok.all() and linkage.is_crank():
        return None
    edges = np.flatnonzero(np.diff(ok.astype(int)))
    ends = _bisect(linkage, grid[edges], grid[edges + 1], ok[edges])
    runs: list[list[float]] = []
    start = lo if ok[0] else None
    for e, rising in zip(ends, ~ok[edges], strict=True):
        if rising:
            start = e
        elif start is not None:
            runs.append([start, e])
            start = None
    if start is not None:
        runs.append([start, hi])
    if linkage.is_crank() and len(runs) > 1 and runs[0][0] == lo and runs[-1][1] == hi:
        runs[0][0] = runs.pop()[0] - TWO_PI
    x0 = float(linkage.drawn_inputs[0])
    runs.sort(key=lambda r: (not (r[0] <= x0 <= r[1] or r[0] <= x0 - TWO_PI <= r[1]), r[0]))
    return tuple((float(a), float(b)) for a, b in runs)


def _bisect(linkage: Linkage, a: np.ndarray, b: np.ndarray, a_ok: np.ndarray) -> np.ndarray:
    """The boundary between feasible and not in each [a, b] (``a_ok``: which side is feasible), to rounding; the
    feasible side's end."""
    good, bad = np.where(a_ok, a, b), np.where(a_ok, b, a)
    for _ in range(64):
        mid = 0.5 * (good + bad)
        if not len(mid):
            break
        ok = _feasible(linkage, mid)
        good, bad = np.where(ok, mid, good), np.where(ok, bad, mid)
    return good


def toggles(linkage: Linkage) -> tuple[Toggle, ...]:
    """The ends of the reachable ranges (which dyad stops the input there) and the change points, by input
    value."""
    dyads = [s for s in linkage.plan.steps if isinstance(s, DyadStep)]
    out = []
    for index, step in enumerate(linkage.plan.steps):
        if isinstance(step, DyadStep):
            out += [Toggle("change point", float(v), step.bodies, step.joint) for v in linkage.flips[index]] \
                if linkage.flips else []
    for rng in input_ranges(linkage) or ():
        for end in rng:
            if linkage.is_crank() and rng[1] - rng[0] >= TWO_PI - 1e-12:
                continue
            lo, hi = span(linkage)
            if not linkage.is_crank() and end in (lo, hi):
                continue
            m = _margins(linkage, np.array([end]), None, None)[:, 0]
            d = int(np.argmin(np.abs(m)))
            out.append(Toggle("limit", end, dyads[d].bodies, dyads[d].joint))
    return tuple(sorted(out, key=lambda t: t.value))


@dataclass(frozen=True)
class Extreme:
    """A limit position of an output: its body (or slider), the input value there and the output's value (rad
    from the drawing for a rocker, mm along its guide for a slider)."""

    output: str
    value: float
    position: float


def rockers(linkage: Linkage) -> list[str]:
    """The bodies turning about a ground pivot that no input drives (the outputs whose swing is reported)."""
    s = linkage.structure
    driven = {inp.link for inp in s.inputs if inp.kind == "crank"}
    out = []
    for step in linkage.plan.steps:
        if isinstance(step, DyadStep):
            for body, att in zip(step.bodies, step.attachments, strict=True):
                if isinstance(att, Pin) and att.body == GROUND and body not in driven:
                    out.append(body)
    return out


def ground_sliders(linkage: Linkage) -> list[str]:
    """The sliders on a ground guide that no input moves (the outputs whose stroke is reported)."""
    s = linkage.structure
    moved = {inp.slider for inp in s.inputs if inp.kind == "slide"}
    return [sl.name for sl in s.sliders if sl.guide == GROUND and sl.name not in moved]


def _output(linkage: Linkage, name: str | tuple[str, int], x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An output's value, rate and acceleration per unit input at inputs x: a rocker's angle from the drawing
    (rad), a ground slider's travel from the drawing along its guide (mm), a point's x or y (``(point, 0 or 1)``,
    mm)."""
    sol = linkage.solve(x[None, :], strict=False)
    sliders = linkage.structure.slider_by_name
    if isinstance(name, tuple):                      # (point, axis): a coordinate of a point (mm)
        point, axis = name
        return sol.points[point][:, axis], sol.velocities[point][:, axis], sol.accelerations[point][:, axis]
    if name not in sliders:
        return sol.angles[name], sol.omegas[name], sol.alphas[name]
    sl = sliders[name]
    u = np.array([math.cos(sl.angle), math.sin(sl.angle)])
    p = sol.points[sl.point] - np.asarray(linkage.structure.points[sl.point])
    return p @ u, sol.velocities[sl.point] @ u, sol.accelerations[sl.point] @ u


def limit_positions(linkage: Linkage, output: str | tuple[str, int], lo: float, hi: float) -> tuple[Extreme, ...]:
    """Where ``output`` (a rocker, a slider on a ground guide, a point's coordinate) stops and turns back over the
    inputs lo..hi: its
    rate's zeros on :data:`GRID` poses, refined by Newton's method with its acceleration (bisection where a step
    would leave its bracket)."""
    grid = np.linspace(lo, hi, GRID + 1)
    _, rate, _ = _output(linkage, output, grid)
    k = np.flatnonzero(np.sign(rate[:-1]) * np.sign(rate[1:]) < 0)
    if not len(k):
        return ()
    xa, xb = grid[k], grid[k + 1]
    fa = rate[k]
    x = 0.5 * (xa + xb)
    for _ in range(60):
        _, w, al = _output(linkage, output, x)
        left = np.sign(w) == np.sign(fa)
        xa, xb = np.where(left, x, xa), np.where(left, xb, x)
        fa = np.where(left, w, fa)
        step = w / np.where(al != 0, al, np.inf)
        nxt = x - step
        done = np.abs(step) <= 1e-15 * np.maximum(1.0, np.abs(x))
        inside = (nxt >= xa) & (nxt <= xb) & np.isfinite(nxt)
        x = np.where(done, x, np.where(inside, nxt, 0.5 * (xa + xb)))
        if done.all():
            break
    value, _, _ = _output(linkage, output, x)
    return tuple(Extreme(str(output), float(v), float(p)) for v, p in zip(x, value, strict=True))


def extent(linkage: Linkage, point: str, lo: float, hi: float) -> tuple[tuple[float, float], tuple[float, float]]:
    """The smallest and largest x and y (mm) of ``point`` over the inputs lo..hi: the coordinates' limit positions
    refined, and the ends of the motion."""
    out = []
    for axis in (0, 1):
        ends, _, _ = _output(linkage, (point, axis), np.array([lo, hi]))
        values = [e.position for e in limit_positions(linkage, (point, axis), lo, hi)] + list(ends)
        out.append((float(min(values)), float(max(values))))
    return out[0], out[1]


def time_ratio(linkage: Linkage, extremes: tuple[Extreme, ...]) -> float | None:
    """Slower stroke over faster (>= 1) for a crank turning fully and an output with two limit positions."""
    if not linkage.is_crank() or input_ranges(linkage) is not None or len(extremes) != 2:
        return None
    travel = (extremes[1].value - extremes[0].value) % TWO_PI
    return max(travel, TWO_PI - travel) / min(travel, TWO_PI - travel)


#: how closely (relative to the drawing's size) a redundant joint must hold over the motion for the linkage to
#: count as paradoxical (it moves although Gruebler says it cannot)
PARADOX_TOL = 1e-9


def check_redundant(linkage: Linkage) -> None:
    """Refuse a linkage whose redundant joints come apart, or whose redundant sliders leave their guides
    (:func:`slider_gaps`), over the motion from the drawing (an over-constrained one); one whose redundant
    constraints hold everywhere is paradoxical and kept (its plan lists them)."""
    from linkgen.kinematics.linkage import body_point

    if not linkage.plan.redundant or len(linkage.structure.inputs) != 1:
        return
    joints = [r for r in linkage.plan.redundant if not r.slider]
    lo, hi = span(linkage)
    x = np.linspace(lo, hi, 721)
    sol = linkage.solve(x[None, :], strict=False, derivatives=False)
    for name, (off, turn) in slider_gaps(linkage, sol).items():
        sl = linkage.structure.slider_by_name[name]
        if off > PARADOX_TOL * linkage.structure.scale:
            why = f"its point {sl.point} cannot stay on its guide on {sl.guide} (it leaves it by up to {off:.3g} mm)"
        elif turn > PARADOX_TOL:
            why = (f"link {sl.body} cannot keep its angle to {sl.guide} (it turns by up to "
                   f"{math.degrees(turn):.3g} degrees)")
        else:
            continue
        raise SpecError(f"over-constrained (mobility {linkage.plan.mobility}): as the input moves, {why}; remove the "
                        "slider or a joint", f"linkage.sliders.{name}")
    for r in joints:
        b1, b2 = r.bodies
        p1 = body_point(linkage.structure, sol, b1, r.name)[sol.ok]
        p2 = body_point(linkage.structure, sol, b2, r.name)[sol.ok]
        gap = float(np.max(np.hypot(*(p1 - p2).T))) if len(p1) else 0.0
        if gap > PARADOX_TOL * linkage.structure.scale:
            raise SpecError(f"over-constrained (mobility {linkage.plan.mobility}): links {b1} and {b2} cannot both "
                            f"hold joint {r.name} as the input moves; remove a link or a joint", "linkage")


def slider_gaps(linkage: Linkage, sol: Solution) -> dict[str, tuple[float, float]]:
    """How far each redundant slider comes apart over the poses of ``sol`` that assemble: the largest distance (mm)
    of its point from its guide's line (each as its own body carries it) and the largest turn (rad) of its sliding
    body relative to the guide's body (a prismatic joint keeps the drawn angle between them)."""
    from linkgen.kinematics.linkage import body_point

    s = linkage.structure
    out = {}
    for r in linkage.plan.redundant:
        if not r.slider:
            continue
        sl = s.slider_by_name[r.name]
        point = body_point(s, sol, sl.body, sl.point)[sol.ok]
        on_guide = body_point(s, sol, sl.guide, sl.point)[sol.ok]
        turn = (sol.angles[sl.guide] + sl.angle)[sol.ok]
        off = np.abs(np.cos(turn) * (point - on_guide)[:, 1] - np.sin(turn) * (point - on_guide)[:, 0])
        twist = np.abs(np.remainder(sol.angles[sl.body] - sol.angles[sl.guide] + math.pi, TWO_PI) - math.pi)[sol.ok]
        out[r.name] = (float(off.max(initial=0.0)), float(twist.max(initial=0.0)))
    return out


def out_of_reach(linkage: Linkage, values: np.ndarray) -> NoReturn:
    """Refuse input values the linkage does not reach, naming its reachable ranges."""
    crank = linkage.structure.inputs[0].kind == "crank"
    unit = "degrees" if crank else "mm"
    value = math.degrees(float(values[0])) if crank else float(values[0])
    if len(linkage.structure.inputs) != 1:
        raise SpecError(f"the inputs {[round(float(v), 9) for v in values]} do not assemble the linkage", "input")
    ranges = input_ranges(linkage) or ()
    if crank:
        # each range turned by whole turns so that its middle lies in (-180, 180] and the value beside it
        shown = [(math.degrees(a) - k, math.degrees(b) - k) for a, b in ranges
                 for k in [360.0 * round((math.degrees(a) + math.degrees(b)) / 720.0)]]
        value = math.remainder(value, 360.0)
    else:
        shown = list(ranges)
    n = digits_apart(value, [x for r in shown for x in r])
    text = " or ".join(f"[{a:.{n}g}, {b:.{n}g}]" for a, b in shown)
    raise SpecError(f"input {value:.{n}g} {unit} is out of reach; the linkage reaches {text} {unit}", "input")
