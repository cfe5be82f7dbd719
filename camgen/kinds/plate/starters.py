"""A plate cam's starter templates (``camgen new``) and the comments of its rules."""
from __future__ import annotations

from camgen.kinds.base import Starter
from camgen.kinds.starting import OUTPUT, motion

#: a plate cam's ``camgen new`` entries by name
STARTERS = {
    "plate": Starter(
        "A plate (linear) cam: the profile along a plate that slides, lifting a roller.",
        (("cam", {"kind": "plate", "travel": 200.0, "base_radius": 20.0, "thickness": 6.0}),
         ("follower", {"type": "translating-roller", "roller_radius": 8.0}), *motion(15.0), OUTPUT),
        {"cam": "a plate cam slides along +X as the program runs: it does not turn and has no bore",
         "cam.travel": "mm: how far the plate slides over the program's 360 degrees: a segment of a degrees "
                       "takes a / 360 of it",
         "cam.base_radius": "mm: the plate's height under the profile; the roller's centre runs at base_radius + "
                            "roller_radius + s",
         "follower.roller_radius": "mm: roller radius; below the pitch curve's least convex radius, else the plate "
                                   "undercuts"}),
}
