"""A machine designed: every cam by its kind (the registry, :mod:`camgen.kinds`), every coupled four-bar driven
through the range its follower swings it, every output over one turn of the main shaft with its rates, the
checks together and the forces carried back onto each follower and camshaft. Nothing is written.

A four-bar driven past a toggle (a crank angle out of its reach) is a :class:`SpecError` naming the coupling, the
cam and the linkage. The linkage's ``output_torque`` is reflected onto its follower as a load against cam angle
(camgen's ``follower.load_table``), and the cam is designed again with it, so its own contact check (with its
follower's mass and spring) says whether the follower stays on the cam with the linkage attached and what preload
or spring rate would hold it (:func:`camgen.dynamics.speed_report`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.kinds import spec_kind
from camgen.kinds.machine import (arms, chain_inertia, clash, frame, general_inertia, indexed_cam, indexing,
                                  kinematics, machine_gears, shaft_motion, slider_coupling)
from camgen.kinds.machine.cranked import CrankedMotion, cranked_motion
from camgen.kinds.machine.ratchet_mount import RatchetMotion, program_load, ratchet_motion
from camgen.kinds.machine.spec import Coupling, MachineSpec
from linkgen import api as linkgen_api
from linkgen.kinematics.fourbar import FourBar

#: rows of the reflected load table (cam angle, degrees) a coupled cam is designed again with
LOAD_ROWS = 360
#: the least transmission angle (degrees from square or flat, whichever is nearer) not warned of
TRANSMISSION_WARN_DEG = 40.0


@dataclass(frozen=True)
class CamMotion:
    """One cam of the machine: its mount's name, its design (by its kind), its shaft's turns per main turn, its
    program angles theta (radians) at the machine's shaft angles and its follower's (s, s', s'') there (camgen's
    units: mm or degrees of swing, per radian of the program)."""

    name: str
    design: Any
    turns: float
    phase_deg: float
    theta: np.ndarray
    follower: np.ndarray
    #: its shaft's motion (:class:`~camgen.kinds.machine.shaft_motion.ShaftMotion`), None: uniform at ``turns``
    shaft: shaft_motion.ShaftMotion | None = None

    @property
    def indexer(self) -> indexing.Indexer | None:
        """The Geneva drive whose wheel turns its shaft (directly or through gears), else None."""
        return None if self.shaft is None else self.shaft.indexer

    @property
    def motion(self) -> shaft_motion.ShaftMotion:
        """Its shaft's motion (uniform at ``turns`` where none was given)."""
        return self.shaft if self.shaft is not None else shaft_motion.ShaftMotion("", self.turns)

    def shaft_rates(self, phi: np.ndarray) -> np.ndarray:
        """(3, n): its shaft's angle and rates in its own sense (rad, rad/rad, rad/rad^2) at main shaft angles
        ``phi`` (rad): Q, Q', Q'' (:meth:`~camgen.kinds.machine.shaft_motion.ShaftMotion.own`)."""
        return self.motion.own(phi)

    def program_angles(self, phi: np.ndarray) -> np.ndarray:
        """Its program angles (rad, in [0, 2 pi)) at main shaft angles ``phi`` (rad): its shaft's angle less its
        phase (an indexing shaft's from its Geneva drive)."""
        if self.indexer is None:
            return kinematics.program_angles(phi, self.turns, math.radians(self.phase_deg))
        return np.mod(self.shaft_rates(phi)[0] - math.radians(self.phase_deg), kinematics.TWO_PI)

    @property
    def unit(self) -> str:
        """The follower's unit: ``"deg"`` for an arm's swing, ``"mm"`` for a translating follower."""
        return str(_cam_of(self.design).follower.lift_unit)

    @property
    def rates(self) -> np.ndarray:
        """(3, n): the follower's (s, ds/dphi, d^2s/dphi^2) at the machine's shaft angles, per radian of the main
        shaft, by the chain rule through its shaft's Q' and Q'': s, s' Q', s'' Q'^2 + s' Q'' (on a uniform shaft
        Q' = |turns|, Q'' = 0)."""
        if self.indexer is None:
            n = abs(self.turns)
            return np.stack([self.follower[0], n * self.follower[1], n * n * self.follower[2]])
        q = self.shaft_rates(kinematics.shaft_angles(len(self.theta)))
        return np.stack([self.follower[0], self.follower[1] * q[1],
                         self.follower[2] * q[1] ** 2 + self.follower[1] * q[2]])

    @property
    def rate(self) -> np.ndarray:
        """d s / d phi: the follower's rate per radian of the main shaft (on an indexing shaft, times its rate)."""
        if self.indexer is None:
            return self.follower[1] * abs(self.turns)
        return self.rates[1]


