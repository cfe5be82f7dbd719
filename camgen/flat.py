"""What the flat cams share: a disc or plate cam's design from its template, and the pieces a conjugate pair's
members and a grooved cam's speeds reuse. No I/O.

A flat cam's design (:func:`design_flat`) is its kind's :class:`~camgen.rig.Mount` made into a
:class:`~camgen.rig.Rig`, sized where ``cam.base_radius = "auto"`` (:func:`camgen.sizing.size_cam`), its profile
cut (:func:`camgen.profile.design_profile`) and its speed at ``cam.rpm`` (:func:`sprung_speed`). The template is
never validated again: a sized cam's spec keeps ``"auto"``, and the size is ``design.cam.base_radius``.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from camgen.cam import Cam
from camgen.core.errors import SpecError
from camgen.profile import Body, Finish, Profile, design_profile
from camgen.rig import Mount, Rig, disc_mount
from camgen.sizing import Sizing, limits_of, pressure_limit, size_cam
from camgen.speed import GravityHold, HeldContact, Speed

if TYPE_CHECKING:
    from camgen.core.bundle import Bundle
    from camgen.spec import CamSpec, FlatSpec


@dataclass(frozen=True, kw_only=True)
class FlatCamDesign(Profile):
    """Everything known about a disc or plate cam before anything is written (made by :func:`design_flat`): its
    :class:`~camgen.profile.Profile` (every attribute of it: ``cam``, ``analysis``, ``outline``, ``part``, ``cut``,
    ``printed``, ``warnings``...) with the template it came from and what the template's speed and sizing add.

    Attributes
    ----------
    spec : CamSpec
        The validated template: ``design.spec.cam.base_radius`` is the base radius as given (``"auto"`` when
        sized: the size chosen is ``design.cam.base_radius``).
    speed : Speed or None
        With ``cam.rpm``: peak velocity, acceleration and jerk in time, the contact check and, with a mass, the
        forces (and the speeds table with ``cam.rpm_range``).
    sizing : Sizing or None
        With ``base_radius = "auto"``: what decided the size, and the size.
    warnings : tuple of str
        The profile's warnings, then the contact's at ``cam.rpm``.
    bundler : callable or None
        Its kind's bundle (:meth:`camgen.kinds.base.Kind.bundle`), which Jupyter's page is made by; None for a
        design no kind writes alone (a conjugate pair's member).
    """

    spec: FlatSpec
    speed: Speed | None = None
    sizing: Sizing | None = None
    bundler: Callable[[FlatCamDesign], tuple[Bundle, dict[str, Any]]] | None = field(default=None, repr=False,
                                                                                      compare=False)

    @classmethod
    def of(cls, profile: Profile, spec: FlatSpec, speed: Speed | None = None, sizing: Sizing | None = None,
           warnings: tuple[str, ...] | None = None,
           bundler: Callable[[FlatCamDesign], tuple[Bundle, dict[str, Any]]] | None = None) -> FlatCamDesign:
        """``profile`` as the design of ``spec``, with its ``speed``, ``sizing``, ``warnings`` (the profile's by
        default) and its kind's ``bundler``."""
        fields = {f.name: getattr(profile, f.name) for f in dataclasses.fields(Profile)}
        if warnings is not None:
            fields["warnings"] = warnings
        return cls(**fields, spec=spec, speed=speed, sizing=sizing, bundler=bundler)

    def _repr_html_(self) -> str | None:
        """Jupyter shows the design's interactive page inline, as its html file holds it (without links to files);
        none when ``output.formats`` leaves out html, or the design has no bundler of its own."""
        from camgen.core.page import bundle_frame

        return None if self.bundler is None else bundle_frame(self.bundler(self)[0])


#: the name scripts know a disc or plate cam's design by
CamDesign = FlatCamDesign


def flat_rig(spec: FlatSpec, mount: Mount) -> Rig:
    """The :class:`~camgen.rig.Rig` of a flat cam's template on its kind's ``mount``."""
    return Rig.of(spec.name, spec.motion, mount)


def design_flat(spec: FlatSpec, mount: Mount,
                bundler: Callable[[FlatCamDesign], tuple[Bundle, dict[str, Any]]] | None = None) -> FlatCamDesign:
    """Build, check and outline the flat cam ``spec`` describes, its follower on ``mount`` (its kind's): sized
    first where ``cam.base_radius = "auto"`` (:mod:`camgen.sizing`), its profile cut
    (:func:`~camgen.profile.design_profile`: refused there for an undercut, unless ``cam.allow_undercut``, and for a
    bore or holes that leave no material), its speed at ``cam.rpm`` (:func:`sprung_speed`); ``bundler`` is its
    kind's bundle (for Jupyter's page)."""
    rig = flat_rig(spec, mount)
    sizing = None
    base = spec.cam.base_radius
    if base == "auto":
        sizing = size_cam(rig, limits_of(spec))
        base = sizing.base_radius_mm
    profile = design_profile(rig, base, Body.of(spec.name, spec.cam, spec.hub), Finish.of(spec.output),
                             spec.cam.allow_undercut, pressure_limit(spec))
    speed = sprung_speed(spec, profile.cam)
    return FlatCamDesign.of(profile, spec, speed, sizing, profile.warnings + contact_warnings(speed), bundler)


def size_flat(spec: FlatSpec, mount: Mount) -> Sizing:
    """The smallest base radius of a flat cam's template, its follower on ``mount`` (:func:`camgen.sizing.size_cam`
    of its rig, searched from its base radius where it gives one)."""
    near = spec.cam.base_radius if isinstance(spec.cam.base_radius, float) else None
    return size_cam(flat_rig(spec, mount), limits_of(spec), near)


def size_disc(spec: FlatSpec) -> Sizing:
    """A disc cam's smallest base radius (:func:`size_flat` on the disc's mount)."""
    return size_flat(spec, disc_mount(spec.follower, spec.cam.rotation))


def build_cam(spec: CamSpec, roller_radius: float | None = None, base_radius: float | None = None) -> Cam:
    """The :class:`~camgen.cam.Cam` a cam template describes (a grooved cam's pitch cam, a conjugate pair's first
    cam, a barrel's developed cam), its follower placed as its kind's spec says
    (:meth:`~camgen.spec.CamSpec.follower_at`): a
    script's and a test's way to a template's cam. A barrel has no base radius: a drafted law on one needs its own
    rig (:func:`camgen.kinds.barrel.design.barrel_rig`).

    Parameters
    ----------
    spec : CamSpec
        A validated cam template.
    roller_radius : float, optional
        The roller's radius to build with (mm), instead of ``follower.roller_radius`` (0 for a flat face or a knife
        edge).
    base_radius : float, optional
        The base radius to build with (mm), instead of ``cam.base_radius``; needed when the spec's is ``"auto"``
        (:func:`size_disc` finds one; :func:`camgen.api.design_cam` sizes and builds at once).

    Returns
    -------
    Cam
        The kinematic cam: its program, follower and base radius; no geometry is checked.

    Raises
    ------
    SpecError
        A segment's law refuses its parameters (naming ``motion[i]`` and the key), the motion does not make one
        turn that returns to its start, or the follower cannot be placed (an offset outside the prime circle, an
        arm that cannot reach it) or cannot follow the program's largest displacement on that base circle, each
        naming the key.
    """
    rr = spec.follower.contact_radius if roller_radius is None else roller_radius
    rb = base_radius if base_radius is not None else spec.base_circle   # a barrel has no base circle: None
    if isinstance(rb, str):
        raise SpecError('is "auto": size the cam first (size_disc) and build it with that base radius',
                        "cam.base_radius")
    rig = Rig.of(spec.name, spec.motion, disc_mount(spec.follower, spec.cam.rotation))
    if rb is None:                                      # no base circle: the plate's height under the roller
        return Cam(spec.name, rig.program(None), spec.follower_at(None, rr), spec.rest_height(rr))
    program = rig.program(rb + rr)
    rig.mount.check_fits(rb, program)                   # a follower whose reach depends on how far it moves
    return Cam(spec.name, program, spec.follower_at(rb, rr), rb)


def parabolic_ratios(motion: Any) -> list[tuple[int, float]]:
    """The acceleration ratio of every parabolic segment of ``motion``, by its index (1 where not given)."""
    return [(i, seg.ratio or 1.0) for i, seg in enumerate(motion) if seg.law == "parabolic"]


def rates(cam: Cam, rpm: float | None, parabolic: list[tuple[int, float]]) -> Speed | None:
    """Peak velocity, acceleration and jerk in time at ``rpm`` (None without a speed), alone: no contact, forces
    nor speeds table (a positive drive has its own, :func:`camgen.forces.drive_speed`)."""
    if rpm is None:
        return None
    from camgen.dynamics import speed_report                       # only with a speed: a plain build loads it not

    return speed_report(cam, rpm, None, None, None, parabolic)


def sprung_speed(spec: FlatSpec, cam: Cam) -> Speed | None:
    """Peak rates and the contact check at ``cam.rpm`` of a follower held on its cam by a spring, its weight or a
    load (None without a speed): with a mass, the forces and, with ``cam.rpm_range``, the speeds table."""
    if spec.cam.rpm is None:
        return None
    from camgen.dynamics import spec_loading, speed_report         # only with a speed: a plain build loads neither
    from camgen.forces import Contact, forces_report, speeds_report

    f = spec.follower
    ld = None if f.mass is None else spec_loading(f, cam.follower, motion=spec.motion, program=cam.program)
    out = speed_report(cam, spec.cam.rpm, f.mass, f.spring_rate, f.preload, parabolic_ratios(spec.motion), f.load,
                       f.orientation, f.contact_margin, ld)
    if ld is not None and isinstance(out.contact, HeldContact | GravityHold):
        contact = None if spec.cam.material is None else Contact(
            spec.cam.material, f.material, min(spec.cam.thickness, f.roller_width or spec.cam.thickness))
        forces = forces_report(cam, ld, spec.cam.rpm, contact)
        return dataclasses.replace(out, forces=forces, speeds=None if spec.cam.rpm_range is None else speeds_report(
            cam, ld, spec.cam.rpm_range, spec.cam.rpm_steps, None if forces.hertz is None else contact,
            out.contact.liftoff_rpm))
    if spec.cam.rpm_range is not None:
        raise SpecError("needs a follower whose contact is analysed: an oscillating roller's arm held by a spring, a "
                        "load or its weight (follower.orientation)", "cam.rpm_range")
    return out


def contact_warnings(speed: Speed | None) -> tuple[str, ...]:
    """The warnings of a sprung follower's contact check (:func:`sprung_speed`): where it leaves the cam."""
    contact = None if speed is None else speed.contact
    if isinstance(contact, GravityHold) and contact.holds is False:
        return (f"the follower leaves the cam near {contact.liftoff_at_deg:.1f} degrees: "
                f"gravity holds it only up to {contact.liftoff_rpm:.4g} rpm",)
    if not isinstance(contact, HeldContact) or contact.holds:
        return ()
    if contact.mode == "gravity":
        return (f"the follower loses contact near {contact.force_min_at_deg:.1f} degrees (force "
                f"{contact.force_min:.3g} N): a spring with a preload of {contact.preload_needed:.4g} N "
                "would hold it",)
    return (f"the spring loses contact near {contact.force_min_at_deg:.1f} degrees (force "
            f"{contact.force_min:.3g} N): a preload of {contact.preload_needed:.4g} N would hold it",)
