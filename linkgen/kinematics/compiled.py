"""An optional compiled path for the fused kernels' positions and rates: the same construction as
:mod:`linkgen.kinematics.fused`, in machine code (numba), a block of poses through the whole program at once.

numpy's kernels make a dozen passes over memory per dyad (each an array of all poses); past about 10^4 poses their
speed is the memory's. Here a block of :data:`BLOCK` poses goes through every op while its bodies' anchors and
vectors stay in the first-level cache, each op one loop the compiler turns into vector instructions (the crank's
cosine and sine too: :func:`~linkgen.kinematics.compiled_kernels.sincos`, not the C library's one value at a time),
and only the joints' positions are written. A run of fewer than :data:`SPLIT` poses stays on the calling thread;
a longer one is cut into chunks (:func:`chunk_size`: a share a thread, at most :data:`CHUNK` poses) that numba's
threads take in turn. numpy stays the default: this path is taken only when asked
for (``Linkage.positions(..., engine="numba")``) and numba is installed (``pip install 'camgen[fast]'``).

The construction is :mod:`~linkgen.kinematics.fused`'s: the crank turned by its angle from the drawing; an RRR's
joint at ``p1 + d (along + i height)`` from its pins' frame (``d = p2 - p1``, height on the branch's side, from the
triangle's squared area ``((r1 + r2)^2 - dd)(dd - (r1 - r2)^2)``); each body's drawn point ``x`` at
``P + a f (x - pd)``; with rates each dyad's 2x2 closure in closed form, as there. So its results equal the numpy
kernels' to rounding (about 1e-13 mm on the bundled legs, rates to about 1e-14 relative; the crank's cosine and sine
within 1.2e-16 of 50 digits). A deltoid whose equal-radius pins meet raises
:class:`~linkgen.kinematics.fused.Folded`, as there.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkgen.kinematics.fused import CrankOp, Folded, Program, RRROp


#: op kinds in :class:`Encoded`
CRANK, RRR = 0, 1
#: poses a block of the kernel holds (each body's anchor and vector: 4 x 8 bytes a pose): with a dozen bodies and the
#: dyad's own ten rows well within a core's 32 KiB first-level cache (measured on the bundled legs: 64 a little
#: faster than 128, 256 by about a tenth, 512 by a third)
BLOCK = 64
#: poses a chunk of the parallel kernel (the threads take chunks in turn); a run of fewer than two chunks, or one
#: thread, runs on the calling thread without waking numba's pool
CHUNK = 8192
#: the fewest poses a run shares among numba's threads (below it one thread runs them all: waking the pool takes
#: some microseconds, the poses of a chunk about 30 ns each)
SPLIT = 2048
#: |crank angle - drawn| (rad) up to which the kernel's own cosine and sine hold (their reduction's products exact);
#: past it (about 43 million turns) the C library's
TRIG_REACH = 2.0 ** 28


def available() -> bool:
    """Whether numba can be imported (the compiled path's one requirement)."""
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


@dataclass(frozen=True)
class Encoded:
    """A :class:`~linkgen.kinematics.fused.Program` as flat arrays for the kernel (few arrays: each is a cost of
    every call). ``ops`` (n_ops, 7) integers, one row an op: its kind (CRANK or RRR), its bodies' indices (an
    RRR's two; a crank's first), the bodies its pins lie on (-1: the ground), the branch's row in the signs, a
    crank's input row. ``nums`` (n_ops, 9) floats: each pin's factor (re, im; its world point is ``P + a k`` on a
    body, ``k`` itself on the ground; a crank's pivot in the first), the radii (mm), the squared fold reach
    (deltoids; -1: none), the squared margin floor and a crank's drawn angle (rad). Each moving point's
    ``holder`` and ``factor`` (n_points, 2: re, im)."""

    ops: np.ndarray
    nums: np.ndarray
    names: tuple[str, ...]
    holder: np.ndarray
    factor: np.ndarray
    bodies: int


def encode(prog: Program, feasibility_tol: float) -> Encoded:
    """The program's ops and moving points as :class:`Encoded` arrays (``feasibility_tol`` the margin's allowance,
    as :func:`linkgen.kinematics.fused.run`'s)."""
    index = {body: i for i, body in enumerate(prog.bodies)}
    ops: list[tuple[int, ...]] = []
    nums: list[tuple[float, ...]] = []
    for op in prog.ops:
        if isinstance(op, CrankOp):
            pivot = prog.drawn[op.pivot]
            ops.append((CRANK, index[op.body], -1, -1, -1, 0, op.index))
            nums.append((pivot.real, pivot.imag, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, op.drawn))
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
            ops.append((RRR, index[op.bodies[0]], index[op.bodies[1]], refs[0], refs[1], op.step, 0))
            nums.append((ks[0].real, ks[0].imag, ks[1].real, ks[1].imag, op.r1, op.r2, fold2, floor, 0.0))
    moving = [(name, holder, xd) for name, holder, xd in prog.points if holder is not None]
    factor = [prog.frames[h].factor(xd) for _, h, xd in moving]
    return Encoded(np.array(ops, dtype=np.int64).reshape(-1, 7), np.array(nums, dtype=float).reshape(-1, 9),
                   tuple(name for name, _, _ in moving), np.array([index[h] for _, h, _ in moving], dtype=np.int64),
                   np.array([(f.real, f.imag) for f in factor], dtype=float).reshape(-1, 2), len(prog.bodies))


@dataclass(frozen=True)
class Poses:
    """The kernel's results: each moving point's position (complex, mm), with rates its velocity and acceleration
    (complex, mm per unit time and its square; empty without), and whether each pose is in reach."""

    points: dict[str, np.ndarray]
    velocities: dict[str, np.ndarray]
    accelerations: dict[str, np.ndarray]
    ok: np.ndarray


def positions(enc: Encoded, x: np.ndarray, signs: list[np.ndarray] | list[float], threads: int | None = None,
              speeds: np.ndarray | None = None) -> Poses:
    """Every moving point (complex, mm) at poses ``x`` (k, n) and whether each pose is in reach, on the branches
    ``signs`` (one per step: a number, or one a pose); with ``speeds`` (the inputs' constant speeds, (k,)) each
    point's velocity and acceleration too. ``threads``: 1 keeps every pose on the calling thread; else numba's
    threads (their number numba's: ``NUMBA_NUM_THREADS``, ``numba.set_num_threads``) take chunks of :data:`CHUNK`
    poses in turn, where there are at least two. The results are the same bits either way.
    Raises :class:`~linkgen.kinematics.fused.Folded` where a deltoid's pins meet."""
    n = x.shape[1]
    if any(np.ndim(g) for g in signs):
        table = np.empty((len(signs), n))
        for row, g in enumerate(signs):
            table[row] = np.asarray(g, dtype=float)
    else:
        table = np.array(signs, dtype=float).reshape(len(signs), 1)
    shape = (len(enc.names), n)
    out = np.empty(shape, dtype=complex)
    rated = speeds is not None
    vel, acc = (np.empty(shape, dtype=complex), np.empty(shape, dtype=complex)) if rated else (_NONE, _NONE)
    ok = np.empty(n, dtype=np.uint8)
    rates = _ONE if speeds is None else np.asarray(speeds, dtype=float).reshape(x.shape[0])
    args = (np.ascontiguousarray(x, dtype=float), table, enc.ops, enc.nums, enc.holder, enc.factor, enc.bodies,
            rates, out, vel, acc, ok)
    kernels = _kernels()
    with warnings.catch_warnings():
        # numba says once, when it starts its threads (the first parallel run, or the first question of how many
        # there are), that it passed over an older TBB for another threading layer
        warnings.filterwarnings("ignore", message=r".*TBB threading layer")
        size = chunk_size(n, 1 if threads == 1 else kernels.threads())
        folded = kernels.poses_serial(*args) if size >= n else kernels.poses_parallel(*args, size)
    if folded <= 0.0:
        raise Folded

    def named(z: np.ndarray) -> dict[str, np.ndarray]:
        return dict(zip(enc.names, z, strict=True)) if len(z) else {}

    return Poses(named(out), named(vel) if rated else {}, named(acc) if rated else {}, ok.view(bool))


def chunk_size(n: int, threads: int) -> int:
    """The poses a chunk of a run of ``n`` poses on ``threads`` threads: one nearly equal share a thread, in whole
    blocks, up to :data:`CHUNK` (a run of 10^4 poses on two threads is two chunks of 5 056, not one thread's 8 192
    and the other's 1 808; a long run many chunks of CHUNK, which the threads take in turn); ``n`` itself (one
    chunk, on the calling thread) for one thread or fewer than :data:`SPLIT` poses, where waking numba's pool costs
    more than the second core wins."""
    if threads <= 1 or n < SPLIT:
        return max(n, 1)
    share = -(-n // threads)
    return min(CHUNK, -(-share // BLOCK) * BLOCK)


#: no rates asked for: the kernel's velocity and acceleration outputs have no rows
_NONE = np.empty((0, 0), dtype=complex)
#: no rates asked for: the inputs' speeds the kernel is given (unread)
_ONE = np.ones(1)


def _kernels() -> Any:
    """The compiled kernels' module (:mod:`linkgen.kinematics.compiled_kernels`, imported here so that numba is
    imported only when the compiled path is asked for; numba compiles them once a process, from its cache where it
    can)."""
    from linkgen.kinematics import compiled_kernels

    return compiled_kernels
