"""Six-bar path generation, timed or untimed: a Watt I, Watt II, Stephenson I or III whose tracer meets N targets.

``task.linkage`` one of :data:`linkgen.synthesis.sixbar_types.SIXBARS` (their drawings there) of a path task,
with ``input_angles`` (timed) or without (untimed: each target met where the curve passes nearest it, the tracer
and similarity fitted by :func:`linkgen.synthesis.sixbar_untimed.nearest_fit`).

A design is a drawing normalised so that O2 = (0, 0) and O4 = (1, 0) (the ground line on +X, so the
crank's direction in it is its angle from the ground line): five free joints, ten numbers. A whole
population is solved at once (:mod:`linkgen.synthesis.sixbar_batch`: the general solver's closed form, its
solve order planned once a type, over designs by crank angles; 150 designs of a Watt I at 88 angles in about
15 ms, where one by one through :class:`linkgen.kinematics.linkage.Linkage` took about 400 ms), at the
targets' crank angles and over a sampled turn, each dyad on the branch the drawing shows.
The tracer's place on its link and the similarity (scale, turn, shift) that puts the drawing onto the
targets are linear: with R_k the tracer link's turn and F_k its reference joint at target k (complex
numbers), the tracer is W_k = R_k u + z F_k + t, so (u, z, t) come by least squares in closed form
(variable projection); the search runs over the ten drawing numbers only, by scipy's differential
evolution, and its best few designs are polished by least squares on the distances (the Jacobian's designs
solved at once too). Each search stops when
it stalls (its best and its median both: :mod:`linkgen.synthesis.sixbar_stop`) or its population collapses,
and the ``starts`` once two agree, as the four-bar's (:mod:`linkgen.synthesis.stop`); ``designs_evaluated``
counts the designs the differential evolution evaluated (each vectorised call a whole population),
``vectorised_calls`` the calls.

Constraints (hard: a design breaking one ranks behind every one that keeps them): every dyad closes
over the whole turn of the crank on its drawn branch (its margin above MARGIN_FLOOR at the sampled
angles); every transmission angle within [mu, 180 - mu] there (``min_transmission``); every link and
the ground within ``link_range``. A candidate is then checked by the solver as ``linkgen analyze``
reads it: the crank turns fully and no dyad passes a change point over the turn (else a ``branch``
defect), its worst transmission angle over FINE_TURN angles at least ``min_transmission``.

The four-bar's best on the same targets (:mod:`linkgen.synthesis.path`, the same seed and budget) is
reported next to it: in the search's ``four_bar`` and each row's ``four_bar_error_mm2``.
Units: mm and degrees (radians inside); angles counter-clockwise.
"""
from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import CamgenError, SpecError
from camgen.core.spec import MAX_LENGTH_MM, MIN_LENGTH_MM
from linkgen.kinematics.fused import Program
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.structure import Structure, make_structure, plan
from linkgen.synthesis.candidates import Candidate, Sketch, table_fits, weighed
from linkgen.synthesis.parallel import run_all, where
from linkgen.synthesis.sixbar_batch import solve_many
from linkgen.synthesis.sixbar_seed import embedded, embedded_stephenson1
from linkgen.synthesis.sixbar_types import CRANK, TOPOLOGIES, Topology
from linkgen.synthesis.sixbar_untimed import assigned_fit, fit, nearest_fit, nearest_on
from linkgen.synthesis.sixbar_stop import why_stop_six
from linkgen.synthesis.stop import rule_for, run_starts

TWO_PI = 2.0 * math.pi
#: the crank angles (evenly over a turn) at which a design's dyads are checked during the search, and a
#: candidate's, for its worst transmission angle and its figure
TURN, FINE_TURN = 72, 1440
#: untimed, the crank angles (evenly over a turn) of the curve each target's nearest point is looked for on
UNTIMED_TURN = 360
#: a dyad's margin (a sine, see :class:`linkgen.kinematics.linkage.DyadResult`) must stay above this over the turn
MARGIN_FLOOR = 1e-3
#: the objective of a design breaking a hard constraint: BIG * (1 + its violation), behind every feasible one
BIG = 1e12
#: distinct designs of each search's final population polished
POLISHED = 3
#: the box of each free joint's coordinates in the normalised drawing (ground lengths, O2 at 0 and O4 at 1)
SHAPE_BOX = 3.0




