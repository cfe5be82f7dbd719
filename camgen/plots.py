"""Plots of a cam: the S-V-A-J diagram and the cam drawing with its checks marked.

Uses matplotlib's object API (no pyplot state) with the Agg canvas; imported only when a plot is asked for (about
0.35 s of CPU). The figures are laid out with fixed margins: matplotlib's constrained layout re-measures every label
each time a figure is written, and took 0.4 s of the 0.9 s these two figures cost as PNG and SVG.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from camgen.cam import Cam
from camgen.analysis import face_extent
from camgen.core.figures import figure, fit_equal
from camgen.flat import FlatCamDesign
from camgen.speed import Forces, SpeedTable

if TYPE_CHECKING:
    from camgen.program import Jump
    from camgen.spec import CamSpec


def sample_cycle(cam: Cam, per_segment: int = 181) -> tuple[np.ndarray, np.ndarray]:
    """Cam angles (rad) and s, s', s'', s''' on every segment's closed interval, segment after segment.

    Jumps show as two values at one angle (for plots). ``per_segment`` points a segment.
    """
    thetas, motions = [], []
    for seg in cam.program.segments:
        t = np.linspace(seg.start, seg.end, per_segment if seg.kind != "dwell" else 2)
        thetas.append(t)
        motions.append(seg.evaluate(t))
    return np.concatenate(thetas), np.concatenate(motions, axis=1)


class Traced(Protocol):
    """What :func:`svaj_figure` draws of a design (a disc, plate, grooved or conjugate cam's, or a barrel's): its
    cam, its spec (its name and ``cam.rpm``) and its program's jumps."""

    @property
    def cam(self) -> Cam: ...

    @property
    def spec(self) -> CamSpec: ...

    @property
    def jumps(self) -> tuple[Jump, ...]: ...


def svaj_figure(design: Traced) -> Any:
    """Displacement, velocity, acceleration and jerk against cam angle: in time at ``cam.rpm`` (mm, m/s, m/s^2,
    m/s^3; an arm's swing in degrees and rad/s^n), else per radian of cam angle."""
    theta, motion = sample_cycle(design.cam)
    motion, labels = _machine_units(design, motion)
    deg = np.degrees(theta)
    fig = figure(8, 9, layout=None)
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.06, top=0.95, hspace=0.1)
    axes = fig.subplots(4, 1, sharex=True)
    starts = [math.degrees(seg.start) for seg in design.cam.program.segments]
    for k, ax in enumerate(axes):
        ax.plot(deg, motion[k], color="C0", lw=1.2)
        ax.axhline(0, color="0.6", lw=0.6)
        ax.vlines(starts, 0, 1, transform=ax.get_xaxis_transform(), color="0.85", lw=0.6, zorder=0)
        for j in design.jumps:
            if j.order < 3 and j.order + 1 == k:
                ax.annotate("∞", (j.at_deg, 0), color="C3", ha="center", va="bottom", fontsize=12)
        ax.set_ylabel(labels[k])
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("cam angle θ (degrees)")
    axes[-1].set_xlim(0, 360)
    axes[-1].set_xticks(range(0, 361, 30))
    speed = getattr(design.spec.cam, "rpm", None)
    at = f" at {speed:g} rpm" if speed else " (per radian of cam angle)"
    axes[0].set_title(f"{design.spec.name}: S-V-A-J{at} (∞ marks infinite acceleration or jerk)")
    return fig


