"""What the groove kinds share: the undercut check of a groove's two flanks (or walls), each an offset of the
pitch curve by the cutter's radius. Used by the grooved face cam (:mod:`camgen.kinds.grooved`) and by the barrel cam on
each cylinder it checks (:mod:`camgen.kinds.barrel`). No I/O.

Radii of curvature follow the project's signs (convex > 0, like the base circle): the inner flank (the one towards
the cam's centre, a plate cam's lower wall) bends with the pitch curve's convex stretches, radius rho - d, and
undercuts (folds into a loop) where the convex pitch radius rho < d; the outer flank bends the other way where the
pitch curve is concave, radius |rho| - d, and undercuts where the concave pitch radius |rho| < d. A velocity jump
is a corner of the pitch curve: a convex corner undercuts the inner flank, a concave one the outer.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from camgen.analysis import analyze
from camgen.cam import Cam


@dataclass(frozen=True)
class Flank:
    """The undercut check of one flank of the groove.

    ``side`` is ``"inner"`` or ``"outer"``. ``pitch_rho_min_mm``: the pitch curve's smallest radius of curvature
    in the sense that bends this flank (convex for the inner flank, concave for the outer; unsigned, mm; infinite
    where the pitch curve never bends that way, 0 at a corner), at cam angle ``at_deg`` (degrees, None where
    infinite). ``offset_mm`` is d = Rr + c/2, the flank's distance from the pitch curve.
    """

    side: str
    pitch_rho_min_mm: float
    at_deg: float | None
    offset_mm: float

    @property
    def rho_min_mm(self) -> float:
        """The flank's own smallest convex radius of curvature (mm): the pitch radius less d; negative: undercut."""
        return self.pitch_rho_min_mm - self.offset_mm

    @property
    def undercut(self) -> bool:
        """True where the pitch radius is below d: the offset folds into a loop, the roller cannot follow."""
        return self.pitch_rho_min_mm < self.offset_mm


def flank_checks(cam: Cam, offset: float) -> tuple[Flank, Flank]:
    """The inner and outer flank checks of a groove ``offset`` mm (Rr + c/2) either side of ``cam``'s pitch curve."""
    a = analyze(cam)
    convex_at = a.pitch_rho_min_at_deg if math.isfinite(a.pitch_rho_min_mm) else None
    inner = Flank("inner", a.pitch_rho_min_mm, convex_at, offset)
    concave_corners = [i for i, turn in cam.corners() if turn < 0]
    if concave_corners:
        at = math.degrees(cam.program.segments[concave_corners[0]].end) % 360.0
        outer = Flank("outer", 0.0, at, offset)
    elif a.pitch_concave_rho_min_mm is None:
        outer = Flank("outer", math.inf, None, offset)
    else:
        outer = Flank("outer", a.pitch_concave_rho_min_mm, a.concave_at_deg, offset)
    return inner, outer
