"""A vectorised solver of the Stephenson II's triad: every design of a population at every crank angle at once.

The Stephenson II searched (:data:`linkgen.synthesis.sixbar_types.STEPHENSON2`) is a ternary crank (O2, A, E)
turning about O2 and a triad, the class-III Assur group: the plate (C, D, F) held by three binary links, A-C and
E-D to the crank's pins and O4-F to the ground. With the crank placed, the plate's turn psi (rad, counter-clockwise,
0 as drawn) is the one unknown: at a given psi the plate's vectors c = C - F and d = D - F are known, and F lies on
three circles, about O4 (radius l3 = |O4-F|), about A - R c (l1 = |A-C|) and about E - R d (l2 = |E-D|), R = e^{i psi}.
Two differences of the circles' equations are linear in F: F is their radical centre, ``F - O4 = N / det`` by
Cramer's rule, with no branch to choose; the third circle's equation is left as one scalar equation in psi,

    h(psi) = |N|^2 - l3^2 det^2 = 0,

a trigonometric polynomial of degree 4 (N is of degree 2 in cos psi and sin psi, det of degree 2), so nine samples
over a turn give it exactly (its five Fourier coefficients by a real FFT) and it is read on a grid of
:data:`GRID` plate turns by one matrix product. Each of the triad's assemblies at a crank angle is a root of h: the
sign changes on the grid bracket them, :data:`COARSE` Newton steps on the Fourier form place them, and the root
drawn (psi = 0 at the drawn crank angle) is followed by continuity: from each crank angle to the next, each root's
nearest root (circularly), the maps composed along the turn by doubling (no Python work per angle). A step is
clean when the root it lands on has the root it came from as its own nearest, and moves at most half as far as the
next-nearest root lies; a turn is clean when every step is and the root followed comes back to the drawn one after
the turn. Anything else (a jump to another assembly, a root lost at a toggle, another assembly after a turn) is a
branch defect: the design is refused. The root followed is then polished by :data:`POLISH` Newton steps on h
evaluated directly.

Transmission: with binary i's pin on the plate at p_i and the lines of the other two binaries meeting at Q (the
plate's instant centre were binary i taken away), p_i would move square to p_i - Q; binary i pushes along its own
line u_i; the transmission angle mu_i is 90 degrees less the angle between the two (the four-bar's, when the two
binaries meet at one pin), ``sin mu_i = dist(Q, line i) / |p_i - Q|``. All three are 0 where the three lines meet
in one point (the triad's toggle); the triad's transmission is the least of them.
Units: the drawing's (the search's normalised drawing, or mm), angles in rad counter-clockwise.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: the plate turns at which h is read for its sign changes (evenly over a turn, offset half a step from the drawn
#: psi = 0): two roots closer than a step may be missed, which loses the root followed only near a toggle
GRID = 48
#: Newton steps on the Fourier form of h for every bracketed root, then on h itself for the root followed
COARSE, POLISH = 3, 3
#: the nine plate turns that give h's Fourier coefficients exactly (its degree is 4)
SAMPLES = 9
TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Triad:
    """A population's triads as drawn: (N,) complex each, the crank's pins A, E about O2 = 0, the plate's pins C, D,
    F and the ground pivot O4."""

    a: np.ndarray
    e: np.ndarray
    c: np.ndarray
    d: np.ndarray
    f: np.ndarray
    o4: np.ndarray

    @property
    def lengths(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The binaries' lengths |A-C|, |E-D|, |O4-F| (N,)."""
        return np.abs(self.c - self.a), np.abs(self.d - self.e), np.abs(self.f - self.o4)


@dataclass(frozen=True)
class TriadSolution:
    """The triads at the crank turns asked for: the plate's turn psi (N, J) rad from its drawing, the pins C, D, F
    (N, J) complex, the triad's transmission angle (N, J) rad, and whether each design's turn was clean (N,)."""

    psi: np.ndarray
    c: np.ndarray
    d: np.ndarray
    f: np.ndarray
    transmission: np.ndarray
    clean: np.ndarray


