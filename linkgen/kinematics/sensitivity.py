"""How a linkage's slack moves it, to first order: the linearised closure equations (pure numpy).

The slack of a linkage as made is a vector pi of small numbers (mm), in four kinds (:class:`SlackModel`):

* **holes**: where a loose pin passes through a part's hole, the pin's centre sits anywhere within the hole's
  play r = (hole - pin) / 2 of the hole's centre: two numbers a pin-hole pair (the pin's offset in the part's own
  drawn frame, x then y), bounded together by a disc of radius r. A joint of k parts is k pairs (the pin floats
  between them), and a slider's pin passes through its sliding part's hole (a pair even where no other part
  holds the point);
* **slots**: a slider's pin sits anywhere across its guide's slot within the same play r: one number a slider,
  the pin's offset along the guide's normal (its direction turned 90 degrees counter-clockwise);
* **lengths**: each point of a part other than its first lies at its drawn distance from the first within
  +- dL: one number each, the change of that distance (a bar's length; a plate's distances from its first hole);
* **lines**: a slider's slot lies on its guide within +- dL across: one number a slider, along the guide's normal
  (the guide's own dimension, as a slider-crank's offset is the ground's).

A tracer that only one part holds (a coupler point) is that part's own point: it moves with the part's lengths
but has no hole's play.

**The closure equations** Phi(q, pi) = 0 hold at every pose. The unknowns q are each moving body's turn phi from
the drawing (rad, counter-clockwise) and the position R (mm) of its first point: 3 a body. The rows: every pin
(its pairs' pin centres coincide: 2 rows for each part after the first), every slider (its pin on its slot's line:
n . (P - G) = slot + line offsets; the sliding part keeps its angle to the guide: 2 rows) and every input (a
crank's turn relative to its reference link, a slide's travel along its guide: 1 row). A linkage of mobility 1 and
one input without redundant constraints has as many rows as unknowns. At each pose the project's solver
(:class:`~linkgen.kinematics.linkage.Linkage`) gives q for pi = 0, and the first-order response to the slack is

    dq/dpi = -Phi_q^-1 Phi_pi

one linear solve a pose, batched over the poses (:func:`response`). This is exact to rounding (no step to choose,
and unlike differences of perturbed solves it does not fail near a toggle, where a step crosses the point the
linkage stops at), costs one factorisation a pose whatever the number of parameters, and reads only the solver's
positions, so the Monte Carlo solves of perturbed linkages by that solver (:func:`perturbed`) check it
independently. The same rows, solved by Newton's method at the drawn pose, assemble a perturbed linkage's drawing.

**The worst case** of a scalar s with gradient g = ds/dpi is the sum of the absolute sensitivities times each
slack (:func:`worst_case`): r |(g_x, g_y)| for a pin-hole pair (the worst offset in its disc points along the
gradient), b |g_j| for the others, each at its own bound. At each pose it is reached by one choice of the pins'
offsets (the pins shift in their holes as the loads turn), and Monte Carlo samples of fixed offsets lie inside it
to second order in the slack.

Frames and signs: the drawing's frame, mm; turns counter-clockwise in rad; parameters in mm, each part's hole
offsets in its own drawn frame (turned with it).
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np

from linkgen.kinematics.dyads import cross, dot, perp
from linkgen.kinematics.linkage import Linkage, Solution
from linkgen.kinematics.structure import GROUND, DyadStep, Pin, Slide, Slider, Structure

#: a pose whose closure Jacobian (columns scaled to mm) has a smallest singular value below this fraction of its
#: largest is singular: a toggle, where the response is unbounded
SINGULAR = 1e-13
#: Newton's method assembles a perturbed drawing to this fraction of the drawing's size
ASSEMBLE_TOL = 1e-12
#: the most Newton steps an assembly takes
ASSEMBLE_STEPS = 30
#: two holders of one pin in an assembled drawing agree to this fraction of the drawing's size
AGREE_TOL = 1e-9


@dataclass(frozen=True)
class SlackModel:
    """The slack parameters of a structure, in the order of the vector pi: two a hole (x, y), then one a slot, a
    length and a line.

    Attributes
    ----------
    holes : tuple of (str, str)
        The pin-hole pairs: (part, point).
    slots : tuple of str
        The sliders whose pin sits across its slot.
    lengths : tuple of (str, str)
        (part, point): the point's distance from the part's first point.
    lines : tuple of str
        The sliders whose slot's line lies across its guide.
    guides : tuple of (str, str)
        (slider, the link guiding it) of every slider: a line's bound is its guide's tolerance.
    """

    holes: tuple[tuple[str, str], ...]
    slots: tuple[str, ...]
    lengths: tuple[tuple[str, str], ...]
    lines: tuple[str, ...]
    guides: tuple[tuple[str, str], ...] = ()

    @property
    def size(self) -> int:
        """How many numbers pi holds."""
        return 2 * len(self.holes) + len(self.slots) + len(self.lengths) + len(self.lines)

    def hole(self, body: str, point: str) -> int | None:
        """The index of a pair's x offset in pi (its y follows), or None where the part has no hole's play there."""
        key = (body, point)
        return 2 * self.holes.index(key) if key in self.holes else None

    def slot(self, slider: str) -> int:
        return 2 * len(self.holes) + self.slots.index(slider)

    def length(self, body: str, point: str) -> int | None:
        """The index of the point's length from the part's first point, or None for the first point."""
        key = (body, point)
        if key not in self.lengths:
            return None
        return 2 * len(self.holes) + len(self.slots) + self.lengths.index(key)

    def line(self, slider: str) -> int:
        return 2 * len(self.holes) + len(self.slots) + len(self.lengths) + self.lines.index(slider)

    def bounds(self, play: float, tolerance: Mapping[str, float]) -> np.ndarray:
        """Each parameter's bound (mm): ``play`` for the holes (both of a pair's numbers: the disc's radius) and the
        slots, the part's ``tolerance`` (by part name) for its lengths and, the guide's, for its slots' lines."""
        guide = dict(self.guides)
        return np.array([play] * (2 * len(self.holes)) + [play] * len(self.slots)
                        + [tolerance[body] for body, _ in self.lengths]
                        + [tolerance[guide[name]] for name in self.lines], dtype=float)


