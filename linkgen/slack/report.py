"""The report's ``slack`` section: the pins' fit, the band's widest places, where the linkage binds, and what the
Monte Carlo check found (mm and degrees; JSON-ready)."""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from linkgen.mechanisms.common import num
from linkgen.slack.band import OutputBand, SlackBand, TracerBand, refine_max, runs
from linkgen.slack.montecarlo import MonteCarlo
from linkgen.slack.table import SlackTable

METHOD = ("first order: the closure equations' Jacobians at each pose (one linear solve a pose), the worst case the "
          "sum of each slack times its sensitivity's size; checked by Monte Carlo samples solved by the linkage's "
          "own solver")
MODEL = ("each pin floats in its holes: its centre within the play (hole - pin) / 2 of each hole's centre, a "
         "slider's pin as far across its slot; each link's hole distances from its first hole within the length "
         "tolerance, a slot's line as far across its guide; a tracer on one link is that link's own point")


def slack_report(band: SlackBand, table: SlackTable, mc: MonteCarlo | None) -> dict[str, Any]:
    """The ``slack`` section of the report of ``band`` (with the ``[slack]`` table it was made from and its Monte
    Carlo check, if any)."""
    a, play = band.analysis, band.play
    unit = "deg" if a.crank else "mm"
    x = band.inputs
    keep = ~band.binds
    cyclic = bool(a.crank and abs(abs(x[-1] - x[0]) - 2 * math.pi) < 1e-9)
    out: dict[str, Any] = {
        "model": MODEL, "method": METHOD, "process": play.process, "pin_diameter_mm": play.pin,
        "hole_drawn_mm": num(play.drawn), "hole_made_mm": num(play.made), "measured": play.measured,
        "play_mm": num(play.radial), "length_tolerance_mm": table.length_tolerance,
        "link_tolerances_mm": {b: v for b, v in band.tolerances.items() if v != table.length_tolerance},
        "parameters": {"holes": len(band.model.holes), "slots": len(band.model.slots),
                       "lengths": len(band.model.lengths), "lines": len(band.model.lines)},
        f"analysed_{unit}": [round(math.degrees(v), 9) if a.crank else round(v, 9)
                             for v in (float(x[0]), float(x[-1]))],
        "samples": len(x),
    }
    out["tracers"] = {t.name: _tracer_row(band, t, keep, unit) for t in band.tracers
                      if (keep & np.isfinite(t.half_width)).any()}
    out["outputs"] = {o.name: _output_row(band, o, keep, unit) for o in band.outputs
                      if (keep & np.isfinite(o.half_width)).any()}
    binds, warnings = [], []
    n = len(x)
    for k, d in enumerate(band.dyads):
        for first, last in runs(d.binds, cyclic):
            lo = band.bind_edge(k, float(x[first]), float(x[first - 1])) if first > 0 and not d.binds[first - 1] \
                else float(x[first])
            hi = band.bind_edge(k, float(x[last]), float(x[last + 1])) if last < n - 1 and not d.binds[last + 1] \
                else float(x[last])
            span = [a.shown(lo), a.shown(hi)]
            binds.append({"kind": d.kind, "links": list(d.bodies), "joint": d.joint, f"input_{unit}": span})
            warnings.append(f"binds: dyad {'-'.join(d.bodies)} (joint {d.joint}) may reach its dead point "
                            f"(its links in line) within its slack from input {span[0]:.6g} to {span[1]:.6g} "
                            f"{'degrees' if a.crank else 'mm'}")
    out["binds"] = binds
    if mc is not None:
        out["monte_carlo"] = _monte_carlo_report(band, mc)
        if mc.outside:
            worst = max(mc.reach.values())
            warnings.append(f"Monte Carlo: {mc.outside} sample poses lie outside the first-order band (by up to "
                            f"{100 * (worst - 1):.3g} % of its half-width): second-order terms, the slack being "
                            "large against the links")
        if not band.reached.any():
            warnings.append("Monte Carlo: the linkage binds where it is drawn, so no pose is reached to compare; draw "
                            "it where it does not (for a dedicated mechanism: --angle)")
        if mc.assembled < mc.count:
            warnings.append(f"Monte Carlo: {mc.count - mc.assembled} of {mc.count} samples do not assemble")
    out["warnings"] = warnings
    return out


def _tracer_row(band: SlackBand, t: TracerBand, keep: np.ndarray, unit: str) -> dict[str, Any]:
    """A tracer's widest band across its path (refined among the samples ``keep``: where it does not bind), its
    mean width and its worst displacement in any direction, with where they are."""
    a, x = band.analysis, band.inputs

    def across(v: np.ndarray) -> np.ndarray:
        return next(b.half_width for b in band.at(v)[0] if b.name == t.name)

    at, half = refine_max(across, x, t.half_width, keep)
    point = a.linkage.solve(np.array([[at]]), strict=False, derivatives=False).points[t.name][0]
    i = int(np.argmax(np.where(keep, t.displacement, -np.inf)))
    return {"width_max_mm": num(2 * half), f"at_input_{unit}": a.shown(at), "x_mm": num(point[0]),
            "y_mm": num(point[1]), "width_mean_mm": num(2 * float(np.mean(t.half_width[keep]))),
            "displacement_max_mm": num(float(t.displacement[i])), f"displacement_at_input_{unit}": a.shown(float(x[i]))}


def _output_row(band: SlackBand, o: OutputBand, keep: np.ndarray, unit: str) -> dict[str, Any]:
    """An output's widest band (refined, among the samples ``keep``) and where, and how much its swing or stroke may
    change: the band at its two limits (sampled)."""
    a = band.analysis

    def half_width(v: np.ndarray) -> np.ndarray:
        return next(b.half_width for b in band.at(v)[1] if b.name == o.name)

    at, half = refine_max(half_width, band.inputs, o.half_width, keep)
    ends = [int(np.argmax(np.where(keep, o.value, -np.inf))), int(np.argmin(np.where(keep, o.value, np.inf)))]
    change = float(sum(o.half_width[i] for i in ends))
    scale, key = (math.degrees, "deg") if o.rocker else (float, "mm")
    return {f"band_max_{key}": num(scale(half)), f"at_input_{unit}": a.shown(at),
            f"{'swing' if o.rocker else 'stroke'}_change_{key}": num(scale(change))}


def _monte_carlo_report(band: SlackBand, mc: MonteCarlo) -> dict[str, Any]:
    units = {t.name: (1.0, "mm") for t in band.tracers}
    units.update({o.name: ((math.degrees(1.0), "deg") if o.rocker else (1.0, "mm")) for o in band.outputs})
    return {"count": mc.count, "seed": mc.seed, "assembled": mc.assembled, "compared_poses": mc.compared,
            "outside": mc.outside,
            "reach": {k: num(v) for k, v in mc.reach.items()},
            "second_order": {k: {f"max_{units[k][1]}": num(units[k][0] * v)} for k, v in mc.second_order.items()}}

