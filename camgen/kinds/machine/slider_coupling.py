"""A translating follower's stem as the slider input of a general linkage (``type = "linkage"``, its one input a
slider on a guide of the ground, ``input = { slider = NAME }``): the slider drives, the linkage's other links are
driven. Pure numpy; nothing is written.

The stem's line is fixed on the frame: the cam's fixed frame is the machine's (the cam's centre on its shaft's
``at``), and the follower slides along x = ``follower.offset`` (+Y its lift, the cam's own convention). The slider's
guide must be drawn along +Y (``angle = 90``); the linkage's drawing is moved (not turned) so that its slider's
point at travel ``rest`` (mm from the drawing) lies on the follower's rest point: the roller's centre (or the flat
face's middle, the knife's edge) with the follower at lift 0. The follower's lift s (mm) is the slider's
displacement from its rest: the slider input's value is ``rest + s``.

Rates per radian of the main shaft (mm/rad, rad/rad); forces in N; torques in N*m, counter-clockwise positive. The
external torque ``output_torque`` T on link ``output`` is carried back by virtual work: the stem pushes the slider
with F = -T d theta_out / d s (N, s in m), which presses the follower onto its cam (its load), and the main shaft
works against it with -T d theta_out / d phi.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.kinds.machine import arms, general_inertia, kinematics
from camgen.kinds.machine.cranked import GeneralMotion

#: the follower types whose stem can be a linkage's slider
STEMS = ("translating-roller", "translating-flat", "knife-edge")
#: how far (degrees) the slider's guide may be drawn from +Y, the follower's lift
GUIDE_TOL_DEG = 1e-9
#: the least transmission angle (degrees from a toggle) not warned of, as a coupled four-bar's
TRANSMISSION_WARN_DEG = 40.0


@dataclass(frozen=True)
class SliderMotion(GeneralMotion):
    """A linkage driven by a translating follower's stem over one turn of the main shaft (arrays by the machine's
    shaft angles).

    Attributes
    ----------
    name, cam : str
        Its mount's name and the cam whose follower drives it.
    coupling : Coupling
        The coupling (:class:`camgen.kinds.machine.spec.Coupling`).
    design : LinkageDesign
        Its linkgen design (its own report and parts).
    layer : int
        Its cam's layer (its parts fill planes 2 layer + their own layers, as a shaft-driven linkage's).
    offset : ndarray
        (2,) mm added to the drawing's coordinates: the follower's rest point less the slider's point at rest.
    lift : ndarray
        (3, n) the follower's lift s (mm), ds/dphi (mm/rad) and d2s/dphi2 (mm/rad^2).
    inputs : ndarray
        The slider input's value, rest + s (mm).
    points, rates : dict of str to ndarray
        Every joint (n, 2) in the machine's frame (mm) and its rate d P / d phi (mm/rad).
    output_angle, output_rate : ndarray
        The output link's turn from the drawing (radians) and d theta_out / d phi (rad/rad); zeros without
        ``coupling.output``.
    force : ndarray
        The output torque reflected onto the stem (N, pressing the follower onto its cam).
    torque : ndarray
        The main shaft's torque working against the output torque (N*m).
    program, turns, phase_deg : object, float, float
        The cam's follower program (:class:`camgen.motion.Program`), its shaft's turns per main turn and its phase
        (degrees): what :meth:`solve` places the slider by.
    base, scale : float
        The input's value is base + scale s: rest (mm) and 1 for a stem; rest in radians and the arm's swing sign
        in radians per degree for an arm (:func:`arm_motion`).
    lever : float
        The follower's path (mm) per unit of s: 1 for a stem, the roller's arc per degree of swing for an arm.
    accelerations : dict of str to ndarray
        Every joint's d^2 P / d phi^2 (n, 2; mm/rad^2) (:mod:`camgen.kinds.machine.general_inertia`).
    output_acc : ndarray or None
        d^2 theta_out / d phi^2 (rad/rad^2); zeros without ``coupling.output``.
    effort : ndarray or None
        With its template's ``[dynamics]``: the input's effort its inverse dynamics gives at the machine's speed
        (N*m on a crank, N on a slider; the output torque's share left out), counted in ``force`` and ``torque``;
        None without.
    """

    name: str
    cam: str
    coupling: Any
    design: Any
    layer: int
    offset: np.ndarray
    lift: np.ndarray
    inputs: np.ndarray
    points: dict[str, np.ndarray]
    rates: dict[str, np.ndarray]
    output_angle: np.ndarray
    output_rate: np.ndarray
    force: np.ndarray
    torque: np.ndarray
    program: Any
    turns: float
    phase_deg: float
    base: float = 0.0
    scale: float = 1.0
    lever: float = 1.0
    accelerations: dict[str, np.ndarray] = field(default_factory=dict)
    output_acc: np.ndarray | None = None
    effort: np.ndarray | None = None
    #: the cam's shaft's motion where it indexes (:class:`~camgen.kinds.machine.shaft_motion.ShaftMotion`), else None
    shaft_motion: Any = None

    #: a slider-driven linkage stands on the frame's front, as its cam (the clash check's planes)
    side = 1
    shaft = ""

    @property
    def ground_slider(self) -> Any:
        """The slider its coupling drives where that slider slides on the ground (a stem, its cam's follower having
        no arm, carries its block), else None."""
        slider = next((s for s in self.analysis.linkage.structure.sliders if s.name == self.coupling.link), None)
        return slider if slider is not None and slider.link is None else None

    def solve(self, phi: np.ndarray) -> Any:
        """Its linkage solved at main shaft angles ``phi`` (radians) in its drawing's frame, by the slider's travel
        rest + s (velocities per mm of it): :class:`linkgen.kinematics.linkage.Solution`."""
        phi = np.asarray(phi, dtype=float)
        if self.shaft_motion is None:
            theta = kinematics.program_angles(phi, self.turns, math.radians(self.phase_deg))
        else:
            theta = np.mod(self.shaft_motion.own(phi)[0] - math.radians(self.phase_deg), kinematics.TWO_PI)
        values = self.base + self.scale * self.program.evaluate(theta)[0]
        return self.analysis.linkage.solve(np.asarray(values, dtype=float)[None, :])


def transmission_warnings(motion: SliderMotion) -> list[str]:
    """A warning for each dyad of ``motion``'s linkage whose transmission angle comes within
    :data:`TRANSMISSION_WARN_DEG` degrees of a toggle (0 or 180 for a pin dyad, 0 for one with a slide) over the
    range the follower drives it through (the linkage's own report judges its whole reach instead)."""
    sol = motion.analysis.linkage.solve(motion.inputs[None, :])
    out = []
    for dyad in sol.dyads:
        gamma = np.degrees(np.asarray(dyad.transmission, dtype=float))
        worst = float(np.min(np.minimum(gamma, 180.0 - gamma)) if dyad.kind == "RRR" else np.min(gamma))
        if worst < TRANSMISSION_WARN_DEG:
            out.append(f"linkages.{motion.name}: the transmission angle of its dyad at joint {dyad.joint} comes "
                       f"within {worst:.1f} degrees of a toggle over the range cams.{motion.cam} drives it through")
    return out


def check(spec: Any, index: int, lspec: Any) -> None:
    """Refuse coupling ``spec.couplings[index]`` of a translating follower to ``lspec`` (the linkage's validated
    spec) unless that is a ``type = "linkage"`` template whose one input is a slider on a ground guide drawn along
    +Y, ``coupling.link`` names that slider, and ``coupling.output`` (if given) is one of its links (a ValueError
    naming the field)."""
    c = spec.couplings[index]
    table = lspec.linkage
    where = f"couplings[{index}]"
    inputs: tuple[Any, ...] = getattr(table, "inputs", ())
    if table.type != "linkage" or len(inputs) != 1 or inputs[0].slider is None:
        raise ValueError(f"{where}.linkage: cams.{c.cam}'s translating follower drives a type = \"linkage\" "
                         f"template whose one input is a slider (input = {{ slider = NAME }}); linkages.{c.linkage} "
                         + (f"is a {table.type}" if table.type != "linkage" else "has another input"))
    name = inputs[0].slider
    if c.link != name:
        raise ValueError(f"{where}.link: a translating follower's stem is its linkage's input slider: "
                         f"{name!r}, not {c.link!r}")
    slider = table.sliders[name]
    if slider.guide != "ground":
        raise ValueError(f"{where}.link: slider {name} of linkages.{c.linkage} slides on {slider.guide}; the stem's "
                         "guide is the frame's (guide = \"ground\")")
    if abs(math.remainder(slider.angle - 90.0, 360.0)) > GUIDE_TOL_DEG:
        raise ValueError(f"{where}.link: slider {name} of linkages.{c.linkage} is drawn at {slider.angle:g} "
                         "degrees; draw its guide along +Y (angle = 90), the follower's lift")
    _check_output(c, where, table)


def check_arm(spec: Any, index: int, lspec: Any) -> None:
    """Refuse coupling ``spec.couplings[index]`` of an oscillating follower's arm to ``lspec``, a ``type =
    "linkage"`` template, unless its one input is a crank about a ground joint (relative to the ground) and
    ``coupling.link`` names that crank (a ValueError naming the field)."""
    c = spec.couplings[index]
    table = lspec.linkage
    where = f"couplings[{index}]"
    inputs: tuple[Any, ...] = table.inputs
    if len(inputs) != 1 or inputs[0].slider is not None or inputs[0].relative_to != "ground" \
            or inputs[0].pivot not in table.ground:
        raise ValueError(f"{where}.linkage: cams.{c.cam}'s arm drives a type = \"linkage\" template whose one "
                         f"input is a crank about a ground joint (input = {{ link, pivot }}); linkages.{c.linkage} "
                         "has another input")
    if c.link != inputs[0].link:
        raise ValueError(f"{where}.link: the follower's arm is its linkage's input crank: {inputs[0].link!r}, not "
                         f"{c.link!r}")
    _check_output(c, where, table)


def _check_output(c: Any, where: str, table: Any) -> None:
    """Refuse an ``output`` that is not one of the linkage's links, or an output torque with no link to act on."""
    if c.output is not None and c.output not in table.links:
        raise ValueError(f"{where}.output: linkages.{c.linkage} has no link {c.output!r}; its links: "
                         f"{', '.join(table.links)}")
    if c.output_torque and c.output is None:
        raise ValueError(f"{where}.output: give the link output_torque acts on (one of "
                         f"{', '.join(table.links)})")


def arm_motion(spec: Any, index: int, mount_index: int, cam: Any, kin: Any, design: Any,
               phi: np.ndarray) -> SliderMotion:
    """The linkage of ``spec.linkages[mount_index]`` (``design``) whose input crank is ``cam``'s follower arm
    (coupling ``index``): the drawing moved (not turned) so that its crank's pivot lies on the arm's, the crank's
    direction (degrees from +X) ``rest`` + the arm's swing turned the way the arm turns, so that the crank and the
    arm are one rigid bell crank."""
    coupling, f = spec.couplings[index], kin.follower
    pivot = design.kinematics.table.inputs[0].pivot
    drawn = np.asarray(design.kinematics.linkage.structure.points[pivot], dtype=float)
    offset = _shaft_at(spec, cam.name) + np.asarray(f.pivot, dtype=float) - drawn
    k = arms.swing_sign(f)
    mapping = (math.radians(coupling.rest), k * math.pi / 180.0,
               arms.lever(f, _crank_length(design, pivot)) * math.pi / 180.0)
    return driven(spec, index, mount_index, cam, kin, design, phi, offset, mapping)


def _crank_length(design: Any, pivot: str) -> float:
    """The distance (mm) from the input crank's ``pivot`` to its nearest other joint in the drawing (its pin)."""
    table = design.kinematics.table
    points = design.kinematics.linkage.structure.points
    at = np.asarray(points[pivot], dtype=float)
    others = [p for p in table.links[table.inputs[0].link] if p != pivot]
    return min(float(np.hypot(*(np.asarray(points[p], dtype=float) - at))) for p in others)


def rest_point(follower: Any) -> np.ndarray:
    """The follower's rest point (mm, the cam's frame): on its axis x = offset, at the roller's centre with lift 0
    (a flat face's or knife's contact height: its base radius)."""
    height = getattr(follower, "d0", None)
    return np.array([float(follower.axis_x), float(follower.base_radius if height is None else height)])


def slider_motion(spec: Any, index: int, mount_index: int, cam: Any, kin: Any, design: Any,
                  phi: np.ndarray) -> SliderMotion:
    """The linkage of ``spec.linkages[mount_index]`` (designed as ``design``) driven through coupling ``index`` by
    ``cam``'s (:class:`~camgen.kinds.machine.design.CamMotion`, its kinematic cam ``kin``: a
    :class:`~camgen.cam.Cam` with a translating follower) at main shaft angles ``phi``.

    Raises
    ------
    SpecError
        ``couplings[i].rest`` where the slider's rest lies out of the linkage's reach; ``couplings[i]`` where the
        follower's stroke drives it past a toggle (out of its reach), naming the cam, the linkage and the first
        main shaft angle.
    """
    coupling, follower = spec.couplings[index], kin.follower
    point = design.kinematics.table.sliders[coupling.link].point
    drawn = np.asarray(design.kinematics.linkage.structure.points[point], dtype=float)
    offset = _shaft_at(spec, cam.name) + rest_point(follower) - drawn - np.array([0.0, coupling.rest])
    return driven(spec, index, mount_index, cam, kin, design, phi, offset, (coupling.rest, 1.0, 1.0))


def driven(spec: Any, index: int, mount_index: int, cam: Any, kin: Any, design: Any, phi: np.ndarray,
           offset: np.ndarray, mapping: tuple[float, float, float]) -> SliderMotion:
    """The linkage of ``spec.linkages[mount_index]`` (``design``) moved by ``offset`` (mm) and driven through
    coupling ``index`` by ``cam``'s follower: its input base + scale s, ``mapping`` = (base, scale, lever), lever
    the follower's path (mm) per unit of s (1 for a stem's lift; the arm's length in mm per degree of swing), by
    which a force along it does the work of the load."""
    coupling = spec.couplings[index]
    base, scale, lever = mapping
    linkage = design.kinematics.linkage
    name = spec.linkages[mount_index].name
    lift = cam.rates                                    # per radian of the main shaft, through its shaft's Q', Q''
    inputs = base + scale * lift[0]
    _check_reach(linkage, coupling, index, inputs, phi, name, base)
    sol = linkage.solve(inputs[None, :])
    points = {p: np.asarray(xy, dtype=float) + offset for p, xy in sol.points.items()}
    rates = {p: np.asarray(v, dtype=float) * (scale * lift[1])[:, None] for p, v in sol.velocities.items()}
    d1, d2 = general_inertia.input_rates(scale, lift)
    if coupling.output is None:
        angle = per_unit = output_acc = np.zeros_like(phi)
    else:
        angle = np.asarray(sol.angle(coupling.output), dtype=float)
        per_unit = scale * np.asarray(sol.omegas[coupling.output], dtype=float)
        output_acc = general_inertia.angular_acceleration(sol, coupling.output, d1, d2)
    layer = next(c.layer for c in spec.cams if c.name == cam.name)
    load = general_inertia.driven_load(design, inputs, lift, mapping, coupling.output_torque, per_unit,
                                       spec.machine.rpm * math.pi / 30.0)
    return SliderMotion(name, cam.name, coupling, design, layer, offset, lift, inputs, points, rates, angle,
                        per_unit * lift[1], load.force, load.torque, kin.program, cam.turns, cam.phase_deg, base,
                        scale, lever, general_inertia.accelerations(sol, d1, d2), output_acc, load.effort,
                        cam.shaft)


def _shaft_at(spec: Any, cam: str) -> np.ndarray:
    """The centre (mm) of the shaft cam ``cam`` is mounted on."""
    shaft = next(c.shaft for c in spec.cams if c.name == cam)
    return next(np.asarray(s.at, dtype=float) for s in spec.shafts if s.name == shaft)


def _check_reach(linkage: Any, coupling: Any, index: int, inputs: np.ndarray, phi: np.ndarray, name: str,
                 base: float) -> None:
    """Refuse a rest out of the input's reach, or a stroke that drives it out (past a toggle), naming the coupling,
    the cam, the linkage and the first main shaft angle (a slider's travel in mm, a crank's angle in degrees)."""
    crank = linkage.structure.inputs[0].kind == "crank"
    noun, unit, shown = ("crank", "degrees", math.degrees) if crank else ("slider", "mm", float)
    ranges = linkage.ranges
    reach = (f"; its {noun} reaches " + " or ".join(f"[{shown(lo):.6g}, {shown(hi):.6g}] {unit}"
                                                     for lo, hi in ranges)) if ranges else ""
    if not linkage.solve(np.array([[base]]), strict=False).ok.all():
        raise SpecError(f"the {noun} of linkages.{name} at rest ({coupling.rest:g} {unit}) is out of its "
                        f"reach{reach}; give a rest within its travel", f"couplings[{index}].rest")
    ok = linkage.solve(inputs[None, :], strict=False).ok
    if ok.all():
        return
    first = int(np.argmin(ok))
    raise SpecError(f"cams.{coupling.cam}'s follower drives the {noun} of linkages.{name} through "
                    f"[{shown(inputs.min()):.6g}, {shown(inputs.max()):.6g}] {unit} (rest {coupling.rest:g} + its "
                    f"{'swing' if crank else 'lift'}), past a toggle from the main shaft's "
                    f"{math.degrees(float(phi[first])):.4g} degrees{reach}; change couplings[{index}].rest, the "
                    "cam's lift or the linkage", f"couplings[{index}]")
