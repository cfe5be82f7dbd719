"""A linkage's interactive page: the linkage through its motion with its joints' and tracers' paths, the tracers'
velocity and acceleration and each dyad's transmission angle against the input, the report's key figures (see
:mod:`camgen.core.page`).

The poses are the general-linkage analysis of the design (a four-bar, slider-crank, quick-return or straight-line
linkage drawn as one, :func:`linkgen.linkage_design.pose_of`), solved at 360 input values over the motion analysed: a
crank's full turn (played round and round) or the input's range (played to and fro). Velocities and accelerations
are per unit input: mm/rad and mm/rad^2 for a crank, mm/mm and mm/mm^2 for a slide.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from camgen.core.page import FRAMES, Body, Mover, Outline, Page, Plot, Scene, key_figures
from linkgen.kinematics.groups import GROUP_KINDS

#: the figures a linkage's page shows, where its report has them: (label, dotted key, unit)
LINKAGE_FIGURES = (
    ("Grashof class", "grashof_class", ""),
    ("inversion", "inversion", ""),
    ("mobility", "mobility", ""),
    ("smallest transmission angle", "transmission_min_deg", "deg"),
    ("... at crank angle", "transmission_min_at_crank_deg", "deg"),
    ("largest transmission angle", "transmission_max_deg", "deg"),
    ("time ratio", "time_ratio", ""),
    ("rocker swing", "rocker_swing_deg", "deg"),
    ("stroke", "stroke_mm", "mm"),
    ("input range", "input_range_deg", "deg"),
    ("speed", "rpm", "rpm"),
)

#: the dynamics' figures a page shows, where the report has them
DYNAMICS_FIGURES = (
    ("moving mass", "dynamics.moving_mass_kg", "kg"),
    ("largest driving torque", "dynamics.max_N_m", "N·m"),
    ("least driving torque", "dynamics.min_N_m", "N·m"),
    ("largest driving force", "dynamics.max_N", "N"),
    ("peak power", "dynamics.power_peak_W", "W"),
    ("peak shaking force", "dynamics.shaking_force_peak_N", "N"),
    ("energy fluctuation", "dynamics.energy_fluctuation_J", "J"),
    ("flywheel inertia", "dynamics.flywheel.flywheel_kg_m2", "kg·m²"),
    ("flywheel diameter", "dynamics.flywheel.diameter_mm", "mm"),
    ("counterweight m·r", "dynamics.counterweight.mass_radius_kg_mm", "kg·mm"),
    ("steady speed from rest", "dynamics.motor.steady.mean_rpm", "rpm"),
    ("speed fluctuation", "dynamics.motor.steady.fluctuation", ""),
    ("time to steady speed", "dynamics.motor.time_to_steady_s", "s"),
    ("motor stalls at", "dynamics.motor.stall.at_input_deg", "deg"),
)

#: the usual band of transmission angles (degrees)
BAND = (40.0, 140.0)


def _general_figures(report: dict[str, Any]) -> list[tuple[str, str, str]]:
    """A general linkage's figures: each dyad's transmission range, each output's swing and time ratio, each
    tracer's extent."""
    out = []
    for i, d in enumerate(report.get("dyads") or ()):
        name = "-".join(d.get("links", ()))
        out += [(f"dyad {name}: smallest transmission angle", f"dyads.{i}.transmission_min_deg", "deg"),
                (f"dyad {name}: largest transmission angle", f"dyads.{i}.transmission_max_deg", "deg")]
    for name, o in (report.get("outputs") or {}).items() if isinstance(report.get("outputs"), dict) else ():
        for key, label, unit in (("swing_deg", "swing", "deg"), ("stroke_mm", "stroke", "mm"),
                                 ("time_ratio", "time ratio", "")):
            if key in o:
                out.append((f"{name}: {label}", f"outputs.{name}.{key}", unit))
    for name in report.get("tracers") or {} if isinstance(report.get("tracers"), dict) else ():
        out += [(f"tracer {name}: x from, to", f"tracers.{name}.x_mm", "mm"),
                (f"tracer {name}: y from, to", f"tracers.{name}.y_mm", "mm")]
    return out


def _inputs(a: Any) -> tuple[np.ndarray, bool]:
    """The input values of the frames (k, FRAMES) and whether they go round a full turn."""
    span = np.asarray(a.span, dtype=float)
    lo, hi = span[:, 0], span[:, -1]
    cyclic = bool(a.crank and len(lo) == 1 and abs(abs(hi[0] - lo[0]) - 2 * math.pi) < 1e-9)
    steps = np.linspace(0.0, 1.0, FRAMES, endpoint=not cyclic)
    return lo[:, None] + (hi - lo)[:, None] * steps[None, :], cyclic


