"""Any planar linkage solved dyad by dyad in closed form, vectorised over input values.

:class:`Linkage` holds a :class:`~linkgen.kinematics.structure.Structure` and its solve order;
:meth:`Linkage.solve` places every body at every input value at once: each dyad in closed
form (:mod:`linkgen.kinematics.dyads`), then velocities and accelerations per unit input speed
by differentiating each dyad's closure, a 2x2 linear solve per dyad in the same order (never
finite differences).

Frame and signs: the drawing's own frame, mm; angles in radians counter-clockwise. A body's
pose is ``world(x) = R(phi) x + T`` for its drawn points x (the drawing is phi = 0, T = 0).
Velocities are per unit speed of the input(s) (rad or mm per unit of input; multiply by the
input's speed), accelerations at constant input speed.

Branches: each dyad keeps the branch the drawing shows (the side its middle joint lies on).
At a change point (a dyad passes through its in-line position and goes on, the two branches
meeting) the smooth continuation swaps sides; :class:`Linkage` finds those input values on
the revolution (or the stroke) that starts at the drawing and counts them, so a crank angle
is read on the revolution that starts at the drawn angle: theta0 <= theta < theta0 + 2 pi (its end
kept as the end where a dyad's branch swaps an odd number of times a turn).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import ClassVar, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from functools import cached_property
from linkgen.kinematics import compiled, dyads, fused, groups
from linkgen.kinematics.dyads import cross, dot, perp
from linkgen.kinematics.grashof import check_finite
from linkgen.kinematics.structure import (GROUND, Attachment, DyadStep, FixedStep, GearStep, GroupStep, Input,
                                          InputStep, Pin, Plan, Slide, Structure, plan)

#: a dyad whose margin (a sine) is above minus this is taken to close, at its toggle: the margin grows like the
#: square root of the distance past the toggle, so this snaps inputs within about 1e-10 (relative to the links)
#: beyond it, as the four-bar's closed form does
FEASIBILITY_TOL = 1e-5
#: within this of a change point (rad or mm of input) the rates are the branch's limit, interpolated from rates
#: one and two of it away
CHANGE_REACH = 1e-2
#: a dyad's slack (see :class:`DyadResult`) within this of 0 is in line to rounding: a change point where it
#: touches 0 and comes back, an end of the input's range where it goes below
CLOSE_TOL = 3e-14
#: within this distance (relative to the drawing's size) of each other, a deltoid's two equal-radius pins are
#: taken to meet: its joint is placed by the limit along the motion (the pins' relative velocity and
#: acceleration), not by the direction between them, which rounding leaves undetermined there
FOLD_REACH = 2e-6
#: the dyads that run away (their joint to infinity) where their guides turn parallel, instead of toggling
RUNAWAY = ("PRP", "RPP", "PPR")
TWO_PI = 2.0 * math.pi
#: the kernels :meth:`Linkage.positions` can run on: numpy's (the default) and numba's, optional
ENGINES = ("numpy", "numba")
T = TypeVar("T")
U = TypeVar("U")


@dataclass(frozen=True)
class Body:
    """A body's pose over the poses: its rotation (cos, sin) (n,) from the drawing and its translation T (n, 2) mm,
    so that its drawn point x is at ``R(phi) x + T``."""

    c: np.ndarray
    s: np.ndarray
    T: np.ndarray

    def at(self, x: np.ndarray) -> np.ndarray:
        """World positions of drawn point(s) x (2,) -> (n, 2)."""
        return np.stack([self.c * x[0] - self.s * x[1], self.s * x[0] + self.c * x[1]], axis=-1) + self.T

    def rotate(self, v: np.ndarray) -> np.ndarray:
        """A drawn direction v (2,) in the world, (n, 2)."""
        return np.stack([self.c * v[0] - self.s * v[1], self.s * v[0] + self.c * v[1]], axis=-1)


@dataclass(frozen=True)
class Rates:
    """A body's velocity field per unit input speed: its angular velocity w (n,) (rad per unit of input,
    counter-clockwise positive) and the velocity vT (n, 2) of its material point at T (n, 2) mm, its pose's
    translation."""

    T: np.ndarray
    w: np.ndarray
    vT: np.ndarray

    def vel(self, xw: np.ndarray) -> np.ndarray:
        """Velocity of the body's material point at world position(s) xw (n, 2)."""
        return self.vT + self.w[:, None] * perp(xw - self.T)


@dataclass(frozen=True)
class Motion(Rates):
    """A body's velocity field (:class:`Rates`) with its acceleration field at constant input speed: its angular
    acceleration al (n,) and the acceleration aT (n, 2) of its material point at T."""

    al: np.ndarray
    aT: np.ndarray

    def acc(self, xw: np.ndarray) -> np.ndarray:
        """Acceleration of the body's material point at world position(s) xw (n, 2)."""
        r = xw - self.T
        return self.aT + self.al[:, None] * perp(r) - (self.w**2)[:, None] * r


def _pinned(c: np.ndarray, s: np.ndarray, pw: np.ndarray, pd: np.ndarray) -> Body:
    """A body turned by (c, s) whose drawn point pd is at world pw."""
    return Body(c, s, pw - np.stack([c * pd[0] - s * pd[1], s * pd[0] + c * pd[1]], axis=-1))


@dataclass(frozen=True)
class DyadResult:
    """One dyad over the poses: its margin (>= 0 where it closes, 0 at its toggle) and its transmission angle
    (rad, in [0, pi] for RRR, [0, pi/2] otherwise; 0 or pi at the toggle)."""

    kind: str
    bodies: tuple[str, ...]
    joint: str
    margin: np.ndarray
    transmission: np.ndarray
    #: how far the dyad is from its in-line position, relative to its links and to where its pins sit (so that
    #: rounding is below :data:`CLOSE_TOL`): (r1 + r2 - d) or (d - |r1 - r2|) for RRR, r - h for RRP, d - |offset|
    #: for RPR, over (the links + the pins' largest coordinate); < 0 where it cannot close. For the dyads with two
    #: slides (PRP, RPP), which run away instead of toggling, the signed sine of their guides' angle (> 0 drawn)
    slack: np.ndarray
    #: the rate (per unit input) at which the dyad's outer joints move apart (their distance, or the pin's from
    #: the guide line): 0 where the dyad is in line at a change point; None without derivatives
    spread: np.ndarray | None = None


@dataclass(frozen=True)
class Solution:
    """Every point's position, velocity and acceleration (n, 2) over the poses; every body's angle (rad from the
    drawing), angular velocity and acceleration; each dyad's margin and transmission angle; the inputs."""

    inputs: np.ndarray
    points: dict[str, np.ndarray]
    velocities: dict[str, np.ndarray]
    accelerations: dict[str, np.ndarray]
    rotations: dict[str, tuple[np.ndarray, np.ndarray]]
    omegas: dict[str, np.ndarray]
    alphas: dict[str, np.ndarray]
    dyads: tuple[DyadResult, ...]
    ok: np.ndarray

    @property
    def angles(self) -> dict[str, np.ndarray]:
        """Each body's turn from the drawing (rad, in (-pi, pi]), computed when asked."""
        return {b: np.arctan2(sn, c) for b, (c, sn) in self.rotations.items()}

    def angle(self, body: str) -> np.ndarray:
        """One body's turn from the drawing (rad, in (-pi, pi])."""
        c, sn = self.rotations[body]
        return np.arctan2(sn, c)


