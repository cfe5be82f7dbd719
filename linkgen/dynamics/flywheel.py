"""The flywheel a crank needs for a coefficient of speed fluctuation, sized as a part of the sheet's material.

The inertia (:mod:`linkgen.kinematics.balance`) is I = dE / (Cs w^2) at the crank in all, the linkage's own mean
generalised inertia included, so the flywheel adds I - J_mean. It is ``plates`` plates of the parts' sheet, each a
disc, or a rim on four spokes (``rim``: the rim and the spokes ``rim_width`` wide, a hub of that width round the
hole), with a hole for the crank's shaft (``parts.pin_diameter`` + ``parts.clearance``, made as the other parts: cut
with the kerf or printed). Its outer radius is the least that gives the inertia as made (the section's exact polar
moment, :mod:`linkgen.dynamics.section`, times the density, the thickness and the plates), found by bisection. It
turns with the crank on its shaft behind the frame (below the base plate: layers -1, -2, ...).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from camgen.core.errors import DesignError
from camgen.core.nesting import SheetRules, nest
from camgen.core.parts import Allowances, Part
from camgen.core.shapes import Contour
from camgen.core.spec import MAX_LENGTH_MM
from linkgen.dynamics.masses import PER_MM3, MassModel
from linkgen.dynamics.section import part_section
from linkgen.kinematics.balance import flywheel_inertia
from linkgen.parts import LinkageBuild, LinkPart, Placement, Stock

if TYPE_CHECKING:
    from linkgen.dynamics.table import FlywheelTable
    from linkgen.spec import PartsTable

#: spokes of a rim flywheel
SPOKES = 4


@dataclass(frozen=True)
class FlywheelPart(LinkPart):
    """A flywheel plate in its own frame (the shaft's hole at the origin): a disc of radius ``half_width`` (mm), or
    a rim on :data:`SPOKES` spokes whose windows run from ``hub`` to ``half_width - rim`` (mm), the spokes ``rim``
    wide."""

    rim: float = 0.0
    hub: float = 0.0

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        """The plate with its outline moved out by ``outline_grow`` and its holes' and windows' edges by
        ``hole_grow`` (mm)."""
        plain = super().part(outline_grow, hole_grow)
        if self.rim <= 0:
            return plain
        return Part(plain.name, plain.outline, plain.holes + self.windows(hole_grow), plain.thickness,
                    plain.tolerance)

    def windows(self, grow: float) -> tuple[Contour, ...]:
        """The rim's windows between the spokes, their edges moved out by ``grow`` (mm): each an annular sector
        from the hub to the rim between two spokes' edges (lines at half the width either side of a spoke)."""
        inner, outer, half = self.hub - grow, self.half_width - self.rim + grow, self.rim / 2 - grow
        out = []
        for k in range(SPOKES):
            a, b = 2 * math.pi * k / SPOKES, 2 * math.pi * (k + 1) / SPOKES
            angles = (a + math.asin(half / inner), a + math.asin(half / outer), b - math.asin(half / outer),
                      b - math.asin(half / inner))
            radii = (inner, outer, outer, inner)
            pts = np.array([[r * math.cos(t), r * math.sin(t)] for r, t in zip(radii, angles, strict=True)])
            bulges = [0.0, math.tan((angles[2] - angles[1]) / 4), 0.0, -math.tan((angles[3] - angles[0]) / 4)]
            out.append(Contour(pts, np.array(bulges)))
        return tuple(out)


@dataclass(frozen=True)
class FlywheelSize:
    """The flywheel of a crank: the coefficient asked, the energy fluctuation (J), the inertia needed at the crank in
    all, the linkage's own mean and the flywheel's part (kg*m^2); with parts, its plates' outer radius (mm), the
    inertia and mass they give as made (kg*m^2, kg), and whether a plate fits the sheet."""

    coefficient: float
    energy: float
    total: float
    own: float
    needed: float
    shape: Literal["disc", "rim"]
    plates: int
    radius: float | None = None
    inertia: float | None = None
    mass: float | None = None
    fits: bool = True
    plate: FlywheelPart | None = None


def _plate(shape: str, radius: float, rim: float, stock: Stock) -> FlywheelPart:
    hub = stock.hole / 2 + rim if shape == "rim" else 0.0
    return FlywheelPart("flywheel", np.zeros((1, 2)), radius, stock, moving=False,
                        rim=rim if shape == "rim" else 0.0, hub=hub)


def _made(plate: FlywheelPart, allowances: Allowances, made: str) -> Part:
    return allowances.cut(plate) if made == "cut" else allowances.printed(plate)


def flywheel_size(table: FlywheelTable, energy: float, speed: float, own: float, masses: MassModel,
                  parts: PartsTable | None) -> FlywheelSize:
    """The flywheel for the energy fluctuation ``energy`` (J) at ``speed`` (rad/s) of a linkage whose mean
    generalised inertia is ``own`` (kg*m^2): its inertia and, with ``[parts]``, its plates."""
    total, needed = flywheel_inertia(energy, table.fluctuation, speed, own)
    base: dict[str, Any] = {"coefficient": table.fluctuation, "energy": energy, "total": total, "own": own,
                            "needed": needed, "shape": table.shape, "plates": table.plates}
    if parts is None or needed <= 0:
        return FlywheelSize(**base)
    stock = Stock(parts.pin_diameter + parts.clearance, parts.thickness, parts.tolerance)
    rim = table.rim_width if table.rim_width is not None else 2 * parts.width
    allowances = Allowances(kerf=parts.kerf, kerf_field="parts.kerf")
    made = masses.material.made
    per_mm2 = masses.density * PER_MM3 * parts.thickness * masses.fill * table.plates

    def inertia(radius: float) -> tuple[float, float]:
        """The plates' inertia (kg*m^2) and mass (kg) as made at outer radius ``radius`` (mm)."""
        section = part_section(_made(_plate(table.shape, radius, rim, stock), allowances, made))
        return per_mm2 * section.polar_about_centroid * 1e-6, per_mm2 * section.area

    least = stock.hole / 2 + (3 * rim if table.shape == "rim" else parts.width / 2)
    lo, hi = least, MAX_LENGTH_MM / 2
    if inertia(lo)[0] < needed:
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if inertia(mid)[0] < needed else (lo, mid)
            if hi - lo <= 1e-13 * hi:
                break
        radius = hi
    else:
        radius = lo
    got, mass = inertia(radius)
    plate = _plate(table.shape, radius, rim, stock)
    sheet = min(parts.sheet) - 2 * parts.margin
    return FlywheelSize(**base, radius=radius, inertia=got, mass=mass, fits=2 * radius + parts.kerf <= sheet,
                        plate=plate)


def flywheel_plates(size: FlywheelSize) -> tuple[FlywheelPart, ...]:
    """The flywheel's plates as parts named ``flywheel-1``, ``flywheel-2``, ... (one, ``flywheel``, for one plate)."""
    if size.plate is None:
        return ()
    if size.plates == 1:
        return (size.plate,)
    return tuple(replace(size.plate, name=f"flywheel-{k + 1}") for k in range(size.plates))


def with_flywheel(build: LinkageBuild, size: FlywheelSize, pivot: tuple[float, float], crank: str) -> LinkageBuild:
    """``build`` with the flywheel's plates among its parts: below the frame (layers -1, -2, ...) on the crank's
    ``pivot`` (mm), turning with the link ``crank``; cut and printed as the other parts, nested with them on the
    sheets. A :class:`DesignError` naming ``dynamics.flywheel.plates`` when a plate is larger than the sheet."""
    plates = flywheel_plates(size)
    if not plates:
        return build
    table = build.table
    if not size.fits:
        gives = "give" if (size.inertia or 0.0) >= size.needed * (1 - 1e-6) else "fall short of"
        raise DesignError(f"dynamics.flywheel.plates: {size.plates} plate(s) {2 * (size.radius or 0.0):.1f} mm "
                          f"across {gives} the {size.needed:.3g} kg*m^2 needed, larger than the sheet "
                          f"({table.sheet[0]:g} x {table.sheet[1]:g} mm); stack more plates, or choose the rim "
                          "shape or a denser material")
    cut = build.cut + tuple(build.allowances.cut(p) for p in plates)
    printed = build.printed + tuple(build.allowances.printed(p) for p in plates)
    nested = nest(cut, SheetRules.of(table, table.kerf, "parts.sheet"))
    layers = {**build.layers, **{p.name: -(k + 1) for k, p in enumerate(plates)}}
    pose = build.pose
    if pose is not None:
        n = len(next(iter(pose.angles.values())))
        turn = pose.angles.get(crank, np.zeros(n))
        where = np.tile(np.asarray(pivot, dtype=float), (n, 1))
        pose = Placement({**pose.angles, **{p.name: turn for p in plates}},
                         {**pose.origins, **{p.name: where for p in plates}}, pose.joints)
    return replace(build, parts=build.parts + plates, layers=layers, cut=cut, printed=printed,
                   sheets=nested.drawings(table.tolerance), nesting=nested, pose=pose)
