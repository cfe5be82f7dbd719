"""An optional compiled path for the fused kernels' positions and rates: the same construction as
:mod:`linkgen.kinematics.fused`, one pose at a time in machine code (numba), every dyad of a pose in registers.

numpy's kernels make a dozen passes over memory per dyad (each an array of all poses); past about 10^4 poses their
speed is the memory's. Here each pose goes through the whole program at once: its bodies' anchors and vectors stay in
a few local numbers, and only the joints' positions are written. The poses are cut into one contiguous run per
thread (numba's ``prange``). numpy stays the default: this path is taken only when asked for
(``Linkage.positions(..., engine="numba")``) and numba is installed (``pip install 'camgen[fast]'``).

The construction is :mod:`~linkgen.kinematics.fused`'s: the crank turned by its angle from the drawing; an RRR's
joint at ``p1 + d (along + i height)`` from its pins' frame (``d = p2 - p1``, height on the branch's side, from the
triangle's squared area ``((r1 + r2)^2 - dd)(dd - (r1 - r2)^2)``); each body's drawn point ``x`` at
``P + a f (x - pd)``; with rates each dyad's 2x2 closure in closed form, as there. So its results equal the numpy
kernels' to rounding (about 1e-13 mm on the bundled legs, rates to about 1e-14 relative). A
deltoid whose equal-radius pins meet raises :class:`~linkgen.kinematics.fused.Folded`, as there.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkgen.kinematics.fused import CrankOp, Folded, Program, RRROp


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
    point's velocity and acceleration too. ``threads``: the runs the poses are cut into (default: numba's threads).
    Raises :class:`~linkgen.kinematics.fused.Folded` where a deltoid's pins meet."""
    n = x.shape[1]
    steps = len(signs)
    per_pose = any(np.ndim(g) for g in signs)
    table = np.empty((steps, n if per_pose else 1))
    for row in range(steps):
        table[row] = np.asarray(signs[row], dtype=float)
    shape = (len(enc.names), n)
    out = np.empty(shape, dtype=complex)
    rated = speeds is not None
    vel, acc = (np.empty(shape, dtype=complex), np.empty(shape, dtype=complex)) if rated else (_NONE, _NONE)
    ok = np.ones(n, dtype=np.uint8)
    kernel = _kernel()
    import numba

    rates = np.ones(x.shape[0]) if speeds is None else np.asarray(speeds, dtype=float).reshape(x.shape[0])
    with warnings.catch_warnings():
        # numba says once, when it starts its threads (asked their number, or the first parallel run), that it
        # passed over an older TBB for another threading layer
        warnings.filterwarnings("ignore", message=r".*TBB threading layer")
        runs = max(1, min(numba.get_num_threads() if threads is None else int(threads), n))
        folded = kernel(np.ascontiguousarray(x, dtype=float), table, enc.kind, enc.b1, enc.b2, enc.ref1, enc.ref2,
                        enc.k1, enc.k2, enc.r1, enc.r2, enc.step, enc.fold2, enc.floor, enc.index, enc.drawn,
                        enc.holder, enc.factor, enc.bodies, runs, rates, out, vel, acc, ok)
    if folded <= 0.0:
        raise Folded

    def named(z: np.ndarray) -> dict[str, np.ndarray]:
        return dict(zip(enc.names, z, strict=True)) if len(z) else {}

    return Poses(named(out), named(vel) if rated else {}, named(acc) if rated else {}, ok.view(bool))


#: no rates asked for: the kernel's velocity and acceleration outputs have no rows
_NONE = np.empty((0, 0), dtype=complex)


def _kernel() -> Any:
    """The compiled kernel (:mod:`linkgen.kinematics.compiled_kernels`, imported here so that numba is imported only
    when the compiled path is asked for; numba compiles it once a process, from its cache where it can)."""
    from linkgen.kinematics.compiled_kernels import poses

    return poses