@dataclass(frozen=True)
class Positions:
    """Every point's position (n, 2) mm over the poses (a ground point as a read-only broadcast row), the inputs as
    given (k, n) and ``ok``: what :meth:`Linkage.positions` gives."""

    inputs: np.ndarray
    points: dict[str, np.ndarray]
    ok: np.ndarray
    #: each point's velocity and acceleration (n, 2) per unit input speed, where asked for (else empty)
    velocities: dict[str, np.ndarray] = field(default_factory=dict)
    accelerations: dict[str, np.ndarray] = field(default_factory=dict)


def _positions_of(sol: Solution) -> Positions:
    return Positions(sol.inputs, sol.points, sol.ok, sol.velocities, sol.accelerations)


#: the searches' hook into a solve (see :meth:`Linkage.solve`): a dyad's step index and result -> its change points
Chooser = Callable[[int, DyadResult], np.ndarray | None]


@dataclass(frozen=True)
class Linkage:
    """A planar linkage with its solve order and its branches over the motion.

    ``flips`` holds, per step, the input values where that dyad's branch swaps sides at a change point (sorted,
    on the revolution that starts at ``origin`` for a crank). Each step's branch is ``start``'s sign at its
    input value (the drawing's signs at the drawn input unless given: another assembly of the same linkage,
    a piece of a circuit), swapped at every change point between there and the pose. ``origin`` (rad) is where
    a crank's revolution starts: the drawn angle, or the low end of the range the drawing lies in when the crank
    does not turn fully, so that the range is one piece of it.

    Made by :meth:`of` from a structure (which finds the flips and checks the redundant constraints); positions
    in the drawing's frame (mm), angles counter-clockwise in radians.

    Parameters
    ----------
    structure : Structure
        The joints' drawn positions, the links, the sliders and the inputs.
    plan : Plan
        The solve order: the inputs, then the dyads.
    flips : tuple of ndarray, optional
        Per step, the input values where its dyad swaps sides.
    origin : float, optional
        Where a crank's revolution starts (rad); the drawn angle unless given.
    start : tuple, optional
        The input value and the steps' branch signs there; the drawing's unless given.
    """

    structure: Structure
    plan: Plan
    flips: tuple[np.ndarray, ...] = field(default=())
    origin: float | None = None
    start: tuple[float, tuple[float, ...]] | None = None
    #: the class-III groups' continuation tracks (:mod:`linkgen.kinematics.groups`), filled when first solved and
    #: shared with the linkages made from this one by ``replace`` (keyed by what a track depends on)
    tracks: dict[tuple[object, ...], groups.Track] = field(default_factory=dict, compare=False, repr=False)

    @classmethod
    def of(cls, structure: Structure) -> Linkage:
        """The linkage of a structure, with its change points found over the motion that starts at the drawing
        (over the range it lies in, when a crank does not turn fully)."""
        from linkgen.kinematics.motion import check_redundant, find_flips, origin_for

        bare = cls(structure, plan(structure))
        linkage = replace(bare, flips=find_flips(bare))
        for _ in range(2):              # a change point below the drawing is passed going down from it, not round
            ranges = linkage.ranges if linkage.is_crank() else None
            if ranges is None:
                break
            origin = origin_for(ranges)
            if linkage.origin is not None and abs(math.remainder(origin - linkage.origin, TWO_PI)) <= 1e-9:
                break
            moved = replace(bare, origin=origin)
            linkage = replace(moved, flips=find_flips(moved))
        check_redundant(linkage)
        return linkage

    def on(self, value: float, signs: tuple[float, ...]) -> Linkage:
        """The same linkage carried from input ``value`` (rad or mm) with each step's branch sign ``signs`` there
        (another assembly, or the next piece of a circuit), its change points found again."""
        from linkgen.kinematics.motion import find_flips

        bare = replace(self, flips=(), start=(float(value), tuple(float(v) for v in signs)))
        return replace(bare, flips=find_flips(bare))

    # ------------------------------------------------------------------ inputs

    @property
    def drawn_inputs(self) -> np.ndarray:
        """Each input's value in the drawing (rad for a crank, 0 mm for a slide)."""
        return np.array([input_angle(self.structure, inp) for inp in self.structure.inputs])

    def is_crank(self) -> bool:
        """Whether the one input turns a link (its values wrap every 2 pi)."""
        return len(self.structure.inputs) == 1 and self.structure.inputs[0].kind == "crank"

    @cached_property
    def revolution(self) -> float:
        """Where a crank's revolution of input values starts (rad): ``origin``, else the drawn angle (found once:
        every solve asks for it)."""
        return float(self.drawn_inputs[0]) if self.origin is None else self.origin

    def unwrap(self, values: np.ndarray) -> np.ndarray:
        """Crank angles on the revolution that starts at :attr:`revolution`, t0 <= theta < t0 + 2 pi, any angle
        turned onto it by whole turns; where a dyad's branch swaps an odd number of times a turn (a kite: not back
        at its start after one), its end t0 + 2 pi is kept as the end."""
        if not self.is_crank():
            return values
        t0 = self.revolution
        values = np.asarray(values, dtype=float)
        wrapped = t0 + np.mod(values - t0, TWO_PI)
        if all(len(f) % 2 == 0 for f in self.flips):
            return wrapped                  # back on its branches after a turn: the end is the start, exactly
        return np.where((values >= t0) & (values <= t0 + TWO_PI), values, wrapped)

    @cached_property
    def base_signs(self) -> tuple[float, ...]:
        """Each step's branch sign at the input value the branches are carried from (+1 for steps without one),
        found once (every fused or compiled solve asks for them)."""
        return _drawn_signs(self.structure, self.plan) if self.start is None else self.start[1]

    @property
    def base_input(self) -> float:
        """The input value the branches are carried from (unwrapped): the drawing's, or ``start``'s."""
        value = float(self.drawn_inputs[0]) if self.start is None else self.start[0]
        return float(self.unwrap(np.array([value]))[0])

    def signs(self, inputs: np.ndarray) -> list[np.ndarray]:
        """Each step's branch sign at each pose: the base sign, swapped at every change point passed on the way
        there from the base input."""
        base = self.base_signs
        if not any(len(f) for f in self.flips) or len(self.structure.inputs) != 1:
            return [np.full(inputs.shape[1], s) for s in base]
        x = self.unwrap(inputs[0])
        return [self.step_signs(s, flips, x) for s, flips in zip(base, self.flips, strict=True)]

    def step_signs(self, base: float, flips: np.ndarray, x: np.ndarray) -> np.ndarray:
        """One step's branch sign at input values x (unwrapped): ``base`` at the base input, swapped at each of its
        change points ``flips`` passed on the way from there (a value at a change point is past it)."""
        x0 = self.base_input
        ahead = np.searchsorted(flips, x, side="right") - np.searchsorted(flips, x0, side="right")
        return base * np.where(ahead % 2 == 0, 1.0, -1.0)

    @cached_property
    def program(self) -> fused.Program | None:
        """The solve order planned once for the fused kernels (:mod:`linkgen.kinematics.fused`), or None where a
        step needs the general path."""
        return fused.program(self.structure, self.plan.steps, tuple(float(v) for v in self.drawn_inputs),
                             FOLD_REACH)

    @cached_property
    def compiled_program(self) -> compiled.Encoded:
        """The fused program as the compiled kernel's arrays (:func:`linkgen.kinematics.compiled.encode`), made
        once; only for a linkage that has a :attr:`program`."""
        prog = self.program
        assert prog is not None
        return compiled.encode(prog, FEASIBILITY_TOL)

    @cached_property
    def ranges(self) -> tuple[tuple[float, float], ...] | None:
        """The input values it reaches on its branches (:func:`linkgen.kinematics.motion.input_ranges`), found
        once."""
        from linkgen.kinematics.motion import input_ranges

        return input_ranges(self)

    # ------------------------------------------------------------------ solving

    def solve(self, inputs: ArrayLike, rates: ArrayLike | None = None, *, strict: bool = True,
              derivatives: bool = True, upto: int | None = None, signs: list[np.ndarray] | None = None,
              choose: Chooser | None = None) -> Solution:
        """Every body at each input value: ``inputs`` (n,) for one input, (k, n) for k; ``rates`` the inputs'
        speeds (1 each unless given) for the velocities and accelerations. With ``strict`` a value the linkage does
        not reach is a :class:`SpecError` naming the input's reachable range, and one that is not a finite number
        (NaN, +-inf) one naming it (degrees or mm); else those poses are marked in ``ok``. ``upto`` stops after
        that many steps, ``signs`` gives each step's branch at each pose, and ``choose`` (index, the dyad's result)
        may answer a dyad's change points once its margins are known, which then place it (for the searches of
        :mod:`linkgen.kinematics.motion`)."""
        x = np.atleast_2d(np.asarray(inputs, dtype=float))
        k = len(self.structure.inputs)
        if x.shape[0] != k:
            raise SpecError(f"the linkage has {k} input(s); give {k} row(s) of values", "input")
        if strict:
            for inp, row in zip(self.structure.inputs, x, strict=True):
                crank = inp.kind == "crank"
                check_finite(row, "input", "input", "degrees" if crank else "mm", math.degrees if crank else float)
        r = np.ones(k) if rates is None else np.asarray(rates, dtype=float).reshape(k)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):   # not strict: +-inf marked, unsaid
            given = x
            x = np.vstack([self.unwrap(x[0]), *x[1:]]) if self.is_crank() else x
            signs = self.signs(x) if signs is None else list(signs)
            sol = _solve(self, x, r, signs, strict, derivatives, upto, choose)
            if strict and not sol.ok.all():
                from linkgen.kinematics.motion import out_of_reach

                out_of_reach(self, given[:, ~sol.ok][:, 0])
            if derivatives and upto is None and len(x) == 1 and any(len(f) for f in self.flips):
                self._rates_at_change_points(sol, r)
            return sol

    def positions(self, inputs: ArrayLike, *, derivatives: bool = False, strict: bool = True,
                  engine: str = "numpy") -> Positions:
        """Every joint's position (n, 2) mm at each input value, with ``derivatives`` its velocity and acceleration
        per unit input speed, and nothing else (no rotations, margins or body rates): what :meth:`solve` gives in
        ``points`` (``velocities``, ``accelerations``), on the same branches, in less time and memory (the fused
        kernels of :mod:`linkgen.kinematics.fused`, chunk by chunk). ``strict`` as for :meth:`solve`.

        ``engine``: ``"numpy"`` (the default) or ``"numba"``, the optional compiled kernel of
        :mod:`linkgen.kinematics.compiled` (positions, and with ``derivatives`` their rates too); a
        :class:`SpecError` naming it where numba is not installed."""
        if engine not in ENGINES:
            raise SpecError(f"one of {', '.join(ENGINES)}, not {engine!r}", "engine")
        if engine == "numba" and not compiled.available():
            raise SpecError("'numba' needs numba installed (pip install 'camgen[fast]')", "engine")
        x = np.atleast_2d(np.asarray(inputs, dtype=float))
        prog = self.program
        flipped = any(len(f) for f in self.flips)
        if prog is None or x.shape[0] != 1 or (derivatives and flipped):
            return _positions_of(self.solve(x, strict=strict, derivatives=derivatives))
        # the least and largest value, found without a temporary array (a fresh one's pages cost more than the
        # compiled kernel at 10^4 poses): NaN where one is NaN, so +-inf or NaN anywhere shows in them
        lo, hi = (float(x[0].min()), float(x[0].max())) if len(x[0]) else (0.0, 0.0)
        if strict and not (math.isfinite(lo) and math.isfinite(hi)):
            check_finite(x[0], "input", "input", "degrees", math.degrees)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            given = x
            # the crank's turn is periodic: values within a few turns of the drawing need no unwrapping unless a
            # change point's branch swap depends on the revolution they lie on
            rev = self.revolution
            near = bool(len(x[0])) and max(hi - rev, rev - lo) <= 4 * TWO_PI
            x = self.unwrap(x[0])[None, :] if flipped or not near else x
            signs = self.signs(x) if flipped else list(self.base_signs)
            try:
                if engine == "numba":
                    got = compiled.positions(self.compiled_program, x, signs,
                                             speeds=np.ones(1) if derivatives else None)
                    out = fused.Outputs(got.points, got.velocities, got.accelerations, {}, {}, {}, [], [], [], [],
                                        got.ok)
                else:
                    out = fused.run(prog, x, np.ones(1), signs, derivatives, False, FEASIBILITY_TOL)
            except fused.Folded:
                return _positions_of(self.solve(given, strict=strict, derivatives=derivatives))
        if strict and not out.ok.all():
            from linkgen.kinematics.motion import out_of_reach

            out_of_reach(self, given[:, ~out.ok][:, 0])
        points, vels, accs = _fused_points(prog, out, x.shape[1], derivatives)
        return Positions(given, points, out.ok, vels, accs)

    def _rates_at_change_points(self, sol: Solution, rates: np.ndarray) -> None:
        """Rates within ``CHANGE_REACH`` of a change point, where a dyad's 2x2 solve is 0/0: the branch's limit,
        the quintic through the analytic rates at 1, 2 and 3 ``CHANGE_REACH`` either side (the branch is smooth;
        there its rates are conditioned well enough for about 7 digits)."""
        x = sol.inputs[0]
        flips = np.unique(np.concatenate([f for f in self.flips if len(f)]))
        nearest = flips[np.argmin(np.abs(x[:, None] - flips[None, :]), axis=1)]
        near = np.abs(x - nearest) < CHANGE_REACH
        if not near.any():
            return
        centre = nearest[near]
        nodes = np.array([-3.0, -2.0, -1.0, 1.0, 2.0, 3.0])
        stencil = [_solve(self, (centre + h * CHANGE_REACH)[None, :], rates,
                          self.signs((centre + h * CHANGE_REACH)[None, :]), False, True, None, None) for h in nodes]
        u = (x[near] - centre) / CHANGE_REACH
        weights = [np.prod([(u - nodes[m]) / (nodes[k] - nodes[m]) for m in range(len(nodes)) if m != k], axis=0)
                   for k in range(len(nodes))]
        for rate in ("velocities", "accelerations", "omegas", "alphas"):
            table = getattr(sol, rate)
            for name, values in table.items():
                mixed = sum(w.reshape(w.shape + (1,) * (values.ndim - 1)) * getattr(st, rate)[name]
                            for w, st in zip(weights, stencil, strict=True))
                values = values.copy()
                values[near] = mixed
                table[name] = values


