"""A law fitted to measured or drawn points: a least-squares B-spline of stated continuity (``law = "table"``).

Points are ``(u, f)`` in normalised units (fraction of the segment angle, fraction of the lift),
as :func:`table_law` makes them from a table of (angle in degrees from the segment's start,
displacement above the segment's low end). The spline has degree ``continuity + 1``, so inside the
segment it is continuous to its ``continuity``-th derivative (2: acceleration, 3: jerk); it passes
exactly through f(0) = 0 and f(1) = 1 and, with ``ends = "dwell"``, has zero velocity and
acceleration at both ends (it meets dwells without a jump). Its knots are evenly spaced; their
number doubles from 2 until every point lies within ``tolerance`` (a fraction of the lift) of the
spline, the least-squares fit under those end conditions (a tiny penalty on the spline's
coefficients' differences keeps knots that no point reaches determined). A fit that cannot get
that close with as many knots as the points allow is refused.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from camgen.laws.base import Law, as_array, pairs

#: the continuities a fit may state (derivative order continuous inside the segment)
CONTINUITIES = (2, 3, 4)
#: the most interior knots a fit takes
MAX_KNOTS = 512
#: the weight of the smoothing penalty, relative to the data's own normal equations
PENALTY = 1e-9


@dataclass(frozen=True)
class FittedLaw(Law):
    """A B-spline fitted to ``samples`` ((u, f) pairs) to within ``tolerance`` (fraction of the lift)."""

    name: ClassVar[str] = "table"
    samples: tuple[tuple[float, float], ...]
    continuity: int = 3
    tolerance: float = 1e-3
    ends: str = "dwell"
    #: the segment's angle (degrees), lift and direction, for messages only
    scale: tuple[float, float, bool] = (1.0, 1.0, False)
    _fit: Any = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        pts = pairs(self.samples, 4, "data", "four (angle, value) rows")
        if self.continuity not in CONTINUITIES:
            raise SpecError(f"must be 2, 3 or 4 (got {self.continuity})", "continuity")
        order = np.argsort(pts[:, 0], kind="stable")
        u, f = pts[order, 0], pts[order, 1]
        if u[0] < -1e-12 or u[-1] > 1 + 1e-12:
            raise SpecError("angles must lie within the segment, from 0 to its angle", "data")
        if np.any(np.diff(u) <= 0):
            raise SpecError("two rows give the same angle", "data")
        fit = _fit(u, f, self.continuity + 1, self.tolerance, self.ends)
        if fit[1] > self.tolerance:
            beta, lift, falling = self.scale
            at = (1.0 - fit[2] if falling else fit[2]) * beta
            raise SpecError(f"a spline of continuity C{self.continuity} with {len(fit[0].t) - 2 * fit[0].k - 2} "
                            f"knots comes no closer than {fit[1] * lift:.3g} to the row at {at:.4g} degrees "
                            f"(fit_tolerance {self.tolerance * lift:.3g}): give more rows, smoother values or a "
                            "larger fit_tolerance", "data")
        object.__setattr__(self, "_fit", fit)

    @property
    def knots(self) -> np.ndarray:
        """The interior knots (values of u)."""
        spline = self._fit[0]
        k = spline.k
        return spline.t[k + 1:-k - 1]

    @property
    def residual(self) -> float:
        """The largest distance of a point from the spline (fraction of the lift)."""
        return float(self._fit[1])

    @property
    def residual_at(self) -> float:
        """Where (u) the largest residual is."""
        return float(self._fit[2])

    @property
    def breakpoints(self) -> tuple[float, ...]:
        """The knots where a cubic's (continuity 2) third derivative steps; none above."""
        return tuple(float(x) for x in self.knots) if self.continuity < 3 else ()

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u = np.clip(as_array(u), 0.0, 1.0)
        spline = self._fit[0]
        return np.stack([spline(u, nu=k) for k in range(4)])


def _fit(u: np.ndarray, f: np.ndarray, k: int, tolerance: float, ends: str) -> tuple[Any, float, float]:
    """The spline (scipy BSpline), its largest residual and where, with the fewest evenly spaced knots (doubling
    from 2) that bring every point within ``tolerance`` (or as many as the points allow)."""
    from scipy.interpolate import BSpline

    most = min(max(len(u) - k - 1, 1), MAX_KNOTS)
    count, best = 2, None
    while True:
        n = min(count, most)
        t = np.r_[np.zeros(k + 1), np.linspace(0.0, 1.0, n + 2)[1:-1], np.ones(k + 1)]
        coef = _solve(u, f, t, k, ends)
        spline = BSpline(t, coef, k, extrapolate=False)
        miss = np.abs(spline(u) - f)
        i = int(np.argmax(miss))
        best = (spline, float(miss[i]), float(u[i]))
        if miss[i] <= tolerance or n >= most:
            break
        count *= 2
    return best


def _solve(u: np.ndarray, f: np.ndarray, t: np.ndarray, k: int, ends: str) -> np.ndarray:
    """Least-squares coefficients under the end conditions (a KKT system), with a tiny penalty on the
    coefficients' k-th differences."""
    from scipy.interpolate import BSpline

    m = len(t) - k - 1
    a = BSpline.design_matrix(u, t, k).toarray()
    rows, rhs = [], []
    orders = (0, 1, 2) if ends == "dwell" else (0,)
    for x, value, near in ((0.0, 0.0, range(k + 1)), (1.0, 1.0, range(m - k - 1, m))):
        for nu in orders:                                # only the k + 1 basis functions at an end reach it
            basis = np.zeros(m)
            for j in near:
                basis[j] = BSpline(t, np.eye(m)[j], k)(x, nu=nu)
            rows.append(basis)
            rhs.append(value if nu == 0 else 0.0)
    c = np.array(rows)
    d = np.diff(np.eye(m), n=min(k, m - 1), axis=0)
    normal = a.T @ a
    normal += PENALTY * max(np.trace(normal) / m, 1.0) * (d.T @ d)
    kkt = np.block([[normal, c.T], [c, np.zeros((len(c), len(c)))]])
    solution = np.linalg.lstsq(kkt, np.r_[a.T @ f, rhs], rcond=None)[0]
    return solution[:m]


def table_law(data: Sequence[Sequence[float]], beta_deg: float, lift: float, falling: bool = False,
              continuity: int = 3, fit_tolerance: float = 0.01, ends: str = "dwell") -> FittedLaw:
    """A :class:`FittedLaw` from rows of (angle in degrees from the segment's start, displacement above the
    segment's low end in the lift's unit) for a segment of ``beta_deg`` degrees and ``lift``; a return
    (``falling``) runs from the lift down to 0. ``fit_tolerance`` is in the lift's unit."""
    rows = pairs(data, 4, "data", "four (angle, value) rows")
    u = rows[:, 0] / beta_deg
    samples = np.column_stack([1.0 - u if falling else u, rows[:, 1] / lift])
    return FittedLaw(tuple(map(tuple, samples)), continuity, fit_tolerance / lift, ends, (beta_deg, lift, falling))