def slack_model(s: Structure) -> SlackModel:
    """The slack parameters of structure ``s``: a hole at every point a part shares with another or slides with, a
    slot and a line a slider, a length at every point of a part but its first."""
    sliding = {(sl.body, sl.point) for sl in s.sliders}
    holes = tuple((body, p) for body, pts in s.bodies.items() for p in pts
                  if len(s.holders(p)) >= 2 or (body, p) in sliding)
    lengths = tuple((body, p) for body, pts in s.bodies.items() for p in pts[1:])
    names = tuple(sl.name for sl in s.sliders)
    return SlackModel(holes, names, lengths, names, tuple((sl.name, sl.guide) for sl in s.sliders))


def worst_case(grad: np.ndarray, model: SlackModel, bounds: np.ndarray) -> np.ndarray:
    """The worst-case first-order change of a scalar whose gradient is ``grad`` (..., P): r |(g_x, g_y)| a hole,
    b |g_j| for the rest; +inf where the gradient is not finite (a toggle)."""
    k = 2 * len(model.holes)
    pairs = np.hypot(grad[..., 0:k:2], grad[..., 1:k:2]) @ bounds[0:k:2]
    out = pairs + np.abs(grad[..., k:]) @ bounds[k:]
    return np.where(np.isfinite(out), out, np.inf)


def sample(model: SlackModel, bounds: np.ndarray, rng: np.random.Generator, count: int) -> np.ndarray:
    """``count`` slack vectors (count, P) drawn uniformly within the bounds: each pin's offset uniform over its
    disc, each other number uniform over [-b, b]."""
    k = len(model.holes)
    radius = bounds[0:2 * k:2] * np.sqrt(rng.random((count, k)))
    angle = 2 * math.pi * rng.random((count, k))
    out = np.empty((count, model.size))
    out[:, 0:2 * k:2] = radius * np.cos(angle)
    out[:, 1:2 * k:2] = radius * np.sin(angle)
    out[:, 2 * k:] = bounds[2 * k:] * (2 * rng.random((count, model.size - 2 * k)) - 1)
    return out