def _h(t: Triad, a: np.ndarray, e: np.ndarray, psi: np.ndarray, derivative: bool = False
       ) -> tuple[np.ndarray, np.ndarray]:
    """h and F - O4 (complex, from N / det) at plate turns psi, the crank's pins at a, e (broadcast together);
    with ``derivative``, dh/dpsi in place of F - O4."""
    l1, l2, l3 = (v.reshape(v.shape + (1,) * (psi.ndim - 1)) for v in t.lengths)

    def col(v: np.ndarray) -> np.ndarray:
        return v.reshape(v.shape + (1,) * (psi.ndim - 1))

    rot = np.exp(1j * psi)
    cv, dv, o4 = col(t.c - t.f), col(t.d - t.f), col(t.o4)
    u = a - rot * cv - o4                     # the second and third circles' centres, from O4
    w = e - rot * dv - o4
    b1 = 0.5 * (np.abs(u) ** 2 - l1**2 + l3**2)
    b2 = 0.5 * (np.abs(w) ** 2 - l2**2 + l3**2)
    det = u.real * w.imag - u.imag * w.real
    nx, ny = b1 * w.imag - b2 * u.imag, b2 * u.real - b1 * w.real
    h = nx**2 + ny**2 - (l3 * det) ** 2
    if not derivative:
        return h, (nx + 1j * ny) / np.where(det == 0.0, np.nan, det)
    du, dw = -1j * rot * cv, -1j * rot * dv
    db1 = u.real * du.real + u.imag * du.imag
    db2 = w.real * dw.real + w.imag * dw.imag
    ddet = du.real * w.imag + u.real * dw.imag - du.imag * w.real - u.imag * dw.real
    dnx = db1 * w.imag + b1 * dw.imag - db2 * u.imag - b2 * du.imag
    dny = db2 * u.real + b2 * du.real - db1 * w.real - b1 * dw.real
    return h, 2.0 * (nx * dnx + ny * dny) - 2.0 * l3**2 * det * ddet


def _wrap(x: np.ndarray) -> np.ndarray:
    """Angles to [-pi, pi] (NaN kept)."""
    return x - TWO_PI * np.round(x / TWO_PI)