@dataclass(frozen=True)
class LinkageMotion:
    """One coupled four-bar over the turn (arrays by the machine's shaft angles; angles in radians).

    Attributes
    ----------
    name, cam : str
        Its mount's name and the cam whose follower drives it.
    coupling : Coupling
        The coupling.
    design : LinkageDesign
        Its linkgen design (its own report and parts).
    fourbar : FourBar
        Its kinematics.
    chain : Chain
        The crank's angle and rates per radian of the main shaft.
    theta3, theta4, gamma : ndarray
        Coupler and rocker angles, transmission angle.
    k3, k4 : ndarray
        d theta3 / d theta2 and d theta4 / d theta2.
    rocker_rate, rocker_acc : ndarray
        d theta4 / d phi (rad/rad) and d^2 theta4 / d phi^2.
    point, point_rate : ndarray
        (n, 2) the coupler point (mm, the linkage's frame) and d P / d phi (mm/rad).
    force : ndarray
        The output torque reflected onto the follower's roller (N, pressing it onto the cam), with the linkage's
        own dynamics where its template has ``[dynamics]`` (:mod:`camgen.kinds.machine.chain_inertia`).
    torque : ndarray
        The main shaft's torque working against the output torque (N*m), and against the linkage's inertia, weight,
        springs and loads with ``[dynamics]``.
    effort : ndarray or None
        With ``[dynamics]``: the inverse dynamics' share of the crank's torque (N*m), the output torque's left out.
    """

    name: str
    cam: str
    coupling: Coupling
    design: Any
    fourbar: FourBar
    chain: kinematics.Chain
    theta3: np.ndarray
    theta4: np.ndarray
    gamma: np.ndarray
    k3: np.ndarray
    k4: np.ndarray
    rocker_rate: np.ndarray
    rocker_acc: np.ndarray
    point: np.ndarray
    point_rate: np.ndarray
    force: np.ndarray
    torque: np.ndarray
    effort: np.ndarray | None = None


@dataclass(frozen=True)
class Output:
    """One output of the timing diagram: its ``label`` (``cams.head`` a follower, ``linkages.arm`` a rocker), its
    ``unit`` and its ``values`` and ``rate`` (per radian of the main shaft) at the machine's shaft angles."""

    label: str
    unit: str
    values: np.ndarray
    rate: np.ndarray

    @property
    def still(self) -> np.ndarray:
        """Where it stands still (:func:`camgen.kinds.machine.kinematics.still`)."""
        return kinematics.still(self.rate, self.values)