# ---------------------------------------------------------------------------------------------------- closure


@dataclass(frozen=True)
class _State:
    """Each moving body's turn from the drawing (n,) and its first point's position (n, 2) mm, over n poses."""

    turns: Mapping[str, np.ndarray]
    origins: Mapping[str, np.ndarray]


class _Closure:
    """The closure rows of a structure at a state: residuals (n, R), their Jacobians in the unknowns (n, R, M) and
    in the slack (n, R, P)."""

    def __init__(self, s: Structure, model: SlackModel, state: _State, values: np.ndarray,
                 params: np.ndarray | None, places: Mapping[tuple[str, str], _Local] | None = None) -> None:
        self.s, self.model, self.state = s, model, state
        self.moving = [b for b in s.bodies if b != GROUND]
        self.column = {b: 3 * i for i, b in enumerate(self.moving)}
        self.n = values.shape[0]
        self.params = np.zeros(model.size) if params is None else params
        self.places = _places(s, model, self.params) if places is None else places
        self.rows: list[tuple[np.ndarray, dict[int, np.ndarray], dict[int, np.ndarray]]] = []
        self._build(values)

    # a body's pose
    def _turn(self, body: str) -> np.ndarray:
        return np.zeros(self.n) if body == GROUND else self.state.turns[body]

    def _rotation(self, body: str) -> tuple[np.ndarray, np.ndarray]:
        phi = self._turn(body)
        return np.cos(phi), np.sin(phi)

    def _origin(self, body: str) -> np.ndarray:
        if body == GROUND:
            return np.broadcast_to(_pt(self.s, self.s.bodies[GROUND][0]), (self.n, 2))
        return self.state.origins[body]

    def point(self, body: str, point: str) -> tuple[np.ndarray, dict[int, np.ndarray], dict[int, np.ndarray]]:
        """Where the body puts its point (its pin's centre where it has a hole) (n, 2), and that position's
        derivatives (n, 2) in the unknowns' and the slack's columns."""
        c, sn = self._rotation(body)
        local, index, directions = self.places[body, point]
        rel = _turned(local, c, sn)
        where = self._origin(body) + rel
        dq: dict[int, np.ndarray] = {}
        if body != GROUND:
            col = self.column[body]
            dq = {col: perp(rel), col + 1: _unit(self.n, 0), col + 2: _unit(self.n, 1)}
        turned = _turned(directions, c[:, None], sn[:, None])                 # (n, terms, 2) in one pass
        dp = {i: turned[:, j] for j, i in enumerate(index)}
        return where, dq, dp

    def material(self, body: str, drawn: np.ndarray) -> tuple[np.ndarray, dict[int, np.ndarray]]:
        """Where the body puts a drawn place of its own (no slack) (n, 2), and its derivatives in the unknowns."""
        c, sn = self._rotation(body)
        rel = _turned(drawn - _pt(self.s, self.s.bodies[body][0]), c, sn)
        if body == GROUND:
            return self._origin(body) + rel, {}
        col = self.column[body]
        return self._origin(body) + rel, {col: perp(rel), col + 1: _unit(self.n, 0), col + 2: _unit(self.n, 1)}

    def _add(self, res: np.ndarray, dq: dict[int, np.ndarray], dp: dict[int, np.ndarray]) -> None:
        self.rows.append((res, dq, dp))

    def _add2(self, res: np.ndarray, dq: dict[int, np.ndarray], dp: dict[int, np.ndarray]) -> None:
        for axis in (0, 1):
            self._add(res[:, axis], {k: v[:, axis] for k, v in dq.items()}, {k: v[:, axis] for k, v in dp.items()})

    def _build(self, values: np.ndarray) -> None:
        s = self.s
        for p in s.points:
            holders = s.holders(p)
            if len(holders) < 2:
                continue
            first, dq0, dp0 = self.point(holders[0], p)
            for other in holders[1:]:
                at, dq1, dp1 = self.point(other, p)
                self._add2(first - at, _minus(dq0, dq1), _minus(dp0, dp1))
        for sl in s.sliders:
            self._slider(sl)
        for i, inp in enumerate(s.inputs):
            if inp.kind == "crank":
                dq = _minus(self._turn_column(inp.link), self._turn_column(inp.relative_to))
                self._add(self._turn(inp.link) - self._turn(inp.relative_to) - values[:, i], dq, {})
            else:
                sl = s.slider_by_name[inp.slider]
                along, dq, dp = self._across(sl, normal=False)
                self._add(along - values[:, i], dq, dp)

    def _turn_column(self, body: str) -> dict[int, np.ndarray]:
        return {} if body == GROUND else {self.column[body]: np.ones(self.n)}

    def _across(self, sl: Slider, normal: bool) -> tuple[np.ndarray, dict[int, np.ndarray], dict[int, np.ndarray]]:
        """The slider's pin's offset from its guide's drawn line through the point, along the guide's normal
        (``normal``) or its direction, and its derivatives."""
        pin, dq_pin, dp = self.point(sl.body, sl.point)
        base, dq_base = self.material(sl.guide, _pt(self.s, sl.point))
        c, sn = self._rotation(sl.guide)
        u = _turned(np.array([math.cos(sl.angle), math.sin(sl.angle)]), c, sn)
        n = perp(u)
        axis, turned = (n, -u) if normal else (u, n)       # d(axis)/d(turn of the guide)
        gap = pin - base
        dq = {k: dot(axis, v) for k, v in _minus(dq_pin, dq_base).items()}
        if sl.guide != GROUND:
            col = self.column[sl.guide]
            dq[col] = dq.get(col, 0.0) + dot(turned, gap)
        return dot(axis, gap), dq, {k: dot(axis, v) for k, v in dp.items()}

    def _slider(self, sl: Slider) -> None:
        across, dq, dp = self._across(sl, normal=True)
        for index in (self.model.slot(sl.name), self.model.line(sl.name)):
            across = across - self.params[index]
            dp[index] = dp.get(index, 0.0) - np.ones(self.n)
        self._add(across, dq, dp)
        turn = _minus(self._turn_column(sl.body), self._turn_column(sl.guide))
        self._add(self._turn(sl.body) - self._turn(sl.guide), turn, {})

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Residuals (n, R), d/dq (n, R, M), d/dpi (n, R, P)."""
        rows, m, p = len(self.rows), 3 * len(self.moving), self.model.size
        res = np.zeros((self.n, rows))
        jq, jp = np.zeros((self.n, rows, m)), np.zeros((self.n, rows, p))
        for r, (value, dq, dp) in enumerate(self.rows):
            res[:, r] = value
            for k, v in dq.items():
                jq[:, r, k] += v
            for k, v in dp.items():
                jp[:, r, k] += v
        return res, jq, jp


#: a point's place in its body's drawn frame relative to the body's first point, with the slack (2,) mm, the
#: slack's columns that move it (their indices in pi) and the drawn direction (2,) a unit of each moves it along
#: (one row a column)
_Local = tuple[np.ndarray, tuple[int, ...], np.ndarray]


def _places(s: Structure, model: SlackModel, params: np.ndarray) -> dict[tuple[str, str], _Local]:
    """Every (body, point) of ``s``'s bodies' places with the slack ``params`` (P,): see :data:`_Local`. They do
    not change with the pose, so Newton's steps in :func:`perturbed` share them."""
    out: dict[tuple[str, str], _Local] = {}
    for body, points in s.bodies.items():
        first = _pt(s, points[0])
        for point in points:
            d = _pt(s, point) - first
            terms: list[tuple[int, np.ndarray]] = []
            h = model.hole(body, point)
            if h is not None:
                terms += [(h, np.array([1.0, 0.0])), (h + 1, np.array([0.0, 1.0]))]
            k = model.length(body, point)
            if k is not None:
                terms.append((k, d / np.linalg.norm(d)))
            offset = d + sum((params[i] * v for i, v in terms), np.zeros(2))
            out[body, point] = offset, tuple(i for i, _ in terms), np.array([v for _, v in terms]).reshape(-1, 2)
    return out


