"""Untimed path synthesis by elliptic Fourier descriptors: atlas first guesses, then the true point-to-curve error.

``task.method = "fourier"`` of a path task without timing:

1. The targets, read as a closed polygon (``closed = true``) or an open one retraced there and
   back, are normalised by their elliptic Fourier descriptors (:mod:`linkgen.synthesis.fourier`):
   position, size, orientation and starting point removed, traversed counter-clockwise. So is
   their mirror image (y -> -y).
2. Both, in both normalised forms, are compared with every entry of the atlas
   (:mod:`linkgen.synthesis.atlas`: whole coupler curves for a closed target, arcs of them for an
   open one) by the distance of their first harmonics (as many as the targets resolve, at most
   the atlas's). The nearest entries, each put onto the targets by the similarity that the two
   normalisations give in closed form (scale E_t / E_a, turn psi_t - psi_a, the mean points
   matched; reflected back for a mirrored match), are the first guesses.
3. The ``guesses`` best of them by the true error are polished by least squares on the true
   point-to-curve distances: the unknowns are the nine design numbers and one crank angle a
   target, the residuals the gaps from each target to the coupler point at its angle; each round
   starts from every target's nearest point found afresh over the motion (the crank's turn; a
   grid of crank angles refined by golden section), so at the end the gaps are the distances to
   the curve. Where the result breaks a requirement (a Grashof crank, the transmission angle,
   the link ratio, the ground region, the coupler range: as for the differential evolution,
   :mod:`linkgen.synthesis.path`), the requirements join the residuals as penalties whose weight
   rises until the result keeps them all (with a margin of MARGIN of the lengths' scale).

The error (mm^2) is the sum of squared distances from the targets to the nearest point of the
curve the coupler point makes: for a crank the whole turn; for ``crank = false`` the crank's travel
from the first target's nearest point to the last's. Untimed, the targets may be met out of the
order listed (``in_order`` in the row says). Past SUBSAMPLE targets, the guesses are polished on
SUBSAMPLE of them and only the FINISHED best on all, so a long curve costs little more than a short one.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics.grashof import classify
from linkgen.synthesis import atlas as atlases
from linkgen.synthesis import fourier
from linkgen.synthesis.candidates import Candidate, coupler_sketch, drawn_table, fourbar_row, table_fits, weighed
from linkgen.synthesis.defects import sense
from linkgen.synthesis.geometry import place, worst_transmission
from linkgen.synthesis.path import BASE, Problem, hard_constraints, problem_of, soft_constraints

TWO_PI = 2.0 * math.pi
#: crank angles of the grid the nearest point is first looked for on, while polishing and for the final error
GRID, FINE_GRID = 720, 8192
#: golden-section steps refining each nearest point within one grid step either side (0.618^60: 3e-13 of a step)
GOLDEN = 60
#: atlas entries put onto the targets (per match of the four: target or mirrored, either form)
NEAREST = 24
#: the golden section's ratio, 1 / phi
GOLDEN_RATIO = (math.sqrt(5.0) - 1.0) / 2.0
#: a polish: at most ROUNDS fresh assignments of nearest points, each at most LSQ_STEPS least-squares evaluations
#: a weight (PENALTIES: the requirements' weights, 0 first) and the margin kept inside every requirement
ROUNDS, LSQ_STEPS, MARGIN = 6, 200, 1e-7
#: more targets than SUBSAMPLE: every guess is polished on SUBSAMPLE of them, the FINISHED best then on all
SUBSAMPLE, FINISHED = 24, 3
PENALTIES = (0.0, 1.0, 10.0, 100.0, 1e3, 1e4, 1e5, 1e6)


def _at(v: np.ndarray, branch: float, theta2: np.ndarray) -> np.ndarray:
    """Coupler points (..., 2) of designs ``v`` (9, ...) broadcast against crank angles ``theta2``."""
    x0, y0, theta0, r1, r2, r3, r4, cx, cy = v
    at = place(x0, y0, theta0, r1, r2, r3, r4, cx, cy, branch, theta2)
    return np.stack([at.px, at.py], axis=-1)


def _placed(v: np.ndarray, branch: Any, theta2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Coupler points (..., 2) of designs ``v`` (9, ...) on ``branch`` (a number or an array broadcast with them)
    at crank angles ``theta2``, and whether each pose is out of reach (...): one placing for both."""
    x0, y0, theta0, r1, r2, r3, r4, cx, cy = v
    at = place(x0, y0, theta0, r1, r2, r3, r4, cx, cy, branch, theta2)
    return np.stack([at.px, at.py], axis=-1), at.out_of_reach > 0


