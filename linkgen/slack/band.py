"""The worst-case band of a linkage's motion under its slack, over the motion analysed (no I/O).

The band is first order in the slack (:mod:`linkgen.kinematics.sensitivity`): at each of :data:`SAMPLES` input
values over the motion analysed (the report's ``analysed`` range, on the drawing's branches) every tracer's
half-width across its path (along the normal, the path's direction turned 90 degrees counter-clockwise) and in
any direction, every output's half-width (a rocker's angle in rad, a ground slider's travel in mm along its
guide) and every dyad's transmission angle's. A dyad *binds* where its slack may bring it to its dead point (its
transmission angle 0, or 180 degrees for two bars): a linkage as made may lock there. For two bars (RRR) that is
where the band of their distance from in line (:class:`~linkgen.kinematics.sensitivity.InLine`), smooth through
the dead point, reaches 0; for a dyad with a slider, where its transmission angle's band reaches 0 (which near the
dead point, the angle going like the square root of the distance to it, gives about half the range). The widest
band is refined to :data:`REFINE_TO` of the range by finer grids round the widest sample.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics import motion
from linkgen.kinematics.dyads import perp
from linkgen.kinematics.linkage import Solution
from linkgen.kinematics.sensitivity import Response, SlackModel, response, slack_model, worst_case
from linkgen.mechanisms.general import Analysis
from linkgen.slack.table import Play, SlackTable

#: input values the band is computed at over the motion analysed (one a degree for a full turn)
SAMPLES = 361
#: how finely the widest band is placed: a fraction of the input's range
REFINE_TO = 1e-7
#: the dyads' kinds (a class-III group's result is named ``triad`` or ``group`` instead)
DYAD_KINDS = frozenset({"RRR", "RRP", "PRR", "RPR", "PRP", "RPP", "PPR"})
#: the directions (over half a turn) a tracer's worst displacement in any direction is the largest of
DIRECTIONS = 180
#: a tracer whose speed per unit input is below this fraction of the drawing's size stands still there: its band
#: across the path is its worst displacement in any direction
STILL = 1e-9


@dataclass(frozen=True)
class TracerBand:
    """A tracer's nominal path (n, 2) mm, the unit normal (n, 2) its band lies along, the band's half-width across
    the path (n,) mm and its worst displacement in any direction (n,) mm; inf where the linkage binds."""

    name: str
    path: np.ndarray
    normal: np.ndarray
    half_width: np.ndarray
    displacement: np.ndarray


@dataclass(frozen=True)
class OutputBand:
    """An output's nominal value (n,) and worst-case half-width (n,): a rocker's turn from the drawing (rad) or a
    ground slider's travel along its guide from the drawing (mm)."""

    name: str
    rocker: bool
    value: np.ndarray
    half_width: np.ndarray


@dataclass(frozen=True)
class DyadBand:
    """A dyad's transmission angle (n,) rad and its worst-case half-width (n,) rad; ``binds`` (n,) where its slack
    may bring it to its dead point (see the module's docstring), or the band is unbounded. For a class-III group
    (``kind`` ``triad`` or ``group``) the transmission is the angle whose sine is its closure's conditioning (as the
    solver reports it), the half-width NaN (not computed: the conditioning's first-order band needs the closure's
    second derivatives), and it binds only where the closure is singular (the response unbounded) or the group
    does not assemble."""

    kind: str
    bodies: tuple[str, ...]
    joint: str
    transmission: np.ndarray
    half_width: np.ndarray
    binds: np.ndarray