def body_point(s: Structure, sol: Solution, body: str, point: str) -> np.ndarray:
    """Where ``body`` puts drawn ``point`` at each pose of ``sol`` (n, 2) mm (a redundant joint's holders may
    disagree)."""
    first = s.bodies[body][0]
    d = _pt(s, point) - _pt(s, first)
    c, sn = np.cos(sol.angles[body]), np.sin(sol.angles[body])
    return sol.points[first] + np.stack([c * d[0] - sn * d[1], sn * d[0] + c * d[1]], axis=-1)


def input_angle(s: Structure, inp: Input) -> float:
    """An input's drawn value: for a crank the direction (rad) of its line from the pivot, measured from its
    reference link's line (the +X axis for the ground); for a slide 0 mm."""
    if inp.kind == "slide":
        return 0.0
    return _line_angle(s, inp.link, inp.pivot) - (
        0.0 if inp.relative_to == GROUND else _line_angle(s, inp.relative_to, inp.pivot))


def _line_angle(s: Structure, body: str, pivot: str) -> float:
    """Direction (rad) in the drawing of the line from ``pivot`` to the first other point of ``body``."""
    other = next(p for p in s.bodies[body] if p != pivot)
    (x0, y0), (x1, y1) = s.points[pivot], s.points[other]
    return math.atan2(y1 - y0, x1 - x0)


