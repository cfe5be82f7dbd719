"""Motion generation: a four-bar whose coupler passes two or three positions of a line (a point P and a direction).

Points are complex numbers (mm). Position k puts P at P_k with the coupler line at phi_k; the
coupler turns alpha_k = phi_k - phi_1 and P moves delta_k = P_k - P_1 from the first. Each side
of the linkage is a dyad: a ground pivot O, a moving pivot A_1 (drawn at the first position),
W = A_1 - O and Z = P_1 - A_1, and the standard dyad form W (e^{i beta_k} - 1) + Z (e^{i alpha_k} - 1)
= delta_k, beta_k the dyad link's turn. The free choices, exposed in every candidate's row:

* three positions, no pivots given: beta_2 and beta_3 of each dyad, on a grid (``samples`` values
  each), W and Z then from the 2x2 complex system;
* ``moving_pivots`` given: each fixed pivot is the centre of the circle through its moving pivot's
  positions (three positions), or any point of their bisector (two: the link's turn beta_2 swept);
* ``fixed_pivots`` given: each moving pivot is found by inversion, the centre of the circle through
  the fixed pivot's positions seen from the coupler (three positions), or a point of their bisector
  (two: swept).

Every pair of dyads (either as the crank) is a four-bar; each is checked for the task's defects
(:mod:`linkgen.synthesis.defects`: Grashof when a crank is asked for, order, branch) before it is
offered, and ranked by its worst transmission angle (over the whole turn for a crank, else over the
crank's travel from the first position to the last), which must be at least ``min_transmission``
(30 degrees by default; where no four-bar keeps it, the nearest are offered and the search's
``bound`` line names the limit). The pairs are screened in blocks, keeping the best so far, so memory
stays bounded (about samples^2 dyads) whatever the number of pairs. Finally the four-bar is
re-solved in closed form at its crank angles (:mod:`linkgen.synthesis.geometry`) and its distance
from each position reported.
"""
from __future__ import annotations

import cmath
import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.spec import MAX_LENGTH_MM, MIN_LENGTH_MM
from linkgen.synthesis.candidates import Candidate, coupler_sketch, drawn_table, fourbar_row
from linkgen.synthesis.defects import defects, sense
from linkgen.synthesis.geometry import frame_of, place_design, worst_transmission

TWO_PI = 2.0 * math.pi
#: the best pairs (by transmission) given the full defect check, at most
CHECKED = 400
#: defect-free candidates gathered, best first, for each one asked (the ranking leaves out near-copies)
ENOUGH = 8
#: pairs of dyads screened at once (about 2 kB each): the screen's memory, whatever the samples
BLOCK = 1 << 16


