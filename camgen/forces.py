"""What the cam and its shaft carry at speed: the contact force over the cycle, the camshaft torque and power, and
the Hertz contact pressure (translating followers with a :class:`~camgen.dynamics.Loading`).

Signs: the axial force F (N) presses the follower onto the cam (see :class:`~camgen.dynamics.Loading`); the normal
contact force is F / cos(phi), phi the pressure angle; the shaft torque T = F s' / 1000 (N*m, s' in mm/rad) is
what the shaft supplies in the cam's direction of turning (power balance: T omega = F v), negative where the
follower drives the cam. The contact pressure is Hertz's for a line contact (:mod:`camgen.contact_stress`) between
the roller (or flat face) and the cam's profile, whose curvature is the pitch curve's moved in by the roller's
radius: kappa_p = kappa / (1 - Rr kappa).
"""
from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from camgen.cam import Cam
from camgen.contact_stress import MATERIALS, effective_modulus, line_contact, relative_curvature
from camgen.dynamics import Loading, Peak, spec_loading, stacked_peaks
from camgen.numeric import boundary
from camgen.speed import Drive, Extreme, Forces, KnifeEdge, SideChange, SpeedRow, SpeedTable, Stress

#: Gauss-Legendre nodes a segment for the means over the cycle (each law is smooth inside its segment)
NODES = 64


@dataclass(frozen=True)
class Contact:
    """The materials in contact (names of :data:`~camgen.contact_stress.MATERIALS`) and the contact length (mm)."""

    cam: str
    follower: str
    length: float

    @property
    def e_star(self) -> float:
        return effective_modulus(MATERIALS[self.cam], MATERIALS[self.follower])

    @property
    def allowable(self) -> float:
        """The lower of the two materials' allowable contact pressures (MPa)."""
        return min(MATERIALS[self.cam].allowable, MATERIALS[self.follower].allowable)


def materials_of(stress: Stress | None) -> Contact | None:
    """The materials in contact and the contact's length a ``stress`` was found for (None without one)."""
    return None if stress is None else Contact(stress.cam_material, stress.follower_material, stress.length)


def cycle_mean(cam: Cam, quantity: Any, breaks: tuple[float, ...] = ()) -> float:
    """The mean over a turn of ``quantity(theta, motion rows)``, segment by segment by Gauss-Legendre quadrature (exact
    to rounding for the laws' smooth pieces; a jump at a segment's end costs nothing), a segment split at the cam
    angles ``breaks`` (radians: a load table's rows, where the load has a kink) inside it."""
    return _mean(_nodes(cam, breaks), quantity)


@dataclass(frozen=True)
class Nodes:
    """Gauss-Legendre nodes over a turn, every stretch's at once: ``halves`` each stretch's half-width (rad, (k,)),
    ``theta`` the cam angles (rad, (k * NODES,), stretch by stretch) and ``motion`` the motion rows there (s and
    its three derivatives, (4, k * NODES)). A stretch is a segment, or the part of one between a load table's
    rows."""

    halves: np.ndarray
    theta: np.ndarray
    motion: np.ndarray


def _nodes(cam: Cam, breaks: tuple[float, ...] = ()) -> Nodes:
    """The nodes of :func:`cycle_mean` (the motion evaluated once for any number of quantities, a segment's
    stretches in one evaluation: the work grows with the stretches' count, not its square)."""
    x, _ = np.polynomial.legendre.leggauss(NODES)
    cuts_all = np.sort(np.asarray(breaks, dtype=float))
    halves, thetas, motions = [], [], []
    for seg in cam.program.segments:
        inside = cuts_all[(cuts_all > seg.start) & (cuts_all < seg.end)]
        cuts = np.concatenate([[seg.start], inside, [seg.end]])
        lo, hi = cuts[:-1], cuts[1:]
        half = (hi - lo) / 2
        theta = (lo[:, None] + half[:, None] * (x + 1)[None, :]).ravel()
        halves.append(half)
        thetas.append(theta)
        motions.append(seg.evaluate(theta))
    return Nodes(np.concatenate(halves), np.concatenate(thetas), np.concatenate(motions, axis=1))


def _mean(nodes: Nodes, quantity: Any) -> float:
    """The mean over the turn of ``quantity(theta, motion rows)`` on the ``nodes`` (:func:`_nodes`): the quantity
    evaluated once on them all, summed stretch by stretch."""
    _, w = np.polynomial.legendre.leggauss(NODES)
    values = np.broadcast_to(quantity(nodes.theta, nodes.motion), nodes.theta.shape)
    total = 0.0
    for half, row in zip(nodes.halves.tolist(), values.reshape(len(nodes.halves), NODES), strict=True):
        total += half * float(w @ row)
    return total / (2 * math.pi)


