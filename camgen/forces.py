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

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.cam import Cam
from camgen.contact_stress import MATERIALS, effective_modulus, line_contact, relative_curvature
from camgen.dynamics import Loading, Peak, peak_at

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


def cycle_mean(cam: Cam, quantity: Any, breaks: tuple[float, ...] = ()) -> float:
    """The mean over a turn of ``quantity(theta, motion rows)``, segment by segment by Gauss-Legendre quadrature (exact
    to rounding for the laws' smooth pieces; a jump at a segment's end costs nothing), a segment split at the cam
    angles ``breaks`` (radians: a load table's rows, where the load has a kink) inside it."""
    x, w = np.polynomial.legendre.leggauss(NODES)
    total = 0.0
    for seg in cam.program.segments:
        cuts = [seg.start, *sorted(b for b in breaks if seg.start < b < seg.end), seg.end]
        for lo, hi in zip(cuts[:-1], cuts[1:]):
            half = (hi - lo) / 2
            theta = lo + half * (x + 1)
            total += half * float(w @ quantity(theta, seg.evaluate(theta)))
    return total / (2 * math.pi)


def _peak_over(cam: Cam, quantity: Any) -> Peak:
    """Largest value of ``quantity(pitch geometry, motion rows)`` over the cycle."""
    segments = cam.program.segments

    def value(i: int, t: np.ndarray) -> np.ndarray:
        m = segments[i].evaluate(np.atleast_1d(t))
        return quantity(cam.follower.pitch(np.atleast_1d(t), m), m)

    return Peak(*cam.program.peak(value))


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


def forces_report(cam: Cam, ld: Loading, rpm: float, contact: Contact | None) -> dict[str, Any]:
    """The report's ``forces``: the torque's extremes and RMS, the peak power, the largest normal contact force
    and, with materials, the largest contact pressure and where."""
    omega = rpm * 2 * math.pi / 60
    hi = peak_at(cam, lambda t, m: torque(ld, omega, m, t))
    lo = peak_at(cam, lambda t, m: -torque(ld, omega, m, t))
    push = _peak_over(cam, lambda g, m: normal_force(ld, omega, g, m))
    out: dict[str, Any] = {
        "torque_max_N_m": hi.value, "torque_max_at_deg": hi.at_deg,
        "torque_min_N_m": -lo.value, "torque_min_at_deg": lo.at_deg,
        "torque_rms_N_m": math.sqrt(cycle_mean(cam, lambda t, m: torque(ld, omega, m, t) ** 2,
                                                ld.table.angles if ld.table else ())),
        "power_max_W": max(hi.value, lo.value) * omega,
        "contact_force_max_N": push.value, "contact_force_max_at_deg": push.at_deg,
    }
    if contact is not None:
        if cam.contact_radius == 0 and not cam.follower.flat:
            out["stress"] = {"note": "a knife edge touches the cam on a line of no width: no Hertz pressure"}
            return out
        p = _peak_over(cam, lambda g, m: contact_pressure(cam, contact, g, normal_force(ld, omega, g, m))[0])
        g = cam.pitch(np.array([math.radians(p.at_deg)]))
        m = cam.program.evaluate(np.array([math.radians(p.at_deg)]))
        half = float(contact_pressure(cam, contact, g, normal_force(ld, omega, g, m))[1][0])
        out["stress"] = {"cam_material": contact.cam, "follower_material": contact.follower,
                         "length_mm": contact.length, "e_star_MPa": contact.e_star,
                         "pressure_max_MPa": p.value, "pressure_max_at_deg": p.at_deg, "half_width_mm": half,
                         "allowable_MPa": contact.allowable, "holds": p.value <= contact.allowable}
    return out
