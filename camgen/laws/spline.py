"""A law through a user's table of points: a quintic interpolating spline (scipy).

Points are ``(u, f)`` in normalised units (fraction of the segment angle, fraction
of the lift), from (0, 0) to (1, 1) with u strictly increasing. ``ends = "dwell"``
(default) makes velocity and acceleration zero at both ends, so the law meets
dwells without a jump; ``"natural"`` leaves them free (third and fourth derivatives
zero instead). Inside, the spline is continuous to the fourth derivative, so jerk
never jumps between points; continuity at the segment's ends is reported with the
program's.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError
from camgen.laws.base import Law, as_array, bounded, pairs

ENDS = {"dwell": ([(1, 0.0), (2, 0.0)], [(1, 0.0), (2, 0.0)]),
        "natural": ([(3, 0.0), (4, 0.0)], [(3, 0.0), (4, 0.0)])}


@dataclass(frozen=True)
class SplineLaw(Law):
    """Quintic spline through ``points`` with end conditions ``ends`` (see the module docstring)."""

    name: ClassVar[str] = "spline"
    points: tuple[tuple[float, ...], ...]       # [u, f] pairs, checked to be so
    ends: str = "dwell"
    _spline: Any = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        from scipy.interpolate import make_interp_spline

        pts = pairs(self.points, 2, "points", "two [u, f] pairs, from [0, 0] to [1, 1]")
        u, f = pts[:, 0], pts[:, 1]
        if u[0] != 0.0 or u[-1] != 1.0 or f[0] != 0.0 or f[-1] != 1.0:
            raise SpecError(f"must start at [0, 0] and end at [1, 1] (got {pts[0].tolist()} ... "
                            f"{pts[-1].tolist()})", "points")
        if np.any(np.diff(u) <= 0):
            i = int(np.argmax(np.diff(u) <= 0)) + 1
            raise SpecError(f"u must increase strictly (entry {i}: {u[i]} after {u[i - 1]})", "points")
        if self.ends not in ENDS:
            raise SpecError(f"must be 'dwell' or 'natural' (got {self.ends!r})", "ends")
        try:
            with np.errstate(all="ignore"):
                spline = make_interp_spline(u, f, k=5, bc_type=ENDS[self.ends])
        except (ValueError, np.linalg.LinAlgError):     # points so close that the fit's system overflows
            raise SpecError(f"no spline through these points: the closest lie {float(np.diff(u).min()):.3g} apart "
                            "in u; keep them further apart", "points") from None
        object.__setattr__(self, "_spline", tuple(spline.derivative(k) if k else spline for k in range(4)))
        bounded(self, "points", "keep the points' f near 0 to 1 and their u further apart",
                np.concatenate([u, (u[1:] + u[:-1]) / 2]))

    def magnitude_bounds(self) -> np.ndarray:
        """The largest coefficient of the spline and of each of its first three derivatives: a B-spline lies within
        its coefficients' range (the convex hull property), so each bounds the magnitude over [0, 1]."""
        with np.errstate(all="ignore"):
            return np.array([np.abs(d.c).max() for d in self._spline])

    def derivatives(self, u: ArrayLike) -> np.ndarray:
        u = as_array(u)
        return np.stack([d(u) for d in self._spline])

    def overshoot(self) -> float:
        """How far (fraction of the lift) the spline leaves [0, 1] between the points; 0 when it stays inside."""
        f = self.derivatives(np.linspace(0, 1, 4001))[0]
        return float(max(0.0, -f.min(), f.max() - 1.0))


def spline_law(points: Sequence[Sequence[float]], ends: str = "dwell") -> SplineLaw:
    return SplineLaw(tuple(tuple(p) for p in points), ends)
