"""A grooved face cam from a spec: its two flanks checked and outlined, the plate with its groove. No I/O.

The pitch curve is the disc cam's (prime radius = base radius + roller radius): the template's
:class:`~camgen.rig.Rig` on the disc's mount. The inner flank is the pitch curve offset inwards by
d = Rr + c/2, the surface a disc cam with a roller of radius d would have: the *island* inside the
groove, the same rig with that roller on a base circle c/2 smaller (the same prime circle), cut by
:func:`camgen.profile.design_profile`, bore, holes and engraving included; the outer flank is the pitch
curve offset outwards by d. Both are checked for undercut (:func:`camgen.groove.flank_checks`).

The plate is a circle ``cam.rim`` mm outside the outer flank's farthest point; the groove
is a pocket ``cam.groove_depth`` mm deep from its top face. The cut files carry the
flanks as a laser cutting the island and the ring round it as two plates needs them: each
flank moved into the groove by half the kerf. The printed groove is the nominal one
(``cam.running_clearance`` is its clearance; ``output.clearance`` opens the holes only).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from camgen.analysis import CamAnalysis, largest_fitting
from camgen.cam import Cam
from camgen.core.errors import DesignError
from camgen.core.parts import Part, Pocket
from camgen.core.shapes import Contour
from camgen.flat import FlatCamDesign, flat_rig, parabolic_ratios, rates
from camgen.forces import Contact, drive_speed
from camgen.groove import Flank, flank_checks
from camgen.outline import Outline, envelope_outline, exact_outline
from camgen.profile import Body, Finish, design_profile, step_part
from camgen.rig import Rig, disc_mount
from camgen.sizing import Sizing, limits_of, pressure_limit, size_cam
from camgen.kinds.grooved.table import GroovedSpec


def pitch_rig(spec: GroovedSpec) -> Rig:
    """The rig of a grooved cam's pitch curve: the disc cam's, the template's own follower and roller."""
    return flat_rig(spec, disc_mount(spec.follower, spec.cam.rotation))


def island_rig(rig: Rig, clearance: float) -> Rig:
    """The disc cam the inner flank bounds: the same pitch curve (the same prime radius) with a roller of radius
    Rr + c/2 (``clearance`` c, mm) on a base circle c/2 smaller (:func:`island_base`), so its surface is the inner
    flank."""
    return rig.with_roller(rig.roller_radius + clearance / 2)


def island_base(base_radius: float, clearance: float) -> float:
    """The island's base radius (mm): the grooved cam's less c/2 (``clearance`` c), the same prime circle. Refused
    naming cam.base_radius where that leaves no base circle."""
    half = clearance / 2
    if not base_radius > half:
        raise DesignError(f"cam.base_radius: must be larger than cam.running_clearance / 2 = {half:g} mm, so the "
                          "inner flank has a base circle")
    return base_radius - half


def largest_roller(rig: Rig, base_radius: float, clearance: float) -> float | None:
    """The largest roller radius (mm), up to the rig's, neither of whose flanks undercuts on a base circle of
    ``base_radius`` with a running ``clearance`` (mm; the pitch curve grows with the roller: prime radius = base +
    roller), by bisection; None when even a vanishing roller undercuts (a velocity jump's corner)."""
    half = clearance / 2

    def margin(rr: float) -> float:
        inner, outer = flank_checks(rig.cam(base_radius, rr), rr + half)
        return min(inner.rho_min_mm, outer.rho_min_mm)

    return largest_fitting(rig, base_radius, margin)


def _undercut_message(rig: Rig, base_radius: float, clearance: float, cam: Cam, flank: Flank) -> str:
    where = f"undercut of the {flank.side} flank at {flank.at_deg:.2f} degrees: "
    if flank.pitch_rho_min_mm == 0.0:
        sense = 1 if flank.side == "inner" else -1
        jump = next(i for i, turn in cam.corners() if sense * turn > 0)
        corner = "convex" if flank.side == "inner" else "concave"
        return (f"motion[{rig.moving_segment(jump)}]: " + where + f"the follower velocity jumps there, so the pitch "
                f"curve has a {corner} corner that the {flank.side} flank cannot follow; use a law with continuous "
                "velocity (e.g. modified-uniform) or set cam.allow_undercut = true")
    best = largest_roller(rig, base_radius, clearance)
    fits = (f"the largest roller that fits is {best:.4g} mm" if best is not None
            else "no roller fits this base radius")
    bend = "convex" if flank.side == "inner" else "concave"
    return (where + f"the pitch curve's {bend} radius of curvature is {flank.pitch_rho_min_mm:.4g} mm, smaller than "
            f"follower.roller_radius + cam.running_clearance / 2 = {flank.offset_mm:.4g} mm; {fits} (or enlarge "
            "cam.base_radius, or set cam.allow_undercut = true)")


