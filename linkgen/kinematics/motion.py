"""The motion of a general linkage over its input: change points, reachable ranges, toggles and limit positions.

Searched on the motion that starts at the drawing: a crank's revolution (from the drawn angle, or
from inside the gap before the range the drawing lies in when the crank does not turn fully), or
a slide's travel of up to ``SLIDE_REACH`` times the drawing's own size either way (the same
wherever the drawing sits). Every search samples :data:`GRID` poses in one vectorised solve and
then refines each event to rounding, all events of a search at once: the outer joints' spread rate's
zero for the bottom of each dip of a dyad's margin (a change point where its slack touches 0 and
comes back, a gap the input cannot pass where it goes below: see
:data:`~linkgen.kinematics.linkage.CLOSE_TOL`), bisection for the ends of the reachable ranges,
golden sections for the transmission angles' extremes, Newton's method on the rate for the limit
positions of rockers, sliders and points (where the rate is 0 on a grid point as well as where it
changes sign between two). Only single-input linkages are searched; with more inputs the drawing's
branches are kept and the ranges are the caller's.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, NoReturn

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics.fourbar import digits_apart
from linkgen.kinematics.linkage import CLOSE_TOL, RUNAWAY, DyadResult
from linkgen.kinematics.groups import GROUP_KINDS
from linkgen.kinematics.structure import GROUND, DyadStep, GearStep, GroupStep, Pin

if TYPE_CHECKING:
    from linkgen.kinematics.linkage import Linkage, Solution

#: poses sampled over the revolution or the travel
GRID = 4096
#: how narrow (relative to max(1, |input|)) a transmission extreme's bracket is made (golden sections once went on
#: to rounding): where the angle is smooth it is flat there, and its value moves by far less than its rounding (its
#: second derivative times a width squared), where it has a corner (0 or 180 degrees at a toggle) by at most the
#: width (under 4e-10 degrees); its place was never known better than the square root of the rounding (a search by
#: values on a flat function)
EXTREME_WIDTH = 1e-12
#: the inputs a round of a transmission extreme's search asks at in each bracket (:func:`_sections`)
SECTIONS = 17
#: the most rounds of :func:`_sections` (each narrows a bracket 8-fold: some 20 reach rounding from a whole turn)
ROUNDS = 64
#: a slide input is searched this many times the drawing's own size (its largest distance between two points)
#: either way
SLIDE_REACH = 4.0
TWO_PI = 2.0 * math.pi
BRANCHED = ("RRR", "RRP", "PRR", "RPR")
#: a margin dip deeper than this on the grid is looked at (a sine: within about 0.6 degrees of in line)
DIP = 1e-2
#: a refined limit position's rate is at most this times the output's median rate over the grid (else the rate
#: changed sign through a pole: no limit there)
STOPPED = 1e-7
#: an output whose values over the grid stay within this of their size of each other does not move (:func:`_still`)
STILL = 1e-12


def reach(linkage: Linkage) -> float:
    """How far (mm) a slide input is searched either way of the drawing: :data:`SLIDE_REACH` times the drawing's
    own size."""
    return SLIDE_REACH * linkage.structure.size


def span(linkage: Linkage) -> tuple[float, float]:
    """The input values searched: the crank's revolution from :attr:`Linkage.revolution`, or the slide's
    travel."""
    if linkage.is_crank():
        x0 = linkage.revolution
        return x0, x0 + TWO_PI
    return -reach(linkage), reach(linkage)


def closes(result: DyadResult) -> np.ndarray:
    """Where a dyad assembles: its slack at least minus :data:`CLOSE_TOL` (in line to rounding counts), or, for a
    dyad with two slides, its guides not parallel (its joint finite)."""
    if result.kind in RUNAWAY:
        return result.slack > 0.0
    return result.slack >= -CLOSE_TOL


def _feasible(linkage: Linkage, x: np.ndarray) -> np.ndarray:
    """Where every dyad closes on the linkage's branches."""
    sol = linkage.solve(x[None, :], strict=False, derivatives=False)
    ok = np.ones(len(x), dtype=bool)
    for d in sol.dyads:
        ok &= closes(d)
    return ok


