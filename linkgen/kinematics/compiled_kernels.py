"""The compiled kernels of :mod:`linkgen.kinematics.compiled` (numba): imported only where the compiled path is
asked for, so that numba (and its start-up) is never a cost of the default numpy path. See that module for the
construction; every function here is compiled on first use and cached by numba where the package folder allows.

Two entry points share one body (:func:`_run`, poses ``lo`` to ``hi`` block by block): :func:`poses_serial` on the
calling thread (no thread pool woken: a short run's fixed cost is the call's), and :func:`poses_parallel`, the poses
cut into chunks (:func:`~linkgen.kinematics.compiled.chunk_size`: :data:`~linkgen.kinematics.compiled.CHUNK` poses
on a long run, many more chunks than threads, so that a thread the system holds back delays one chunk, not half the
run; one nearly equal share a thread on a short one) that numba's threads take in turn. Each pose is computed alone,
so either gives the same bits.
"""
from __future__ import annotations

import math

import numpy as np
from numba import get_num_threads, njit, prange

from linkgen.kinematics.compiled import BLOCK, CRANK, TRIG_REACH

#: pi / 2 in three parts (Cody and Waite's, as Cephes's sine): the first two with trailing zero bits, so that k times
#: each is exact for |k| < 2^29; their sum is pi / 2 to about 1e-31
_PIO2_1, _PIO2_2, _PIO2_3 = 1.570796251296997, 7.549789415861596e-08, 5.390302858158119e-15
#: 2 / pi
_TWO_OVER_PI = 0.6366197723675814


@njit(cache=True, error_model="numpy")
def sincos(x: float) -> tuple[float, float]:
    """cos x and sin x to about 1 ulp of 1 (an absolute error below 1.2e-16) for |x| <= :data:`TRIG_REACH` rad,
    NaN for NaN or +-inf; branch-free (a select per quadrant), so that a loop of it becomes vector instructions
    (the C library's are called one value at a time, about half the kernel's time). Reduced by the nearest
    multiple k of pi / 2 (three-part pi / 2: r = x - k pi / 2 exact to about 1e-31 rad a turn), then Cephes's
    minimax polynomials on |r| <= pi / 4, the quadrant k mod 4 choosing and signing them."""
    k = np.floor(x * _TWO_OVER_PI + 0.5)
    r = x - k * _PIO2_1
    r = r - k * _PIO2_2
    r = r - k * _PIO2_3
    z = r * r
    s = r + r * z * (((((1.58962301576546568060e-10 * z - 2.50507477628578072866e-8) * z
                        + 2.75573136213857245213e-6) * z - 1.98412698295895385996e-4) * z
                      + 8.33333333332211858878e-3) * z - 1.66666666666666307295e-1)
    c = 1.0 - 0.5 * z + z * z * (((((-1.13585365213876817300e-11 * z + 2.08757008419747316778e-9) * z
                                    - 2.75573141792967388112e-7) * z + 2.48015872888517045348e-5) * z
                                  - 1.38888888888730564116e-3) * z + 4.16666666666665929218e-2)
    q = k - 4.0 * np.floor(k * 0.25)             # the quadrant, 0 to 3
    odd = q == 1.0 or q == 3.0
    cs = s if odd else c
    sn = c if odd else s
    cs = -cs if q == 1.0 or q == 2.0 else cs
    sn = -sn if q >= 2.0 else sn
    return cs, sn


def threads() -> int:
    """The threads numba's parallel kernel runs on (``NUMBA_NUM_THREADS``, or ``numba.set_num_threads``)."""
    return int(get_num_threads())


@njit(cache=True, nogil=True, error_model="numpy")
def poses_serial(x: np.ndarray, table: np.ndarray, ops: np.ndarray, nums: np.ndarray, holder: np.ndarray,
                 factor: np.ndarray, bodies: int, speeds: np.ndarray, out: np.ndarray, vel: np.ndarray,
                 acc: np.ndarray, ok: np.ndarray) -> float:
    """Every pose on the calling thread (see :func:`_run`)."""
    return _run(0, x.shape[1], x, table, ops, nums, holder, factor, bodies, speeds, out, vel, acc, ok)


