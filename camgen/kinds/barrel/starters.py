"""A barrel cam's starter templates (``camgen new``) and the comments of its rules."""
from __future__ import annotations

from camgen.kinds.base import Starter
from camgen.kinds.starting import OUTPUT

#: a barrel cam's ``camgen new`` entries by name
STARTERS = {
    "barrel": Starter(
        "A barrel (cylindrical) cam: a groove round a cylinder moves the roller along the axis.",
        (("cam", {"kind": "barrel", "pitch_radius": 30.0, "length": 50.0, "groove_depth": 6.0, "bore": 10.0,
                  "rpm": 60.0}),
         ("follower", {"type": "translating-roller", "roller_radius": 5.0}),
         *(("[motion]", seg) for seg in ({"type": "rise", "law": "cycloidal", "lift": 20.0, "angle": 150.0},
                                         {"type": "dwell", "angle": 30.0},
                                         {"type": "return", "law": "modified-sine", "lift": 20.0, "angle": 150.0},
                                         {"type": "dwell", "angle": 30.0})), OUTPUT),
        {"cam": "a barrel cam, sized by pitch_radius, length and groove_depth; the pressure angle is "
                "atan(s' / pitch_radius)",
         "follower": "a roller moving along the cam's axis, driven both ways by the groove (no return spring)",
         "cam.pitch_radius": "mm: radius of the pitch cylinder, the groove's mid-depth",
         "cam.length": "mm: the cylinder's axial length; more than the follower's stroke and the groove's width, "
                       "2 roller_radius + running_clearance",
         "cam.groove_depth": "mm: depth of the groove about pitch_radius; its floor, at pitch_radius - "
                             "groove_depth / 2, must lie outside the bore as printed (bore / 2 + "
                             "output.clearance / 2) and outside roller_radius + running_clearance / 2",
         "cam.bore": "mm: bore diameter, 0 for none; within the groove's floor"}),
}