def _pt(s: Structure, name: str) -> np.ndarray:
    return np.asarray(s.points[name], dtype=float)


def _direction(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


def _drawn_signs(s: Structure, p: Plan) -> tuple[float, ...]:
    """Each step's branch in the drawing (+1 or -1; +1 for steps without a branch)."""
    out = []
    sliders = s.slider_by_name
    for step in p.steps:
        sign = 1.0
        if isinstance(step, DyadStep):
            a1, a2 = step.attachments
            kind = step.kind
            if kind == "RRR":
                p1, p2, j = _pt(s, _expect(Pin, a1).point), _pt(s, _expect(Pin, a2).point), _pt(s, step.joint)
                sign = float(np.sign(cross(p2 - p1, j - p1))) or 1.0
            elif kind in ("RRP", "PRR"):
                pin, slide = _split(Pin, Slide, a1, a2)
                u = _direction(sliders[slide.slider].angle)
                sign = float(np.sign(dot(_pt(s, step.joint) - _pt(s, pin.point), u))) or 1.0
            elif kind == "RPR":
                sl = sliders[step.joint]
                pin_m, pin_g = (a1, a2) if step.bodies[0] == sl.body else (a2, a1)
                d = _pt(s, _expect(Pin, pin_m).point) - _pt(s, _expect(Pin, pin_g).point)
                sign = float(np.sign(cross(d, perp(_direction(sl.angle))))) or 1.0
            elif kind in RUNAWAY:
                sign = float(np.sign(_runaway_rate(s, step))) or 1.0
        out.append(sign)
    return tuple(out)


def _runaway_rate(s: Structure, step: DyadStep) -> float:
    """In the drawing, what a dyad with two slides divides by (its margin before the sign): the cross product of
    its two guides (PRP), or how fast its sliding body's travel moves its point across the joint's guide (RPP)."""
    sliders = s.slider_by_name
    a1, a2 = step.attachments
    if step.kind == "PRP":
        g1, g2 = (_direction(sliders[_expect(Slide, a).slider].angle) for a in (a1, a2))
        return float(cross(g1, g2))
    _, slide = _split(Pin, Slide, a1, a2)
    sliding = step.bodies[1] if isinstance(a1, Pin) else step.bodies[0]
    joint = sliders[step.joint]
    n = perp(_direction(joint.angle))
    sigma = 1.0 if slide.moving else -1.0
    return float(dot(n, sigma * _direction(sliders[slide.slider].angle))) * (1.0 if joint.body == sliding else -1.0)


# ---------------------------------------------------------------------- the solve, step by step

#: one closure row of a dyad in its two unknowns' rates over the poses: a x1 + b x2 = r
Row = tuple[np.ndarray, np.ndarray, np.ndarray]


@dataclass(frozen=True)
class _Turning:
    """A dyad body whose one unknown over the poses is its turn about a pin of the known body ``ref``: the pin at
    world ``pin`` (n, 2), drawn at ``pd`` (2,).

    Its velocity is ``base(x) + rate * g(x)`` and its angular velocity ``w_base + rate * dw`` in its unknown's rate
    (here its angular velocity); accelerations the same in the unknown's acceleration. ``known`` is the motion of
    ``ref``."""

    name: str
    attachment: Pin
    ref: Body
    pin: np.ndarray
    pd: np.ndarray
    dw: ClassVar[float] = 1.0

    def turned(self, c: np.ndarray, sn: np.ndarray) -> Body:
        """The body once its turn (c, s) is known."""
        return _pinned(c, sn, self.pin, self.pd)

    def base_v(self, known: Motion, xw: np.ndarray) -> np.ndarray:
        return np.broadcast_to(known.vel(self.pin), xw.shape)

    def base_a(self, known: Motion, xw: np.ndarray, w: np.ndarray, tdot: np.ndarray) -> np.ndarray:
        return known.acc(self.pin) - (w**2)[:, None] * (xw - self.pin)

    def g(self, xw: np.ndarray) -> np.ndarray:
        return perp(xw - self.pin)

    def w_base(self, known: Motion) -> np.ndarray:
        return np.zeros(len(self.ref.c))

    def al_base(self, known: Motion) -> np.ndarray:
        return np.zeros(len(self.ref.c))

    def rates(self, known: Motion, body: Body, x: np.ndarray) -> Rates:
        """The body's velocity field from its solved unknown rate x (its angular velocity)."""
        return Rates(body.T, x, known.vel(self.pin) + x[:, None] * perp(body.T - self.pin))

    def motion(self, known: Motion, rates: Rates, y: np.ndarray, tdot: np.ndarray) -> Motion:
        """The body's motion from its velocity field and its solved unknown acceleration y (angular)."""
        r = rates.T - self.pin
        return Motion(rates.T, rates.w, rates.vT, y,
                      known.acc(self.pin) + y[:, None] * perp(r) - (rates.w**2)[:, None] * r)


@dataclass(frozen=True)
class _Sliding:
    """A dyad body whose one unknown over the poses is its travel t (mm) along a guide of the known body ``ref``,
    along world directions ``u`` (n, 2): ``sigma`` +1 where the body is the slider's sliding body, -1 where it
    carries the guide. Its velocity and angular velocity in its unknown's rate as for :class:`_Turning`: a point
    moves with the known body's coincident point plus the slide (and, at acceleration level, Coriolis' term)."""

    name: str
    attachment: Slide
    ref: Body
    u: np.ndarray
    sigma: float
    dw: ClassVar[float] = 0.0

    def slid(self, t: np.ndarray) -> Body:
        """The body once its travel t (n,) mm is known."""
        return Body(self.ref.c, self.ref.s, self.ref.T + self.sigma * t[:, None] * self.u)

    def base_v(self, known: Motion, xw: np.ndarray) -> np.ndarray:
        return known.vel(xw)

    def base_a(self, known: Motion, xw: np.ndarray, w: np.ndarray, tdot: np.ndarray) -> np.ndarray:
        return known.acc(xw) + 2.0 * self.sigma * (tdot * known.w)[:, None] * perp(self.u)

    def g(self, xw: np.ndarray) -> np.ndarray:
        return np.broadcast_to(self.sigma * self.u, xw.shape)

    def w_base(self, known: Motion) -> np.ndarray:
        return known.w

    def al_base(self, known: Motion) -> np.ndarray:
        return known.al

    def rates(self, known: Motion, body: Body, x: np.ndarray) -> Rates:
        """The body's velocity field from its solved travel rate x (mm per unit input)."""
        return Rates(body.T, known.w, known.vel(body.T) + self.sigma * x[:, None] * self.u)

    def motion(self, known: Motion, rates: Rates, y: np.ndarray, tdot: np.ndarray) -> Motion:
        """The body's motion from its velocity field, its travel rate tdot and its travel's acceleration y."""
        return Motion(rates.T, rates.w, rates.vT, known.al,
                      known.acc(rates.T) + self.sigma * (y[:, None] * self.u
                                                         + 2.0 * (tdot * known.w)[:, None] * perp(self.u)))


_Unknown = _Turning | _Sliding


def _unknown(s: Structure, name: str, attachment: Attachment, bodies: dict[str, Body]) -> _Unknown:
    """Body ``name``'s unknown, held by ``attachment`` to a known body."""
    ref = bodies[attachment.body]
    if isinstance(attachment, Pin):
        pd = _pt(s, attachment.point)
        return _Turning(name, attachment, ref, ref.at(pd), pd)
    sl = s.slider_by_name[attachment.slider]
    return _Sliding(name, attachment, ref, ref.rotate(_direction(sl.angle)), 1.0 if attachment.moving else -1.0)


def _expect(kind: type[T], thing: object) -> T:
    """``thing``, which its step's kind says is a ``kind`` (a pin, a slide, an unknown turning or sliding)."""
    if isinstance(thing, kind):
        return thing
    raise TypeError(f"a {type(thing).__name__} where a {kind.__name__} was expected")


def _split(first: type[T], second: type[U], a: object, b: object) -> tuple[T, U]:
    """``a`` and ``b``, whichever is a ``first``, then the other, a ``second``: the pin and the slide of a step
    with one of each."""
    if isinstance(a, first):
        return a, _expect(second, b)
    return _expect(first, b), _expect(second, a)


def _ratio(num: np.ndarray, den: np.ndarray) -> np.ndarray:
    """num / den; +-inf where den is 0 (0 where both are): a toggle, never NaN."""
    with np.errstate(divide="ignore", invalid="ignore"):
        out = num / den
    bad = den == 0
    out[bad] = np.where(num[bad] == 0, 0.0, np.copysign(np.inf, num[bad]))
    return out


def _solve2(rows: list[Row]) -> tuple[np.ndarray, np.ndarray]:
    """Solve two linear rows a x1 + b x2 = r by Cramer's rule; +-inf where singular (a toggle)."""
    (a1, b1, r1), (a2, b2, r2) = rows
    det = a1 * b2 - a2 * b1
    return _ratio(r1 * b2 - r2 * b1, det), _ratio(a1 * r2 - a2 * r1, det)


def _rows(step: DyadStep, s: Structure, u1: _Unknown, u2: _Unknown, bodies: dict[str, Body],
          motions: dict[str, Motion], solved: dict[str, tuple[Rates, np.ndarray]] | None = None) -> list[Row]:
    """The dyad's two closure rows in its unknowns at velocity level, or at acceleration level given ``solved``:
    each of its bodies' velocity field and its unknown's rate, by body name."""
    b1, b2 = bodies[u1.name], bodies[u2.name]

    def base(u: _Unknown, xw: np.ndarray) -> np.ndarray:
        known = motions[u.attachment.body]
        if solved is None:
            return u.base_v(known, xw)
        rates, tdot = solved[u.name]
        return u.base_a(known, xw, rates.w, tdot)

    if not step.prismatic:
        jw = b1.at(_pt(s, step.joint))
        g1, g2 = u1.g(jw), u2.g(jw)
        rhs = base(u2, jw) - base(u1, jw)
        return [(g1[:, 0], -g2[:, 0], rhs[:, 0]), (g1[:, 1], -g2[:, 1], rhs[:, 1])]
    sl = s.slider_by_name[step.joint]
    moving_first = step.bodies[0] == sl.body
    um, ug = (u1, u2) if moving_first else (u2, u1)
    bm, bg = (b1, b2) if moving_first else (b2, b1)
    km, kg = motions[um.attachment.body], motions[ug.attachment.body]
    uw = bg.rotate(_direction(sl.angle))
    n = perp(uw)
    jw = bm.at(_pt(s, sl.point))
    ones = np.ones(len(jw))
    # the two bodies turn together, and the moving body's point does not leave the guide's line (the relative
    # velocity of the coincident points lies along it; at acceleration level, less Coriolis' term)
    if solved is None:
        turn_rhs = ug.w_base(kg) - um.w_base(km)
        line_rhs = dot(n, base(ug, jw) - base(um, jw))
    else:
        (rm, _), (rg, _) = solved[um.name], solved[ug.name]
        turn_rhs = ug.al_base(kg) - um.al_base(km)
        slip = dot(uw, rm.vel(jw) - rg.vel(jw))
        line_rhs = dot(n, base(ug, jw) - base(um, jw)) + 2.0 * rg.w * slip
    rows = [(um.dw * ones, -ug.dw * ones, turn_rhs), (dot(n, um.g(jw)), -dot(n, ug.g(jw)), line_rhs)]
    return rows if moving_first else [(b, a, r) for a, b, r in rows]


def _magnitude(*points: np.ndarray) -> np.ndarray:
    """The largest coordinate (mm) among points (n, 2) at each pose: the scale of their rounding."""
    return np.max(np.abs(np.concatenate(points, axis=1)), axis=1)


def _place_dyad(step: DyadStep, s: Structure, u1: _Unknown, u2: _Unknown, sign: np.ndarray,
                bodies: dict[str, Body], fold: tuple[np.ndarray, np.ndarray] | None = None
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Place both bodies of a dyad; its margin, transmission angle and slack. ``fold`` (poses, unit directions):
    where an RRR's equal-radius pins meet, the direction the pins part along, which places its joint there."""
    kind = step.kind
    sliders = s.slider_by_name
    if kind == "RRR":
        p1, p2 = _expect(_Turning, u1), _expect(_Turning, u2)
        jd = _pt(s, step.joint)
        r1, r2 = float(np.linalg.norm(jd - p1.pd)), float(np.linalg.norm(jd - p2.pd))
        jw, margin = dyads.circle_circle(p1.pin, r1, p2.pin, r2, sign)
        d = np.hypot(*(p2.pin - p1.pin).T)
        if fold is not None:
            # the meeting circles of (nearly) equal radii: their intersection from the midpoint of the pins
            at, unit = fold
            half = np.sqrt(np.maximum((0.5 * (r1 + r2)) ** 2 - 0.25 * d[at] ** 2, 0.0))
            side = np.broadcast_to(sign, d.shape)[at]
            jw[at] = 0.5 * (p1.pin[at] + p2.pin[at]) + (side * half)[:, None] * perp(unit)
        for p in (p1, p2):
            bodies[p.name] = _turn_to(p, jw - p.pin, jd - p.pd)
        a, b = p1.pin - jw, p2.pin - jw
        slack = np.minimum(r1 + r2 - d, d - abs(r1 - r2)) / (r1 + r2 + _magnitude(p1.pin, p2.pin))
        return margin, np.arctan2(np.abs(cross(a, b)), dot(a, b)), slack
    if kind in ("RRP", "PRR"):
        up, us = _split(_Turning, _Sliding, u1, u2)
        jd = _pt(s, step.joint)
        r = float(np.linalg.norm(jd - up.pd))
        c = us.ref.at(jd)
        jw, margin = dyads.circle_line(up.pin, r, c, us.u, sign)
        bodies[up.name] = _turn_to(up, jw - up.pin, jd - up.pd)
        bodies[us.name] = us.slid(us.sigma * dot(jw - c, us.u))
        rod = jw - up.pin
        slack = (r - np.abs(cross(us.u, c - up.pin))) / (r + _magnitude(up.pin, c))
        return margin, np.arctan2(np.abs(dot(rod, us.u)), np.abs(cross(us.u, rod))), slack
    if kind == "RPR":
        sl = sliders[step.joint]
        p1, p2 = _expect(_Turning, u1), _expect(_Turning, u2)
        um, ug = (p1, p2) if step.bodies[0] == sl.body else (p2, p1)
        nd = perp(_direction(sl.angle))
        offset = float(dot(nd, um.pd - ug.pd))
        rot, margin = dyads.line_through(ug.pin, um.pin, math.atan2(nd[1], nd[0]), offset, sign)
        if fold is not None:
            # the pins (nearly) meet on a slot through the pivot: the slot lies along the way they part
            at, unit = fold
            along = unit if um is p2 else -unit
            normal = np.broadcast_to(sign, (len(rot),))[at][:, None] * perp(along)
            rot[at] = np.column_stack([normal @ nd, nd[0] * normal[:, 1] - nd[1] * normal[:, 0]])
        for p in (um, ug):
            bodies[p.name] = p.turned(rot[:, 0], rot[:, 1])
        d = um.pin - ug.pin
        dist = np.hypot(d[:, 0], d[:, 1])
        slack = (dist - abs(offset)) / np.maximum(abs(offset) + dist + _magnitude(um.pin, ug.pin), 1e-300)
        return margin, np.arctan2(np.sqrt(np.maximum((dist - abs(offset)) * (dist + abs(offset)), 0.0)),
                                  abs(offset)), slack
    if kind == "PRP":
        s1, s2 = _expect(_Sliding, u1), _expect(_Sliding, u2)
        jd = _pt(s, step.joint)
        c1, c2 = s1.ref.at(jd), s2.ref.at(jd)
        jw, _ = dyads.line_line(c1, s1.u, c2, s2.u)
        bodies[s1.name] = s1.slid(s1.sigma * dot(jw - c1, s1.u))
        bodies[s2.name] = s2.slid(s2.sigma * dot(jw - c2, s2.u))
        margin = sign * cross(s1.u, s2.u)          # signed: > 0 drawn, 0 where the guides turn parallel
        return margin, np.arcsin(np.minimum(np.abs(margin), 1.0)), margin
    # RPP / PPR: the pinned body takes the sliding one's angle; the sliding one's travel follows (a linear solve)
    up, us = _split(_Turning, _Sliding, u1, u2)
    turned = up.turned(us.ref.c, us.ref.s)
    bodies[up.name] = turned
    sl = sliders[step.joint]
    moving = sl.body == us.name
    guide_body = turned if moving else us.ref
    uw = guide_body.rotate(_direction(sl.angle))
    n = perp(uw)
    qd = _pt(s, sl.point)
    # the sliding body's point qd moves by sigma t u along its own guide; the constraint n . (moving - guide) = 0
    gap = (us.ref.at(qd) - turned.at(qd)) if moving else (turned.at(qd) - us.ref.at(qd))
    rate = dot(n, us.sigma * us.u) * (1.0 if moving else -1.0)
    margin = sign * rate                           # signed: > 0 drawn, 0 where the travel runs along the guide
    t = _ratio(-dot(n, gap), rate)
    bodies[us.name] = us.slid(np.where(np.isfinite(t), t, 0.0))
    return margin, np.arcsin(np.minimum(np.abs(margin), 1.0)), margin


def _turn_to(u: _Turning, now: np.ndarray, drawn: np.ndarray) -> Body:
    """The pinned body turned so that its drawn vector ``drawn`` lies along ``now``."""
    length = float(np.hypot(*drawn))
    c = (now[:, 0] * drawn[0] + now[:, 1] * drawn[1]) / length**2
    sn = (drawn[0] * now[:, 1] - drawn[1] * now[:, 0]) / length**2
    return u.turned(c, sn)


def _solve(linkage: Linkage, x: np.ndarray, rates: np.ndarray, signs: list[np.ndarray], strict: bool,
           derivatives: bool, upto: int | None, choose: Chooser | None) -> Solution:
    if choose is None and upto is None and linkage.program is not None:
        try:
            return _solve_fused(linkage.program, x, rates, signs, derivatives)
        except fused.Folded:
            pass                        # a deltoid's pins meet: its joint is placed by the motion, below
    s, p = linkage.structure, linkage.plan
    n = x.shape[1]
    ground = Body(np.ones(n), np.zeros(n), np.zeros((n, 2)))
    bodies: dict[str, Body] = {GROUND: ground}
    # each placed body's velocities and accelerations, only where they are asked for
    motions = ({GROUND: Motion(ground.T, np.zeros(n), np.zeros((n, 2)), np.zeros(n), np.zeros((n, 2)))}
               if derivatives else None)
    results: list[DyadResult] = []
    ok = np.ones(n, dtype=bool)
    drawn = linkage.drawn_inputs
    # the turns from the drawing (rad) known exactly, not modulo a turn: the ground's, an input's, a gear's
    turns = {GROUND: np.zeros(n)}
    for index, step in enumerate(p.steps[:upto]):
        if isinstance(step, InputStep):
            _place_input(s, step, x[step.index] - drawn[step.index], rates[step.index], bodies, motions)
            _input_turn(s, step, x[step.index] - drawn[step.index], turns)
        elif isinstance(step, GearStep):
            from linkgen.kinematics import gearing

            gearing.place(s, step, bodies, motions, turns)
        elif isinstance(step, FixedStep):
            _place_fixed(s, step, bodies, motions)
        elif isinstance(step, GroupStep):
            result = _place_group(linkage, index, step, x, bodies, motions)
            results.append(result)
            ok &= result.slack >= 0.0
        else:
            u1, u2 = (_unknown(s, b, a, bodies) for b, a in zip(step.bodies, step.attachments, strict=True))
            flips = linkage.flips[index] if linkage.flips else np.empty(0)
            fold = _fold(linkage, index, u1, u2, x, signs, flips, strict)
            margin, gamma, slack = _place_dyad(step, s, u1, u2, signs[index], bodies, fold)
            spread = None if motions is None else _spread(u1, u2, motions)
            result = DyadResult(step.kind, step.bodies, step.joint, margin, gamma, slack, spread)
            chosen = None if choose is None else choose(index, result)
            if chosen is not None and len(chosen):             # the search found this dyad's change points
                signs[index] = linkage.step_signs(linkage.base_signs[index], chosen, x[0])
                fold = _fold(linkage, index, u1, u2, x, signs, chosen, strict)
                _place_dyad(step, s, u1, u2, signs[index], bodies, fold)
            results.append(result)
            ok &= (margin > 0.0) if step.kind in RUNAWAY else (margin >= -FEASIBILITY_TOL)
            if motions is not None:
                _move_dyad(step, s, u1, u2, bodies, motions)
    return _gather(s, x, bodies, motions, tuple(results), ok)


def _solve_fused(prog: fused.Program, x: np.ndarray, rates: np.ndarray, signs: list[np.ndarray],
                 derivatives: bool) -> Solution:
    """:func:`_solve` by the fused kernels: the same solution, the ground's points and rates as constants
    (read-only broadcast arrays)."""
    out = fused.run(prog, x, rates, signs, derivatives, True, FEASIBILITY_TOL)
    n = x.shape[1]
    zero, one = np.broadcast_to(0.0, (n,)), np.broadcast_to(1.0, (n,))
    points, vels, accs = _fused_points(prog, out, n, derivatives)
    rotations = {GROUND: (one, zero), **{b: (q.real, q.imag) for b, q in out.rotations.items()}}
    omegas = {GROUND: zero, **out.omegas} if derivatives else {}
    alphas = {GROUND: zero, **out.alphas} if derivatives else {}
    ops = [op for op in prog.ops if isinstance(op, fused.RRROp)]
    results = tuple(DyadResult("RRR", op.bodies, op.joint, out.margins[i], out.transmissions[i], out.slacks[i],
                               out.spreads[i] if derivatives else None) for i, op in enumerate(ops))
    return Solution(x, points, vels, accs, rotations, omegas, alphas, results, out.ok)


def _fused_points(prog: fused.Program, out: fused.Outputs, n: int, derivatives: bool
                  ) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray], dict[str, np.ndarray]]:
    """The fused outputs' points (and velocities, accelerations) as (n, 2) float views; a ground point's as one
    broadcast row."""
    points, vels, accs = {}, {}, {}
    for name, holder, xd in prog.points:
        if holder is None:
            points[name] = fused.constant_point(xd, n)
            if derivatives:
                vels[name] = accs[name] = fused.constant_point(0j, n)
        else:
            points[name] = fused.point_view(out.points[name])
            if derivatives:
                vels[name] = fused.point_view(out.velocities[name])
                accs[name] = fused.point_view(out.accelerations[name])
    return points, vels, accs