@dataclass(frozen=True)
class SlackBand:
    """The band of a linkage's motion under its slack (made by :func:`slack_band`).

    Attributes
    ----------
    analysis : Analysis
        The general-linkage analysis the band is of (a dedicated mechanism's general drawing).
    play : Play
        The pins' fit in their holes.
    tolerances : dict of str to float
        Each link's length tolerance (mm), the ground's too.
    model : SlackModel
        The slack's parameters.
    bounds : ndarray
        Each parameter's bound (mm).
    inputs : ndarray
        The input values (n,): rad for a crank, mm for a slide.
    tracers, outputs, dyads : tuple
        The bands of each tracer, output and dyad over ``inputs``.
    solution : Solution
        The nominal linkage solved at ``inputs``.
    response : Response
        Its first-order response to the slack there.
    """

    analysis: Analysis
    play: Play
    tolerances: dict[str, float]
    model: SlackModel
    bounds: np.ndarray
    inputs: np.ndarray
    tracers: tuple[TracerBand, ...]
    outputs: tuple[OutputBand, ...]
    dyads: tuple[DyadBand, ...]
    solution: Solution
    response: Response

    @property
    def reached(self) -> np.ndarray:
        """(n,) the samples the linkage as made reaches from its drawing without passing where it binds (past such
        a place it may lock, and past a change point its branch is not known): the run of samples round the drawn
        input where no dyad binds, round the end of a full turn too."""
        keep = ~self.binds
        a = self.analysis
        x = self.inputs
        start = int(np.argmin(np.abs(x - a.linkage.base_input)))
        out = np.zeros(len(x), dtype=bool)
        cyclic = bool(a.crank and abs(abs(x[-1] - x[0]) - 2 * math.pi) < 1e-9)
        for first, last in runs(keep, cyclic):
            if first <= start <= last:
                out[first:last + 1] = True
            elif last < first and (start >= first or start <= last):      # round the end of the turn
                out[first:] = True
                out[:last + 1] = True
        return out

    @property
    def binds(self) -> np.ndarray:
        """(n,) where any dyad binds."""
        out = np.zeros(len(self.inputs), dtype=bool)
        for d in self.dyads:
            out |= d.binds
        return out

    def at(self, x: np.ndarray) -> tuple[tuple[TracerBand, ...], tuple[OutputBand, ...], tuple[DyadBand, ...]]:
        """The tracers', outputs' and dyads' bands at input values ``x`` (rad or mm)."""
        return _bands(self.analysis, self.model, self.bounds, np.asarray(x, dtype=float))[:3]

    def bind_edge(self, dyad: int, inside: float, outside: float) -> float:
        """Where dyad number ``dyad`` starts to bind between an input ``inside`` a range where it binds and one
        ``outside`` it, by bisection to :data:`REFINE_TO` of the range."""
        span = float(self.inputs[-1] - self.inputs[0])
        while abs(inside - outside) > REFINE_TO * span:
            middle = 0.5 * (inside + outside)
            if bool(self.at(np.array([middle]))[2][dyad].binds[0]):
                inside = middle
            else:
                outside = middle
        return inside


def tolerances_of(table: SlackTable, a: Analysis) -> dict[str, float]:
    """Each body's length tolerance (mm): ``slack.links``'s for the links it names, ``length_tolerance`` else; a
    :class:`SpecError` naming ``slack.links.<name>`` for a link the linkage has not."""
    bodies = a.linkage.structure.bodies
    for name in table.links:
        if name not in bodies:
            raise SpecError(f"no link {name!r} in this linkage (links: {', '.join(bodies)})", f"slack.links.{name}")
    return {b: table.links.get(b, table.length_tolerance) for b in bodies}


def slack_band(table: SlackTable, play: Play, a: Analysis) -> SlackBand:
    """The band of the linkage ``a`` draws, with the pins' ``play`` and the table's length tolerances, at
    :data:`SAMPLES` input values over its motion analysed.

    Raises
    ------
    SpecError
        Naming ``slack``: a linkage of more than one input, or one with redundant constraints (a paradoxical or
        over-constrained linkage, which its slack lets move but no first order describes); naming
        ``slack.links.<name>`` for a link it has not.
    """
    if len(a.table.inputs) != 1:
        raise SpecError("the band is for a linkage of one input (with two, no one motion carries it)", "slack")
    if a.linkage.plan.redundant:
        names = ", ".join(r.name for r in a.linkage.plan.redundant)
        raise SpecError(f"the linkage has redundant constraints ({names}): its slack is what lets it move, which no "
                        "first-order band describes", "slack")
    tolerances = tolerances_of(table, a)
    model = slack_model(a.linkage.structure)
    bounds = model.bounds(play.radial, tolerances)
    inputs = np.linspace(float(a.span[0, 0]), float(a.span[0, -1]), SAMPLES)
    return SlackBand(a, play, tolerances, model, bounds, inputs, *_bands(a, model, bounds, inputs))


