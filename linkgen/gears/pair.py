"""A meshing pair: an external pair, an internal gear with its pinion, or a rack and pinion; how it turns and the
checks a gear designer makes.

Frame: the pinion's centre at the origin. An external gear's centre is at (c, 0), an internal gear's too (the pinion
inside it, meshing on its -X side), c the working centre distance; a rack lies below the pinion, its datum line at
y = -(r1 + x1 m), its teeth up, and moves along +X as the pinion turns counter-clockwise. Angles are
counter-clockwise, in radians; lengths mm.

**Working pressure angle and centre distance** of shifted gears (zero backlash on the nominal teeth):
inv a_w = inv a + 2 tan a (x1 + x2) / (z1 + z2) for an external pair, inv a + 2 tan a (x2 - x1) / (z2 - z1) for an
internal one (x2: the shift of the external gear whose teeth are the ring's spaces, :mod:`linkgen.gears.tooth`);
c = (r2 +- r1) cos a / cos a_w; the working pitch radii r_wi = ri cos a / cos a_w. A rack meshes at a = a_w, on the
pinion's reference circle.

**Backlash** j (circular, on the working pitch circles): each member's teeth are thinned by j / 2 there, which is
j cos a_w / (2 cos a) on its reference circle (the rack's j / 2 everywhere); the normal backlash is j cos a_w.

**Contact ratio** (length of the path of contact over the base pitch p_b = pi m cos a):
external (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - c sin a_w) / p_b; internal
(sqrt(ra1^2 - rb1^2) - sqrt(ra2^2 - rb2^2) + c sin a_w) / p_b with ra2 the ring's tip (inner) radius; rack
(sqrt(ra1^2 - rb1^2) - r1 sin a + (1 - x1) m / sin a) / p_b.

**Phases**: at pinion angle 0 tooth 0 of the pinion is centred on +X; each member is placed so that a tooth and a
space are centred on the line of centres at once, the backlash then shared equally between both flanks.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np

from linkgen.gears.involute import inv, inv_inverse
from linkgen.gears.tooth import ADDENDUM, DEDENDUM, BasicRack, ExternalTooth, OnRack

Kind = Literal["external", "internal", "rack"]


def _near_zero(angle: float, pitch: float) -> float:
    """``angle`` (rad) less whole ``pitch`` angles, in [-pitch / 2, pitch / 2)."""
    return (angle + pitch / 2) % pitch - pitch / 2


@dataclass(frozen=True)
class GearPair(OnRack):
    """A meshing pair (see the module's notes): ``kind``, the basic ``rack`` (module and pressure angle), the pinion's
    teeth and shift, the other member's teeth (a rack's: how many it has) and shift (0 for a rack), the backlash
    (mm, circular on the working pitch circles)."""

    kind: Kind
    rack: BasicRack
    pinion_teeth: int
    pinion_shift: float
    gear_teeth: int
    gear_shift: float
    backlash: float

    @cached_property
    def working_pressure_angle(self) -> float:
        """a_w (rad)."""
        a = self.pressure_angle
        z1, z2, x1, x2 = self.pinion_teeth, self.gear_teeth, self.pinion_shift, self.gear_shift
        if self.kind == "rack":
            return a
        if self.kind == "external":
            value = float(inv(a)) + 2 * math.tan(a) * (x1 + x2) / (z1 + z2)
        else:
            value = float(inv(a)) + 2 * math.tan(a) * (x2 - x1) / (z2 - z1)
        return float(inv_inverse(value))

    @property
    def _stretch(self) -> float:
        """cos a / cos a_w: the working pitch radii over the reference radii."""
        return math.cos(self.pressure_angle) / math.cos(self.working_pressure_angle)

    @cached_property
    def pinion_tooth(self) -> ExternalTooth:
        """The pinion, thinned by its half of the backlash."""
        return ExternalTooth(self.rack, self.pinion_teeth, self.pinion_shift, self.backlash / (2 * self._stretch))

    @cached_property
    def gear_tooth(self) -> ExternalTooth | None:
        """The external gear thinned by its half of the backlash; for an internal gear the external gear whose teeth
        are its spaces (thickened by that half, its tips on the ring's root circle); None for a rack."""
        m = self.module
        if self.kind == "rack":
            return None
        thinning = self.backlash / (2 * self._stretch)
        if self.kind == "external":
            return ExternalTooth(self.rack, self.gear_teeth, self.gear_shift, thinning)
        root = self.module * self.gear_teeth / 2 + (DEDENDUM + self.gear_shift) * m
        return ExternalTooth(self.rack, self.gear_teeth, self.gear_shift, -thinning, root)

    @property
    def rack_thinning(self) -> float:
        """How much thinner than pi m / 2 a rack's teeth are (mm): half the backlash."""
        return self.backlash / 2

    @property
    def ring_tip_radius(self) -> float:
        """An internal gear's tip (inner) radius r2 - (1 - x2) m (mm)."""
        return self.module * self.gear_teeth / 2 - (ADDENDUM - self.gear_shift) * self.module

    @property
    def centre_distance(self) -> float:
        """c (mm): the working centre distance; for a rack, from the pinion's centre to the rack's datum line."""
        r1 = self.module * self.pinion_teeth / 2
        if self.kind == "rack":
            return r1 + self.pinion_shift * self.module
        r2 = self.module * self.gear_teeth / 2
        return (r2 + r1 if self.kind == "external" else r2 - r1) * self._stretch

    @property
    def working_pitch_radii(self) -> tuple[float, float]:
        """(r_w1, r_w2) mm; a rack's r_w2 is infinite."""
        r1 = self.module * self.pinion_teeth / 2
        if self.kind == "rack":
            return r1, math.inf
        return r1 * self._stretch, self.module * self.gear_teeth / 2 * self._stretch

    @property
    def speed_ratio(self) -> float:
        """The gear's angular speed over the pinion's: -z1 / z2 (external, opposite senses), +z1 / z2 (internal);
        for a rack its speed (mm/s) per pinion speed (rad/s), r1."""
        if self.kind == "rack":
            return self.module * self.pinion_teeth / 2
        sign = -1.0 if self.kind == "external" else 1.0
        return sign * self.pinion_teeth / self.gear_teeth

    @property
    def contact_ratio(self) -> float:
        """The textbook contact ratio (see the module's notes)."""
        m, a, aw = self.module, self.pressure_angle, self.working_pressure_angle
        p = self.pinion_tooth
        first = math.sqrt(p.tip_radius**2 - p.base_radius**2)
        base_pitch = math.pi * m * math.cos(a)
        if self.kind == "rack":
            return (first - p.pitch_radius * math.sin(a) + (ADDENDUM - self.pinion_shift) * m / math.sin(a)) \
                / base_pitch
        g = self.gear_tooth
        assert g is not None
        c = self.centre_distance
        if self.kind == "external":
            second = math.sqrt(g.tip_radius**2 - g.base_radius**2)
            return (first + second - c * math.sin(aw)) / base_pitch
        second = math.sqrt(max(self.ring_tip_radius**2 - g.base_radius**2, 0.0))
        return (first - second + c * math.sin(aw)) / base_pitch

    @property
    def tip_clearance(self) -> tuple[float, float]:
        """The radial clearance (mm) between each member's tips and the other's root circle on the line of centres:
        the pinion's tips first."""
        p, g, c = self.pinion_tooth, self.gear_tooth, self.centre_distance
        if g is None:
            m = self.module
            return c + DEDENDUM * m - p.tip_radius, c - ADDENDUM * m - p.root_radius
        if self.kind == "external":
            return c - p.tip_radius - g.root_radius, c - g.tip_radius - p.root_radius
        # the ring's root circle is its master's tip circle
        return g.tip_radius - (c + p.tip_radius), (self.ring_tip_radius - c) - p.root_radius

    @property
    def ring_interference(self) -> float:
        """For an internal gear: how far (mm) along the line of action the ring's tips reach short of the point where
        it touches the pinion's base circle, sqrt(ra2^2 - rb2^2) - c sin a_w (negative: its tips dig into the
        pinion's flanks below their involutes); +inf for the other kinds."""
        g = self.gear_tooth
        if self.kind != "internal" or g is None:
            return math.inf
        reach = math.sqrt(max(self.ring_tip_radius**2 - g.base_radius**2, 0.0))
        return reach - self.centre_distance * math.sin(self.working_pressure_angle)

    # --------------------------------------------------------------------------------------------- motion

    @property
    def mesh_phases(self) -> tuple[float, float]:
        """(pinion angle, gear angle) (rad) at which a pinion tooth is centred on the line of centres (pinion angle in
        [-pitch/2, pitch/2)) and the other member's space too; for a rack, its shift (mm) then, 0."""
        z1 = self.pinion_teeth
        pitch = 2 * math.pi / z1
        if self.kind == "external":
            return 0.0, math.pi - math.pi / self.gear_teeth
        if self.kind == "internal":
            return _near_zero(math.pi, pitch), math.pi
        return _near_zero(-math.pi / 2, pitch), 0.0

    def gear_angle(self, theta: np.ndarray) -> np.ndarray:
        """The other member's position at pinion angles ``theta`` (rad): its angle (rad) about its own centre, or a
        rack's shift along +X (mm) from where a space is centred under the pinion."""
        theta = np.asarray(theta, dtype=float)
        first, second = self.mesh_phases
        return second + self.speed_ratio * (theta - first)
