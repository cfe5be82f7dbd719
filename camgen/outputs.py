"""Write a cam design's files: DXF, STL, JSON report and plots, all-or-nothing."""
from __future__ import annotations

from pathlib import Path
from typing import Any

from camgen.design import CamDesign
from camgen.errors import ExportError
from camgen.parts.drawing import Drawing
from camgen.parts.files import staged
from camgen.report import cam_report, report_json


def write_cam(design: CamDesign, directory: str | Path) -> dict[str, Any]:
    """Write the files the template's ``output.formats`` asks for into ``directory``; return the report.

    Names: ``<name>.dxf``, ``<name>-cut.svg`` (cut files, kerf applied), ``<name>.stl``,
    ``<name>.3mf`` (printed files, clearance applied), ``<name>.json``,
    ``<name>-svaj.png|svg``, ``<name>-cam.png|svg`` (plots). Nothing is left behind if any fails.
    """
    formats = set(design.template.output.formats)
    name = design.template.name
    files: dict[str, str] = {}
    mesh_check = None
    with staged(directory) as stage:
        out = design.template.output
        cut_drawing = Drawing.of_part(design.cut[1])
        if "dxf" in formats:
            from camgen.parts.dxf import write_dxf

            files["dxf"] = stage.write(f"{name}.dxf", lambda p: write_dxf(
                cut_drawing, p, out.dxf_version, out.dxf, out.tolerance)).name
        if "cut-svg" in formats:
            from camgen.parts.svg import svg_document

            files["cut_svg"] = stage.write(f"{name}-cut.svg", lambda p: p.write_text(
                svg_document(cut_drawing), encoding="utf-8")).name
        if formats & {"stl", "3mf"}:
            from camgen.parts.mesh import extrude
            from camgen.parts.stl import check_mesh, stl_bytes

            mesh = extrude(design.printed)
            mesh_check = check_mesh(mesh)
            if not mesh_check.ok:
                raise ExportError(f"{name}: the mesh is not a closed outward solid ({mesh_check})")
            if "stl" in formats:
                files["stl"] = stage.write_bytes(f"{name}.stl", stl_bytes(mesh)).name
            if "3mf" in formats:
                from camgen.parts.threemf import threemf_bytes

                files["3mf"] = stage.write_bytes(f"{name}.3mf", threemf_bytes(mesh)).name
        plot_formats = [f for f in ("png", "svg") if f in formats]
        if plot_formats:
            from camgen.plots import cam_figure, save, svaj_figure

            for kind, make in (("svaj", svaj_figure), ("cam", cam_figure)):
                fig = make(design)
                for fmt in plot_formats:
                    files[f"{kind}_{fmt}"] = stage.write(
                        f"{name}-{kind}.{fmt}", lambda p, fig=fig, fmt=fmt: save(fig, p, fmt)).name
        report = cam_report(design, mesh_check, files)
        if "json" in formats:
            files["json"] = f"{name}.json"
            report["files"] = dict(files)
            stage.write(f"{name}.json", lambda p: p.write_text(report_json(report), encoding="utf-8"))
    return report


def build_member(raw: dict, folder: Path) -> dict[str, Any]:
    """Build one family member from its raw template into ``folder``; its summary figures and a thumbnail."""
    from camgen.design import design_cam
    from camgen.spec import validate_template

    design = design_cam(validate_template(raw))
    report = write_cam(design, folder)
    ring = design.outline.contour.flatten(max(design.template.output.tolerance, 0.2))
    return {"pressure_angle_max_deg": report["pressure_angle_max_deg"],
            "profile_rho_min_mm": report["profile_rho_min_mm"], "undercut": report["undercut"],
            "outline_vertices": report["outline_vertices"], "outline_max_error_mm": report["outline_max_error_mm"],
            "files": " ".join(sorted(report["files"].values())), "thumbnail": ring.round(3).tolist()}
