"""Stephenson II path generation, timed: a ternary crank and a triad whose plate carries the tracer to N targets.

``task.linkage = "stephenson2"`` of a path task with ``input_angles``. The linkage is
:data:`linkgen.synthesis.sixbar_types.STEPHENSON2`: the ternary crank (O2, A, E), the plate (C, D, F) held by the
rods A-C, E-D and the rocker O4-F (a triad, the class-III Assur group), the tracer P on the plate. A design is its
drawing normalised so that O2 = (0, 0) and O4 = (1, 0): A, E, C, D, F, ten numbers. A whole population is solved
at once by :mod:`linkgen.synthesis.sixbar_triad` (the triad's closure as one equation in the plate's turn, the
drawn assembly followed by continuity over the crank's turn) at the targets' crank angles and TURN angles evenly
over a turn; a design whose triad jumps, loses its root at a toggle or comes back on another assembly after the
turn is refused. As for the other six-bars (:mod:`linkgen.synthesis.sixbar`), the tracer's place on the plate and
the similarity (scale, turn, shift) onto the targets come by least squares in closed form (W_k = R_k u + z F_k + t,
R_k the plate's turn and F_k its pin F at target k, complex), the search runs by scipy's differential evolution
over the ten drawing numbers, and its best few designs are polished by least squares on the distances.

Hard constraints (a design breaking one ranks behind every one that keeps them): the triad clean over the turn;
its transmission angle (:func:`linkgen.synthesis.sixbar_triad.transmission`: the least of its three binaries')
at least ``min_transmission`` at the sampled angles; every link and the ground within ``link_range``; and the
crank's pins apart by more than the shorter rod and SWEEP_MM, so that the shorter rod, turning with the crank's
pin, never sweeps over the other pin and the parts stack (``linkgen build`` finds a layer order: the crank on the
ground plate, the shorter rod next, the longer above). A candidate is then placed by the general solver as
``linkgen analyze`` reads it (:class:`linkgen.kinematics.linkage.Linkage`: Newton continuation of the triad): the
crank turns fully, no branch is passed, and its tracer at the targets gives the row's error.

The triad's transmission angle in the rows is this module's; ``linkgen analyze`` reports another figure for a
class-III group (its Jacobian's conditioning, about 0.08 where this angle is 63 degrees). The four-bar's best on
the same targets (the same seed and budget) is reported next to it, as for the other six-bars.
Units: mm and degrees (radians inside); angles counter-clockwise.
"""
from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from camgen.core.errors import CamgenError, SpecError
from camgen.core.spec import MAX_LENGTH_MM, MIN_LENGTH_MM
from linkgen.kinematics.linkage import Linkage
from linkgen.synthesis.candidates import Candidate, Sketch, table_fits, weighed
from linkgen.synthesis.parallel import run_all, where
from linkgen.synthesis.sixbar import BIG, FINE_TURN, POLISHED, SHAPE_BOX, Problem, four_bar_best, link_lengths
from linkgen.synthesis.sixbar_triad import Triad, solve as solve_triad, transmission
from linkgen.synthesis.sixbar_types import STEPHENSON2

TWO_PI = 2.0 * math.pi
#: the crank angles (evenly over a turn) at which a design's triad is followed and checked during the search
TURN = 72
#: the least gap (mm) between the crank's other pin and the shorter rod's reach, for the parts to stack
SWEEP_MM = 10.0
#: the ``[linkage]`` table of a candidate, but for its joints
TABLE = {"type": "linkage", "ground": list(STEPHENSON2.ground), "input": {"link": "crank", "pivot": "O2"},
         "tracers": ["P"], "links": {k: list(v) for k, v in STEPHENSON2.links.items()}}
#: each link's pairs of joints (the ground's too), for the link_range constraint: P left out
PAIRS = (("O2", "O4"), ("O2", "A"), ("O2", "E"), ("A", "E"), ("A", "C"), ("E", "D"), ("C", "D"), ("C", "F"),
         ("D", "F"), ("O4", "F"))


