"""The base of every motion law: a normalised rise f(u) on u in [0, 1].

A law knows nothing of lifts, angles or segments: it gives f, f', f'', f''' with
respect to u = theta / beta, with f(0) = 0 and f(1) = 1. Scaling to a segment
(s = h f, s' = h/beta f', s'' = h/beta^2 f'', s''' = h/beta^3 f''') happens once, in
:mod:`camgen.program`, for every law.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from itertools import pairwise
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from camgen.numeric import left_of, piecewise_maxima

@dataclass(frozen=True)
class Law(ABC):
    """A normalised rise law. Subclasses are frozen dataclasses of their parameters."""

    #: registry name, e.g. ``"cycloidal"``
    name: ClassVar[str]
    #: True for a law with no parameters at all, every instance one and the same function (a cycloidal rise and a
    #: cycloidal return), which :mod:`camgen.program` evaluates once for all the segments using it. Each class
    #: states its own: a subclass that does not say so is False (see :meth:`__init_subclass__`)
    PARAMETERLESS: ClassVar[bool] = False

    def __init_subclass__(cls, **kwargs: object) -> None:
        """A subclass does not inherit :attr:`PARAMETERLESS` (a law with parameters deriving from one without
        them would otherwise share its segments' evaluations with other instances)."""
        super().__init_subclass__(**kwargs)
        if "PARAMETERLESS" not in cls.__dict__:
            cls.PARAMETERLESS = False

    @abstractmethod
    def derivatives(self, u: ArrayLike) -> np.ndarray:
        """Array of shape ``(4, *u.shape)``: f, df/du, d2f/du2, d3f/du3 at ``u`` in [0, 1].

        Where pieces meet (see :attr:`breakpoints`) the value of the piece on the
        right is returned; evaluate just below a breakpoint for the left limit.
        """

    def magnitude_bounds(self) -> np.ndarray | None:
        """Upper bounds on the magnitudes of f and its first three derivatives over [0, 1] that the law's
        coefficients give at once (a B-spline's lie within its coefficients' range), or None for a law that has none
        (:func:`bounded` then samples it)."""
        return None

    @property
    def breakpoints(self) -> tuple[float, ...]:
        """Interior values of u where the law changes piece (and a derivative may jump)."""
        return ()

    def smooth_intervals(self) -> list[tuple[float, float]]:
        """Closed sub-intervals of [0, 1] on which the law is smooth, with left limits at their right ends."""
        breakpoints = self.breakpoints
        if not breakpoints:             # one piece (what the general case makes of none, without its sorting)
            return [(0.0, 1.0)]
        edges = [0.0, *sorted(set(breakpoints)), 1.0]
        return [(a, left_of(b) if b < 1.0 else 1.0) for a, b in pairwise(edges) if b > a]

    def peaks(self) -> np.ndarray:
        """Peak magnitudes of f', f'', f''' over [0, 1]: the (Cv, Ca, Cj) coefficients for h = beta = 1."""
        lo, hi = zip(*self.smooth_intervals(), strict=True)
        _, value, _ = piecewise_maxima(lambda u, piece: np.abs(self.derivatives(u)[1:]), lo, hi)
        return value.max(axis=1)

    def jumps(self) -> list[tuple[float, int, float]]:
        """Jumps of f', f'', f''' inside the law and at its ends against dwells.

        Returns ``(u, order, right - left)`` for every jump larger than 1e-9 of the
        law's own peak of that order (order 1 = velocity, 2 = acceleration, 3 = jerk).
        At u = 0 and u = 1 the neighbour is taken to be a dwell (all derivatives zero).
        """
        scale = np.maximum(self.peaks(), 1.0)
        found: list[tuple[float, int, float]] = []
        zero = np.zeros(4)
        points = [(0.0, zero, self.derivatives(0.0))]
        points += [(u, self.derivatives(left_of(u)), self.derivatives(u)) for u in sorted(set(self.breakpoints))]
        points.append((1.0, self.derivatives(1.0), zero))
        for u, left, right in points:
            for k in (1, 2, 3):
                step = float(right[k] - left[k])
                if abs(step) > 1e-9 * scale[k - 1]:
                    found.append((u, k, step))
        return found

    def infinite(self) -> list[str]:
        """Which of "v", "a", "j" become infinite in a segment that starts and ends at dwells.

        A jump in f' makes the acceleration (and jerk) infinite; a jump in f'' makes
        the jerk infinite; a jump in f''' is a finite jerk step. f itself never jumps.
        """
        orders = {k for _, k, _ in self.jumps()}
        if 1 in orders:
            return ["a", "j"]
        if 2 in orders:
            return ["j"]
        return []


#: the largest magnitude (normalised: a lift and an angle of 1) a law made from a user's numbers (a polynomial's
#: conditions, a spline's points) may reach in f or any of its first three derivatives anywhere on [0, 1]. A rise
#: from 0 to 1 needs a few units (cycloidal: 1, 2, 2 pi, 4 pi^2; a degree-24 polynomial with twelve derivatives
#: fixed at each end: 1, 4, 24, 364); far below this bound a cam can no longer be drawn (its outline would need
#: more vertices than a file may hold), and near 1e150 the squares in its geometry overflow
MAX_NORMALISED = 1e12
#: the names of f and its first three derivatives in messages
ORDER_NAMES = ("displacement", "velocity", "acceleration", "jerk")
#: grid points on [0, 1] the bound is checked at (with each law's own points of interest)
_BOUND_GRID = np.linspace(0.0, 1.0, 4097)


def bounded(law: Law, field: str, hint: str, at: ArrayLike = ()) -> Law:
    """``law``, if f and its first three derivatives stay within :data:`MAX_NORMALISED` over [0, 1]: certainly, by
    the law's :meth:`~Law.magnitude_bounds`, or else as sampled on a grid of 4097 points, at ``at`` (the points a
    law made from data passes through, where it bends most) and just below each breakpoint; otherwise a
    :class:`SpecError` naming ``field``, ending with ``hint`` (what to change)."""
    bounds = law.magnitude_bounds()
    if bounds is not None and bool(np.all(np.asarray(bounds) <= MAX_NORMALISED)):
        return law                                      # certain, and without evaluating the law
    u = np.concatenate([_BOUND_GRID, np.asarray(at, dtype=float).ravel(), [left_of(b) for b in law.breakpoints]])
    with np.errstate(all="ignore"):                     # an overflow is what is looked for, not to be warned of
        d = np.asarray(law.derivatives(np.clip(u, 0.0, 1.0)), dtype=float)
        size = np.where(np.isfinite(d), np.abs(d), np.inf).max(axis=1)
    over = np.flatnonzero(size > MAX_NORMALISED)
    if not over.size:
        return law
    order = int(over[0])
    reach = "overflows" if not np.isfinite(size[order]) else f"reaches {size[order]:.3g}"
    raise SpecError(f"the law's {ORDER_NAMES[order]} {reach}; it must stay within {MAX_NORMALISED:g} in normalised "
                    f"units (for a lift and an angle of 1): {hint}", field)


def as_array(u: ArrayLike) -> np.ndarray:
    """``u`` as a float array (a 0-d array for a scalar)."""
    return np.asarray(u, dtype=float)


def rows(*values: np.ndarray) -> np.ndarray:
    """``values`` (arrays of one shape) as the rows of one array, shape ``(len(values), *shape)``: np.stack's result
    without its checks (a law's derivatives are made on every evaluation)."""
    first = values[0]
    out = np.empty((len(values), *first.shape))
    for i, v in enumerate(values):
        out[i] = v
    return out


def blank(u: np.ndarray) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """An empty array ``(4, *u.shape)`` for a law's f and its first three derivatives, and its four rows as views
    to fill in place (0-d for a scalar ``u``)."""
    out = np.empty((4, *u.shape))
    return out, (out[0, ...], out[1, ...], out[2, ...], out[3, ...])


def pairs(values: ArrayLike, least: int, field: str, what: str) -> np.ndarray:
    """``values`` as an (n, 2) float array of at least ``least`` finite rows, or a :class:`SpecError` naming
    ``field`` that asks for ``what``."""
    pts = np.array(values, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < least:
        raise SpecError(f"give at least {what}", field)
    if not np.isfinite(pts).all():
        raise SpecError("must hold finite numbers", field)
    return pts