def _trig(coef: np.ndarray, psi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The trigonometric polynomial of real coefficients ``coef`` (..., 9: the constant, then cos n psi and sin n
    psi for n = 1..4) and its derivative at psi (..., k)."""
    c1, s1 = np.cos(psi), np.sin(psi)
    cn, sn = c1, s1
    f = np.broadcast_to(coef[..., :1], psi.shape).copy()
    df = np.zeros_like(f)
    for k in range(1, (coef.shape[-1] + 1) // 2):
        a, b = coef[..., k:k + 1], coef[..., 4 + k:5 + k]
        f += a * cn + b * sn
        df += k * (b * cn - a * sn)
        cn, sn = cn * c1 - sn * s1, sn * c1 + cn * s1
    return f, df


def _roots(t: Triad, a: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Every assembly's plate turn (N, J, R) rad in [0, 2 pi) at the crank's pins a, e (N, J), R the most found at
    any, the slots of fewer roots NaN: sign changes of h on the grid, placed by Newton on h's Fourier form."""
    m = np.arange(SAMPLES) * TWO_PI / SAMPLES
    h, _ = _h(t, a[..., None], e[..., None], np.broadcast_to(m, (*a.shape, SAMPLES)))
    spectrum = np.fft.rfft(h, axis=-1) / SAMPLES
    spectrum[..., 1:] *= 2.0                  # h(psi) = Re sum_n spectrum_n e^{i n psi}, n = 0..4
    coef = np.concatenate([spectrum.real, -spectrum.imag[..., 1:]], axis=-1)          # constant, cos n, sin n
    grid = (np.arange(GRID) + 0.5) * TWO_PI / GRID
    harmonics = np.arange(1, spectrum.shape[-1])
    basis = np.vstack([np.ones(GRID), np.cos(np.outer(harmonics, grid)), np.sin(np.outer(harmonics, grid))])
    vals = coef @ basis                                                               # (N, J, GRID)
    nxt = coef @ np.roll(basis, -1, axis=1)
    change = (vals > 0) != (nxt > 0)
    most = max(1, int(np.max(np.sum(change, axis=-1), initial=1)))
    with np.errstate(divide="ignore", invalid="ignore"):
        psi = grid + (TWO_PI / GRID) * vals / (vals - nxt)
    # the bracketed roots first (at most 8: h's degree is 4), then Newton on them within their brackets
    psi = np.sort(np.where(change, psi, np.nan), axis=-1)[..., :most]
    found = np.isfinite(psi)
    psi = np.where(found, psi, 0.0)
    cell = TWO_PI / GRID                      # each root kept in its own bracket, so that no two become one
    lo = grid[0] + cell * np.floor((psi - grid[0]) / cell)
    for _ in range(COARSE):
        f, df = _trig(coef, psi)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = f / df
        psi = np.clip(psi - np.where(np.isfinite(step), step, 0.0), lo, lo + cell)
    return np.where(found, psi - TWO_PI * np.floor(psi / TWO_PI), np.nan)


def _follow(roots: np.ndarray, start: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The root slot followed at every crank angle (N, J) from slot ``start`` (N,) at the first, and whether each
    design's turn is clean (N,): the last crank angle's step goes back to the first's roots and must land on
    ``start``."""
    ahead = np.concatenate([roots[:, 1:], roots[:, :1]], axis=1)                     # (N, J, R) the next angle's
    gap = np.abs(_wrap(roots[..., :, None] - ahead[..., None, :]))                    # (N, J, R, R)
    gap[np.isnan(gap)] = np.inf
    forward = np.argmin(gap, axis=3)                                                  # slot at j -> slot at j + 1
    back = np.argmin(gap, axis=2)                                                     # slot at j + 1 -> slot at j
    composed = forward.copy()                 # composed[:, j] = the map from the first angle to angle j + 1
    step = 1
    while step < composed.shape[1]:
        composed[:, step:] = np.take_along_axis(composed[:, step:], composed[:, :-step], axis=2)
        step *= 2
    rows = np.arange(roots.shape[0])
    at = np.concatenate([start[:, None], composed[rows, :, start]], axis=1)           # (N, J + 1)
    here, there = at[:, :-1], at[:, 1:]
    row = np.take_along_axis(gap, here[..., None, None], axis=2)[:, :, 0]             # (N, J, R) from the root
    moved = np.take_along_axis(row, there[..., None], axis=2)[..., 0]
    second = np.partition(row, 1, axis=2)[..., 1] if row.shape[2] > 1 else np.full(moved.shape, np.inf)
    mutual = np.take_along_axis(back, there[..., None], axis=2)[..., 0] == here
    clean = np.all(mutual & np.isfinite(moved) & (moved <= 0.5 * second), axis=1) & (at[:, -1] == start)
    return here, clean


def transmission(a: np.ndarray, e: np.ndarray, o4: np.ndarray, c: np.ndarray, d: np.ndarray, f: np.ndarray
                 ) -> np.ndarray:
    """The triad's transmission angle (rad, in [0, pi/2]): the least of its three binaries' (the module's
    docstring), the pins complex (broadcast together)."""
    lines = []
    for start, pin in ((a, c), (e, d), (o4, f)):
        u = pin - start
        u = u / np.where(u == 0, 1.0, np.abs(u))
        lines.append(np.stack([u.imag, -u.real, u.real * pin.imag - u.imag * pin.real], axis=-1))
    det = np.abs(np.sum(lines[0] * np.cross(lines[1], lines[2]), axis=-1))
    out = np.full(det.shape, np.pi / 2)
    for i, pin in enumerate((c, d, f)):
        q = np.cross(lines[(i + 1) % 3], lines[(i + 2) % 3])
        reach = np.abs(pin * q[..., 2] - (q[..., 0] + 1j * q[..., 1]))
        with np.errstate(divide="ignore", invalid="ignore"):
            sin = np.where(reach > 0, det / reach, 0.0)
        out = np.minimum(out, np.arcsin(np.clip(sin, 0.0, 1.0)))
    return out


def solve(t: Triad, turns: np.ndarray) -> TriadSolution:
    """The triads (N designs) at crank turns ``turns`` (J,) or (N, J) rad from the drawn crank, counter-clockwise.

    Each design's turn is followed from its drawing in order of ``np.mod(turns, 2 pi)``, from the drawn turn 0 (put
    first) and back to it; the results are in the order asked for. ``clean`` is False for a design whose turn has
    a branch defect (the module's docstring), or whose polished roots do not close its circles to 1e-9 of its
    size; its poses are then not to be used.
    """
    n = len(t.a)
    turns = np.broadcast_to(np.asarray(turns, dtype=float), (n, np.shape(turns)[-1]))
    path = np.concatenate([np.zeros((n, 1)), np.mod(turns, TWO_PI)], axis=1)
    order = np.argsort(path, axis=1, kind="stable")         # the drawn turn 0 stays first
    path = np.take_along_axis(path, order, axis=1)
    rot = np.exp(1j * path)
    a, e = t.a[:, None] * rot, t.e[:, None] * rot
    roots = _roots(t, a, e)
    drawn = np.argmin(np.where(np.isnan(roots[:, 0]), np.inf, np.abs(_wrap(roots[:, 0]))), axis=1)
    slots, clean = _follow(roots, drawn)
    clean &= np.abs(_wrap(np.take_along_axis(roots[:, 0], drawn[:, None], axis=1)[:, 0])) < 2.0 * TWO_PI / GRID
    psi = np.take_along_axis(roots, slots[..., None], axis=2)[..., 0]
    psi[:, 0] = 0.0                           # the drawing itself
    psi = np.where(np.isfinite(psi), psi, 0.0)
    for _ in range(POLISH):
        h, dh = _h(t, a, e, psi, derivative=True)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(dh != 0, h / dh, 0.0)
        psi = psi - np.where(np.isfinite(step), np.clip(step, -0.1, 0.1), 0.0)
    _, rel = _h(t, a, e, psi)
    f = t.o4[:, None] + rel
    r = np.exp(1j * psi)
    c, d = f + r * (t.c - t.f)[:, None], f + r * (t.d - t.f)[:, None]
    l1, l2, l3 = (v[:, None] for v in t.lengths)
    size = np.max(np.abs(np.stack([t.a, t.e, t.c, t.d, t.f, t.o4])), axis=0)[:, None]
    closes = np.maximum.reduce([np.abs(np.abs(c - a) - l1), np.abs(np.abs(d - e) - l2),
                                np.abs(np.abs(f - t.o4[:, None]) - l3)])
    clean &= np.all(np.where(np.isfinite(closes), closes, np.inf) <= 1e-9 * size, axis=1)
    mu = transmission(a, e, t.o4[:, None], c, d, f)
    back = np.empty_like(order)
    np.put_along_axis(back, order, np.arange(order.shape[1])[None, :].repeat(n, axis=0), axis=1)
    back = back[:, 1:]                        # where each turn asked for sits on the path

    def asked(v: np.ndarray) -> np.ndarray:
        return np.take_along_axis(v, back, axis=1)

    return TriadSolution(asked(_wrap(psi)), asked(c), asked(d), asked(f), asked(mu), clean)