def _place_group(linkage: Linkage, index: int, step: GroupStep, x: np.ndarray, bodies: dict[str, Body],
                 motions: dict[str, Motion] | None) -> DyadResult:
    """Place a class-III group (:mod:`linkgen.kinematics.groups`) by Newton's method from its track at x, its
    motion too given ``motions``; its result as a dyad's: margin and slack its Jacobian's conditioning (-1 where it
    does not assemble), transmission the angle whose sine that is."""
    group = groups.group_of(linkage.structure, step)
    from linkgen.kinematics.motion import span

    drawn = linkage.drawn_inputs
    x0 = float(drawn[0])
    # a crank's track runs a turn either way of the drawing (its revolution may start below it), a slide's its span
    lo, hi = ((x0 - TWO_PI, x0 + TWO_PI) if linkage.is_crank() else span(linkage)) if len(drawn) == 1 else (x0, x0)
    key = (index, lo, hi, x0, tuple((i, tuple(f)) for i, f in enumerate(linkage.flips[:index]) if len(f)))
    track = linkage.tracks.get(key)
    if track is None:
        def upstream(values: np.ndarray) -> dict[str, Body]:
            xs = np.vstack([values, *np.broadcast_to(drawn[1:, None], (len(drawn) - 1, len(values)))])
            sol = _solve(linkage, xs, np.ones(len(drawn)), linkage.signs(xs), False, False, index, None)
            return {b: _body_of(linkage.structure, sol, b) for b in sol.rotations}

        track = linkage.tracks[key] = groups.track(group, x0, lo, hi, upstream,
                                                   TWO_PI if linkage.is_crank() else None)
    known = {b: bodies[b] for b in bodies}
    guess = track.guess(x[0])
    q, converged = groups.newton(group, guess, known)
    # on the track's assembly: a pose near the track's (not another assembly Newton's method found instead)
    moved = np.max(np.hypot(*np.moveaxis(group.points(q) - group.points(guess), -1, 0)), axis=1, initial=0.0)
    converged &= track.covers(x[0]) & (moved <= groups.JUMP * group.size)
    _, jac = group.residual(q, known)
    margin = np.where(converged, group.margin(q, jac), -1.0)
    for j, b in enumerate(step.bodies):
        bodies[b] = Body(np.cos(q[:, 3 * j]), np.sin(q[:, 3 * j]), q[:, 3 * j + 1:3 * j + 3])
    if motions is not None:
        for b, (w, vt, al, at) in groups.derivatives(group, q, known, motions).items():
            motions[b] = Motion(bodies[b].T, w, vt, al, at)
    return DyadResult(step.kind, step.bodies, ", ".join(step.joints), margin, np.arcsin(np.clip(margin, 0.0, 1.0)),
                      margin)