def _pt(s: Structure, name: str) -> np.ndarray:
    return np.asarray(s.points[name], dtype=float)


def _unit(n: int, axis: int) -> np.ndarray:
    out = np.zeros((n, 2))
    out[:, axis] = 1.0
    return out


def _turned(v: np.ndarray, c: np.ndarray, sn: np.ndarray) -> np.ndarray:
    """A drawn vector v (2,) (or vectors (..., 2)) turned by (c, sn) (n,) (or arrays broadcasting with v's
    leading axes): (n, 2) (or the broadcast shape, 2)."""
    x, y = v[..., 0], v[..., 1]
    out = np.empty((*np.broadcast_shapes(np.shape(c), np.shape(x)), 2))
    out[..., 0] = c * x - sn * y
    out[..., 1] = sn * x + c * y
    return out


def _minus(a: Mapping[int, np.ndarray], b: Mapping[int, np.ndarray]) -> dict[int, np.ndarray]:
    out = dict(a)
    for k, v in b.items():
        out[k] = out[k] - v if k in out else -v
    return out


# --------------------------------------------------------------------------------------------------- response


@dataclass(frozen=True)
class InLine:
    """How far a dyad of two bars (RRR) is from in line, over n poses: ``extended`` = r1 + r2 - d and ``folded`` =
    d - |r1 - r2| (mm; 0 at its dead point, where its transmission angle is 180 or 0 degrees), r1 and r2 its bars
    between their pins, d its outer pins' distance; and their derivatives in the slack (n, P). Unlike the
    transmission angle, which goes like the square root of the distance to the dead point, both are smooth through
    it, so their first order holds up to it."""

    extended: np.ndarray
    folded: np.ndarray
    d_extended: np.ndarray
    d_folded: np.ndarray


