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
arccosine near +-1 would lose half the digits there).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SolverError, SpecError
from linkgen.kinematics.grashof import CHANGE_POINT_TOL, Grashof, check_lengths, classify

Assembly = Literal["open", "crossed"]
ASSEMBLIES: tuple[str, ...] = ("open", "crossed")
#: inputs this far (relative to the longest link) beyond a toggle are snapped onto it
FEASIBILITY_TOL = 1e-10
TWO_PI = 2.0 * math.pi


def _sign(assembly: str) -> int:
    if assembly not in ASSEMBLIES:
        raise SpecError(f"must be 'open' or 'crossed' (got {assembly!r})", "assembly")
    return 1 if assembly == "open" else -1


def _area4(a: float, b: float, c: np.ndarray) -> np.ndarray:
    """Four times the area of triangles with sides a, b (numbers) and c (array), by Kahan's stable form of
    Heron's formula with the sides sorted x >= y >= z; 0 where they only just close.

    With two sides fixed, the order is chosen by comparisons alone (no arithmetic), so it is exact.
    """
    p, q = max(a, b), min(a, b)
    x = np.maximum(c, p)
    z = np.minimum(c, q)
    y = np.where(c > p, p, np.where(c < q, q, c))
    prod = (x + (y + z)) * (z - (x - y)) * (z + (x - y)) * (x + (y - z))
    return np.sqrt(np.maximum(prod, 0.0))


def _degrees_range(lo: float, hi: float) -> tuple[float, float]:
    return (math.degrees(lo), math.degrees(hi))


@dataclass(frozen=True)
class Poses:
    """Positions at each input angle (arrays of the same length; angles in radians, points in mm)."""

    theta2: np.ndarray
    theta3: np.ndarray
    theta4: np.ndarray
    gamma: np.ndarray          # transmission angle
    a: np.ndarray              # (n, 2) crank pin
    b: np.ndarray              # (n, 2) coupler-rocker pin
    point: np.ndarray          # (n, 2) coupler point (the crank pin A when point_distance is 0)
    assembly: np.ndarray       # +1 open, -1 crossed, per pose


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
    theta3: float
    theta4: float
    steps: tuple[NewtonStep, ...]