@dataclass(frozen=True)
class GroovedDesign:
    """Everything known about a grooved cam before anything is written (mm, degrees).

    ``spec`` is the template's (its base radius ``"auto"`` where it was: the size is ``base_radius_mm``);
    ``profile`` the island: the disc cam whose surface is the inner flank (pitch curve, analysis, inner outline,
    holes, marks, warnings), as a design of the template with the groove's speed and sizing; ``outer`` and
    ``cut_outer`` the outer flank as designed and as the cut files carry it; ``part``, ``cut`` and ``printed`` the
    plate with its groove as a :class:`~camgen.core.parts.Pocket`.

    Attributes
    ----------
    spec : GroovedSpec
        The template as given: its base radius ``"auto"`` where it was sized.
    profile : FlatCamDesign
        The island: the disc cam whose surface is the inner flank, with the groove's speed and sizing.
    base_radius_mm : float
        The groove's pitch base radius (mm): the template's, or the size chosen for ``"auto"``.
    inner, outer : Flank
        Each flank's undercut check: the pitch curve's least radius bending that flank and where.
    outer_outline, cut_outer : Outline
        The outer flank as designed and as the cut files carry it (moved into the groove by half the kerf).
    plate_radius_mm : float
        The plate's radius (mm): the pitch curve's farthest reach, the roller's and the rim.
    part, cut, printed : Part
        The plate with its groove: nominal, as cut and as printed.
    warnings : tuple of str
        The design's warnings, as the console prints them.
    """

    spec: GroovedSpec
    profile: FlatCamDesign
    base_radius_mm: float
    inner: Flank
    outer: Flank
    outer_outline: Outline
    cut_outer: Outline
    plate_radius_mm: float
    part: Part
    cut: Part
    printed: Part
    warnings: tuple[str, ...]

    @property
    def cam(self) -> Cam:
        return self.profile.cam

    @property
    def analysis(self) -> CamAnalysis:
        """The island's analysis: the pressure angle, and the pitch curve's radii (its profile is the inner flank)."""
        return self.profile.analysis

    @property
    def outline(self) -> Outline:
        """The inner flank (the island's outline)."""
        return self.profile.outline

    @property
    def tolerance(self) -> float:
        return self.spec.output.tolerance

    @property
    def offset_mm(self) -> float:
        """d = Rr + c/2: each flank's distance from the pitch curve (mm)."""
        return self.inner.offset_mm

    @property
    def written_error_mm(self) -> float:
        """A bound (mm) on the distance of both flanks, as the cut files carry them, from the exact flanks."""
        chords = self.cut_outer.contour.flatten_error(self.tolerance) if self.spec.output.dxf == "segments" else 0
        return max(self.profile.written_error_mm, self.cut_outer.max_error_mm, chords)

    def _repr_svg_(self) -> str:
        return self.cut._repr_svg_()

    def _repr_html_(self) -> str | None:
        """Jupyter shows the interactive page, as :meth:`camgen.profile.CamDesign._repr_html_` does."""
        from camgen.core.page import bundle_frame
        from camgen.kinds.grooved.outputs import grooved_bundle

        return bundle_frame(grooved_bundle(self)[0])


def _circle(radius: float) -> Contour:
    """A counter-clockwise circle about the origin as two exact half arcs."""
    return Contour(np.array([[radius, 0.0], [-radius, 0.0]]), np.array([1.0, 1.0]))


def _plate(spec: GroovedSpec, island: Part, outer: Outline, radius: float) -> Part:
    """The plate of ``radius`` mm with the island's holes and marks, and the groove between its outline and
    ``outer`` as a pocket."""
    groove = Pocket(outer.contour, island.outline, spec.cam.groove_depth)
    return Part(spec.name, _circle(radius), island.holes, spec.cam.thickness, spec.output.tolerance, island.marks,
                pockets=(groove,))


def step_plate(design: GroovedDesign) -> Part:
    """The printed plate as the STEP file carries it: both flanks made of biarcs (exact arcs within
    ``output.tolerance`` mm of the exact flanks, measured), whatever ``output.curves`` says, as a disc cam's
    (:func:`camgen.profile.step_part`); an undercut outer flank's envelope keeps its chords."""
    island, _ = step_part(design.profile)
    cam = design.profile.cam
    outer = (design.outer_outline if design.outer.undercut
             else exact_outline(cam, design.spec.output.tolerance, "biarcs", 2 * cam.contact_radius))
    return _plate(design.spec, island, outer, design.plate_radius_mm)


