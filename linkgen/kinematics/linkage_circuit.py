"""The circuit a general linkage is drawn on, and what its outputs do over it.

A linkage whose input does not turn fully moves on one *circuit*: from the drawing the input runs to an end
of its range, where a dyad toggles (its two links in line); there the dyad goes over to its other branch and
the input comes back, and so on until the linkage is back on the drawing's branches. A four-bar triple
rocker's circuit is its range once on each assembly; a Grashof double rocker's range on the drawing's
branches is one of two pieces, each a circuit of its own, which the linkage never passes between (nor do
two limit positions on different circuits bound a swing). A slide whose range ends at the searched span's
bound (no toggle within reach) leaves its circuit open there.

:func:`circuit` follows the circuit piece by piece (each a :class:`~linkgen.kinematics.linkage.Linkage`
carried from the toggle with the toggling dyad's branch swapped, its change points found again);
:func:`outputs_over` gives each rocker's and ground slider's limit positions over it (refined where its rate
is 0: :func:`linkgen.kinematics.motion.limits`), the arc a rocker actually sweeps (its angle followed
continuously round the circuit: more than 180 degrees where it swings through), or that it turns fully, and
a slider's travel; :func:`extents_over` and :func:`transmission_over` the tracers' extents and the
transmission angles over every piece.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from linkgen.kinematics import motion
from linkgen.kinematics.linkage import DyadResult, Linkage, Solution
from linkgen.kinematics.motion import BRANCHED, Extreme
from linkgen.kinematics.structure import DyadStep

#: at most this many pieces are followed round a circuit
MAX_PIECES = 32
#: poses sampled on each piece to follow an output's angle round the circuit
SAMPLES = 1025
TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Piece:
    """One stretch of a circuit: the linkage on its branches there, the input values ``lo`` .. ``hi`` it covers
    (rad or mm), the way the input runs along it (``forward``: lo to hi), and the dyads running on the branch
    other than the drawing's, by joint."""

    linkage: Linkage
    lo: float
    hi: float
    forward: bool
    other: tuple[str, ...]

    def inputs(self, n: int) -> np.ndarray:
        """n input values along the piece, in the order the motion runs."""
        x = np.linspace(self.lo, self.hi, n)
        return x if self.forward else x[::-1]


@dataclass(frozen=True)
class Circuit:
    """The pieces of the drawing's circuit in the order the motion runs them (the drawing's first), whether they
    join up (``closed``; an open circuit ends at a slide's searched bound), whether the input turns fully (one
    piece, a revolution), and the other ranges the input reaches on the drawing's branches (separate circuits,
    never reached from the drawing)."""

    pieces: tuple[Piece, ...]
    closed: bool
    turns: bool
    separate: tuple[tuple[float, float], ...]


def _signs_at(linkage: Linkage, value: float) -> list[float]:
    return [float(s[0]) for s in linkage.signs(np.array([[value]]))]


def _other(linkage: Linkage, drawn: Linkage, value: float) -> tuple[str, ...]:
    """The joints of the dyads whose branch at ``value`` differs from the drawing linkage's there."""
    steps = linkage.plan.steps
    mine, theirs = _signs_at(linkage, value), _signs_at(drawn, value)
    return tuple(step.joint for i, step in enumerate(steps) if isinstance(step, DyadStep) and mine[i] != theirs[i])


def _run_at(ranges: Sequence[tuple[float, float]], value: float) -> tuple[float, float]:
    """The range that holds ``value`` (an end of it, to rounding)."""
    def distance(r: tuple[float, float]) -> float:
        return max(r[0] - value, value - r[1], 0.0)

    return min(ranges, key=distance)


