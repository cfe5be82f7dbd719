"""A Geneva drive's design from its spec: the law's figures, the three parts (nominal, as cut, as printed) and the
assembly's checks. No I/O.

The parts (see :mod:`camgen.kinds.geneva.geometry`), each a :class:`~camgen.core.parts.Part` in its own frame: the
wheel (its bore), the locking disc (the driver's bore) and the crank (the driver's bore and the pin's hole).
Printed, the driver is one solid: the crank with the locking disc on top of it, in the wheel's plane; the pin
(a dowel in the crank's hole) reaches up into the wheel's slots. The cut files carry each part with its outline
grown by half the kerf, exactly, and its holes shrunk by as much; the printed ones open the holes by the
printing clearance (:class:`~camgen.core.parts.Allowances`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import DesignError
from camgen.core.parts import Allowances, Part
from camgen.core.shapes import Circle
from camgen.kinds.geneva.assembly import AssemblyCheck, check_assembly
from camgen.kinds.geneva.geometry import GenevaGeometry
from camgen.kinds.geneva.kinematics import GenevaLaw
from camgen.kinds.geneva.table import GenevaSpec

#: the parts, in the order they are written
PARTS = ("wheel", "lock", "crank")
#: thinnest wall (mm) round a bore before a warning
THIN_WALL = 2.0


@dataclass(frozen=True)
class _Maker:
    """One part of the drive at any allowance (a :class:`~camgen.core.parts.PartMaker`)."""

    spec: GenevaSpec
    which: str

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        g, t = self.spec.geometry, self.spec.geneva
        bore = t.wheel_bore if self.which == "wheel" else t.driver_bore
        holes: list = [Circle((0.0, 0.0), bore / 2 + hole_grow)] if bore > 0 else []
        if self.which == "crank":
            holes.append(g.pin_hole(hole_grow))
        outline = {"wheel": g.wheel, "lock": g.lock, "crank": g.crank}[self.which](outline_grow)
        return Part(f"{self.spec.name}-{self.which}", outline, tuple(holes), t.thickness, self.spec.output.tolerance)


@dataclass(frozen=True)
class GenevaDesign:
    """Everything known about a Geneva drive before anything is written (mm, degrees of driver angle).

    ``parts``, ``cut`` and ``printed`` map each of :data:`PARTS` to its part: nominal, as cut (kerf) and as
    printed (clearance). ``motion`` holds the law's figures (per radian of driver angle; see
    :func:`motion_figures`), ``speed`` the same in time at ``geneva.rpm`` (None without it).

    Attributes
    ----------
    spec : GenevaSpec
        The validated template.
    geometry : GenevaGeometry
        The drive's dimensions (mm) and its parts' outlines.
    parts, cut, printed : dict of str to Part
        Each of ``"wheel"``, ``"lock"``, ``"crank"``: nominal, as cut and as printed.
    assembly : AssemblyCheck
        The clearances of the assembled drive over a turn and its entry.
    motion : dict
        The law's figures per radian of driver angle.
    speed : dict or None
        The same in time at ``geneva.rpm``.
    warnings : tuple of str
        The design's warnings, as the console prints them.
    """

    spec: GenevaSpec
    geometry: GenevaGeometry
    parts: dict[str, Part]
    cut: dict[str, Part]
    printed: dict[str, Part]
    assembly: AssemblyCheck
    motion: dict[str, Any]
    speed: dict[str, Any] | None
    warnings: tuple[str, ...]

    @property
    def law(self) -> GenevaLaw:
        return self.geometry.law

    @property
    def tolerance(self) -> float:
        return self.spec.output.tolerance

    @property
    def written_error_mm(self) -> float:
        """A bound (mm) on the cut files' distance from the exact parts: 0, every piece an exact line or arc, but for
        the DXF ``segments`` flavour, whose chords stray from the arcs by up to this."""
        if self.spec.output.dxf != "segments":
            return 0.0
        return max(c.flatten_error(self.tolerance) for p in self.cut.values()
                   for c in (p.outline, *(h for h in p.holes if not isinstance(h, Circle))))

    def _repr_svg_(self) -> str:
        return self.cut["wheel"]._repr_svg_()

    def _repr_html_(self) -> str | None:
        """Jupyter shows the interactive page, as :meth:`camgen.profile.CamDesign._repr_html_` does."""
        from camgen.core.page import bundle_frame
        from camgen.kinds.geneva.outputs import geneva_bundle

        return bundle_frame(geneva_bundle(self)[0])


def motion_figures(law: GenevaLaw) -> dict[str, Any]:
    """The Geneva law's figures per radian of driver angle (beta' per omega, beta'' per omega^2), angles in
    degrees: the index and dwell, the peaks and where, and the acceleration's jumps at entry and exit."""
    e = math.degrees(law.engagement)
    v, v_at = law.velocity_peak()
    acc, acc_at = law.acceleration_peak()
    jump = law.acceleration_jump
    return {
        "index_deg": 360.0 / law.slots, "motion_deg": 2 * e, "dwell_deg": 360.0 - 2 * e,
        "engagement_deg": [-e, e], "dwell_to_motion": (360.0 - 2 * e) / (2 * e),
        "velocity_ratio_max": v, "velocity_ratio_max_at_deg": math.degrees(v_at),
        "acceleration_ratio_max": acc, "acceleration_ratio_max_at_deg": [-math.degrees(acc_at), math.degrees(acc_at)],
        "jumps": [{"at_deg": -e, "where": "entry", "acceleration_before": 0.0, "acceleration_after": jump,
                   "size": jump},
                  {"at_deg": e, "where": "exit", "acceleration_before": -jump, "acceleration_after": 0.0,
                   "size": jump}],
        "jerk": "infinite at entry and exit (the acceleration jumps there)",
    }