def checks_figure(design: FlatCamDesign) -> Any:
    """What the design is checked against, over the turn: the pressure angle with its limit (a translating flat
    face's is 0 by definition, so the profile's radius stands alone), the radius of curvature of the cam's surface
    signed with its undercut limits (:func:`radius_panel`: convex, the roller + ``cam.min_rho_margin``; concave,
    ``output.tool_radius``) and, at a speed with a mass, the contact force and camshaft torque, and
    with materials the Hertz pressure against its allowable."""
    from camgen.dynamics import spec_loading
    from camgen.forces import contact_pressure, materials_of, normal_force, torque

    cam, spec = design.cam, design.spec
    theta, motion = sample_cycle(cam)
    g = cam.follower.pitch(theta, motion)             # each segment's own, as the motion is
    deg = np.degrees(theta)
    f = spec.follower
    forces = None if design.speed is None else design.speed.forces
    hertz = None if forces is None else forces.hertz
    panels = ["pressure", "radius"] + (["force"] if forces else []) + (["stress"] if hertz else [])
    fig = figure(8, 2.4 * len(panels) + 1.2, layout=None)
    # room on the right only for the force panel's torque axis (no empty band without one)
    fig.subplots_adjust(left=0.12, right=0.88 if forces else 0.97, bottom=0.08, top=0.94, hspace=0.15)
    axes = np.atleast_1d(fig.subplots(len(panels), 1, sharex=True))
    ax = axes[0]
    flat = cam.follower.flat and not f.oscillating
    if flat:
        ax.text(0.5, 0.5, "pressure angle 0 by definition: a translating flat face is pushed square to its face",
                transform=ax.transAxes, ha="center", va="center", fontsize=9)
    else:
        ax.plot(deg, np.degrees(g.pressure_angle), color="C0", lw=1.2)
        for sign in (1, -1):
            ax.axhline(sign * design.pressure_limit_deg, color="C3", lw=0.8, ls="--")
    ax.set_ylabel("pressure angle (deg)")
    with np.errstate(divide="ignore", invalid="ignore"):
        rho = g.rho if g.rho is not None else 1.0 / g.kappa - cam.contact_radius
    radius_panel(axes[1], [("cam surface", deg, rho, "C0")], _size(cam), cam.contact_radius, spec.cam.min_rho_margin,
                 spec.output.tool_radius, flat=cam.follower.flat)
    rpm = spec.cam.rpm
    if forces and rpm is not None:                      # forces are found at a speed
        ld = spec_loading(f, cam.follower, motion=spec.motion, program=cam.program)
        omega = rpm * 2 * math.pi / 60
        push = normal_force(ld, omega, g, motion)
        axes[2].plot(deg, push, color="C0", lw=1.2, label="contact force (N)")
        axes[2].axhline(0.0, color="C3", lw=0.8, ls="--")
        axes[2].set_ylabel("contact force (N)")
        twin = axes[2].twinx()
        twin.plot(deg, torque(ld, omega, motion, theta), color="C1", lw=1.0, ls="-.")
        twin.set_ylabel("shaft torque (N·m)", color="C1")
        contact = materials_of(hertz)
        if hertz is not None and contact is not None:
            axes[3].plot(deg, contact_pressure(cam, contact, g, push)[0], color="C0", lw=1.2)
            axes[3].axhline(hertz.allowable, color="C3", lw=0.8, ls="--")
            axes[3].set_ylabel("Hertz pressure (MPa)")
    for a in axes:
        a.grid(alpha=0.3)
    axes[-1].set_xlabel("cam angle θ (degrees)")
    axes[-1].set_xlim(0, 360)
    axes[-1].set_xticks(range(0, 361, 30))
    at = f" at {spec.cam.rpm:g} rpm" if forces else ""
    axes[0].set_title(f"{spec.name}: checks over the turn{at} (dashed: limits)")
    return fig


def speeds_figure(design: Any) -> Any:
    """The report's ``speeds`` table drawn against cam speed: :func:`speeds_plot` of ``design.speed``."""
    return speeds_plot(design.spec.name, design.speed.speeds)