def dyad_steps(linkage: Linkage) -> list[int]:
    """The step index of each dyad (and class-III group), in solve order (the order of a solution's ``dyads``)."""
    return [i for i, s in enumerate(linkage.plan.steps) if isinstance(s, (DyadStep, GroupStep))]


def _events(linkage: Linkage, index: int, grid: np.ndarray, result: DyadResult) -> tuple[np.ndarray, np.ndarray]:
    """A dyad's change points and gaps over the grid (sorted input values): each dip of its margin on the grid
    refined to the bottom (the zero of its outer joints' spread rate, or golden sections for a dyad of two
    slides), a change point where its slack there is within :data:`CLOSE_TOL` of 0, a gap (a stretch the input
    cannot pass, its bottom given) where it is below."""
    # a slotted link's margin is 1 until its pins meet (a slot through the pivot): its dips show in its slack
    if result.kind in GROUP_KINDS:
        return np.empty(0), np.empty(0)          # a group's track stops at its toggles: no change points, no gaps
    m = {"RPR": result.slack}.get(result.kind, np.abs(result.margin) if result.kind in RUNAWAY else result.margin)
    k = np.flatnonzero((m[1:-1] <= m[:-2]) & (m[1:-1] <= m[2:]) & (m[:-2] > 0) & (m[2:] > 0) & (m[1:-1] < DIP)) + 1
    empty = np.empty(0)
    if not len(k):
        return empty, empty

    def at(x: np.ndarray) -> DyadResult:
        return linkage.solve(x[None, :], strict=False, upto=index + 1).dyads[-1]

    def spread(x: np.ndarray) -> np.ndarray:
        rate = at(x).spread
        if rate is None:                           # a dyad of two slides, which runs away instead
            raise TypeError(f"dyad {result.kind} has no spread rate")
        return rate

    if result.kind in RUNAWAY:
        found, _ = _golden(lambda x: np.abs(at(x).margin), grid[k - 1], grid[k + 1])
    else:
        found = _root(spread, grid[k - 1], grid[k + 1])
    inside = (found > grid[0]) & (found < grid[-1])
    found = found[inside]
    bottom = at(found)
    if result.kind in RUNAWAY:
        change, gap = np.zeros(len(found), dtype=bool), np.abs(bottom.margin) <= CLOSE_TOL
    else:
        change, gap = np.abs(bottom.slack) <= CLOSE_TOL, bottom.slack < -CLOSE_TOL
    return np.unique(found[change]), np.unique(found[gap])


def find_flips(linkage: Linkage) -> tuple[np.ndarray, ...]:
    """Per step, the input values where its branch swaps at a change point (sorted), found dyad by dyad in one
    solve over the searched span: each dyad's as soon as its margins are known, the earlier dyads' swaps applied.
    A margin that dips below 0 between two grid points is a gap the input cannot pass, not a change point."""
    steps = linkage.plan.steps
    if len(linkage.structure.inputs) != 1:
        return ()
    bare = replace(linkage, flips=())
    lo, hi = span(bare)
    grid = np.linspace(lo, hi, GRID + 1)
    flips: list[np.ndarray] = [np.empty(0) for _ in steps]

    def choose(index: int, result: DyadResult) -> np.ndarray | None:
        if result.kind not in BRANCHED:
            return None
        current = replace(bare, flips=tuple(flips))
        flips[index], _ = _events(current, index, grid, result)
        return flips[index]

    bare.solve(grid[None, :], strict=False, derivatives=False, choose=choose)
    return tuple(flips)


