"""Write a linkage analysis: the JSON report and the plots, all-or-nothing (see camgen.parts.files)."""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from camgen.errors import ExportError
from camgen.parts.files import staged
from camgen.report import report_json
from linkgen.analyze import build_linkage
from linkgen.fourbar import FourBar


def write_analysis(template: Any, report: dict[str, Any], directory: str | Path,
                   build: Any = None) -> dict[str, str]:
    """Write the files ``output.formats`` asks for (with ``build``, the parts too); return their names by kind."""
    formats = set(template.output.formats)
    name, spec = template.name, template.linkage
    files: dict[str, str] = {}
    with staged(directory) as stage:
        if build is not None:
            report = {**report, **_write_parts(stage, template, build, formats, files)}
        plots = [f for f in ("png", "svg") if f in formats]
        if plots:
            from camgen.plots import save
            from linkgen import plots as lp

            mech = build_linkage(spec)
            fb = mech if isinstance(mech, FourBar) else getattr(mech, "linkage", None)
            assembly = getattr(spec, "assembly", getattr(mech, "assembly", "open"))
            if fb is not None:
                figures = {"transmission": lp.transmission_figure(name, fb, assembly),
                           "dead-centres": lp.dead_centre_figure(name, fb, assembly)}
            else:
                figures = {"motion": lp.slider_figure(name, mech, spec.rpm * 2 * math.pi / 60)}
            for kind, fig in figures.items():
                for fmt in plots:
                    files[f"{kind}_{fmt}"] = stage.write(
                        f"{name}-{kind}.{fmt}", lambda p, fig=fig, fmt=fmt: save(fig, p, fmt)).name
        if "json" in formats:
            files["json"] = f"{name}.json"
            stage.write(f"{name}.json", lambda p: p.write_text(report_json({**report, "files": files}),
                                                                  encoding="utf-8"))
    return files


def _write_parts(stage: Any, template: Any, build: Any, formats: set, files: dict[str, str]) -> dict[str, Any]:
    """Sheet and assembly drawings, a mesh per part, an optional pin; returns the report's parts section."""
    from camgen.parts.dxf import write_dxf
    from camgen.parts.svg import svg_document

    name, table = template.name, template.parts
    tol = table.tolerance
    for kind, drawing in (("sheet", build.sheet), ("assembly", build.assembly)):
        if "dxf" in formats:
            files[f"{kind}_dxf"] = stage.write(f"{name}-{kind}.dxf", lambda p, d=drawing: write_dxf(
                d, p, tolerance=tol)).name
        if "svg" in formats:
            files[f"{kind}_svg"] = stage.write(f"{name}-{kind}.svg", lambda p, d=drawing: p.write_text(
                svg_document(d), encoding="utf-8")).name
    if "png" in formats:
        from camgen.plots import drawing_figure, save

        fig = drawing_figure(build.assembly, f"{name}: assembly at the dead centres, with the path")
        files["assembly_png"] = stage.write(f"{name}-assembly.png", lambda p: save(fig, p, "png")).name
    parts_report = []
    if formats & {"stl", "3mf"}:
        from camgen.parts.mesh import extrude, pin
        from camgen.parts.stl import check_mesh, stl_bytes
        from camgen.parts.threemf import threemf_bytes

        meshes = [(part.name, extrude(part)) for part in build.printed]
        if table.pins:
            top = max(build.layers.values()) + 1
            meshes.append(("pin", pin(table.pin_diameter, top * table.thickness + 1.0, tol)))
        for part_name, mesh in meshes:
            check = check_mesh(mesh)
            if not check.ok:
                raise ExportError(f"{name}-{part_name}: the mesh is not a closed outward solid")
            if "stl" in formats:
                files[f"{part_name}_stl"] = stage.write_bytes(f"{name}-{part_name}.stl", stl_bytes(mesh)).name
            if "3mf" in formats:
                files[f"{part_name}_3mf"] = stage.write_bytes(f"{name}-{part_name}.3mf", threemf_bytes(mesh)).name
    spec = build.spec
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
    return {"parts": parts_report, "layer_order": order, "layers": dict(build.layers),
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
    import math

    from linkgen.analyze import build_linkage
    from linkgen.fourbar import FourBar

    mech = build_linkage(spec.linkage)
    fb = mech if isinstance(mech, FourBar) else getattr(mech, "linkage", None)
    if fb is None:
        return {}
    ranges = fb.input_ranges()
    lo, hi = (0.0, 2 * math.pi) if ranges is None else ranges[0]
    poses = fb.sweep(np.linspace(lo, hi, 121), getattr(spec.linkage, "assembly", getattr(mech, "assembly", "open")))
    path = poses.point if fb.point_distance > 0 else poses.b
    return {"thumbnail": path.round(3).tolist(), "thumbnail_kind": "path"}