def speeds_plot(name: str, speeds: SpeedTable) -> Any:
    """The ``speeds`` table (:func:`camgen.forces.speeds_report`) against rpm: the camshaft torque's extremes and
    RMS with the peak power, the contact force's largest and (for a follower held on) least values with the margin
    (dashed) and the lift-off speed (dotted, every panel), and with materials the Hertz pressure against its
    allowable (dashed)."""
    rows = speeds.rows
    rpm = np.array([r.rpm for r in rows])
    column = lambda key: np.array([getattr(r, key) for r in rows])   # noqa: E731
    stress = speeds.allowable is not None
    fig = figure(8, 2.4 * (3 if stress else 2) + 1.2, layout=None)
    fig.subplots_adjust(left=0.12, right=0.88, bottom=0.08, top=0.94, hspace=0.15)
    axes = np.atleast_1d(fig.subplots(3 if stress else 2, 1, sharex=True))
    for key, label, style in (("torque_max", "torque max", "-"), ("torque_min", "torque min", "--"),
                              ("torque_rms", "torque RMS", ":")):
        axes[0].plot(rpm, column(key), color="C0", lw=1.2, ls=style, label=label)
    axes[0].set_ylabel("shaft torque (N·m)")
    axes[0].legend(fontsize=7, loc="upper left")
    twin = axes[0].twinx()
    twin.plot(rpm, column("power_max"), color="C1", lw=1.0, ls="-.")
    twin.set_ylabel("peak power (W)", color="C1")
    axes[1].plot(rpm, column("contact_force_max"), color="C0", lw=1.2, label="largest normal force")
    if speeds.margin is not None:
        axes[1].plot(rpm, column("contact_force_min"), color="C2", lw=1.2, label="least contact force")
        axes[1].axhline(speeds.margin, color="C3", lw=0.8, ls="--", label="margin")
    axes[1].set_ylabel("contact force (N)")
    axes[1].legend(fontsize=7, loc="upper left")
    if speeds.allowable is not None:
        axes[2].plot(rpm, column("pressure_max"), color="C0", lw=1.2)
        axes[2].axhline(speeds.allowable, color="C3", lw=0.8, ls="--")
        axes[2].set_ylabel("Hertz pressure max (MPa)")
    off = speeds.liftoff_rpm
    for a in axes:
        a.grid(alpha=0.3)
        if off is not None and rpm[0] <= off <= rpm[-1]:
            a.axvline(off, color="C3", lw=0.8, ls=":")
    axes[-1].set_xlabel("cam speed (rpm)")
    axes[-1].set_xlim(rpm[0], rpm[-1])
    lift = "" if off is None else f", lift-off at {off:.4g} rpm"
    axes[0].set_title(f"{name}: over {rpm[0]:g} to {rpm[-1]:g} rpm (dashed: limits{lift})")
    return fig


def drive_checks_plot(title: str, limit_deg: float, contacts: list[tuple[str, Cam, Any, Any, Any]],
                      torque_of: Any, allowable: float | None, fold: float, tool_radius: float = 0.0) -> Any:
    """The checks figure of a positive drive (a groove, a pair) at a speed with a mass: over the turn the pressure
    angle with its limit, and for each contact ``(label, cam, radius(geometry), force(geometry, motion),
    pressure(geometry, motion) or None)``: the radius of curvature of its surface (mm, convex positive, concave
    negative, on :func:`radius_panel`'s scale; ``fold`` mm, the roller's reach from the pitch curve, and a cutter of
    ``tool_radius`` mm its limits), the normal force it carries (N, 0 while the other contact carries it) and with
    materials its Hertz pressure (MPa) against ``allowable``; the shaft torque ``torque_of(theta, motion)`` (N*m) on
    the force panel's right axis."""
    stress = allowable is not None
    fig = figure(8, 2.4 * (4 if stress else 3) + 1.2, layout=None)
    fig.subplots_adjust(left=0.12, right=0.88, bottom=0.08, top=0.94, hspace=0.15)
    axes = np.atleast_1d(fig.subplots(4 if stress else 3, 1, sharex=True))
    drawn: list[int] = []
    curves: list[tuple[str, np.ndarray, np.ndarray, str]] = []
    for k, (label, cam, radius, force, pressure) in enumerate(contacts):
        theta, motion = sample_cycle(cam)
        g = cam.follower.pitch(theta, motion)
        deg = np.degrees(theta)
        if id(cam) not in drawn:
            axes[0].plot(deg, np.degrees(g.pressure_angle), color=f"C{k}", lw=1.2)
            drawn.append(id(cam))
        with np.errstate(divide="ignore", invalid="ignore"):
            curves.append((label, deg, radius(g), f"C{k}"))
        axes[2].plot(deg, force(g, motion), color=f"C{k}", lw=1.2, label=label)
        if stress:
            axes[3].plot(deg, pressure(g, motion), color=f"C{k}", lw=1.2, label=label)
    for sign in (1, -1):
        axes[0].axhline(sign * limit_deg, color="C3", lw=0.8, ls="--")
    axes[0].set_ylabel("pressure angle (deg)")
    radius_panel(axes[1], curves, _size(contacts[0][1]), fold, 0.0, tool_radius, flat=False)
    axes[2].set_ylabel("normal force (N)")
    twin = axes[2].twinx()
    theta, motion = sample_cycle(contacts[0][1])
    twin.plot(np.degrees(theta), torque_of(theta, motion), color="C7", lw=1.0, ls="-.")
    twin.set_ylabel("shaft torque (N·m)", color="C7")
    if stress:
        axes[3].axhline(allowable, color="C3", lw=0.8, ls="--")
        axes[3].set_ylabel("Hertz pressure (MPa)")
    for a in axes:
        a.grid(alpha=0.3)
    for a in axes[2:]:                                   # the radius panel has its own (radius_panel)
        a.legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("cam angle θ (degrees)")
    axes[-1].set_xlim(0, 360)
    axes[-1].set_xticks(range(0, 361, 30))
    axes[0].set_title(f"{title}: checks over the turn (dashed: limits)")
    return fig