def _body_of(s: Structure, sol: Solution, body: str) -> Body:
    """A placed body's pose from a solution: its rotation and where its first point is."""
    c, sn = sol.rotations[body]
    pd = _pt(s, s.bodies[body][0])
    pw = sol.points[s.bodies[body][0]]
    return _pinned(np.asarray(c), np.asarray(sn), pw, pd)


def _move_dyad(step: DyadStep, s: Structure, u1: _Unknown, u2: _Unknown, bodies: dict[str, Body],
               motions: dict[str, Motion]) -> None:
    """The velocities and accelerations of a placed dyad's bodies: its closure's 2x2 solve at velocity level for
    its unknowns' rates, then at acceleration level."""
    known = [motions[u.attachment.body] for u in (u1, u2)]
    xv = _solve2(_rows(step, s, u1, u2, bodies, motions))
    solved = {u.name: (u.rates(k, bodies[u.name], rate), rate) for u, k, rate in zip((u1, u2), known, xv, strict=True)}
    ya = _solve2(_rows(step, s, u1, u2, bodies, motions, solved))
    for u, k, acc in zip((u1, u2), known, ya, strict=True):
        rates, tdot = solved[u.name]
        motions[u.name] = u.motion(k, rates, acc, tdot)


def _fold(linkage: Linkage, index: int, u1: _Unknown, u2: _Unknown, x: np.ndarray, signs: list[np.ndarray],
          flips: np.ndarray, strict: bool) -> tuple[np.ndarray, np.ndarray] | None:
    """Where a deltoid's two pins (of equal radii) meet or nearly do (within :data:`FOLD_REACH` of the drawing's
    size), or the two pins of a slotted link whose slot runs through its pivot: the poses and the unit direction
    the pins part along there, from their relative velocity v and acceleration a per unit input at the pose, h
    past the change point: d = v h - a h^2 / 2 to second order (so that the joint is the branch's limit through
    the fold, as the motion carries it); None elsewhere. With more than one input there is no motion to take the
    limit along: a pose where the pins meet is refused (strict), else placed as the directions between them
    say."""
    s = linkage.structure
    step = linkage.plan.steps[index]
    if not isinstance(step, DyadStep) or step.kind not in ("RRR", "RPR"):
        return None
    p1, p2 = _expect(_Turning, u1), _expect(_Turning, u2)
    if step.kind == "RRR":
        jd = _pt(s, step.joint)
        apart = abs(float(np.linalg.norm(jd - p1.pd)) - float(np.linalg.norm(jd - p2.pd)))
    else:
        sl = s.slider_by_name[step.joint]
        um, ug = (p1, p2) if step.bodies[0] == sl.body else (p2, p1)
        apart = abs(float(dot(perp(_direction(sl.angle)), um.pd - ug.pd)))
    if apart > FOLD_REACH * s.size:
        return None                   # unequal radii, an offset slot: pins that meet leave the dyad open
    d = np.hypot(*(p2.pin - p1.pin).T)
    near = d <= FOLD_REACH * s.size
    if not near.any():
        return None
    at = np.flatnonzero(near)
    j1, j2 = p1.attachment.point, p2.attachment.point
    if len(s.inputs) != 1:
        met = d <= 1e-12 * s.size
        if met.any() and strict:
            crank = s.inputs[0].kind == "crank"
            value = float(x[0, np.flatnonzero(met)[0]])
            shown = f"{math.degrees(value):.9g} degrees" if crank else f"{value:.9g} mm"
            raise SpecError(f"at input {shown} the joints {j1} and {j2} meet, so dyad {step.kind} at {step.joint} "
                            "could take any angle (a change point); give inputs that keep them apart", "input")
        return None
    # the pins' relative motion per unit input, from a solve of these poses up to this step with its rates
    sub = _solve(linkage, x[:, at], np.ones(len(s.inputs)), [np.broadcast_to(g, x.shape[1:])[at] for g in signs],
                 False, True, index, None)
    rel_v = sub.velocities[j2] - sub.velocities[j1]
    rel_a = sub.accelerations[j2] - sub.accelerations[j1]
    # h from the nearest change point of this dyad (a pose at one is past it); without one, from the pose itself
    if len(flips):
        nearest = flips[np.argmin(np.abs(x[0, at, None] - flips[None, :]), axis=1)]
        h = x[0, at] - nearest
        side = np.where(h >= 0.0, 1.0, -1.0)
    else:
        h = np.zeros(len(at))
        side = np.ones(len(at))
    direction = rel_v - 0.5 * h[:, None] * rel_a               # d(h) / h to second order, from the pose's rates
    length = np.hypot(*direction.T)
    usable = length > 0
    unit = np.where(usable[:, None], side[:, None] * direction / np.where(usable, length, 1.0)[:, None],
                    (p2.pin[at] - p1.pin[at]) / np.maximum(d[at], 1e-300)[:, None])
    return at, unit