@dataclass(frozen=True)
class Problem:
    """A six-bar path task in numbers: the topology, the targets (n,) complex mm, the crank angles there (n,) rad
    from the ground line, the lengths' limits (mm), cos of the least transmission angle (or None) and the budget."""

    topology: Topology
    targets: np.ndarray
    timing: np.ndarray | None
    lengths: tuple[float, float]
    min_transmission: float
    generations: int
    population: int
    scale: float


def problem_of(task: Any) -> Problem:
    """The numbers of a validated six-bar path task; the lengths' limits those of the four-bar's search on the same
    targets (:func:`linkgen.synthesis.path.problem_of`: by default 1/20 to 4 times the targets' spread)."""
    from linkgen.synthesis import path

    four = path.problem_of(task)
    targets = four.targets[:, 0] + 1j * four.targets[:, 1]
    timing = None if task.input_angles is None else np.radians(task.input_angles)
    return Problem(TOPOLOGIES[task.linkage], targets, timing, four.box[3],
                   math.radians(task.min_transmission), task.generations, task.population, four.scale)


def drawing(x: np.ndarray, topology: Topology, tracer: complex | None = None) -> dict[str, tuple[float, float]]:
    """The normalised drawing of design ``x`` (10,): O2 at the origin, O4 at (1, 0), the free joints from ``x``
    (and the tracer P, when given)."""
    points = {"O2": (0.0, 0.0), "O4": (1.0, 0.0)}
    points |= {name: (float(x[2 * i]), float(x[2 * i + 1])) for i, name in enumerate(topology.free)}
    if tracer is not None:
        points["P"] = (tracer.real, tracer.imag)
    return points


def structure_of(points: dict[str, tuple[float, float]], topology: Topology) -> Structure:
    """The solver's structure of a drawing (with or without the tracer P)."""
    links = {k: tuple(p for p in v if p in points) for k, v in topology.links.items()}
    return make_structure(points, links, topology.ground, (), CRANK)


def pairs(topology: Topology) -> tuple[tuple[str, str], ...]:
    """Every pair of joints of one link (the ground's pivots too), P left out, in :func:`link_lengths`' order."""
    out = []
    for pts in (topology.ground, *topology.links.values()):
        joints = [p for p in pts if p != "P"]
        out += [(a, b) for i, a in enumerate(joints) for b in joints[i + 1:]]
    return tuple(out)


def link_lengths(points: dict[str, tuple[float, float]], topology: Topology) -> dict[str, float]:
    """Every distance between two joints of one link (the ground's pivots too), by ``"J1-J2"`` (P left out)."""
    return {f"{a}-{b}": math.dist(points[a], points[b]) for a, b in pairs(topology) if a in points and b in points}


@dataclass(frozen=True)
class Evaluation:
    """One design evaluated: the residuals (n,) complex mm, the similarity and tracer (u, z, t), the hard
    constraints' rows (>= 0 kept, dimensionless) and the crank angles at the targets (rad)."""

    residuals: np.ndarray
    uzt: np.ndarray
    rows: np.ndarray
    angles: np.ndarray


@dataclass(frozen=True)
class Evaluations:
    """N designs evaluated (:func:`evaluate_many`): whether each is a linkage (N,) (False: joints of a link drawn
    together, or not finite), and per design as :class:`Evaluation` the residuals (N, n) complex mm (NaN where a
    target's crank angle is not reached), (u, z, t) (N, 3) complex, the constraints' rows (N, R) (the link_range
    rows 0 where the residuals are NaN) and the crank angles at the targets (N, n) rad; untimed, the assignment
    (N, n) of the targets to the turn's samples that (u, z, t) was fitted on (-1 where none was fitted; timed, None)."""

    linkage: np.ndarray
    residuals: np.ndarray
    uzt: np.ndarray
    rows: np.ndarray
    angles: np.ndarray
    assignment: np.ndarray | None = None