def nearest(v: np.ndarray, branch: float, targets: np.ndarray, grid: int = GRID,
            span: tuple[float, float] = (0.0, TWO_PI)) -> tuple[np.ndarray, np.ndarray]:
    """The crank angles (n,) of the nearest coupler points of design ``v`` (9,) to each target (n, 2), over the
    crank's ``span`` (rad from the ground line), and those points (n, 2): :func:`nearest_many` of one design."""
    th, pts = nearest_many(np.asarray(v, dtype=float)[None], np.array([branch], dtype=float), targets, grid, span)
    return th[0], pts[0]


def nearest_many(vs: np.ndarray, branches: np.ndarray, targets: np.ndarray, grid: int = GRID,
                 span: tuple[float, float] = (0.0, TWO_PI)) -> tuple[np.ndarray, np.ndarray]:
    """For each design of ``vs`` (k, 9) on its branch of ``branches`` (k,), the crank angles (k, n) of its nearest
    coupler points to each target (n, 2) over the crank's ``span`` (rad from the ground line), and those points
    (k, n, 2). A grid of ``grid`` angles, then golden section within a step either side; poses out of reach count
    as far away. Every design is worked by the same operations on its own numbers, all of them at once: a design's
    row is what it gets alone."""
    lo, hi = span
    t = np.linspace(lo, hi, grid, endpoint=hi - lo < TWO_PI - 1e-12)
    col = vs.T[:, :, None]                                                   # (9, k, 1)
    branch = branches[:, None]
    pts, far = _placed(col, branch, t[None, :])                              # (k, grid, 2), (k, grid)
    d2 = np.sum((targets[None, :, None, :] - pts[:, None, :, :]) ** 2, axis=-1) + np.where(far, np.inf, 0.0)[:, None]
    j = np.argmin(d2, axis=2)                                                # (k, n)
    h = (hi - lo) / grid
    a, b = t[j] - h, t[j] + h
    if hi - lo < TWO_PI - 1e-12:
        a, b = np.maximum(a, lo), np.minimum(b, hi)

    def f(x: np.ndarray) -> np.ndarray:
        p, out = _placed(col, branch, x)
        return np.sum((p - targets) ** 2, axis=2) + np.where(out, np.inf, 0.0)

    g = GOLDEN_RATIO
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(GOLDEN):
        left = fc <= fd                                  # the least lies in [a, d]
        a, b = np.where(left, a, c), np.where(left, d, b)
        c, d = np.where(left, b - g * (b - a), d), np.where(left, c, a + g * (b - a))
        fx = f(np.where(left, c, d))
        fc, fd = np.where(left, fx, fd), np.where(left, fc, fx)
    best = np.where(fc <= fd, c, d)
    better = np.minimum(fc, fd) <= np.take_along_axis(d2, j[:, :, None], axis=2)[:, :, 0]
    out = np.where(better, best, t[j])
    return out, _placed(col, branch, out)[0]


def errors(v: np.ndarray, branch: float, targets: np.ndarray, crank: bool, grid: int = FINE_GRID
           ) -> tuple[np.ndarray, np.ndarray]:
    """The squared distances (n,) from the targets to the curve design ``v`` makes (see the module) and the crank
    angles there (n,)."""
    th, pts = nearest(v, branch, targets, grid)
    if not crank:                          # only the crank's travel from the first target to the last is made
        turn = sense(th) or 1
        travel = np.mod(turn * (th - th[0]), TWO_PI)
        start, end = (th[0], th[0] + travel.max()) if turn > 0 else (th[0] - travel.max(), th[0])
        th, pts = nearest(v, branch, targets, grid, (start, end))
    return np.sum((pts - targets) ** 2, axis=1), th


def _points(u: np.ndarray, branch: float, n: int) -> np.ndarray:
    """Coupler points (k, n, 2) of unknowns ``u`` (k, 9 + n): a design and a crank angle for each target."""
    return _at(u[:, :9].T[:, :, None], branch, u[:, 9:])


def _gaps(u: np.ndarray, branch: float, targets: np.ndarray) -> np.ndarray:
    """The residuals (2 n,) of unknowns ``u`` (9 + n,): x then y of each coupler point less its target (mm)."""
    return (_points(u[None], branch, len(targets))[0] - targets).T.reshape(-1)