@dataclass(frozen=True)
class Response:
    """The first-order response to the slack at each of n poses of a solution: derivatives in pi (P columns).

    Attributes
    ----------
    model : SlackModel
        The parameters.
    points : dict of str to ndarray
        Each point's pin centre (its first holder's point) (n, 2, P), mm per mm.
    turns : dict of str to ndarray
        Each moving body's turn (n, P), rad per mm.
    transmission : tuple of ndarray
        Each dyad's transmission angle (n, P), rad per mm, in the plan's order (as
        :attr:`~linkgen.kinematics.linkage.Solution.dyads`).
    singular : ndarray
        (n,) bool: the poses where the closure's Jacobian is singular (a toggle); every derivative is inf there.
    inline : tuple of InLine or None
        Each dyad's distance from in line and its derivatives, for the dyads of two bars (None for the others).
    """

    model: SlackModel
    points: dict[str, np.ndarray]
    turns: dict[str, np.ndarray]
    transmission: tuple[np.ndarray, ...]
    singular: np.ndarray
    inline: tuple[InLine | None, ...] = ()


def _state(s: Structure, sol: Solution) -> _State:
    moving = [b for b in s.bodies if b != GROUND]
    return _State({b: sol.angle(b) for b in moving}, {b: sol.points[s.bodies[b][0]] for b in moving})


