"""A grooved face cam's own figure: the checks of its two flanks (:func:`camgen.plots.groove_checks_plot`)."""
from __future__ import annotations

from typing import Any

from camgen.plots import groove_checks_plot


def grooved_checks_figure(design: Any) -> Any:
    """:func:`groove_checks_plot` of a grooved cam: its inner flank (convex, carrying F > 0) and outer flank
    (concave round the roller, carrying F < 0), d = roller + running clearance / 2 either side of the pitch curve."""
    return groove_checks_plot(design.spec, design.cam, design.profile.speed.forces,
                              design.profile.pressure_limit_deg, design.cam.contact_radius,
                              design.spec.follower.roller_radius, ("inner flank", "outer flank"))