def _follow(drawn: Linkage, start: Linkage, end: float, lo: float, hi: float) -> tuple[list[Piece], bool]:
    """The pieces after the one (``start``, lo..hi) from its end ``end``, until the circuit comes back to it
    (closed) or ends at a bound or a runaway (open)."""
    pieces: list[Piece] = []
    current = start
    mid0 = _signs_at(start, 0.5 * (lo + hi))
    steps = motion.dyad_steps(drawn)
    for _ in range(MAX_PIECES):
        if motion.bounded(current, end):
            return pieces, False
        kind, d = motion.stopping_dyad(current, np.array([end]))[0]
        index = steps[d]
        step = current.plan.steps[index]
        if kind != "limit" or not isinstance(step, DyadStep) or step.kind not in BRANCHED:
            return pieces, False
        signs = _signs_at(current, end)
        signs[index] = -signs[index]
        nxt = current.on(end, tuple(signs))
        if nxt.ranges is None:                       # cannot happen at a toggle; kept open rather than guessed
            return pieces, False
        a, b = _run_at(nxt.ranges, end)
        forward = abs(end - a) <= abs(end - b)
        if abs(a - lo) <= 1e-9 * max(1.0, abs(lo)) and abs(b - hi) <= 1e-9 * max(1.0, abs(hi)) \
                and _signs_at(nxt, 0.5 * (a + b)) == mid0:
            return pieces, True
        pieces.append(Piece(nxt, a, b, forward, _other(nxt, drawn, 0.5 * (a + b))))
        current, end = nxt, (b if forward else a)
    return pieces, False


def _revolutions(linkage: Linkage) -> tuple[Piece, ...]:
    """A crank that turns fully: its revolution from the drawing, and the next ones while a dyad's branch has
    swapped an odd number of times (a kite is back on its drawing only after two turns)."""
    lo, hi = motion.span(linkage)
    pieces = [Piece(linkage, lo, hi, True, ())]
    current = linkage
    for _ in range(MAX_PIECES):
        end = tuple(_signs_at(current, hi))
        if end == tuple(linkage.base_signs):
            break
        current = current.on(lo, end)
        pieces.append(Piece(current, lo, hi, True, _other(current, linkage, 0.5 * (lo + hi))))
    return tuple(pieces)


def circuit(linkage: Linkage) -> Circuit:
    """The circuit the drawing lies on (see the module's docstring): the drawing's range on its branches, then
    each piece the toggles lead to, both ways when the circuit is open."""
    ranges = linkage.ranges
    if ranges is None:
        return Circuit(_revolutions(linkage), True, True, ())
    lo, hi = ranges[0]
    first = Piece(linkage, lo, hi, True, ())
    after, closed = _follow(linkage, linkage, hi, lo, hi)
    before: list[Piece] = []
    if not closed:
        back, _ = _follow(linkage, linkage, lo, lo, hi)
        before = [Piece(p.linkage, p.lo, p.hi, not p.forward, p.other) for p in reversed(back)]
    pieces = (*before, first, *after)
    visited = [(p.lo, p.hi) for p in pieces if not p.other]
    separate = tuple(r for r in ranges[1:] if not any(abs(r[0] - a) <= 1e-9 and abs(r[1] - b) <= 1e-9
                                                       for a, b in visited))
    return Circuit(pieces, closed, False, separate)


@dataclass(frozen=True)
class OutputMotion:
    """What an output does over the circuit: its limit positions (rate 0; ``piece`` says on which), its least and
    greatest value (rad from the drawing, followed continuously round the circuit, for a rocker; mm along its
    guide for a slider) and where (input value, piece), and whether a rocker turns fully instead (then no
    limits bound it)."""

    limits: tuple[Extreme, ...]
    pieces: tuple[int, ...]
    least: tuple[float, float, int]
    greatest: tuple[float, float, int]
    turns: bool

    @property
    def travel(self) -> float:
        """Its swing (rad) or stroke (mm): greatest less least."""
        return self.greatest[0] - self.least[0]


def _sampled(c: Circuit, n: int) -> list[Solution]:
    return [p.linkage.solve(p.inputs(n)[None, :], strict=False) for p in c.pieces]


