"""Hub features of a cam: a keyed bore (DIN 6885-1 parallel keys), mounting holes on a bolt circle.

Standard: DIN 6885-1 (ISO/R 773) parallel keys, form A. For a shaft diameter d in a
range, the key is b wide and the hub's keyseat t2 deep, measured from the bore's
surface on the keyway's centre line. The keyway sits on +Y (in line with the
follower at theta = 0).

Every feature takes ``grow`` (mm): its edges move outward into the material by that
much (half the printing clearance), or inward for a negative value (half the kerf),
so allowances stay exact lines and arcs.
"""
from __future__ import annotations

import math

import numpy as np

from camgen.core.errors import DesignError, SpecError
from camgen.core.shapes import Circle, Contour

#: (over d, up to d, key width b, hub keyseat depth t2), mm; DIN 6885-1
KEYS = (
    (6, 8, 2, 1.0), (8, 10, 3, 1.4), (10, 12, 4, 1.8), (12, 17, 5, 2.3), (17, 22, 6, 2.8), (22, 30, 8, 3.3),
    (30, 38, 10, 3.3), (38, 44, 12, 3.3), (44, 50, 14, 3.8), (50, 58, 16, 4.3), (58, 65, 18, 4.4),
    (65, 75, 20, 4.9), (75, 85, 22, 5.4), (85, 95, 25, 5.4), (95, 110, 28, 6.4),
)


def key_for(bore: float) -> tuple[float, float]:
    """(key width b, hub keyseat depth t2) in mm for a bore of diameter ``bore`` mm."""
    for low, high, b, t2 in KEYS:
        if low < bore <= high:
            return float(b), t2
    raise SpecError(f"DIN 6885-1 keys cover bores over 6 up to 110 mm (got {bore:g} mm)", "hub.keyway")


def keyed_bore(bore: float, grow: float = 0.0) -> Contour:
    """The bore with its keyway as one counter-clockwise contour (lines and one arc), edges moved by ``grow``.
    Raises :class:`DesignError` where edges moved in (a negative ``grow``: half a kerf) close the keyway."""
    b, t2 = key_for(bore)
    r = bore / 2 + grow
    half = b / 2 + grow
    if not half > 0:
        raise DesignError(f"output.kerf: a kerf of {-2 * grow:g} mm closes the {b:g} mm keyway of a {bore:g} mm bore "
                          f"(the laser would burn it away); the kerf must be < {b:g} mm")
    top = bore / 2 + t2 + grow
    y = math.sqrt(r * r - half * half)
    verts = np.array([[half, y], [half, top], [-half, top], [-half, y]])
    # from (-half, y) the long way round counter-clockwise back to (half, y)
    sweep = 2 * math.pi - 2 * math.asin(half / r)
    return Contour(verts, np.array([0.0, 0.0, 0.0, math.tan(sweep / 4)]))


def bolt_holes(circle_diameter: float, count: int, hole_diameter: float, grow: float = 0.0) -> tuple[Circle, ...]:
    """``count`` holes evenly on the bolt circle, the first on +X."""
    r = circle_diameter / 2
    return tuple(Circle((r * math.cos(a), r * math.sin(a)), hole_diameter / 2 + grow)
                 for a in 2 * math.pi * np.arange(count) / count)
