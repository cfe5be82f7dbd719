"""Four-bar linkage kinematics, vectorised over input angles, exact up to the toggle positions.

Frame and signs:

* The input (crank) pivot O2 is at the origin, the output (rocker) pivot O4 at
  (ground, 0) on +X. Every angle is measured counter-clockwise from +X, the ground
  line; radians inside, degrees at the interfaces.
* theta2 is the crank angle (O2 -> A), theta3 the coupler angle (A -> B), theta4 the
  rocker angle (O4 -> B).
* Assembly ``open`` puts B to the left of the line from A to O4, ``crossed`` to the
  right (with the crank up, the open quadrilateral O2 A B O4 does not cross itself).
  At a change point the two assemblies meet and swap labels; :meth:`FourBar.sweep`
  follows one branch through them.
* The transmission angle gamma is the angle at B between coupler and rocker, in
  [0, pi]; it is 0 or pi at a toggle.

Angles of the triangle A-B-O4 are computed from its area with Kahan's stable form of
Heron's formula, so poses stay accurate to rounding right up to the toggles (an
arccosine near +-1 would lose half the digits there). Near a change point z = |A O4|
itself has lost those digits; there the area is the product of two roots that are
half-angle sines or cosines (:meth:`FourBar._roots`), and the rates differentiate that
placement in a form with no 0/0, so they are the branch's, to rounding, through the fold.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from functools import cached_property, partial
from typing import Literal, get_args

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SolverError, SpecError
from linkgen.kinematics.grashof import CHANGE_POINT_TOL, Grashof, check_finite, check_lengths, classify

Assembly = Literal["open", "crossed"]
ASSEMBLIES: tuple[Assembly, ...] = get_args(Assembly)
#: inputs this far (relative to the longest link) beyond a toggle are snapped onto it
FEASIBILITY_TOL = 1e-10
TWO_PI = 2.0 * math.pi
#: crank angles placed at a time (:meth:`FourBar._poses`): each of the 10 intermediates 128 kB, together within a
#: core's caches; of 4 096 to 32 768 at 100 000 angles, 4 096 and 8 192 measured slower (docs/guides/speed.md)
CHUNK = 16384
#: up to this many angles :meth:`FourBar._poses` places every pin and angle in one pass: below it a second pass's
#: own cost (some 50 numpy calls) is more than the arithmetic the pins and angles not asked for take
EAGER = 512
#: bytes from which numpy asks the kernel for huge pages (numpy/_core/src/multiarray/alloc.c)
HUGE = 1 << 22
#: rows of a chunk's workspace (:meth:`FourBar._triangle` and its callers)
_ROWS = 10


def _sign(assembly: str) -> int:
    if assembly not in ASSEMBLIES:
        raise SpecError(f"must be 'open' or 'crossed' (got {assembly!r})", "assembly")
    return 1 if assembly == "open" else -1


def _area4(a: float, b: float, c: np.ndarray, out: np.ndarray | None = None,
           work: np.ndarray | None = None) -> np.ndarray:
    """Four times the area of triangles with sides a, b (numbers) and c (array), by Kahan's stable form of
    Heron's formula with the sides sorted x >= y >= z; 0 where they only just close. Written into ``out`` with
    ``work`` (5 rows as long as c) for the intermediates when given.

    With two sides fixed, the order is chosen by comparisons alone (no arithmetic), so it is exact; where every
    c is on one side of a and b the sorted sides are c and two numbers, and the numbers' sums are made once
    (the same sums: the same bits). Each intermediate is worked in place: over many triangles the cost is
    memory traffic, not arithmetic.
    """
    rows = iter(np.empty((5, *np.shape(c))) if work is None else work)
    first = np.empty(np.shape(c)) if out is None else out
    p, q = float(max(a, b)), float(min(a, b))
    low, high = (np.fmin.reduce(c), np.fmax.reduce(c)) if np.size(c) else (p, p)
    x: np.ndarray | float
    y: np.ndarray | float
    z: np.ndarray | float
    if low >= p:
        x, y, z = c, p, q
    elif low >= q and high <= p:
        x, y, z = p, c, q
    elif high <= q:
        x, y, z = p, q, c
    else:
        x, z = np.maximum(c, p, out=next(rows)), np.minimum(c, q, out=next(rows))
        middle = np.maximum(c, q, out=next(rows))
        y = np.minimum(middle, p, out=middle)    # the middle side: c between q and p, else the nearer of them

    def op(ufunc: np.ufunc, u: np.ndarray | float, v: np.ndarray | float, into: np.ndarray) -> np.ndarray | float:
        return ufunc(u, v) if isinstance(u, float) and isinstance(v, float) else ufunc(u, v, out=into)

    x_y, second = op(np.subtract, x, y, next(rows)), next(rows)
    np.add(op(np.add, y, z, first), x, out=first)                    # x + (y + z)
    first *= op(np.subtract, z, x_y, second)                         # z - (x - y)
    first *= op(np.add, z, x_y, second)                              # z + (x - y)
    first *= op(np.add, op(np.subtract, y, z, second), x, second)    # x + (y - z)
    np.maximum(first, 0.0, out=first)
    return np.sqrt(first, out=first)


@dataclass(frozen=True)
class Poses:
    """Positions at each input angle (arrays of the same length; angles in radians, points in mm).

    ``theta2``, the rocker pin ``b`` and ``assembly`` are computed when the poses are made; the rest (theta3,
    theta4, the transmission angle gamma, the crank pin A and the coupler point) the first time one of them is
    read, all together, by ``derive``, and kept: nothing is computed that nobody asked for (the rocker pin alone
    costs about 40 % of the whole at 100 000 angles).
    """

    theta2: np.ndarray
    b: np.ndarray              # (n, 2) coupler-rocker pin
    assembly: np.ndarray       # +1 open, -1 crossed, per pose
    #: theta3, theta4, gamma, A and the coupler point, computed when first asked for
    derive: Callable[[], tuple[np.ndarray, ...]] = field(repr=False, compare=False)

    @cached_property
    def _derived(self) -> tuple[np.ndarray, ...]:
        return self.derive()

    @property
    def theta3(self) -> np.ndarray:
        """Coupler angle, A -> B (rad)."""
        return self._derived[0]

    @property
    def theta4(self) -> np.ndarray:
        """Rocker angle, O4 -> B (rad)."""
        return self._derived[1]

    @property
    def gamma(self) -> np.ndarray:
        """Transmission angle: the angle at B between coupler and rocker, in [0, pi] (rad)."""
        return self._derived[2]

    @property
    def a(self) -> np.ndarray:
        """(n, 2) crank pin (mm)."""
        return self._derived[3]

    @property
    def point(self) -> np.ndarray:
        """(n, 2) coupler point (mm; the crank pin A when point_distance is 0)."""
        return self._derived[4]


@dataclass(frozen=True)
class DeadCentre:
    """A dead-centre (toggle) position: ``kind`` and the crank and rocker angles (radians).

    ``extended`` / ``folded``: crank and coupler collinear (the rocker's limit
    positions when the crank drives; dead points when the rocker drives).
    ``toggle-extended`` / ``toggle-folded``: coupler and rocker collinear (where a
    crank input stops: the ends of its reachable range).
    """

    kind: str
    crank: float
    rocker: float


@dataclass(frozen=True)
class NewtonStep:
    """One row of the Newton-Raphson table: the estimate after ``iteration`` steps and its residuals (mm)."""

    iteration: int
    theta3: float
    theta4: float
    f1: float
    f2: float

    @property
    def residual(self) -> float:
        return math.hypot(self.f1, self.f2)


@dataclass(frozen=True)
class NewtonResult:
    """Newton-Raphson's answer (radians) and its table; ``least_squares`` when it stopped at a toggle's
    least-squares pose (the residual as low as rounding lets it go, within the closed form's reach
    tolerance) rather than below the tolerance."""

    theta3: float
    theta4: float
    steps: tuple[NewtonStep, ...]
    least_squares: bool = False


@dataclass(frozen=True)
class FourBar:
    """A four-bar: ``ground`` L1, ``crank`` L2 (input), ``coupler`` L3, ``rocker`` L4, all mm.

    An optional coupler point lies at ``point_distance`` mm from A, at
    ``point_angle`` radians counter-clockwise from the coupler line A -> B.

    The input pivot O2 is the origin and the output pivot O4 lies on +X, ``ground`` away; every angle is counter-
    clockwise from that ground line, in radians.

    Parameters
    ----------
    ground : float
        L1 (mm): O2 to O4.
    crank : float
        L2 (mm): the input link, O2 to the crank pin A.
    coupler : float
        L3 (mm): A to the rocker pin B.
    rocker : float
        L4 (mm): the output link, O4 to B.
    point_distance : float, optional
        The coupler point's distance from A (mm), >= 0; 0 puts it on A.
    point_angle : float, optional
        The coupler point's angle from the line A -> B (radians, counter-clockwise).

    Raises
    ------
    SpecError
        A length that is not finite and > 0 (naming ``linkage.<link>``), a longest link not shorter than the
        other three together (the chain closes only flat), or a negative or non-finite point distance.
    """

    ground: float
    crank: float
    coupler: float
    rocker: float
    point_distance: float = 0.0
    point_angle: float = 0.0

    def __post_init__(self) -> None:
        check_lengths({"linkage.ground": self.ground, "linkage.crank": self.crank,
                       "linkage.coupler": self.coupler, "linkage.rocker": self.rocker})
        if not (math.isfinite(self.point_distance) and self.point_distance >= 0):
            raise SpecError(f"must be a finite distance >= 0 mm (got {self.point_distance})", "linkage.point_distance")

    # ------------------------------------------------------------------ classification

    @property
    def longest(self) -> float:
        return max(self.ground, self.crank, self.coupler, self.rocker)

    @property
    def grashof(self) -> Grashof:
        """Class and inversion with the crank as input (see :mod:`linkgen.kinematics.grashof`)."""
        return classify(self.ground, self.crank, self.coupler, self.rocker)

    # ------------------------------------------------------------------ reach

    def _z(self, theta2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Vector A -> O4 without cancellation: (L1 - L2) + 2 L2 sin^2(theta2 / 2), -L2 sin theta2 (worked in
        place, see :meth:`_poses`)."""
        dx = np.divide(theta2, 2.0, out=np.empty(np.shape(theta2)))
        np.sin(dx, out=dx)
        np.square(dx, out=dx)
        np.multiply(2.0 * self.crank, dx, out=dx)
        np.add(self.ground - self.crank, dx, out=dx)
        dy = np.sin(theta2, out=np.empty(np.shape(theta2)))
        np.multiply(-self.crank, dy, out=dy)
        return dx, dy

    def input_ranges(self) -> tuple[tuple[float, float], ...] | None:
        """Crank angles (radians) the linkage can reach: None when the crank turns fully.

        Otherwise one or two closed intervals ``(lo, hi)`` with lo < hi, within
        (-pi, 2 pi); their ends are the toggle positions.
        """
        l1, l2, l3, l4 = self.ground, self.crank, self.coupler, self.rocker
        tol = FEASIBILITY_TOL * self.longest
        # Z <= L3 + L4  <=>  cos theta2 >= c_hi ;  Z >= |L3 - L4|  <=>  cos theta2 <= c_lo
        c_hi = (l1**2 + l2**2 - (l3 + l4) ** 2) / (2 * l1 * l2)
        c_lo = (l1**2 + l2**2 - (l3 - l4) ** 2) / (2 * l1 * l2)
        limit_hi = l1 + l2 > l3 + l4 + tol          # Z would exceed L3 + L4 near theta2 = pi
        limit_lo = abs(l1 - l2) < abs(l3 - l4) - tol  # Z would fall below |L3 - L4| near theta2 = 0
        if not limit_hi and not limit_lo:
            return None
        a_hi = math.acos(max(-1.0, min(1.0, c_hi))) if limit_hi else math.pi
        a_lo = math.acos(max(-1.0, min(1.0, c_lo))) if limit_lo else 0.0
        if a_lo > a_hi:
            raise SpecError("these lengths cannot be assembled at any crank angle", "linkage")
        if not limit_lo:
            return ((-a_hi, a_hi),)
        if not limit_hi:
            return ((a_lo, TWO_PI - a_lo),)
        return ((a_lo, a_hi), (TWO_PI - a_hi, TWO_PI - a_lo))

    def _check_reach(self, theta2: np.ndarray, mirrored: bool = False) -> None:
        """A clear error if a crank angle is out of reach (or puts the crank pin on the rocker pivot).

        ``mirrored``: this is the mirror image of a rocker-driven linkage (see :meth:`rocker_positions`), and
        the errors speak of the rocker's angles, 180 degrees minus the mirror's crank angles.
        """
        dx, dy = self._z(theta2)
        z = np.hypot(dx, dy)
        tol = FEASIBILITY_TOL * self.longest
        far, near = self.coupler + self.rocker + tol, abs(self.coupler - self.rocker) - tol
        if (z > far).any() or (z < near).any():
            bad = (z > far) | (z < near)
            link, angle = _input_angle(float(np.asarray(theta2)[bad][0]), mirrored)
            ranges = [_input_angle(x, mirrored)[1] for r in self.input_ranges() or () for x in r]
            ranges = sorted(ranges)                 # the mirror's ranges turn round: (180 - hi, 180 - lo)
            digits = digits_apart(angle, ranges)
            pairs = zip(ranges[::2], ranges[1::2], strict=True)
            text = " or ".join(f"[{lo:.{digits}g}, {hi:.{digits}g}]" for lo, hi in pairs)
            raise SpecError(f"{link} angle {angle:.{digits}g} degrees is out of reach; this linkage reaches {link} "
                            f"angles {text} degrees", "angle")
        _refuse_coincident(theta2, z <= tol, "coupler's position is", mirrored)

    # ------------------------------------------------------------------ positions

    def _poses(self, theta2: np.ndarray, sign: int | np.ndarray, check: bool = False, mirrored: bool = False,
               from_o4: bool = False) -> Poses:
        """Poses at crank angles ``theta2`` (1-D, not to be changed afterwards: the rest is derived from it when
        first read) with assembly ``sign`` (+-1, for all or each); with ``check``, every angle must be a finite
        number and its reach is checked first as :meth:`_check_reach` does (``mirrored`` as there), with its
        errors. ``from_o4``: the poses' ``b`` is the vector O4 -> B instead (for :meth:`rocker_positions`, whose
        crank pin it is, as exact as B - O4 is not when the ground is long).

        Only the rocker pin B is placed here; theta3, theta4, gamma, A and the coupler point when one of them is
        first read (:meth:`_rest`), but with at most :data:`EAGER` angles all at once, in this pass. The angles
        are placed :data:`CHUNK` at a time into results made once: over 100 000 angles each intermediate of the
        whole would be 800 kB that the allocator takes from the system page by page, and those page faults cost
        more than the arithmetic; a chunk's intermediates stay in the cache and in the allocator's own memory.
        Each angle sees the same operations in the same order whatever its chunk and whenever its rest is
        derived, so the poses are the same to the last bit."""
        if check:
            check_finite(theta2, "rocker angle" if mirrored else "crank angle",
                         said=lambda t: _input_angle(t, mirrored)[1])
        n = theta2.size
        b, work = _block((n, 2), (_ROWS, min(n, CHUNK)))     # B, and each chunk's intermediates (rows reused)
        rest = self._rest_arrays(n)[:5] if n <= EAGER else None
        fold = any(self.folds())
        for part in _chunks(n):
            room = work[:, :part.stop - part.start]
            triangle = self._triangle(theta2[part], _part(sign, part), room, fold, theta2 if check else None,
                                      mirrored)
            self._place_b(triangle, room, b[part], from_o4)
            if rest is not None:
                self._place_rest(theta2[part], triangle, room, rest, part)
        assembly = np.full(n, sign) if isinstance(sign, int) else sign
        derive = partial(self._finish, rest) if rest is not None else partial(self._rest, theta2, sign)
        return Poses(theta2, b, assembly, derive)

    def _triangle(self, t: np.ndarray, sign: int | np.ndarray, work: np.ndarray, fold: bool,
                  reach: np.ndarray | None = None, mirrored: bool = False) -> tuple[np.ndarray, ...]:
        """The triangle A-B-O4 at crank angles ``t`` (a chunk) with assembly ``sign`` (+-1, for all or each), in
        rows of ``work`` (:data:`_ROWS` rows as long as ``t``): dx, dy (the vector D = A -> O4, mm), r = 1 / (2 z^2)
        (1/mm^2, z = |D|), z^2 (mm^2), 4 times the triangle's area (mm^2, >= 0) and q = sign area4 r (1).

        B is then A + p D + q perp(D) = O4 + (p - 1) D + q perp(D), p = (L3^2 - L4^2 + z^2) r, with perp(D) D
        turned 90 degrees counter-clockwise: the intersection of the circles about A and O4, with no angle
        computed. The sides are :meth:`_sides`'. ``reach``: all the angles, checked as :meth:`_poses` says when this
        chunk has one out of reach or one that puts the crank pin on the rocker pivot; without it, no angle may put
        it there (z = 0, where r is infinite: what needs no B there takes :meth:`_sides` alone)."""
        dx, dy, z2, area4 = self._sides(t, work, fold, reach, mirrored)
        r, q = work[2], work[5]                                 # z is done with
        np.divide(0.5, z2, out=r)
        np.multiply(area4, r, out=q)
        if not (isinstance(sign, int) and sign == 1):
            q *= sign
        return dx, dy, r, z2, area4, q

    def _sides(self, t: np.ndarray, work: np.ndarray, fold: bool, reach: np.ndarray | None = None,
               mirrored: bool = False) -> tuple[np.ndarray, ...]:
        """dx, dy (D = A -> O4, mm), z^2 (mm^2) and 4 times the area of the triangle A-B-O4 (mm^2, >= 0) at crank
        angles ``t`` (a chunk), in rows 0, 1, 3 and 4 of ``work`` (row 2 holds z; rows 5 to 9 the area's
        intermediates). Nothing is divided: defined also where z = 0. The area comes from Kahan's stable form of
        Heron's formula (:func:`_area4`) on z, or at a linkage that folds (``fold``, :meth:`folds`) from the roots
        (:meth:`_roots`), so it stays exact up to the toggles. ``reach``, ``mirrored``: as :meth:`_triangle`'s."""
        l1, l2, l3, l4 = self.ground, self.crank, self.coupler, self.rocker
        dx, dy, z, z2, area4 = work[:5]
        # A -> O4 without cancellation, as _z: (L1 - L2) + 2 L2 sin^2(theta2 / 2), -L2 sin theta2
        np.multiply(t, 0.5, out=dx)
        np.sin(dx, out=dx)
        np.square(dx, out=dx)
        np.multiply(2.0 * l2, dx, out=dx)
        np.add(l1 - l2, dx, out=dx)
        np.sin(t, out=dy)
        np.multiply(-l2, dy, out=dy)
        np.hypot(dx, dy, out=z)
        if reach is not None and z.size:
            tol, low, high = FEASIBILITY_TOL * self.longest, np.fmin.reduce(z), np.fmax.reduce(z)   # NaN ignored
            if high > l3 + l4 + tol or low < abs(l3 - l4) - tol or low <= tol:
                self._check_reach(reach, mirrored)            # the error, said of all the angles as asked
        np.square(z, out=z2)
        if fold:
            # near a fold z has lost the digits the area needs: it is the product of the roots instead
            m, p = self._roots(t)
            np.abs(m.value * p.value, out=area4)
        else:
            _area4(l3, l4, z, area4, work[5:10])
        return dx, dy, z2, area4

    def _place_b(self, triangle: tuple[np.ndarray, ...], work: np.ndarray, b: np.ndarray, from_o4: bool) -> None:
        """The rocker pin B (rows of ``b``, mm) of a chunk's ``triangle`` (:meth:`_triangle`): O4 + (p - 1) D +
        q perp(D), p - 1 = (L3^2 - L4^2 - z^2) r; ``from_o4``: O4 -> B. Rows 6, 7 and 9 of ``work`` for the
        intermediates."""
        dx, dy, r, z2, _, q = triangle
        along, x, tmp = work[6], work[7], work[9]
        np.subtract((self.coupler - self.rocker) * (self.coupler + self.rocker), z2, out=along)
        along *= r
        _turn(along, q, dx, dy, x, b[:, 1], tmp)
        np.add(x, 0.0 if from_o4 else self.ground, out=b[:, 0])

    def _rest_arrays(self, n: int) -> list[np.ndarray]:
        """Room for n poses' theta3, theta4, gamma, A, A -> B (for the coupler point, if any) and a workspace for
        the chunks (:data:`_ROWS` rows), in one block."""
        return _block((n,), (n,), (n,), (n, 2), (2, n if self.point_distance else 0), (_ROWS, min(n, CHUNK)))

    def _place_rest(self, t: np.ndarray, triangle: tuple[np.ndarray, ...], work: np.ndarray,
                    rest: Sequence[np.ndarray], part: slice) -> None:
        """theta3, theta4, gamma (rad), A and A -> B (mm) at crank angles ``t`` (a chunk) into the ``part`` of
        ``rest`` (:meth:`_rest_arrays`), from their ``triangle`` (:meth:`_triangle`): the directions A -> B =
        p D + q perp(D) and O4 -> B = (p - 1) D + q perp(D) straight from it, not from the pins' differences (which
        lose digits when a pin is far from the origin). Rows 6 to 9 of ``work`` for the intermediates."""
        dx, dy, r, z2, area4, q = triangle
        theta3, theta4, gamma, a = (x[part] for x in rest[:4])
        ab = rest[4][:, part]
        l3, l4 = self.coupler, self.rocker
        k = (l3 - l4) * (l3 + l4)
        along, x, y, tmp = work[6:10]
        abx, aby = (ab[0], ab[1]) if self.point_distance else (x, y)
        np.add(k, z2, out=along)                 # p: A -> B
        along *= r
        _turn(along, q, dx, dy, abx, aby, tmp)
        np.arctan2(aby, abx, out=theta3)
        np.subtract(k, z2, out=along)            # p - 1: O4 -> B
        along *= r
        _turn(along, q, dx, dy, x, y, tmp)
        np.arctan2(y, x, out=theta4)
        np.subtract(l3**2 + l4**2, z2, out=tmp)
        np.arctan2(area4, tmp, out=gamma)        # angle at B: the transmission angle
        # the crank pin: dy is -L2 sin theta2, so A's y is -dy to the last bit, with no second sine
        np.cos(t, out=a[:, 0])
        a[:, 0] *= self.crank
        np.negative(dy, out=a[:, 1])

    def _rest(self, theta2: np.ndarray, sign: int | np.ndarray) -> tuple[np.ndarray, ...]:
        """theta3, theta4, gamma (rad), A and the coupler point (mm) of :meth:`_poses`'s poses, derived when first
        read: a chunk at a time, each chunk's triangle made again as it was for B."""
        n = theta2.size
        *rest, work = self._rest_arrays(n)
        fold = any(self.folds())
        for part in _chunks(n):
            room = work[:, :part.stop - part.start]
            self._place_rest(theta2[part], self._triangle(theta2[part], _part(sign, part), room, fold), room,
                             rest, part)
        return self._finish(rest)

    def _finish(self, rest: Sequence[np.ndarray]) -> tuple[np.ndarray, ...]:
        """theta3, theta4, gamma, A and the coupler point from :meth:`_rest_arrays`' arrays, filled."""
        theta3, theta4, gamma, a, ab = rest
        return theta3, theta4, gamma, a, self._coupler_point(a, ab[0], ab[1])

    def _coupler_point(self, a: np.ndarray, abx: np.ndarray, aby: np.ndarray) -> np.ndarray:
        """The coupler point (mm) from the crank pin ``a`` and the vector A -> B (mm, length L3): that vector turned
        by point_angle and scaled to point_distance; ``a`` itself when point_distance is 0."""
        if not self.point_distance:
            return a
        c, s = (self.point_distance / self.coupler * f(self.point_angle) for f in (math.cos, math.sin))
        return np.column_stack([a[:, 0] + (c * abx - s * aby), a[:, 1] + (s * abx + c * aby)])

    def positions(self, theta2: ArrayLike, assembly: Assembly = "open") -> Poses:
        """Closed-form poses at crank angles ``theta2`` (radians) for one assembly label.

        Every angle must be reachable: an angle outside the reachable range is a
        :class:`SpecError` naming that range (never NaN), and so is one that is not a finite number (NaN, +-inf),
        said in degrees. Labels swap at change
        points; use :meth:`sweep` to follow one branch through them.
        """
        return self._placed(theta2, assembly)

    def _placed(self, theta2: ArrayLike, assembly: Assembly, mirrored: bool = False) -> Poses:
        return self._poses(_angles(theta2), _sign(assembly), check=True, mirrored=mirrored)

    def rocker_positions(self, theta4: ArrayLike, assembly: Assembly = "open") -> Poses:
        """Poses when the rocker drives, at rocker angles ``theta4`` (rad).

        Solved on the mirror image (reflected across the perpendicular bisector of
        the ground, the rocker becomes the crank) and reflected back; ``assembly``
        names the two solutions as the rocker sees them, i.e. the mirror's labels.
        """
        t4 = _angles(theta4)
        mirror = FourBar(self.ground, self.rocker, self.coupler, self.crank)
        m = mirror._poses(math.pi - t4, _sign(assembly), check=True, mirrored=True, from_o4=True)
        a = np.column_stack([np.negative(m.b[:, 0]), m.b[:, 1]])    # the mirror's O4 -> B, reflected: O2 -> A
        b = np.column_stack([self.ground + self.rocker * np.cos(t4), self.rocker * np.sin(t4)])
        return Poses(np.arctan2(a[:, 1], a[:, 0]), b, m.assembly, partial(self._rocker_rest, t4, m, a))

    def _rocker_rest(self, theta4: np.ndarray, mirror: Poses, a: np.ndarray) -> tuple[np.ndarray, ...]:
        """theta3, theta4, gamma (rad), A and the coupler point (mm) of :meth:`rocker_positions`'s poses from the
        mirror's: reflected, A -> B is the mirror's A -> B with its y negated, so theta3 is minus the mirror's."""
        theta3 = np.negative(mirror.theta3)
        abx, aby = self.coupler * np.cos(theta3), self.coupler * np.sin(theta3)
        return theta3, theta4, mirror.gamma, a, self._coupler_point(a, abx, aby)

    def change_points(self) -> tuple[float, ...]:
        """Crank angles (radians, 0 or pi) where the two assemblies cross: all four links collinear."""
        tol = CHANGE_POINT_TOL * self.longest
        l1, l2, l3, l4 = self.ground, self.crank, self.coupler, self.rocker
        out = []
        if abs(abs(l1 - l2) - abs(l3 - l4)) <= tol:
            out.append(0.0)
        if abs((l1 + l2) - (l3 + l4)) <= tol:
            out.append(math.pi)
        return tuple(out)

    def sweep(self, theta2: ArrayLike, assembly: Assembly = "open") -> Poses:
        """Poses along a path of crank angles, following one branch continuously.

        ``assembly`` names the branch at the first angle (taken just after it when
        the first angle is a change point). Crossing a change point (the two
        assemblies meet with all links collinear) swaps the open/crossed label of
        the smooth branch, so a parallelogram stays a parallelogram.
        """
        t = _angles(theta2)
        half = _half_turns(t)
        flips = np.zeros(t.shape, dtype=int)
        for cp in self.change_points():
            turn = np.floor((half - round(cp / math.pi)) / 2)     # change points at or below each angle
            flips[1:] += np.cumsum(np.abs(np.diff(turn))).astype(int)
        sign = _sign(assembly) * np.where(flips % 2 == 0, 1, -1)
        return self._poses(t, sign, check=True)

    # ------------------------------------------------------------------ Newton-Raphson

    def residual(self, theta2: float, theta3: float, theta4: float) -> tuple[float, float]:
        """Loop-closure residuals (mm): L2 e^(i t2) + L3 e^(i t3) - L4 e^(i t4) - L1."""
        f1 = (self.crank * math.cos(theta2) + self.coupler * math.cos(theta3)
              - self.rocker * math.cos(theta4) - self.ground)
        f2 = self.crank * math.sin(theta2) + self.coupler * math.sin(theta3) - self.rocker * math.sin(theta4)
        return f1, f2

    def newton(self, theta2: float, guess: tuple[float, float], tol: float = 1e-12,
               max_iter: int = 50, tolerance_mm: float | None = None) -> NewtonResult:
        """Newton-Raphson on the loop closure for (theta3, theta4), radians, from ``guess``.

        Converged when the residual is below ``tol`` times the longest link and the next step (the
        iteration's own error estimate) below ``1000 tol`` rad; with ``tolerance_mm`` (mm, > 0) instead
        at the first estimate whose residual norm |(f1, f2)| is at most that (the course's test). Each step
        is the full Newton step, halved until it lowers the residual where it does not. At a toggle
        (coupler and rocker collinear) the root is double: the Jacobian is singular there and the
        convergence only linear; an input past the toggle by less than the closed form accepts
        (``FEASIBILITY_TOL``) has no exact root at all. So the iteration also stops where the Jacobian is
        singular or no step lowers the residual any more (at rounding) while the loop closes to within the
        tolerance plus that one: the least-squares pose, the toggle's, as the closed form has it. Raises
        :class:`SolverError` at a singular Jacobian far from a root (a guess with coupler and rocker
        collinear), when no step helps far from a root, or after ``max_iter`` steps. The result carries
        the iteration table.
        """
        if tolerance_mm is not None and not (math.isfinite(tolerance_mm) and tolerance_mm > 0):
            raise SpecError(f"must be a finite number of mm > 0 (got {tolerance_mm})", "tolerance")
        t3, t4 = float(guess[0]), float(guess[1])
        f1, f2 = self.residual(theta2, t3, t4)
        steps: list[NewtonStep] = []
        scale = self.longest
        target = tol * scale if tolerance_mm is None else tolerance_mm
        closes = target + FEASIBILITY_TOL * scale       # the loop closes as nearly as the closed form asks
        where = f"at crank angle {math.degrees(theta2):.6g} degrees"
        for k in range(max_iter + 1):
            steps.append(NewtonStep(k, t3, t4, f1, f2))
            res = math.hypot(f1, f2)
            if tolerance_mm is not None and res <= tolerance_mm:
                return NewtonResult(t3, t4, tuple(steps))
            # J = d(f1, f2)/d(t3, t4) = [[-L3 sin t3, L4 sin t4], [L3 cos t3, -L4 cos t4]]
            j11, j12 = -self.coupler * math.sin(t3), self.rocker * math.sin(t4)
            j21, j22 = self.coupler * math.cos(t3), -self.rocker * math.cos(t4)
            det = j11 * j22 - j12 * j21
            if abs(det) <= 1e-12 * self.coupler * self.rocker:
                if res <= closes:
                    return NewtonResult(t3, t4, tuple(steps), least_squares=res > target)
                raise SolverError(f"Newton-Raphson: singular Jacobian at iteration {k} ({where}): coupler and "
                                  "rocker are collinear, a toggle position; start from another guess or use the "
                                  "closed form")
            d3, d4 = (j22 * f1 - j12 * f2) / det, (-j21 * f1 + j11 * f2) / det
            if tolerance_mm is None and res <= target and max(abs(d3), abs(d4)) <= 1e3 * tol:
                return NewtonResult(t3, t4, tuple(steps))
            if k == max_iter:
                break
            found = _descent(lambda a, b: self.residual(theta2, a, b), (t3, t4), (d3, d4), res)
            if found is None:                           # no step lowers the residual: rounding level
                if res <= closes:
                    return NewtonResult(t3, t4, tuple(steps), least_squares=res > target)
                raise SolverError(f"Newton-Raphson stalled at iteration {k} ({where}): no step lowers the "
                                  f"residual {res:.3g} mm; start from another guess or use the closed form")
            t3, t4, f1, f2 = found
        raise SolverError(f"Newton-Raphson did not converge in {max_iter} iterations {where} "
                          f"(residual {math.hypot(f1, f2):.3g} mm)")

    # ------------------------------------------------------------------ derivatives

    def folds(self) -> tuple[bool, bool]:
        """Whether the lengths fold flat at theta2 = 0 ((L1 - L2)^2 = (L3 - L4)^2) and at theta2 = pi
        (L1 + L2 = L3 + L4) exactly, to rounding. Lengths nearer a change point than
        :data:`CHANGE_POINT_TOL` but not this near are solved exactly as given: their two assemblies
        pass each other without touching (or stop short), and their rates are those of what they are."""
        close = 4.0 * np.finfo(float).eps * self.longest
        return (bool(abs(abs(self.ground - self.crank) - abs(self.coupler - self.rocker)) <= close),
                bool(abs((self.ground + self.crank) - (self.coupler + self.rocker)) <= close))

    def _roots(self, theta2: np.ndarray) -> tuple[_Root, _Root]:
        """The two roots m = sqrt(z^2 - (L3 - L4)^2) and p = sqrt((L3 + L4)^2 - z^2) whose product is four
        times the area of the triangle A-B-O4 (mm), from z^2 = (L1 - L2)^2 + 4 L1 L2 sin^2(theta2 / 2)
        = (L1 + L2)^2 - 4 L1 L2 cos^2(theta2 / 2): at a fold one of them is 2 sqrt(L1 L2) times a half-angle
        sine or cosine, computed without cancellation, and signed so as to stay smooth along a branch."""
        l1, l2, l3, l4 = self.ground, self.crank, self.coupler, self.rocker
        fold0, fold_pi = self.folds()
        k = l1 * l2
        s, c = _half_angle(theta2)
        half1, half2 = 2.0 * k * s * c, k * np.cos(theta2)      # half of d(z^2)/d theta2 and its derivative
        return (_root(fold0, (abs(l1 - l2), abs(l3 - l4)), math.sqrt(k), s, c, half1, half2),
                _root(fold_pi, (l3 + l4, l1 + l2), math.sqrt(k), c, -s, -half1, -half2))

    def rates(self, poses: Poses) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """d theta3 / d theta2, d theta4 / d theta2 (dimensionless) and their derivatives (1/rad) along the
        branch the poses lie on (see :func:`_branch_rates`).

        Finite and accurate to rounding at and near change points: there the limit along the branch,
        which the label names at the fold itself (the branch beyond, as :meth:`sweep` counts it).
        +-inf (never NaN) at a toggle of coupler and rocker, where the crank input stops.
        """
        theta2 = np.asarray(poses.theta2, dtype=float)
        _refuse_coincident(theta2, np.hypot(*self._z(theta2)) <= FEASIBILITY_TOL * self.longest,
                           "rates per unit crank speed are")
        m, p = self._roots(theta2)
        return _branch_rates((self.ground, self.crank, self.coupler, self.rocker), theta2, m, p,
                             self._label(poses))

    def _label(self, poses: Poses) -> np.ndarray:
        """Each pose's assembly as its geometry shows it (+1: B left of A -> O4), its label where B lies on
        that line to rounding (at a change point both assemblies meet there, and the label names the branch)."""
        ax, ay = poses.a[:, 0], poses.a[:, 1]
        cross = (self.ground - ax) * (poses.b[:, 1] - ay) + ay * (poses.b[:, 0] - ax)
        clear = np.abs(cross) > 64 * np.finfo(float).eps * self.longest**2
        return np.where(clear, np.sign(cross), np.asarray(poses.assembly, dtype=float))

    def velocities(self, poses: Poses, omega2: float) -> tuple[np.ndarray, np.ndarray]:
        """Angular velocities (omega3, omega4) in rad/s for crank speed ``omega2`` rad/s.

        Along the branch the poses lie on, also at and near change points (see :meth:`rates`);
        unbounded (+-inf, never NaN) at a toggle, where coupler and rocker are collinear.
        """
        d3, d4, _, _ = self.rates(poses)
        return _times(d3, omega2), _times(d4, omega2)

    def accelerations(self, poses: Poses, omega2: float, alpha2: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Angular accelerations (alpha3, alpha4) in rad/s^2 for crank speed ``omega2`` and acceleration ``alpha2``
        (rad/s, rad/s^2): alpha = theta'' omega2^2 + theta' alpha2, primes along the branch (see :meth:`rates`)."""
        d3, d4, dd3, dd4 = self.rates(poses)
        return (_times(dd3, omega2**2) + _times(d3, alpha2), _times(dd4, omega2**2) + _times(d4, alpha2))

    def mechanical_advantage(self, poses: Poses) -> np.ndarray:
        """Output torque over input torque, |omega2 / omega4| (lossless): infinite at the rocker's dead centres,
        0 at a toggle, and the branch's limit at a change point."""
        return _ratio(np.ones(len(poses.theta2)), np.abs(self.rates(poses)[1]))

    # ------------------------------------------------------------------ special positions

    def dead_centres(self, assembly: Assembly = "open") -> tuple[DeadCentre, ...]:
        """Dead-centre and toggle positions of the given assembly, in order of crank angle.

        Crank and coupler collinear (``extended``, ``folded``) where the geometry
        allows, then coupler and rocker collinear (``toggle-extended``,
        ``toggle-folded``) at the ends of a limited crank range.
        """
        sign = _sign(assembly)
        l1, l2, l3, l4 = self.ground, self.crank, self.coupler, self.rocker
        tol = FEASIBILITY_TOL * self.longest
        out: list[DeadCentre] = []
        for kind, reach in (("extended", l2 + l3), ("folded", abs(l3 - l2))):
            if not (abs(l1 - l4) - tol <= reach <= l1 + l4 + tol) or reach <= tol:
                continue
            cos_phi = max(-1.0, min(1.0, (l1**2 + reach**2 - l4**2) / (2 * l1 * reach)))
            for side in (1.0, -1.0):
                phi = side * math.acos(cos_phi)
                pin = reach * np.array([math.cos(phi), math.sin(phi)])
                crank = phi if kind == "extended" or l2 > l3 else phi + math.pi
                crank = math.atan2(math.sin(crank), math.cos(crank))
                seen = any(d.kind == kind and abs(math.remainder(d.crank - crank, TWO_PI)) < 1e-9 for d in out)
                if seen or math.hypot(*self._z(np.array(crank))) <= tol:   # undetermined: A on O4
                    continue
                pose = self._poses(np.array([crank]), sign)
                if np.linalg.norm(pose.b[0] - pin) <= 1e-7 * self.longest:
                    out.append(DeadCentre(kind, crank, float(pose.theta4[0])))
        for lo, hi in self.input_ranges() or ():
            for end in (lo, hi):
                pose = self._poses(np.array([end]), sign)
                kind = "toggle-extended" if pose.gamma[0] > math.pi / 2 else "toggle-folded"
                out.append(DeadCentre(kind, end, float(pose.theta4[0])))
        return tuple(sorted(out, key=lambda d: d.crank % TWO_PI))

    def time_ratio(self, assembly: Assembly = "open") -> float | None:
        """Quick-return time ratio (>= 1) of a crank-driven rocker: slower stroke over faster, or None."""
        if self.input_ranges() is not None:
            return None
        ends = {d.kind: d.crank for d in self.dead_centres(assembly) if d.kind in ("extended", "folded")}
        if len(ends) != 2:
            return None
        travel = (ends["folded"] - ends["extended"]) % TWO_PI
        return max(travel, TWO_PI - travel) / min(travel, TWO_PI - travel)

    def transmission_extremes(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """((gamma_min, crank angle), (gamma_max, crank angle)) in radians over the reachable crank angles.

        gamma grows with the distance Z from A to O4, so its extremes lie where Z is
        smallest and largest: crank angles 0 and pi, or the ends of a limited range.
        """
        ranges = self.input_ranges()
        ends = [x for r in ranges or () for x in r]
        inside = [x for x in (0.0, math.pi) if ranges is None
                  or any(lo <= y <= hi for lo, hi in ranges for y in (x, x + TWO_PI, x - TWO_PI))]
        candidates = np.array(ends + inside)
        gamma = self._gammas(candidates)
        i, j = int(np.argmin(gamma)), int(np.argmax(gamma))
        return (float(gamma[i]), float(candidates[i])), (float(gamma[j]), float(candidates[j]))

    def _gammas(self, theta2: np.ndarray) -> np.ndarray:
        """Transmission angles (rad) at crank angles ``theta2`` (1-D, within reach) from the triangle's sides alone,
        as :meth:`_place_rest` has them: also where the crank pin sits on the rocker pivot (a deltoid's fold, where
        no pose is determined but coupler and rocker overlap whatever B is: gamma 0)."""
        _, _, z2, area4 = self._sides(theta2, np.empty((_ROWS, theta2.size)), any(self.folds()))
        return np.arctan2(area4, (self.coupler**2 + self.rocker**2) - z2)


def _input_angle(theta2: float, mirrored: bool) -> tuple[str, float]:
    """The driven link's name and its angle (degrees) at crank angle ``theta2`` (rad): the crank's own, or on a
    rocker-driven linkage's mirror image (see :meth:`FourBar.rocker_positions`) the rocker's, 180 minus it."""
    return ("rocker", 180.0 - math.degrees(theta2)) if mirrored else ("crank", math.degrees(theta2))


def digits_apart(angle: float, limits: list[float]) -> int:
    """The fewest significant digits, 6 to 17, with which ``angle`` prints differently from each of ``limits``
    (17 tell any two doubles apart): an angle just out of reach must not read as its limit."""
    return next((n for n in range(6, 17) if all(f"{angle:.{n}g}" != f"{x:.{n}g}" for x in limits)), 17)


def _refuse_coincident(theta2: np.ndarray, coincident: np.ndarray, what: str, mirrored: bool = False) -> None:
    """Refuse crank angles where the crank pin sits on the rocker pivot (a deltoid's change point): there the
    crank angle does not determine ``what``. ``mirrored``: said of a rocker-driven linkage's mirror image."""
    if np.any(coincident):
        link, angle = _input_angle(float(np.asarray(theta2)[coincident][0]), mirrored)
        pins = "the rocker pin sits on the crank pivot" if mirrored else "the crank pin sits on the rocker pivot"
        raise SpecError(f"at {link} angle {angle:.6g} degrees {pins}, so the {what} undetermined (a deltoid "
                        "change point)", "angle")


def _block(*shapes: tuple[int, ...]) -> list[np.ndarray]:
    """Arrays of floats of the given shapes, views of one block; a block of at least half of :data:`HUGE` bytes
    made that large: from that size numpy asks the kernel for huge pages, so that it is a few page faults instead
    of one every 4 kB (at 100 000 angles that was the cost, not the arithmetic; docs/guides/speed.md)."""
    sizes = [math.prod(shape) for shape in shapes]
    total = sum(sizes)
    block = np.empty(max(total, HUGE // 8) if 16 * total >= HUGE else total)
    ends = np.cumsum([0, *sizes]).tolist()
    return [block[lo:hi].reshape(shape) for lo, hi, shape in zip(ends[:-1], ends[1:], shapes, strict=True)]


def _angles(theta: ArrayLike) -> np.ndarray:
    """Input angles (rad) as a 1-D array of floats of our own, read-only: the poses derive from it later."""
    out = np.array(theta, dtype=float, ndmin=1)
    out.setflags(write=False)
    return out


def _chunks(n: int) -> Iterator[slice]:
    """The slices of n angles placed :data:`CHUNK` at a time, in order."""
    return (slice(i, min(i + CHUNK, n)) for i in range(0, n, CHUNK))


def _part(sign: int | np.ndarray, part: slice) -> int | np.ndarray:
    """Assembly signs of the ``part`` of the angles: one for all, or theirs."""
    return sign if isinstance(sign, int) else sign[part]


def _turn(c: np.ndarray, q: np.ndarray, dx: np.ndarray, dy: np.ndarray, x: np.ndarray, y: np.ndarray,
          tmp: np.ndarray) -> None:
    """The vector c D + q perp(D) (D = (dx, dy), perp(D) = (-dy, dx): D turned 90 degrees counter-clockwise) into
    ``x`` and ``y``; ``tmp`` holds the intermediates."""
    np.multiply(c, dx, out=tmp)
    np.multiply(q, dy, out=x)
    np.subtract(tmp, x, out=x)
    np.multiply(c, dy, out=tmp)
    np.multiply(q, dx, out=y)
    np.add(tmp, y, out=y)


def _half_turns(theta2: np.ndarray) -> np.ndarray:
    """floor(theta2 / pi): the half-turn each crank angle lies in.

    :meth:`FourBar.sweep` counts change-point crossings with it and :func:`_branch_rates` names the side of
    a change point with it, so the two agree to the last bit: an angle that rounds onto a change point
    counts as just past it (its label names the branch beyond).
    """
    return np.floor(theta2 / math.pi)


def _half_angle(theta2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """sin(theta2 / 2) and cos(theta2 / 2), their signs read from :func:`_half_turns` (the quadrant of theta2 / 2)."""
    quadrant = np.mod(_half_turns(theta2), 4.0)
    s = np.abs(np.sin(theta2 / 2.0)) * np.where(quadrant < 2, 1.0, -1.0)
    c = np.abs(np.cos(theta2 / 2.0)) * np.where((quadrant == 0) | (quadrant == 3), 1.0, -1.0)
    return s, c


@dataclass(frozen=True)
class _Root:
    """A root of the triangle A-B-O4's area along the crank angles: its value (mm^2 / mm = mm), first and
    second derivatives with respect to theta2 (mm/rad, mm/rad^2), its sign (+-1) and where it is 0 at a
    toggle (where the derivatives, unbounded, are to be ignored)."""

    value: np.ndarray
    d1: np.ndarray
    d2: np.ndarray
    sign: np.ndarray
    toggle: np.ndarray


def _root(fold: bool, pair: tuple[float, float], r: float, u: np.ndarray, v: np.ndarray, h1: np.ndarray,
          h2: np.ndarray) -> _Root:
    """sqrt(x^2 - y^2 + 4 r^2 u^2) with (x, y) = ``pair``, u = sin or cos of theta2 / 2 and v = 2 du / d(theta2);
    h1, h2: half the radicand's first and second derivatives.

    At a change point (``fold``, x = y) the root is 2 r u, taken with its sign so that it stays smooth
    through the fold (u = 0 there exactly, with no cancellation); otherwise the positive root, 0 at a
    toggle (to rounding).
    """
    if fold:
        return _Root(2.0 * r * u, r * v, -0.5 * r * u, np.where(u >= 0, 1.0, -1.0), np.zeros(u.shape, dtype=bool))
    x, y = pair
    value = (x - y) * (x + y) + 4.0 * r * r * u * u
    zero = value <= 8.0 * np.finfo(float).eps * (x * x + y * y + 4.0 * r * r * u * u)
    root = np.sqrt(np.where(zero, 1.0, value))
    root1 = h1 / root
    return _Root(np.where(zero, 0.0, root), root1, (h2 - root1**2) / root, np.ones(u.shape), zero)


def _branch_rates(lengths: tuple[float, float, float, float], theta2: np.ndarray, m: _Root, p: _Root,
                  label: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """theta3', theta4', theta3'', theta4'' (derivatives with respect to theta2) of the closed-form placement.

    theta3 = delta + alpha and theta4 = delta + pi - beta: delta is the direction of A -> O4, alpha and
    beta the angles at A and O4 of the triangle A-B-O4 (sides L3, L4 and z = |A O4|). With its area's
    roots m = sqrt(z^2 - (L3 - L4)^2) and p = sqrt((L3 + L4)^2 - z^2) (see :meth:`FourBar._roots`),
    tan alpha = b p m / (2 L3 (L3 - L4) + m^2) and tan beta = b p m / (2 L4 (L4 - L3) + m^2), where
    b = +-1 names the branch: differentiated in this form nothing is divided by a vanishing quantity,
    at a change point nor where z -> 0 at a deltoid's (z^2 = m^2 + (L3 - L4)^2). Through a change point
    the branch keeps b while its label (the sign of b p m) changes, so the rates there are the branch's,
    accurate to rounding at and near the fold. Where a root is 0 (a toggle) the rates are the limits
    from inside the reach: +-inf.
    """
    l1, l2, l3, l4 = lengths
    s, c = _half_angle(theta2)
    sin_t = 2.0 * s * c
    z2 = ((l1 - l2) + 2.0 * l2 * s**2) ** 2 + (l2 * sin_t) ** 2
    d_delta = l2 * ((l2 - l1) + 2.0 * l1 * s**2) / z2
    dd_delta = l1 * l2 * (l1 * l1 - l2 * l2) * sin_t / z2**2
    branch = label * m.sign * p.sign
    d2 = (l3 - l4) ** 2
    zm = m.value**2 + d2                                  # z^2 from m: 0 only with m at a deltoid's fold
    toggle = m.toggle | p.toggle
    out = []
    for lk, e, sense in ((l3, 2.0 * l3 * (l3 - l4), 1.0), (l4, 2.0 * l4 * (l4 - l3), -1.0)):
        f, g = (e + m.value**2) / zm, (e - m.value**2) / zm
        f1 = 2.0 * m.value * m.d1 * (d2 - e) / zm**2
        g1 = -2.0 * m.value * m.d1 * (d2 + e) / zm**2
        rate = (p.d1 * m.value * f + p.value * m.d1 * g) / (4.0 * lk * lk)
        accel = ((p.d2 * m.value + p.d1 * m.d1) * f + p.d1 * m.value * f1 + (p.d1 * m.d1 + p.value * m.d2) * g
                 + p.value * m.d1 * g1) / (4.0 * lk * lk)
        # at a toggle a root is 0 and its derivatives unbounded (like 1/root, 1/root^3): the limits
        toward = np.where(e + m.value**2 >= 0, 1.0, -1.0)
        up = np.where(sin_t >= 0, 1.0, -1.0) * toward * np.where(m.toggle, 1.0, -1.0)
        rate = np.where(toggle, up * np.inf, rate)
        accel = np.where(toggle, -toward * np.inf, accel)
        out.append((d_delta + sense * branch * rate, dd_delta + sense * branch * accel))
    return out[0][0], out[1][0], out[0][1], out[1][1]


def _descent(residual: Callable[[float, float], tuple[float, float]], at: tuple[float, float],
             step: tuple[float, float], res: float) -> tuple[float, float, float, float] | None:
    """The Newton step from ``at`` (``at - step``), halved until the residual falls below ``res``: the new point
    and its residuals, or None when even 2^-30 of the step does not lower it (the residual is at rounding)."""
    fraction = 1.0
    while fraction >= 2.0**-30:
        a, b = at[0] - fraction * step[0], at[1] - fraction * step[1]
        f1, f2 = residual(a, b)
        if math.hypot(f1, f2) < res:
            return a, b, f1, f2
        fraction /= 2.0
    return None


def _times(x: np.ndarray, factor: float) -> np.ndarray:
    """x * factor, 0 where the factor is 0 (an unbounded rate times a zero speed adds nothing, never NaN)."""
    return np.zeros_like(x) if factor == 0 else x * factor


def _ratio(num: np.ndarray, den: np.ndarray) -> np.ndarray:
    """num / den with +-inf (never NaN) where den is 0; 0 where both are."""
    num, den = np.broadcast_arrays(np.asarray(num, dtype=float), np.asarray(den, dtype=float))
    out = np.zeros(num.shape)
    ok = den != 0
    out[ok] = num[ok] / den[ok]
    out[~ok & (num != 0)] = np.copysign(np.inf, num[~ok & (num != 0)])
    return out