@dataclass(frozen=True)
class MachineDesign:
    """Everything known about a machine before anything is written: its spec, the main shaft's angles ``phi``
    (radians, one turn), each cam's motion and each coupled linkage's, the warnings, the clash check's findings, and
    each linkage a shaft's crank drives (``cranked``)."""

    spec: MachineSpec
    phi: np.ndarray
    cams: tuple[CamMotion, ...]
    linkages: tuple[LinkageMotion, ...]
    warnings: tuple[str, ...]
    clashes: tuple[clash.Clash, ...] = ()
    unchecked: tuple[str, ...] = ()
    cranked: tuple[CrankedMotion, ...] = ()
    #: every part the clash check placed (:func:`camgen.kinds.machine.clash.machine_parts`, a frame's spacers too)
    bodies: tuple[clash.Body, ...] = ()
    #: the frame ``machine.frame`` asks for (:mod:`camgen.kinds.machine.frame`), None for none
    frame: frame.Frame | None = None
    #: each linkage a translating follower's stem drives (:mod:`camgen.kinds.machine.slider_coupling`)
    slid: tuple[slider_coupling.SliderMotion, ...] = ()
    #: each Geneva drive between two shafts (:mod:`camgen.kinds.machine.indexing`)
    indexed: tuple[indexing.Indexer, ...] = ()
    #: each gear pair as real involute gears (:mod:`camgen.kinds.machine.machine_gears`)
    gears: tuple[machine_gears.MachineGear, ...] = ()
    #: each ratchet a follower's arm indexes (:mod:`camgen.kinds.machine.ratchet_mount`)
    ratchets: tuple[RatchetMotion, ...] = ()

    @cached_property
    def written_linkages(self) -> tuple[tuple[Any, Any], ...]:
        """Each mounted linkage and its design as the machine writes it, without the parts other parts of the machine
        are (:func:`camgen.kinds.machine.coupled_kit.machine_made`): made once a design, for its files, its kit and
        its report (each nests the linkage's cut sheets again without those parts)."""
        from camgen.kinds.machine.coupled_kit import machine_made

        return machine_made(self)

    @property
    def tolerance(self) -> float:
        """The finest chord tolerance (mm) its cams were made to (0.01 mm for a machine of no cams)."""
        return min((float(c.design.tolerance) for c in self.cams), default=0.01)

    @property
    def omega(self) -> float:
        """The main shaft's speed (rad/s)."""
        return self.spec.machine.rpm * math.pi / 30.0

    @property
    def outputs(self) -> tuple[Output, ...]:
        """The timing diagram's outputs in order: each follower (its swing in degrees, or its lift in mm), then each
        coupled four-bar's rocker (its angle in degrees), then each follower-driven general linkage's output link
        (its turn from its drawing, degrees), then each shaft-driven and each follower-driven general linkage's
        tracers (x and y, mm in the machine's frame), then each Geneva drive's wheel and each ratchet's wheel (its
        turn from the start, degrees)."""
        cams = tuple(Output(f"cams.{c.name}", c.unit, c.follower[0], c.rate) for c in self.cams)
        traced = tuple(Output(f"linkages.{m.name}.{p}.{axis}", "mm", m.points[p][:, k], m.rates[p][:, k])
                       for m in (*self.cranked, *self.slid) for p in m.tracers for k, axis in enumerate("xy"))
        slid = tuple(Output(f"linkages.{m.name}", "deg", np.degrees(m.output_angle), np.degrees(m.output_rate))
                     for m in self.slid if m.coupling.output is not None)
        wheels = tuple(Output(f"genevas.{g.name}", "deg", *map(np.degrees, g.wheel_motion(self.phi)))
                       for g in self.indexed)
        ratchets = tuple(Output(f"ratchets.{r.name}", "deg", np.degrees(r.angle), np.degrees(r.rate))
                         for r in self.ratchets)
        return (*cams, *(Output(f"linkages.{m.name}", "deg", np.degrees(m.theta4), np.degrees(m.rocker_rate))
                         for m in self.linkages), *slid, *traced, *wheels, *ratchets)

    @property
    def shaft_torque(self) -> np.ndarray:
        """The main shaft's torque (N*m) working against every linkage's output torque, at its angles (and against
        each linkage's own dynamics, where its template has ``[dynamics]``), and every ratchet's load."""
        cranked = (m.torque for m in self.cranked if m.torque is not None)
        return sum((*(m.torque for m in self.linkages), *cranked, *(m.torque for m in self.slid),
                    *(r.torque for r in self.ratchets)), np.zeros_like(self.phi))

    def together(self, a: str, b: str) -> bool:
        """Whether outputs labelled ``a`` and ``b`` move together by construction (left out of the overlaps): a
        follower and the linkage it drives (and its tracers), two outputs of one general linkage, a Geneva drive's
        wheel and a cam on its shaft, or a ratchet's wheel and the follower whose arm indexes it."""
        driven = [(m.cam, m.name) for m in self.linkages] + [(m.cam, m.name) for m in self.slid]
        pairs = {frozenset((f"cams.{cam}", f"linkages.{name}")) for cam, name in driven}
        own = [m.name for m in (*self.cranked, *self.slid) if a.startswith(f"linkages.{m.name}")
               and b.startswith(f"linkages.{m.name}")]
        followed = [m.name for m in self.slid if {a, b} & {f"cams.{m.cam}"}
                    and any(x.startswith(f"linkages.{m.name}.") for x in (a, b))]
        indexed = {frozenset((f"cams.{c.name}", f"genevas.{c.indexer.name}")) for c in self.cams if c.indexer}
        ratcheted = {frozenset((f"cams.{r.cam}", f"ratchets.{r.name}")) for r in self.ratchets}
        return frozenset((a, b)) in pairs | indexed | ratcheted or bool(own) or bool(followed)

    def cam(self, name: str) -> CamMotion:
        """The cam mounted as ``name``."""
        return next(c for c in self.cams if c.name == name)

    def _repr_svg_(self) -> str:
        """Jupyter shows the timing diagram."""
        import io

        from camgen.kinds.machine.plots import timing_figure

        text = io.StringIO()
        timing_figure(self).savefig(text, format="svg")
        return text.getvalue()

    def _repr_html_(self) -> str | None:
        return None


