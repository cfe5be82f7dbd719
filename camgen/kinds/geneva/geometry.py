"""The parts of a Geneva drive as exact lines and arcs: the wheel, the locking disc and the crank.

Each part is drawn in its own frame about its own axis (the origin). The wheel: slot k's centre
line runs from the axis along the direction 2 pi k / n (slot 0 on +X); its flanks are lines
h = (pin diameter + slot clearance) / 2 either side, closed at the bottom by a half circle of
radius h about the point C - a from the axis (where the pin's centre gets nearest), open at the
rim, a circle of radius R_w = sqrt(b^2 + h^2) (b = C cos(pi/n)), so a flank ends at the rim
exactly where the pin's centre enters. Between two slots the rim carries a concave locking arc
of radius R_l = locking-disc radius + lock clearance about the point C from the axis on the
bisector (where the driver's axis stands during the dwell). The locking disc (driver frame, the
crank along +X): a circle of its radius less a cutout, an arc about (C, 0), where the wheel's
axis stands when the pin is deepest in a slot, that lets the wheel pass while it turns: its
radius is the farthest from (C, 0) any point of the wheel comes inside the lock clearance round
the disc's circle, over the whole index, plus the lock clearance (found by placing the wheel at
the driver's angles, refined round the worst; see :meth:`GenevaGeometry.cutout_radius`). The
crank: a bar of ``crank_width`` with round ends from the driver's axis to the pin at (a, 0).

Poses. In the assembly the driver's axis is the origin and the wheel's (C, 0); at driver angle
alpha the driver's frame is turned by alpha and the wheel's by pi - beta(alpha) about its axis
(slot 0 then points at the driver's axis when beta = 0; see :mod:`camgen.kinds.geneva.kinematics`).

Every outline can be made with its material grown outwards by ``grow`` mm (a laser's half kerf):
the flanks, slot bottoms, locking arcs and the cutout move into the air, the rims and the disc
grow, exactly (they stay lines and arcs). Lengths in mm, angles in radians, counter-clockwise.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from camgen.core.shapes import Circle, Contour, rounded_hull
from camgen.kinds.geneva.kinematics import GenevaLaw
from camgen.numeric import maximise

#: the chord tolerance (mm) of the outlines the cutout is sized from
_FINE = 1e-4


def _unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


def _bulge(sweep: float) -> float:
    return math.tan(sweep / 4.0)


def cosine_rule(a: float, b: float, opposite: float) -> float:
    """The angle (rad) between sides ``a`` and ``b`` of a triangle whose third side is ``opposite``."""
    return math.acos(max(-1.0, min(1.0, (a * a + b * b - opposite * opposite) / (2 * a * b))))


@dataclass(frozen=True)
class GenevaGeometry:
    """The dimensions of a Geneva drive (mm) and its parts' outlines. ``lock_radius`` is the locking disc's."""

    slots: int
    centre_distance: float
    pin_diameter: float
    slot_clearance: float
    lock_clearance: float
    lock_radius: float
    crank_width: float
    driver_bore: float = 0.0
    wheel_bore: float = 0.0

    @property
    def law(self) -> GenevaLaw:
        return GenevaLaw(self.slots, self.centre_distance)

    @property
    def crank_radius(self) -> float:
        """a = C sin(pi/n): the pin's circle about the driver's axis."""
        return self.law.crank_radius

    @property
    def half_width(self) -> float:
        """h: half the slot's width, (pin diameter + slot clearance) / 2."""
        return (self.pin_diameter + self.slot_clearance) / 2

    @property
    def bottom(self) -> float:
        """C - a: the slot bottom's half circle's centre, from the wheel's axis (the pin's nearest)."""
        return self.centre_distance - self.crank_radius

    @property
    def wheel_radius(self) -> float:
        """R_w = sqrt(b^2 + h^2): the wheel's rim, where each flank ends at the pin's entry point."""
        return math.hypot(self.law.entry_radius, self.half_width)

    @property
    def lock_arc_radius(self) -> float:
        """R_l: the wheel's concave locking arcs, the locking disc's radius plus the lock clearance."""
        return self.lock_radius + self.lock_clearance

    @cached_property
    def cutout_radius(self) -> float:
        """The locking disc's cutout (mm), about (C, 0) in the driver's frame: the lock clearance plus the farthest
        from (C, 0) that the wheel comes inside the lock clearance round the disc's circle during an index.

        Any point p inside the cutout's circle is at least R - |p - (C, 0)| from the disc, so this keeps every
        point of the wheel at least the clearance from it. The farthest is the largest over the vertices of the
        wheel's outline (chords within 1e-4 mm) clipped to the circle of radius disc + clearance - 2e-4 mm (the
        chords of the locking arcs, concentric at entry and exit, stay out of it), maximised over the driver's
        angle in the engagement (a grid refined round the best, :func:`camgen.numeric.maximise`); and at least
        enough to cut the disc.
        """
        import shapely

        centre, zone = np.array([self.centre_distance, 0.0]), self.lock_radius + self.lock_clearance - 2 * _FINE
        ring = self.wheel().flatten(_FINE)
        disc = shapely.Polygon(Circle((0.0, 0.0), zone).flatten(_FINE))

        def farthest(alpha: np.ndarray) -> np.ndarray:
            inside = shapely.intersection(shapely.polygons(self.in_driver_frame(ring, alpha)), disc)
            out = np.zeros(len(alpha))
            for i, shape in enumerate(inside):
                pts = shapely.get_coordinates(shape)
                out[i] = np.linalg.norm(pts - centre, axis=1).max() if len(pts) else 0.0
            return out

        e = self.law.engagement
        found = maximise(farthest, -e, e, n=181, rounds=6)[1] + self.lock_clearance
        return max(found, self.centre_distance - self.lock_radius + 2 * _FINE)     # it always cuts the disc

    def in_driver_frame(self, points: np.ndarray, alpha: np.ndarray) -> np.ndarray:
        """``points`` (m, 2) of the wheel's frame, at each driver angle ``alpha`` (k,), in the driver's frame
        (k, m, 2): turned by pi - beta about the wheel's axis, moved to (C, 0), turned back by -alpha."""
        alpha = np.asarray(alpha, dtype=float)
        turn = math.pi - self.law.motion(alpha)[0] - alpha
        c, s = np.cos(turn)[:, None], np.sin(turn)[:, None]
        x, y = points[None, :, 0], points[None, :, 1]
        cx, sx = (self.centre_distance * np.cos(-alpha))[:, None], (self.centre_distance * np.sin(-alpha))[:, None]
        return np.stack([c * x - s * y + cx, s * x + c * y + sx], axis=-1)

    @property
    def lock_radius_range(self) -> tuple[float, float]:
        """The locking disc's radii (mm) that work, exclusive: it must reach inside the wheel's rim, or the wheel
        could turn past it (R > C - R_w), and its arcs must meet the rim clear of the slots' flanks (R_l < a - h,
        where they would touch them at the mouth)."""
        return self.centre_distance - self.wheel_radius, self.crank_radius - self.half_width - self.lock_clearance

    def check(self) -> None:
        """Raise ``ValueError("geneva.<field>: ...")`` naming the first dimension that leaves no part, with its
        allowed range."""
        n, c, h = self.slots, self.centre_distance, self.half_width
        web = 2 * self.bottom * math.sin(math.pi / n)
        if not 2 * h < web:
            raise ValueError(f"geneva.pin_diameter: a slot {2 * h:.6g} mm wide (pin_diameter + slot_clearance) leaves "
                             f"no wheel between neighbouring slots; for {n} slots {c:g} mm apart it must be < "
                             f"{web:.6g} mm")
        low, high = self.lock_radius_range
        if not low < self.lock_radius < high:
            raise ValueError(f"geneva.lock_radius: must be > {low:.6g} and < {high:.6g} mm, so the disc reaches inside "
                             "the wheel's rim and its arcs meet the rim clear of the slots "
                             f"(got {self.lock_radius:.6g})")
        if not self.wheel_bore / 2 < self.bottom - h:
            raise ValueError(f"geneva.wheel_bore: must be < {2 * (self.bottom - h):.6g} mm, inside the slots' bottoms "
                             f"(got {self.wheel_bore:g})")
        if not self.pin_diameter < self.crank_width:
            raise ValueError(f"geneva.crank_width: must be > pin_diameter {self.pin_diameter:g} mm, so the crank holds "
                             f"the pin (got {self.crank_width:g})")
        if not (self.lock_overlap > 0 and c - self.cutout_radius > 0):
            what = ("leaves the wheel unlocked at the ends of the dwell" if c - self.cutout_radius > 0
                    else "reaches past the driver's axis")
            raise ValueError(f"geneva.lock_radius: the cutout the wheel needs in a locking disc of "
                             f"{self.lock_radius:.6g} mm {what}; a larger disc works (up to < {high:.6g} mm)")
        reach = min(self.lock_radius, c - self.cutout_radius, self.crank_width / 2)
        if not self.driver_bore / 2 < reach:
            raise ValueError(f"geneva.driver_bore: must be < {2 * reach:.6g} mm, inside the locking disc clear of "
                             f"its cutout and inside the crank (got {self.driver_bore:g})")

    @property
    def lock_overlap(self) -> float:
        """How far (rad, about the driver's axis) the locking disc still covers a locking arc where the dwell starts
        and ends: the engagement's half angle plus the arc's half span, less the cutout's half span. Positive: the
        wheel is held over the whole dwell."""
        c, disc = self.centre_distance, self.lock_radius
        epsilon = cosine_rule(c, self.lock_arc_radius, self.wheel_radius)
        return self.law.engagement + epsilon - cosine_rule(disc, c, self.cutout_radius)

    def _rim_tips(self, grow: float) -> tuple[float, float]:
        """(s_t, delta) with the material grown by ``grow``: where a flank meets the rim, along the slot, and the
        half angle (seen from the wheel's axis) of a locking arc's ends about its bisector."""
        h, rim, lock = self.half_width - grow, self.wheel_radius + grow, self.lock_arc_radius - grow
        return math.sqrt(rim * rim - h * h), cosine_rule(self.centre_distance, rim, lock)

    def wheel(self, grow: float = 0.0) -> Contour:
        """The wheel's outline (counter-clockwise), its material grown by ``grow`` mm."""
        n, c = self.slots, self.centre_distance
        h, rim, lock = self.half_width - grow, self.wheel_radius + grow, self.lock_arc_radius - grow
        s_t, delta = self._rim_tips(grow)
        flank = math.atan2(h, s_t)                     # a flank's end on the rim, from its slot's centre line
        epsilon = cosine_rule(c, lock, rim)           # a locking arc's half angle about its own centre
        verts, bulges = [], []
        for k in range(n):
            phi = 2 * math.pi * k / n
            e, m = _unit(phi), _unit(phi + math.pi / 2)
            bisector = phi + math.pi / n
            verts += [s_t * e - h * m, self.bottom * e - h * m, self.bottom * e + h * m, s_t * e + h * m,
                      rim * _unit(bisector - delta), rim * _unit(bisector + delta)]
            bulges += [0.0, _bulge(-math.pi), 0.0, _bulge(bisector - delta - phi - flank), _bulge(-2 * epsilon),
                       _bulge(phi + 2 * math.pi / n - flank - bisector - delta)]
        return Contour(np.array(verts), np.array(bulges))

    def lock(self, grow: float = 0.0) -> Contour:
        """The locking disc's outline (counter-clockwise, the crank along +X), its material grown by ``grow`` mm."""
        c, disc, cut = self.centre_distance, self.lock_radius + grow, self.cutout_radius - grow
        eta = cosine_rule(disc, c, cut)               # the cutout's ends, seen from the driver's axis
        zeta = cosine_rule(c, cut, disc)              # ... and from the cutout's centre
        return Contour(np.array([disc * _unit(eta), disc * _unit(-eta)]),
                       np.array([_bulge(2 * math.pi - 2 * eta), _bulge(-2 * zeta)]))

    def crank(self, grow: float = 0.0) -> Contour:
        """The crank's outline: a bar of ``crank_width`` (+ 2 grow) with round ends about the axis and the pin."""
        return rounded_hull(np.array([[0.0, 0.0], [self.crank_radius, 0.0]]), self.crank_width / 2 + grow)

    def pin_hole(self, grow: float = 0.0) -> Circle:
        """The crank's hole for the pin, at (a, 0), its edge moved out by ``grow`` mm."""
        return Circle((self.crank_radius, 0.0), self.pin_diameter / 2 + grow)

    def tip_width(self) -> float:
        """The rim between a flank and the next locking arc (mm, along the rim): the wheel's thinnest tip."""
        s_t, delta = self._rim_tips(0.0)
        return self.wheel_radius * (math.pi / self.slots - delta - math.atan2(self.half_width, s_t))