def problem_of(task: Any) -> Problem:
    """The numbers of a validated Stephenson II path task (timed); the lengths' limits those of the four-bar's search
    on the same targets (:func:`linkgen.synthesis.path.problem_of`)."""
    from linkgen.synthesis import path

    four = path.problem_of(task)
    targets = four.targets[:, 0] + 1j * four.targets[:, 1]
    return Problem(STEPHENSON2, targets, np.radians(task.input_angles), four.box[3],
                   math.radians(task.min_transmission), task.generations, task.population, four.scale)


def triads(x: np.ndarray) -> Triad:
    """The triads of designs x (10, N): A, E, C, D, F of the normalised drawing, O4 at 1."""
    z = x[0::2] + 1j * x[1::2]
    return Triad(z[0], z[1], z[2], z[3], z[4], np.ones(x.shape[1], complex))


def evaluate(x: np.ndarray, p: Problem) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Designs x (10, N) at the targets and over the turn: the residuals (N, n) complex mm (NaN where the triad is
    not clean), (u, z, t) (N, 3) complex, and each design's violation of the hard constraints (N,) (0 where kept,
    dimensionless)."""
    t = triads(x)
    first = np.angle(t.a)
    n = len(p.targets)
    turn = np.linspace(0.0, TWO_PI, TURN, endpoint=False)
    assert p.timing is not None
    turns = np.concatenate([p.timing[None, :] - first[:, None], np.broadcast_to(turn, (len(first), TURN))], axis=1)
    with np.errstate(all="ignore"):
        sol = solve_triad(t, turns)
        rot, ref = np.exp(1j * sol.psi[:, :n]), sol.f[:, :n]
        a = np.stack([rot, ref, np.ones_like(rot)], axis=2)                           # (N, n, 3)
        ah = np.conj(np.swapaxes(a, 1, 2))
        uzt = np.linalg.solve(ah @ a + 1e-14 * np.eye(3), ah @ p.targets[None, :, None])[:, :, 0]
        residuals = (a @ uzt[:, :, None])[:, :, 0] - p.targets[None, :]
        scale = np.abs(uzt[:, 1])
        lengths = np.stack([np.abs(_point(t, i) - _point(t, j)) for i, j in PAIRS], axis=1) * scale[:, None]
        lo, hi = p.lengths
        rows = [np.maximum(0.0, lo - lengths) / p.scale, np.maximum(0.0, lengths - hi) / p.scale]
        if p.min_transmission > 0:
            rows.append(np.maximum(0.0, p.min_transmission - sol.transmission))
        l1, l2, _ = t.lengths
        rows.append(np.maximum(0.0, SWEEP_MM / p.scale - (np.abs(t.a - t.e) - np.minimum(l1, l2)) * scale / p.scale))
        violation = sum(np.sum(np.where(np.isfinite(r), r, 1.0).reshape(len(first), -1), axis=1) for r in rows)
    violation = np.where(sol.clean, violation, 1.0 + violation)
    residuals = np.where(sol.clean[:, None], residuals, np.nan)
    return residuals, uzt, violation


def _point(t: Triad, name: str) -> np.ndarray:
    """A joint of the normalised drawings (N,) complex."""
    return {"O2": np.zeros_like(t.a), "O4": t.o4, "A": t.a, "E": t.e, "C": t.c, "D": t.d, "F": t.f}[name]


def objective(x: np.ndarray, p: Problem) -> np.ndarray:
    """The error (mm^2) of each design of a population x (10, N), or BIG (1 + violation) where it breaks a hard
    constraint: the whole population solved at once."""
    residuals, _, violation = evaluate(x, p)
    err = np.sum(np.abs(residuals) ** 2, axis=1)
    bad = (violation > 0) | ~np.isfinite(err)
    return np.where(bad, BIG * (1.0 + violation), err)


def _polish(x: np.ndarray, p: Problem) -> tuple[np.ndarray, float]:
    """Design x polished by least squares on the distances (the Jacobian by forward differences, its eleven designs
    solved at once); the polished design if it keeps every hard constraint and is no worse, else x."""
    from scipy.optimize import least_squares

    step = 1e-7

    def residuals(v: np.ndarray) -> np.ndarray:
        r, _, _ = evaluate(v[:, None], p)
        r = np.where(np.isfinite(r), r, p.scale)[0]
        return np.concatenate([r.real, r.imag])

    def jacobian(v: np.ndarray) -> np.ndarray:
        designs = v[:, None] + np.hstack([np.zeros((len(v), 1)), step * np.eye(len(v))])
        r, _, _ = evaluate(designs, p)
        r = np.where(np.isfinite(r), r, p.scale)
        rows = np.concatenate([r.real, r.imag], axis=1)
        return ((rows[1:] - rows[0]) / step).T

    found = float(objective(x[:, None], p)[0])
    try:
        v = least_squares(residuals, x, jac=jacobian, method="trf", bounds=(-SHAPE_BOX, SHAPE_BOX), xtol=1e-12,
                          ftol=1e-12, gtol=1e-12, max_nfev=30 * len(x)).x
    except (ValueError, ArithmeticError):
        return x, found
    polished = float(objective(v[:, None], p)[0])
    return (v, polished) if polished <= found else (x, found)


def search(args: tuple[Problem, int]) -> dict[str, Any]:
    """One seeded search: differential evolution over the drawing from scipy's Latin hypercube, then its best few
    distinct designs polished. Returns those that keep every constraint (design, error) and the designs
    evaluated."""
    from scipy.optimize import differential_evolution

    p, seed = args
    bounds = [(-SHAPE_BOX, SHAPE_BOX)] * 10
    designs = [0]

    def counted(x: np.ndarray) -> np.ndarray:
        designs[0] += x.shape[1]
        return objective(x, p)

    r = differential_evolution(counted, bounds, vectorized=True, updating="deferred", seed=seed,
                               maxiter=p.generations, popsize=p.population, tol=1e-12, polish=False)
    # the best distinct designs that keep every constraint, best first
    order = [int(i) for i in np.argsort(r.population_energies) if r.population_energies[i] < BIG]
    picked: list[int] = []
    for i in order:
        gaps = [np.max(np.abs(r.population[i] - r.population[j])) for j in picked]
        picked += [i] if min(gaps, default=np.inf) > 1e-3 * SHAPE_BOX and len(picked) < POLISHED else []
    found = [_polish(r.population[i], p) for i in picked]
    return {"found": [(v.tolist(), e) for v, e in found if e < BIG], "evaluations": designs[0],
            "best_energy": float(np.min(r.population_energies))}


def placed(x: np.ndarray, p: Problem) -> tuple[dict[str, tuple[float, float]], np.ndarray] | None:
    """The drawing of design x in the task's frame at the first target's crank angle, with the tracer P, and its
    (u, z, t); None where its triad is not clean."""
    residuals, uzt, _ = evaluate(x[:, None], p)
    if not np.all(np.isfinite(residuals)):
        return None
    t = triads(x[:, None])
    assert p.timing is not None
    turn = p.timing[:1] - np.angle(t.a)
    sol = solve_triad(t, turn[:, None])
    u, z, shift = uzt[0]
    spin = np.exp(1j * turn[0])
    at = {"O2": 0j, "O4": 1 + 0j, "A": complex(t.a[0] * spin), "E": complex(t.e[0] * spin), "C": complex(sol.c[0, 0]),
          "D": complex(sol.d[0, 0]), "F": complex(sol.f[0, 0])}
    at = {k: z * v + shift for k, v in at.items()}
    at["P"] = complex(np.exp(1j * sol.psi[0, 0]) * u + z * sol.f[0, 0] + shift)
    return {k: (float(v.real), float(v.imag)) for k, v in at.items()}, uzt[0]


def _candidate(x: np.ndarray, p: Problem) -> Candidate | None:
    """A polished design as a candidate, placed by the general solver (None if the general solver finds the crank
    does not turn fully or a branch passed, its triad's transmission breaks the limit over FINE_TURN angles, or it
    does not fit a template): the ``[linkage]`` table drawn at the first target, its row, its figure."""
    from linkgen.synthesis.sixbar import structure_of

    got = placed(x, p)
    if got is None:
        return None
    joints, uzt = got
    try:
        linkage = Linkage.of(structure_of(joints, p.topology))
        if linkage.ranges is not None or any(len(f) for f in linkage.flips):
            return None
        first = math.atan2(joints["A"][1] - joints["O2"][1], joints["A"][0] - joints["O2"][0])
        turn = first + np.linspace(0.0, TWO_PI, FINE_TURN + 1)
        assert p.timing is not None
        directions = p.timing + float(np.angle(uzt[1]))
        sol = linkage.solve(np.concatenate([turn, directions])[None, :], strict=False, derivatives=False)
    except (CamgenError, ValueError, ArithmeticError):
        return None
    if not sol.ok.all():
        return None
    pin = {k: v[:, 0] + 1j * v[:, 1] for k, v in sol.points.items()}
    mu = transmission(pin["A"], pin["E"], pin["O4"], pin["C"], pin["D"], pin["F"])
    worst = float(np.min(mu))
    if worst < p.min_transmission - 1e-9:
        return None
    table = {**TABLE, "joints": {k: list(v) for k, v in joints.items()}}
    if not table_fits(table):
        return None
    targets = np.column_stack([p.targets.real, p.targets.imag])
    k = len(turn)
    reached = sol.points["P"][k:]
    sq = np.sum((reached - targets) ** 2, axis=1)
    lengths = link_lengths(joints, STEPHENSON2)
    if not all(MIN_LENGTH_MM <= v <= MAX_LENGTH_MM for v in lengths.values()):
        return None
    row = {"error_mm2": float(sq.sum()), "linkage": STEPHENSON2.name, "timed": True, "joints": table["joints"],
           "link_lengths": lengths, "input_angles": [round(math.degrees(t) % 360.0, 9) % 360.0 for t in p.timing],
           "input_directions": (np.degrees(directions) % 360.0).tolist(), "errors_mm": np.sqrt(sq).tolist(),
           "transmission_worst_deg": math.degrees(worst), "defects": []}
    pose = np.array([joints[j] for j in ("O2", "A", "C", "F", "O4", "F", "D", "E", "O2")])
    sketch = Sketch(paths=(("tracer curve", sol.points["P"][:k]),), poses=(("at the first target", pose),),
                    targets=targets, reached=reached)
    signature = tuple(v for xy in joints.values() for v in xy)
    return Candidate(table, row, float(sq.sum()), signature, sketch)


def solve(task: Any, jobs: int = 1, scheduler: str | None = None) -> tuple[list[Candidate], dict[str, Any]]:
    """Stephenson II path generation for a validated timed path task: the candidates (unranked) and how the search
    went, the four-bar's best next to it."""
    p = problem_of(task)
    spawned = np.random.SeedSequence(task.seed).spawn(task.starts)
    four, _ = four_bar_best(task, jobs, scheduler)
    clock = time.perf_counter()
    runs = run_all(search, [(p, int(seq.generate_state(1)[0])) for seq in spawned], jobs, scheduler)
    seconds = time.perf_counter() - clock
    made = [_candidate(np.asarray(x), p) for run in runs for x, _ in run["found"]]
    out = [weighed(c) for c in made if c is not None]
    tried = sum(r["evaluations"] for r in runs)
    if not out:
        raise SpecError("no stephenson2 six-bar found whose crank turns fully with its triad on its assembly, its "
                        f"transmission angle at least {task.min_transmission:g} degrees, its links within "
                        f"link_range and its parts stacking ({tried} designs tried): give more generations, widen "
                        "link_range or lower min_transmission", "task.points")
    out = [Candidate(c.linkage, {**c.row, "four_bar_error_mm2": four["error_mm2"]}, c.score, c.signature, c.sketch)
           for c in out]
    info = {"method": "stephenson2 six-bar: differential evolution (scipy) over the normalised drawing, each "
                      "population's triads solved at once (one equation in the plate's turn, the drawn assembly "
                      "followed over the turn), the tracer and the similarity by least squares; polished by least "
                      "squares; each candidate placed by the general solver",
            "seed": task.seed, "starts": task.starts, "generations": task.generations,
            "designs_evaluated": tried, "seconds": round(seconds, 3), "ran_on": where(jobs, scheduler),
            "four_bar": four, "seeded_from_four_bar": False, "bound": []}
    return out, info