@functools.cache
def _program(name: str) -> Program:
    """The solve order of six-bar type ``name``, planned once (it depends on the links, not on where the joints are
    drawn): from a drawing of its free joints spread around the ground line."""
    topo = TOPOLOGIES[name]
    x = np.array([v for i in range(len(topo.free)) for v in (0.5 + 0.6 * math.cos(1.3 * i + 0.7),
                                                             0.4 + 0.5 * math.sin(1.3 * i + 0.7))])
    s = structure_of(drawing(x, topo), topo)
    prog = Linkage(s, plan(s)).program
    assert prog is not None, "a six-bar type is a crank and RRR dyads"
    return prog


def _general(x: np.ndarray, p: Problem, angles: np.ndarray) -> tuple[np.ndarray, ...] | None:
    """Design ``x`` (10,) by the general solver at ``angles`` (M,): reached (M,), least margin and transmission
    angle over the dyads (M,), the tracer link's turn and its reference joint (M,) complex; None where it is not a
    linkage. For a drawing whose deltoid's pins meet (:mod:`linkgen.synthesis.sixbar_batch`)."""
    topo = p.topology
    try:
        s = structure_of(drawing(x, topo), topo)
        sol = Linkage(s, plan(s)).solve(angles[None, :], strict=False, derivatives=False)
    except (CamgenError, ValueError, ArithmeticError):
        return None
    margin = np.min([d.margin for d in sol.dyads], axis=0)
    gamma = np.min([np.minimum(d.transmission, math.pi - d.transmission) for d in sol.dyads], axis=0)
    c, sn = sol.rotations[topo.tracer_link]
    ref = sol.points[topo.reference]
    return sol.ok, margin, gamma, c + 1j * sn, ref[:, 0] + 1j * ref[:, 1]


def evaluate_many(x: np.ndarray, p: Problem, assignment: np.ndarray | None = None,
                  fit_broken: bool = True) -> Evaluations:
    """Designs ``x`` (10, N) at the targets' crank angles and over a sampled turn, all at once
    (:func:`linkgen.synthesis.sixbar_batch.solve_many`; a drawing whose deltoid's pins meet by the general solver):
    each dyad's margin and transmission angle over the turn, the tracer and the similarity fitted by least squares
    (timed: at the targets' crank angles; untimed: at each target's nearest point of the turn, found by
    :func:`linkgen.synthesis.sixbar_untimed.nearest_fit`, or fitted on a known ``assignment`` (N, n) of the targets
    to the turn's samples by :func:`linkgen.synthesis.sixbar_untimed.assigned_fit` where its row has no -1).
    ``fit_broken=False`` leaves unfitted, untimed, each design a dyad's margin or transmission angle already breaks
    (its residuals NaN, its length rows 0): for a caller that only asks which designs keep every constraint and
    the errors of those (:func:`errors`), not how far the others break them."""
    topo = p.topology
    count = x.shape[1]
    z = x[0::2] + 1j * x[1::2]
    joints = {"O2": np.zeros(count, complex), "O4": np.ones(count, complex)} | {
        name: z[i] for i, name in enumerate(topo.free)}
    turn = np.linspace(0.0, TWO_PI, TURN if p.timing is not None else UNTIMED_TURN, endpoint=False)
    angles = turn if p.timing is None else np.concatenate([p.timing, turn])
    links = {k: tuple(j for j in v if j != "P") for k, v in topo.links.items()}
    sol = solve_many(_program(topo.name), joints, links, topo.ground, angles, topo.tracer_link, topo.reference)
    ok, margin, gamma, rot, ref = (np.array(v) for v in (sol.ok, sol.margin, sol.gamma, sol.rot, sol.ref))
    linkage = sol.drawn.copy()
    for j in np.flatnonzero(sol.general & sol.drawn):
        got = _general(x[:, j], p, angles)
        if got is None:
            linkage[j] = False
            continue
        ok[j], margin[j], gamma[j], rot[j], ref[j] = got
    n = 0 if p.timing is None else len(p.timing)
    k = len(p.targets)
    rows = [np.where(ok, margin, -1.0) - MARGIN_FLOOR]
    if p.min_transmission > 0:
        rows.append(np.where(ok, gamma, -1.0) - p.min_transmission)
    reached = linkage & (ok[:, :n].all(axis=1) if p.timing is not None else ok.all(axis=1))
    uzt = np.full((count, 3), np.nan, complex)
    at = np.full((count, k), np.nan)
    a = np.full((count, k, 3), np.nan, complex)
    fitted = np.full((count, k), -1)
    if p.timing is not None:
        a[reached] = np.stack([rot[reached, :n], ref[reached, :n], np.ones((int(reached.sum()), n))], axis=2)
        uzt[reached] = fit(a[reached], p.targets)
        at[reached] = p.timing
    else:
        if not fit_broken:                              # a dyad already breaks: its fit cannot mend that
            reached = reached & np.all(np.concatenate(rows, axis=1) >= 0, axis=1)
        for j in np.flatnonzero(reached):
            if assignment is not None and np.all(assignment[j] >= 0):
                fitted[j] = assignment[j]
                uzt[j], nearest = assigned_fit(rot[j], ref[j], p.targets, fitted[j])
            else:
                uzt[j], nearest, fitted[j] = nearest_fit(rot[j], ref[j], p.targets)
            at[j] = turn[nearest]
            a[j] = np.column_stack([rot[j, nearest], ref[j, nearest], np.ones(k)])
    residuals = (a @ uzt[:, :, None])[:, :, 0] - p.targets[None, :]
    scale = np.abs(uzt[:, 1])
    lengths = np.stack([np.abs(joints[i] - joints[j]) for i, j in pairs(topo)], axis=1) * scale[:, None]
    lo, hi = p.lengths
    fits = np.concatenate([(lengths - lo) / p.scale, (hi - lengths) / p.scale], axis=1)
    rows.append(np.where(reached[:, None], fits, 0.0))
    return Evaluations(linkage, residuals, uzt, np.concatenate(rows, axis=1), at,
                       None if p.timing is not None else fitted)


