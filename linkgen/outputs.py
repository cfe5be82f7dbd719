"""A linkage as files: the report and plots, and with parts the cut sheet, assembly and meshes (a bundle)."""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from camgen.core.bundle import Bundle, Report, item, write_bundle
from camgen.core.errors import ExportError
from linkgen.analyze import build_linkage
from linkgen.fourbar import FourBar


def linkage_bundle(template: Any, report: dict[str, Any], build: Any = None) -> Bundle:
    """The files ``output.formats`` asks for (with ``build``, the parts too)."""
    formats = template.output.formats
    name, spec = template.name, template.linkage
    items: list = []
    if build is not None:
        parts_items, parts_report = _parts_items(template, build, formats)
        items += parts_items
        report = {**report, **parts_report}
    mech = build_linkage(spec)
    fb = mech if isinstance(mech, FourBar) else getattr(mech, "linkage", None)
    assembly = getattr(spec, "assembly", getattr(mech, "assembly", "open"))

    def plot(kind: str) -> Any:
        from linkgen import plots as lp

        if kind == "transmission":
            return lp.transmission_figure(name, fb, assembly)
        if kind == "dead-centres":
            return lp.dead_centre_figure(name, fb, assembly)
        return lp.slider_figure(name, mech, spec.rpm * 2 * math.pi / 60)

    kinds = ("transmission", "dead-centres") if fb is not None else ("motion",)
    items += [item(lambda kind=kind: plot(kind), [("png", f"{kind}_png", f"{name}-{kind}.png"),
                                                  ("svg", f"{kind}_svg", f"{name}-{kind}.svg")], formats)
              for kind in kinds]
    items.append(item(Report(report), [("json", "json", f"{name}.json")], formats))
    return Bundle.of(items)


def write_analysis(template: Any, report: dict[str, Any], directory: str | Path,
                   build: Any = None) -> dict[str, str]:
    """Write the files ``output.formats`` asks for (with ``build``, the parts too); return their names by key."""
    return write_bundle(linkage_bundle(template, report, build), directory)


def _parts_items(template: Any, build: Any, formats: Any) -> tuple[list, dict[str, Any]]:
    """Sheet and assembly drawings, a mesh per part, an optional pin; and the report's parts section."""
    name, table = template.name, template.parts
    tol = table.tolerance
    items: list = []
    for kind, drawing in (("sheet", build.sheet), ("assembly", build.assembly)):
        items.append(item(drawing, [("dxf", f"{kind}_dxf", f"{name}-{kind}.dxf"),
                                    ("cut-svg", f"{kind}_svg", f"{name}-{kind}.svg")], formats))

    def assembly_figure() -> Any:
        from camgen.core.figures import drawing_figure

        return drawing_figure(build.assembly, f"{name}: assembly at the dead centres, with the path")

    items.append(item(assembly_figure, [("png", "assembly_png", f"{name}-assembly.png")], formats))
    if {"stl", "3mf"} & set(formats):
        from camgen.core.solids import check_mesh, extrude, pin

        meshes = [(part.name, extrude(part)) for part in build.printed]
        if table.pins:
            top = max(build.layers.values()) + 1
            meshes.append(("pin", pin(table.pin_diameter, top * table.thickness + 1.0, tol)))
        for part_name, mesh in meshes:
            if not check_mesh(mesh).ok:
                raise ExportError(f"{name}-{part_name}: the mesh is not a closed outward solid")
            items.append(item(mesh, [("stl", f"{part_name}_stl", f"{name}-{part_name}.stl"),
                                     ("3mf", f"{part_name}_3mf", f"{name}-{part_name}.3mf")], formats))
    spec = build.spec
    parts_report = []
    for link in build.parts:
        holes = [{"x_mm": round(c[0], 9), "y_mm": round(c[1], 9)} for c in link.centres]
        entry = {"name": link.name, "layer": build.layers[link.name], "holes": holes,
                 "width_mm": 2 * link.half_width, "thickness_mm": spec.thickness,
                 "cut_hole_diameter_mm": spec.pin_diameter + spec.clearance - spec.kerf,
                 "printed_hole_diameter_mm": spec.pin_diameter + spec.clearance}
        if len(link.centres) >= 2:
            entry["hole_distance_mm"] = float(np.linalg.norm(link.centres[1] - link.centres[0]))
        parts_report.append(entry)
    order = sorted(build.layers, key=lambda k: build.layers[k])
    return items, {"parts": parts_report, "layer_order": order, "layers": dict(build.layers),
                   "allowances": {"kerf_mm": spec.kerf, "clearance_mm": spec.clearance,
                                  "cut_holes": "pin + clearance - kerf", "cut_outlines": "grown by kerf / 2",
                                  "printed_holes": "pin + clearance"},
                   "assembly_layers": [f"DC{i + 1}-{k}" for i, (k, _) in enumerate(build.positions)]}


def build_member(raw: dict, folder: Path) -> dict[str, Any]:
    """Analyse one family member (and make its parts when it has a [parts] table) into ``folder``."""
    from linkgen.analyze import analyze
    from linkgen.build import build_parts
    from linkgen.spec import validate_linkage

    spec = validate_linkage(raw)
    report = analyze(spec)
    built = build_parts(spec) if spec.parts is not None else None
    files = write_analysis(spec, report, folder, built)
    keep = ("grashof_class", "inversion", "transmission_min_deg", "transmission_max_deg", "time_ratio",
            "stroke_mm", "input_range_deg")
    row = {**{k: report[k] for k in keep if k in report}, "files": " ".join(sorted(files.values()))}
    if "straightness" in report:
        row["straightness_error_mm"] = report["straightness"]["error_mm"]
    return {**row, **_thumbnail(spec)}


def _thumbnail(spec: Any) -> dict[str, Any]:
    """The path a four-bar's coupler point (or rocker pin) traces, for the family's overview picture."""
    mech = build_linkage(spec.linkage)
    fb = mech if isinstance(mech, FourBar) else getattr(mech, "linkage", None)
    if fb is None:
        return {}
    ranges = fb.input_ranges()
    lo, hi = (0.0, 2 * math.pi) if ranges is None else ranges[0]
    poses = fb.sweep(np.linspace(lo, hi, 121), getattr(spec.linkage, "assembly", getattr(mech, "assembly", "open")))
    path = poses.point if fb.point_distance > 0 else poses.b
    return {"thumbnail": path.round(3).tolist(), "thumbnail_kind": "path"}
