"""A grooved face cam's page: the cam turning with its groove round the island under the roller, the island's S-V-A-J
and checks (the disc cam whose surface is the inner flank), its curvature's undercut limit the groove's cutter's."""
from __future__ import annotations

from typing import Any

from camgen.core.page import Outline, Page
from camgen.page import hole_outlines, page_tolerance, pitch_outline, profile_page, ring


def grooved_page(design: Any, report: dict[str, Any]) -> Page:
    """The page of a grooved cam's design (its groove round the island, the disc cam whose surface is the inner
    flank), whose report is ``report``."""
    spec, cam = design.spec, design.profile.cam
    tol = page_tolerance(design, cam)
    outlines = (Outline(ring(design.part.outline.flatten(tol)), "part"),
                Outline(ring(design.outer_outline.contour.flatten(tol)), "groove"),
                Outline(ring(design.outline.contour.flatten(tol)), "island"), pitch_outline(cam),
                *hole_outlines(design.part, tol))
    cutter = float(spec.follower.roller_radius or 0.0) + float(spec.cam.running_clearance) / 2
    return profile_page(design, cam, report, outlines, "grooved face cam", cutter)