def _load_nodes(cam: Cam, ld: Loading) -> Nodes:
    """The nodes of the means of a loading ``ld``: its load table's rows (kinks of the load) split the segments."""
    return _nodes(cam, ld.table.angles if ld.table else ())


def _peaks_over(cam: Cam, *quantities: Any) -> list[Peak]:
    """Largest value over the cycle of each ``quantity(pitch geometry, motion rows)``, all from one search (the
    motion and the pitch geometry evaluated once for them all: :func:`camgen.dynamics.stacked_peaks`)."""
    def values(theta: np.ndarray, m: np.ndarray) -> np.ndarray:
        g = cam.follower.pitch(theta, m)
        return np.stack([np.broadcast_to(q(g, m), theta.shape) for q in quantities])

    return stacked_peaks(cam, values)


def _peaks_each(cam: Cam, *quantities: Any) -> list[Peak]:
    """:func:`_peaks_over`, one search a quantity: the figures at ``cam.rpm`` are found so, to the bit as they
    always were (a stacked search solves its refinement quartics in one matrix product, whose rounding follows how
    many rows it has: a peak's last bits would move with the quantities searched beside it, ~1e-14)."""
    return [peak for q in quantities for peak in _peaks_over(cam, q)]


def profile_curvature(cam: Cam, geometry: Any) -> np.ndarray:
    """The cam profile's signed curvature at the contact (1/mm, convex positive)."""
    if geometry.rho is not None:                         # a flat face: the profile's own radius
        with np.errstate(divide="ignore"):
            return np.where(geometry.rho != 0, 1.0 / geometry.rho, np.inf)
    rr = cam.contact_radius
    return geometry.kappa / (1.0 - rr * geometry.kappa)