def outputs_over(c: Circuit, names: Sequence[str]) -> dict[str, OutputMotion]:
    """Each output's (a rocker's or a ground slider's) motion over the circuit."""
    if not names:
        return {}
    sliders = c.pieces[0].linkage.structure.slider_by_name
    found = [motion.limits(p.linkage, list(names), p.lo, p.hi) for p in c.pieces]
    samples = _sampled(c, SAMPLES)
    out = {}
    for name in names:
        rocker = name not in sliders
        values = [motion.values_of(p.linkage, sol, name)[0] for p, sol in zip(c.pieces, samples, strict=True)]
        flat = np.concatenate(values)
        followed = np.unwrap(flat) if rocker else flat
        # each refined limit's value on the followed scale: the nearest sample of its piece, plus the difference
        at: list[tuple[float, float, int]] = []
        limits: list[Extreme] = []
        pieces: list[int] = []
        offset = 0
        for k, (p, sol_values) in enumerate(zip(c.pieces, values, strict=True)):
            x = p.inputs(SAMPLES)
            for e in found[k][name]:
                j = int(np.argmin(np.abs(x - e.value)))
                here = followed[offset + j] + (math.remainder(e.position - sol_values[j], TWO_PI) if rocker
                                               else e.position - sol_values[j])
                at.append((here, e.value, k))
                limits.append(e)
                pieces.append(k)
            at += [(float(followed[offset + j]), float(x[j]), k) for j in (0, len(x) - 1)]
            offset += len(x)
        turns = rocker and c.closed and abs(followed[-1] - followed[0]) > math.pi
        least, greatest = min(at), max(at)
        out[name] = OutputMotion(tuple(limits), tuple(pieces), least, greatest, bool(turns))
    return out


def extents_over(c: Circuit, points: Sequence[str]) -> dict[str, tuple[tuple[float, float], tuple[float, float]]]:
    """Each point's least and greatest x and y (mm) over every piece of the circuit."""
    per = [motion.extents(p.linkage, points, p.lo, p.hi) for p in c.pieces]
    out = {}
    for point in points:
        xs = [e[point][0] for e in per]
        ys = [e[point][1] for e in per]
        out[point] = ((min(x[0] for x in xs), max(x[1] for x in xs)), (min(y[0] for y in ys), max(y[1] for y in ys)))
    return out


def transmission_over(c: Circuit) -> list[tuple[float, float, float, float, int, int]]:
    """Each dyad's least and greatest transmission angle (rad) over the circuit, where (input values) and on which
    piece: (min, at, max, at, piece of min, piece of max)."""
    per = [motion.transmission_extremes(p.linkage, p.lo, p.hi) for p in c.pieces]
    out = []
    for d in range(len(per[0])):
        lows = [(row[d][0], row[d][1], k) for k, row in enumerate(per) if not math.isnan(row[d][0])]
        highs = [(row[d][2], row[d][3], k) for k, row in enumerate(per) if not math.isnan(row[d][2])]
        lo = min(lows) if lows else (math.nan, per[0][d][1], 0)
        hi = max(highs) if highs else (math.nan, per[0][d][3], 0)
        out.append((lo[0], lo[1], hi[0], hi[1], lo[2], hi[2]))
    return out


def sweep_over(c: Circuit, n: int) -> Solution:
    """The linkage at n poses on each piece, the pieces one after another in the order the motion runs (one
    solution: its inputs go up and come back)."""
    sols = [p.linkage.solve(p.inputs(n)[None, :], strict=False) for p in c.pieces]
    if len(sols) == 1:
        return sols[0]
    first = sols[0]

    def joined(table: str) -> dict:
        return {k: np.concatenate([getattr(s, table)[k] for s in sols]) for k in getattr(first, table)}

    rotations = {b: (np.concatenate([s.rotations[b][0] for s in sols]), np.concatenate([s.rotations[b][1]
                                                                                         for s in sols]))
                 for b in first.rotations}
    def cat(i: int, figure: str) -> np.ndarray:
        return np.concatenate([getattr(s.dyads[i], figure) for s in sols])

    dyads = tuple(DyadResult(d.kind, d.bodies, d.joint, cat(i, "margin"), cat(i, "transmission"), cat(i, "slack"))
                  for i, d in enumerate(first.dyads))
    return Solution(np.concatenate([s.inputs for s in sols], axis=1), joined("points"), joined("velocities"),
                    joined("accelerations"), rotations, joined("omegas"), joined("alphas"), dyads,
                    np.concatenate([s.ok for s in sols]))
