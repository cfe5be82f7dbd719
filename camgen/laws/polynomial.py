"""Polynomial laws: 3-4-5, 4-5-6-7 and the general law from boundary conditions.

The general law is solved in normalised u on [0, 1] in the Chebyshev basis with
equilibrated rows, which keeps degree 20 and beyond accurate (raw powers of theta
would scale the system by beta^n and lose every digit by degree ~12).
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numpy.polynomial import Chebyshev, Polynomial
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from camgen.laws.base import Law, as_array, bounded, rows

#: most derivative orders a boundary condition may name
MAX_ORDER = 25
#: highest degree the general law accepts
MAX_DEGREE = 25


@dataclass(frozen=True)
class Bernstein:
    """A polynomial on u in [0, 1] in the Bernstein basis: sum_i coef[i] C(n, i) u^i (1 - u)^(n - i).

    Evaluated by de Casteljau's algorithm (stable at any degree); its derivative is the
    Bernstein polynomial of n times the coefficients' differences.
    """

    coef: np.ndarray

    def degree(self) -> int:
        return len(self.coef) - 1

    def deriv(self, order: int = 1) -> "Bernstein":
        c = np.asarray(self.coef, dtype=float)
        for _ in range(order):
            c = (len(c) - 1) * np.diff(c) if len(c) > 1 else np.zeros(1)
        return Bernstein(c)

    def __call__(self, u: ArrayLike) -> np.ndarray:
        u = np.atleast_1d(np.asarray(u, dtype=float))
        b = np.tile(np.asarray(self.coef, dtype=float), (len(u), 1))
        for _ in range(len(self.coef) - 1):
            b = (1 - u)[:, None] * b[:, :-1] + u[:, None] * b[:, 1:]
        return b[:, 0]


@dataclass(frozen=True)
class PolynomialLaw(Law):
    """A polynomial rise law f(u) held as a numpy series on the window u in [0, 1]."""

    name: ClassVar[str] = "polynomial"
    series: Chebyshev | Polynomial | Bernstein
    _derivs: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        s = self.series
        s.coef.setflags(write=False)
        object.__setattr__(self, "_derivs", (s, s.deriv(1), s.deriv(2), s.deriv(3)))

    @property
    def degree(self) -> int:
        return self.series.degree()

    def magnitude_bounds(self) -> np.ndarray:
        """Bounds on the magnitudes of f and its first three derivatives over [0, 1] from their coefficients: the
        largest in the Bernstein basis (its functions are positive and add up to 1), the sum of their magnitudes in
        the Chebyshev basis (each function within [-1, 1] on its window) and in powers of u (u in [0, 1])."""
        with np.errstate(all="ignore"):
            return np.array([np.abs(d.coef).max() if isinstance(d, Bernstein) else np.abs(d.coef).sum()
                             for d in self._derivs])

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u = as_array(u)
        return rows(*(d(u) for d in self._derivs))


def poly345() -> PolynomialLaw:
    """The 3-4-5 polynomial: f = 10u^3 - 15u^4 + 6u^5."""
    return PolynomialLaw(Polynomial([0, 0, 0, 10, -15, 6]))


def poly4567() -> PolynomialLaw:
    """The 4-5-6-7 polynomial: f = 35u^4 - 84u^5 + 70u^6 - 20u^7."""
    return PolynomialLaw(Polynomial([0, 0, 0, 0, 35, -84, 70, -20]))


def _condition_row(u: float, order: int, n_coef: int) -> np.ndarray:
    """d^order/du^order of each Chebyshev basis function T_j(2u - 1) at u."""
    eye = np.eye(n_coef)
    return np.array([Chebyshev(eye[j], domain=[0, 1]).deriv(order)(u) if order else
                     Chebyshev(eye[j], domain=[0, 1])(u) for j in range(n_coef)])


def _rank(a: np.ndarray) -> int:
    """Numerical rank, counting singular values above 1e-12 of the largest."""
    sv = np.linalg.svd(a, compute_uv=False)
    return int(np.sum(sv > sv[0] * 1e-12)) if sv.size and sv[0] > 0 else 0


def _two_point(conds: list[tuple], n: int) -> PolynomialLaw | None:
    """The law meeting conditions at u = 0 and u = 1 only, of consecutive orders from 0 at each end (a two-point
    Hermite problem: always exactly one polynomial of degree n = their number - 1); None for any other set.

    Solved in the Bernstein basis, where the k-th derivative at u = 0 involves only the first k + 1
    coefficients and at u = 1 only the last k + 1 (forward differences), so both ends are triangular
    solves; the law stays in that basis (its derivatives at the ends are the conditions, to rounding).
    """
    ends: dict[float, dict[int, float]] = {0.0: {}, 1.0: {}}
    for u, k, v in conds:
        if u not in ends or int(k) in ends[u]:
            return None
        ends[u][int(k)] = float(v)
    m, p = len(ends[0.0]), len(ends[1.0])
    if sorted(ends[0.0]) != list(range(m)) or sorted(ends[1.0]) != list(range(p)) or m + p != n + 1:
        return None
    c = np.zeros(n + 1)
    for k in range(m):                      # f^(k)(0) = n!/(n-k)! sum_i (-1)^(k-i) C(k, i) c_i
        scaled = ends[0.0][k] * math.factorial(n - k) / math.factorial(n)
        c[k] = scaled - sum((-1) ** (k - i) * math.comb(k, i) * c[i] for i in range(k))
    for k in range(p):                      # f^(k)(1) = n!/(n-k)! sum_i (-1)^i C(k, i) c_(n-i)
        scaled = ends[1.0][k] * math.factorial(n - k) / math.factorial(n)
        c[n - k] = (-1) ** k * (scaled - sum((-1) ** i * math.comb(k, i) * c[n - i] for i in range(k)))

    return PolynomialLaw(Bernstein(c))


def from_conditions(conditions: Sequence[Sequence[float]], degree: int | None = None) -> PolynomialLaw:
    """The polynomial rise law meeting boundary conditions in normalised units.

    Each condition is ``(u, order, value)``: the ``order``-th derivative of f = s/h
    with respect to u = theta/beta equals ``value`` at ``u`` in [0, 1] (so a slope of
    s' mm/rad is given as s' * beta / h). The degree defaults to the number of
    conditions minus one. The conditions must include f(0) = 0 and f(1) = 1, and
    must determine the polynomial exactly: too few independent conditions, or
    contradictory ones, raise :class:`SpecError` naming ``conditions``. Conditions at the two ends only, of
    consecutive orders from 0 at each, always do (see :func:`_two_point`), at any degree up to 25.

    Parameters
    ----------
    conditions : sequence of tuple
        The boundary conditions, each (u, order, value): u in [0, 1], a whole order 0 to 25, and the value of
        that derivative of f at u, in normalised units (a lift and an angle of 1).
    degree : int, optional
        The polynomial's degree, 1 to 25; by default the number of conditions less one.

    Returns
    -------
    PolynomialLaw
        The law, f and its first three derivatives within 1e12 on [0, 1].

    Raises
    ------
    SpecError
        Naming ``conditions``: an entry that is not three finite numbers, u outside [0, 1], an order out of range,
        conditions that contradict each other or are too few to fix the polynomial, a law that does not rise from
        f(0) = 0 to f(1) = 1 or whose values pass 1e12; naming ``degree``: a degree outside 1 to 25.
    """
    conds = [tuple(c) for c in conditions]
    for i, c in enumerate(conds):
        if len(c) != 3:
            raise SpecError(f"each condition is [u, order, value]; entry {i} has {len(c)} numbers", "conditions")
        u, order, value = c
        if not all(np.isfinite([u, order, value])):
            raise SpecError(f"entry {i} must hold finite numbers (got {list(c)})", "conditions")
        if not 0.0 <= u <= 1.0:
            raise SpecError(f"entry {i}: u must be in [0, 1] (got {u})", "conditions")
        if order != int(order) or not 0 <= order <= MAX_ORDER:
            raise SpecError(f"entry {i}: order must be a whole number 0 to {MAX_ORDER} (got {order})", "conditions")
    n_coef = (degree if degree is not None else len(conds) - 1) + 1
    if not 2 <= n_coef <= MAX_DEGREE + 1:
        raise SpecError(f"degree must be 1 to {MAX_DEGREE} (got {n_coef - 1})", "degree")
    law = _two_point(conds, n_coef - 1)
    if law is not None:
        return _starts_and_ends(law)
    a = np.array([_condition_row(u, int(k), n_coef) for u, k, _ in conds])
    b = np.array([v for _, _, v in conds], dtype=float)
    rows = np.abs(a).max(axis=1)
    rows[rows == 0] = 1.0
    a, b = a / rows[:, None], b / rows
    cols = np.abs(a).max(axis=0)
    cols[cols == 0] = 1.0
    a = a / cols
    rank, rank_ab = _rank(a), _rank(np.column_stack([a, b]))
    if rank_ab > rank:
        raise SpecError(f"the conditions contradict each other: no polynomial of degree {n_coef - 1} meets them all",
                        "conditions")
    if rank < n_coef:
        raise SpecError(f"{rank} independent conditions cannot fix a polynomial of degree {n_coef - 1} "
                        f"({n_coef} coefficients): add {n_coef - rank} or lower the degree", "conditions")
    # LU on the square system keeps ~1e-14 at degree 25; an SVD least-squares solve loses digits from degree 9
    coef = np.linalg.solve(a, b) if a.shape[0] == n_coef else np.linalg.lstsq(a, b, rcond=None)[0]
    coef = coef / cols
    return _starts_and_ends(PolynomialLaw(Chebyshev(coef, domain=[0, 1])))


def _starts_and_ends(law: PolynomialLaw) -> PolynomialLaw:
    """``law``, if its values stay bounded (:func:`~camgen.laws.base.bounded`) and it rises from f(0) = 0 to
    f(1) = 1; otherwise an error naming ``conditions``."""
    bounded(law, "conditions", "give values of the size a rise from 0 to 1 has")
    ends = law.derivatives(np.array([0.0, 1.0]))[0]
    if abs(ends[0]) > 1e-9 or abs(ends[1] - 1.0) > 1e-9:
        raise SpecError(f"a rise law must go from f(0) = 0 to f(1) = 1 (these give {ends[0]:.6g} and {ends[1]:.6g}); "
                        "include [0, 0, 0] and [1, 0, 1]", "conditions")
    return law