def contact_pressure(cam: Cam, contact: Contact, geometry: Any, normal_force: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """The largest Hertz pressure (MPa) and the strip's half-width (mm) at each sample."""
    rr = cam.contact_radius
    curvature = relative_curvature(profile_curvature(cam, geometry), 1.0 / rr if rr > 0 else 0.0)
    return line_contact(normal_force, curvature, contact.length, contact.e_star)


def normal_force(ld: Loading, omega: float, geometry: Any, m: np.ndarray) -> np.ndarray:
    """The contact force along the normal (N): the axial force over cos(pressure angle)."""
    return ld.force(m, omega, geometry.theta) / np.cos(geometry.pressure_angle)


def torque(ld: Loading, omega: float, m: np.ndarray, theta: np.ndarray | None = None) -> np.ndarray:
    """The torque (N*m) the shaft supplies: F s' / 1000 (s' the contact's path, mm per radian of cam angle; the cam
    angles ``theta`` in radians for a load table)."""
    return ld.force(m, omega, theta) * ld.scale * m[1] / 1000.0


def _torques(ld: Loading, omega: float, push: Any) -> tuple[Any, ...]:
    """The quantities (of pitch geometry and motion) whose peaks :func:`_torque_figures` takes: the torque, its
    negative and ``push(geometry, motion)``, the normal contact force (N)."""
    return (lambda g, m: torque(ld, omega, m, g.theta), lambda g, m: -torque(ld, omega, m, g.theta), push)


def _torque_figures(ld: Loading, omega: float, peaks: list[Peak], nodes: Nodes) -> Forces:
    """The torque's extremes and RMS, the peak power and the largest normal contact force (N), from the ``peaks`` of
    :func:`_torques`'s quantities and the loading's ``nodes`` (:func:`_load_nodes`) for the RMS."""
    hi, lo, most = peaks
    return Forces(hi.value, hi.at_deg, -lo.value, lo.at_deg,
                  math.sqrt(_mean(nodes, lambda t, m: torque(ld, omega, m, t) ** 2)), max(hi.value, lo.value) * omega,
                  most.value, most.at_deg)


def _omega(rpm: float) -> float:
    """The cam's speed (rad/s) at ``rpm``."""
    return rpm * 2 * math.pi / 60


def forces_report(cam: Cam, ld: Loading, rpm: float, contact: Contact | None) -> Forces:
    """The report's ``forces``: the torque's extremes and RMS, the peak power, the largest normal contact force
    and, with materials, the largest contact pressure and where."""
    omega = _omega(rpm)
    quantities = _torques(ld, omega, lambda g, m: normal_force(ld, omega, g, m))
    knife = cam.contact_radius == 0 and not cam.follower.flat

    hertz = None if contact is None or knife else contact

    def pressure(g: Any, m: np.ndarray, hertz: Contact) -> tuple[np.ndarray, np.ndarray]:
        return contact_pressure(cam, hertz, g, normal_force(ld, omega, g, m))

    peaks = _peaks_each(cam, *quantities, *(() if hertz is None else (lambda g, m: pressure(g, m, hertz)[0],)))
    out = _torque_figures(ld, omega, peaks[:3], _load_nodes(cam, ld))
    if contact is not None and knife:
        return replace(out, stress=KnifeEdge())
    if hertz is not None:
        return replace(out, stress=_stress(cam, hertz, lambda g, m: pressure(g, m, hertz), peaks[3])[0])
    return out


def _stress(cam: Cam, contact: Contact, pressure: Any, peak: Peak) -> tuple[Stress, Any, np.ndarray]:
    """The report's ``stress`` of ``pressure(geometry, motion)`` -> (pressure MPa, half-width mm) whose ``peak`` over
    the turn is given: where, the strip's half-width there, the materials and the allowable; and the geometry and
    motion there."""
    at = np.array([math.radians(peak.at_deg)])
    g, m = cam.pitch(at), cam.program.evaluate(at)
    return (Stress(contact.cam, contact.follower, contact.length, contact.e_star, peak.value, peak.at_deg,
                   float(pressure(g, m)[1][0]), contact.allowable, peak.value <= contact.allowable), g, m)


def flank_pressure(contact: Contact, geometry: Any, force: np.ndarray, offset: float, roller: float
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Hertz pressure (MPa) and half-width (mm) where a roller of radius ``roller`` (mm) runs between two walls
    ``offset`` mm either side of the pitch curve (a groove): the pitch curve's curvature kappa (1/mm) is convex
    towards the wall that carries a force ``force`` > 0 (N, normal), that wall's curvature kappa / (1 - offset kappa)
    (the disc cam's profile), the other's -kappa / (1 + offset kappa) (concave round the roller) carries |force|
    where it is negative."""
    k = geometry.kappa
    wall = np.where(force > 0, k / (1.0 - offset * k), -k / (1.0 + offset * k))
    return line_contact(np.abs(force), relative_curvature(wall, 1.0 / roller), contact.length, contact.e_star)


def _row_quantities(cam: Cam, ld: Loading, rpm: float, contact: Contact | None, positive: bool,
                    walls: tuple[float, float] | None) -> tuple[Any, ...]:
    """The quantities whose peaks make a row of the ``speeds`` table at ``rpm`` (see :func:`_row`)."""
    omega = _omega(rpm)
    push = (lambda g, m: np.abs(normal_force(ld, omega, g, m))) if positive else \
        (lambda g, m: normal_force(ld, omega, g, m))
    out = _torques(ld, omega, push)
    if not positive:
        out += (lambda g, m: -ld.force(m, omega, g.theta),)
    if contact is not None:
        out += ((lambda g, m: contact_pressure(cam, contact, g, push(g, m))[0]) if walls is None else
                (lambda g, m: flank_pressure(contact, g, normal_force(ld, omega, g, m), *walls)[0]),)
    return out


def _row(ld: Loading, rpm: float, peaks: list[Peak], nodes: Nodes, contact: Contact | None,
         positive: bool) -> SpeedRow:
    """One row of the ``speeds`` table at ``rpm`` from the ``peaks`` of :func:`_row_quantities`'s quantities: the
    torque's extremes and RMS, the peak power, the largest normal contact force, and for a follower held on (not
    ``positive``) the least axial contact force, where, and whether it stays above ``ld.margin``; with materials
    the largest Hertz pressure (MPa)."""
    row = _speed_row(rpm, _torque_figures(ld, _omega(rpm), peaks[:3], nodes))
    rest = peaks[3:]
    if not positive:
        low, *rest = rest
        row = replace(row, contact_force_min=-low.value, contact_force_min_at_deg=low.at_deg,
                      holds=-low.value > ld.margin)
    return row if contact is None else replace(row, pressure_max=rest[0].value)


def _speed_row(rpm: float, figures: Forces) -> SpeedRow:
    """The row of the ``speeds`` table at ``rpm`` of the torque ``figures`` there (no least force nor pressure)."""
    return SpeedRow(rpm, figures.torque_max, figures.torque_min, figures.torque_rms, figures.power_max,
                    figures.contact_force_max)


def speed_list(rpm_range: tuple[float, float], steps: int, liftoff: float | None) -> list[float]:
    """The speeds (rpm) of the ``speeds`` table: ``steps`` evenly spaced over ``rpm_range`` (both ends), and the
    lift-off speed among them where it lies inside the range."""
    lo, hi = rpm_range
    speeds = [float(v) for v in np.linspace(lo, hi, steps)]
    if liftoff is not None and lo < liftoff < hi and all(abs(v - liftoff) > 1e-12 * hi for v in speeds):
        speeds = sorted([*speeds, liftoff])
    return speeds


def _split(peaks: list[Peak], sizes: list[int]) -> list[list[Peak]]:
    """``peaks`` cut into consecutive runs of ``sizes``."""
    ends = list(itertools.accumulate(sizes))
    return [peaks[end - size:end] for size, end in zip(sizes, ends, strict=True)]


def speeds_report(cam: Cam, ld: Loading, rpm_range: tuple[float, float], steps: int, contact: Contact | None,
                  liftoff: float | None = None, positive: bool = False,
                  walls: tuple[float, float] | None = None) -> SpeedTable:
    """The report's ``speeds``: at each of :func:`speed_list`'s speeds, the torque's extremes and RMS, the peak
    power, the largest normal contact force, and for a follower held on (not ``positive``) the least axial contact
    force, where, and whether it stays above ``ld.margin``; with materials the largest Hertz pressure (MPa), for a
    roller in a groove on the wall carrying the force (``walls``: their offset from the pitch curve and the roller's
    radius, mm; :func:`flank_pressure`). Also the lift-off speed (``liftoff``, rpm; None: held at any speed) and
    the limits the figure draws (the contact margin, N, and with materials the allowable pressure, MPa). Every
    inertia term scales with rpm^2: at each cam angle the torque is T_static + (rpm / rpm0)^2 T_inertia, the contact
    force likewise. A ``positive`` drive (a groove) has no lift-off nor margin. Every row's peaks come from one
    search over the turn, and their means from one evaluation of the motion."""
    speeds = speed_list(rpm_range, steps, liftoff)
    wanted = [_row_quantities(cam, ld, rpm, contact, positive, walls) for rpm in speeds]
    found = _split(_peaks_over(cam, *itertools.chain(*wanted)), [len(q) for q in wanted])
    nodes = _load_nodes(cam, ld)
    return SpeedTable(rpm_range, liftoff, tuple(_row(ld, rpm, peaks, nodes, contact, positive)
                                                for rpm, peaks in zip(speeds, found, strict=True)),
                      None if positive else ld.margin, None if contact is None else contact.allowable)


def flank_changes(cam: Cam, force: Any, sides: tuple[str, str]) -> list[SideChange]:
    """Where the force ``force(theta, motion)`` (N) changes sign over the turn and which side carries it from there
    (``sides[0]`` while it is positive, ``sides[1]`` while negative): each segment sampled every half degree, a
    change inside one found by bisection (:func:`camgen.numeric.boundary`) to ~1e-12 rad, the last angle where the
    force keeps its sign before it, one across a segment's end placed there. Stretches where
    the force is 0 (a dwell with nothing on the follower: no side carries anything) keep the side before them."""
    changes: list[SideChange] = []
    last, first = 0.0, None
    for seg in cam.program.segments:
        t = np.linspace(seg.start, seg.end, max(3, int(math.degrees(seg.end - seg.start) * 2) + 1))
        v = force(t, seg.evaluate(t))
        scale = max(float(np.max(np.abs(v))), 1e-300)
        for k, value in enumerate(v):
            if abs(value) <= 1e-12 * scale or value * last > 0:
                continue
            at = float(t[k])
            if last and k > 0:                              # a sign change inside the segment: bisect
                lo, hi = float(t[k - 1]), at

                def same(x: float, seg: Any = seg, sign: float = last) -> bool:
                    return float(force(np.array([x]), seg.evaluate(np.array([x])))[0]) * sign > 0

                at = boundary(same, lo, hi, 1e-12 / max(abs(lo), abs(hi)))
            if last:
                changes.append(SideChange(math.degrees(at) % 360.0, sides[0 if value > 0 else 1]))
            else:
                first = (math.degrees(at) % 360.0, sides[0 if value > 0 else 1])
            last = float(np.sign(value))
    if first is not None and sides[0 if last > 0 else 1] != first[1]:   # the turn wraps to the other side
        changes.insert(0, SideChange(*first))
    return changes


def drive_report(cam: Cam, ld: Loading, rpm: float, sides: tuple[str, str],
                 walls: tuple[Contact, float, float] | None = None) -> Forces:
    """The ``forces`` of a positive drive (a groove or a conjugate pair: no spring, contact both ways): the force F
    on the follower along its path (:class:`~camgen.dynamics.Loading`, its inertia, loads and weights) is carried by
    ``sides[0]`` where F > 0 (it presses the follower against its rise) and by ``sides[1]`` where F < 0; the torque
    T = F s' / 1000 either way (the power balance), the largest normal contact force |F| / cos(phi), and where the
    contact changes side. With ``walls`` (the :class:`Contact`, the walls' offset from the pitch curve and the
    roller's radius, mm) the ``stress``: :func:`flank_pressure`'s peak and the side carrying it there."""
    return _drive(cam, ld, rpm, sides, walls)[0]


def _drive(cam: Cam, ld: Loading, rpm: float, sides: tuple[str, str], walls: tuple[Contact, float, float] | None,
           extra: tuple[Any, ...] = ()) -> tuple[Forces, list[Peak]]:
    """:func:`drive_report`, and the peaks of the ``extra`` quantities (of pitch geometry and motion) found in the
    same search."""
    omega = _omega(rpm)
    quantities = _torques(ld, omega, lambda g, m: np.abs(normal_force(ld, omega, g, m)))
    if walls is not None:
        contact, offset, roller = walls

        def pressure(g: Any, m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            return flank_pressure(contact, g, normal_force(ld, omega, g, m), offset, roller)

        quantities += (lambda g, m: pressure(g, m)[0],)
    peaks = _peaks_each(cam, *quantities, *extra)
    out = replace(_torque_figures(ld, omega, peaks[:3], _load_nodes(cam, ld)), drive=Drive(
        *sides, tuple(flank_changes(cam, lambda t, m: ld.force(m, omega, t), sides))))
    if walls is not None:
        stress, g, m = _stress(cam, contact, pressure, peaks[3])
        out = replace(out, stress=replace(stress, on=sides[0] if float(ld.force(m, omega, g.theta)[0]) > 0
                                          else sides[1]))
    return out, peaks[len(quantities):]


def pair_forces(pair: tuple[Cam, Cam], ld: Loading, omega: float) -> tuple[Any, Any]:
    """Each cam's normal contact force (N) at ``omega`` rad/s as a function of its pitch geometry and motion rows (0
    where it runs unloaded): N1 = F / cos(phi1) where F > 0, N2 = -F (L1 / L2) / cos(phi2) where F < 0, L1 / L2
    the arms' ratio of a bell crank (1 for a yoke; see :func:`pair_report`)."""
    first, second = pair
    ratio = getattr(first.follower, "arm_length", 1.0) / getattr(second.follower, "arm_length", 1.0)

    def loaded(sign: float) -> Callable[[Any, np.ndarray], np.ndarray]:
        return lambda g, m: np.maximum(sign * normal_force(ld, omega, g, m), 0.0)

    return loaded(1.0), loaded(-ratio)


def pair_report(pair: tuple[Cam, Cam], ld: Loading, rpm: float, contact: Contact | None = None
                ) -> Forces:
    """The ``forces`` of a conjugate pair: :func:`drive_report` on the first cam (the torque T = F s' / 1000 is the
    follower's power over the cam's speed whichever cam drives), the first cam carrying F > 0 (pressing the follower
    against its rise) and the second F < 0: a rigid follower with no preload between its rollers, so one contact
    carries the force while the other runs unloaded. Each cam's largest normal force: N1 = F / cos(phi1), N2 =
    -F (L1 / L2) / cos(phi2) (phi2 the second cam's pressure angle from the return's direction, L1 / L2 the arms'
    ratio of a bell crank, 1 for a yoke); the torque is then the sum of both contacts' moments about the axis."""
    omega = _omega(rpm)
    forces = pair_forces(pair, ld, omega)
    pressures = _pair_pressures(pair, contact, forces)
    out, found = _drive(pair[0], ld, rpm, ("cam 1", "cam 2"), None, (forces[0], *pressures[:1]))
    peaks = [found, _peaks_each(pair[1], forces[1], *pressures[1:])]
    first, second = (Extreme(most.value, most.at_deg) for most, *_ in peaks)
    out = replace(out, pair=(first, second))
    if contact is not None:          # each roller on its cam, as a disc cam's (its own roller's radius)
        cams = tuple(replace(_stress(cam, contact, lambda g, m, cam=cam, force=force: contact_pressure(
            cam, contact, g, force(g, m)), peak)[0], on=f"cam {k + 1}")
            for k, (cam, force, (_, peak)) in enumerate(zip(pair, forces, peaks, strict=True)))
        out = replace(out, stress=replace(max(cams, key=lambda c: c.pressure_max), cams=cams))
    return out


def _pair_pressures(pair: tuple[Cam, Cam], contact: Contact | None, forces: tuple[Any, Any]) -> tuple[Any, ...]:
    """Each cam's Hertz pressure (MPa) under its normal force ``forces`` (quantities of pitch geometry and motion),
    as a disc cam's (its own roller's radius); none without materials."""
    if contact is None:
        return ()
    return tuple(lambda g, m, cam=cam, force=force: contact_pressure(cam, contact, g, force(g, m))[0]
                 for cam, force in zip(pair, forces, strict=True))


def pair_speeds(pair: tuple[Cam, Cam], ld: Loading, rpm_range: tuple[float, float], steps: int,
                contact: Contact | None) -> SpeedTable:
    """The ``speeds`` table of a conjugate pair: at each of :func:`speed_list`'s speeds :func:`pair_report`'s
    torque figures, the larger of both cams' normal forces and with materials both cams' larger Hertz pressure (no
    lift-off: the pair drives both ways). One search over the turn a cam for every row's peaks."""
    first, second = pair
    speeds = speed_list(rpm_range, steps, None)
    per_speed = []
    for rpm in speeds:
        omega = _omega(rpm)
        forces = pair_forces(pair, ld, omega)
        per_speed.append((forces, _pair_pressures(pair, contact, forces)))
    wanted = [(*_torques(ld, _omega(rpm), forces[0]), *pressures[:1])
              for rpm, (forces, pressures) in zip(speeds, per_speed, strict=True)]
    firsts = _split(_peaks_over(first, *itertools.chain(*wanted)), [len(q) for q in wanted])
    seconds = _split(_peaks_over(second, *itertools.chain(*((forces[1], *pressures[1:])
                                                            for forces, pressures in per_speed))),
                     [1 + (contact is not None)] * len(speeds))
    nodes = _load_nodes(first, ld)
    rows = []
    for rpm, one, two in zip(speeds, firsts, seconds, strict=True):
        row = replace(_speed_row(rpm, _torque_figures(ld, _omega(rpm), one[:3], nodes)),
                      contact_force_max=max(one[2].value, two[0].value))
        rows.append(row if contact is None else replace(row, pressure_max=max(one[3].value, two[1].value)))
    return SpeedTable(rpm_range, None, tuple(rows), None, None if contact is None else contact.allowable)


def drive_speed(spec: Any, cam: Cam, sides: tuple[str, str] = ("cam 1", "cam 2"),
                walls: tuple[Contact, float, float] | None = None, pair: tuple[Cam, Cam] | None = None,
                contact: Contact | None = None) -> tuple[Forces, SpeedTable | None]:
    """The ``forces`` and, with ``cam.rpm_range``, the ``speeds`` of a positive drive's ``spec`` (no spring: its
    ``[follower]``'s mass, loads and weights pressing the follower either way, :func:`~camgen.dynamics.spec_loading`
    of a positive drive) on its built ``cam``: a groove's or a barrel's (:func:`drive_report` with ``sides`` and
    ``walls``, :func:`speeds_report` with no lift-off), or a conjugate ``pair``'s whose first cam ``cam`` is
    (:func:`pair_report`, :func:`pair_speeds`, each roller on its cam with ``contact``); no speeds table (None)
    without a range."""
    ld = spec_loading(spec.follower, cam.follower, True, spec.motion, cam.program)
    table = spec.cam
    span = table.rpm_range
    if pair is not None:
        return (pair_report(pair, ld, table.rpm, contact),
                None if span is None else pair_speeds(pair, ld, span, table.rpm_steps, contact))
    return (drive_report(cam, ld, table.rpm, sides, walls),
            None if span is None else speeds_report(cam, ld, span, table.rpm_steps, None if walls is None else walls[0],
                                                    positive=True, walls=None if walls is None else walls[1:]))
