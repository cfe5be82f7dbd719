"""What the designer draws of a design, computed by the project's own code: a linkage's scene at an input angle
(from :func:`linkgen.api.design`'s report and its kinematics), the interactive page of a cam or a linkage."""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.bundle import with_formats

#: the samples of a tracer's path over the analysed input (its coupler curve)
PATH_SAMPLES = 181


def page(design: Any) -> str | None:
    """The design's interactive page (S-V-A-J, pressure angle, curvature and profile of a cam; motion, speeds and
    transmission angles of a linkage) as an ``<iframe>``, the html format added where ``output.formats`` leaves it
    out; None for a design that has none."""
    shown: str | None = design._repr_html_()
    if shown is None and "html" not in design.spec.output.formats:
        shown = with_formats(design, [*design.spec.output.formats, "html"])._repr_html_()
    return shown


def drawn_angle(design: Any) -> float:
    """The input's value (degrees; mm for a slide) in the template's drawing: where its analysis starts."""
    analysed = design.report.get("analysed_deg") or design.report.get("analysed_mm")
    return float(analysed[0]) if analysed else 0.0


def linkage_scene(design: Any) -> dict[str, Any] | None:
    """A general linkage (``type = "linkage"``) at ``design.angle``, for the designer to draw and drag.

    Returns
    -------
    dict or None
        ``joints`` {name: [x, y] mm} where the report's positions put them (rounded as the report rounds them, to
        1e-9 mm), ``drawn`` the template's drawing, ``ground``, ``links`` {name: [joints]}, ``paths`` {tracer: [[x,
        y], ...]} over the analysed input (NaN-free: poses that do not close left out), ``transmission`` each
        dyad's transmission angle (degrees) at the angle, the report's ``toggles`` and ``dyads``, ``angle``,
        ``drawn_angle``, ``span`` [from, to], ``crank`` (True: degrees; False: a slide's mm) and ``refined`` (True:
        the dyads' extremes are the report's, refined between samples). None for a mechanism that is not a general
        linkage (its page still shows it).
    """
    a = design.kinematics
    table = design.spec.linkage
    if getattr(table, "type", None) != "linkage" or not hasattr(a, "linkage"):
        return None
    report = design.report
    return scene_of(a, table, design.angle, report["positions"], report.get("toggles", []),
                    report.get("dyads", []), refined=True)


def scene_of(a: Any, table: Any, angle: float, shown: dict[str, Any], toggles: list[dict[str, Any]],
             dyads: list[dict[str, Any]], refined: bool) -> dict[str, Any]:
    """The scene of :func:`linkage_scene` of the general linkage's analysis ``a`` (its ``table``) at the input
    ``angle`` (degrees; mm for a slide), ``shown`` its positions there as the report gives them
    (:func:`linkgen.mechanisms.general.positions`), ``toggles`` and ``dyads`` as the report lists them (``refined``
    False: the dyads' extremes only at the analysed samples)."""
    lo, hi = float(a.span[0, 0]), float(a.span[0, -1])
    sol = a.linkage.solve(np.linspace(lo, hi, PATH_SAMPLES)[None, :])
    ok = np.asarray(sol.ok, dtype=bool).reshape(-1)
    paths = {t: np.asarray(sol.points[t], dtype=float)[ok].round(6).tolist() for t in table.tracers}
    value = math.radians(angle) if a.crank else angle
    here = a.linkage.solve(np.array([[value]], dtype=float))
    transmission = [{"joint": d.joint, "links": list(d.bodies),
                     "deg": round(math.degrees(float(np.asarray(d.transmission).reshape(-1)[0])), 9)}
                    for d in here.dyads]
    span = [math.degrees(lo), math.degrees(hi)] if a.crank else [lo, hi]
    start = round(math.degrees(lo), 9) if a.crank else round(lo, 9)
    return {"joints": {p: [j["x_mm"], j["y_mm"]] for p, j in shown["joints"].items()},
            "drawn": {p: list(xy) for p, xy in table.joints.items()},
            "ground": list(table.ground), "links": {k: list(v) for k, v in table.links.items()},
            "paths": paths, "transmission": transmission, "toggles": toggles, "dyads": dyads, "angle": angle,
            "drawn_angle": start, "span": span, "crank": bool(a.crank), "refined": refined}