def linkage_page(name: str, a: Any, report: dict[str, Any],
                 extra: Callable[[np.ndarray], tuple[Plot, ...]] | None = None) -> Page:
    """The page of a linkage drawn as the general-linkage analysis ``a`` (:class:`linkgen.mechanisms.general.
    Analysis`) whose report is ``report`` (the JSON report's dict, its figures shown as they are there); ``extra``
    gives more plots at the frames' input values (k, frames), rad or mm (the dynamics')."""
    values, cyclic = _inputs(a)
    sol = a.linkage.solve(values)
    s = a.linkage.structure
    ok = np.asarray(sol.ok, dtype=bool).reshape(-1)
    points = {p: np.where(ok[:, None], np.asarray(xy, dtype=float), np.nan) for p, xy in sol.points.items()}
    every = np.concatenate([v[np.isfinite(v).all(axis=1)] for v in points.values()])
    scale = float(np.ptp(every, axis=0).max()) or 1.0
    ground = set(s.bodies.get("ground", ()))
    tracers = tuple(a.table.tracers)
    still: list[Outline] = []
    for p, xy in points.items():
        if p not in ground and np.isfinite(xy).any():
            still.append(Outline(xy[np.isfinite(xy).all(axis=1)], "tracer" if p in tracers else "path", cyclic))
    for sl in s.sliders:
        if sl.guide == "ground":
            xy = points[sl.point]
            d = np.array([math.cos(sl.angle), math.sin(sl.angle)])
            along = (xy - xy[np.isfinite(xy).all(axis=1)][0]) @ d
            lo, hi = np.nanmin(along) - 0.1 * scale, np.nanmax(along) + 0.1 * scale
            base = xy[np.isfinite(xy).all(axis=1)][0]
            still.append(Outline(np.array([base + lo * d, base + hi * d]), "guide", False))
    pivot = 0.012 * scale
    still += [Outline(_triangle(np.asarray(s.points[p], dtype=float), 2.2 * pivot), "ground") for p in sorted(ground)]
    movers = []
    for body, pts in s.bodies.items():
        if body == "ground" or not pts:
            continue
        xy = np.stack([points[p] for p in pts], axis=1)
        movers.append(Mover(body, xy, "plate" if len(pts) > 2 else "link", closed=len(pts) > 2))
    moving = [p for p in points if p not in ground]
    movers.append(Mover("joints", np.stack([points[p] for p in moving], axis=1), "joint", pivot))
    if tracers:
        movers.append(Mover("tracers", np.stack([points[p] for p in tracers], axis=1), "pin", 1.3 * pivot))
    shown = np.degrees(values[0]) if a.crank else values[0]
    watched = tracers or tuple(moving[-2:])
    unit = "mm/rad" if a.crank else "mm/mm"
    plots = [Plot("speed of " + ", ".join(watched), unit,
                  tuple((p, np.where(ok, np.linalg.norm(sol.velocities[p], axis=1), np.nan)) for p in watched)),
             Plot("acceleration of " + ", ".join(watched), unit + "^2" if a.crank else "1/mm",
                  tuple((p, np.where(ok, np.linalg.norm(sol.accelerations[p], axis=1), np.nan)) for p in watched))]
    dyads = [d for d in sol.dyads if d.kind not in GROUP_KINDS]      # a class-III group has no transmission angle
    if dyads:
        plots.append(Plot("transmission angle", "deg",
                          tuple((f"{'-'.join(d.bodies)} ({d.joint})", np.where(ok, np.degrees(d.transmission), np.nan))
                                for d in dyads[:4]),
                          tuple(("usual band", v) for v in BAND)))
    if extra is not None:
        plots += [Plot(p.title, p.unit, tuple((label, np.where(ok, v, np.nan)) for label, v in p.series), p.marks)
                  for p in extra(values)]
    figures = key_figures(report, (*LINKAGE_FIGURES, *DYNAMICS_FIGURES, *_general_figures(report)))
    kind = report.get("inversion") or report.get("type", "linkage")
    title = f"{name}: {kind}"
    subtitle = (f"{len(s.bodies) - 1} moving links, {len(moving)} moving joints; "
                + ("a full turn of the crank" if cyclic else "over the input's range, to and fro"))
    return Page(name, title, subtitle, "crank angle" if a.crank else "slide", "deg" if a.crank else "mm",
                shown, Scene((Body("ground and paths", tuple(still)),), tuple(movers)), tuple(plots), figures,
                tuple(report.get("warnings", ())), cyclic=cyclic)


def _triangle(at: np.ndarray, size: float) -> np.ndarray:
    return np.array([at, at + np.array([-size, -1.6 * size]), at + np.array([size, -1.6 * size])])
