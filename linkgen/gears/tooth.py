"""An involute spur gear's teeth as the basic rack cuts them: involute flanks, trochoidal roots, tip and root circles.

**The basic rack** (ISO 53 profile A, in units of the module m): straight flanks at the pressure angle a, tooth
thickness pi m / 2 on its datum line, addendum 1 m, dedendum 1.25 m, and a fillet of radius rho where the flank
meets the dedendum line. Here rho = 0.25 m / (1 - sin a) (0.380 m at 20 degrees, ISO 53's 0.38 m), which ends the
straight flank exactly 1 m below the datum, so that the rack generates involutes down to the textbook working depth;
at pressure angles above about 22 degrees that fillet no longer fits the rack tooth's tip and rho is the largest that
does, the straight flank then reaching deeper (:attr:`BasicRack.straight_depth`).

**Generating** a gear of z teeth with profile shift x: the rack (as the cutter, its teeth cutting the gear's spaces)
rolls without slip on the reference (pitch) circle r = m z / 2 with its datum line x m outside it. The gear's
flanks are the envelope of the rack's flanks: involutes of the base circle rb = r cos a. Its root is the envelope of
the rack tip's fillet, a trochoid: the fillet's centre traces a curtate involute of the reference circle and the
root is that curve's parallel at rho; the contact point lies where the line from the fillet's centre through the
rolling point (the instantaneous centre) meets the fillet. Its root circle is the rack's tip line,
rf = r - (1.25 - x) m; its tip circle the blank's, ra = r + (1 + x) m (no tip shortening). The tooth thickness on the
reference circle is s = m (pi / 2 + 2 x tan a) less a thinning (the backlash allowance), which moves the rack's
flanks into the tooth and keeps the root.

**Undercut**: where the rack's straight flank reaches below the point where the line of action touches the base
circle, its tip fillet cuts away the involute's foot. With the flank straight to h m below the datum (h = 1 here up to
about 22 degrees), that happens for z < z_min = 2 (h - x) / sin^2 a (17.1 at 20 degrees, x = 0); the root trochoid
then crosses the involute and the flank starts at the crossing, a corner.

Frame (:class:`ExternalTooth`): the gear's centre at the origin, tooth 0 centred on +X; the "right" side is the
clockwise one (negative polar angles), the other its mirror image in the X axis. Lengths mm, angles rad.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from camgen.core.errors import DesignError
from linkgen.gears.fit import fit_arcs
from linkgen.gears.involute import involute_points, inv, roll_of, thickness_angle

#: the basic rack's addendum and dedendum, and the bottom clearance between them, in modules
ADDENDUM = 1.0
DEDENDUM = 1.25
CLEARANCE = DEDENDUM - ADDENDUM


@dataclass(frozen=True)
class BasicRack:
    """The basic rack of ``module`` (mm) and ``pressure_angle`` (rad) (see the module's notes)."""

    module: float
    pressure_angle: float

    @cached_property
    def fillet_radius(self) -> float:
        """rho (mm): 0.25 m / (1 - sin a), or the largest fillet that fits the tooth's tip where that one does not."""
        a, m = self.pressure_angle, self.module
        ideal = CLEARANCE * m / (1.0 - math.sin(a))
        tip_half = (math.pi * m / 2 - 2 * DEDENDUM * m * math.tan(a)) / 2
        return min(ideal, tip_half / math.tan(math.pi / 4 - a / 2))

    @property
    def straight_depth(self) -> float:
        """How far below the datum line the straight flank reaches, in modules (1 where the fillet is the ideal)."""
        return DEDENDUM - self.fillet_radius * (1.0 - math.sin(self.pressure_angle)) / self.module

    def fewest_teeth(self, shift: float) -> float:
        """z_min = 2 (h - x) / sin^2 a: the fewest teeth this rack cuts without undercut at profile shift ``shift``
        (h: :attr:`straight_depth`; 2 (1 - x) / sin^2 a in the textbook's range of pressure angles)."""
        return 2.0 * (self.straight_depth - shift) / math.sin(self.pressure_angle) ** 2


class OnRack:
    """What is cut by a basic rack (its ``rack``) has that rack's module and pressure angle."""

    rack: BasicRack

    @property
    def module(self) -> float:
        """m (mm)."""
        return self.rack.module

    @property
    def pressure_angle(self) -> float:
        """a (rad)."""
        return self.rack.pressure_angle


@dataclass(frozen=True)
class ExternalTooth(OnRack):
    """One tooth of an external gear cut by ``rack``: ``teeth`` z, profile ``shift`` x (in modules) and ``thinning``
    (mm: how much thinner than m (pi/2 + 2 x tan a) the tooth is on its reference circle; the backlash allowance).

    ``tip_radius`` overrides the blank's r + (1 + x) m (an internal gear's master, whose tips are the ring's roots).
    """

    rack: BasicRack
    teeth: int
    shift: float
    thinning: float = 0.0
    tip_radius_override: float | None = None

    # ------------------------------------------------------------------------------------------- closed forms

    @property
    def pitch_radius(self) -> float:
        """r = m z / 2 (mm): the reference circle."""
        return self.module * self.teeth / 2

    @property
    def base_radius(self) -> float:
        """rb = r cos a (mm)."""
        return self.pitch_radius * math.cos(self.pressure_angle)

    @property
    def tip_radius(self) -> float:
        """ra = r + (1 + x) m (mm), unless overridden."""
        if self.tip_radius_override is not None:
            return self.tip_radius_override
        return self.pitch_radius + (ADDENDUM + self.shift) * self.module

    @property
    def root_radius(self) -> float:
        """rf = r - (1.25 - x) m (mm): the rack's tip line."""
        return self.pitch_radius - (DEDENDUM - self.shift) * self.module

    @property
    def thickness(self) -> float:
        """The tooth's circular thickness on the reference circle, as made (mm): m (pi/2 + 2 x tan a) - thinning."""
        m, a = self.module, self.pressure_angle
        return m * (math.pi / 2 + 2 * self.shift * math.tan(a)) - self.thinning

    def thickness_at(self, radius: float) -> float:
        """The circular tooth thickness (mm) at ``radius`` (mm, on the involute: base radius or more)."""
        return 2 * radius * float(thickness_angle(radius, self.base_radius, self.pitch_radius, self.thickness))

    @property
    def tip_thickness(self) -> float:
        """The circular thickness on the tip circle (mm); <= 0 for a pointed tooth."""
        return self.thickness_at(self.tip_radius)

    @property
    def fewest_teeth(self) -> float:
        """z_min for this shift (:meth:`BasicRack.fewest_teeth`)."""
        return self.rack.fewest_teeth(self.shift)

    @property
    def undercut(self) -> bool:
        """Whether the rack's fillet cuts the involute's foot away (z < z_min)."""
        return self._form_distance < 0

    @property
    def _form_distance(self) -> float:
        """How far (mm) from the base circle's tangent point along the line of action the rack's lowest straight flank
        point generates its involute point: r sin a - (h - x) m / sin a; negative where it is undercut."""
        a, m = self.pressure_angle, self.module
        return self.pitch_radius * math.sin(a) - (self.rack.straight_depth - self.shift) * m / math.sin(a)

    # ------------------------------------------------------------------------------------------- the generation

    @property
    def _fillet_centre(self) -> tuple[float, float]:
        """The rack's tip fillet centre in the generating frame (xi along the rack, Y from the gear's centre)."""
        a, m, rho = self.pressure_angle, self.module, self.rack.fillet_radius
        eta = -DEDENDUM * m + rho
        xi = math.pi * m / 4 - self.thinning / 2 - eta * math.tan(a) + rho / math.cos(a)
        return xi, self.pitch_radius + self.shift * m + eta

    @property
    def fillet_range(self) -> tuple[float, float]:
        """The gear's roll angles (rad) at which the fillet cuts the root circle and meets the rack's flank."""
        xi, yc = self._fillet_centre
        r = self.pitch_radius
        return xi / r, (xi + (r - yc) / math.tan(self.pressure_angle)) / r

    def fillet(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Points (n, 2) mm and unit tangents (n, 2) of the right side's root trochoid at roll angles ``phi`` (rad).

        In the generating frame (tooth on +Y) the gear turns by phi counter-clockwise while the rack moves by
        -r phi; the fillet's centre C = (xi - r phi, Yc) is seen from the gear at R(-phi) C; the contact point is
        C + rho (C - P) / |C - P| with P = (0, r) the rolling point. The frame is then turned by -90 degrees.
        """
        phi = np.asarray(phi, dtype=float)
        xi, yc = self._fillet_centre
        r, rho = self.pitch_radius, self.rack.fillet_radius
        cx, cy = xi - r * phi, np.full_like(phi, yc)
        dx, dy = cx, cy - r
        length = np.hypot(dx, dy)
        ex, ey = dx / length, dy / length
        wx, wy = cx + rho * ex, cy + rho * ey
        # d/dphi of the contact point: C' = (-r, 0), e' = (C' - (e.C') e) / |C - P|
        dot = -r * ex
        dwx = -r + rho * (-r - dot * ex) / length
        dwy = rho * (-dot * ey) / length
        # turning: d/dphi R(-phi) W = R(-phi) (W' - J W) with J W = (-W_y, W_x)
        tx, ty = dwx + wy, dwy - wx
        c, s = np.cos(phi), np.sin(phi)
        gx, gy = c * wx + s * wy, -s * wx + c * wy
        vx, vy = c * tx + s * ty, -s * tx + c * ty
        norm = np.hypot(vx, vy)
        # turned by -90 degrees: (x, y) -> (y, -x)
        return np.column_stack([gy, -gx]), np.column_stack([vy / norm, -vx / norm])

    @property
    def involute_start(self) -> float:
        """The polar angle (rad) where the right flank's involute leaves the base circle: -(s / 2r + inv a)."""
        return -(self.thickness / (2 * self.pitch_radius) + float(inv(self.pressure_angle)))

    def flank(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Points and unit tangents of the right flank's involute at roll angles ``u`` (rad)."""
        return involute_points(self.base_radius, self.involute_start, u)

    def _crossing(self) -> float:
        """The roll angle (rad) where an undercut root's trochoid crosses the involute (found by halving the first
        change of sign of their angular distance at the same radius)."""
        lo, hi = self.fillet_range

        def gap(phi: np.ndarray) -> np.ndarray:
            points, _ = self.fillet(phi)
            radius = np.hypot(points[:, 0], points[:, 1])
            angle = np.arctan2(points[:, 1], points[:, 0])
            on = self.involute_start + inv(np.arctan(roll_of(radius, self.base_radius)))
            return np.where(radius >= self.base_radius, angle - on, np.inf)

        phi = np.linspace(lo, hi, 2001)
        g = gap(phi)
        change = np.flatnonzero((g[:-1] > 0) & (g[1:] <= 0))
        if not len(change):
            raise DesignError("the root trochoid of an undercut tooth does not cross its involute")
        a, b = float(phi[change[0]]), float(phi[change[0] + 1])
        for _ in range(60):
            middle = (a + b) / 2
            if gap(np.array([middle]))[0] > 0:
                a = middle
            else:
                b = middle
        return (a + b) / 2

    @cached_property
    def form(self) -> tuple[float, float]:
        """Where the root meets the flank: the fillet's roll angle (rad) and the involute's roll angle (rad) there
        (the involute's start; the crossing when undercut)."""
        if not self.undercut:
            return self.fillet_range[1], self._form_distance / self.base_radius
        phi = self._crossing()
        point, _ = self.fillet(np.array([phi]))
        return phi, float(roll_of(np.hypot(*point[0]), self.base_radius))

    @property
    def form_radius(self) -> float:
        """The radius (mm) where the involute flank starts."""
        return self.base_radius * math.hypot(1.0, self.form[1])

    @property
    def tip_roll(self) -> float:
        return float(roll_of(self.tip_radius, self.base_radius))

    def side(self, tolerance: float, root: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """The right side as arcs within ``tolerance`` mm, from the root circle (``root``: the fillet first; else the
        involute from its start) up to the tip circle: its pieces' start vertices (k, 2) and bulges (k,); the chain
        ends at the flank's tip corner, the last vertex given (with a bulge of 0 that the caller replaces)."""
        phi, u = self.form
        pieces = [fit_arcs(self.fillet, self.fillet_range[0], phi, tolerance)] if root else []
        pieces.append(fit_arcs(self.flank, u, self.tip_roll, tolerance))
        tip, _ = self.flank(np.array([self.tip_roll]))
        return np.vstack([*(v for v, _ in pieces), tip]), np.concatenate([*(b for _, b in pieces), [0.0]])

    def check(self) -> None:
        """Refuse a tooth that cannot be drawn: pointed (its flanks meet inside the tip circle), a flank that starts
        at or beyond the tip, a root circle at or inside the centre."""
        if self.root_radius <= 0:
            raise DesignError(f"the root circle's radius is {self.root_radius:.6g} mm: the tooth leaves no gear")
        if self.tip_thickness <= 0:
            raise DesignError(f"the teeth come to a point inside the tip circle (tip thickness "
                              f"{self.tip_thickness:.4g} mm)")
        if self.form_radius >= self.tip_radius:
            raise DesignError("the involute flank starts at or beyond the tip circle")
