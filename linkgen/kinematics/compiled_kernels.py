"""The compiled kernels of :mod:`linkgen.kinematics.compiled` (numba): imported only where the compiled path is
asked for, so that numba (and its start-up) is never a cost of the default numpy path. See that module for the
construction; every function here is compiled on first use and cached by numba where the package folder allows."""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from linkgen.kinematics.compiled import BLOCK, CRANK


@njit(parallel=True, cache=True, nogil=True, error_model="numpy")
def poses(x: np.ndarray, table: np.ndarray, kind: np.ndarray, b1: np.ndarray, b2: np.ndarray, ref1: np.ndarray,
           ref2: np.ndarray, k1: np.ndarray, k2: np.ndarray, r1: np.ndarray, r2: np.ndarray, step: np.ndarray,
           fold2: np.ndarray, floor: np.ndarray, index: np.ndarray, drawn: np.ndarray, holder: np.ndarray,
           factor: np.ndarray, bodies: int, runs: int, speeds: np.ndarray, out: np.ndarray, vel: np.ndarray,
           acc: np.ndarray, ok: np.ndarray) -> float:
    """Poses ``x`` cut into ``runs`` contiguous runs, each run
    into blocks of :data:`BLOCK` poses; each op of :class:`Encoded` over a block in one branch-free loop (which the
    compiler turns into vector instructions), the bodies' anchors and vectors held for the block only; the ground
    is one more body (anchor 0, vector 1), so a pin's world point is ``P + a k`` wherever it lies. Writes ``out`` and
    ``ok`` (0 where a pose is out of reach), and where ``vel`` has rows each point's velocity and acceleration into
    ``vel`` and ``acc`` (the inputs turning at ``speeds``, rad per unit time, constant): each body's anchor velocity
    and acceleration, angular velocity w and acceleration al held for the block beside its pose, each dyad's 2x2
    closure i w1 a - i w2 b = v2 - v1 solved in closed form (a, b its bodies' vectors to the joint; +-inf where
    a x b = 0, as the numpy kernels' rule). Returns the least squared distance of a deltoid's pins less its squared
    fold reach (negative: they met)."""
    n = x.shape[1]
    rates = vel.shape[0] > 0
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
        # each body's anchor velocity (x, y), acceleration (x, y), w and al; the ground's row all zero
        st = np.zeros((6, bodies + 1, BLOCK))
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
                    if rates:                # about a ground pivot at constant speed
                        st[4, u, :m] = speeds[row]
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
                if rates:
                    _dyad_rates(st, pr, vr, vi, tmp, g1, g2, a1r, a1i, a2r, a2i, u, w, m)
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
                    rx, ry = vr[h, c] * fr - vi[h, c] * fi, vr[h, c] * fi + vi[h, c] * fr
                    out[p, start + c] = complex(pr[h, c] + rx, pi[h, c] + ry)
                    if rates:                # v = vP + i w r, acc = aP + (-w^2 + i al) r; NaN past a toggle: inf
                        om, al = st[4, h, c], st[5, h, c]
                        vx, vy = st[0, h, c] - om * ry, st[1, h, c] + om * rx
                        cx = st[2, h, c] - om * om * rx - al * ry
                        cy = st[3, h, c] - om * om * ry + al * rx
                        vel[p, start + c] = complex(_bounded(vx), _bounded(vy))
                        acc[p, start + c] = complex(_bounded(cx), _bounded(cy))
        nearest[run] = near
    return nearest.min()


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