def response(linkage: Linkage, sol: Solution, model: SlackModel | None = None) -> Response:
    """The first-order response of every point, turn and transmission angle to the slack, at the poses of ``sol``
    (a solution of ``linkage``, of one or more inputs), by the closure equations' Jacobians.

    Parameters
    ----------
    linkage : Linkage
        The linkage; without redundant constraints (so that its closure's Jacobian is square).
    sol : Solution
        Its solution at the poses (positions are enough: ``derivatives=False`` will do).
    model : SlackModel, optional
        The parameters; :func:`slack_model` of the structure unless given.

    Returns
    -------
    Response
        Derivatives in mm per mm (points) and rad per mm (turns, transmission angles); inf at singular poses and
        at poses the solution marks as not reached.
    """
    s = linkage.structure
    model = slack_model(s) if model is None else model
    n = sol.inputs.shape[-1]
    closure = _Closure(s, model, _state(s, sol), np.zeros((n, len(s.inputs))), None)
    _, jq, jp = closure.arrays()
    if jq.shape[1] != jq.shape[2]:
        raise ValueError(f"the closure has {jq.shape[1]} rows for {jq.shape[2]} unknowns: a linkage with redundant "
                         "constraints (or of another mobility than its inputs)")
    scale = np.ones(jq.shape[2])
    scale[0::3] = s.size                                   # turn columns in mm, as the others
    scaled = jq / scale
    with np.errstate(invalid="ignore", over="ignore"):
        singulars = np.linalg.svd(np.where(np.isfinite(scaled), scaled, 0.0), compute_uv=False)
    singular = ~(singulars[:, -1] > SINGULAR * singulars[:, 0]) | ~np.asarray(sol.ok, dtype=bool)
    finite = ~singular[:, None, None]
    dq = -np.linalg.solve(np.where(finite, jq, np.eye(jq.shape[1])), np.where(finite, jp, 0.0))

    points = {}
    for p in s.points:
        _, dq_terms, dp_terms = closure.point(s.holders(p)[0], p)
        out = np.zeros((n, 2, model.size))
        for k, v in dq_terms.items():
            out += v[:, :, None] * dq[:, None, k, :]
        for k, v in dp_terms.items():
            out[:, :, k] += np.where(finite[:, :, 0], v, 0.0)
        points[p] = out
    turns = {b: dq[:, closure.column[b], :] for b in closure.moving}
    with np.errstate(divide="ignore", invalid="ignore"):
        transmission = tuple(_transmission(s, step, sol, points, turns) for step in linkage.plan.steps
                             if isinstance(step, DyadStep))
    unbounded = singular[:, None]
    inline = tuple(_inline(closure, step, sol, points, unbounded) if step.kind == "RRR" else None
                   for step in linkage.plan.steps if isinstance(step, DyadStep))
    return Response(model, {p: np.where(unbounded[:, :, None], np.inf, v) for p, v in points.items()},
                    {b: np.where(unbounded, np.inf, v) for b, v in turns.items()},
                    tuple(np.where(unbounded, np.inf, t) for t in transmission), singular, inline)


def _inline(closure: _Closure, step: DyadStep, sol: Solution, points: Mapping[str, np.ndarray],
            unbounded: np.ndarray) -> InLine:
    """An RRR dyad's distance from in line and its derivatives: each bar's length between its pins changes with its
    own slack alone (a rigid motion keeps it), the outer pins' distance with the known bodies' motion."""
    a1, a2 = step.attachments
    assert isinstance(a1, Pin) and isinstance(a2, Pin)
    j = sol.points[step.joint]
    n, size = len(j), closure.model.size
    lengths, d_lengths = [], []
    for body, pin in zip(step.bodies, (a1.point, a2.point), strict=True):
        rel = j - sol.points[pin]
        r = np.hypot(rel[:, 0], rel[:, 1])
        d_r = np.zeros((n, size))
        for place, sign in ((step.joint, 1.0), (pin, -1.0)):
            for k, v in closure.point(body, place)[2].items():
                d_r[:, k] += sign * dot(rel, v) / r
        lengths.append(r)
        d_lengths.append(d_r)
    rel = sol.points[a2.point] - sol.points[a1.point]
    d = np.hypot(rel[:, 0], rel[:, 1])
    d_d = np.where(unbounded, np.inf, _dot_d(rel, points[a2.point] - points[a1.point]) / d[:, None])
    (r1, r2), (d1, d2) = lengths, d_lengths
    side = np.where(r1 >= r2, 1.0, -1.0)[:, None]
    return InLine(r1 + r2 - d, d - np.abs(r1 - r2), d1 + d2 - d_d, d_d - side * (d1 - d2))


def _direction(s: Structure, sol: Solution, slider: str, body: str) -> np.ndarray:
    """A slider's guide direction in the world (n, 2), turned with ``body`` (the guide or the sliding body)."""
    sl = s.slider_by_name[slider]
    c, sn = sol.rotations[body]
    return _turned(np.array([math.cos(sl.angle), math.sin(sl.angle)]), c, sn)


