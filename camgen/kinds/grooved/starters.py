"""A grooved cam's starter templates (``camgen new``) and the comments of its rules."""
from __future__ import annotations

from camgen.kinds.base import Starter
from camgen.kinds.starting import OUTPUT, cam_table, motion

#: a grooved cam's ``camgen new`` entries by name
STARTERS = {
    "grooved": Starter(
        "A grooved face cam: the roller runs in a groove that drives it both ways, no spring.",
        (cam_table("grooved", thickness=12.0, groove_depth=6.0, running_clearance=0.2, rim=5.0),
         ("follower", {"type": "translating-roller", "roller_radius": 6.0}), *motion(), OUTPUT),
        {"cam": "a grooved face cam: flanks roller_radius + running_clearance / 2 either side of the pitch curve; "
                "the inner flank undercuts where the pitch curve's convex radius falls below that, the outer where "
                "its concave radius does",
         "follower": "positive drive: the groove drives the roller both ways, no return spring",
         "cam.groove_depth": "mm: depth of the groove's pocket in the face; < thickness (it is no slot)",
         "cam.thickness": "mm: plate thickness (STL extrusion); > groove_depth",
         "cam.rim": "mm: wall outside the groove's outer flank"}),
}
