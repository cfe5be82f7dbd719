"""The whole machine at any main shaft angles: every part placed (the clash check's bodies,
:func:`camgen.kinds.machine.clash.machine_parts`) and its named points (rollers, pins, tracers), in the machine's
frame (mm, y up); what the page animates, the figures draw and the report's ``poses`` give.

A part's pose is a turn (degrees, counter-clockwise) and a shift (mm) of its outline in its own frame: machine point
= R(turn) local + shift. A part drawn mirrored (a four-bar on an arm that swings clockwise) has its outline mirrored
in its own x axis first (local (x, y) -> (x, -y)), then turned and shifted.

Points, by name: ``cams.<cam>.roller`` (an oscillating roller's centre) and ``cams.<cam>.pivot`` (its arm's pivot,
an oscillating flat face's too);
a coupled four-bar's ``linkages.<linkage>.A`` (its crank pin, on the arm), ``.B`` (its rocker pin), ``.O4`` (its
rocker's pivot) and ``.P`` (its coupler point, where it has one); a shaft-driven linkage's every joint,
``linkages.<linkage>.<joint>``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.kinds.machine import clash, kinematics
from camgen.kinds.machine.guides import guides

#: mirrors a part's outline in its own x axis
MIRROR = np.diag([1.0, -1.0])


@dataclass(frozen=True)
class Placed:
    """A part over some main shaft angles: its ``name``, its planes ``low`` to ``high``, its ``outline`` (m, 2) mm
    in its own frame (already mirrored where ``mirrored``), its ``turn`` (n,) degrees and ``shift`` (n, 2) mm."""

    name: str
    low: int
    high: int
    outline: np.ndarray
    mirrored: bool
    turn: np.ndarray
    shift: np.ndarray

    def at(self, k: int) -> np.ndarray:
        """The outline (m, 2) in the machine's frame at the ``k``-th angle."""
        a = math.radians(float(self.turn[k]))
        c, s = math.cos(a), math.sin(a)
        return self.outline @ np.array([[c, s], [-s, c]]) + self.shift[k]


def placed_parts(design: Any, phi: np.ndarray) -> tuple[Placed, ...]:
    """Every part of ``design`` (a :class:`~camgen.kinds.machine.design.MachineDesign`) that the clash check places,
    at main shaft angles ``phi`` (radians)."""
    phi = np.asarray(phi, dtype=float)
    out = []
    for body in clash.machine_parts(design)[0]:
        m, t = body.place(phi)
        m = np.asarray(m, dtype=float)
        mirrored = bool(np.linalg.det(m[0]) < 0)
        outline = body.outline
        if mirrored:                               # M = R D: the outline mirrored by D, then turned by R = M D
            m, outline = m @ MIRROR, outline @ MIRROR
        turn = np.degrees(np.arctan2(m[:, 1, 0], m[:, 0, 0]))
        out.append(Placed(body.name, body.low, body.high, np.asarray(outline, dtype=float), mirrored, turn,
                          np.array(np.broadcast_to(t, (len(phi), 2)), dtype=float)))
    return tuple(out)