def _turn_of(turns: Mapping[str, np.ndarray], body: str, like: np.ndarray) -> np.ndarray:
    return np.zeros_like(like) if body == GROUND else turns[body]


def _transmission(s: Structure, step: DyadStep, sol: Solution, points: Mapping[str, np.ndarray],
                  turns: Mapping[str, np.ndarray]) -> np.ndarray:
    """The derivative (n, P) of a dyad's transmission angle as the solver defines it
    (:func:`linkgen.kinematics.linkage._place_dyad`), from the points' and turns' derivatives."""
    a1, a2 = step.attachments
    kind = step.kind
    if kind == "RRR":
        assert isinstance(a1, Pin) and isinstance(a2, Pin)
        j = sol.points[step.joint]
        a, b = sol.points[a1.point] - j, sol.points[a2.point] - j
        da = points[a1.point] - points[step.joint]
        db = points[a2.point] - points[step.joint]
        sign = np.where(cross(a, b) >= 0, 1.0, -1.0)
        x, y = dot(a, b), sign * cross(a, b)
        dx = _dot_d(a, db) + _dot_d(b, da)
        dy = sign[:, None] * (_cross_d(a, db) - _cross_d(b, da))
        return (x[:, None] * dy - y[:, None] * dx) / (x**2 + y**2)[:, None]
    if kind in ("RRP", "PRR"):
        pin, slide = (a1, a2) if isinstance(a1, Pin) else (a2, a1)
        assert isinstance(pin, Pin) and isinstance(slide, Slide)
        u = _direction(s, sol, slide.slider, slide.body)
        rod = sol.points[step.joint] - sol.points[pin.point]
        drod = points[step.joint] - points[pin.point]
        dphi = _turn_of(turns, slide.body, drod[:, 0, :])
        du = perp(u)[:, :, None] * dphi[:, None, :]
        s1, s2 = np.where(cross(u, rod) >= 0, 1.0, -1.0), np.where(dot(rod, u) >= 0, 1.0, -1.0)
        x, y = s1 * cross(u, rod), s2 * dot(rod, u)
        dx = s1[:, None] * (_cross_d(u, drod) - _cross_d(rod, du))
        dy = s2[:, None] * (_dot_d(u, drod) + _dot_d(rod, du))
        return (x[:, None] * dy - y[:, None] * dx) / (x**2 + y**2)[:, None]
    if kind == "RPR":
        sl = s.slider_by_name[step.joint]
        (pm, bm), (pg, _) = sorted(((a1, step.bodies[0]), (a2, step.bodies[1])), key=lambda t: t[1] != sl.body)
        assert isinstance(pm, Pin) and isinstance(pg, Pin)
        d = sol.points[pm.point] - sol.points[pg.point]
        dd = points[pm.point] - points[pg.point]
        u = _direction(s, sol, sl.name, bm)
        n = perp(u)
        off = dot(n, d)
        doff = _dot_d(n, dd) - dot(u, d)[:, None] * _turn_of(turns, bm, dd[:, 0, :])
        dist = np.hypot(d[:, 0], d[:, 1])
        ddist = _dot_d(d, dd) / dist[:, None]
        w = np.sqrt(np.maximum(dist**2 - off**2, 0.0))
        sgn = np.where(off >= 0, 1.0, -1.0)
        dw = (dist[:, None] * ddist - off[:, None] * doff) / w[:, None]
        return (np.abs(off)[:, None] * dw - (w * sgn)[:, None] * doff) / (dist**2)[:, None]
    like = next(iter(points.values()))[:, 0, :]
    if kind == "PRP":
        # the angle between the guides, atan2(|u1 x u2|, |u1 . u2|), turns as they turn apart
        assert isinstance(a1, Slide) and isinstance(a2, Slide)
        u1, u2 = _direction(s, sol, a1.slider, a1.body), _direction(s, sol, a2.slider, a2.body)
        side = np.where(cross(u1, u2) >= 0, 1.0, -1.0) * np.where(dot(u1, u2) >= 0, 1.0, -1.0)
        return side[:, None] * (_turn_of(turns, a2.body, like) - _turn_of(turns, a1.body, like))
    return np.zeros_like(like)          # RPP / PPR: the pinned body keeps the sliding one's angle, the guides theirs


