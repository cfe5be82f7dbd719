"""A machine's interactive page (``<name>.html``, see :mod:`camgen.core.page`): every part of every mechanism moving
together over one turn of the main shaft, a frame a degree (frame k at k degrees), with a slider and a play button;
the timing diagram beneath, a row per output with a cursor at the shown angle; the report's key figures, warnings
and files.

The parts are the clash check's, placed by :func:`camgen.kinds.machine.poses.placed_parts` (cams as cut, follower
arms and rollers, the linkages' parts as cut), drawn from the lowest plane up, those behind the frame (a
shaft-driven linkage on its back) in orange; shafts and pins are white discs, each named point
(:func:`~camgen.kinds.machine.poses.points`) a small disc, the tracers' paths over the turn in red and the gear
pairs' pitch circles dashed; each slider's guide (:mod:`camgen.kinds.machine.guides`) a still line over its
travel, after the moving parts. The frames' data are rounded to 1e-8 mm (and degrees), so that a frame shows the poses
the report gives (its ``poses``) to far better than a micrometre.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.core.page import FRAMES, Body, KeyFigure, Mover, Outline, Page, Plot, Scene, key_figures, pose_motion
from camgen.kinds.machine import poses
from camgen.kinds.machine.clash import circle
from camgen.kinds.machine.guides import guides

#: the rounding step of the page's frames (mm, and degrees for turns)
PRECISION = 1e-8


def frame_angles() -> np.ndarray:
    """The main shaft angles (radians) of the page's frames: one a degree from 0."""
    return np.radians(np.arange(FRAMES) * (360.0 / FRAMES))


def _style(p: poses.Placed) -> str:
    if p.high < 0:
        return "second"
    if p.name.startswith(("pins.", "shafts.")):
        return "joint"
    if p.name.endswith(".roller"):
        return "roller"
    if p.name.startswith("gears.") and not p.name.endswith(".hub"):
        return "part"
    return "part" if p.name.startswith("cams.") and p.name.count(".") == 1 else "plate"


def _still(design: Any, paths: list[np.ndarray]) -> Body:
    """What stands still: each shaft's centre marked, each gear pair's working pitch circles, the tracers' paths."""
    at = {s.name: np.asarray(s.at, dtype=float) for s in design.spec.shafts}
    size = 6.0
    outlines = []
    across, up = np.array([size, 0.0]), np.array([0.0, size])
    for c in at.values():
        outlines += [Outline(np.array([c - across, c + across]), "guide", False),
                     Outline(np.array([c - up, c + up]), "guide", False)]
    for g in design.gears:
        outlines += [Outline(circle(radius, 0.05) + at[shaft], "pitch")
                     for shaft, radius in zip(g.shafts, g.pair.working_pitch_radii, strict=True)]
    outlines += [Outline(path, "tracer") for path in paths]
    return Body("frame, gears' pitch circles and paths", tuple(outlines))


def traced(design: Any) -> tuple[str, ...]:
    """The points whose paths the page draws: each coupled four-bar's coupler point, each shaft-driven linkage's
    tracers."""
    return (*(f"linkages.{m.name}.P" for m in design.linkages if m.fourbar.point_distance > 0),
            *(f"linkages.{m.name}.{p}" for m in (*design.cranked, *design.slid) for p in m.tracers))


def outputs_at(design: Any, phi: np.ndarray) -> dict[str, tuple[str, np.ndarray]]:
    """The timing diagram's outputs (labels and units as :attr:`~camgen.kinds.machine.design.MachineDesign.outputs`)
    at main shaft angles ``phi`` (radians): each follower, each coupled four-bar's rocker angle (degrees, from its
    ground line), each follower-driven general linkage's output turn (degrees), each shaft- or follower-driven
    general linkage's tracers' x and y (mm, the machine's frame)."""
    out = {f"cams.{c.name}": (c.unit, poses.swing(c, phi)[0]) for c in design.cams}
    for m in design.linkages:
        out[f"linkages.{m.name}"] = ("deg", np.degrees(poses.fourbar_at(design, m, phi)[1].theta4))
    for m in design.slid:
        if m.coupling.output is not None:
            out[f"linkages.{m.name}"] = ("deg", np.degrees(m.solve(phi).angle(m.coupling.output)))
    for m in (*design.cranked, *design.slid):
        sol = m.solve(phi)
        for p in m.tracers:
            for k, axis in enumerate("xy"):
                out[f"linkages.{m.name}.{p}.{axis}"] = ("mm", np.asarray(sol.points[p])[:, k] + m.offset[k])
    return out