def _spread(u1: _Unknown, u2: _Unknown, motions: dict[str, Motion]) -> np.ndarray | None:
    """How fast the dyad's outer joints move apart: the pins' relative velocity along the line between them, or a
    pin's velocity off the guide line relative to the guide (None for dyads of two slides)."""
    if isinstance(u1, _Turning) and isinstance(u2, _Turning):
        return dot(u2.pin - u1.pin, motions[u2.attachment.body].vel(u2.pin) - motions[u1.attachment.body].vel(u1.pin))
    if isinstance(u1, _Sliding) and isinstance(u2, _Sliding):
        return None
    up, us = _split(_Turning, _Sliding, u1, u2)
    return dot(perp(us.u), motions[up.attachment.body].vel(up.pin) - motions[us.attachment.body].vel(up.pin))


def _place_input(s: Structure, step: InputStep, delta: np.ndarray, rate: float, bodies: dict[str, Body],
                 motions: dict[str, Motion] | None) -> None:
    """The driven body moved by ``delta`` (rad or mm) from the drawing, at unit ``rate`` of its input; its motion
    too, given ``motions``."""
    inp = s.inputs[step.index]
    if inp.kind == "crank":
        ref = bodies[inp.relative_to]
        c, sn = np.cos(delta), np.sin(delta)
        cc, ss = ref.c * c - ref.s * sn, ref.s * c + ref.c * sn
        pd = _pt(s, inp.pivot)
        pw = ref.at(pd)
        body = _pinned(cc, ss, pw, pd)
        if motions is not None:
            known = motions[inp.relative_to]
            motions[step.body] = pivoted(known, pw, body.T, known.w + rate, known.al)
    else:
        sl = s.slider_by_name[inp.slider]
        ref = bodies[sl.guide]
        u = ref.rotate(_direction(sl.angle))
        body = Body(ref.c, ref.s, ref.T + delta[:, None] * u)
        if motions is not None:
            zero = np.zeros(len(delta))
            motions[step.body] = slid(motions[sl.guide], body.T, u, delta, zero + rate, zero)
    bodies[step.body] = body


