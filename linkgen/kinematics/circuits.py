"""The circuits of a four-bar, and on each the limits and the swing of every link pivoted on the ground.

A circuit is a set of poses the linkage moves through without being taken apart. In the frame of
:mod:`linkgen.kinematics.fourbar` (crank angle theta2, assembly labels open +1 and crossed -1):

* a crank that turns fully (crank-rocker, double crank): each assembly is a circuit of its own, the
  crank's full turn;
* a crank whose angles are limited (Grashof double rocker, rocker-crank, non-Grashof triple rocker):
  each range of crank angles is one circuit holding both assemblies, which meet at its ends, the toggles
  (coupler and rocker in line), where the crank turns back while the rest moves on. One range (a
  non-Grashof linkage's) is the only circuit; two ranges are two circuits the linkage never passes between;
* at a change point (Grashof class III) the assemblies meet inside the crank's travel, and the circuit
  is the branch :meth:`FourBar.sweep` follows through the fold (its label swaps there): with one change
  point a crank turn that branch comes back to its start after two turns.

On a circuit a link pivoted on the ground either turns fully or oscillates between two limits, where
its rate is zero: the rocker where crank and coupler are in line (extended or folded), the crank where
coupler and rocker are (the toggles). Its swing is the arc it actually sweeps between them,
counter-clockwise from the first limit to the second; a non-Grashof linkage's links sweep through the
ground line (theta = 0 or pi), by more than pi where the arc needs it. All angles in radians.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkgen.kinematics.fourbar import FEASIBILITY_TOL, TWO_PI, FourBar

#: poses a crank turn (or a range, each way) along a branch through a change point (class III)
SAMPLES = 4096
#: a sampled extreme of the rocker along such a branch is an exact limit position this near it (rad)
MATCH = 1e-3
#: a link whose angle varies by no more than this (rad) along such a branch does not move
STILL = 1e-9


@dataclass(frozen=True)
class Limit:
    """A limit position on a circuit: ``kind`` as :class:`~linkgen.kinematics.fourbar.DeadCentre`'s
    (``extended`` / ``folded``: crank and coupler in line, the rocker's limits; ``toggle-extended`` /
    ``toggle-folded``: coupler and rocker in line, the crank's), the crank and rocker angles there (rad)
    and the assembly there (+1 open, -1 crossed, 0 at a toggle, where the two meet)."""

    kind: str
    crank: float
    rocker: float
    assembly: int


@dataclass(frozen=True)
class Swing:
    """How a link pivoted on the ground moves on a circuit: it turns fully (no ``limits``, ``arc`` 2 pi),
    sweeps ``arc`` (rad, in (0, 2 pi)) counter-clockwise from ``start`` (rad, in (-pi, pi]) between its two
    ``limits``, in that order (its angle at the first is ``start``, at the second ``start + arc``), or stays
    at ``start`` (no ``limits``, ``arc`` 0: a rhombus's rocker on its kite branch)."""

    limits: tuple[Limit, ...]
    start: float
    arc: float

    @property
    def turns(self) -> bool:
        """Whether the link turns fully (a crank)."""
        return not self.limits and self.arc > 0

    @property
    def still(self) -> bool:
        """Whether the link does not move at all on the circuit."""
        return not self.limits and self.arc == 0

    @property
    def end(self) -> float:
        """The angle (rad) at the second limit: ``start + arc``, so above pi where the arc passes it."""
        return self.start + self.arc

    def through(self) -> tuple[float, ...]:
        """The ground line's directions (0 and pi, rad) that the oscillation sweeps through (strictly inside
        its arc): the course's rocker "oscillating through the ground line"; () for a link that turns or stays."""
        if not self.limits:
            return ()
        return tuple(d for d in (0.0, math.pi) if 0.0 < (d - self.start) % TWO_PI < self.arc)


@dataclass(frozen=True)
class Circuit:
    """One circuit of a four-bar: ``input_range`` (rad, lo < hi) the input angles it holds, None when the
    input turns fully; ``assemblies`` the labels on it (both for a range; for a full turn its label just
    after 0); ``turns`` the input turns after which it repeats (1, or 2 along a branch through one change
    point a turn; 0 for a range); ``folds`` the change points (input angles, rad) its branch passes through,
    its label swapping there; the ``crank`` and ``rocker`` swings, and how the coupler moves relative to the
    ground: ``turns`` (fully), ``oscillates`` or ``translates`` (never turning: a parallelogram's)."""

    input_range: tuple[float, float] | None
    assemblies: tuple[int, ...]
    turns: int
    folds: tuple[float, ...]
    crank: Swing
    rocker: Swing
    coupler: str

    def holds(self, theta: float, label: int) -> bool:
        """Whether the pose at input angle ``theta`` (rad) with assembly ``label`` (+-1, or 0 for a pose both
        assemblies place alike) is on this circuit (for a full turn taken as :meth:`FourBar.sweep` counts, from
        just after 0 with the first label)."""
        if self.input_range is not None:
            return _inside(theta, self.input_range)
        return self.turns == 2 or label in (0, self.label(theta))

    def label(self, theta: float) -> int:
        """The assembly label at input angle ``theta`` (rad) of a one-turn branch: its first label, swapped past
        a change point at pi (the one at 0 is where the branch starts)."""
        past = math.pi in self.folds and theta % TWO_PI >= math.pi
        return self.assemblies[0] * (-1 if past else 1)


def input_spans(fb: FourBar) -> tuple[tuple[float, float], ...]:
    """The crank angles (rad) the drawings sweep: a full turn (0, 2 pi), or every reachable range."""
    ranges = fb.input_ranges()
    return ((0.0, TWO_PI),) if ranges is None else ranges


def input_span(fb: FourBar) -> tuple[float, float]:
    """The crank angles (rad) a single drawing sweeps (the parts, a thumbnail): the first of :func:`input_spans`."""
    return input_spans(fb)[0]


def input_grid(fb: FourBar, n: int, span: tuple[float, float] | None = None) -> np.ndarray:
    """``n`` crank angles (rad) over ``span`` (by default :func:`input_span`), ascending, ends included, that the
    linkage can be drawn at: off a deltoid's undetermined fold. Where the crank pin meets the rocker pivot at crank
    angle 0 (ground = crank and coupler = rocker: no pose is determined there, and the poses refuse it), a full
    turn's ``n`` angles sit in the middle of ``n`` equal steps, half a step off its ends, and in a range that holds
    the fold (a double rocker's) the angles within half a step of it give way to the two half a step either side
    of it (one more angle where one sat on it), so that the drawing passes the fold as a sweep does."""
    lo, hi = input_span(fb) if span is None else span
    grid = np.linspace(lo, hi, n)
    if math.hypot(*fb._z(np.array(0.0))) > FEASIBILITY_TOL * fb.longest or n < 2:
        return grid
    if fb.input_ranges() is None:
        return lo + (np.arange(n) + 0.5) * ((hi - lo) / n)
    half = 0.5 * (hi - lo) / (n - 1)
    for turn in range(math.ceil((lo - half) / TWO_PI), math.floor((hi + half) / TWO_PI) + 1):
        fold = turn * TWO_PI
        sides = [x for x in (fold - half, fold + half) if lo <= x <= hi]
        grid = np.unique(np.concatenate([grid[np.abs(grid - fold) >= half], sides]))
    return grid


def circuits(fb: FourBar) -> tuple[Circuit, ...]:
    """The circuits of a crank-driven four-bar: one a range of crank angles, else one an assembly (or one
    branch of two turns through a change point); see the module's docstring."""
    ranges = fb.input_ranges()
    folds = fb.change_points()
    frames: list[tuple[tuple[float, float] | None, tuple[int, ...], int]]     # (input range, labels, turns)
    if ranges is not None:
        frames = [(r, (1, -1), 0) for r in ranges]
    elif len(folds) == 1:
        frames = [(None, (1, -1), 2)]
    else:
        frames = [(None, (1,), 1), (None, (-1,), 1)]
    candidates = _rocker_limits(fb)
    out = []
    for span, labels, turns in frames:
        bare = Circuit(span, labels, turns, folds, _TURNS, _TURNS, "")
        crank = _TURNS if span is None else _crank_swing(fb, span)
        limits = tuple(c for c in candidates if bare.holds(c.crank, c.assembly))
        if folds:
            rocker, coupler = _along_branch(fb, bare, limits)
        else:
            rocker, coupler = _swing(limits, _rocker_sample(fb, bare)), _coupler_turns(fb)
        out.append(Circuit(span, labels, turns, folds, crank, rocker, coupler))
    return tuple(out)


def drawn(found: tuple[Circuit, ...], theta: float, label: int) -> int:
    """The index of the circuit holding the pose at input angle ``theta`` (rad) with assembly ``label`` (the first
    if none does: an angle at the very end of a range, taken as rounding has it)."""
    return next((i for i, c in enumerate(found) if c.holds(theta, label)), 0)


def mirrored(circuit: Circuit) -> Circuit:
    """A circuit of a rocker-driven four-bar from its mirror image's (the mirror's crank is the rocker, see
    :meth:`FourBar.rocker_positions`; the labels are the mirror's, as the rocker sees them): the names swap,
    every angle theta becomes pi - theta (the input's range and folds are then the rocker's angles) and each
    arc runs the other way. Its :meth:`Circuit.holds` is then of no use: ask the mirror's."""
    def limit(m: Limit) -> Limit:
        kind = {"extended": "toggle-extended", "folded": "toggle-folded", "toggle-extended": "extended",
                "toggle-folded": "folded"}.get(m.kind, m.kind)          # a fold is all four links in line
        return Limit(kind, math.pi - m.rocker, math.pi - m.crank, m.assembly)

    def swing(m: Swing) -> Swing:
        if m.turns:
            return m
        return Swing(tuple(limit(x) for x in reversed(m.limits)), _principal(math.pi - m.end), m.arc)

    span = None if circuit.input_range is None else (math.pi - circuit.input_range[1],
                                                     math.pi - circuit.input_range[0])
    return Circuit(span, circuit.assemblies, circuit.turns, tuple(math.pi - f for f in circuit.folds),
                   swing(circuit.rocker), swing(circuit.crank), circuit.coupler)


_TURNS = Swing((), 0.0, TWO_PI)


def _principal(x: float) -> float:
    """x (rad) in (-pi, pi]."""
    y = math.remainder(x, TWO_PI)
    return math.pi if y == -math.pi else y


def _inside(theta: float, span: tuple[float, float]) -> bool:
    lo, hi = span
    return any(lo <= theta + k * TWO_PI <= hi for k in (-1, 0, 1))


def _rocker_limits(fb: FourBar) -> list[Limit]:
    """Every pose with crank and coupler in line (the rocker's limit positions on whichever circuit holds
    them): B at L2 + L3 (extended) or |L2 - L3| (folded) from O2 and at L4 from O4, on either side of the
    ground line, by the law of cosines; each with the assembly that places B there (0: both do)."""
    l1, l2, l3, l4 = fb.ground, fb.crank, fb.coupler, fb.rocker
    tol = FEASIBILITY_TOL * fb.longest
    found = []
    for kind, reach in (("extended", l2 + l3), ("folded", abs(l3 - l2))):
        if not (abs(l1 - l4) - tol <= reach <= l1 + l4 + tol) or reach <= tol:
            continue
        phi = math.acos(max(-1.0, min(1.0, (l1**2 + reach**2 - l4**2) / (2 * l1 * reach))))
        for side in ((1.0, -1.0) if 0.0 < phi < math.pi else (1.0,)):       # one pose on the ground line
            pin = reach * np.array([math.cos(side * phi), math.sin(side * phi)])
            crank = _principal(side * phi + (0.0 if kind == "extended" or l2 > l3 else math.pi))
            if math.hypot(*fb._z(np.array(crank))) <= tol:         # the crank pin on the rocker pivot
                continue
            found.append((kind, crank, pin))
    if not found:
        return []
    cranks = [crank for _, crank, _ in found]
    placed = {s: fb.positions(cranks, "open" if s > 0 else "crossed").b for s in (1, -1)}
    out = []
    for k, (kind, crank, pin) in enumerate(found):
        labels = [s for s in (1, -1) if np.linalg.norm(placed[s][k] - pin) <= 1e-7 * fb.longest]
        if labels:
            out.append(Limit(kind, crank, math.atan2(pin[1], pin[0] - l1), labels[0] if len(labels) == 1 else 0))
    return out


def _crank_swing(fb: FourBar, span: tuple[float, float]) -> Swing:
    """The crank's swing over a range of crank angles: from its low end to its high end, both toggles. There B
    lies on the line A -> O4, L4 from O4: the rocker points at A (coupler and rocker extended, |A O4| = L3 + L4,
    or folded with L4 > L3) or away from it (folded with L3 > L4), exactly, with no triangle solved."""
    lo, hi = span
    limits = []
    for crank in span:
        ax, ay = fb.crank * math.cos(crank), fb.crank * math.sin(crank)
        z = math.hypot(*fb._z(np.array(crank)))
        extended = abs(z - (fb.coupler + fb.rocker)) < abs(z - abs(fb.coupler - fb.rocker))
        away = not extended and fb.coupler > fb.rocker
        rocker = math.atan2(ay, ax - fb.ground) + (math.pi if away else 0.0)
        limits.append(Limit("toggle-extended" if extended else "toggle-folded", crank, _principal(rocker), 0))
    return Swing(tuple(limits), _principal(lo), hi - lo)


def _rocker_sample(fb: FourBar, circuit: Circuit) -> list[float]:
    """Rocker angles (rad) at a few poses of a circuit that passes no change point (so on its first label
    throughout) away from its ends, to tell which of the two arcs between the rocker's limits it sweeps."""
    if circuit.input_range is not None:
        lo, hi = circuit.input_range
        cranks = [lo + f * (hi - lo) for f in (0.5, 0.3, 0.7)]
    else:
        cranks = [f * TWO_PI for f in (0.3, 0.55, 0.8)]
    return fb.positions(cranks, "open" if circuit.assemblies[0] > 0 else "crossed").theta4.tolist()


def _swing(limits: tuple[Limit, ...], sample: list[float]) -> Swing:
    """The swing between two limits: the arc between their rocker angles that holds the sampled angles
    (the first one off both limits); a link with no limits turns fully."""
    if not limits:
        return _TURNS
    first, second = sorted(limits, key=lambda x: x.rocker)[:2]
    a, b = first.rocker, second.rocker
    arc = (b - a) % TWO_PI
    clear = [s for s in sample if min(abs(math.remainder(s - a, TWO_PI)), abs(math.remainder(s - b, TWO_PI))) > 1e-6]
    if clear and (clear[0] - a) % TWO_PI > arc:          # the other arc, from b round to a
        first, second, arc = second, first, TWO_PI - arc
    return Swing((first, second), _principal(first.rocker), arc)


def _coupler_turns(fb: FourBar) -> str:
    """How the coupler moves relative to the ground off a change point: it turns fully on a Grashof linkage
    (class I) whose ground or coupler is the shortest link (the shortest turns fully relative to its neighbours,
    and ground and coupler are opposite links), else oscillates (never on a non-Grashof one, class II)."""
    turns = fb.grashof.grashof_class == "I" and min(fb.ground, fb.coupler) == min(
        fb.ground, fb.crank, fb.coupler, fb.rocker)
    return "turns" if turns else "oscillates"


def _along_branch(fb: FourBar, circuit: Circuit, candidates: tuple[Limit, ...]) -> tuple[Swing, str]:
    """The rocker's swing and the coupler's motion on a circuit through a change point (class III),
    from poses along its branch (:data:`SAMPLES` a crank turn, off the folds): there the branch may pass a
    pose with crank and coupler in line (the fold itself, all four links in line) with the rocker turning on,
    or turn back at a fold where the crank pin sits on the rocker pivot. The rocker turns fully if its angle
    winds once round the loop, stays put if its angle varies by :data:`STILL` at most; otherwise its limits
    are the smallest and largest angle along the loop, each the exact limit position of crank and coupler
    in line that lies there (within :data:`MATCH` rad), else the pose sampled at the fold, of kind ``fold``.
    The coupler turns, oscillates or translates (its angle varies by :data:`STILL` at most) likewise."""
    theta2, theta3, theta4, labels = _loop(fb, circuit)
    if abs(_winding(theta3)) > 0.5:
        coupler = "turns"
    else:
        coupler = "translates" if np.ptp(np.cumsum(_steps(theta3))) <= STILL else "oscillates"
    if abs(_winding(theta4)) > 0.5:
        return _TURNS, coupler
    unwrapped = theta4[0] + np.concatenate([[0.0], np.cumsum(_steps(theta4)[:-1])])
    if np.ptp(unwrapped) <= STILL:
        return Swing((), _principal(float(theta4[0])), 0.0), coupler
    ends = []
    for k in (int(np.argmin(unwrapped)), int(np.argmax(unwrapped))):
        near = [c for c in candidates if abs(math.remainder(c.rocker - theta4[k], TWO_PI)) <= MATCH]
        ends.append(near[0] if near else Limit("fold", float(theta2[k]), float(theta4[k]), int(labels[k])))
    first, second = ends
    return Swing((first, second), _principal(first.rocker), (second.rocker - first.rocker) % TWO_PI), coupler


def _loop(fb: FourBar, circuit: Circuit) -> tuple[np.ndarray, ...]:
    """Crank, coupler and rocker angles and the labels at poses once round a circuit, in order: a full turn's
    branch (twice round for two turns), or a range up on one label and back on the other."""
    if circuit.input_range is None:
        n = SAMPLES * circuit.turns
        t = (np.arange(n) + 0.5) * (TWO_PI * circuit.turns / n)
        p = fb.sweep(t, "open" if circuit.assemblies[0] > 0 else "crossed")
        poses = [(t, p)]
    else:
        lo, hi = circuit.input_range
        t = lo + (np.arange(SAMPLES) + 0.5) * ((hi - lo) / SAMPLES)
        up = fb.sweep(t, "open")
        # at the toggle hi the labels meet: the way back is on the other one
        poses = [(t, up), (t[::-1], fb.sweep(t[::-1], "crossed" if up.assembly[-1] > 0 else "open"))]
    return tuple(np.concatenate(x) for x in zip(*[(t, p.theta3, p.theta4, p.assembly) for t, p in poses],
                                                strict=True))


def _steps(theta: np.ndarray) -> np.ndarray:
    """The turns between successive angles of a closed loop (rad, each within +-pi), the last back to the first."""
    return np.remainder(np.diff(np.append(theta, theta[0])) + math.pi, TWO_PI) - math.pi


def _winding(theta: np.ndarray) -> float:
    """Net turns (counter-clockwise positive) of an angle once round a closed loop of samples."""
    return float(np.sum(_steps(theta)) / TWO_PI)
