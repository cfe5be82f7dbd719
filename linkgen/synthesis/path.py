"""Path generation: a four-bar whose coupler point passes N target points, with or without the crank angles there.

The unknowns (see :mod:`linkgen.synthesis.geometry`) are the crank pivot (x0, y0), the ground
line's direction theta0, the four lengths, the coupler point (cx, cy) and the branch; without
timing also the crank angle at each target, as a start angle, a sense of turning and a partition
of one turn (so the targets are always met in order, within one turn). The error is the sum of
squared distances from the targets (mm^2).

For given theta0, lengths, branch and crank angles, the coupler point is linear in (x0, y0, cx,
cy): P_k = O2 + A_k + cx e_k + cy e_k', e_k the coupler's direction. So the search runs over the
others and solves for those four by least squares in closed form (variable projection), for the
whole population at once. Each search is scipy's differential evolution with the population
evaluated in one vectorised call (``vectorized=True``): a design breaking a hard constraint ranks
behind every feasible one (BIG (1 + violation)); one outside the box of the linear unknowns or
the ground region pays a penalty growing with the distance. Its best few distinct designs are
then polished over all the unknowns: least squares on the distances, or where that breaks a
constraint, SLSQP with the constraints as inequalities first.

Constraints: a Grashof crank (the crank the shortest link, S + L < P + Q) when asked; the crank
meeting the targets in order within one turn; one branch (the crank reaching every target, and
the motion between them, without a toggle); the lengths within ``link_range`` and their ratio
within ``link_ratio``; the coupler point within ``coupler_range`` of the crank pin (each of cx,
cy); both ground pivots within ``ground_region``; the transmission angle within [mu, 180 - mu]
over the motion (``min_transmission``, 30 degrees unless the task says otherwise; the whole turn
for a crank), exactly. Where no design keeps the hard ones, the nearest are offered
(:mod:`linkgen.synthesis.path_nearest`); where the best candidate sits on a limit, the search's
``bound`` line names it.
Each search stops when it stalls or its population collapses, and the ``starts`` (independent
searches, each seeded from ``seed``) once two agree (:mod:`linkgen.synthesis.stop`); they run here,
on local processes or on a Dask cluster, with the same results.
"""
from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.spec import MAX_LENGTH_MM, MIN_LENGTH_MM
from linkgen.kinematics.grashof import classify
from linkgen.synthesis.candidates import Candidate, coupler_sketch, drawn_table, fourbar_row, table_fits, weighed
from linkgen.synthesis.defects import defects
from linkgen.synthesis.geometry import place, place_design, transmission_range, worst_transmission
from linkgen.synthesis.parallel import run_all, where
from linkgen.synthesis.stop import rule_for, run_starts, why_stop

BASE = ("x0", "y0", "theta0", "r1", "r2", "r3", "r4", "cx", "cy")
#: what differential evolution searches over (then, without timing, the start angle, sense and partition)
SEARCHED = ("theta0", "r1", "r2", "r3", "r4", "branch")
#: the objective of a design breaking a hard constraint: BIG * (1 + its violation), behind every feasible one
BIG = 1e12
#: the penalty of a design outside the box or region: SOFT scale^2 (v + v^2), v its relative distance outside
SOFT = 10.0
#: S + L must stay this far (relative to the scale) below P + Q: clear of change points
GRASHOF_MARGIN = 1e-4
#: the fractions of each step between targets where a crank that does not turn fully is checked for reach
STEPS = np.array([0.25, 0.5, 0.75])
#: distinct designs of each search's final population polished (the task's budget counts them: POLISH_EVALUATIONS)
POLISHED = 3
#: the transmission limit is kept this far inside (rad), so that a candidate on it reports no less than the limit
TRANSMISSION_MARGIN = 1e-10
#: designs of each search's final population kept as the nearest where none keeps every hard constraint
NEAREST_KEPT = 12
TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Problem:
    """A path task in numbers: targets (n, 2) mm, the crank angles there (rad from the ground line, or None), the
    searched unknowns' bounds, the box of all nine design numbers (:data:`BASE`), the ground region, the other
    constraints, the search's budget and the lengths' scale (mm)."""

    targets: np.ndarray
    timing: np.ndarray | None
    crank: bool
    bounds: tuple[tuple[float, float], ...]
    box: tuple[tuple[float, float], ...]
    region: tuple[float, float, float, float]
    link_ratio: float | None
    cos_transmission: float | None
    generations: int
    population: int
    scale: float
    #: the candidates asked for: the starts go on until their designs have as many distinct errors
    wanted: int = 1

    @property
    def n(self) -> int:
        return len(self.targets)