def _input_turn(s: Structure, step: InputStep, delta: np.ndarray, turns: dict[str, np.ndarray]) -> None:
    """The driven body's turn from the drawing, exactly, where its reference body's is known so."""
    inp = s.inputs[step.index]
    ref = inp.relative_to if inp.kind == "crank" else s.slider_by_name[inp.slider].guide
    if ref in turns:
        turns[step.body] = turns[ref] + delta if inp.kind == "crank" else turns[ref]


def pivoted(known: Motion, pw: np.ndarray, T: np.ndarray, w: np.ndarray, al: np.ndarray) -> Motion:
    """The motion of a body turning about the material point at ``pw`` (n, 2) mm of a body moving as ``known``, at
    angular velocity ``w`` and acceleration ``al`` (n,), its pose's translation ``T`` (n, 2)."""
    r = T - pw
    return Motion(T, w, known.vel(pw) + w[:, None] * perp(r), al,
                  known.acc(pw) + al[:, None] * perp(r) - (w**2)[:, None] * r)


def slid(known: Motion, T: np.ndarray, u: np.ndarray, t: np.ndarray, tdot: np.ndarray, tddot: np.ndarray) -> Motion:
    """The motion of a body sliding on a guide of a body moving as ``known``: travel ``t`` (n,) mm along the guide's
    world direction ``u`` (n, 2) from where the two bodies' poses coincide, its rate ``tdot`` and acceleration
    ``tddot``, its pose's translation ``T``; the guide's coincident point's motion, the slide and Coriolis'
    term."""
    w, al = known.w, known.al
    return Motion(T, w, known.vT + tdot[:, None] * u + (t * w)[:, None] * perp(u), al,
                  known.aT + tddot[:, None] * u + 2.0 * (tdot * w)[:, None] * perp(u)
                  + t[:, None] * (al[:, None] * perp(u) - (w**2)[:, None] * u))


def _place_fixed(s: Structure, step: FixedStep, bodies: dict[str, Body], motions: dict[str, Motion] | None) -> None:
    """A body held by two attachments: two pins fix its angle by their direction; a pin and a slide by the
    slide's. Its motion too, given ``motions``."""
    a1, a2 = step.attachments
    pin, other = (a1, a2) if isinstance(a1, Pin) else (_expect(Pin, a2), a1)
    pd = _pt(s, pin.point)
    pw = bodies[pin.body].at(pd)
    if isinstance(other, Pin):
        qd = _pt(s, other.point)
        qw = bodies[other.body].at(qd)
        now, drawn = qw - pw, qd - pd
        length2 = float(dot(drawn, drawn))
        c, sn = dot(now, drawn) / length2, cross(drawn, now) / length2
        norm = np.hypot(c, sn)
        body = _pinned(c / norm, sn / norm, pw, pd)
    else:
        ref = bodies[other.body]
        body = _pinned(ref.c, ref.s, pw, pd)
    bodies[step.body] = body
    if motions is None:
        return
    held, guide = motions[pin.body], motions[other.body]
    if isinstance(other, Pin):
        d = qw - pw
        dd = dot(d, d)
        w = cross(d, guide.vel(qw) - held.vel(pw)) / dd
        al = cross(d, guide.acc(qw) - held.acc(pw)) / dd
    else:
        w, al = guide.w, guide.al
    motions[step.body] = pivoted(held, pw, body.T, w, al)


def _unbounded(x: np.ndarray) -> np.ndarray:
    """Rates past a toggle (where a dyad's 2x2 solve is singular) are unbounded: +inf, never NaN."""
    return np.where(np.isnan(x), np.inf, x)


def _gather(s: Structure, x: np.ndarray, bodies: dict[str, Body], motions: dict[str, Motion] | None,
            results: tuple[DyadResult, ...], ok: np.ndarray) -> Solution:
    """Each point from the first body placed that holds it, with its velocity and acceleration given
    ``motions``."""
    points: dict[str, np.ndarray] = {}
    vels: dict[str, np.ndarray] = {}
    accs: dict[str, np.ndarray] = {}
    for name in s.points:
        holder = next((b for b in s.holders(name) if b in bodies), None)
        if holder is None:
            continue
        xw = bodies[holder].at(_pt(s, name))
        points[name] = xw
        if motions is not None:
            vels[name], accs[name] = _unbounded(motions[holder].vel(xw)), _unbounded(motions[holder].acc(xw))
    rotations = {b: (body.c, body.s) for b, body in bodies.items()}
    omegas = {} if motions is None else {b: _unbounded(motions[b].w) for b in bodies}
    alphas = {} if motions is None else {b: _unbounded(motions[b].al) for b in bodies}
    return Solution(x, points, vels, accs, rotations, omegas, alphas, results, ok)
