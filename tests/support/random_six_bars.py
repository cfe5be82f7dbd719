"""Six-bars drawn at random joint positions: the fused and the compiled solvers' tests compare them with the general
solve on linkages nobody chose."""
from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np

from camgen.core.errors import SpecError
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.structure import Input, make_structure


def random_six_bar(rng: np.random.Generator, kind: str) -> Linkage:
    """A six-bar drawn at random joint positions (mm): Watt I (coupler A-B-E and rocker O4-B-F ternary, dyad
    F-G-E) or Stephenson III (coupler A-B-E ternary, dyad E-G-O6 to the ground)."""
    pts: dict[str, tuple[float, float]] = {}
    for name in ("B", "E", "F", "G", "O6"):
        x, y = rng.uniform(-100.0, 100.0, 2)
        pts[name] = (float(x), float(y))
    pts["O2"], pts["O4"] = (0.0, 0.0), (float(rng.uniform(60.0, 120.0)), float(rng.uniform(-20.0, 20.0)))
    crank = float(rng.uniform(10.0, 30.0))
    angle = float(rng.uniform(0.0, 2 * math.pi))
    pts["A"] = (crank * math.cos(angle), crank * math.sin(angle))
    if kind == "watt":
        links = {"crank": ("O2", "A"), "coupler": ("A", "B", "E"), "rocker": ("O4", "B", "F"), "output": ("F", "G"),
                 "rod": ("E", "G")}
        ground: tuple[str, ...] = ("O2", "O4")
        del pts["O6"]
    else:
        links = {"crank": ("O2", "A"), "coupler": ("A", "B", "E"), "rocker": ("O4", "B"), "rod": ("E", "G"),
                 "output": ("O6", "G")}
        ground = ("O2", "O4", "O6")
        del pts["F"]
    return Linkage.of(make_structure(pts, links, ground, (), (Input("crank", "crank", "O2"),)))


def random_six_bars(kind: str, count: int = 6) -> Iterator[Linkage]:
    """``count`` six-bars of ``kind`` ("watt" or "stephenson", see :func:`random_six_bar`) from a seeded generator
    (38 for Watt's, 3838 for Stephenson's), so every test that takes them gets the same linkages; a drawing that
    cannot move (e.g. at a toggle) is drawn again."""
    rng = np.random.default_rng(38 if kind == "watt" else 3838)
    done = 0
    while done < count:
        try:
            linkage = random_six_bar(rng, kind)
        except SpecError:
            continue
        yield linkage
        done += 1
