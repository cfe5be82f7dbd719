"""The moving links' mass properties over the motion: each link's centre of mass and its rates, and the linkage's
generalised inertia J(q) per unit input speed with its derivative (pure numpy).

A link's mass properties (:class:`LinkMass`) are its mass m (kg), its centre of mass G (mm, in the drawing's
frame: the link as drawn) and its moment of inertia I_G (kg*mm^2, about an axis through G normal to the plane).
Over the poses of a :class:`~linkgen.kinematics.linkage.Solution` (solved at unit input speed), G moves with its
link: :func:`centre_motion` gives its position, its velocity per unit input speed (mm per rad of a crank, mm per
mm of a slide) and its acceleration at constant unit input speed (the second derivative along the motion: mm/rad^2
or 1/mm), with the link's angular velocity and acceleration per unit input speed.

The generalised inertia (:func:`generalised_inertia`) is the inertia the input sees: the linkage's kinetic energy is
1/2 J(q) qdot^2 with

    J(q) = sum over the moving links of m |v_G|^2 + I_G omega^2       (v_G, omega per unit input speed)
    dJ/dq = 2 sum of m v_G . a_G + I_G omega alpha                    (a_G, alpha the second derivatives along q)

in SI: kg*m^2 (per rad^2) and kg*m^2 per rad for a crank, kg and kg/m for a slide. The equation of motion of a
one-input linkage driven by an effort Q(q, qdot) against loads needing Q_load(q) at rest is then
``J qddot + 1/2 J' qdot^2 = Q - Q_load`` (forward dynamics).
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from linkgen.kinematics.dyads import perp
from linkgen.kinematics.linkage import Solution
from linkgen.kinematics.structure import GROUND, Structure

#: mm in a metre
MM = 1e-3


@dataclass(frozen=True)
class LinkMass:
    """One link's mass properties: ``mass`` (kg), ``centre`` (x, y; mm, in the drawing's frame), ``inertia`` (kg*mm^2,
    about the centre, normal to the plane).

    Parameters
    ----------
    mass : float
        The link's mass (kg), >= 0.
    centre : tuple of float
        Its centre of mass where the drawing shows the link (mm).
    inertia : float
        Its moment of inertia about its centre (kg*mm^2), >= 0.
    """

    mass: float
    centre: tuple[float, float]
    inertia: float

    def moved(self, origin: tuple[float, float], angle: float) -> LinkMass:
        """The same mass with its centre given in a frame turned by ``angle`` (rad, counter-clockwise) and moved to
        ``origin`` (mm): the centre in the outer frame."""
        c, s = math.cos(angle), math.sin(angle)
        x, y = self.centre
        return LinkMass(self.mass, (origin[0] + c * x - s * y, origin[1] + s * x + c * y), self.inertia)


def combined(parts: list[LinkMass]) -> LinkMass:
    """The mass properties of rigidly joined ``parts`` (a link, its pins and spacers): masses add, the centre is
    their mass-weighted mean, and the inertias add about it (parallel axes). All massless: the first's centre."""
    total = sum(p.mass for p in parts)
    if total <= 0:
        return LinkMass(0.0, parts[0].centre if parts else (0.0, 0.0), 0.0)
    cx = sum(p.mass * p.centre[0] for p in parts) / total
    cy = sum(p.mass * p.centre[1] for p in parts) / total
    inertia = sum(p.inertia + p.mass * ((p.centre[0] - cx) ** 2 + (p.centre[1] - cy) ** 2) for p in parts)
    return LinkMass(total, (cx, cy), inertia)


def link_frame(structure: Structure, body: str) -> tuple[tuple[float, float], float]:
    """A link's own frame in the drawing: its origin at the link's first joint (mm) and its x axis (rad,
    counter-clockwise from +X) towards its second; a slider's block (one joint) along its guide. The frame its part
    is drawn in (:mod:`linkgen.parts`), where a user gives its centre of mass."""
    pts = structure.bodies[body]
    x0, y0 = structure.points[pts[0]]
    if len(pts) >= 2:
        x1, y1 = structure.points[pts[1]]
        return (float(x0), float(y0)), math.atan2(y1 - y0, x1 - x0)
    slider = next((sl for sl in structure.sliders if sl.body == body), None)
    return (float(x0), float(y0)), 0.0 if slider is None else slider.angle


@dataclass(frozen=True)
class CentreMotion:
    """A link's centre of mass over the poses (mm; per unit input speed, see the module's note), and the link's
    angular velocity and acceleration per unit input speed."""

    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray


def centre_motion(structure: Structure, sol: Solution, body: str, centre: tuple[float, float]) -> CentreMotion:
    """Where the drawn point ``centre`` (mm) of link ``body`` is at each pose of ``sol`` and how it moves: the
    rigid body's field from its first joint, v = v_P + omega k x r and a = a_P + alpha k x r - omega^2 r."""
    first = structure.bodies[body][0]
    x0, y0 = structure.points[first]
    d = np.array([centre[0] - x0, centre[1] - y0])
    c, s = sol.rotations[body]
    r = np.stack([c * d[0] - s * d[1], s * d[0] + c * d[1]], axis=-1)
    w, al = sol.omegas[body], sol.alphas[body]
    turned = perp(r)
    return CentreMotion(sol.points[first] + r, sol.velocities[first] + w[:, None] * turned,
                        sol.accelerations[first] + al[:, None] * turned - (w**2)[:, None] * r, w, al)


def moving_links(structure: Structure) -> tuple[str, ...]:
    """The bodies that move: every one but the ground, in the structure's order."""
    return tuple(b for b in structure.bodies if b != GROUND)


def input_scale(structure: Structure) -> float:
    """The input's unit in SI: 1 for a crank (rad), 1e-3 for a slide (a mm of travel in m)."""
    return 1.0 if structure.inputs[0].kind == "crank" else MM


def generalised_inertia(structure: Structure, sol: Solution,
                        masses: Mapping[str, LinkMass]) -> tuple[np.ndarray, np.ndarray]:
    """J(q) and dJ/dq over the poses of ``sol`` (solved at unit input speed, with derivatives), in SI: kg*m^2 and
    kg*m^2/rad for a crank, kg and kg/m for a slide (see the module's note). Links missing from ``masses`` are
    massless.

    Parameters
    ----------
    structure : Structure
        The linkage's structure (one input).
    sol : Solution
        Its poses, solved with derivatives at unit input speed.
    masses : mapping of str to LinkMass
        Each moving link's mass properties (centre in the drawing's frame).

    Returns
    -------
    tuple of ndarray
        J (n,) and dJ/dq (n,).
    """
    f = input_scale(structure)
    n = sol.inputs.shape[-1]
    j, dj = np.zeros(n), np.zeros(n)
    for body, m in masses.items():
        if body == GROUND or (m.mass == 0 and m.inertia == 0):
            continue
        g = centre_motion(structure, sol, body, m.centre)
        v = g.velocity * (MM / f)
        a = g.acceleration * (MM / f**2)
        w, al = g.omega / f, g.alpha / f**2
        inertia = m.inertia * MM**2
        j += m.mass * np.einsum("ij,ij->i", v, v) + inertia * w**2
        dj += 2.0 * (m.mass * np.einsum("ij,ij->i", v, a) + inertia * w * al)
    return j, dj