@dataclass(frozen=True)
class FourBar:
    """A four-bar: ``ground`` L1, ``crank`` L2 (input), ``coupler`` L3, ``rocker`` L4, all mm.

    An optional coupler point lies at ``point_distance`` mm from A, at
    ``point_angle`` radians counter-clockwise from the coupler line A -> B.
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
        """Vector A -> O4 without cancellation: (L1 - L2) + 2 L2 sin^2(theta2 / 2), -L2 sin theta2."""
        dx = (self.ground - self.crank) + 2.0 * self.crank * np.sin(theta2 / 2.0) ** 2
        dy = -self.crank * np.sin(theta2)
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

    def _check_reach(self, theta2: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The vector A -> O4 and its length at each crank angle, or a clear error if one is out of reach."""
        dx, dy = self._z(theta2)
        z = np.hypot(dx, dy)
        tol = FEASIBILITY_TOL * self.longest
        bad = (z > self.coupler + self.rocker + tol) | (z < abs(self.coupler - self.rocker) - tol)
        if np.any(bad):
            ranges = self.input_ranges() or ()
            text = " or ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in (_degrees_range(*r) for r in ranges))
            first = math.degrees(float(np.asarray(theta2)[bad][0]))
            raise SpecError(f"crank angle {first:.6g} degrees is out of reach; this linkage reaches crank angles "
                            f"{text} degrees", "angle")
        if np.any(z <= tol):
            first = math.degrees(float(np.asarray(theta2)[z <= tol][0]))
            raise SpecError(f"at crank angle {first:.6g} degrees the crank pin sits on the rocker pivot, so the "
                            "coupler's position is undetermined (a deltoid change point)", "angle")
        return dx, dy, z

    # ------------------------------------------------------------------ positions

    def _poses(self, theta2: np.ndarray, sign: np.ndarray,
               reach: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None) -> Poses:
        l1, l3, l4 = self.ground, self.coupler, self.rocker
        if reach is None:
            dx, dy = self._z(theta2)
            z = np.hypot(dx, dy)
        else:
            dx, dy, z = reach
        area4 = _area4(l3, l4, z)
        # A -> B is the unit vector A -> O4 turned by the triangle's angle at A (its cosine by the law of
        # cosines, its sine from the stable area): no angle needs computing to place B
        two_l3z = 2.0 * l3 * z
        cos_a = (l3**2 + z**2 - l4**2) / two_l3z
        sin_a = sign * area4 / two_l3z
        ux, uy = dx / z, dy / z
        ex, ey = cos_a * ux - sin_a * uy, cos_a * uy + sin_a * ux
        ax, ay = self.crank * np.cos(theta2), self.crank * np.sin(theta2)
        bx, by = ax + l3 * ex, ay + l3 * ey
        theta3 = np.arctan2(ey, ex)
        theta4 = np.arctan2(by, bx - l1)
        gamma = np.arctan2(area4, l3**2 + l4**2 - z**2)           # angle at B: the transmission angle
        a = np.column_stack([ax, ay])
        b = np.column_stack([bx, by])
        if self.point_distance:
            ang = theta3 + self.point_angle
            point = a + self.point_distance * np.column_stack([np.cos(ang), np.sin(ang)])
        else:
            point = a
        return Poses(theta2, theta3, theta4, gamma, a, b, point, sign)

    def positions(self, theta2: ArrayLike, assembly: Assembly = "open") -> Poses:
        """Closed-form poses at crank angles ``theta2`` (radians) for one assembly label.

        Every angle must be reachable: an angle outside the reachable range is a
        :class:`SpecError` naming that range (never NaN). Labels swap at change
        points; use :meth:`sweep` to follow one branch through them.
        """
        t = np.atleast_1d(np.asarray(theta2, dtype=float))
        return self._poses(t, np.full(t.shape, _sign(assembly)), self._check_reach(t))

    def rocker_positions(self, theta4: ArrayLike, assembly: Assembly = "open") -> Poses:
        """Poses when the rocker drives, at rocker angles ``theta4`` (rad).

        Solved on the mirror image (reflected across the perpendicular bisector of
        the ground, the rocker becomes the crank) and reflected back; ``assembly``
        names the two solutions as the rocker sees them, i.e. the mirror's labels.
        """
        t4 = np.atleast_1d(np.asarray(theta4, dtype=float))
        m = FourBar(self.ground, self.rocker, self.coupler, self.crank).positions(math.pi - t4, assembly)
        a = np.column_stack([self.ground - m.b[:, 0], m.b[:, 1]])
        b = np.column_stack([self.ground - m.a[:, 0], m.a[:, 1]])
        theta2 = np.arctan2(a[:, 1], a[:, 0])
        theta3 = np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0])
        ang = theta3 + self.point_angle
        point = a + self.point_distance * np.column_stack([np.cos(ang), np.sin(ang)])
        return Poses(theta2, theta3, t4, m.gamma, a, b, point, m.assembly)

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
        t = np.atleast_1d(np.asarray(theta2, dtype=float))
        reach = self._check_reach(t)
        flips = np.zeros(t.shape, dtype=int)
        for cp in self.change_points():
            turn = np.floor((t - cp) / TWO_PI)
            flips[1:] += np.cumsum(np.abs(np.diff(turn))).astype(int)
        sign = _sign(assembly) * np.where(flips % 2 == 0, 1, -1)
        return self._poses(t, sign, reach)

    # ------------------------------------------------------------------ Newton-Raphson

    def residual(self, theta2: float, theta3: float, theta4: float) -> tuple[float, float]:
        """Loop-closure residuals (mm): L2 e^(i t2) + L3 e^(i t3) - L4 e^(i t4) - L1."""
        f1 = (self.crank * math.cos(theta2) + self.coupler * math.cos(theta3)
              - self.rocker * math.cos(theta4) - self.ground)
        f2 = self.crank * math.sin(theta2) + self.coupler * math.sin(theta3) - self.rocker * math.sin(theta4)
        return f1, f2

    def newton(self, theta2: float, guess: tuple[float, float], tol: float = 1e-12,
               max_iter: int = 50) -> NewtonResult:
        """Newton-Raphson on the loop closure for (theta3, theta4), radians, from ``guess``.

        Stops when the residual is below ``tol`` times the longest link. Raises
        :class:`SolverError` at a singular Jacobian (coupler and rocker collinear, a
        toggle) or after ``max_iter`` steps. The result carries the iteration table.
        """
        t3, t4 = float(guess[0]), float(guess[1])
        steps: list[NewtonStep] = []
        scale = self.longest
        for k in range(max_iter + 1):
            f1, f2 = self.residual(theta2, t3, t4)
            steps.append(NewtonStep(k, t3, t4, f1, f2))
            if math.hypot(f1, f2) <= tol * scale:
                return NewtonResult(t3, t4, tuple(steps))
            if k == max_iter:
                break
            # J = d(f1, f2)/d(t3, t4) = [[-L3 sin t3, L4 sin t4], [L3 cos t3, -L4 cos t4]]
            j11, j12 = -self.coupler * math.sin(t3), self.rocker * math.sin(t4)
            j21, j22 = self.coupler * math.cos(t3), -self.rocker * math.cos(t4)
            det = j11 * j22 - j12 * j21
            if abs(det) <= 1e-12 * self.coupler * self.rocker:
                raise SolverError(f"Newton-Raphson: singular Jacobian at iteration {k} (crank angle "
                                  f"{math.degrees(theta2):.6g} degrees): coupler and rocker are collinear, a toggle "
                                  "position; start from another guess or use the closed form")
            t3 -= (j22 * f1 - j12 * f2) / det
            t4 -= (-j21 * f1 + j11 * f2) / det
        raise SolverError(f"Newton-Raphson did not converge in {max_iter} iterations at crank angle "
                          f"{math.degrees(theta2):.6g} degrees (residual {math.hypot(f1, f2):.3g} mm)")

    # ------------------------------------------------------------------ derivatives

    def velocities(self, poses: Poses, omega2: float) -> tuple[np.ndarray, np.ndarray]:
        """Angular velocities (omega3, omega4) in rad/s for crank speed ``omega2`` rad/s.

        Unbounded (+-inf, never NaN) at a toggle, where coupler and rocker are collinear.
        """
        t2, t3, t4 = poses.theta2, poses.theta3, poses.theta4
        l2, l3, l4 = self.crank, self.coupler, self.rocker
        det = l3 * l4 * np.sin(t3 - t4)
        n3 = l2 * l4 * omega2 * np.sin(t4 - t2)
        n4 = l2 * l3 * omega2 * np.sin(t3 - t2)
        return _ratio(n3, det), _ratio(n4, det)

    def accelerations(self, poses: Poses, omega2: float, alpha2: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Angular accelerations (alpha3, alpha4) in rad/s^2 for crank speed ``omega2`` and acceleration ``alpha2``."""
        t2, t3, t4 = poses.theta2, poses.theta3, poses.theta4
        l2, l3, l4 = self.crank, self.coupler, self.rocker
        w3, w4 = self.velocities(poses, omega2)
        r1 = l2 * (np.cos(t2) * omega2**2 + np.sin(t2) * alpha2) + l3 * np.cos(t3) * w3**2 - l4 * np.cos(t4) * w4**2
        r2 = l2 * (np.sin(t2) * omega2**2 - np.cos(t2) * alpha2) + l3 * np.sin(t3) * w3**2 - l4 * np.sin(t4) * w4**2
        # [[-L3 s3, L4 s4], [L3 c3, -L4 c4]] [a3, a4] = [r1, r2]
        det = l3 * l4 * np.sin(t3 - t4)
        a3 = (-l4 * np.cos(t4) * r1 - l4 * np.sin(t4) * r2)
        a4 = (-l3 * np.sin(t3) * r2 - l3 * np.cos(t3) * r1)
        return _ratio(a3, det), _ratio(a4, det)

    def mechanical_advantage(self, poses: Poses) -> np.ndarray:
        """Output torque over input torque, |omega2 / omega4| (lossless): infinite at the rocker's dead centres."""
        num = self.rocker * np.abs(np.sin(poses.theta4 - poses.theta3))
        den = self.crank * np.abs(np.sin(poses.theta2 - poses.theta3))
        return _ratio(num, den)

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
                pose = self._poses(np.array([crank]), np.array([sign]))
                seen = any(d.kind == kind and abs(math.remainder(d.crank - crank, TWO_PI)) < 1e-9 for d in out)
                undetermined = math.hypot(*self._z(np.array(crank))) <= tol
                if np.linalg.norm(pose.b[0] - pin) <= 1e-7 * self.longest and not seen and not undetermined:
                    out.append(DeadCentre(kind, crank, float(pose.theta4[0])))
        for lo, hi in self.input_ranges() or ():
            for end in (lo, hi):
                pose = self._poses(np.array([end]), np.array([sign]))
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
        poses = self._poses(candidates, np.ones_like(candidates))
        i, j = int(np.argmin(poses.gamma)), int(np.argmax(poses.gamma))
        return (float(poses.gamma[i]), float(candidates[i])), (float(poses.gamma[j]), float(candidates[j]))


def _ratio(num: np.ndarray, den: np.ndarray) -> np.ndarray:
    """num / den with +-inf (never NaN) where den is 0; 0 where both are."""
    num, den = np.broadcast_arrays(np.asarray(num, dtype=float), np.asarray(den, dtype=float))
    out = np.zeros(num.shape)
    ok = den != 0
    out[ok] = num[ok] / den[ok]
    out[~ok & (num != 0)] = np.copysign(np.inf, num[~ok & (num != 0)])
    return out