def _cam_of(design: Any) -> Any:
    """The kinematic cam (:class:`~camgen.cam.Cam`) of a cam kind's design: its own, or its profile's (a grooved
    cam's island)."""
    cam = getattr(design, "cam", None)
    if cam is None:
        cam = getattr(getattr(design, "profile", None), "cam", None)
    return cam


def design_machine(spec: MachineSpec) -> MachineDesign:
    """The machine ``spec`` describes: its cams designed by their kinds, its couplings composed over one turn.

    Raises
    ------
    SpecError
        A cam whose kind has no single follower program to drive a linkage with (naming ``cams[i].template``), a
        four-bar whose follower swings it past a toggle (naming ``couplings[i]``, the cam and the linkage).
    DesignError
        A cam or linkage that cannot be made as asked (its own message, the key under its template).
    """
    frame.check_names(spec)
    phi = kinematics.shaft_angles(spec.machine.samples)
    indexed = indexing.indexers(spec, tuple(_geneva(spec, i) for i in range(len(spec.genevas))))
    shafts = shaft_motion.shaft_motions(spec, indexed)
    cams = {mount.name: _cam_motion(spec, i, phi, shafts[mount.shaft]) for i, mount in enumerate(spec.cams)}
    gears = machine_gears.designed(spec, min((float(c.design.tolerance) for c in cams.values()), default=0.01),
                                   shafts)
    linkages = []
    slid = []
    warnings: list[str] = []
    for i, coupling in enumerate(spec.couplings):
        index = next(j for j, m in enumerate(spec.linkages) if m.name == coupling.linkage)
        if _cam_of(cams[coupling.cam].design).follower.lift_unit == "mm" \
                or spec.linkage_specs[index].linkage.type == "linkage":
            driven = _slider_motion(spec, i, index, cams[coupling.cam])
            slid.append(driven)
            warnings += slider_coupling.transmission_warnings(driven)
            if coupling.output_torque or driven.effort is not None:
                cams[coupling.cam] = _loaded_stem(spec, cams[coupling.cam], driven)
            continue
        found = _linkage_motion(spec, i, index, cams[coupling.cam])
        linkages.append(found)
        worst = float(np.degrees(np.min(np.minimum(found.gamma, math.pi - found.gamma))))
        if worst < TRANSMISSION_WARN_DEG:
            warnings.append(f"linkages.{coupling.linkage}: the transmission angle comes within {worst:.1f} degrees "
                            f"of a toggle over the range cams.{coupling.cam} drives it through")
        if coupling.output_torque or found.effort is not None:
            cams[coupling.cam] = _loaded(spec, cams[coupling.cam], found)
    ratchets = tuple(_ratchet(spec, i, cams[r.cam]) for i, r in enumerate(spec.ratchets))
    for r in ratchets:
        if r.mount.load_torque:
            cams[r.cam] = _loaded_ratchet(spec, cams[r.cam], r)
    for c in cams.values():
        warnings += [f"cams.{c.name}: {w}" for w in c.design.warnings]
        real = indexed_cam.indexed_cam(c, _cam_of(c.design), spec.machine.rpm * math.pi / 30.0, phi)
        if real is not None and real.warning() is not None:
            warnings.append(str(real.warning()))
    cranked = []
    for i, mount in enumerate(spec.linkages):
        if mount.shaft is not None:
            lspec = spec.linkage_specs[i]
            try:
                made_linkage = linkgen_api.design(lspec, parts=lspec.parts is not None)
            except SpecError as exc:
                raise exc.under(f"linkages[{i}].template") from None
            cranked.append(cranked_motion(spec, i, phi, made_linkage, shafts[mount.shaft]))
            warnings += [f"linkages.{mount.name}: {w}" for w in made_linkage.report.get("warnings", ())]
    warnings += [f"genevas.{g.name}: {w}" for g in indexed for w in g.design.warnings]
    made = MachineDesign(spec, phi, tuple(cams.values()), tuple(linkages), tuple(warnings), cranked=tuple(cranked),
                         slid=tuple(slid), indexed=indexed, ratchets=ratchets)
    warnings += [w for g in gears for w in machine_gears.warnings_of(g)]
    made = replace(made, gears=gears, warnings=tuple(warnings))
    bodies, joints, unchecked = clash.machine_parts(made, one_plate=spec.machine.frame == "one")
    if spec.machine.frame == "two":
        bodies, joints = frame.with_top_plate(bodies, joints)
    met = clash.clashes(bodies, joints, spec.machine.clash_samples)
    if met and spec.machine.clash == "error":
        more = f" (and {len(met) - 1} more clash(es))" if len(met) > 1 else ""
        raise SpecError(f"{met[0].message()}{more}; move a part to another layer, or set machine.clash = "
                        '"warn"',
                        "machine.clash")
    noted = (*warnings, *(f"clash: {c.message()}" for c in met))
    return replace(made, clashes=met, unchecked=unchecked, warnings=noted, bodies=bodies,
                   frame=frame.machine_frame(made, bodies, joints))