def groove_checks_plot(spec: Any, cam: Cam, forces: Forces, limit_deg: float, d: float, rr: float,
                       labels: tuple[str, str]) -> Any:
    """:func:`drive_checks_plot` of a roller in a groove whose walls lie ``d`` mm either side of ``cam``'s pitch
    curve (a grooved cam's flanks, a barrel's developed walls): ``labels[0]`` the wall carrying F > 0 (curvature
    kappa / (1 - d kappa)), ``labels[1]`` the other (-kappa / (1 + d kappa)), the roller of radius ``rr`` mm."""
    from camgen.dynamics import spec_loading
    from camgen.forces import flank_pressure, materials_of, normal_force, torque

    ld = spec_loading(spec.follower, cam.follower, True, spec.motion, cam.program)
    omega = spec.cam.rpm * 2 * math.pi / 60
    st = forces.hertz
    contact = materials_of(st)

    def contact_of(sign: float) -> tuple[Any, Any]:
        def force(g: Any, m: np.ndarray) -> np.ndarray:
            return np.maximum(sign * normal_force(ld, omega, g, m), 0.0)

        if contact is None:                             # no materials: no pressure panel
            return force, None

        def pressure(g: Any, m: np.ndarray) -> np.ndarray:
            return flank_pressure(contact, g, sign * force(g, m), d, rr)[0]
        return force, pressure

    return drive_checks_plot(spec.name, limit_deg, [
        (labels[0], cam, lambda g: 1.0 / g.kappa - d, *contact_of(1.0)),
        (labels[1], cam, lambda g: -(1.0 / g.kappa + d), *contact_of(-1.0))],
        lambda t, m: torque(ld, omega, m, t), None if st is None else st.allowable, d,
        getattr(spec.output, "tool_radius", 0.0))


#: the radius panel: the farthest it draws (a multiple of the cam's size, rounded up to a power of ten: a straight
#: stretch, of infinite radius, is drawn there), and the least half-width of its linear band about 0 (mm)
_RADIUS_REACH, _LINEAR_MM = 20.0, 1.0


def _size(cam: Cam) -> float:
    """A cam's size for the radius panel's scale (mm): its base radius, its roller's and its lift (in mm)."""
    lift = cam.program.max_lift if cam.follower.lift_unit == "mm" else 0.0
    return max((cam.base_radius or 0.0) + cam.contact_radius + lift, 1.0)


def plotted_radius(rho: np.ndarray, reach: float) -> np.ndarray:
    """A signed radius of curvature (mm, convex positive, concave negative) as :func:`radius_panel` draws it: finite,
    its sign kept, anything beyond ``reach`` mm drawn at +-``reach`` and a straight stretch (an infinite radius, or
    NaN: no curvature to speak of) at +``reach``."""
    rho = np.asarray(rho, dtype=float)
    straight = ~np.isfinite(rho)
    return np.where(straight, reach, np.clip(np.where(straight, 0.0, rho), -reach, reach))


