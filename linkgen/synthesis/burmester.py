"""Motion generation for four and five positions of a coupler line: Burmester theory, vectorised numpy.

Notation as :mod:`linkgen.synthesis.motion`: points are complex numbers (mm); position k puts the
coupler point at P_k with the coupler line at phi_k, so the coupler turns alpha_k = phi_k - phi_1
and the point moves delta_k = P_k - P_1 from the first position. A dyad is a ground pivot O (its
*centre point*) and a moving pivot A_1 drawn at the first position (its *circle point*), with
W = A_1 - O, Z = P_1 - A_1 and W (e^{i beta_k} - 1) + Z (e^{i alpha_k} - 1) = delta_k, beta_k the
dyad link's turn from the first position (counter-clockwise, rad).

Four positions give three such equations in the two unknowns W and Z: they have a solution only
where the 3x3 determinant of the system is zero, which expanded along the beta column reads
D_1 + D_2 e^{i beta_2} + D_3 e^{i beta_3} + D_4 e^{i beta_4} = 0, the loop of the *compatibility
linkage* (links D_k, complex numbers of the positions alone; D_1 = -(D_2 + D_3 + D_4)). Each beta_2
(the curve's parameter, swept over a turn) closes that loop in up to two ways (the two intersections
of a circle pair, the curve's two branches), and each closure gives W and Z by Cramer's rule on the
two best-conditioned equations: O traces the centre-point curve and A_1 the circle-point curve (the
classical circular cubics). Where the loop cannot close or the equations are singular (the trivial
root beta_k = alpha_k, a pivot at infinity), the curve has a gap (NaN).

Five positions add a fourth equation: the dyads that meet it too are the Ball-Burmester points,
where the centre-point curve of positions 1-4 meets that of positions 1, 2, 3, 5. Along the first
curve the fifth equation asks |delta_5 + W - Z (e^{i alpha_5} - 1)| = |W| (the link's length is
kept); its sign changes between samples of either branch are refined by Brent's method to the
roots, of which there are zero, two or four (real ones; a root closer than the sampling to another
or to a branch's end can be missed; a pivot at infinity, a slider's dyad, is left out).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from camgen.core.errors import SpecError

TWO_PI = 2.0 * math.pi
#: samples of the curve's parameter a branch searched for the five-position roots (then refined to 1e-15 rad)
ROOT_SAMPLES = 7200
#: a dyad link longer than this many times the positions' spread counts as a pivot at infinity (a slider's dyad)
FAR = 1e6
#: relative size of the compatibility linkage's links below which four positions leave the dyads undetermined
DEGENERATE = 1e-9


@dataclass(frozen=True)
class Dyads:
    """Dyads through the positions (arrays of one length): the curve's parameter ``beta2`` (rad), the ``branch``
    (+1 or -1), the link's turns from the first position to each other ``betas`` (n - 1 columns, rad, in [0, 2 pi)),
    the centre points ``centre`` (ground pivots) and circle points ``circle`` (moving pivots at the first position),
    complex, mm; NaN in a gap of the curve."""

    beta2: np.ndarray
    branch: np.ndarray
    betas: np.ndarray
    centre: np.ndarray
    circle: np.ndarray

    def take(self, keep: np.ndarray) -> Dyads:
        """The dyads where ``keep`` (a mask or indices)."""
        return Dyads(self.beta2[keep], self.branch[keep], self.betas[keep], self.centre[keep], self.circle[keep])


def poses(positions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The positions ``[x mm, y mm, angle degrees]`` (n, 3) as (P_k complex mm, alpha_k rad from the first)."""
    q = np.asarray(positions, dtype=float)
    return q[:, 0] + 1j * q[:, 1], np.radians(q[:, 2] - q[0, 2])


def compatibility(p: np.ndarray, alpha: np.ndarray) -> np.ndarray:
    """The compatibility linkage's links (D_1, D_2, D_3, D_4), complex mm, of the first four positions; raises a
    :class:`SpecError` on ``task.positions`` where they are all nearly zero (the coupler does not turn, or the
    positions leave every dyad free)."""
    f = np.exp(1j * alpha[1:4]) - 1.0
    d = p[1:4] - p[0]
    d2, d3, d4 = f[1] * d[2] - f[2] * d[1], -(f[0] * d[2] - f[2] * d[0]), f[0] * d[1] - f[1] * d[0]
    links = np.array([-(d2 + d3 + d4), d2, d3, d4])
    if np.max(np.abs(links)) <= DEGENERATE * max(float(np.max(np.abs(d))), 1e-300):
        raise SpecError("the coupler must turn between the positions (its angle differs) so that four positions "
                        "fix the dyads: give positions whose angles differ", "task.positions")
    return links