def _dot_d(a: np.ndarray, db: np.ndarray) -> np.ndarray:
    """d(a . b) for a fixed a (n, 2) and db (n, 2, P): (n, P)."""
    return a[:, 0, None] * db[:, 0, :] + a[:, 1, None] * db[:, 1, :]


def _cross_d(a: np.ndarray, db: np.ndarray) -> np.ndarray:
    """d(a x b) for a fixed a (n, 2) and db (n, 2, P): (n, P)."""
    return a[:, 0, None] * db[:, 1, :] - a[:, 1, None] * db[:, 0, :]


# -------------------------------------------------------------------------------------------------- perturbed


@dataclass(frozen=True)
class Perturbed:
    """A linkage as made with one slack vector: its structure drawn (assembled) at the nominal drawing's input,
    the amount its inputs' drawn values differ from the nominal's (so that input x of the nominal linkage is
    ``x + shift`` of this one: the same turn of each crank from the nominal drawing), and each body's turn in
    its drawing from the nominal one (rad: add it to the turns its solutions give)."""

    linkage: Linkage
    shift: np.ndarray
    turns: dict[str, float]

    def solve(self, inputs: np.ndarray) -> Solution:
        """Its solution at the nominal linkage's input values ``inputs`` (k, n) (positions only; poses it does not
        reach are marked in ``ok``)."""
        return self.linkage.solve(np.asarray(inputs) + self.shift[:, None], strict=False, derivatives=False)


def perturbed(linkage: Linkage, params: np.ndarray, model: SlackModel | None = None) -> Perturbed | None:
    """The linkage as made with slack ``params`` (P,): its bodies' points moved by the slack in their own frames, the
    drawing assembled by Newton's method on the closure equations at the drawn input, its solve order and its
    branches kept (a perturbation small against the links) and no change point (a perturbed change-point linkage
    toggles or passes on its branch). None where the drawing does not
    assemble (within :data:`ASSEMBLE_STEPS` steps, to :data:`ASSEMBLE_TOL` of its size).

    Solved by the project's own solver (:meth:`Perturbed.solve`), it checks :func:`response` independently."""
    s = linkage.structure
    model = slack_model(s) if model is None else model
    moving = [b for b in s.bodies if b != GROUND]
    turns = {b: np.zeros(1) for b in moving}
    origins = {b: _pt(s, s.bodies[b][0])[None, :].copy() for b in moving}
    values = np.zeros((1, len(s.inputs)))
    drawn = _places(s, model, params)
    for _ in range(ASSEMBLE_STEPS):
        closure = _Closure(s, model, _State(turns, origins), values, params, drawn)
        res, jq, _ = closure.arrays()
        if np.max(np.abs(res)) <= ASSEMBLE_TOL * s.size:
            break
        try:
            step = np.linalg.solve(jq[0], -res[0])
        except np.linalg.LinAlgError:
            return None
        for b in moving:
            col = closure.column[b]
            turns[b] = turns[b] + step[col]
            origins[b] = origins[b] + step[col + 1:col + 3]
    else:
        return None
    points: dict[str, tuple[float, float]] = {}
    for p in s.points:
        places = [closure.point(b, p)[0][0] for b in s.holders(p)]
        if any(np.hypot(*(q - places[0])) > AGREE_TOL * s.size for q in places[1:]):
            return None
        points[p] = (float(places[0][0]), float(places[0][1]))
    turned = {b: float(turns[b][0]) for b in moving}
    sliders = tuple(replace(sl, angle=sl.angle + turned.get(sl.guide, 0.0)) for sl in s.sliders)
    made = replace(linkage, structure=replace(s, points=points, sliders=sliders), flips=(), tracks={})
    shift = np.array([made.drawn_inputs[i] - linkage.drawn_inputs[i] if inp.kind == "crank" else 0.0
                      for i, inp in enumerate(s.inputs)])
    return Perturbed(made, shift, turned)