def radius_panel(ax: Any, curves: list[tuple[str, np.ndarray, np.ndarray, str]], size: float, fold: float,
                 margin: float, tool_radius: float, flat: bool) -> float:
    """The radius of curvature of a cam's surface against cam angle: each of ``curves`` ``(label, cam angles in
    degrees, rho mm, colour)``, signed (convex positive, concave negative) on a symmetric log scale that shows
    both sides (linear within a few mm of 0, straight stretches drawn at the edge, see :func:`plotted_radius`), with
    where the surface undercuts: below the convex limit ``margin`` mm (the pitch curve's radius less than the
    roller's radius ``fold`` + margin) down to -``fold`` (a roller's surface there is the fold of a pitch curve
    bending tighter than the roller; a concave surface lies beyond -``fold``), for a flat face (``flat``)
    everything below the limit (a cusp; its profile is never concave), and on the concave side a cutter's
    ``tool_radius`` (mm, none at 0). ``size`` (mm) sets the reach: the return value, the largest radius drawn as
    itself."""
    reach = 10.0 ** math.ceil(math.log10(_RADIUS_REACH * size))
    drawn = [plotted_radius(rho, reach) for _, _, rho, _ in curves]
    for (label, deg, _, colour), values in zip(curves, drawn, strict=True):
        ax.plot(deg, values, color=colour, lw=1.2, label=label)
    bottom = -reach if flat else -fold
    band = (f"cusp: below {margin:g} mm (a flat face cannot follow it)" if flat else
            f"undercut: {bottom:g} to {margin:g} mm (the pitch curve bends tighter than roller + margin)" if fold > 0
            else f"below the margin: 0 to {margin:g} mm")
    ax.axhspan(bottom, margin, color="C3", alpha=0.12, lw=0, label=band)
    limit = (f"convex limit: pitch radius = roller {fold:g} + margin {margin:g} mm" if fold > 0 and not flat else
             f"convex limit: margin {margin:g} mm")
    ax.axhline(margin, color="C3", lw=0.8, ls="--", label=limit)
    if tool_radius > 0 and not flat:
        ax.axhline(-tool_radius, color="C1", lw=0.8, ls="--", label=f"concave limit: tool radius {tool_radius:g} mm")
    linear = max(_LINEAR_MM, fold, margin, tool_radius)
    ax.set_yscale("symlog", linthresh=linear, linscale=0.6)
    every = np.concatenate(drawn)
    high = 1.6 * max(float(every.max()), linear, margin)  # as far as the curves go: no empty half without a concave
    low = -1.6 * max(-float(every.min()), fold, tool_radius) if every.min() < 0 else -max(fold, tool_radius, linear)
    ticks = np.concatenate([-_steps(linear, -low), [0.0], _steps(linear, high)])
    ax.set_yticks(ticks[(ticks >= low) & (ticks <= high)])
    ax.yaxis.set_major_formatter(_plain)
    ax.yaxis.set_minor_locator(_no_ticks())
    ax.set_ylim(low, high)
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.set_ylabel("radius (mm)\nconvex +, concave −" if not flat else "profile radius (mm)\ncusp −")
    if np.any(np.abs(every) >= reach):
        ax.plot([], [], " ", label=f"straight (|ρ| ≥ {reach:g} mm): drawn at ±{reach:g}")
    ax.legend(fontsize=6.5, loc="center right", framealpha=0.85)
    return reach


def _steps(linear: float, most: float) -> np.ndarray:
    """The ticks (mm, > 0, ascending) of one side of a symmetric log scale linear to ``linear`` and drawn to ``most``:
    ``linear`` and 1, 2, 5 x 10^k beyond it, or across more than a decade and a half the powers of ten alone (a tick
    within a factor 1.5 of ``linear`` is left out, so that no two labels overlap)."""
    if most < linear:
        return np.array([])
    powers = 10.0 ** np.arange(math.floor(math.log10(linear)), math.floor(math.log10(most)) + 1)
    steps = (powers[:, None] * ([1.0] if most / linear > 10 ** 1.5 else [1.0, 2.0, 5.0])).ravel()
    return np.concatenate([[linear], steps[(steps >= 1.5 * linear) & (steps <= most)]])


def _plain(value: float, _position: Any = None) -> str:
    """A tick's label as a plain number (1000, not 10^3)."""
    return f"{value:g}"


def _no_ticks() -> Any:
    from matplotlib.ticker import NullLocator

    return NullLocator()


