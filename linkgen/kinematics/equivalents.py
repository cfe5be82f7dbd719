"""linkgen's dedicated mechanisms drawn as general linkages (:mod:`linkgen.kinematics.structure`).

Each function draws its mechanism at one input angle ``theta0`` (rad) in the mechanism's own
frame, so that the general solver (:class:`~linkgen.kinematics.linkage.Linkage`) reproduces
the dedicated closed form: the tests compare the two over the cycle and through change
points, the bench times both, and the mechanisms without parts of their own (the scotch
yoke and the quick returns) are cut through the general parts layer.
"""
from __future__ import annotations

import math

import numpy as np

from linkgen.kinematics.fourbar import Assembly, FourBar
from linkgen.kinematics.quickreturn import CrankShaper, Whitworth
from linkgen.kinematics.slidercrank import ScotchYoke, SliderCrank
from linkgen.kinematics.structure import Input, Slider, Structure, make_structure

CRANK = (Input("crank", "crank", "O2"),)


def _xy(p: np.ndarray) -> tuple[float, float]:
    return float(p[0]), float(p[1])


def fourbar(fb: FourBar, theta0: float, assembly: Assembly = "open") -> Structure:
    """Ground O2-O4, crank O2-A, coupler A-B (with the coupler point P when it has one), rocker O4-B."""
    p = fb.positions([theta0], assembly)
    points = {"O2": (0.0, 0.0), "O4": (fb.ground, 0.0), "A": _xy(p.a[0]), "B": _xy(p.b[0])}
    coupler: tuple[str, ...] = ("A", "B")
    if fb.point_distance > 0:
        points["P"] = _xy(p.point[0])
        coupler = ("A", "B", "P")
    return make_structure(points, {"crank": ("O2", "A"), "coupler": coupler, "rocker": ("O4", "B")},
                          ("O2", "O4"), (), CRANK)


def slider_crank(sc: SliderCrank, theta0: float) -> Structure:
    """Crank O2-A, rod A-B, a block at B sliding along the ground line y = offset."""
    m = sc.motion(np.array([theta0]), 1.0)
    a = (sc.crank * math.cos(theta0), sc.crank * math.sin(theta0))
    points = {"O2": (0.0, 0.0), "A": a, "B": (float(m.x[0]), sc.offset)}
    return make_structure(points, {"crank": ("O2", "A"), "rod": ("A", "B")}, ("O2",),
                          (Slider("slider", "B", "ground", 0.0),), CRANK)


def scotch_yoke(sy: ScotchYoke, theta0: float) -> Structure:
    """Crank O2-A; a block (named ``block``) at A sliding in the yoke's slot (along +Y); the yoke sliding along +X
    with its point Y on the axis three cranks to the right of the slot (clear of the crank)."""
    a = (sy.crank * math.cos(theta0), sy.crank * math.sin(theta0))
    points = {"O2": (0.0, 0.0), "A": a, "Y": (a[0] + 3 * sy.crank, 0.0)}
    sliders = (Slider("block", "A", "yoke", math.pi / 2), Slider("yoke-guide", "Y", "ground", 0.0, link="yoke"))
    return make_structure(points, {"crank": ("O2", "A"), "yoke": ("Y",)}, ("O2",), sliders, CRANK)


def crank_shaper(cs: CrankShaper, theta0: float) -> Structure:
    """Crank O2-A; the lever turning about O4 = (ground, 0) with a block on the crank pin sliding in it; the ram's
    pin R where the lever crosses the line x = ground - lever, sliding along the lever (a second block) and along
    the ram guide (+Y). The ram's y is minus the dedicated form's u (which counts along the lever's turn)."""
    a = np.array([cs.crank * math.cos(theta0), cs.crank * math.sin(theta0)])
    o4 = np.array([cs.ground, 0.0])
    slot = math.atan2(*(a - o4)[::-1])
    direction = np.array([math.cos(slot), math.sin(slot)])
    r = _xy(o4 - cs.lever / direction[0] * direction)
    end = o4 + 1.2 * math.hypot(r[0] - o4[0], r[1]) * direction
    points = {"O2": (0.0, 0.0), "A": _xy(a), "O4": _xy(o4), "E": _xy(end), "R": r}
    sliders = (Slider("block", "A", "lever", slot), Slider("ram", "R", "ground", math.pi / 2),
               Slider("ram-block", "R", "lever", slot))
    return make_structure(points, {"crank": ("O2", "A"), "lever": ("O4", "E")}, ("O2", "O4"), sliders, CRANK)


def whitworth(w: Whitworth, theta0: float) -> Structure:
    """Crank O2-A; the slotted link turning fully about O4 = (ground, 0) with a block on the crank pin, its arm
    end C; the rod C-D driving a block at D along the line through O4 along +Y."""
    a = np.array([w.crank * math.cos(theta0), w.crank * math.sin(theta0)])
    o4 = np.array([w.ground, 0.0])
    slot = math.atan2(*(a - o4)[::-1])
    c = o4 + w.arm * np.array([math.cos(slot), math.sin(slot)])
    d = (w.ground, float(w.motion(np.array([theta0]), 1.0).x[0]))
    points = {"O2": (0.0, 0.0), "A": _xy(a), "O4": _xy(o4), "C": _xy(c), "D": d}
    sliders = (Slider("block", "A", "slotted", slot), Slider("ram", "D", "ground", math.pi / 2))
    return make_structure(points, {"crank": ("O2", "A"), "slotted": ("O4", "C"), "rod": ("C", "D")},
                          ("O2", "O4"), sliders, CRANK)
