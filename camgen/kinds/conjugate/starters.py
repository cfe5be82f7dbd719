"""A conjugate pair's starter templates (``camgen new``) and the comments of its rules."""
from __future__ import annotations

from camgen.kinds.base import Starter
from camgen.kinds.starting import OUTPUT, ROLLER, cam_table, motion

#: a conjugate pair's ``camgen new`` entries by name
STARTERS = {
    "conjugate": Starter(
        "A conjugate pair: two discs on one shaft drive a yoke's two rollers, both ways, no spring.",
        (cam_table("conjugate", bore=12.0), ("follower", {"type": "translating-roller", "roller_radius": 8.0}),
         *motion(), ("hub", {"keyway": True}), OUTPUT),
        {"cam": "a conjugate pair: a second disc drives a second roller on the far end of the yoke; its base circle "
                "is cam.second_base_radius (default: base_radius); both cams are checked for pressure angle and "
                "undercut",
         "follower": "positive drive: the two cams drive the yoke both ways, no return spring",
         **ROLLER}),
}