def size_grooved(spec: GroovedSpec) -> Sizing:
    """The smallest base radius meeting the pressure-angle limit and ``cam.min_rho_margin`` for the inner flank's
    convex radius (:func:`camgen.sizing.size_cam` of the island, searched from the template's base radius where it
    gives one), in the grooved cam's terms: its base radius is c/2 more than the island's."""
    base, clearance = spec.cam.base_radius, spec.cam.running_clearance
    near = island_base(base, clearance) if isinstance(base, float) else None
    half = clearance / 2
    found = size_cam(island_rig(pitch_rig(spec), clearance), limits_of(spec), near)
    return dataclasses.replace(found, base_radius_mm=found.base_radius_mm + half,
                               pressure_radius_mm=found.pressure_radius_mm + half,
                               curvature_radius_mm=found.curvature_radius_mm + half)


def design_grooved(spec: GroovedSpec) -> GroovedDesign:
    """Build, check and outline the grooved cam ``spec`` describes (sized first where ``cam.base_radius =
    "auto"``, :func:`size_grooved`; the spec keeps ``"auto"``, the size is ``design.base_radius_mm``).

    Parameters
    ----------
    spec : GroovedSpec
        A validated template with ``cam.kind = "grooved"``; a base radius of ``"auto"`` is sized first.

    Returns
    -------
    GroovedDesign
        The island (the disc cam whose surface is the inner flank), both flanks, the plate with its groove, as
        designed, as cut and as printed, and the warnings.

    Raises
    ------
    DesignError
        An undercut of either flank, naming the flank, the angle and the radii (unless ``cam.allow_undercut``:
        that flank is then the envelope a cutter of the roller's size leaves); a kerf that closes the groove
        (naming ``output.kerf``); a bore or holes that leave no material inside the inner flank.
    """
    rig, clearance = pitch_rig(spec), spec.cam.running_clearance
    base, sizing = spec.cam.base_radius, None
    if not isinstance(base, float):
        sizing = size_grooved(spec)
        base = sizing.base_radius_mm
    inside, inner_base = island_rig(rig, clearance), island_base(base, clearance)
    cam = inside.cam(inner_base)
    d = cam.contact_radius
    inner, outer = flank_checks(cam, d)
    for flank in (inner, outer):
        if flank.undercut and not spec.cam.allow_undercut:
            raise DesignError(_undercut_message(rig, base, clearance, cam, flank))
    out = spec.output
    if out.kerf >= 2 * d:
        raise DesignError(f"output.kerf: a kerf of {out.kerf:g} mm closes the groove ({2 * d:g} mm wide); the kerf "
                          "must be narrower than the groove")
    cut = design_profile(inside, inner_base, Body.of(spec.name, spec.cam, spec.hub), Finish.of(out),
                         spec.cam.allow_undercut, pressure_limit(spec))
    speed = rates(cut.cam, spec.cam.rpm, parabolic_ratios(spec.motion))      # forces: the groove's, not a spring's
    if speed is not None and spec.follower.mass is not None:
        f, depth = spec.follower, spec.cam.groove_depth
        walls = None if spec.cam.material is None else (      # the flanks roller + clearance / 2 off the pitch curve
            Contact(spec.cam.material, f.material, min(depth, f.roller_width or depth)), inner.offset_mm,
            f.roller_radius)
        # the island's cam: the same pitch curve, arm
        forces, speeds = drive_speed(spec, cam, ("inner flank", "outer flank"), walls)
        speed = dataclasses.replace(speed, forces=forces, speeds=speeds)
    profile = FlatCamDesign.of(cut, spec, speed, sizing)
    curves = cut.finish.outline_curves

    def outer_flank(grow: float) -> Outline:      # the outer flank with its material grown by ``grow`` mm
        offset = 2 * d - grow                     # the island's surface lies d inside the pitch curve: 2 d out
        return (envelope_outline(cam, out.tolerance, offset) if outer.undercut
                else exact_outline(cam, out.tolerance, curves, offset))

    nominal, cut_outer = outer_flank(0.0), outer_flank(out.kerf / 2)
    reach = cam.program.peak(lambda i, t: np.linalg.norm(cam.segment_pitch(i, t).point, axis=1))[0]
    radius = reach + d + spec.cam.rim
    warnings = profile.warnings
    if outer.undercut:
        warnings += (f"undercut allowed: the outer flank is the cutter's envelope, and near {outer.at_deg:.2f} degrees "
                     "the follower does not follow the motion law",)
    return GroovedDesign(spec, profile, base, inner, outer, nominal, cut_outer, radius,
                         _plate(spec, profile.part, nominal, radius),
                         _plate(spec, profile.cut, cut_outer, radius + out.kerf / 2),
                         _plate(spec, profile.printed, nominal, radius), warnings)