def evaluate(x: np.ndarray, p: Problem) -> Evaluation | None:
    """Design ``x`` (10,) as :func:`evaluate_many` gives it; None where it is not a linkage (joints drawn
    together)."""
    e = evaluate_many(np.asarray(x, dtype=float)[:, None], p)
    if not e.linkage[0]:
        return None
    return Evaluation(e.residuals[0], e.uzt[0], e.rows[0], e.angles[0])


def objective(x: np.ndarray, p: Problem, fit_broken: bool = True) -> np.ndarray:
    """The error (mm^2) of each design of a population ``x`` (10, N), or BIG (1 + violation) where it breaks a hard
    constraint (2 BIG where it is not a linkage): the whole population solved at once. ``fit_broken=False`` (see
    :func:`evaluate_many`): a design a dyad breaks is not fitted, so its violation leaves out its links' lengths
    (still at least BIG)."""
    e = evaluate_many(x, p, fit_broken=fit_broken)
    broken = np.sum(np.maximum(0.0, -e.rows), axis=1)
    err = np.sum(np.abs(e.residuals) ** 2, axis=1)
    out = np.where((broken > 0) | ~np.isfinite(err), BIG * (1.0 + broken), err)
    return np.where(e.linkage, out, 2.0 * BIG)


#: the polish's forward-difference step (drawing units: ground lengths)
STEP = 1e-7


def _polish(x: np.ndarray, p: Problem) -> tuple[np.ndarray, float]:
    """Design ``x`` polished by least squares on the distances (the Jacobian by forward differences of STEP, its
    eleven designs solved at once; untimed, the ten shifted designs keep the targets' assignment to the turn's
    samples that the design itself was fitted on: the derivative of the error at its nearest points); the polished
    design if it keeps every hard constraint and is no worse, else ``x``."""
    from scipy.optimize import least_squares

    def error(v: np.ndarray) -> float:
        e = evaluate(v, p)
        if e is None or np.any(e.rows < 0):
            return math.inf
        return float(np.sum(np.abs(e.residuals) ** 2))

    def rows(designs: np.ndarray, assignment: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray | None]:
        e = evaluate_many(designs, p, assignment)
        r = np.where(e.linkage[:, None] & np.isfinite(e.residuals), e.residuals, p.scale)
        return np.concatenate([r.real, r.imag], axis=1), e.assignment

    def jacobian(v: np.ndarray) -> np.ndarray:
        shifted = v[:, None] + np.hstack([np.zeros((len(v), 1)), STEP * np.eye(len(v))])
        if p.timing is not None:
            r = rows(shifted)[0]
        else:
            r0, fitted = rows(shifted[:, :1])
            assert fitted is not None
            r = np.vstack([r0, rows(shifted[:, 1:], np.repeat(fitted, len(v), axis=0))[0]])
        return ((r[1:] - r[0]) / STEP).T

    found = error(x)
    try:
        v = least_squares(lambda v: rows(v[:, None])[0][0], x, jac=jacobian, method="trf",
                          bounds=(-SHAPE_BOX, SHAPE_BOX), xtol=1e-12, ftol=1e-12, gtol=1e-12,
                          max_nfev=60 * len(x)).x
    except (ValueError, ArithmeticError):
        return x, found
    polished = error(v)
    return (v, polished) if polished <= found else (x, found)


