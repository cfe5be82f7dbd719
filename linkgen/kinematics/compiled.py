"""An optional compiled path for the fused kernels' positions: the same construction as
:mod:`linkgen.kinematics.fused`, one pose at a time in machine code (numba), every dyad of a pose in registers.

numpy's kernels make a dozen passes over memory per dyad (each an array of all poses); past about 10^4 poses their
speed is the memory's. Here each pose goes through the whole program at once: its bodies' anchors and vectors stay in
a few local numbers, and only the joints' positions are written. The poses are cut into one contiguous run per
thread (numba's ``prange``). numpy stays the default: this path is taken only when asked for
(``Linkage.positions(..., engine="numba")``) and numba is installed (``pip install 'camgen[fast]'``).

The construction is :mod:`~linkgen.kinematics.fused`'s: the crank turned by its angle from the drawing; an RRR's
joint at ``p1 + d (along + i height)`` from its pins' frame (``d = p2 - p1``, height on the branch's side, from the
triangle's squared area ``((r1 + r2)^2 - dd)(dd - (r1 - r2)^2)``); each body's drawn point ``x`` at
``P + a f (x - pd)``. So its results equal the numpy kernels' to rounding (about 1e-13 mm on the bundled legs). A
deltoid whose equal-radius pins meet raises :class:`~linkgen.kinematics.fused.Folded`, as there.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkgen.kinematics.fused import CrankOp, Folded, Program, RRROp

try:                                   # the kernel's parallel loop; a plain range where numba is absent (never run)
    from numba import prange
except ImportError:                    # pragma: no cover - numba is optional
    prange = range  # type: ignore[misc]

#: op kinds in :class:`Encoded`
CRANK, RRR = 0, 1
#: poses a block of the kernel holds (each body's anchor and vector: 4 x 8 bytes a pose), small enough for a core's
#: first-level cache with a dozen bodies
BLOCK = 256


def available() -> bool:
    """Whether numba can be imported (the compiled path's one requirement)."""
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


@dataclass(frozen=True)
class Encoded:
    """A :class:`~linkgen.kinematics.fused.Program` as flat arrays for the kernel, one row an op (``kind``: CRANK or
    RRR): its bodies' indices ``b1``, ``b2`` (an RRR's; a crank's in ``b1``), the bodies its pins lie on ``ref1``,
    ``ref2`` (-1: the ground) with each pin's factor ``k1``, ``k2`` (its world point is ``P + a k`` on a body, ``k``
    itself on the ground), the radii, the branch's row in the signs, the squared fold reach (deltoids; -1: none) and
    the squared margin floor; a crank's input row and drawn angle (rad) and pivot. Each moving point's holder
    ``holder`` and factor ``factor``."""

    kind: np.ndarray
    b1: np.ndarray
    b2: np.ndarray
    ref1: np.ndarray
    ref2: np.ndarray
    k1: np.ndarray
    k2: np.ndarray
    r1: np.ndarray
    r2: np.ndarray
    step: np.ndarray
    fold2: np.ndarray
    floor: np.ndarray
    index: np.ndarray
    drawn: np.ndarray
    names: tuple[str, ...]
    holder: np.ndarray
    factor: np.ndarray
    bodies: int


def encode(prog: Program, feasibility_tol: float) -> Encoded:
    """The program's ops and moving points as :class:`Encoded` arrays (``feasibility_tol`` the margin's allowance,
    as :func:`linkgen.kinematics.fused.run`'s)."""
    index = {body: i for i, body in enumerate(prog.bodies)}
    rows: list[tuple[Any, ...]] = []
    for op in prog.ops:
        if isinstance(op, CrankOp):
            pivot = prog.drawn[op.pivot]
            rows.append((CRANK, index[op.body], -1, -1, -1, pivot, 0j, 0.0, 0.0, 0, -1.0, 0.0, op.index, op.drawn))
        else:
            assert isinstance(op, RRROp)
            ks = []
            refs = []
            for ref, pin in zip(op.refs, op.pins, strict=True):
                xd = prog.drawn[pin]
                refs.append(-1 if ref is None else index[ref])
                ks.append(xd if ref is None else prog.frames[ref].factor(xd))
            fold2 = op.fold_reach ** 2 if op.deltoid else -1.0
            floor = -(feasibility_tol * 2.0 * op.r1 * op.r2) ** 2
            rows.append((RRR, index[op.bodies[0]], index[op.bodies[1]], refs[0], refs[1], ks[0], ks[1], op.r1, op.r2,
                         op.step, fold2, floor, 0, 0.0))
    cols = list(zip(*rows, strict=True))
    ints = [np.array(cols[i], dtype=np.int64) for i in (0, 1, 2, 3, 4, 9, 12)]
    moving = [(name, holder, xd) for name, holder, xd in prog.points if holder is not None]
    return Encoded(ints[0], ints[1], ints[2], ints[3], ints[4],
                   np.array(cols[5], dtype=complex), np.array(cols[6], dtype=complex),
                   np.array(cols[7], dtype=float), np.array(cols[8], dtype=float), ints[5],
                   np.array(cols[10], dtype=float), np.array(cols[11], dtype=float), ints[6],
                   np.array(cols[13], dtype=float), tuple(name for name, _, _ in moving),
                   np.array([index[h] for _, h, _ in moving], dtype=np.int64),
                   np.array([prog.frames[h].factor(xd) for _, h, xd in moving], dtype=complex), len(prog.bodies))


def positions(enc: Encoded, x: np.ndarray, signs: list[np.ndarray] | list[float],
              threads: int | None = None) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Every moving point (complex, mm) at poses ``x`` (k, n) and whether each pose is in reach, on the branches
    ``signs`` (one per step: a number, or one a pose); ``threads`` the runs the poses are cut into (default: numba's
    threads). Raises :class:`~linkgen.kinematics.fused.Folded` where a deltoid's pins meet."""
    n = x.shape[1]
    steps = len(signs)
    per_pose = any(np.ndim(g) for g in signs)
    table = np.empty((steps, n if per_pose else 1))
    for row in range(steps):
        table[row] = np.asarray(signs[row], dtype=float)
    out = np.empty((len(enc.names), n), dtype=complex)
    ok = np.ones(n, dtype=np.uint8)
    kernel = _kernel()
    import numba

    runs = max(1, min(numba.get_num_threads() if threads is None else int(threads), n))
    folded = kernel(np.ascontiguousarray(x, dtype=float), table, enc.kind, enc.b1, enc.b2, enc.ref1, enc.ref2,
                    enc.k1, enc.k2, enc.r1, enc.r2, enc.step, enc.fold2, enc.floor, enc.index, enc.drawn,
                    enc.holder, enc.factor, enc.bodies, runs, out, ok)
    if folded <= 0.0:
        raise Folded
    return dict(zip(enc.names, out, strict=True)), ok.view(bool)


@functools.cache
def _kernel() -> Any:
    """The compiled kernel, built on first use (numba compiles it once a process, from its cache where it can)."""
    import numba

    return numba.njit(parallel=True, cache=True, nogil=True)(_poses)


def _poses(x: np.ndarray, table: np.ndarray, kind: np.ndarray, b1: np.ndarray, b2: np.ndarray, ref1: np.ndarray,
           ref2: np.ndarray, k1: np.ndarray, k2: np.ndarray, r1: np.ndarray, r2: np.ndarray, step: np.ndarray,
           fold2: np.ndarray, floor: np.ndarray, index: np.ndarray, drawn: np.ndarray, holder: np.ndarray,
           factor: np.ndarray, bodies: int, runs: int, out: np.ndarray, ok: np.ndarray) -> float:
    """The kernel's source (compiled by :func:`_kernel`): poses ``x`` cut into ``runs`` contiguous runs, each run
    into blocks of :data:`BLOCK` poses; each op of :class:`Encoded` over a block in one branch-free loop (which the
    compiler turns into vector instructions), the bodies' anchors and vectors held for the block only; the ground
    is one more body (anchor 0, vector 1), so a pin's world point is ``P + a k`` wherever it lies. Writes ``out`` and
    ``ok`` (0 where a pose is out of reach); returns the least squared distance of a deltoid's pins less its squared
    fold reach (negative: they met)."""
    n = x.shape[1]
    per_pose = table.shape[1] > 1
    nearest = np.full(runs, np.inf)
    for run in prange(runs):
        lo, hi = run * n // runs, (run + 1) * n // runs
        pr = np.zeros((bodies + 1, BLOCK))
        pi = np.zeros((bodies + 1, BLOCK))
        vr = np.ones((bodies + 1, BLOCK))
        vi = np.zeros((bodies + 1, BLOCK))
        sg = np.empty(BLOCK)
        tmp = np.empty((10, BLOCK))
        near = np.inf
        for start in range(lo, hi, BLOCK):
            m = min(BLOCK, hi - start)
            for j in range(kind.shape[0]):
                u, w = b1[j], b2[j]
                if kind[j] == CRANK:
                    row, th0, cr, ci = index[j], drawn[j], k1[j].real, k1[j].imag
                    for c in range(m):
                        th = x[row, start + c] - th0
                        pr[u, c] = cr
                        pi[u, c] = ci
                        vr[u, c] = math.cos(th)
                        vi[u, c] = math.sin(th)
                    continue
                g1 = ref1[j] if ref1[j] >= 0 else bodies
                g2 = ref2[j] if ref2[j] >= 0 else bodies
                a1r, a1i, a2r, a2i = k1[j].real, k1[j].imag, k2[j].real, k2[j].imag
                s1, s2 = r1[j] + r2[j], r1[j] - r2[j]
                s1, s2, dr2 = s1 * s1, s2 * s2, r1[j] * r1[j] - r2[j] * r2[j]
                low, srow = floor[j], step[j]
                if per_pose:
                    for c in range(m):
                        sg[c] = table[srow, start + c]
                else:
                    sg[:m] = table[srow, 0]
                for c in range(m):           # reads the bodies' rows, writes only the dyad's own rows
                    x1 = pr[g1, c] + vr[g1, c] * a1r - vi[g1, c] * a1i
                    y1 = pi[g1, c] + vr[g1, c] * a1i + vi[g1, c] * a1r
                    x2 = pr[g2, c] + vr[g2, c] * a2r - vi[g2, c] * a2i
                    y2 = pi[g2, c] + vr[g2, c] * a2i + vi[g2, c] * a2r
                    dx, dy = x2 - x1, y2 - y1
                    dd = dx * dx + dy * dy
                    prod = (s1 - dd) * (dd - s2)
                    inv = 0.5 / dd if dd > 0.0 else 0.5
                    along = inv * dr2 + 0.5
                    height = math.sqrt(max(prod, 0.0)) * inv * sg[c]
                    ax, ay = dx * along - dy * height, dx * height + dy * along
                    tmp[0, c], tmp[1, c], tmp[2, c], tmp[3, c] = x1, y1, ax, ay
                    tmp[4, c], tmp[5, c], tmp[6, c], tmp[7, c] = x2, y2, x1 + ax - x2, y1 + ay - y2
                    tmp[8, c], tmp[9, c] = dd, prod
                for c in range(m):
                    pr[u, c], pi[u, c], vr[u, c], vi[u, c] = tmp[0, c], tmp[1, c], tmp[2, c], tmp[3, c]
                    pr[w, c], pi[w, c], vr[w, c], vi[w, c] = tmp[4, c], tmp[5, c], tmp[6, c], tmp[7, c]
                    ok[start + c] &= tmp[9, c] >= low
                if fold2[j] >= 0.0:
                    for c in range(m):
                        near = min(near, tmp[8, c] - fold2[j])
            for p in range(holder.shape[0]):
                h, fr, fi = holder[p], factor[p].real, factor[p].imag
                for c in range(m):
                    out[p, start + c] = complex(pr[h, c] + vr[h, c] * fr - vi[h, c] * fi,
                                                pi[h, c] + vr[h, c] * fi + vi[h, c] * fr)
        nearest[run] = near
    return nearest.min()