def _bands(a: Analysis, model: SlackModel, bounds: np.ndarray, x: np.ndarray
           ) -> tuple[tuple[TracerBand, ...], tuple[OutputBand, ...], tuple[DyadBand, ...], Solution, Response]:
    linkage = a.linkage
    s = linkage.structure
    sol = linkage.solve(x[None, :], strict=False)
    r = response(linkage, sol, model)
    tracers = tuple(_tracer(s.size, name, sol.points[name], sol.velocities[name], r, bounds)
                    for name in a.table.tracers)
    outputs = []
    for name in motion.rockers(linkage) + motion.ground_sliders(linkage):
        if name in s.slider_by_name:
            sl = s.slider_by_name[name]
            u = np.array([math.cos(sl.angle), math.sin(sl.angle)])
            value = (sol.points[sl.point] - np.asarray(s.points[sl.point])) @ u
            grad = np.einsum("i,nip->np", u, r.points[sl.point])
            outputs.append(OutputBand(name, False, value, worst_case(grad, model, bounds)))
        else:
            outputs.append(OutputBand(name, True, sol.angle(name), worst_case(r.turns[name], model, bounds)))
    dyads = []
    grads = iter(zip(r.transmission, r.inline, strict=True))
    for d in sol.dyads:
        if d.kind not in DYAD_KINDS:     # a class-III group: it locks where its closure (the response) is singular
            dyads.append(DyadBand(d.kind, d.bodies, d.joint, d.transmission, np.full(len(x), np.nan),
                                  r.singular | ~np.asarray(sol.ok, dtype=bool)))
            continue
        grad, inline = next(grads)
        h = worst_case(grad, model, bounds)
        if inline is None:               # a dyad with a slider: its transmission angle's band reaches 0
            binds = ~np.isfinite(h) | (d.transmission - h <= 0.0)
        else:                            # two bars: their distance from in line, extended or folded, reaches 0
            binds = ~np.isfinite(h)
            for margin, d_margin in ((inline.extended, inline.d_extended), (inline.folded, inline.d_folded)):
                binds |= margin - worst_case(d_margin, model, bounds) <= 0.0
        dyads.append(DyadBand(d.kind, d.bodies, d.joint, d.transmission, h, binds))
    return tracers, tuple(outputs), tuple(dyads), sol, r


def _tracer(size: float, name: str, path: np.ndarray, velocity: np.ndarray, r: Response,
            bounds: np.ndarray) -> TracerBand:
    """A tracer's band: across its path (along the normal), and its worst displacement in any direction."""
    grad = r.points[name]
    model = r.model
    angles = np.linspace(0.0, math.pi, DIRECTIONS, endpoint=False)
    directions = np.column_stack([np.cos(angles), np.sin(angles)])
    with np.errstate(invalid="ignore"):
        every = worst_case(np.einsum("di,nip->ndp", directions, grad), model, bounds)
    displacement = np.max(every, axis=1)
    speed = np.hypot(velocity[:, 0], velocity[:, 1])
    moving = np.isfinite(speed) & (speed > STILL * size)
    tangent = np.where(moving[:, None], velocity / np.where(moving, speed, 1.0)[:, None], np.array([1.0, 0.0]))
    normal = perp(tangent)
    with np.errstate(invalid="ignore"):
        across = worst_case(np.einsum("ni,nip->np", normal, grad), model, bounds)
    return TracerBand(name, path, normal, np.where(moving, across, displacement), displacement)


def refine_max(f: Callable[[np.ndarray], np.ndarray], x: np.ndarray, values: np.ndarray,
               keep: np.ndarray) -> tuple[float, float]:
    """The largest value of ``f`` near the largest of ``values`` on the grid ``x`` among the samples ``keep``: finer
    grids across the samples either side that are kept too, to :data:`REFINE_TO` of the range; (input, value)."""
    masked = np.where(keep & np.isfinite(values), values, -np.inf)
    i = int(np.argmax(masked))
    below, above = max(i - 1, 0), min(i + 1, len(x) - 1)
    lo, hi = float(x[below if keep[below] else i]), float(x[above if keep[above] else i])
    best_x, best = float(x[i]), float(values[i])
    span = float(x[-1] - x[0])
    while hi - lo > REFINE_TO * span:
        grid = np.linspace(lo, hi, 21)
        got = f(grid)
        got = np.where(np.isfinite(got), got, -np.inf)
        k = int(np.argmax(got))
        if got[k] > best:
            best_x, best = float(grid[k]), float(got[k])
        step = grid[1] - grid[0]
        lo, hi = max(float(grid[k]) - step, float(x[0])), min(float(grid[k]) + step, float(x[-1]))
    return best_x, best


def runs(mask: np.ndarray, cyclic: bool) -> list[tuple[int, int]]:
    """The runs of true samples of ``mask``, (first, last) index each; on a full turn (``cyclic``, the last
    sample the first) a run through the end joins the one from the start."""
    out: list[tuple[int, int]] = []
    start = None
    for i, flag in enumerate(mask):
        if flag and start is None:
            start = i
        if not flag and start is not None:
            out.append((start, i - 1))
            start = None
    if start is not None:
        out.append((start, len(mask) - 1))
    if cyclic and len(out) > 1 and out[0][0] == 0 and out[-1][1] == len(mask) - 1:
        out = [(out[-1][0], out[0][1]), *out[1:-1]]
    return out

