"""The quick-return mechanisms, Whitworth and the crank-shaper: their ``[linkage]`` tables and reports (their ram is
a slider: see :mod:`linkgen.mechanisms.slidercrank`). Their parts are those of the general linkage each draws
(:mod:`linkgen.kinematics.equivalents`), the crank-shaper's; Whitworth's crank sweeps over the slotted link's
pivot and its rod over the crank pin's slot, which no stack of plates keeps clear: no parts for it.

Frame (see :mod:`linkgen.kinematics.quickreturn`): the driving crank's pivot at the
origin, the slotted link's pivot at (ground, 0); crank angle counter-clockwise from +X.
"""
from __future__ import annotations

import math
from typing import Any

from linkgen.kinematics import equivalents
from linkgen.kinematics.quickreturn import CrankShaper, Whitworth
from linkgen.kinematics.slidercrank import SliderMotion
from linkgen.mechanisms.common import lengths_table
from linkgen.mechanisms.slidercrank import SliderMechanism

WhitworthTable = lengths_table(
    "WhitworthTable", "``[linkage]`` of a Whitworth quick return (mm).", ("whitworth",),
    crank="driving crank", ground="crank pivot to slotted-link pivot (< crank)",
    arm="ram-driving arm on the slotted link", rod="connecting rod from the arm to the ram")
CrankShaperTable = lengths_table(
    "CrankShaperTable", "``[linkage]`` of a crank-shaper (mm).", ("crank-shaper",),
    crank="driving crank", ground="crank pivot to lever pivot (> crank)", lever="lever pivot to the ram line")


def _link(mech: Any, m: SliderMotion, speed: float) -> dict[str, Any]:
    """The slotted link's (or the lever's) angle at one pose, degrees."""
    return {"link_deg": round(math.degrees(m.rod[0]), 9)}


def _swing(shaper: CrankShaper) -> dict[str, Any]:
    """The lever's full swing, degrees."""
    return {"lever_swing_deg": round(math.degrees(shaper.swing), 9)}


REGISTER = (
    # no parts for Whitworth: its crank sweeps over the slotted link's pivot and its rod over the crank pin's
    # slot, so no stack of plates (even with a top plate for the pivot) keeps every pin clear
    SliderMechanism(WhitworthTable, lambda t: Whitworth(t.crank, t.ground, t.arm, t.rod), at=_link),
    SliderMechanism(CrankShaperTable, lambda t: CrankShaper(t.crank, t.ground, t.lever),
                    extra=_swing, at=_link, drawn=lambda k: equivalents.crank_shaper(k, 0.0), traced="R"),
)