def _closures(links: np.ndarray, beta2: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """The compatibility loop closed at each ``beta2`` (rad): for each branch (+1, -1), (e^{i beta_3},
    e^{i beta_4}); NaN where it cannot close."""
    k1, k2, k3, k4 = links
    r = -(k1 + k2 * np.exp(1j * beta2))
    dist = np.abs(r)
    with np.errstate(divide="ignore", invalid="ignore"):
        a = (abs(k3) ** 2 - abs(k4) ** 2 + dist**2) / (2.0 * dist)
        h = np.sqrt(abs(k3) ** 2 - a * a)
        out = []
        for s in (1.0, -1.0):
            u = r / dist * (a + 1j * s * h)
            out.append((u / k3, (r - u) / k4))
    return out


def _solve(p: np.ndarray, alpha: np.ndarray, rot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(W, Z) from the dyad equations of positions 2-4 given e^{i beta_k} (m, 3): Cramer's rule on the pair of
    equations whose determinant is the largest; NaN where every pair is singular."""
    e = rot - 1.0
    f = np.exp(1j * alpha[1:4]) - 1.0
    d = p[1:4] - p[0]
    pairs = ((0, 1), (0, 2), (1, 2))
    dets = np.stack([e[:, j] * f[k] - e[:, k] * f[j] for j, k in pairs], axis=1)
    best = np.argmax(np.abs(dets), axis=1)
    rows = np.arange(len(e))
    j, k = np.array(pairs)[best].T
    det = dets[rows, best]
    scale = np.max(np.abs(e), axis=1) * np.max(np.abs(f))
    with np.errstate(divide="ignore", invalid="ignore"):
        w = (d[j] * f[k] - d[k] * f[j]) / det
        z = (e[rows, j] * d[k] - e[rows, k] * d[j]) / det
    bad = ~(np.abs(det) > 1e-12 * scale)
    return np.where(bad, np.nan, w), np.where(bad, np.nan, z)


def four_position_dyads(p: np.ndarray, alpha: np.ndarray, beta2: np.ndarray) -> Dyads:
    """The dyads of the first four positions at the curve's parameters ``beta2`` (rad; both branches, the +1 branch
    first): the centre-point and circle-point curves sampled there."""
    links = compatibility(p, alpha)
    parts = [_branch(p, alpha, links, np.asarray(beta2, dtype=float), s) for s in (1.0, -1.0)]
    return _joined(parts)


def _joined(parts: list[Dyads]) -> Dyads:
    """The dyads of ``parts`` one after the other."""
    return Dyads(*(np.concatenate([getattr(x, k) for x in parts]) for k in ("beta2", "branch", "betas", "centre",
                                                                             "circle")))


def _fifth(p: np.ndarray, alpha: np.ndarray, dyads: Dyads) -> np.ndarray:
    """How far the dyads miss the fifth position (mm): |delta_5 + W - Z (e^{i alpha_5} - 1)| - |W|."""
    w = dyads.circle - dyads.centre
    z = p[0] - dyads.circle
    return np.abs(p[4] - p[0] + w - z * (np.exp(1j * alpha[4]) - 1.0)) - np.abs(w)


def burmester_points(p: np.ndarray, alpha: np.ndarray) -> Dyads:
    """The Ball-Burmester dyads of five positions (those that meet all five), with the fifth link turn appended to
    ``betas``; none (empty arrays) where the curves do not meet."""
    links = compatibility(p, alpha)
    grid = np.linspace(0.0, TWO_PI, ROOT_SAMPLES + 1)
    size = max(float(np.max(np.abs(p - p[0]))), 1e-300)
    found: list[tuple[float, float]] = []
    for s in (1.0, -1.0):
        def miss(b: float, s: float = s) -> float:
            return float(_fifth(p, alpha, _branch(p, alpha, links, np.array([b]), s))[0])

        g = _fifth(p, alpha, _branch(p, alpha, links, grid, s))
        change = np.flatnonzero(np.isfinite(g[:-1]) & np.isfinite(g[1:]) & (np.sign(g[:-1]) != np.sign(g[1:])))
        for k in change:
            try:
                root = brentq(miss, grid[k], grid[k + 1], xtol=1e-15, maxiter=200)
            except ValueError:                      # the branch has a gap inside the interval: no root there
                continue
            dyad = _branch(p, alpha, links, np.array([root]), s)
            arm = float(np.abs(dyad.circle - dyad.centre)[0])
            # a sign change through a pivot at infinity is no root (nor is a pivot at infinity, a slider's dyad):
            # keep those the fifth equation holds at with the link within FAR of the positions' size
            held = math.isfinite(arm) and arm <= FAR * size and abs(miss(root)) <= 1e-9 * max(size, arm)
            if held and not any(s == t and abs(math.remainder(root - r, TWO_PI)) < 1e-9 for r, t in found):
                found.append((root, s))
    if not found:
        empty = np.zeros(0)
        return Dyads(empty, empty, np.zeros((0, 4)), empty.astype(complex), empty.astype(complex))
    d = _joined([_branch(p, alpha, links, np.array([b]), s) for b, s in found])
    a5 = p[4] - (p[0] - d.circle) * np.exp(1j * alpha[4])          # A_5 = P_5 - Z e^{i alpha_5}
    beta5 = np.mod(np.angle((a5 - d.centre) / (d.circle - d.centre)), TWO_PI)
    return Dyads(d.beta2, d.branch, np.column_stack([d.betas, beta5]), d.centre, d.circle)


def _branch(p: np.ndarray, alpha: np.ndarray, links: np.ndarray, beta2: np.ndarray, s: float) -> Dyads:
    """The dyads of one branch (``s`` = +1 or -1) of the four-position curves at ``beta2`` (rad)."""
    e3, e4 = _closures(links, beta2)[0 if s > 0 else 1]
    rot = np.column_stack([np.exp(1j * beta2), e3, e4])
    w, z = _solve(p, alpha, rot)
    circle = p[0] - z
    return Dyads(beta2, np.full(beta2.shape, s), np.mod(np.angle(rot), TWO_PI), circle - w, circle)