def _gap_jacobian(u: np.ndarray, branch: float, n: int) -> np.ndarray:
    """d(residuals)/d(unknowns) (2 n, 9 + n) by central differences, every shifted design and angle in one
    vectorised call (a target's point moves only with its own angle: those columns are diagonal)."""
    h = np.finfo(float).eps ** (1 / 3) * np.maximum(1.0, np.abs(u))
    shifted = np.vstack([u + np.diag(h)[:9], u - np.diag(h)[:9], u + np.r_[np.zeros(9), h[9:]],
                         u - np.r_[np.zeros(9), h[9:]]])                          # (20, 9 + n)
    pts = _points(shifted, branch, n)                                             # (20, n, 2)
    out = np.zeros((2 * n, 9 + n))
    d = (pts[:9] - pts[9:18]) / (2.0 * h[:9])[:, None, None]                     # (9, n, 2)
    out[:, :9] = np.concatenate([d[:, :, 0], d[:, :, 1]], axis=1).T
    dt = (pts[18] - pts[19]) / (2.0 * h[9:])[:, None]                            # (n, 2)
    k = np.arange(n)
    out[k, 9 + k], out[n + k, 9 + k] = dt[:, 0], dt[:, 1]
    return out


def _feasible(v: np.ndarray, th: np.ndarray, p: Problem) -> np.ndarray:
    """Every requirement's rows g >= 0 (as the differential evolution keeps them) for designs ``v`` (9, k) meeting
    the targets at crank angles ``th`` (k, n): (m, k)."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        return np.concatenate([hard_constraints(v, th, p), soft_constraints(v, p)])


def _true_error(v: np.ndarray, branch: float, p: Problem) -> tuple[float, np.ndarray]:
    """The sum of squared distances (mm^2) from the targets to the nearest points of the whole curve (grid, then
    golden section) and the crank angles there."""
    th, pts = nearest(v, branch, p.targets)
    return float(np.sum((pts - p.targets) ** 2)), th


def polish(v0: np.ndarray, branch: float, p: Problem) -> tuple[np.ndarray, float]:
    """Design ``v0`` (9,) polished on the true point-to-curve error (see the module): the best design found that
    keeps every requirement, and its error (mm^2; inf where none does).

    The unknowns are the design and one crank angle a target; least squares on the gaps there is the
    point-to-curve error wherever each angle is its target's nearest point, so each round starts from the nearest
    points found afresh over the whole curve, and rounds go on while that lowers the error (at most ROUNDS).
    Where the result breaks a requirement, the rows g >= 0 of every requirement join the residuals as
    ``weight * scale * min(0, g - MARGIN)``, the weight raised through PENALTIES until the result keeps them all."""
    from scipy.optimize import least_squares

    n = p.n
    lo = np.r_[[b[0] for b in p.box], np.full(n, -np.inf)]
    hi = np.r_[[b[1] for b in p.box], np.full(n, np.inf)]
    found: list[tuple[float, np.ndarray]] = []

    def keep(v: np.ndarray) -> tuple[float, np.ndarray]:
        """Record design ``v`` where it keeps every requirement; its true error and nearest angles."""
        if not np.all(np.isfinite(v)):
            return math.inf, np.zeros(n)
        err, th = _true_error(v, branch, p)
        if math.isfinite(err) and np.all(_feasible(v[:, None], th[None], p) >= -1e-12):
            found.append((err, v))
        return err, th

    def short(u: np.ndarray) -> np.ndarray:
        """The requirements' rows less the margin, (m, k) for unknowns ``u`` (k, 9 + n)."""
        return _feasible(u[:, :9].T, u[:, 9:], p) - MARGIN

    def residuals(u: np.ndarray, weight: float) -> np.ndarray:
        r = _gaps(u, branch, p.targets)
        if weight == 0.0:
            return r
        return np.r_[r, weight * p.scale * np.minimum(short(u[None])[:, 0], 0.0)]

    def jacobian(u: np.ndarray, weight: float) -> np.ndarray:
        j = _gap_jacobian(u, branch, n)
        if weight == 0.0:
            return j
        h = np.finfo(float).eps ** (1 / 3) * np.maximum(1.0, np.abs(u))
        g = short(np.vstack([u + np.diag(h), u - np.diag(h)]))                 # (m, 2 (9 + n))
        slope = (g[:, :len(u)] - g[:, len(u):]) / (2.0 * h)
        active = short(u[None])[:, 0] < 0.0
        return np.vstack([j, weight * p.scale * slope * active[:, None]])

    def squares(u: np.ndarray, weight: float) -> np.ndarray:
        return np.asarray(least_squares(residuals, np.clip(u, lo, hi), jac=jacobian, bounds=(lo, hi), method="trf",
                                        x_scale="jac", xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=LSQ_STEPS,
                                        args=(weight,)).x)

    v = np.array(v0, dtype=float)
    v[2] = math.remainder(v[2], TWO_PI)                                      # the ground line's direction in [-pi, pi]
    err, th = keep(v)
    u = np.r_[v, th]
    try:
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            for _ in range(ROUNDS):
                kept = len(found)
                for weight in PENALTIES:
                    u = squares(u, weight)
                    new, th_new = keep(u[:9])
                    if len(found) > kept:
                        break
                if not new < err * (1.0 - 1e-9):
                    break
                err, u = new, np.r_[u[:9], th_new]
    except (ValueError, ArithmeticError, np.linalg.LinAlgError):
        pass
    if not found:
        return np.asarray(v0, dtype=float), math.inf
    err, best = min(found, key=lambda f: f[0])
    return best, err