def problem_of(task: Any) -> Problem:
    """The numbers of a validated :class:`~linkgen.synthesis.task.PathTask`; defaults: lengths from 1/20 to 4
    times the targets' spread, the coupler point within the longest length, the ground pivots within the
    targets' box grown by the longest length; all within what a template holds (MIN_LENGTH_MM to MAX_LENGTH_MM,
    joints within MAX_LENGTH_MM of the origin)."""
    targets = np.array(task.points, dtype=float)
    spread = float(np.max(np.ptp(targets, axis=0)))
    if task.link_range is not None:
        lo, hi = task.link_range
    else:
        lo = max(spread / 20, MIN_LENGTH_MM)
        hi = min(max(4 * spread, 10 * lo), MAX_LENGTH_MM)
    reach = task.coupler_range if task.coupler_range is not None else hi
    if task.ground_region is not None:
        (x_min, y_min), (x_max, y_max) = task.ground_region
    else:
        (x_min, y_min), (x_max, y_max) = (np.clip(targets.min(axis=0) - hi, -MAX_LENGTH_MM, MAX_LENGTH_MM),
                                          np.clip(targets.max(axis=0) + hi, -MAX_LENGTH_MM, MAX_LENGTH_MM))
    box = ((x_min, x_max), (y_min, y_max), (-math.pi, math.pi), *[(lo, hi)] * 4, (-reach, reach), (-reach, reach))
    bounds = [box[2], *box[3:7], (-1.0, 1.0)]
    timing = None if task.input_angles is None else np.radians(task.input_angles)
    if timing is None:
        bounds += [(0.0, TWO_PI), (-1.0, 1.0)] + [(0.05, 1.0)] * len(targets)
    mu = task.min_transmission
    return Problem(targets, timing, task.crank, tuple(bounds), box, (x_min, y_min, x_max, y_max), task.link_ratio,
                   None if mu == 0 else math.cos(math.radians(mu) + TRANSMISSION_MARGIN), task.generations,
                   task.population, hi, task.candidates)


def angles(x: np.ndarray, p: Problem) -> np.ndarray:
    """The crank angles (N, n) at the targets of a population ``x`` (D, N): the timing, or the start angle plus
    the sense times the partition of a turn."""
    if p.timing is not None:
        return np.broadcast_to(p.timing, (x.shape[1], p.n))
    start, turn, w = x[6], np.where(x[7] >= 0, 1.0, -1.0), x[8:8 + p.n]
    cum = np.vstack([np.zeros(x.shape[1]), np.cumsum(w[:-1], axis=0)]) / w.sum(axis=0)
    return (start + turn * TWO_PI * cum).T


