"""Untimed six-bar path fitting: the tracer and the similarity that put a six-bar's curve nearest the targets.

A six-bar design solved over a turn gives, at each crank angle theta_j of the turn, its tracer link's turn R_j and
the reference joint F_j of that link (complex numbers, normalised drawing); the tracer placed by (u, z, t) is
W_j = R_j u + z F_j + t (u the tracer's offset, z the similarity's scale and turn, t its shift: complex, mm).
Untimed, each target k is met at the angle of the curve's point nearest it, so the error (mm^2) is
``sum_k min_j |W_j - T_k|^2``, the four-bar's untimed metric (:mod:`linkgen.synthesis.fourier_path`).

(u, z, t) come by alternating, as the iterative closest point method does: each target given a point of the
curve, (u, z, t) by least squares in closed form (the normal equations, 3 complex unknowns); then each target's
nearest point of the curve so placed; neither step raises the error. It starts from STARTS assignments of the
targets, in their order, spread evenly over the turn, each way round and from STARTS // 2 starting angles, all
iterated together, and keeps the best. A design a hair from one already fitted (the polish's forward differences)
keeps that design's assignment (:func:`assigned_fit`): one least squares and one nearest search instead of STARTS
assignments iterated ROUNDS times, and the same numbers wherever its own iteration would end on that assignment.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

#: the starting assignments tried (half each way round the turn) and the rounds of assignment and least squares
STARTS, ROUNDS = 16, 8


def fit(a: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """(u, z, t) (B, 3) complex by least squares for each of B systems ``a`` (B, n, 3) (columns: the tracer link's
    turn, its reference joint, 1) on the targets (n,) complex mm: the normal equations, 3 complex unknowns."""
    ah = np.conj(np.swapaxes(a, 1, 2))
    normal = ah @ a + 1e-14 * np.eye(3)
    return np.linalg.solve(normal, (ah @ targets[None, :, None]))[:, :, 0]


def _fit(rot: np.ndarray, ref: np.ndarray, targets: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """(u, z, t) (B, 3) complex by least squares for each assignment ``idx`` (B, n) of the targets to the curve."""
    return fit(np.stack([rot[idx], ref[idx], np.ones(idx.shape, complex)], axis=2), targets)


def nearest_fit(rot: np.ndarray, ref: np.ndarray, targets: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The best (u, z, t) (3,) complex, each target's nearest index (n,) into the turn's samples, and the assignment
    (n,) (indices into the turn's samples) that (u, z, t) was fitted on (:func:`assigned_fit` gives the same two
    from it).

    Parameters
    ----------
    rot, ref : ndarray
        The tracer link's turn (unit complex) and its reference joint (normalised drawing) at m crank angles
        evenly over a turn, (m,) each.
    targets : ndarray
        The targets (n,) complex, mm.
    """
    m, n = len(rot), len(targets)
    half = STARTS // 2
    offsets = (np.arange(half) * m) // half
    steps = np.round(np.arange(n) * m / n).astype(int)
    idx = np.concatenate([(offsets[:, None] + steps[None, :]) % m, (offsets[:, None] - steps[None, :]) % m])
    for _ in range(ROUNDS):
        idx = np.argmin(_gaps(rot, ref, _fit(rot, ref, targets, idx), targets), axis=2)
    uzt = _fit(rot, ref, targets, idx)
    gap = _gaps(rot, ref, uzt, targets)
    best = int(np.argmin(np.sum(np.min(gap, axis=2), axis=1)))
    return uzt[best], np.argmin(gap[best], axis=1), idx[best]


def assigned_fit(rot: np.ndarray, ref: np.ndarray, targets: np.ndarray, assignment: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
    """(u, z, t) (3,) complex fitted on a given ``assignment`` (n,) of the targets to the turn's samples and each
    target's nearest index (n,) into them so placed: :func:`nearest_fit`'s last step, for a design whose
    assignment is known (rot, ref and targets as there)."""
    uzt = _fit(rot, ref, targets, np.asarray(assignment)[None, :])
    return uzt[0], np.argmin(_gaps(rot, ref, uzt, targets)[0], axis=1)


def _gaps(rot: np.ndarray, ref: np.ndarray, uzt: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """The squared distances (B, n, m) mm^2 of each target from each of the turn's samples of the curve placed by
    each (u, z, t) of ``uzt`` (B, 3): the curve ``u rot + z ref + t`` (B, m)."""
    curve = rot[None, :] * uzt[:, :1] + uzt[:, 1:2] * ref[None, :] + uzt[:, 2:3]
    return np.abs(curve[:, None, :] - targets[None, :, None]) ** 2


#: the crank angles tried about each target's nearest sample of the fine turn, within one sample either side, and
#: the passes of it (each about the last's best, within one of its steps either side: 1/400 of a sample in all)
REFINE, PASSES = 41, 2


def nearest_on(tracer: Callable[[np.ndarray], np.ndarray], turn: np.ndarray, curve: np.ndarray,
               targets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each target's nearest point of a candidate's curve and the crank direction there: the nearest of the fine
    turn's samples, then, PASSES times, of REFINE crank directions within one step either side of the last.

    Parameters
    ----------
    tracer : callable
        Crank directions (rad, world frame) -> the tracer there (k, 2) mm.
    turn, curve : ndarray
        The fine turn's crank directions (m,) rad, evenly spaced, and the tracer there (m, 2) mm.
    targets : ndarray
        The targets (n, 2) mm.

    Returns
    -------
    points, directions : ndarray
        The nearest points (n, 2) mm and the crank directions (n,) rad there.
    """
    gap = np.sum((curve[None, :, :] - targets[:, None, :]) ** 2, axis=2)
    step = float(turn[1] - turn[0])
    at, rows = turn[np.argmin(gap, axis=1)], np.arange(len(targets))
    for _ in range(PASSES):
        around = at[:, None] + np.linspace(-step, step, REFINE)[None, :]
        near = tracer(around.ravel()).reshape(len(targets), REFINE, 2)
        best = np.argmin(np.sum((near - targets[:, None, :]) ** 2, axis=2), axis=1)
        at, point, step = around[rows, best], near[rows, best], 2.0 * step / (REFINE - 1)
    return point, at
