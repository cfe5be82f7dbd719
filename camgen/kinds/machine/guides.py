"""The guides of a machine's sliders, drawn as fixed parts: each general linkage's slider on a guide of the ground (a
follower's stem driving it, a carriage an arm shuttles) is a line through the slider's point at its guide's drawn
angle (the linkage's drawing is moved, not turned, into the machine's frame), from one end of the point's travel
over a turn of the main shaft to the other, on the slider's plane. A guide is drawn (figures, page, the report's
``poses``); it is a line, not a clash body.

The travel's ends are found on the design's main shaft samples and each refined by a bounded scalar search within
a sample either side (an end between samples, as a shaft-turned slider-crank's), to :data:`ANGLE_TOL_RAD`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

#: the main shaft angle (radians) to which a travel's end between samples is found
ANGLE_TOL_RAD = 1e-10


@dataclass(frozen=True)
class Guide:
    """A slider's guide: its ``name`` (``linkages.<linkage>.<slider>.guide``), its ``plane`` (the clash check's)
    and its ``ends`` (2, 2) mm in the machine's frame, the travel's start (least along the guide's direction) first."""

    name: str
    plane: int
    ends: np.ndarray


def guides(design: Any) -> tuple[Guide, ...]:
    """Every ground guide of the sliders of ``design``'s (a :class:`~camgen.kinds.machine.design.MachineDesign`)
    shaft- and follower-driven general linkages."""
    out = []
    for m in (*getattr(design, "cranked", ()), *getattr(design, "slid", ())):
        build = m.design.build
        for slider in m.analysis.linkage.structure.sliders:
            if slider.guide != "ground":
                continue
            u = np.array([math.cos(slider.angle), math.sin(slider.angle)])
            layer = build.layers.get(slider.name, 0) if build is not None else 0
            start, end = _travel(m, slider.point, u, np.asarray(design.phi, dtype=float))
            out.append(Guide(f"linkages.{m.name}.{slider.name}.guide", m.side * (2 * m.layer + layer),
                             np.stack([start, end])))
    return tuple(out)


def _travel(m: Any, point: str, u: np.ndarray, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The ends (mm) of joint ``point``'s travel along ``u`` over the turn, ``m`` solved at the samples ``phi``."""
    def at(angles: np.ndarray) -> np.ndarray:
        return np.asarray(m.solve(angles).points[point], dtype=float) + m.offset

    placed = at(phi)
    origin = placed[0]
    along = (placed - origin) @ u
    step = float(phi[1] - phi[0]) if len(phi) > 1 else math.pi

    from scipy.optimize import minimize_scalar          # here: scipy's optimisers are 0.3 s of a command's start

    def refined(k: int, sign: float) -> float:
        found = minimize_scalar(lambda x: sign * float((at(np.array([x]))[0] - origin) @ u),
                                bounds=(float(phi[k]) - step, float(phi[k]) + step), method="bounded",
                                options={"xatol": ANGLE_TOL_RAD})
        return min(sign * float(along[k]), float(found.fun)) * sign

    low, high = refined(int(np.argmin(along)), 1.0), refined(int(np.argmax(along)), -1.0)
    return origin + low * u, origin + high * u