def _geneva(spec: MachineSpec, index: int) -> Any:
    """The Geneva drive of ``spec.genevas[index]`` designed by its kind."""
    gspec = spec.geneva_specs[index]
    try:
        return spec_kind(gspec).design(gspec)
    except SpecError as exc:
        raise exc.under(f"genevas[{index}].template") from None


def _cam_motion(spec: MachineSpec, index: int, phi: np.ndarray,
                shaft: shaft_motion.ShaftMotion | None = None) -> CamMotion:
    """The cam of ``spec.cams[index]`` designed by its kind, and its follower's motion at shaft angles ``phi`` (its
    shaft's angle from ``shaft``, its shaft's motion: a Geneva drive's wheel's, or uniform)."""
    mount, cam_spec = spec.cams[index], spec.cam_specs[index]
    try:
        design = spec_kind(cam_spec).design(cam_spec)
    except SpecError as exc:
        raise exc.under(f"cams[{index}].template") from None
    cam = _cam_of(design)
    if cam is None:
        raise SpecError(f"{spec_kind(cam_spec).title} has no single follower program for a machine to drive "
                        "with; give a disc, plate or grooved cam", f"cams[{index}].template")
    turns = spec.turns[mount.shaft]
    made = CamMotion(mount.name, design, turns, mount.phase, phi, np.zeros((3, len(phi))),
                     None if shaft is None or shaft.uniform else shaft)
    theta = made.program_angles(phi)
    return replace(made, theta=theta, follower=cam.program.evaluate(theta)[:3])


