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


def bore_reach(bore: float, keyway: bool, clearance: float) -> float:
    """How far (mm) from the axis a bore of diameter ``bore`` reaches as printed: its radius grown by ``clearance`` /
    2, and with a ``keyway`` its key's seat t2 (DIN 6885-1, the largest key's above its range) further; 0 for no
    bore."""
    if not bore:
        return 0.0
    seat = 0.0
    if keyway:
        seat = next((t2 for _, high, _, t2 in KEYS if bore <= high), KEYS[-1][3])
    return bore / 2 + clearance / 2 + seat


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


#: the least material (mm) a hub keeps between two of its holes (the bore with its keyway, the bolt holes), as drawn
#: and as printed with its holes opened by the clearance: less and a printed web breaks or does not print at all,
#: and at 0 the holes merge (a ring of bolt holes that meet cuts the hub out of the cam)
MIN_WEB_MM = 1.0


def hub_web(bore: float, keyway: bool, bolt_circle: float, count: int, hole_diameter: float,
            grow: float = 0.0) -> tuple[float, str]:
    """The narrowest material (mm) between two holes of a hub whose edges move out by ``grow`` (mm): the bore (0 for
    none; keyed with ``keyway``) and ``count`` bolt holes on the circle (:func:`bolt_holes`), and which two they are
    ("two bolt holes" or "a bolt hole and the bore"); negative where they overlap (by that much), ``(inf, "")`` with
    fewer than two holes. Exact: circles' distances, and the distance from each hole's centre to the keyed bore's
    disc and slot."""
    if count == 0:
        return math.inf, ""
    r = hole_diameter / 2 + grow
    webs = []
    if count >= 2:
        webs.append((bolt_circle * math.sin(math.pi / count) - 2 * r, "two bolt holes"))
    if bore > 0:
        centres = np.array([(c.centre[0], c.centre[1]) for c in bolt_holes(bolt_circle, count, hole_diameter)])
        disc = bore / 2 + grow
        reach = np.hypot(centres[:, 0], centres[:, 1]) - disc          # to the round bore
        if keyway:
            b, t2 = key_for(bore)
            half, top = b / 2 + grow, bore / 2 + t2 + grow
            low = math.sqrt(max(disc * disc - half * half, 0.0))     # where the slot's sides meet the disc
            dx = np.maximum(np.abs(centres[:, 0]) - half, 0.0)
            dy = np.maximum.reduce([centres[:, 1] - top, low - centres[:, 1], np.zeros(len(centres))])
            reach = np.minimum(np.maximum(reach, 0.0), np.hypot(dx, dy))
        webs.append((float(reach.min()) - r, "a bolt hole and the bore"))
    return min(webs)


def largest_clearance(bore: float, keyway: bool, bolt_circle: float, count: int, hole_diameter: float,
                      web: float = MIN_WEB_MM) -> float:
    """The largest printing clearance (mm; holes opened by half of it a side) that keeps :func:`hub_web` at least
    ``web`` mm, to 1e-9 mm; 0 where the holes as drawn keep less (by bisection: the web shrinks by the clearance
    between circles, somewhat faster at a keyway's corners)."""
    def web_at(clearance: float) -> float:
        return hub_web(bore, keyway, bolt_circle, count, hole_diameter, clearance / 2)[0]

    if not web_at(0.0) >= web:
        return 0.0
    low, high = 0.0, web_at(0.0) - web + 1e-9        # the web shrinks by at least the clearance
    while high - low > 1e-10:
        mid = (low + high) / 2
        low, high = (mid, high) if web_at(mid) >= web else (low, mid)
    return low


def web_refusal(bore: float, keyway: bool, bolt_circle: float, count: int, hole_diameter: float,
                clearance: float) -> SpecError | None:
    """Why a hub's holes keep too little material between them (:data:`MIN_WEB_MM`), as drawn (naming
    ``hub.bolt_circle``) or as printed, opened by ``clearance`` mm (naming ``output.clearance`` and the largest
    clearance that keeps the web); None where they keep it."""
    holes = (bore, keyway, bolt_circle, count, hole_diameter)
    drawn, pair = hub_web(*holes)
    if drawn < MIN_WEB_MM:
        what = (("two bolt holes overlap" if pair == "two bolt holes" else "a bolt hole cuts into the bore")
                if drawn <= 0 else f"{pair} are only {drawn:.3g} mm apart")
        return SpecError(f"{what} ({count} holes of {hole_diameter:g} mm on a {bolt_circle:g} mm circle, bore "
                         f"{bore:g} mm); holes must keep {MIN_WEB_MM:g} mm of material between them: use fewer or "
                         "smaller holes, or another circle", "hub.bolt_circle")
    printed, pair = hub_web(*holes, clearance / 2)
    if printed < MIN_WEB_MM:
        opened = "into each other" if printed <= 0 else f"to {printed:.3g} mm apart"
        return SpecError(f"must be at most {largest_clearance(*holes):.4g} mm with these holes (got {clearance:g}): "
                         f"it opens {pair} {opened}, and holes must keep {MIN_WEB_MM:g} mm of material between them",
                         "output.clearance")
    return None