def _speed(law: GenevaLaw, rpm: float | None) -> dict[str, Any] | None:
    """The wheel's peak rates in time at the driver's ``rpm`` (rad/s, rad/s^2; the jumps too)."""
    if rpm is None:
        return None
    omega = 2 * math.pi * rpm / 60.0
    return {"driver_rpm": rpm, "driver_rad_s": omega,
            "wheel_velocity_max_rad_s": law.velocity_peak()[0] * omega,
            "wheel_velocity_max_rpm": law.velocity_peak()[0] * rpm,
            "wheel_acceleration_max_rad_s2": law.acceleration_peak()[0] * omega**2,
            "acceleration_jump_rad_s2": law.acceleration_jump * omega**2,
            "index_time_s": 2 * law.engagement / omega, "dwell_time_s": (2 * math.pi - 2 * law.engagement) / omega}


def _warnings(spec: GenevaSpec, check: AssemblyCheck) -> tuple[str, ...]:
    g, out = spec.geometry, []
    walls = (("wheel", spec.geneva.wheel_bore, g.bottom - g.half_width),
             ("driver", spec.geneva.driver_bore, g.centre_distance - g.cutout_radius))
    for what, bore, reach in walls:
        if bore > 0 and reach - bore / 2 < THIN_WALL:
            out.append(f"only {reach - bore / 2:.3g} mm of material round the {what}'s bore")
    shaft = g.centre_distance - g.crank_radius - g.crank_width / 2 - spec.geneva.wheel_bore / 2
    if shaft < 0:
        out.append(f"the crank sweeps {-shaft:.3g} mm into the wheel's shaft: the wheel's shaft must not reach down "
                   "into the crank's plane")
    if g.tip_width() < 1.0:
        out.append(f"the wheel's tips are only {g.tip_width():.3g} mm wide at the rim: a smaller geneva.lock_radius "
                   "widens them")
    if check.lock_clearance_min_mm < spec.geneva.lock_clearance - spec.output.tolerance:
        out.append(f"the locking disc comes within {check.lock_clearance_min_mm:.3g} mm of the wheel")
    return tuple(out)


def design_geneva(spec: GenevaSpec) -> GenevaDesign:
    """The drive ``spec`` describes: its parts and checks.

    Parameters
    ----------
    spec : GenevaSpec
        A validated Geneva template.

    Returns
    -------
    GenevaDesign
        The wheel, locking disc and crank (nominal, as cut, as printed), the assembly's clearances over a turn,
        the law's figures and the warnings.

    Raises
    ------
    DesignError
        A kerf that closes the wheel's slots (naming ``output.kerf``) or a hole, or the locking disc or the pin
        running into the wheel over the turn (naming ``geneva`` and the driver angle).
    """
    g = spec.geometry
    kerf = spec.output.kerf
    if kerf / 2 >= g.half_width:
        raise DesignError(f"output.kerf: a kerf of {kerf:g} mm closes the wheel's slots ({2 * g.half_width:g} mm "
                          "wide); the kerf must be narrower")
    allowances = Allowances(kerf, spec.output.clearance, "output.kerf", spec.output.elephant_foot)
    makers = {name: _Maker(spec, name) for name in PARTS}
    check = check_assembly(g)
    if check.lock_clearance_min_mm <= 0 or check.pin_clearance_min_mm <= 0:
        what = "the locking disc" if check.lock_clearance_min_mm <= 0 else "the pin"
        at = check.lock_clearance_at_deg if check.lock_clearance_min_mm <= 0 else check.pin_clearance_at_deg
        raise DesignError(f"geneva: {what} runs into the wheel at a driver angle of {at:.2f} degrees")
    return GenevaDesign(spec, g, {k: m.part(0.0, 0.0) for k, m in makers.items()},
                        {k: allowances.cut(m) for k, m in makers.items()},
                        {k: allowances.printed(m) for k, m in makers.items()},
                        check, motion_figures(g.law), _speed(g.law, spec.geneva.rpm), _warnings(spec, check))


def sample_turn(law: GenevaLaw, per_stretch: int = 721) -> tuple[np.ndarray, np.ndarray]:
    """Driver angles (rad) over a turn from -pi to pi and the law there (4, m): the dwell, the engagement and the
    dwell again, each on its closed interval (the jumps show as two values at one angle), for plots."""
    e = law.engagement
    stretches = [np.linspace(-math.pi, -e, 2), np.linspace(-e, e, per_stretch), np.linspace(e, math.pi, 2)]
    values = [law.motion(s) for s in stretches]
    # the dwells' values up to the jumps (at -pi the wheel is still at -pi/n, the turn's start)
    values[0] = law.motion(np.array([np.nextafter(-math.pi, 0.0), np.nextafter(-e, -math.pi)]))
    values[2] = law.motion(np.array([np.nextafter(e, math.pi), math.pi]))
    return np.concatenate(stretches), np.concatenate(values, axis=1)