def _linkage_motion(spec: MachineSpec, index: int, mount_index: int, cam: CamMotion) -> LinkageMotion:
    """The four-bar of ``spec.linkages[mount_index]`` driven by ``cam``'s follower through coupling ``index``."""
    coupling, lspec = spec.couplings[index], spec.linkage_specs[mount_index]
    table = lspec.linkage
    fb = FourBar(table.ground, table.crank, table.coupler, table.rocker, table.point_distance,
                 math.radians(table.point_angle))
    chain = kinematics.follower_chain(coupling.rest, cam.rates)
    _check_reach(fb, chain.theta2, index, coupling)
    poses = fb.positions(chain.theta2, table.assembly)
    k3, k4, _, k4d = fb.rates(poses)
    rocker_rate, rocker_acc = kinematics.output_rates(k4, k4d, chain)
    arm = arms.lever(_cam_of(cam.design).follower, fb.crank)
    try:
        design = linkgen_api.design(lspec, parts=lspec.parts is not None)
    except SpecError as exc:
        raise exc.under(f"linkages[{mount_index}].template") from None
    load = chain_inertia.coupled_input_torque(design, chain.theta2, chain.d1, chain.d2,
                                              spec.machine.rpm * math.pi / 30.0, coupling.output_torque, k4)
    force, torque = chain_inertia.carried(load, coupling.output_torque, k4, arm, chain)
    return LinkageMotion(
        coupling.linkage, coupling.cam, coupling, design, fb, chain, poses.theta3, poses.theta4, poses.gamma, k3, k4,
        rocker_rate, rocker_acc, poses.point,
        kinematics.point_rate(fb.crank, fb.point_distance, fb.point_angle, poses.theta3, k3, chain), force, torque,
        load.dynamic)


def _check_reach(fb: FourBar, theta2: np.ndarray, index: int, coupling: Coupling) -> None:
    """Refuse a follower that swings the crank out of the four-bar's reach (past a toggle), naming both."""
    ranges = fb.input_ranges()
    if ranges is None:
        return
    lo, hi = float(theta2.min()), float(theta2.max())
    for a, b in ranges:
        shift = math.floor((lo - a) / kinematics.TWO_PI) * kinematics.TWO_PI     # the range's copy at or below lo
        for base in (a + shift, a + shift + kinematics.TWO_PI):
            if base <= lo and hi <= base - a + b:
                return
    reach = " or ".join(f"[{math.degrees(a):.4g}, {math.degrees(b):.4g}]" for a, b in ranges)
    raise SpecError(f"cams.{coupling.cam}'s follower swings the crank of linkages.{coupling.linkage} through "
                    f"[{math.degrees(lo):.4g}, {math.degrees(hi):.4g}] degrees (rest {coupling.rest:g} + its swing), "
                    f"past a toggle: this four-bar's crank reaches {reach} degrees; change couplings[{index}].rest, "
                    "the cam's lift or the linkage", f"couplings[{index}]")


def _loaded(spec: MachineSpec, cam: CamMotion, linkage: LinkageMotion) -> CamMotion:
    """``cam`` designed again with the linkage's output torque (and, with ``[dynamics]``, its inverse dynamics at
    the cam's speed) reflected onto its follower as a load table (cam angle in degrees, N pressing onto the cam),
    sampled at :data:`LOAD_ROWS` program angles."""
    index = next(i for i, m in enumerate(spec.cams) if m.name == cam.name)
    theta = np.arange(LOAD_ROWS) * (kinematics.TWO_PI / LOAD_ROWS)
    swing = _cam_of(cam.design).program.evaluate(theta)[:3]
    chain = kinematics.crank_chain(linkage.coupling.rest, swing, 1.0)
    poses = linkage.fourbar.positions(chain.theta2, spec.linkage_specs[
        next(i for i, m in enumerate(spec.linkages) if m.name == linkage.name)].linkage.assembly)
    k4 = linkage.fourbar.rates(poses)[1]
    arm = arms.lever(_cam_of(cam.design).follower, linkage.fourbar.crank)
    load = chain_inertia.coupled_input_torque(linkage.design, chain.theta2, chain.d1, chain.d2,
                                              cam.design.spec.cam.rpm * math.pi / 30.0,
                                              linkage.coupling.output_torque, k4)
    force = chain_inertia.carried(load, linkage.coupling.output_torque, k4, arm, chain)[0]
    return _redesigned(spec, index, cam, theta, force)