def _machine_units(design: Traced, motion: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """The rows s, s', s'', s''' and their axis labels: per radian of cam angle without a speed, in time at
    ``cam.rpm`` (v = omega s', a = omega^2 s'', j = omega^3 s''', in m/s^n, or rad/s^n for an arm)."""
    u = design.cam.follower.lift_unit
    rpm = getattr(design.spec.cam, "rpm", None)
    if rpm is None:
        return motion, [f"s ({u})", f"s' ({u}/rad)", f"s'' ({u}/rad²)", f"s''' ({u}/rad³)"]
    omega = rpm * 2 * math.pi / 60
    unit, scale = ("rad", math.pi / 180) if u == "deg" else ("m", 1e-3)
    rates = np.array([omega ** k * scale for k in (1, 2, 3)])[:, None] * motion[1:]
    return np.vstack([motion[:1], rates]), [f"s ({u})", f"v ({unit}/s)", f"a ({unit}/s²)", f"j ({unit}/s³)"]


def _draw_follower(ax: Any, cam: Cam, circle: np.ndarray) -> None:
    """The follower at theta = 0 as it poses itself (:meth:`~camgen.followers.drawing.Follower.pose`): its links,
    its pivot marked, its roller; a flat face 5 mm past the contact's travel each side."""
    contact, f = cam.pitch(np.array([0.0])).point[0], cam.follower
    style = {"color": "C2", "lw": 2}
    reach = cam.base_radius + cam.program.max_lift if f.lift_unit == "mm" else cam.base_radius
    face = None
    if f.flat:
        lo, hi = face_extent(cam)
        face = (lo - 5, hi + 5)
    label = {"label": "follower at θ = 0"}
    for stroke in f.pose(contact, reach, face):
        centre = stroke.points[0]
        if stroke.style == "pivot":
            ax.plot(*centre, "^", color="C2", ms=9)
        elif stroke.radius > 0:
            ax.plot(centre[0] + stroke.radius * np.cos(circle), centre[1] + stroke.radius * np.sin(circle),
                    color="C2", lw=1)
        else:
            ax.plot(stroke.points[:, 0], stroke.points[:, 1], **label, **style)
            label = {}


def cam_figure(design: FlatCamDesign) -> Any:
    """The cam at theta = 0: outline, pitch curve, base and prime circles, follower, checks marked."""
    cam, a, t = design.cam, design.analysis, design.spec
    fig = figure(8, 9, layout=None)
    ax = fig.add_subplot()
    ring = design.outline.contour.flatten(design.tolerance)
    ax.fill(ring[:, 0], ring[:, 1], color="0.88", zorder=0)
    ax.plot(*np.vstack([ring, ring[:1]]).T, color="k", lw=1.2, label="cam outline")
    pitch = cam.pitch(np.linspace(0, 2 * math.pi, 721)).point
    ax.plot(pitch[:, 0], pitch[:, 1], "--", color="C0", lw=0.8, label="pitch curve")
    circle = np.linspace(0, 2 * math.pi, 361)
    if cam.is_plate:
        ax.axhline(cam.base_radius, ls=":", color="0.5", lw=0.7, label="base line")
    else:
        circles = [(cam.base_radius, ":", "base circle")]
        if cam.contact_radius > 0:
            circles.append((cam.base_radius + cam.contact_radius, "-.", "prime circle"))
        for radius, style, label in circles:
            ax.plot(radius * np.cos(circle), radius * np.sin(circle), style, color="0.5", lw=0.7, label=label)
    if t.cam.bore > 0:
        r = t.cam.bore / 2
        ax.fill(r * np.cos(circle), r * np.sin(circle), color="white", ec="k", lw=0.8)
    _draw_follower(ax, cam, circle)
    pa = cam.pitch(np.radians([a.pressure_angle_max_at_deg])).point[0]
    ax.plot(*pa, "o", color="C3", label=f"max pressure angle {a.pressure_angle_max_deg:.1f}° "
                                        f"at θ = {a.pressure_angle_max_at_deg:.1f}°")
    g = cam.pitch(np.radians([a.pitch_rho_min_at_deg]))
    rho = (g.point - cam.contact_radius * g.normal)[0]
    ax.plot(*rho, "s", color="C1", label=f"min convex radius {a.profile_rho_min_mm:.2f} mm (pitch "
                                          f"{a.pitch_rho_min_mm:.2f}) at θ = {a.pitch_rho_min_at_deg:.1f}°")
    if not cam.is_plate:
        arrow = 1 if t.cam.rotation == "ccw" else -1
        ax.annotate("", xy=(0.25 * cam.base_radius * arrow, -0.2 * cam.base_radius),
                    xytext=(-0.25 * cam.base_radius * arrow, -0.2 * cam.base_radius),
                    arrowprops={"arrowstyle": "->", "connectionstyle": f"arc3,rad={0.5 * arrow}", "color": "0.3"})
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.grid(alpha=0.3)
    # sized to the drawing: a plate cam is long and low, a disc with its arm's pivot wide (no empty bands)
    fit_equal(fig, [ax], width=10.0 if cam.is_plate else 8.0,
              legend_rows=math.ceil(len(ax.get_legend_handles_labels()[1]) / 2), max_height=9.5, top=0.1)
    fig.legend(loc="lower center", ncols=2, fontsize=8)
    what = "plate cam; θ spreads over the travel" if cam.is_plate else f"cam at θ = 0 ({t.cam.rotation})"
    ax.set_title(f"{t.name}: {what}, {t.follower.type} follower")
    return fig