def _figures(design: Any, report: dict[str, Any]) -> tuple[KeyFigure, ...]:
    wanted = [("main shaft speed", "machine.rpm", "rpm")]
    for name in report.get("cams", {}):
        wanted += [(f"cams.{name}: largest pressure angle", f"cams.{name}.pressure_angle_max_deg", "deg"),
                   (f"cams.{name}: phase", f"cams.{name}.phase_deg", "deg")]
    for name in report.get("linkages", {}):
        wanted += [(f"linkages.{name}: rocker from, to", f"linkages.{name}.rocker_deg", "deg"),
                   (f"linkages.{name}: transmission from, to", f"linkages.{name}.transmission_deg", "deg")]
    for name, entry in report.get("cranked", {}).items():
        wanted.append((f"linkages.{name}: phase", f"cranked.{name}.phase_deg", "deg"))
        for p in entry.get("tracers", {}):
            wanted += [(f"linkages.{name}.{p}: x from, to", f"cranked.{name}.tracers.{p}.x_mm", "mm"),
                       (f"linkages.{name}.{p}: y from, to", f"cranked.{name}.tracers.{p}.y_mm", "mm")]
    wanted += [("main shaft torque, least", "shaft_torque_n_m.min", "N·m"),
               ("main shaft torque, largest", "shaft_torque_n_m.max", "N·m")]
    found = key_figures(report, wanted)
    return (*found, KeyFigure("clashes found", "clashes", len(report.get("clashes", ())), ""))


def machine_page(design: Any, report: dict[str, Any]) -> Page:
    """The page of a machine ``design`` whose report is ``report`` (see the module docstring)."""
    phi = frame_angles()
    parts = sorted(poses.placed_parts(design, phi), key=lambda p: (p.low, p.high))
    named = poses.points(design, phi)
    every = np.concatenate([v for v in named.values()] + [p.shift for p in parts])
    scale = float(np.ptp(every, axis=0).max()) if len(every) else 100.0
    bodies = [_still(design, [named[t] for t in traced(design)])]
    bodies += [Body(p.name, (Outline(p.outline, _style(p)),), pose_motion(p.turn, p.shift)) for p in parts]
    bodies += [Body(g.name, (Outline(g.ends, "guide", False),)) for g in guides(design)]
    movers = tuple(Mover(n, xy[:, None, :], "pin" if n in traced(design) else "joint", 0.006 * max(scale, 1.0))
                   for n, xy in named.items())
    plots = tuple(Plot(label, unit, ((label, values),)) for label, (unit, values) in outputs_at(design, phi).items())
    spec = design.spec
    mounts = len(design.cams) + len(design.linkages) + len(design.cranked)
    subtitle = (f"{mounts} mechanism(s) on {len(spec.shafts)} shaft(s), one turn of the main shaft {spec.machine.main} "
                f"at {spec.machine.rpm:g} rpm; the timing diagram beneath, a row an output")
    notes = ("the timing diagram: each output against the main shaft's angle; its dwells and overlaps are in the "
             "report's timing and in the timing figure",
             "not drawn: the gears' teeth (their pitch circles are dashed) and the frame; parts behind the frame "
             "are orange")
    return Page(spec.name, f"{spec.name}: a machine", subtitle, "main shaft angle", "deg", np.degrees(phi),
                Scene(tuple(bodies), movers, precision=PRECISION), plots, _figures(design, report),
                tuple(report.get("warnings", ())), notes)
