"""A drag's preview of a general linkage, fast enough to follow the pointer: the scene of
:func:`camgen.designer.views.linkage_scene` from the linkage's analysis alone, without its report. The positions,
coupler curves, toggles and the transmission at the angle are the report's own (the same functions on the same
analysis); only each dyad's transmission extremes are taken at the analysed samples instead of refined between
them (the refinement is most of a report's time). The released drag answers the whole design, as ``linkgen
analyze`` gives it."""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.designer.views import scene_of


def _extreme(values: np.ndarray, inputs: np.ndarray, pick: Any) -> tuple[float, float]:
    """The least (``pick`` = np.nanargmin) or greatest transmission angle of ``values`` (rad) over the samples and
    the input value there; NaN, NaN where no sample closes."""
    finite = np.isfinite(values)
    if not finite.any():
        return math.nan, math.nan
    k = int(pick(np.where(finite, values, np.nan)))
    return float(values[k]), float(inputs[k])


def sampled_dyads(a: Any) -> list[dict[str, Any]]:
    """Each dyad of the analysis ``a`` as the report lists it (``dyads``), its transmission extremes (degrees) and
    the inputs where they fall taken at the samples of the motion analysed (the report refines them between)."""
    from linkgen.kinematics.groups import GROUP_KINDS
    from linkgen.mechanisms.common import num

    unit = "deg" if a.crank else "mm"
    travel = a.travel
    inputs = np.asarray(travel.inputs[0], dtype=float).reshape(-1)
    out: list[dict[str, Any]] = []
    for d in travel.dyads:
        values = np.asarray(d.transmission, dtype=float).reshape(-1)
        (gmin, at_min), (gmax, at_max) = _extreme(values, inputs, np.nanargmin), _extreme(values, inputs, np.nanargmax)
        row: dict[str, Any] = {"kind": d.kind, "links": list(d.bodies), "joint": d.joint}
        if d.kind in GROUP_KINDS:
            row.update(conditioning_min=num(math.sin(gmin)), conditioning_max=num(math.sin(gmax)))
        else:
            row.update({"transmission_min_deg": num(math.degrees(gmin)),
                        f"transmission_min_at_{unit}": None if math.isnan(at_min) else a.shown(at_min),
                        "transmission_max_deg": num(math.degrees(gmax)),
                        f"transmission_max_at_{unit}": None if math.isnan(at_max) else a.shown(at_max)})
        out.append(row)
    return out


def quick_scene(spec: Any, angle: float) -> dict[str, Any] | None:
    """The preview scene of the validated linkage ``spec`` at the input ``angle`` (degrees; mm for a slide), its
    ``refined`` False; None where it is not a general linkage with one input (the caller designs it whole).

    Raises
    ------
    SpecError
        As :func:`linkgen.api.design` refuses the linkage's kinematics (a structure that does not solve ...).
    """
    from linkgen.mechanisms.general import positions

    table = spec.linkage
    if getattr(table, "type", None) != "linkage" or len(table.inputs) != 1:
        return None
    a = spec.mechanism.build(table)
    unit = "deg" if a.crank else "mm"
    toggles = [{"kind": t.kind, f"input_{unit}": a.shown(t.value), "links": list(t.bodies), "joint": t.joint}
               for t in a.toggles]
    return scene_of(a, table, angle, positions(table, a, angle), toggles, sampled_dyads(a), refined=False)