def project(x: np.ndarray, th: np.ndarray, p: Problem) -> np.ndarray:
    """The nine design numbers (9, N) of a population ``x`` (D, N) meeting the targets at ``th`` (N, n): (x0, y0,
    cx, cy) by least squares. With S = sum of e_k (a scaled rotation [[Sx, -Sy], [Sy, Sx]]), the normal equations
    [[n I, S], [S^T, n I]] (o, c) = (h1, h2) give c = (n h2 - S^T h1) / (n^2 - |S|^2) and o = (h1 - S c) / n;
    NaN where the coupler does not turn between the targets (|S| = n)."""
    t0, r1, r2, r3, r4, branch = (v[:, None] for v in x[:6])
    at = place(0.0, 0.0, t0, r1, r2, r3, r4, 1.0, 0.0, branch, th)     # the coupler point 1 along A -> B
    ex, ey = at.px - at.ax, at.py - at.ay
    rx, ry = p.targets[:, 0] - at.ax, p.targets[:, 1] - at.ay
    n = p.n
    sx, sy = ex.sum(axis=1), ey.sum(axis=1)
    h1x, h1y = rx.sum(axis=1), ry.sum(axis=1)
    h2x, h2y = (rx * ex + ry * ey).sum(axis=1), (ry * ex - rx * ey).sum(axis=1)
    den = n * n - (sx * sx + sy * sy)
    den = np.where(den > 1e-9 * n * n, den, np.nan)
    cx = (n * h2x - (sx * h1x + sy * h1y)) / den
    cy = (n * h2y - (sx * h1y - sy * h1x)) / den
    x0 = (h1x - (sx * cx - sy * cy)) / n
    y0 = (h1y - (sy * cx + sx * cy)) / n
    return np.vstack([x0, y0, x[0], x[1], x[2], x[3], x[4], cx, cy])


def hard_groups(base: np.ndarray, th: np.ndarray, p: Problem) -> dict[str, np.ndarray]:
    """The hard constraints as rows g >= 0 (m, N), dimensionless, for designs ``base`` (9, N) meeting the targets
    at crank angles ``th`` (N, n), by the task's field each keeps: reach (``task.link_range``; for a Grashof crank
    ``task.crank``), link ratio, and the transmission angle over the motion (the whole turn for a crank, else the
    crank's travel from the first target to the last, exact: :func:`~linkgen.synthesis.geometry.transmission_range`)."""
    r1, r2, r3, r4 = base[3:7]
    s = p.scale
    groups: dict[str, np.ndarray] = {}
    checked = th if p.crank else np.hstack([th, (th[:, :-1, None] + STEPS * np.diff(th, axis=1)[:, :, None])
                                            .reshape(len(r1), -1)])
    if not p.crank:                                 # a Grashof crank reaches every angle: nothing to check
        z2 = (r1**2 + r2**2)[:, None] - 2.0 * (r1 * r2)[:, None] * np.cos(checked)
        groups["task.link_range"] = np.vstack([(((r3 + r4) ** 2)[:, None] - z2).T / s**2,
                                               (z2 - ((r3 - r4) ** 2)[:, None]).T / s**2])
    else:
        total = r1 + r2 + r3 + r4
        groups["task.crank"] = np.vstack([np.array([(r - r2) / s for r in (r1, r3, r4)]),
                                          np.array([(total - 2 * r2 - 2 * r) / s - GRASHOF_MARGIN
                                                    for r in (r1, r3, r4)])])
    if p.link_ratio is not None:
        links = (r1, r2, r3, r4)
        groups["task.link_ratio"] = np.array([(p.link_ratio * links[i] - links[j]) / s for i in range(4)
                                              for j in range(4) if i != j])
    if p.cos_transmission is not None:
        start, end = (th[:, 0], th[:, 0] + TWO_PI) if p.crank else (th[:, 0], th[:, -1])
        cos_min, cos_max = transmission_range(r1, r2, r3, r4, start, end)
        groups["task.min_transmission"] = np.array([p.cos_transmission - cos_min, cos_max + p.cos_transmission])
    return groups


def hard_constraints(base: np.ndarray, th: np.ndarray, p: Problem) -> np.ndarray:
    """Every row of :func:`hard_groups` as one array (m, N)."""
    return np.vstack(list(hard_groups(base, th, p).values()))


