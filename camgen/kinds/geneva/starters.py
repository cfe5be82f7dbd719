"""A Geneva drive's starter templates (``camgen new``) and the comments of its rules."""
from __future__ import annotations

from camgen.kinds.base import Starter

#: a Geneva drive's ``camgen new`` entries by name
STARTERS = {
    "geneva": Starter(
        "A Geneva drive: the wheel indexes a quarter turn while the driver turns 90 degrees.",
        (("geneva", {"slots": 4, "centre_distance": 80.0, "pin_diameter": 6.0, "slot_clearance": 0.2,
                     "lock_clearance": 0.2, "thickness": 6.0, "driver_bore": 8.0, "wheel_bore": 8.0, "rpm": 30.0}),
         ("output", {"tolerance": 0.01})),
        {"geneva": "the wheel indexes 360 / slots degrees while the driver turns 180 - 360 / slots, then dwells; the "
                   "pin runs at centre_distance sin(180 / slots) from the driver's axis (a radial entry)",
         "geneva.slots": "number of slots in the wheel, 3 to 36",
         "geneva.pin_diameter": "mm: diameter of the driver's pin; the slots are pin_diameter + slot_clearance wide"}),
}