def _root(f: Callable[[np.ndarray], np.ndarray], a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """A zero of f in each [a, b] (vectorised bisection to rounding), or the end where |f| is smaller when f keeps
    its sign there.

    At most 64 halvings; once a halving leaves every bracket as it was (each at rounding: its midpoint one of its
    ends), every later one would ask f the same and leave them so again, and the search stops there."""
    fa, fb = f(a), f(b)
    keeps = np.sign(fa) == np.sign(fb)
    for _ in range(64):
        mid = 0.5 * (a + b)
        fm = f(mid)
        left = np.sign(fm) == np.sign(fa)
        was = a, b
        a, fa = np.where(left, mid, a), np.where(left, fm, fa)
        b = np.where(left, b, mid)
        if np.array_equal(a, was[0]) and np.array_equal(b, was[1]):
            break
    return np.where(keeps, np.where(np.abs(fa) <= np.abs(fb), a, b), 0.5 * (a + b))


def _golden(f: Callable[[np.ndarray], np.ndarray], a: np.ndarray, b: np.ndarray,
            iterations: int = 80) -> tuple[np.ndarray, np.ndarray]:
    """Minimisers of f on the brackets [a, b] (vectorised golden sections: f is asked for both inner points of
    every bracket at once) and f there.

    At most ``iterations`` sections; once a section leaves every bracket as it was (at rounding), every later one
    would ask f the same and leave them so again, and the search stops there."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    n = len(a)
    c, d = b - g * (b - a), a + g * (b - a)
    both = f(np.concatenate([c, d]))
    fc, fd = both[:n], both[n:]
    for _ in range(iterations):
        left = fc < fd
        was = a, b
        b, a = np.where(left, d, b), np.where(left, a, c)
        if np.array_equal(a, was[0]) and np.array_equal(b, was[1]):
            break                                  # c, d and f there as they are
        c, d = b - g * (b - a), a + g * (b - a)
        both = f(np.concatenate([c, d]))
        fc, fd = both[:n], both[n:]
    return np.where(fc < fd, c, d), np.minimum(fc, fd)


def _sections(f: Callable[[np.ndarray], np.ndarray], a: np.ndarray, b: np.ndarray, width: float,
              points: int = SECTIONS) -> tuple[np.ndarray, np.ndarray]:
    """Minimisers of f on the brackets [a, b] and f there, by sections: each round asks f at ``points`` evenly
    spaced inputs of every bracket at once (one call, the brackets' first inputs, then their second..., as
    :func:`_golden` asks its two) and keeps the two sections about the least, so that a bracket narrows
    (points - 1) / 2-fold a round, until each is at most ``width`` times max(1, |a|) wide or at rounding (at most
    :data:`ROUNDS` rounds). A solve of a few columns costs about what one of a few hundred does, so few rounds of
    many points each cost less than golden sections' many rounds of two: the narrowing a solve sets the cost."""
    n = len(a)
    rows = np.arange(n)
    u = np.linspace(0.0, 1.0, points)
    for _ in range(ROUNDS):
        x = a[:, None] + (b - a)[:, None] * u
        fx = f(x.T.ravel()).reshape(points, n).T
        k = np.argmin(fx, axis=1)
        lo, hi = x[rows, np.maximum(k - 1, 0)], x[rows, np.minimum(k + 1, points - 1)]
        if np.all(hi - lo <= width * np.maximum(1.0, np.abs(lo))) or (np.array_equal(lo, a) and
                                                                       np.array_equal(hi, b)):
            break
        a, b = lo, hi
    return x[rows, k], fx[rows, k]


def transmission_extremes(linkage: Linkage, lo: float, hi: float) -> list[tuple[float, float, float, float]]:
    """Each dyad's smallest and largest transmission angle (rad) over the inputs lo..hi, and where: (min, at,
    max, at), found on :data:`GRID` poses and refined by sections (:func:`_sections`, every dyad's two at once)."""
    grid = np.linspace(lo, hi, GRID + 1)
    sol = linkage.solve(grid[None, :], strict=False, derivatives=False)
    if not sol.dyads:
        return []
    gamma = np.array([d.transmission for d in sol.dyads])                  # (dyads, grid)
    usable = sol.ok & np.isfinite(gamma)
    rows, signs, best, at = [], [], [], []
    for d in range(len(sol.dyads)):
        for sign in (1.0, -1.0):
            values = np.where(usable[d], sign * gamma[d], np.inf)
            k = int(np.argmin(values))
            rows.append(d)
            signs.append(sign)
            best.append(values[k])
            at.append(k)
    rows_a, signs_a, k_a = np.array(rows), np.array(signs), np.array(at)

    def f(x: np.ndarray) -> np.ndarray:
        s = linkage.solve(x[None, :], strict=False, derivatives=False)
        table = np.array([d.transmission for d in s.dyads])
        which = np.tile(rows_a, len(x) // len(rows_a))
        sign = np.tile(signs_a, len(x) // len(rows_a))
        value = sign * table[which, np.arange(len(x))]
        return np.where(s.ok & np.isfinite(value), value, np.inf)

    x, value = _sections(f, grid[np.maximum(k_a - 1, 0)], grid[np.minimum(k_a + 1, GRID)], EXTREME_WIDTH)
    def extreme(j: int) -> tuple[float, float]:
        if value[j] < best[j]:                     # the sections keep the grid's best if they lose it
            return float(signs_a[j] * value[j]), float(x[j])
        return float(signs_a[j] * best[j]) if np.isfinite(best[j]) else float("nan"), float(grid[k_a[j]])

    return [extreme(2 * d) + extreme(2 * d + 1) for d in range(len(sol.dyads))]


@dataclass(frozen=True)
class Toggle:
    """A dyad in line: ``kind`` 'limit' (the input stops there: an end of a reachable range), 'change point'
    (the branches meet and the motion goes on) or 'runaway' (a dyad of two slides whose guides turn parallel: its
    joint runs to infinity there); the input value, the dyad's bodies and middle joint."""

    kind: str
    value: float
    bodies: tuple[str, ...]
    joint: str


def input_ranges(linkage: Linkage) -> tuple[tuple[float, float], ...] | None:
    """The input values (rad or mm) over which the linkage assembles on its branches: None when a crank turns
    fully; else closed intervals, the one holding the base input (the drawing's) first. A gap narrower than the
    grid is found from the dips of the dyads' margins; a slide's ranges may end at the searched span
    (:func:`bounded`)."""
    if len(linkage.structure.inputs) != 1:
        return None
    lo, hi = span(linkage)
    grid = np.linspace(lo, hi, GRID + 1)
    sol = linkage.solve(grid[None, :], strict=False, derivatives=False)
    ok = np.ones(len(grid), dtype=bool)
    gaps = []
    for index, result in zip(dyad_steps(linkage), sol.dyads, strict=True):
        ok &= closes(result)
        gaps.append(_events(linkage, index, grid, result)[1])
    bottoms = np.concatenate(gaps) if gaps else np.empty(0)
    if len(bottoms):                             # each gap's bottom, a pose that does not close, among the samples
        order = np.argsort(np.concatenate([grid, bottoms]), kind="stable")
        grid = np.concatenate([grid, bottoms])[order]
        ok = np.concatenate([ok, np.zeros(len(bottoms), dtype=bool)])[order]
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
    x0 = linkage.base_input
    runs.sort(key=lambda r: (not (r[0] <= x0 <= r[1] or r[0] <= x0 - TWO_PI <= r[1]), r[0]))
    return tuple((float(a), float(b)) for a, b in runs)


def bounded(linkage: Linkage, value: float) -> bool:
    """Whether a slide input's range end ``value`` is the searched span's bound (no toggle within reach)."""
    return not linkage.is_crank() and abs(value) >= reach(linkage)


def origin_for(ranges: Sequence[tuple[float, float]]) -> float:
    """Where a crank's revolution should start so that the first range is one piece of it: in the middle of the
    gap before it."""
    a = ranges[0][0]
    back = min((a - b) % TWO_PI or TWO_PI for _, b in ranges)
    return a - 0.5 * back


def _bisect(linkage: Linkage, a: np.ndarray, b: np.ndarray, a_ok: np.ndarray) -> np.ndarray:
    """The boundary between feasible and not in each [a, b] (``a_ok``: which side is feasible), to rounding; the
    feasible side's end. At most 64 halvings, stopping once one leaves every bracket as it was (as :func:`_root`)."""
    good, bad = np.where(a_ok, a, b), np.where(a_ok, b, a)
    for _ in range(64):
        mid = 0.5 * (good + bad)
        if not len(mid):
            break
        ok = _feasible(linkage, mid)
        was = good, bad
        good, bad = np.where(ok, mid, good), np.where(ok, bad, mid)
        if np.array_equal(good, was[0]) and np.array_equal(bad, was[1]):
            break
    return good


def stopping_dyad(linkage: Linkage, values: np.ndarray) -> list[tuple[str, int]]:
    """At each range end: whether a dyad toggles there ('limit') or runs away ('runaway'), and which (its index
    among the dyads): the one nearest in line (least slack, or least sine for a dyad of two slides)."""
    sol = linkage.solve(values[None, :], strict=False, derivatives=False)
    near = np.array([np.abs(d.slack) if d.kind not in RUNAWAY else np.abs(d.margin) for d in sol.dyads])
    out = []
    for column in range(len(values)):
        d = int(np.argmin(near[:, column]))
        out.append(("runaway" if sol.dyads[d].kind in RUNAWAY else "limit", d))
    return out


def toggles(linkage: Linkage) -> tuple[Toggle, ...]:
    """The ends of the reachable ranges (which dyad stops the input there; a slide's bound of the search is none)
    and the change points, by input value."""
    dyads = [(s.bodies, s.joint if isinstance(s, DyadStep) else ", ".join(s.joints)) for s in linkage.plan.steps
             if isinstance(s, (DyadStep, GroupStep))]
    out = []
    for index, step in enumerate(linkage.plan.steps):
        if isinstance(step, DyadStep) and linkage.flips:
            out += [Toggle("change point", float(v), step.bodies, step.joint) for v in linkage.flips[index]]
    ends = [end for rng in linkage.ranges or () for end in rng if not bounded(linkage, end)]
    if ends:
        for end, (kind, d) in zip(ends, stopping_dyad(linkage, np.array(ends)), strict=True):
            out.append(Toggle(kind, end, *dyads[d]))
    return tuple(sorted(out, key=lambda t: t.value))


@dataclass(frozen=True)
class Extreme:
    """A limit position of an output: its body (or slider), the input value there and the output's value (rad
    from the drawing for a rocker, mm along its guide for a slider)."""

    output: str
    value: float
    position: float


#: an output: a body (its angle), a ground slider (its travel) or a point's coordinate (point, 0 for x or 1 for y)
Output = str | tuple[str, int]


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
        elif isinstance(step, GroupStep):
            out += [body for _, body, other in step.pins if other == GROUND and body not in driven]
        elif isinstance(step, GearStep) and isinstance(step.attachment, Pin) and step.attachment.body == GROUND:
            out.append(step.body)                   # a gear or pinion turning on the frame
    return out


def ground_sliders(linkage: Linkage) -> list[str]:
    """The sliders on a ground guide that no input moves (the outputs whose stroke is reported)."""
    s = linkage.structure
    moved = {inp.slider for inp in s.inputs if inp.kind == "slide"}
    return [sl.name for sl in s.sliders if sl.guide == GROUND and sl.name not in moved]


def values_of(linkage: Linkage, sol: Solution, name: Output) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An output's value, rate and acceleration per unit input over a solution: a body's angle from the drawing
    (rad), a ground slider's travel from the drawing along its guide (mm), a point's x or y (mm)."""
    sliders = linkage.structure.slider_by_name
    if isinstance(name, tuple):
        point, axis = name
        return sol.points[point][:, axis], sol.velocities[point][:, axis], sol.accelerations[point][:, axis]
    if name not in sliders:
        return sol.angle(name), sol.omegas[name], sol.alphas[name]
    sl = sliders[name]
    u = np.array([math.cos(sl.angle), math.sin(sl.angle)])
    p = sol.points[sl.point] - np.asarray(linkage.structure.points[sl.point])
    # a pose the linkage cannot take is NaN (strict=False) and a rate at a toggle unbounded (inf): along the guide
    # those have no value, NaN, which the callers skip as not finite
    with np.errstate(invalid="ignore"):
        return p @ u, sol.velocities[sl.point] @ u, sol.accelerations[sl.point] @ u


def _brackets(grid: np.ndarray, rate: np.ndarray, periodic: bool) -> tuple[np.ndarray, np.ndarray]:
    """Brackets [a, b] of the rate's sign changes over the grid: between neighbours of opposite signs, and across
    the grid points where it is exactly 0 (the neighbours with a sign either side); across the ends too where the
    grid is one revolution of a motion that repeats (its last point is its first)."""
    n = len(grid) - 1 if periodic else len(grid)
    sign = np.where(np.isfinite(rate[:n]), np.sign(rate[:n]), 0.0)       # a toggle's unbounded rate says nothing
    nz = np.flatnonzero(sign != 0)
    if len(nz) < 2:
        return np.empty(0), np.empty(0)
    i, j = nz[:-1], nz[1:]
    if periodic:
        i, j = np.append(i, nz[-1]), np.append(j, nz[0] + n)
    change = sign[i] != sign[j % n]
    i, j = i[change], j[change]
    period = grid[-1] - grid[0]
    return grid[i], np.where(j >= n, grid[j % n] + period, grid[np.minimum(j, n - 1)])


def _repeats(linkage: Linkage, sol: Solution, lo: float, hi: float) -> bool:
    """Whether the inputs lo..hi are one revolution of a crank that brings every point back where it started."""
    if not linkage.is_crank() or abs(hi - lo - TWO_PI) > 1e-9 * TWO_PI:
        return False
    apart = [np.hypot(*(p[0] - p[-1])) for p in sol.points.values()]
    return max(apart, default=0.0) <= 1e-9 * linkage.structure.size


def limits(linkage: Linkage, outputs: Sequence[Output], lo: float, hi: float) -> dict[Output, tuple[Extreme, ...]]:
    """Where each output stops and turns back over the inputs lo..hi: its rate's sign changes on :data:`GRID`
    poses (across a grid point where it is 0 as well as between two), refined by Newton's method with its
    acceleration (bisection where a step would leave its bracket), every output's at once. Over one revolution
    of a crank that brings the linkage back, a limit at the ends is found too (the grid wraps)."""
    grid = np.linspace(lo, hi, GRID + 1)
    sol = linkage.solve(grid[None, :], strict=False)
    periodic = _repeats(linkage, sol, lo, hi)
    owner, xa, xb, scale = [], [], [], []
    for k, name in enumerate(outputs):
        value, rate, _ = values_of(linkage, sol, name)
        finite = np.abs(rate[np.isfinite(rate)])
        scale.append(float(np.median(finite)) if len(finite) else 0.0)
        if _still(value):
            continue                            # it does not move: its rate's signs are rounding's, no limits
        a, b = _brackets(grid, rate, periodic)
        owner += [k] * len(a)
        xa.append(a)
        xb.append(b)
    out: dict[Output, tuple[Extreme, ...]] = {name: () for name in outputs}
    if not owner:
        return out
    who = np.array(owner)
    xa_, xb_ = np.concatenate(xa), np.concatenate(xb)
    x = _newton(linkage, outputs, who, xa_, xb_)
    value, rate, _ = _pick(linkage, outputs, who, x)
    # a zero, not a sign change through a pole (where a dyad toggles and the rate is unbounded)
    stops = np.abs(rate) <= STOPPED * np.array(scale)[who]
    if periodic:
        x = np.where(x >= hi, x - TWO_PI, x)
    for k, name in enumerate(outputs):
        mine = (who == k) & stops
        order = np.argsort(x[mine], kind="stable")
        out[name] = tuple(Extreme(str(name), float(v), float(p))
                          for v, p in zip(x[mine][order], value[mine][order], strict=True))
    return out


def _still(value: np.ndarray) -> bool:
    """Whether an output's values over the grid stay within :data:`STILL` of their size (max(1, |value|)) of each
    other: it does not move (a slider's point across its guide, a pin on the ground), and the signs of its rate
    are rounding's, no limit positions (their brackets were every grid step, each refined to no purpose)."""
    finite = value[np.isfinite(value)]
    if not len(finite):
        return False
    return float(np.ptp(finite)) <= STILL * max(1.0, float(np.max(np.abs(finite))))


def _pick(linkage: Linkage, outputs: Sequence[Output], who: np.ndarray, x: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each column's own output's value, rate and acceleration at inputs x (one solve)."""
    sol = linkage.solve(x[None, :], strict=False)
    value, rate, acc = np.empty(len(x)), np.empty(len(x)), np.empty(len(x))
    for k in np.unique(who):
        mine = who == k
        v, w, al = values_of(linkage, sol, outputs[k])
        value[mine], rate[mine], acc[mine] = v[mine], w[mine], al[mine]
    return value, rate, acc


def _newton(linkage: Linkage, outputs: Sequence[Output], who: np.ndarray, xa: np.ndarray,
            xb: np.ndarray) -> np.ndarray:
    """The zero of each column's output's rate in its bracket [xa, xb]: Newton's method with its acceleration,
    bisection where a step would leave the bracket.

    At most 60 rounds; once a round leaves every column's input, bracket and rate at its end as they were (a
    column whose rate is rounding's about a flat zero, its Newton steps leaving the bracket and its bisection at
    rounding), every later round would ask the same and leave them so again, and the search stops there."""
    fa = _pick(linkage, outputs, who, xa)[1]
    x = 0.5 * (xa + xb)
    for _ in range(60):
        was = x, xa, xb, fa
        _, w, al = _pick(linkage, outputs, who, x)
        left = np.sign(w) == np.sign(fa)
        xa, xb = np.where(left, x, xa), np.where(left, xb, x)
        fa = np.where(left, w, fa)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(al != 0, w / np.where(al != 0, al, 1.0), np.inf)
        nxt = x - step
        done = np.abs(step) <= 1e-15 * np.maximum(1.0, np.abs(x))
        inside = (nxt >= xa) & (nxt <= xb) & np.isfinite(nxt)
        x = np.where(done, x, np.where(inside, nxt, 0.5 * (xa + xb)))
        if done.all() or all(np.array_equal(a, b, equal_nan=True) for a, b in zip(was, (x, xa, xb, fa),
                                                                                  strict=True)):
            break
    return x


def limit_positions(linkage: Linkage, output: Output, lo: float, hi: float) -> tuple[Extreme, ...]:
    """Where one output (a rocker, a slider on a ground guide, a point's coordinate) stops and turns back over the
    inputs lo..hi (see :func:`limits`)."""
    return limits(linkage, [output], lo, hi)[output]


def extents(linkage: Linkage, points: Sequence[str], lo: float, hi: float
            ) -> dict[str, tuple[tuple[float, float], tuple[float, float]]]:
    """The smallest and largest x and y (mm) of each point over the inputs lo..hi: the coordinates' limit
    positions refined, and the ends of the motion."""
    outputs: list[Output] = [(p, axis) for p in points for axis in (0, 1)]
    found = limits(linkage, outputs, lo, hi)
    ends = linkage.solve(np.array([[lo, hi]]), strict=False, derivatives=False)
    out = {}
    for p in points:
        axes = []
        for axis in (0, 1):
            values = [e.position for e in found[(p, axis)]] + list(ends.points[p][:, axis])
            axes.append((float(min(values)), float(max(values))))
        out[p] = (axes[0], axes[1])
    return out


def extent(linkage: Linkage, point: str, lo: float, hi: float) -> tuple[tuple[float, float], tuple[float, float]]:
    """The smallest and largest x and y (mm) of ``point`` over the inputs lo..hi (see :func:`extents`)."""
    return extents(linkage, [point], lo, hi)[point]


def time_ratio(linkage: Linkage, extremes: tuple[Extreme, ...]) -> float | None:
    """Slower stroke over faster (>= 1) for a crank turning fully and an output with two limit positions."""
    if not linkage.is_crank() or linkage.ranges is not None or len(extremes) != 2:
        return None
    travel = (extremes[1].value - extremes[0].value) % TWO_PI
    shorter = min(travel, TWO_PI - travel)
    return max(travel, TWO_PI - travel) / shorter if shorter > 0 else None


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


def shown_ranges(linkage: Linkage, ranges: Sequence[tuple[float, float]]) -> list[tuple[float, float]]:
    """Ranges in the user's unit: a crank's in degrees, each turned by whole turns so that its middle lies in
    (-180, 180]; a slide's in mm."""
    if not linkage.is_crank():
        return [(float(a), float(b)) for a, b in ranges]
    return [(math.degrees(a) - k, math.degrees(b) - k) for a, b in ranges
            for k in [360.0 * round((math.degrees(a) + math.degrees(b)) / 720.0)]]


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
    shown = shown_ranges(linkage, linkage.ranges or ())
    if crank:
        value = math.remainder(value, 360.0)
        value = value + 360.0 if value <= -180.0 else value          # in (-180, 180]
    n = digits_apart(value, [x for r in shown for x in r])
    text = " or ".join(f"[{a:.{n}g}, {b:.{n}g}]" for a, b in shown)
    raise SpecError(f"input {value:.{n}g} {unit} is out of reach; the linkage reaches {text} {unit}", "input")