def _first_population(p: Problem, seed: int, start: np.ndarray | None) -> np.ndarray | str:
    """The differential evolution's first population: scipy's Latin hypercube, or (with a ``start`` design) one
    of the same size drawn from the same seed with ``start`` as its first member."""
    if start is None:
        return "latinhypercube"
    from scipy.stats import qmc

    dim = 2 * len(p.topology.free)
    out = -SHAPE_BOX + 2.0 * SHAPE_BOX * qmc.LatinHypercube(d=dim, seed=seed).random(p.population * dim)
    out[0] = start
    return out


def search(args: tuple[Problem, int, np.ndarray | None]) -> dict[str, Any]:
    """One seeded search: differential evolution over the drawing (its first population holding ``start``, the
    best four-bar embedded, where given) until it stalls or its population collapses
    (:func:`linkgen.synthesis.sixbar_stop.why_stop_six`) or its generations run out, then its best few distinct
    designs polished. Returns those that keep every constraint (design, error), the vectorised calls (each of a whole
    population), the designs they evaluated, the generations run and why the search stopped ("stall", "collapse"
    or "budget")."""
    from scipy.optimize import differential_evolution

    p, seed, start = args
    rule = rule_for(p.scale)
    best: list[float] = []
    median: list[float] = []
    stopped: list[str] = []

    def hook(intermediate_result: Any) -> bool:      # scipy passes the result so far to a parameter of this name
        energies = np.asarray(intermediate_result.population_energies)
        best.append(float(np.min(energies)))
        median.append(float(np.median(energies)))
        why = why_stop_six(best, median, energies, rule)
        if why is not None:
            stopped.append(why)
        return why is not None

    bounds = [(-SHAPE_BOX, SHAPE_BOX)] * (2 * len(p.topology.free))
    r = differential_evolution(objective, bounds, args=(p,), vectorized=True, updating="deferred", seed=seed,
                               maxiter=p.generations, popsize=p.population, tol=0, atol=0, polish=False,
                               init=_first_population(p, seed, start), callback=hook)
    picked: list[int] = []
    for i in np.argsort(r.population_energies, kind="stable"):
        if r.population_energies[i] >= BIG:
            break
        if all(np.max(np.abs(r.population[i] - r.population[j])) > 1e-3 * SHAPE_BOX for j in picked):
            picked.append(int(i))
        if len(picked) == POLISHED:
            break
    found = [_polish(r.population[i], p) for i in picked]
    # scipy counts a vectorised call as one evaluation (nfev); each evaluates the whole population
    return {"found": [(v.tolist(), e) for v, e in found if math.isfinite(e)], "calls": int(r.nfev),
            "evaluations": int(r.nfev) * len(r.population), "generations": int(r.nit),
            "stopped": stopped[0] if stopped else "budget", "best_energy": float(np.min(r.population_energies))}


def placed(x: np.ndarray, p: Problem) -> tuple[dict[str, tuple[float, float]], Evaluation] | None:
    """The drawing of design ``x`` in the task's frame at the first target's crank angle, with the tracer P: every
    joint where the solver puts it there, moved by the similarity z (.) + t."""
    topo = p.topology
    e = evaluate(x, p)
    if e is None:
        return None
    u, z, t = e.uzt
    norm = drawing(x, topo)
    s = structure_of(norm, topo)
    sol = Linkage(s, plan(s)).solve(e.angles[:1][None, :], strict=False, derivatives=False)
    c, sn = sol.rotations[topo.tracer_link]
    at = {k: complex(*v[0]) for k, v in sol.points.items()}
    at["P"] = complex((c[0] + 1j * sn[0]) * u + z * at[topo.reference] + t)
    world = {k: (v if k == "P" else z * v + t) for k, v in at.items()}
    return {k: (float(v.real), float(v.imag)) for k, v in world.items()}, e