def target_descriptors(targets: np.ndarray, closed: bool, harmonics: int) -> tuple[list[fourier.Normalised],
                                                                                   np.ndarray]:
    """The normalised descriptors of the targets and of their mirror image (as a closed polygon, or an open one
    retraced), and the query vectors (4, H, 4): each of the two in both forms."""
    out: list[fourier.Normalised] = []
    queries: list[np.ndarray] = []
    for pts in (targets, fourier.mirrored(targets)):
        poly = pts if closed else fourier.retrace(pts)
        centre, coeffs = fourier.coefficients(poly, harmonics)
        norm = fourier.normalise(centre, coeffs)
        out.append(norm)
        queries.extend(fourier.forms(norm.coefficients))
    return out, np.array(queries)


def used_harmonics(points: int, closed: bool, most: int) -> int:
    """The harmonics compared: no more than the targets resolve ((vertices - 1) // 2 of the polygon) nor ``most``."""
    vertices = points if closed else 2 * points - 2
    return max(2, min(most, (vertices - 1) // 2))


def guesses(targets: np.ndarray, closed: bool, entries: atlases.Atlas, count: int = NEAREST
            ) -> list[tuple[float, np.ndarray, float]]:
    """The atlas's first guesses for the targets: (descriptor distance, design (9,) in the task's frame, branch),
    the ``count`` nearest of each of the four matches, nearest first."""
    h = used_harmonics(len(targets), closed, entries.curves.coefficients.shape[1])
    norms, queries = target_descriptors(targets, closed, h)
    atlas_c = entries.curves.coefficients[:, :h].reshape(len(entries), -1)
    out = []
    for q, query in enumerate(queries):
        mirror, other_end = divmod(q, 2)
        d2 = np.sum((atlas_c - query.reshape(-1)) ** 2, axis=1)
        pick = np.argsort(d2)[:count]
        ref = fourier.Normalised(entries.curves.coefficients[pick], entries.curves.centre[pick],
                                 entries.curves.scale[pick], entries.curves.rotation[pick],
                                 entries.curves.phase[pick], entries.curves.reversed[pick])
        target = norms[mirror]
        scale, turn, shift = fourier.similarity(target, ref, bool(other_end))
        l1, l3, l4, cx, cy = entries.linkages[pick].T
        x0, y0 = shift[:, 0], shift[:, 1]
        designs = np.array([x0, y0, turn, scale * l1, scale, scale * l3, scale * l4, scale * cx, scale * cy])
        branch = 1.0
        if mirror:
            designs[[1, 2, 8]] *= -1.0
            branch = -1.0
        out += [(float(d2[i]), designs[:, k], branch) for k, i in enumerate(pick)]
    return sorted(out, key=lambda g: g[0])


def guess_errors(first: list[tuple[float, np.ndarray, float]], targets: np.ndarray, block: int = 32) -> np.ndarray:
    """The error (mm^2) of each guess of ``first`` (see :func:`guesses`) on the targets (n, 2) over the whole turn,
    on the polish's grid: what :func:`errors` of each with a crank and ``GRID`` gives (the same numbers), worked
    ``block`` guesses at once (:func:`nearest_many`)."""
    out = np.empty(len(first))
    for k in range(0, len(first), block):
        vs = np.array([v for _, v, _ in first[k:k + block]])
        branches = np.array([branch for _, _, branch in first[k:k + block]])
        pts = nearest_many(vs, branches, targets, GRID)[1]
        out[k:k + block] = np.sum(np.sum((pts - targets) ** 2, axis=2), axis=1)
    return out


def _candidate(v: np.ndarray, branch: float, p: Problem, crank: bool) -> Candidate | None:
    sq, th = errors(v, branch, p.targets, crank)
    d = dict(zip(BASE, v.tolist(), strict=True)) | {"branch": branch}
    lengths = (d["r1"], d["r2"], d["r3"], d["r4"])
    g = classify(*lengths)
    if crank and not (g.grashof_class == "I" and g.input_turns_fully):
        return None
    end = th[0] + TWO_PI if crank else th[0] + (sense(th) or 1) * np.mod((sense(th) or 1) * (th - th[0]),
                                                                         TWO_PI).max()
    worst = math.degrees(float(worst_transmission(*lengths, th[0], end)))
    row = {"error_mm2": float(sq.sum()), **fourbar_row(d, th.tolist()), "errors_mm": np.sqrt(sq).tolist(),
           "inversion": g.inversion, "transmission_worst_deg": worst, "in_order": sense(th) != 0, "defects": []}
    table = drawn_table(d, float(th[0]))
    if not table_fits(table):
        return None
    sketch = coupler_sketch(d, th.tolist(), p.targets, np.linspace(0.0, TWO_PI, 721))
    signature = (d["x0"], d["y0"], *lengths, d["cx"], d["cy"], d["theta0"] * p.scale)
    return Candidate(table, row, float(sq.sum()), signature, sketch)


def _polished(starts: list[tuple[np.ndarray, float]], p: Problem) -> list[tuple[np.ndarray, float]]:
    """The designs (and branches) that polishing ``starts`` gives and that keep every requirement. With more than
    SUBSAMPLE targets each start is polished first on SUBSAMPLE of them spread evenly (the ends kept), and only the
    FINISHED best of those, by their error on every target, are polished on all: so the cost hardly grows with the
    targets."""
    n = p.n
    rough = p
    if n > SUBSAMPLE:
        rough = replace(p, targets=p.targets[np.unique(np.round(np.linspace(0, n - 1, SUBSAMPLE)).astype(int))])
    done = [(w, branch) for v, branch in starts for w, err in [polish(v, branch, rough)] if math.isfinite(err)]
    if rough is p:
        return done
    ranked = sorted(done, key=lambda d: float(errors(d[0], d[1], p.targets, True, GRID)[0].sum()))
    return [(w, branch) for v, branch in ranked[:FINISHED] for w, err in [polish(v, branch, p)] if math.isfinite(err)]


def solve(task: Any) -> tuple[list[Candidate], dict[str, Any]]:
    """Fourier-descriptor path synthesis for a validated untimed path task with ``method = "fourier"``: the
    candidates (unranked) and how the search went."""
    clock = time.perf_counter()
    cpu = time.process_time()
    p = problem_of(task)
    closed = bool(task.closed)
    entries, info = atlases.load("closed" if closed else "arcs", task.atlas_folder)
    first = guesses(p.targets, closed, entries)
    scored = sorted(zip(guess_errors(first, p.targets).tolist(), *zip(*first, strict=True), strict=True),
                    key=lambda s: s[0])
    out: list[Candidate] = []
    for w, branch in _polished([(v, branch) for _, _, v, branch in scored[:task.guesses]], p):
        c = _candidate(w, branch, p, task.crank)
        if c is not None:
            out.append(weighed(c))
    if not out:
        raise SpecError(f"no linkage found that keeps every requirement from the {task.guesses} best of "
                        f"{len(first)} atlas guesses: lower min_transmission, widen link_range, ground_region or "
                        "coupler_range, or raise guesses", "task.points")
    search = {"method": "elliptic Fourier descriptors: the nearest atlas entries put onto the targets in closed form, "
                        "polished by least squares on the true point-to-curve distances (the requirements as "
                        "penalties where one is in the way)",
              "atlas": info, "guesses": len(first), "polished": task.guesses,
              "harmonics": used_harmonics(len(p.targets), closed, entries.curves.coefficients.shape[1]),
              "seconds": round(time.perf_counter() - clock, 3),
              "cpu_seconds": round(time.process_time() - cpu, 3), "ran_on": "this process", "bound": []}
    return out, search
