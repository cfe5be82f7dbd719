"""Standard hardware a kit is sized for: ball bearings, metric bolts, nuts, washers and shafts (all mm).

Sources of the figures (nominal sizes; a kit's holes add the process allowance to them):

* Deep-groove ball bearings, bore d x outside diameter D x width B: ISO 15 (dimension series 02 for the 62x
  and 60x sizes, 00/10 for 608), as the SKF and NSK catalogues list them: 623 3 x 10 x 4, 624 4 x 13 x 5,
  625 5 x 16 x 5, 608 8 x 22 x 7.
* Clearance holes for bolts: ISO 273, medium series (H13): M3 3.4, M4 4.5, M5 5.5.
* Hexagon nuts: ISO 4032 (style 1): width across flats s and height m: M3 5.5 / 2.4, M4 7 / 3.2, M5 8 / 4.7.
* Plain washers: ISO 7089 (normal series): inner d1, outer d2, thickness h: M3 3.2 / 7 / 0.5, M4 4.3 / 9 / 0.8,
  M5 5.3 / 10 / 1.
* Socket head cap screws: ISO 4762: head diameter dk and height k: M3 5.5 / 3, M4 7 / 4, M5 8.5 / 5; the
  preferred nominal lengths l of its table (6 to 100 mm).
* Shafts: ground steel rod (h6) of 3, 4, 5 and 8 mm, the bores of the bearings above.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal


@dataclass(frozen=True)
class Bearing:
    """A deep-groove ball bearing (ISO 15): bore, outside diameter and width (mm)."""

    name: str
    bore: float
    outside: float
    width: float


@dataclass(frozen=True)
class Bolt:
    """A metric bolt with its hexagon nut and washer (mm): nominal diameter, ISO 273 medium clearance hole,
    ISO 4032 nut (across flats, height), ISO 7089 washer (outside diameter, thickness), ISO 4762 head
    (diameter, height)."""

    name: str
    diameter: float
    clearance_hole: float
    nut_across_flats: float
    nut_height: float
    washer_outside: float
    washer_thickness: float
    head_diameter: float
    head_height: float

    @property
    def nut_across_corners(self) -> float:
        """The nut's width across its corners (mm): across flats x 2 / sqrt(3)."""
        return self.nut_across_flats * 2.0 / math.sqrt(3.0)


#: the designations of :data:`BEARINGS` and :data:`BOLTS`, written out for the type checker
BearingName = Literal["623", "624", "625", "608"]
BoltName = Literal["M3", "M4", "M5"]

#: the bearings a kit may seat, by their designation
BEARINGS: dict[str, Bearing] = {b.name: b for b in (
    Bearing("623", 3.0, 10.0, 4.0), Bearing("624", 4.0, 13.0, 5.0), Bearing("625", 5.0, 16.0, 5.0),
    Bearing("608", 8.0, 22.0, 7.0))}

#: the bolts a kit may use, by their designation
BOLTS: dict[str, Bolt] = {b.name: b for b in (
    Bolt("M3", 3.0, 3.4, 5.5, 2.4, 7.0, 0.5, 5.5, 3.0),
    Bolt("M4", 4.0, 4.5, 7.0, 3.2, 9.0, 0.8, 7.0, 4.0),
    Bolt("M5", 5.0, 5.5, 8.0, 4.7, 10.0, 1.0, 8.5, 5.0))}

#: shaft diameters a kit is sized for (mm)
SHAFTS = (3.0, 4.0, 5.0, 8.0)

#: ISO 4762's preferred nominal lengths (mm)
BOLT_LENGTHS = (6.0, 8.0, 10.0, 12.0, 16.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0, 50.0, 55.0, 60.0, 65.0, 70.0,
                80.0, 90.0, 100.0)

#: a plain (bearing-less) shaft hole runs on this much diametral play over the shaft (mm)
RUNNING_PLAY = 0.2


def bolt_length(bolt: Bolt, grip: float) -> float:
    """The shortest preferred length (mm) of ``bolt`` through ``grip`` mm of stacked parts with a washer and a nut
    under its end and 1 mm of thread proud of the nut; inf when no length of the table is long enough."""
    needed = grip + bolt.washer_thickness + bolt.nut_height + 1.0
    return next((length for length in BOLT_LENGTHS if length >= needed), math.inf)