def circumcentre(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Centres of the circles through three points each (complex arrays); NaN where the points are in line."""
    ab, ac = b - a, c - a
    den = 2.0 * (ab.real * ac.imag - ab.imag * ac.real)
    with np.errstate(divide="ignore", invalid="ignore"):
        centre = a + 1j * (ab * abs(ac) ** 2 - ac * abs(ab) ** 2) / den
    return np.where(np.abs(den) > 1e-12 * (np.abs(ab) * np.abs(ac) + 1e-300), centre, np.nan)


def bisector(p: complex, q: complex, turns: np.ndarray) -> np.ndarray:
    """Points on the bisector of p q from which the chord turns by ``turns`` (rad, counter-clockwise, in (0, 2 pi))
    when p is carried onto q."""
    chord = abs(q - p)
    normal = 1j * (q - p) / chord
    return (p + q) / 2.0 + normal * (chord / 2.0) / np.tan(turns / 2.0)


def _turns(samples: int) -> np.ndarray:
    """``samples`` link turns spread over (0, 2 pi), keeping clear of 0 (a pivot at infinity)."""
    return np.linspace(0.0, TWO_PI, samples + 2)[1:-1]


def free_dyads(p: np.ndarray, alpha: np.ndarray, samples: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Three positions, nothing given: (O, A_1, choices (k, 2) of beta_2, beta_3) over the grid of link turns."""
    b2, b3 = (g.ravel() for g in np.meshgrid(_turns(samples), _turns(samples), indexing="ij"))
    e2, e3 = np.exp(1j * b2) - 1.0, np.exp(1j * b3) - 1.0
    f2, f3 = cmath.exp(1j * alpha[1]) - 1.0, cmath.exp(1j * alpha[2]) - 1.0
    d2, d3 = p[1] - p[0], p[2] - p[0]
    det = e2 * f3 - e3 * f2
    ok = np.abs(det) > 1e-9
    w = (d2 * f3 - d3 * f2) / det[ok]              # Cramer's rule on e W + f Z = delta at positions 2 and 3
    z = (e2[ok] * d3 - e3[ok] * d2) / det[ok]
    a1 = p[0] - z
    return a1 - w, a1, np.column_stack([b2[ok], b3[ok]])


def moving_dyads(p: np.ndarray, alpha: np.ndarray, moving: complex, samples: int) -> tuple[np.ndarray, ...]:
    """The fixed pivots (and the link's turns) of a given moving pivot: the circumcentre, or swept on a bisector."""
    a = p + (moving - p[0]) * np.exp(1j * alpha)
    if len(p) == 3:
        o = circumcentre(a[:1], a[1:2], a[2:3])
        return o, np.full(o.shape, moving), _betas(o, a)
    o = bisector(a[0], a[1], _turns(samples))
    return o, np.full(o.shape, moving), _betas(o, a)


def fixed_dyads(p: np.ndarray, alpha: np.ndarray, fixed: complex, samples: int) -> tuple[np.ndarray, ...]:
    """The moving pivots of a given fixed pivot, by inversion: the fixed pivot seen from the coupler at each
    position, and the centre of the circle through those (three positions) or points on their bisector (two)."""
    seen = (fixed - p) * np.exp(-1j * alpha)
    rel = circumcentre(seen[:1], seen[1:2], seen[2:3]) if len(p) == 3 else bisector(seen[0], seen[1],
                                                                                      _turns(samples))
    a1 = p[0] + rel
    a = p[None, :] + rel[:, None] * np.exp(1j * alpha)[None, :]
    o = np.full(a1.shape, fixed)
    return o, a1, _betas(o, a.T)


def _betas(o: np.ndarray, a: np.ndarray) -> np.ndarray:
    """The link's turn (rad) from the first position to each other, for pivots ``o`` (k,) and moving pivot
    positions ``a`` (n,) or (n, k)."""
    a = a.reshape(len(a), -1)
    return np.column_stack([np.angle((a[k] - o) / (a[0] - o)) % TWO_PI for k in range(1, len(a))])


def _pair_blocks(crank: tuple[np.ndarray, ...], rocker: tuple[np.ndarray, ...],
                 same: bool) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """Every pairing (i, j) of a crank dyad with a rocker dyad (not a dyad with itself when both sides are one set),
    in order (i, then j), in blocks of about :data:`BLOCK` pairs: the screen's memory stays bounded whatever the
    number of dyads."""
    rows = np.flatnonzero(np.isfinite(crank[0]))
    cols = np.flatnonzero(np.isfinite(rocker[0]))
    if len(cols) == 0:
        return
    step = max(1, BLOCK // len(cols))
    for k in range(0, len(rows), step):
        i, j = (g.ravel() for g in np.meshgrid(rows[k:k + step], cols, indexing="ij"))
        keep = i != j if same else slice(None)
        yield i[keep], j[keep]


def inside(*points: np.ndarray) -> np.ndarray:
    """Where every point (complex, mm) lies within what a linkage template holds: each coordinate within
    MAX_LENGTH_MM of the origin."""
    return np.all([(np.abs(q.real) <= MAX_LENGTH_MM) & (np.abs(q.imag) <= MAX_LENGTH_MM) for q in points], axis=0)


def _screen(p: np.ndarray, alpha: np.ndarray, o2, a, o4, b, task: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The vectorised first screen of pairs: (passes the lengths, Grashof, branch and order checks; fits a template
    as well; worst transmission angle over the motion, rad). The motion is the whole turn for a crank, else the
    crank's travel from the first position to the last, the way it meets them in order."""
    r1, r2, r3, r4 = np.abs(o4 - o2), np.abs(a - o2), np.abs(b - a), np.abs(b - o4)
    rot = np.exp(1j * alpha)[None, :]
    ak, bk = p[None, :] + (a - p[0])[:, None] * rot, p[None, :] + (b - p[0])[:, None] * rot
    links = np.stack([r1, r2, r3, r4])
    scale = links.max(axis=0)
    ok = (links.min(axis=0) > 1e-9 * scale) & np.isfinite(scale)
    if task.link_range is not None:
        ok &= (links.min(axis=0) >= task.link_range[0]) & (scale <= task.link_range[1])
    short, total = links.min(axis=0), links.sum(axis=0)
    if task.crank:
        ok &= (r2 <= short) & (total - 2 * short - 2 * scale > 1e-9 * scale)
    cross = ((o4[:, None] - ak) * np.conj(bk - ak)).imag
    ok &= np.all(cross > 0, axis=1) | np.all(cross < 0, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):    # a pair with O2 on O4 is refused above
        theta = np.angle((ak - o2[:, None]) / (o4 - o2)[:, None])
    travel = [np.mod(s * (theta[:, 1:] - theta[:, :1]), TWO_PI) for s in (1, -1)]
    order = [np.all(t > 1e-9, axis=1) & np.all(np.diff(t, axis=1) > 1e-9, axis=1) for t in travel]
    ok &= order[0] | order[1]
    if task.crank:
        start, end = np.zeros(len(r1)), np.full(len(r1), TWO_PI)
    else:
        start = theta[:, 0]
        end = start + np.where(order[0], travel[0][:, -1], -travel[1][:, -1])
    with np.errstate(invalid="ignore", divide="ignore"):
        worst = worst_transmission(r1, r2, r3, r4, start, end)
    fits = inside(o2, o4, a, b) & (links.min(axis=0) >= MIN_LENGTH_MM)
    return ok & np.isfinite(worst), fits, worst


@dataclass(frozen=True)
class Screened:
    """How the screen of pairs went: pairs tried, passing the checks, and of those fitting a template."""

    tried: int
    passed: int
    fitting: int


def best_pairs(left: tuple[np.ndarray, ...], right: tuple[np.ndarray, ...], same: bool, p: np.ndarray,
               alpha: np.ndarray, task: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, Screened]:
    """The :data:`CHECKED` best pairs (crank dyad i, rocker dyad j, worst transmission angle in rad), best first
    and in pair order among equals, of those that pass the screen and fit a template, whether or not they keep the
    transmission limit (those that do come first); and how the screen went. Screened block by block, keeping only
    the best so far."""
    kept_i, kept_j, kept_w = (np.zeros(0, dtype=int),) * 2 + (np.zeros(0),)
    tried = passed = fitting = 0
    for i, j in _pair_blocks(left, right, same):
        ok, fits, worst = _screen(p, alpha, left[0][i], left[1][i], right[0][j], right[1][j], task)
        tried += len(i)
        passed += int(np.count_nonzero(ok))
        ok &= fits
        fitting += int(np.count_nonzero(ok))
        order = np.lexsort((np.concatenate([kept_j, j[ok]]), np.concatenate([kept_i, i[ok]]),
                            -np.concatenate([kept_w, worst[ok]])))[:CHECKED]
        kept_i, kept_j, kept_w = (np.concatenate([kept_i, i[ok]])[order], np.concatenate([kept_j, j[ok]])[order],
                                  np.concatenate([kept_w, worst[ok]])[order])
    return kept_i, kept_j, kept_w, Screened(tried, passed, fitting)


def _candidate(p: np.ndarray, alpha: np.ndarray, o2: complex, a: complex, o4: complex, b: complex, task: Any,
               choice: dict[str, Any], worst: float) -> Candidate | None:
    """The candidate of one pair, fully checked (None on a defect), with its positions re-solved and its errors."""
    pt = np.array([[v.real, v.imag] for v in (o2, o4, a, b, p[0])])
    d = frame_of(*pt)
    rot = np.exp(1j * alpha)
    ak, bk = p + (a - p[0]) * rot, p + (b - p[0]) * rot
    theta = np.angle((ak - o2) / (o4 - o2))
    branches = np.sign(((o4 - ak) * np.conj(bk - ak)).imag)
    if defects((d["r1"], d["r2"], d["r3"], d["r4"]), theta, branches, task.crank):
        return None
    args = [d[k] for k in ("x0", "y0", "theta0", "r1", "r2", "r3", "r4", "cx", "cy", "branch")]
    at = place_design(args, theta)
    got = at.px + 1j * at.py
    line = np.angle((at.bx + 1j * at.by - at.ax - 1j * at.ay) / (b - a)) - alpha
    targets = np.column_stack([p.real, p.imag])
    row = {"error_mm2": float(np.sum(np.abs(got - p) ** 2)), **fourbar_row(d, theta),
           "errors_mm": np.abs(got - p).tolist(),
           "angle_errors_deg": np.degrees(np.abs(np.remainder(line + math.pi, TWO_PI) - math.pi)).tolist(),
           "moving_pivots": [[a.real, a.imag], [b.real, b.imag]],
           "transmission_worst_deg": math.degrees(worst), "free_choice": choice, "defects": []}
    turn = sense(theta)
    sweep = np.linspace(0.0, TWO_PI, 721) if task.crank else np.linspace(theta[0], theta[0] + turn * np.mod(
        turn * (theta[-1] - theta[0]), TWO_PI), 181)
    return Candidate(drawn_table(d, float(theta[0])), row, -worst, tuple(args[:9]),
                     coupler_sketch(d, theta, targets, sweep))


def _choices(mode: str, k_crank: np.ndarray, k_rocker: np.ndarray) -> dict[str, Any]:
    """The free choices of one pair, in degrees, as the row shows them."""
    return {"given": mode, "crank_turns_deg": np.degrees(k_crank).tolist(),
            "rocker_turns_deg": np.degrees(k_rocker).tolist()}


def solve(task: Any) -> tuple[list[Candidate], dict[str, Any]]:
    """The four-bars of a validated motion task (unranked) and how they were found."""
    p = np.array([complex(x, y) for x, y, _ in task.positions])
    alpha = np.radians([a - task.positions[0][2] for _, _, a in task.positions])
    if task.moving_pivots is not None:
        mode = "moving pivots"
        sides = [moving_dyads(p, alpha, complex(*m), task.samples) for m in task.moving_pivots]
    elif task.fixed_pivots is not None:
        mode = "fixed pivots"
        sides = [fixed_dyads(p, alpha, complex(*f), task.samples) for f in task.fixed_pivots]
    else:
        mode = "none: the dyads' turns swept"
        sides = [free_dyads(p, alpha, task.samples)] * 2
    same = task.moving_pivots is None and task.fixed_pivots is None
    out, tried, bound = paired(p, alpha, sides, same, task, mode)
    info = {"method": "dyad form W (e^{i beta} - 1) + Z (e^{i alpha} - 1) = delta, pairs screened for Grashof, "
                      "order and branch defects", "free_choices": mode, "pairs_tried": tried, "offered": len(out),
            "bound": bound}
    return out, info


def paired(p: np.ndarray, alpha: np.ndarray, sides: list[tuple[np.ndarray, ...]], same: bool, task: Any,
           mode: str) -> tuple[list[Candidate], int, list[str]]:
    """The defect-free four-bars (best worst transmission angle first) that pair a dyad of ``sides[0]`` with one of
    ``sides[1]`` (either as the crank; one set paired with itself when ``same``), each side (centre points O, circle
    points A_1 (complex mm), the link's turns (k, n - 1) rad); the pairs tried; and the line naming
    ``task.min_transmission`` when no four-bar keeps it and the nearest (those whose worst transmission angle comes
    closest) are offered instead. Raises the one-line refusal naming the requirement that bound when none is
    found."""
    mu = math.radians(task.min_transmission)
    screens, screened, picks = [], 0, []
    for left, right in ((sides[0], sides[1]), (sides[1], sides[0]))[: 1 if same else 2]:
        i, j, worst, found = best_pairs(left, right, same, p, alpha, task)
        screens.append(found)
        screened += len(i)
        picks += [(left, right, i[k], j[k], float(worst[k])) for k in range(len(i))]
    out: list[Candidate] = []
    for keeps in (True, False):                         # those that keep the limit; else the nearest
        for crank, rocker, a, b, gamma in picks:
            if (gamma >= mu) != keeps or len(out) >= ENOUGH * task.candidates:
                continue
            c = _candidate(p, alpha, crank[0][a], crank[1][a], rocker[0][b], rocker[1][b], task,
                           _choices(mode, crank[2][a], rocker[2][b]), gamma)
            if c is not None:
                out.append(c)
        if out:
            break
    if not out:
        _refuse(task, screens, screened)
    best = max(c.row["transmission_worst_deg"] for c in out)
    bound = [] if best >= task.min_transmission else [
        f"task.min_transmission: no defect-free four-bar through these positions keeps its transmission angle at "
        f"least {task.min_transmission:g} degrees over its motion; the nearest are offered (the best reaches "
        f"{best:.4g}): lower min_transmission, or give other positions or pivots"]
    return out, sum(s.tried for s in screens), bound


def _refuse(task: Any, screens: list[Screened], checked: int) -> None:
    """The one-line refusal of a motion task that found nothing to offer (``checked`` pairs passed the screen and
    failed the full defect check), naming the requirement that bound."""
    tried = sum(s.tried for s in screens)
    if not checked and any(s.passed for s in screens):
        raise SpecError(f"every four-bar through these positions has a pivot or pin farther than {MAX_LENGTH_MM:g} mm "
                        f"from the origin or a link shorter than {MIN_LENGTH_MM:g} mm, which no template holds: move "
                        "the positions nearer the origin, or give pivots", "task.positions")
    what = "a Grashof crank" if task.crank else "a linkage"
    raise SpecError(f"no defect-free four-bar with {what} passes these positions ({tried} dyad pairs tried): "
                    "give other pivots, more samples, a wider link_range, or crank = false", "task.positions")

