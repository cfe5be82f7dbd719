"""A conjugate pair's own figure: the checks of each roller on its cam (:func:`camgen.plots.drive_checks_plot`)."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from camgen.cam import Cam
from camgen.plots import drive_checks_plot

if TYPE_CHECKING:
    from camgen.forces import Contact


def _pressure(cam: Cam, force: Any, contact: Contact) -> Any:
    """The Hertz pressure (MPa) of ``contact`` on ``cam`` under the normal force
    ``force(geometry, motion)`` (N), as a function of pitch geometry and motion."""
    from camgen.forces import contact_pressure

    return lambda g, m: contact_pressure(cam, contact, g, force(g, m))[0]


def pair_checks_figure(design: Any) -> Any:
    """:func:`drive_checks_plot` of a conjugate pair: each roller on its cam, cam 1 carrying F > 0 (N1 = F /
    cos(phi1)), cam 2 F < 0 (N2 = -F (L1 / L2) / cos(phi2)), each profile's radius its pitch curve's less its own
    roller's."""
    from camgen.dynamics import spec_loading
    from camgen.forces import materials_of, pair_forces, torque

    spec, pair = design.spec, tuple(d.cam for d in design.cams)
    forces = design.cams[0].speed.forces
    ld = spec_loading(spec.follower, pair[0].follower, True, spec.motion, pair[0].program)
    omega = spec.cam.rpm * 2 * math.pi / 60
    st = forces.hertz
    contact = materials_of(st)
    contacts = []
    for k, (cam, force) in enumerate(zip(pair, pair_forces(pair, ld, omega), strict=True)):
        contacts.append((f"cam {k + 1}", cam, lambda g, cam=cam: 1.0 / g.kappa - cam.contact_radius, force,
                         None if contact is None else _pressure(cam, force, contact)))
    return drive_checks_plot(spec.name, design.cams[0].pressure_limit_deg, contacts,
                             lambda t, m: torque(ld, omega, m, t), None if st is None else st.allowable,
                             max(cam.contact_radius for cam in pair), getattr(spec.output, "tool_radius", 0.0))