def soft_groups(base: np.ndarray, p: Problem) -> dict[str, np.ndarray]:
    """The box of (x0, y0, cx, cy) and the ground region of O4 as rows g >= 0 (m, N), relative to the scale, by the
    task's field each keeps."""
    x0, y0, t0, r1 = base[:4]
    ox, oy = x0 + r1 * np.cos(t0), y0 + r1 * np.sin(t0)
    x_min, y_min, x_max, y_max = p.region
    region = [ox - x_min, x_max - ox, oy - y_min, y_max - oy]
    region += [b for k in (0, 1) for b in (base[k] - p.box[k][0], p.box[k][1] - base[k])]
    coupler = [b for k in (7, 8) for b in (base[k] - p.box[k][0], p.box[k][1] - base[k])]
    return {"task.ground_region": np.array(region) / p.scale, "task.coupler_range": np.array(coupler) / p.scale}


def soft_constraints(base: np.ndarray, p: Problem) -> np.ndarray:
    """Every row of :func:`soft_groups` as one array (m, N)."""
    return np.vstack(list(soft_groups(base, p).values()))


def squared_errors(base: np.ndarray, branch: np.ndarray, th: np.ndarray, p: Problem) -> np.ndarray:
    """Squared distances (N, n) of the coupler point from each target."""
    q = [v[:, None] for v in base] + [branch[:, None]]
    at = place_design(q, th)
    return (at.px - p.targets[:, 0]) ** 2 + (at.py - p.targets[:, 1]) ** 2


def objective(x: np.ndarray, p: Problem) -> np.ndarray:
    """The error (mm^2) of each design of a population ``x`` (D, N), with the penalty of any soft constraint, or
    BIG (1 + violation) where a hard one is broken: one vectorised evaluation of the whole population."""
    th = angles(x, p)
    base = project(x, th, p)
    err = squared_errors(base, x[5], th, p).sum(axis=1)
    hard = np.sum(np.maximum(0.0, -hard_constraints(base, th, p)), axis=0)
    soft = np.sum(np.maximum(0.0, -soft_constraints(base, p)), axis=0)
    out = err + SOFT * p.scale**2 * (soft + soft**2)
    return np.where((hard > 0) | ~np.isfinite(out), BIG * (1.0 + np.nan_to_num(hard, nan=1.0)), out)


def _central(f: Any, v: np.ndarray) -> np.ndarray:
    """The Jacobian (q, m) of ``f`` (designs (k, m) -> values (k, q)) at ``v`` by central differences, all the
    shifted designs in one vectorised call."""
    h = np.finfo(float).eps ** (1 / 3) * np.maximum(1.0, np.abs(v))
    shifts = np.diag(h)
    values = f(np.vstack([v + shifts, v - shifts]))
    return ((values[: len(v)] - values[len(v):]) / (2.0 * h)[:, None]).T


