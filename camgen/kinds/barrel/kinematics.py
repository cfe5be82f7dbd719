"""The exact walls of a barrel cam's groove, and the distance of any point from them. numpy only.

Frame and signs. The cam's axis is +Z, the cylinder runs from z = 0 to z = length. The roller's
axis is radial; at cam angle theta its centre (on the pitch cylinder, radius Rm) is at the height
zc(theta) = z0 + s(theta). The cam turns in its sense of rotation, so in the cam's own frame the
roller stands at the polar angle psi = -sense theta (sense +1 counter-clockwise seen from +Z);
everything below is worked in theta ("the program's angle": the developed drawing's x = Rm theta)
and turned into psi at the end, a reflection for a counter-clockwise cam, which keeps distances.

The groove is what a cylinder of radius Rw = Rr + c/2 (the roller and half the running clearance)
about that radial axis sweeps. On the cylinder of radius r a point at angle phi (theta-space) and
height z lies in the roller at theta when (r sin(phi - theta))^2 + (z - zc(theta))^2 <= Rw^2; the
wall at radius r is the envelope of those curves over theta. With w = r sin(phi - theta) and
zc' = dzc/dtheta, the envelope condition r^2 sin cos (phi - theta) = -(z - zc) zc' gives, on the
side ``side`` (-1 the lower wall, towards z = 0; +1 the upper),

    w^2 (r^2 - w^2) = zc'^2 (Rw^2 - w^2),   w = -side sign(zc') |w|,   z = zc + side sqrt(Rw^2 - w^2)

(the smaller root: w^2 = 2 zc'^2 Rw^2 / (r^2 + zc'^2 + sqrt((r^2 + zc'^2)^2 - 4 zc'^2 Rw^2))), so the wall
is explicit in theta. At r = Rm it differs from the developed curve's plane offset by Rw (what a
flat drawing would give) by about Rw^3 / (6 Rm^2) where the groove is steep; the walls at other radii
differ more (the developed curve at radius r is (r theta, zc), steeper for smaller r).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.followers.barrel import Arm, contact, translating_pose

#: Newton steps of the distance from a point to the walls, the largest step, and the step (rad) at which every
#: point has settled (the distance then off by about the step squared times the cutter's radius: 1e-24 mm)
_NEWTON, _STEP, _SETTLED = 30, 0.05, 1e-12


@dataclass(frozen=True)
class GrooveWalls:
    """The groove round a barrel: the program (s, s', s'' of theta, mm), the pitch curve's rest height ``z0`` (mm),
    the cutter's radius ``cutter`` = Rr + c/2 (mm) and the cam's ``sense`` of rotation (+1 counter-clockwise)."""

    program: Any
    z0: float
    cutter: float
    sense: int = 1
    arm: Arm | None = None
    taper: float = 0.0
    pitch_radius: float = 0.0

    @property
    def r0(self) -> float:
        """The cutter's radius (mm) where its axis passes nearest the cam's axis: R(a) = r0 + taper a."""
        return self.cutter - self.taper * self.pitch_radius

    def pose(self, theta: np.ndarray) -> np.ndarray:
        """zc, zc', zc'', e, e', e'' (mm, per rad^k) at cam angles ``theta`` (rad): the roller axis's height and its
        tangential offset from the cam's axis in theta-space (see :mod:`camgen.followers.barrel`), and their rates."""
        m = self.program.evaluate(np.asarray(theta, dtype=float))
        return translating_pose(m, self.z0) if self.arm is None else self.arm.pose(m)

    def centre(self, theta: np.ndarray) -> np.ndarray:
        """zc, zc', zc'' (mm, per rad^k) at cam angles ``theta`` (rad): the roller centre's height and its rates."""
        return self.pose(theta)[:3]

    def wall(self, theta: np.ndarray, radius: np.ndarray, side: int) -> tuple[np.ndarray, np.ndarray]:
        """The wall point the roller at cam angle ``theta`` touches on the cylinder of ``radius`` (broadcast):
        (its polar angle psi in the cam's frame, rad; its height z, mm). ``side`` -1: the lower wall, +1: upper."""
        phi, z = self.developed(theta, radius, side)
        return -self.sense * phi, z

    def developed(self, theta: np.ndarray, radius: np.ndarray | float, side: int) -> tuple[np.ndarray, np.ndarray]:
        """As :meth:`wall`, the angle in theta-space (the developed drawing's x is the radius times it)."""
        theta, radius = np.broadcast_arrays(np.asarray(theta, dtype=float), np.asarray(radius, dtype=float))
        if self.arm is not None or self.taper:
            pose = self.pose(theta.ravel())
            w, v, _, _ = contact(radius.ravel(), pose, self.r0, self.taper, side)
            phi = theta.ravel() + np.arcsin((w + pose[3]) / radius.ravel())
            return phi.reshape(theta.shape), (pose[0] + v).reshape(theta.shape)
        zc, slope, _ = self.centre(theta.ravel())
        zc, slope = zc.reshape(theta.shape), slope.reshape(theta.shape)
        r2, rw = radius**2, self.cutter
        a = r2 + slope**2
        w2 = 2 * slope**2 * rw**2 / (a + np.sqrt(np.maximum(a * a - 4 * slope**2 * rw**2, 0.0)))
        w = -side * np.sign(slope) * np.sqrt(w2)
        return theta + np.arcsin(w / radius), zc + side * np.sqrt(np.maximum(rw**2 - w2, 0.0))

    def deviation(self, points: np.ndarray) -> np.ndarray:
        """Signed distance (mm) of ``points`` (n, 3) from the groove's surface: the distance to the nearest roller
        axis less Rw (negative inside the groove). The nearest axis by Newton's method on the squared distance
        h(theta) = (r sin(phi - theta))^2 + (z - zc(theta))^2, started at the point's own angle (the roller
        nearest a wall point stands within a few degrees of it) and stopped once every point has settled."""
        points = np.asarray(points, dtype=float)
        r = np.hypot(points[:, 0], points[:, 1])
        phi = -self.sense * np.arctan2(points[:, 1], points[:, 0])
        z = points[:, 2]
        theta = phi.copy()
        for _ in range(_NEWTON):
            zc, z1, z2, e, e1, e2 = self.pose(np.mod(theta, 2 * math.pi))
            u = phi - theta
            if self.taper:
                h1, h2 = self._cone_rates(r, u, z - zc, z1, z2, e, e1, e2)
            else:
                h1 = -r**2 * np.sin(2 * u) - 2 * (z - zc) * z1 + 2 * (e * r * np.cos(u) + e * e1 - e1 * r * np.sin(u))
                h2 = 2 * r**2 * np.cos(2 * u) + 2 * z1**2 - 2 * (z - zc) * z2 + 2 * (
                    2 * r * np.cos(u) * e1 + e1**2 - r * np.sin(u) * e2 + e * r * np.sin(u) + e * e2)
            step = np.clip(np.where(h2 > 0, h1 / np.where(h2 > 0, h2, 1.0), -np.sign(h1) * _STEP), -_STEP, _STEP)
            theta = theta - step
            if float(np.abs(step).max(initial=0.0)) < _SETTLED:
                break
        zc, _, _, e, _, _ = self.pose(np.mod(theta, 2 * math.pi))
        rho = np.sqrt((r * np.sin(phi - theta) - e) ** 2 + (z - zc) ** 2)
        if self.taper:
            return (rho - self.r0 - self.taper * r * np.cos(phi - theta)) / math.hypot(1.0, self.taper)
        return rho - self.cutter

    def _cone_rates(self, r: np.ndarray, u: np.ndarray, v: np.ndarray, z1: np.ndarray, z2: np.ndarray,
                    e: np.ndarray, e1: np.ndarray, e2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The first and second rates with theta of g = rho - taper a (its distance from the cone, times
        sqrt(1 + taper^2), less r0) at the point (r, u = phi - theta, v = z - zc): what Newton's method minimises."""
        w, w1, w2 = r * np.sin(u) - e, -r * np.cos(u) - e1, -r * np.sin(u) - e2
        rho = np.sqrt(w**2 + v**2)
        h1 = 2 * (w * w1 - v * z1)
        h2 = 2 * (w1**2 + w * w2 + z1**2 - v * z2)
        return (h1 / (2 * rho) - self.taper * r * np.sin(u),
                h2 / (2 * rho) - h1**2 / (4 * rho**3) + self.taper * r * np.cos(u))

    def plane_offset_gap(self, radius: float, samples: int = 2048) -> float:
        """The largest distance (mm) of the exact walls on the cylinder of ``radius`` from the plane offsets by Rw
        of the developed curve (r theta, zc) there, what a flat drawing would take for the walls: the distance
        from each exact wall point to the developed curve (Newton on it, near the point's own angle) less Rw."""
        theta = 2 * math.pi * np.arange(samples) / samples
        worst = 0.0
        for side in (-1, 1):
            phi, z = self.developed(theta, radius, side)
            t = phi.copy()
            for _ in range(_NEWTON):
                zc, z1, z2, e, e1, e2 = self.pose(np.mod(t, 2 * math.pi))
                root = np.sqrt(radius**2 - e**2)
                k1, k2 = e1 / root, e2 / root + e * e1**2 / root**3
                dx = radius * (phi - t - np.arcsin(e / radius))
                h1 = -2 * radius * (1 + k1) * dx - 2 * (z - zc) * z1
                h2 = 2 * radius**2 * (1 + k1) ** 2 + 2 * z1**2 - 2 * (z - zc) * z2 - 2 * radius * dx * k2
                t = t - np.clip(h1 / h2, -_STEP, _STEP)
            zc, _, _, e, _, _ = self.pose(np.mod(t, 2 * math.pi))
            gap = np.hypot(radius * (phi - t - np.arcsin(e / radius)), z - zc) - (self.r0 + self.taper * radius)
            worst = max(worst, float(np.abs(gap).max()))
        return worst