def _candidate(x: np.ndarray, p: Problem) -> Candidate | None:
    """A polished design as a candidate (None if it has a branch defect, breaks the transmission limit over the
    fine turn, or does not fit a template): the ``[linkage]`` table drawn at the first target, its row, figure."""
    topo = p.topology
    got = placed(x, p)
    if got is None:
        return None
    joints, e = got
    try:
        linkage = Linkage.of(structure_of(joints, topo))
    except CamgenError:
        return None
    if linkage.ranges is not None or any(len(f) for f in linkage.flips):
        return None                               # the crank does not turn fully, or a dyad passes a change point
    z = complex(e.uzt[1])
    first = float(np.angle(complex(*joints["A"]) - complex(*joints["O2"])))
    turn = first + np.linspace(0.0, TWO_PI, FINE_TURN + 1)
    sol = linkage.solve(turn[None, :], strict=False, derivatives=False)
    if not sol.ok.all():
        return None
    worst = min(float(np.min(np.minimum(d.transmission, math.pi - d.transmission))) for d in sol.dyads)
    if worst < p.min_transmission - 1e-9:
        return None
    table = {"type": "linkage", "ground": list(topo.ground), "input": {"link": "crank", "pivot": "O2"},
             "tracers": ["P"], "joints": {k: list(v) for k, v in joints.items()},
             "links": {k: list(v) for k, v in topo.links.items()}}
    if not table_fits(table):
        return None
    targets = np.column_stack([p.targets.real, p.targets.imag])
    if p.timing is None:
        def tracer(t: np.ndarray) -> np.ndarray:
            return linkage.solve(t[None, :], strict=False, derivatives=False).points["P"]

        reached, world = nearest_on(tracer, turn, sol.points["P"], targets)
        timing = world - np.angle(z)
    else:
        reached, timing = targets + np.column_stack([e.residuals.real, e.residuals.imag]), p.timing
    sq = np.sum((reached - targets) ** 2, axis=1)
    directions = np.degrees(timing + np.angle(z)) % 360.0
    lengths = link_lengths(joints, topo)
    row = {"error_mm2": float(sq.sum()), "linkage": topo.name, "timed": p.timing is not None,
           "joints": table["joints"], "link_lengths": lengths,
           "input_angles": [round(math.degrees(t) % 360.0, 9) % 360.0 for t in timing],
           "input_directions": directions.tolist(), "errors_mm": np.sqrt(sq).tolist(),
           "transmission_worst_deg": math.degrees(worst), "defects": []}
    if not all(MIN_LENGTH_MM <= v <= MAX_LENGTH_MM for v in lengths.values()):
        return None
    curve = sol.points["P"]
    pose = np.array([joints[k] for k in (*topo.ground[:1], "A", "B", topo.ground[1], "B",
                                         *[j for j in topo.free[2:]], topo.reference, "P")])
    sketch = Sketch(paths=(("tracer curve", curve),), poses=(("at the first target", pose),), targets=targets,
                    reached=reached)
    signature = tuple(v for xy in joints.values() for v in xy)
    return Candidate(table, row, float(sq.sum()), signature, sketch)


def four_bar_best(task: Any, jobs: int, scheduler: str | None) -> tuple[dict[str, Any], dict[str, Any]]:
    """The best four-bar on the same targets, timing, seed and budget (:func:`linkgen.synthesis.path.solve`): its
    error, worst transmission angle, lengths, joints drawn at the first target and crank directions at the targets
    (degrees), or why none was found; and its joints again (empty where none was found)."""
    from linkgen.synthesis import path

    four = task.model_copy(update={"linkage": "four-bar"})
    try:
        found, info = path.solve(four, jobs, scheduler)
    except SpecError as exc:
        return {"error_mm2": None, "why": str(exc)}, {}
    if found and "violation" in found[0].row:           # none keeps the requirements: the nearest, not a best
        return {"error_mm2": None, "why": "; ".join(info["bound"])}, {}
    best = min((weighed(c) for c in found), key=lambda c: c.score)
    return ({"error_mm2": best.row["error_mm2"], "transmission_worst_deg": best.row["transmission_worst_deg"],
             "lengths": [best.row[k] for k in ("ground", "crank", "coupler", "rocker")],
             "joints": best.linkage["joints"], "input_directions": best.row["input_directions"]},
            best.linkage["joints"])