def _polish(x: np.ndarray, p: Problem) -> tuple[np.ndarray, float, np.ndarray, float]:
    """Design ``x`` (a DE vector) polished over all its numbers: least squares on the distances, and where that
    breaks a constraint SLSQP with the constraints as inequalities first (derivatives by central differences, the
    shifted designs evaluated together). Returns (base, branch, angles, error): the polished design if it keeps
    every constraint and is no worse, else ``x``'s own (error inf if that breaks one)."""
    from scipy.optimize import least_squares, minimize

    th0 = angles(x[:, None], p)
    base0 = project(x[:, None], th0, p)[:, 0]
    branch = 1.0 if x[5] >= 0 else -1.0
    turn = 1.0 if p.timing is not None or x[7] >= 0 else -1.0

    def split(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Designs (k, m) as their base (9, k) and crank angles (k, n)."""
        return v[:, :9].T, np.broadcast_to(th0[0], (len(v), p.n)) if p.timing is not None else v[:, 9:]

    def residuals(v: np.ndarray) -> np.ndarray:
        base, th = split(v)
        at = place_design([*(b[:, None] for b in base), branch], th)
        return np.hstack([at.px - p.targets[:, 0], at.py - p.targets[:, 1]])

    def squared(v: np.ndarray) -> np.ndarray:
        return np.sum(residuals(v) ** 2, axis=1, keepdims=True)

    def constraints(v: np.ndarray) -> np.ndarray:
        base, th = split(v)
        g = np.vstack([hard_constraints(base, th, p), soft_constraints(base, p)])
        if p.timing is not None:
            return g.T
        step = turn * np.diff(th, axis=1).T
        return np.vstack([g, step - 1e-4, TWO_PI - 1e-4 - step.sum(axis=0)]).T

    def err(v: np.ndarray) -> float:
        return float(squared(v[None])[0, 0])

    def cons(v: np.ndarray) -> np.ndarray:
        return constraints(v[None])[0]

    def better(v: np.ndarray) -> bool:
        return bool(np.all(np.isfinite(v)) and np.all(cons(v) >= 0) and err(v) <= found)

    start = base0 if p.timing is not None else np.concatenate([base0, th0[0]])
    bounds = list(p.box) + ([] if p.timing is not None else [(None, None)] * p.n)
    lo, hi = (np.array([b[k] if b[k] is not None else (-1) ** (k + 1) * np.inf for b in bounds]) for k in (0, 1))
    found = err(start) if np.all(np.isfinite(start)) and np.all(cons(start) >= 0) else math.inf

    def squares(v: np.ndarray) -> np.ndarray:
        """Least squares on the distances themselves (exact to rounding where no constraint is met on the way)."""
        return least_squares(lambda u: residuals(u[None])[0], np.clip(v, lo, hi),
                             jac=lambda u: _central(residuals, u), bounds=(lo, hi), xtol=1e-15, ftol=1e-15,
                             gtol=1e-15, max_nfev=50 * len(v)).x

    if np.all(np.isfinite(start)):
        try:
            v = squares(start)
            if not better(v):           # a constraint is in the way: SLSQP keeps them, least squares finishes
                v = minimize(err, np.clip(start, lo, hi), jac=lambda u: _central(squared, u)[0], method="SLSQP",
                             bounds=bounds, constraints=[{"type": "ineq", "fun": cons,
                                                          "jac": lambda u: _central(constraints, u)}],
                             options={"maxiter": 200, "ftol": 1e-18}).x
                if better(v):
                    start, found = v, err(v)
                v = squares(v)
            if better(v):
                start, found = v, err(v)
        except (ValueError, ArithmeticError):
            pass
    base, th = split(start[None])
    return base[:, 0], branch, th[0], found


def search(args: tuple[Problem, int], generation: Callable[[int], None] | None = None) -> dict[str, Any]:
    """One seeded search: differential evolution until it stalls or collapses (:mod:`linkgen.synthesis.stop`) or
    its budget runs out, then its best few distinct designs polished. Returns the polished designs that keep every
    constraint (base, branch, angles, error), the number of vectorised evaluations (each of the whole population),
    the generations run and why it stopped ("stall", "collapse" or "budget"). ``generation``, if given, is called
    with the count of generations run after each (it may raise to stop the search; it changes nothing of the
    search's numbers)."""
    from scipy.optimize import differential_evolution

    p, seed = args
    rule = rule_for(p.scale)
    best: list[float] = []
    stopped: list[str] = []

    def hook(intermediate_result: Any) -> bool:      # scipy passes the result so far to a parameter of this name
        if generation is not None:
            generation(int(intermediate_result.nit))
        energies = np.asarray(intermediate_result.population_energies)
        best.append(float(np.min(energies)))
        why = why_stop(best, energies, rule)
        if why is not None:
            stopped.append(why)
        return why is not None

    r = differential_evolution(objective, p.bounds, args=(p,), vectorized=True, updating="deferred", seed=seed,
                               maxiter=p.generations, popsize=p.population, tol=0, atol=0, polish=False,
                               callback=hook)
    lo, hi = np.array(p.bounds).T
    unit = (r.population - lo) / (hi - lo)
    picked: list[int] = []
    for i in np.argsort(r.population_energies, kind="stable"):
        if r.population_energies[i] >= BIG:
            break
        # in the unit box of the bounds, two designs within 1e-3 of each other are copies
        if all(np.max(np.abs(unit[i][:6] - unit[j][:6])) > 1e-3 for j in picked):
            picked.append(int(i))
        if len(picked) == POLISHED:
            break
    found = [_polish(r.population[i], p) for i in picked]
    order = np.argsort(r.population_energies, kind="stable")
    # where no design keeps every hard constraint: the few that break them least, the nearest a task can offer
    closest = [r.population[i].tolist() for i in order[:NEAREST_KEPT]] if r.population_energies[order[0]] >= BIG \
        else []
    nearest = r.population[int(order[0])][:, None]
    at = angles(nearest, p)
    return {"found": [(b.tolist(), br, th.tolist(), e) for b, br, th, e in found if math.isfinite(e)],
            "evaluations": int(r.nfev), "generations": int(r.nit), "population": len(r.population),
            "stopped": stopped[0] if stopped else "budget", "closest": closest,
            # the best design of the final population, for a refusal: its energy and its shortfalls by field
            "nearest": (float(np.min(r.population_energies)), shortfalls(project(nearest, at, p)[:, 0], at[0], p))}


def shortfalls(base: np.ndarray, th: np.ndarray, p: Problem) -> dict[str, float]:
    """How far one design (``base`` (9,), crank angles ``th`` (n,)) falls short of each field's constraints: the
    most negative of its rows, as a positive number (0 where every row is kept; inf where the design is not a
    linkage at all)."""
    b, t = np.asarray(base, dtype=float)[:, None], np.asarray(th, dtype=float)[None, :]
    if not np.all(np.isfinite(b)):
        return {"task.points": math.inf}
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        groups = {**hard_groups(b, t, p), **soft_groups(b, p)}
    return {k: float(max(0.0, -np.min(np.nan_to_num(v, nan=-math.inf)))) for k, v in groups.items()}


def held_by(c: Candidate, base: list[float], th: list[float], p: Problem, task: Any) -> list[str]:
    """The requirements that hold candidate ``c`` (a design ``base`` at crank angles ``th``) back: its transmission
    angle at the least allowed, a length at an end of ``link_range``, its coupler point at the edge of
    ``coupler_range``, a ground pivot on the edge of ``ground_region``, its link ratio at ``link_ratio``."""
    near = 1e-6
    out = []
    if p.cos_transmission is not None and c.row["transmission_worst_deg"] - task.min_transmission < 1e-3:
        out.append(f"task.min_transmission (its transmission angle falls to the {task.min_transmission:g} degrees "
                   "allowed)")
    lo, hi = p.box[3]
    at_ends = [f"{name} {value:.6g} mm" for name, value in zip(("ground", "crank", "coupler", "rocker"), base[3:7],
                                                                strict=True)
               if min(abs(value - lo), abs(value - hi)) <= near * hi]
    if at_ends:
        default = "" if task.link_range is not None else "; by default 1/20 to 4 times the targets' spread"
        out.append(f"task.link_range ({', '.join(at_ends)}{default})")
    b, t = np.array(base)[:, None], np.array(th)[None, :]
    groups = {**hard_groups(b, t, p), **soft_groups(b, p)}
    for key, what in (("task.coupler_range", "its coupler point at the edge of the range, by default the longest "
                                             "link"),
                      ("task.ground_region", "a ground pivot on its edge, by default the targets' box grown by the "
                                             "longest link"),
                      ("task.link_ratio", "its links at the ratio")):
        if key in groups and float(np.min(groups[key])) <= near:
            out.append(f"{key} ({what})")
    return out


def _candidate(base: list[float], branch: float, th: list[float], p: Problem, crank: bool) -> Candidate | None:
    """A polished design as a candidate (None if it has a defect): its row, signature and figure."""
    d = dict(zip(BASE, base, strict=True)) | {"branch": branch}
    lengths = (d["r1"], d["r2"], d["r3"], d["r4"])
    if defects(lengths, th, [branch] * p.n, crank):
        return None
    sq = squared_errors(np.array(base)[:, None], np.array([branch]), np.array([th]), p)[0]
    end = th[0] + TWO_PI if crank else th[-1]
    worst = math.degrees(float(worst_transmission(*lengths, th[0], end)))
    row = {"error_mm2": float(sq.sum()), **fourbar_row(d, th), "errors_mm": np.sqrt(sq).tolist(),
           "inversion": classify(*lengths).inversion, "transmission_worst_deg": worst, "defects": []}
    table = drawn_table(d, th[0])
    if not table_fits(table):
        return None
    sweep = np.linspace(0.0, TWO_PI, 721)
    sketch = coupler_sketch(d, th, p.targets, sweep)
    signature = (d["x0"], d["y0"], *lengths, d["cx"], d["cy"], d["theta0"] * p.scale)
    return Candidate(table, row, float(sq.sum()), signature, sketch)


#: what :func:`solve` reports as it goes: the fraction done (0 to 1), the stage in words and the candidates found so
#: far (weighed, unranked); it may raise to stop the search
Report = Callable[[float, str, list[Candidate]], None]


def _runs(p: Problem, seeds: list[int], jobs: int, scheduler: str | None, report: Report | None,
          found: Callable[[dict[str, Any]], list[Candidate]]) -> tuple[list[dict[str, Any]], bool]:
    """The seeded searches' runs until two starts agree (:func:`linkgen.synthesis.stop.run_starts`), and whether they
    did: ``jobs`` at a time on local processes, or all on the cluster (``report`` called once, at the end), or, with
    a ``report`` and ``jobs`` 1, one after another here with ``report`` called after each generation and each
    search (``found`` gives a run's candidates). Wherever they run, the same runs are kept."""
    atol = rule_for(p.scale).atol
    if report is None or jobs > 1 or scheduler is not None:
        done, agree = run_starts(lambda batch: run_all(search, [(p, s) for s in batch], jobs, scheduler), seeds,
                                 len(seeds) if scheduler is not None else jobs, atol, p.wanted)
        if report is not None:
            report(1.0, f"{len(done)} searches done", [c for r in done for c in found(r)])
        return done, agree
    so_far: list[Candidate] = []
    ran: list[dict[str, Any]] = []
    total = len(seeds) * p.generations

    def one(batch: list[int]) -> list[dict[str, Any]]:
        nonlocal so_far
        k, seed = len(ran), batch[0]

        def generation(nit: int) -> None:
            report(min(k * p.generations + nit, total) / total,
                   f"search {k + 1} of {len(seeds)}, generation {nit} of {p.generations}", so_far)

        run = search((p, seed), generation)
        so_far = so_far + found(run)
        report((k + 1) / len(seeds), f"search {k + 1} of {len(seeds)} polished", so_far)
        ran.append(run)
        return [run]

    return run_starts(one, seeds, 1, atol, p.wanted)


def solve(task: Any, jobs: int = 1, scheduler: str | None = None,
          report: Report | None = None) -> tuple[list[Candidate], dict[str, Any]]:
    """Path generation for a validated path task: the candidates (unranked) and how the search went; ``report``
    (see :data:`Report`) follows it, each generation where it runs here (``jobs`` 1), without changing it."""
    p = problem_of(task)
    seeds = [int(s.generate_state(1)[0]) for s in np.random.SeedSequence(task.seed).spawn(task.starts)]

    def found(run: dict[str, Any]) -> list[Candidate]:
        made = (_candidate(base, branch, th, p, task.crank) for base, branch, th, _ in run["found"])
        return [weighed(c) for c in made if c is not None]

    clock = time.perf_counter()
    runs, agree = _runs(p, seeds, jobs, scheduler, report, found)
    seconds = time.perf_counter() - clock
    out, designs, polished = [], [], 0
    for run in runs:
        for base, branch, th, _ in run["found"]:
            polished += 1
            c = _candidate(base, branch, th, p, task.crank)
            if c is not None:
                out.append(c)
                designs.append((base, th))
    tried = sum(r["evaluations"] * r["population"] for r in runs)
    bound: list[str] = []
    if not out and not polished:
        from linkgen.synthesis.path_nearest import nearest_candidates   # it builds on this module's functions

        out, bound = nearest_candidates(task, runs, p, tried)
    if not out:
        _refuse(task, runs, polished, tried)
    if not bound:
        out = [weighed(c) for c in out]
        best = int(np.argmin([c.score for c in out]))
        held = held_by(out[best], *designs[best], p, task)
        bound = [f"the best candidate is held by {'; '.join(held)}"] if held else []
    info = {"method": "differential evolution (scipy, the whole population per call) over the ground line, lengths, "
                      "branch and crank angles, the pivot and coupler point by least squares; polished by least "
                      "squares (SLSQP where a constraint is in the way)",
            "seed": task.seed, "starts": task.starts, "generations": task.generations, "starts_run": len(runs),
            "starts_agreed": agree, "generations_run": [r["generations"] for r in runs],
            "stopped": [r["stopped"] for r in runs],
            "population": runs[0]["population"], "vectorised_calls": sum(r["evaluations"] for r in runs),
            "designs_evaluated": sum(r["evaluations"] * r["population"] for r in runs),
            "seconds": round(seconds, 3), "ran_on": where(jobs, scheduler),
            "bound": bound}
    return out, info


#: what each field's constraint asks, and what to change, for a refusal
_ASKED = {
    "task.min_transmission": ("keeps its transmission angle at least {mu:g} degrees over its motion",
                              "lower min_transmission, widen link_range, or give more generations"),
    "task.crank": ("is a Grashof four-bar whose crank turns fully", "set crank = false, widen link_range, or give "
                   "more generations"),
    "task.link_range": ("reaches every target with its links within link_range", "widen link_range, or give more "
                        "generations"),
    "task.link_ratio": ("keeps its links within link_ratio", "raise link_ratio, or give more generations"),
    "task.ground_region": ("has both ground pivots within ground_region (by default the targets' box grown by the "
                           "longest link)", "widen ground_region or link_range, or give more generations"),
    "task.coupler_range": ("has its coupler point within coupler_range of the crank pin", "raise coupler_range, or "
                           "give more generations"),
    "task.points": ("is a linkage through these targets", "give other targets, or more generations")}


def _refuse(task: Any, runs: list[dict[str, Any]], polished: int, tried: int) -> None:
    """The one-line refusal of a path task that found nothing to offer, naming the requirement that bound: the one
    the best design of the searches falls shortest of; or, where designs were polished but each had a defect or
    did not fit a template, the targets."""
    if polished:
        raise SpecError(f"each of the {polished} linkages found has a branch, order or Grashof defect, or a pivot or "
                        f"pin beyond {MAX_LENGTH_MM:g} mm of the origin: give other targets, a ground_region, or more "
                        "generations", "task.input_angles" if task.input_angles is not None else "task.points")
    _, short = min((r["nearest"] for r in runs), key=lambda n: n[0])
    field = max(short, key=lambda k: short[k]) if any(short.values()) else "task.points"
    asked, hint = _ASKED[field]
    also = [k for k in sorted(short) if short[k] > 0 and k != field]
    more = f"; the nearest also breaks {', '.join(also)}" if also else ""
    raise SpecError(f"no linkage found that {asked.format(mu=task.min_transmission)} ({tried} designs tried{more}): "
                    f"{hint}", field)