def points(design: Any, phi: np.ndarray) -> dict[str, np.ndarray]:
    """Every named point (see the module docstring) of ``design`` at main shaft angles ``phi`` (radians): (n, 2) mm
    in the machine's frame."""
    from camgen.followers.oscillating_flat import OscillatingFlat
    from camgen.followers.oscillating_roller import OscillatingRoller
    from camgen.kinds.machine.design import _cam_of

    phi = np.asarray(phi, dtype=float)
    spec = design.spec
    at = {s.name: np.asarray(s.at, dtype=float) for s in spec.shafts}
    out: dict[str, np.ndarray] = {}
    for cam, mount in zip(design.cams, spec.cams, strict=True):
        f = _cam_of(cam.design).follower
        if isinstance(f, OscillatingFlat):                  # a flat face's arm: its pivot
            out[f"cams.{cam.name}.pivot"] = np.tile(at[mount.shaft] + f.pivot, (len(phi), 1))
        if not isinstance(f, OscillatingRoller):
            continue
        pivot = at[mount.shaft] + f.pivot
        psi = np.radians(swing(cam, phi)[0])
        rest = np.array([0.0, f.prime_radius]) - f.pivot
        c, s = np.cos(f._swing_sign * psi), np.sin(f._swing_sign * psi)
        out[f"cams.{cam.name}.pivot"] = np.tile(pivot, (len(phi), 1))
        out[f"cams.{cam.name}.roller"] = pivot + np.column_stack([c * rest[0] - s * rest[1], s * rest[0] + c * rest[1]])
    for m in design.linkages:
        cam = design.cam(m.cam)
        mount = next(c for c in spec.cams if c.name == m.cam)
        f = _cam_of(cam.design).follower
        pivot, frame = at[mount.shaft] + f.pivot, clash.arm_frame(f, m.coupling.rest)
        fb = m.fourbar
        theta2, p = fourbar_at(design, m, phi)
        a = fb.crank * np.column_stack([np.cos(theta2), np.sin(theta2)])
        o4 = np.array([fb.ground, 0.0])
        b = o4 + fb.rocker * np.column_stack([np.cos(p.theta4), np.sin(p.theta4)])
        local = {"A": a, "B": b, "O4": np.tile(o4, (len(phi), 1))}
        if fb.point_distance > 0:
            u = p.theta3 + fb.point_angle
            local["P"] = a + fb.point_distance * np.column_stack([np.cos(u), np.sin(u)])
        out.update({f"linkages.{m.name}.{k}": pivot + v @ frame.T for k, v in local.items()})
    for m in (*design.cranked, *design.slid):
        sol = m.solve(phi)
        out.update({f"linkages.{m.name}.{k}": np.asarray(v, dtype=float) + m.offset for k, v in sol.points.items()})
    return out


def fourbar_at(design: Any, m: Any, phi: np.ndarray) -> tuple[np.ndarray, Any]:
    """A coupled four-bar ``m`` (:class:`~camgen.kinds.machine.design.LinkageMotion`) at main shaft angles ``phi``:
    its crank angle theta2 (radians, rest + its follower's swing) and its positions there
    (:meth:`linkgen.kinematics.fourbar.FourBar.positions`, its template's assembly)."""
    cam = design.cam(m.cam)
    theta2 = kinematics.crank_chain(m.coupling.rest, swing(cam, phi), cam.turns).theta2
    return theta2, m.fourbar.positions(theta2, m.design.spec.linkage.assembly)


def swing(cam: Any, phi: np.ndarray) -> np.ndarray:
    """A cam's follower (s, s', s'') at main shaft angles ``phi``: its program at its program angles."""
    from camgen.kinds.machine.design import _cam_of

    return _cam_of(cam.design).program.evaluate(cam.program_angles(phi))[:3]


def poses_report(design: Any) -> list[dict[str, Any]]:
    """The report's ``poses``: at each of ``machine.figure_angles``, every part's pose (its turn in degrees, its
    shift in mm, whether it is mirrored), every named point (mm) and every slider's guide (its two ends, mm, which
    stand still: :func:`camgen.kinds.machine.guides.guides`), to 1e-9."""
    angles = design.spec.machine.figure_angles
    phi = np.radians(np.asarray(angles, dtype=float))
    parts = placed_parts(design, phi)
    named = points(design, phi)
    fixed = {g.name: [[_num(v) for v in end] for end in g.ends] for g in guides(design)}
    return [{"angle_deg": a,
             "parts": {p.name: {"turn_deg": _num(p.turn[k]), "at_mm": [_num(v) for v in p.shift[k]],
                                "mirrored": p.mirrored} for p in parts},
             "points": {n: [_num(v) for v in xy[k]] for n, xy in named.items()},
             "guides": fixed}
            for k, a in enumerate(angles)]


def _num(value: float) -> float:
    """``value`` to 1e-9 for the report (-0 written as 0)."""
    return round(float(value), 9) + 0.0