def _keeps(x: np.ndarray, p: Problem) -> bool:
    """Whether design ``x`` keeps every hard constraint of the search."""
    e = evaluate(x, p)
    return e is not None and bool(np.all(e.rows >= 0)) and bool(np.all(np.isfinite(e.residuals)))


def errors(x: np.ndarray, p: Problem) -> np.ndarray:
    """The error (mm^2) of each design of ``x`` (10, N), infinite where it breaks a hard constraint (a design a
    dyad's margin or transmission angle breaks is not fitted: its error is infinite whatever its fit)."""
    value = objective(x, p, fit_broken=False)
    return np.where(value < BIG, value, math.inf)


def _start(joints: dict[str, Any], p: Problem) -> np.ndarray | None:
    """The best four-bar (drawn at ``joints``) embedded as a design of the task's six-bar type, or None: a
    Stephenson III by :func:`linkgen.synthesis.sixbar_seed.embedded`, a Stephenson I by
    :func:`linkgen.synthesis.sixbar_seed.embedded_stephenson1`."""
    if p.topology.name == "stephenson1":
        shortest = p.lengths[0] / math.dist(joints["O2"], joints["O4"])
        return embedded_stephenson1(joints, SHAPE_BOX, shortest, lambda x: errors(x, p))
    return embedded(joints, p.topology.name, SHAPE_BOX, lambda x: _keeps(x, p))


def solve(task: Any, jobs: int = 1, scheduler: str | None = None) -> tuple[list[Candidate], dict[str, Any]]:
    """Six-bar path generation for a validated path task (``linkage`` a six-bar, timed): the candidates
    (unranked) and how the search went, the four-bar's best next to it."""
    p = problem_of(task)
    seeds = [int(s.generate_state(1)[0]) for s in np.random.SeedSequence(task.seed).spawn(task.starts)]
    four, joints = four_bar_best(task, jobs, scheduler)
    start = _start(joints, p) if joints else None
    clock = time.perf_counter()
    runs, agree = run_starts(lambda batch: run_all(search, [(p, s, start) for s in batch], jobs, scheduler), seeds,
                             len(seeds) if scheduler is not None else jobs, rule_for(p.scale).atol, task.candidates)
    seconds = time.perf_counter() - clock
    out = []
    for run in runs:
        for x, _ in run["found"]:
            c = _candidate(np.asarray(x), p)
            if c is not None:
                out.append(weighed(c))
    tried = sum(r["evaluations"] for r in runs)
    if not out:
        raise SpecError(f"no {task.linkage} six-bar found whose crank turns fully with every dyad on its branch, "
                        f"its transmission angle at least {task.min_transmission:g} degrees and its links within "
                        f"link_range ({tried} designs tried): give more generations, widen link_range or lower "
                        "min_transmission", "task.points")
    out = [Candidate(c.linkage, {**c.row, "four_bar_error_mm2": four["error_mm2"]}, c.score, c.signature, c.sketch)
           for c in out]
    info = {"method": f"{task.linkage} six-bar: differential evolution (scipy) over the normalised drawing, each "
                      "design solved by the general solver at the targets and over a turn, the tracer and the "
                      "similarity by least squares; polished by least squares",
            "seed": task.seed, "starts": task.starts, "generations": task.generations, "starts_run": len(runs),
            "starts_agreed": agree, "generations_run": [r["generations"] for r in runs],
            "stopped": [r["stopped"] for r in runs], "vectorised_calls": sum(r["calls"] for r in runs),
            "designs_evaluated": tried, "seconds": round(seconds, 3), "ran_on": where(jobs, scheduler),
            "four_bar": four, "seeded_from_four_bar": start is not None, "bound": []}
    return out, info