def _ratchet(spec: MachineSpec, index: int, cam: CamMotion) -> RatchetMotion:
    """The ratchet of ``spec.ratchets[index]`` indexed by ``cam``'s follower's arm over the machine's turn."""
    kin = _cam_of(cam.design)
    f = kin.follower
    return ratchet_motion(index, spec.ratchets[index], kin.program, float(f.arm_length), cam.turns, cam.phase_deg,
                          kinematics.shaft_angles(spec.machine.samples), int(getattr(f, "_swing_sign", 1.0)))


def _loaded_ratchet(spec: MachineSpec, cam: CamMotion, ratchet: RatchetMotion) -> CamMotion:
    """``cam`` designed again with its ratchet's ``load_torque`` on its follower's roller (N pressing it onto the
    cam while the arm's pawl drives) as a load table at :data:`LOAD_ROWS` program angles."""
    index = next(i for i, m in enumerate(spec.cams) if m.name == cam.name)
    theta = np.arange(LOAD_ROWS) * (kinematics.TWO_PI / LOAD_ROWS)
    return _redesigned(spec, index, cam, theta, program_load(ratchet, _cam_of(cam.design).program, theta))


def _slider_motion(spec: MachineSpec, index: int, mount_index: int,
                   cam: CamMotion) -> slider_coupling.SliderMotion:
    """The general linkage of ``spec.linkages[mount_index]`` driven by ``cam``'s follower through coupling
    ``index``: a translating one's stem as its slider (:func:`camgen.kinds.machine.slider_coupling.slider_motion`),
    an arm as its crank (:func:`~camgen.kinds.machine.slider_coupling.arm_motion`)."""
    lspec = spec.linkage_specs[mount_index]
    try:
        made = linkgen_api.design(lspec, parts=lspec.parts is not None)
    except SpecError as exc:
        raise exc.under(f"linkages[{mount_index}].template") from None
    kin = _cam_of(cam.design)
    motion = slider_coupling.slider_motion if kin.follower.lift_unit == "mm" else slider_coupling.arm_motion
    return motion(spec, index, mount_index, cam, kin, made, kinematics.shaft_angles(spec.machine.samples))


def _loaded_stem(spec: MachineSpec, cam: CamMotion, driven: slider_coupling.SliderMotion) -> CamMotion:
    """``cam`` designed again with the output torque of the linkage its follower drives (and, with ``[dynamics]``,
    the linkage's inverse dynamics at the cam's speed) reflected onto its follower (N pressing it onto the cam) as a
    load table against cam angle, at :data:`LOAD_ROWS` program angles
    (:func:`camgen.kinds.machine.general_inertia.program_load`)."""
    index = next(i for i, m in enumerate(spec.cams) if m.name == cam.name)
    theta = np.arange(LOAD_ROWS) * (kinematics.TWO_PI / LOAD_ROWS)
    force = general_inertia.program_load(driven, theta, cam.design.spec.cam.rpm * math.pi / 30.0)
    return _redesigned(spec, index, cam, theta, force)


def _redesigned(spec: MachineSpec, index: int, cam: CamMotion, theta: np.ndarray, force: np.ndarray) -> CamMotion:
    """``cam`` (``spec.cams[index]``) designed again with the load table ``force`` (N) at program angles
    ``theta`` (radians)."""
    rows = [[round(float(a), 9), round(float(f), 9)] for a, f in zip(np.degrees(theta), force, strict=True)]
    cam_spec = spec.cam_specs[index].with_changes({"follower.load_table": rows})
    try:
        design = spec_kind(cam_spec).design(cam_spec)
    except SpecError as exc:
        raise exc.under(f"cams[{index}].template") from None
    return replace(cam, design=design)