@njit(parallel=True, cache=True, nogil=True, error_model="numpy")
def poses_parallel(x: np.ndarray, table: np.ndarray, ops: np.ndarray, nums: np.ndarray, holder: np.ndarray,
                   factor: np.ndarray, bodies: int, speeds: np.ndarray, out: np.ndarray, vel: np.ndarray,
                   acc: np.ndarray, ok: np.ndarray, size: int) -> float:
    """The poses in chunks of ``size``, numba's threads taking them in turn (see :func:`_run`)."""
    n = x.shape[1]
    chunks = -(-n // size)
    nearest = np.full(chunks, np.inf)
    for chunk in prange(chunks):
        nearest[chunk] = _run(chunk * size, min(n, (chunk + 1) * size), x, table, ops, nums, holder, factor,
                              bodies, speeds, out, vel, acc, ok)
    return nearest.min()


@njit(cache=True, nogil=True, error_model="numpy")
def _run(lo: int, hi: int, x: np.ndarray, table: np.ndarray, ops: np.ndarray, nums: np.ndarray, holder: np.ndarray,
         factor: np.ndarray, bodies: int, speeds: np.ndarray, out: np.ndarray, vel: np.ndarray, acc: np.ndarray,
         ok: np.ndarray) -> float:
    """Poses ``lo`` to ``hi`` of ``x``, in blocks of :data:`BLOCK` poses; each op of
    :class:`~linkgen.kinematics.compiled.Encoded` over a block in one branch-free loop (which the compiler turns into
    vector instructions), the bodies' anchors and vectors held for the block only (structure of arrays: a row a
    body and coordinate); the ground is one more body (anchor 0, vector 1), so a pin's world point is ``P + a k``
    wherever it lies. Writes ``out`` and ``ok`` (0 where a pose is out of reach: a dyad's squared area below its
    floor, or NaN), and where ``vel`` has rows each point's velocity and acceleration into ``vel`` and ``acc`` (the
    inputs turning at ``speeds``, rad per unit time, constant): each body's anchor velocity and acceleration,
    angular velocity w and acceleration al held for the block beside its pose, each dyad's 2x2 closure
    i w1 a - i w2 b = v2 - v1 solved in closed form (a, b its bodies' vectors to the joint; +-inf where a x b = 0,
    as the numpy kernels' rule). Returns the least squared distance of a deltoid's pins less its squared fold reach
    (negative: they met)."""
    rates = vel.shape[0] > 0
    per_pose = table.shape[1] > 1
    pr = np.zeros((bodies + 1, BLOCK))
    pi = np.zeros((bodies + 1, BLOCK))
    vr = np.ones((bodies + 1, BLOCK))
    vi = np.zeros((bodies + 1, BLOCK))
    sg = np.empty(BLOCK)
    bad = np.empty(BLOCK)                  # a pose's count of dyads out of reach (a float: one vector type a loop)
    tmp = np.empty((10, BLOCK))
    # each body's anchor velocity (x, y), acceleration (x, y), w and al; the ground's row all zero
    st = np.zeros((6, bodies + 1, BLOCK) if rates else (6, 1, 1))
    near = np.inf
    for start in range(lo, hi, BLOCK):
        m = min(BLOCK, hi - start)
        bad[:m] = 0.0
        for j in range(ops.shape[0]):
            u, w = ops[j, 1], ops[j, 2]
            if ops[j, 0] == CRANK:
                row, th0, cr, ci = ops[j, 6], nums[j, 8], nums[j, 0], nums[j, 1]
                for c in range(m):
                    co, si = sincos(x[row, start + c] - th0)
                    pr[u, c] = cr
                    pi[u, c] = ci
                    vr[u, c] = co
                    vi[u, c] = si
                for c in range(m):           # past the reduction's reach (never on a crank's few turns): libm's
                    th = x[row, start + c] - th0
                    if abs(th) > TRIG_REACH:
                        vr[u, c] = math.cos(th)
                        vi[u, c] = math.sin(th)
                if rates:                # about a ground pivot at constant speed
                    st[4, u, :m] = speeds[row]
                continue
            g1 = ops[j, 3] if ops[j, 3] >= 0 else bodies
            g2 = ops[j, 4] if ops[j, 4] >= 0 else bodies
            a1r, a1i, a2r, a2i = nums[j, 0], nums[j, 1], nums[j, 2], nums[j, 3]
            r1, r2 = nums[j, 4], nums[j, 5]
            s1, s2 = r1 + r2, r1 - r2
            s1, s2, dr2 = s1 * s1, s2 * s2, r1 * r1 - r2 * r2
            low, fold2, srow = nums[j, 7], nums[j, 6], ops[j, 5]
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
            if rates:
                _dyad_rates(st, pr, vr, vi, tmp, g1, g2, a1r, a1i, a2r, a2i, u, w, m)
            for c in range(m):
                pr[u, c], pi[u, c], vr[u, c], vi[u, c] = tmp[0, c], tmp[1, c], tmp[2, c], tmp[3, c]
                pr[w, c], pi[w, c], vr[w, c], vi[w, c] = tmp[4, c], tmp[5, c], tmp[6, c], tmp[7, c]
                bad[c] += 0.0 if tmp[9, c] >= low else 1.0
            if fold2 >= 0.0:
                for c in range(m):
                    near = min(near, tmp[8, c] - fold2)
        for c in range(m):
            ok[start + c] = bad[c] == 0.0
        for p in range(holder.shape[0]):
            h, fr, fi = holder[p], factor[p, 0], factor[p, 1]
            for c in range(m):
                rx, ry = vr[h, c] * fr - vi[h, c] * fi, vr[h, c] * fi + vi[h, c] * fr
                out[p, start + c] = complex(pr[h, c] + rx, pi[h, c] + ry)
            if rates:
                for c in range(m):           # v = vP + i w r, acc = aP + (-w^2 + i al) r; NaN past a toggle: inf
                    rx, ry = vr[h, c] * fr - vi[h, c] * fi, vr[h, c] * fi + vi[h, c] * fr
                    om, al = st[4, h, c], st[5, h, c]
                    vx, vy = st[0, h, c] - om * ry, st[1, h, c] + om * rx
                    cx = st[2, h, c] - om * om * rx - al * ry
                    cy = st[3, h, c] - om * om * ry + al * rx
                    vel[p, start + c] = complex(_bounded(vx), _bounded(vy))
                    acc[p, start + c] = complex(_bounded(cx), _bounded(cy))
    return near


@njit(cache=True, error_model="numpy")
def _bounded(v: float) -> float:
    """v, or +inf where it is NaN (rates past a toggle are unbounded, never NaN)."""
    return math.inf if v != v else v


@njit(cache=True, error_model="numpy")
def _over(num: float, den: float) -> float:
    """-num / den; +-inf where den is 0 (0 where both are): the numpy kernels' rule for the 2x2 solve."""
    if den != 0.0:
        return -num / den
    return 0.0 if num == 0.0 else math.copysign(math.inf, -num)


@njit(cache=True, error_model="numpy")
def _dyad_rates(st: np.ndarray, pr: np.ndarray, vr: np.ndarray, vi: np.ndarray, tmp: np.ndarray, g1: int, g2: int,
                a1r: float, a1i: float, a2r: float, a2i: float, u: int, w: int, m: int) -> None:
    """A dyad's bodies' rates over a block (compiled with the kernel): its pins' velocities and accelerations from
    the bodies they lie on (radius r = a k from each anchor), then w1 = -(dv . b) / (a x b), w2 = -(dv . a) / (a x b)
    and the same with the accelerations' right-hand side dc - w2^2 b + w1^2 a (``tmp`` holds the pins' positions and
    a, b as the kernel's dyad loop left them)."""
    for c in range(m):
        ra = (vr[g1, c] * a1r - vi[g1, c] * a1i, vr[g1, c] * a1i + vi[g1, c] * a1r)
        rb = (vr[g2, c] * a2r - vi[g2, c] * a2i, vr[g2, c] * a2i + vi[g2, c] * a2r)
        o1, l1, o2, l2 = st[4, g1, c], st[5, g1, c], st[4, g2, c], st[5, g2, c]
        v1x, v1y = st[0, g1, c] - o1 * ra[1], st[1, g1, c] + o1 * ra[0]
        c1x = st[2, g1, c] - o1 * o1 * ra[0] - l1 * ra[1]
        c1y = st[3, g1, c] - o1 * o1 * ra[1] + l1 * ra[0]
        v2x, v2y = st[0, g2, c] - o2 * rb[1], st[1, g2, c] + o2 * rb[0]
        c2x = st[2, g2, c] - o2 * o2 * rb[0] - l2 * rb[1]
        c2y = st[3, g2, c] - o2 * o2 * rb[1] + l2 * rb[0]
        ax, ay, bx, by = tmp[2, c], tmp[3, c], tmp[6, c], tmp[7, c]
        den = ay * bx - ax * by
        dvx, dvy = v2x - v1x, v2y - v1y
        w1, w2 = _over(dvx * bx + dvy * by, den), _over(dvx * ax + dvy * ay, den)
        dax = c2x - c1x - w2 * w2 * bx + w1 * w1 * ax
        day = c2y - c1y - w2 * w2 * by + w1 * w1 * ay
        al1, al2 = _over(dax * bx + day * by, den), _over(dax * ax + day * ay, den)
        st[0, u, c], st[1, u, c], st[2, u, c], st[3, u, c], st[4, u, c], st[5, u, c] = v1x, v1y, c1x, c1y, w1, al1
        st[0, w, c], st[1, w, c], st[2, w, c], st[3, w, c], st[4, w, c], st[5, w, c] = v2x, v2y, c2x, c2y, w2, al2
