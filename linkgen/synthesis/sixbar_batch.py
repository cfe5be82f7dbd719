"""Many six-bar drawings of one type solved at once: the fused kernels' closed form
(:mod:`linkgen.kinematics.fused`) with each drawing's numbers as arrays over the designs.

The six-bar search (:mod:`linkgen.synthesis.sixbar`) evaluates a whole population (150 designs) a generation.
Solving them one by one through the general solver costs about 1 ms of Python each (a structure, a plan and a
program built per design) against some 10 us of arithmetic. Every design of one type has the same solve order (the
crank, then RRR dyads, as :func:`linkgen.kinematics.fused.program` plans it from the links alone), so that order is
planned once and each step runs over an (N, M) array: N designs by M crank angles. Each dyad's joint is the
fused kernel's (the pins' frame, the height 4 area / (2 d^2) from the squared distance, on the side the drawing
shows), its margin 4 area / (2 r1 r2), its transmission angle that between its two links, and a pose is not
reached where the margin is below -FEASIBILITY_TOL, as in the general solver: the results equal the general
solver's to rounding (tests/synthesis/test_sixbar_batch.py). A drawing whose equal-radius (deltoid) pins meet is
left to the general solver (``general``), as the fused kernels leave it.

Drawings are normalised (O2 at 0, O4 at 1; mm in the caller's units), angles in radians counter-clockwise from the
ground line, the crank's from its drawn direction as the general solver takes it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkgen.kinematics.fused import CrankOp, Program, RRROp
from linkgen.kinematics.linkage import FEASIBILITY_TOL, FOLD_REACH
from linkgen.kinematics.structure import COINCIDENT

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Solved:
    """N drawings over M crank angles: each pose reached (N, M) bool, the least dyad margin (N, M) and the least
    transmission angle min(mu, pi - mu) over the dyads (N, M) rad, the turn of the tracer's link (N, M) unit
    complex and its reference joint (N, M) complex (mm); ``drawn`` (N,) where the drawing is a linkage (finite, no
    two joints of a link at one place), ``general`` (N,) where a deltoid's pins meet and the general solver must
    place it."""

    ok: np.ndarray
    margin: np.ndarray
    gamma: np.ndarray
    rot: np.ndarray
    ref: np.ndarray
    drawn: np.ndarray
    general: np.ndarray


def drawn_ok(joints: dict[str, np.ndarray], bodies: tuple[tuple[str, ...], ...]) -> np.ndarray:
    """(N,) whether each drawing is finite and has no two joints of one body within COINCIDENT of the drawing's
    scale (its largest coordinate, at least 1): what :func:`linkgen.kinematics.structure.make_structure` refuses."""
    names = list(joints)
    z = np.stack([joints[k] for k in names], axis=1)
    at = {k: i for i, k in enumerate(names)}
    pairs = np.array([(at[a], at[b]) for pts in bodies for i, a in enumerate(pts) for b in pts[i + 1:]
                      if a in at and b in at], dtype=int).reshape(-1, 2)
    with np.errstate(invalid="ignore"):
        scale = np.maximum(1.0, np.max(np.maximum(np.abs(z.real), np.abs(z.imag)), axis=1))
        apart = np.all(np.abs(z[:, pairs[:, 0]] - z[:, pairs[:, 1]]) > COINCIDENT * scale[:, None], axis=1)
    return np.all(np.isfinite(z), axis=1) & apart


def solve_many(prog: Program, joints: dict[str, np.ndarray], links: dict[str, tuple[str, ...]],
               ground: tuple[str, ...], angles: np.ndarray, tracer_link: str, reference: str) -> Solved:
    """Drawings ``joints`` (name -> (N,) complex, every joint of the program) at crank angles ``angles`` (M,) rad,
    through the solve order ``prog`` planned for their type from ``links`` (name -> joints) and ``ground``; the
    tracer's link ``tracer_link`` turned, and its joint ``reference`` placed."""
    n = len(next(iter(joints.values())))
    d = {k: np.asarray(v, dtype=complex)[:, None] for k, v in joints.items()}
    z = np.stack([v[:, 0] for v in d.values()], axis=1)
    # the drawing's size: the largest distance between two of its joints (at least 1e-9), (N, 1)
    size = np.maximum(np.max(np.abs(z[:, :, None] - z[:, None, :]), axis=(1, 2)), 1e-9)[:, None]
    P: dict[str, np.ndarray] = {}
    vec: dict[str, np.ndarray] = {}
    frame: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    ok = np.ones((n, len(angles)), dtype=bool)
    margins, gammas = [], []
    general = np.zeros(n, dtype=bool)

    def point(body: str | None, name: str) -> np.ndarray:
        if body is None:
            return d[name]
        pd, f = frame[body]
        return vec[body] * (f * (d[name] - pd)) + P[body]

    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for op in prog.ops:
            if isinstance(op, CrankOp):
                other = next(p for p in links[op.body] if p != op.pivot)
                t0 = np.angle(d[other] - d[op.pivot])                    # the crank's drawn direction, (N, 1)
                x = t0 + np.mod(angles[None, :] - t0, TWO_PI)
                h = (x - t0) * 0.5
                np.tan(h, out=h)
                h2 = np.square(h)
                inv = 1.0 / (h2 + 1.0)
                e = np.empty(h.shape, dtype=complex)
                e.real = (1.0 - h2) * inv
                e.imag = 2.0 * (h * inv)
                P[op.body], vec[op.body], frame[op.body] = d[op.pivot], e, (d[op.pivot], np.ones((n, 1), complex))
                continue
            assert isinstance(op, RRROp)
            (b1, b2), (k1, k2), (n1, n2) = op.bodies, op.refs, op.pins
            v1, v2 = d[op.joint] - d[n1], d[op.joint] - d[n2]
            r1, r2 = np.abs(v1), np.abs(v2)
            p1, p2 = point(k1, n1), point(k2, n2)
            dv = p2 - p1
            dd = np.square(dv.real) + np.square(dv.imag)
            reach = FOLD_REACH * size
            general |= ((np.abs(r1 - r2) <= reach) & (np.min(dd, axis=1, keepdims=True) <= reach**2))[:, 0]
            prod = ((r1 + r2) ** 2 - dd) * (dd - (r1 - r2) ** 2)
            inv = 0.5 / np.where(dd > 0, dd, 1.0)
            # the drawing's side: the sign of cross(pin 2 - pin 1, joint - pin 1) as drawn, +1 where it is 0
            q = d[n2] - d[n1]
            side = np.sign(q.real * v1.imag - q.imag * v1.real)
            side = np.where(side == 0, 1.0, side)
            wj = np.empty(dd.shape, dtype=complex)
            wj.real = inv * (r1 * r1 - r2 * r2) + 0.5
            wj.imag = np.sqrt(np.maximum(prod, 0.0)) * inv * side
            a = dv * wj
            jw = p1 + a
            b = jw - p2
            P[b1], vec[b1], frame[b1] = p1, a, (d[n1], v1.conjugate() / (r1 * r1))
            P[b2], vec[b2], frame[b2] = p2, b, (d[n2], v2.conjugate() / (r2 * r2))
            ok &= prod >= -(FEASIBILITY_TOL * 2.0 * r1 * r2) ** 2
            margins.append(np.copysign(np.sqrt(np.abs(prod)), prod) / (2.0 * r1 * r2))
            ab = np.conjugate(a) * b
            mu = np.arctan2(np.abs(ab.imag), ab.real)
            gammas.append(np.minimum(mu, math.pi - mu))
        rot = vec[tracer_link] * frame[tracer_link][1]
        ref = point(tracer_link, reference)
    drawn = drawn_ok(joints, (ground, *links.values()))
    return Solved(ok, np.min(margins, axis=0), np.min(gammas, axis=0), rot, ref, drawn, general)
