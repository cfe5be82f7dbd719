"""A cam design as files: the bundle of its cut drawing, printed solid, report and plots.

Names: ``<name>.dxf``, ``<name>-cut.svg`` (cut files, kerf applied), ``<name>.stl``,
``<name>.3mf`` (printed files, clearance applied), ``<name>.step`` (the printed part as an exact solid, only when
asked), ``<name>.json``,
``<name>-svaj.png|svg``, ``<name>-cam.png|svg`` (plots), ``<name>-construction.png|svg`` (the graphical
construction, with ``camgen build --construction``), ``<name>.html`` (the interactive page,
:mod:`camgen.page`). Only the formats the spec's
``output.formats`` asks for are made; nothing is written if any file fails.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from camgen.core.bundle import Bundle, mesh_files, part_files, solid_files, tail
from camgen.core.parts import Drawing, Part
from camgen.core.routing import add_routing
from camgen.core.writers import WriteOptions
from camgen.flat import FlatCamDesign
from camgen.profile import step_chords, step_part
from camgen.report import cam_report

#: chord tolerance (mm) of the outline drawn in a family's overview: a thumbnail an inch wide
THUMBNAIL_TOLERANCE_MM = 0.2


def cam_bundle(design: FlatCamDesign, with_kit: bool = False) -> tuple[Bundle, dict[str, Any]]:
    """The files of a disc or plate cam's ``design`` and its report, made but not written.

    Parameters
    ----------
    design : FlatCamDesign
        A design from :func:`camgen.api.design_cam`.
    with_kit : bool, optional
        Whether the kit round the cam its spec's ``[kit]`` describes (a disc cam's, :func:`camgen.kit.cam_kit`)
        joins the files and the report.

    Returns
    -------
    tuple
        The files ``output.formats`` asks for, each made when written, and the report without its ``files`` map
        (which the bundle adds).
    """
    mesh, mesh_check = printed_mesh(design.spec, design.printed)
    report = cam_report(design, mesh_check)

    def plot(kind: str) -> Any:
        from camgen import plots

        return {"svaj": plots.svaj_figure, "cam": plots.cam_figure, "checks": plots.checks_figure,
                "speeds": plots.speeds_figure}[kind](design)

    def page() -> Any:
        from camgen.page import cam_page

        return cam_page(design, report)

    kit = None
    if with_kit:
        from camgen.kit import cam_kit

        kit = cam_kit(design)
        report["kit"] = kit.report
    solid = step_solid(design, report) if "step" in design.spec.output.formats else design.printed
    tabled = design.speed is not None and design.speed.speeds is not None
    bundle = cam_files(design.spec, design.cut, mesh, plot, report, page,
                       ("svaj", "cam", "checks", *(("speeds",) if tabled else ())), solid)
    if kit is None:
        return bundle, report
    from camgen.core.kit import kit_items

    name = design.spec.name
    items = kit_items(name, kit.made, kit.drawing, kit.meshes, design.spec.output.formats,
                      f"{name}: the kit assembled at theta = 0, 90, 180 and 270 deg", kit.bom,
                      lambda: kit.placed(solid))
    return bundle.plus(items, design.spec.output.formats), report


def step_solid(design: FlatCamDesign, report: dict[str, Any]) -> Part:
    """The part the STEP file carries (its outline biarcs, see :func:`camgen.profile.step_part`); the report gains
    ``step_outline``: how it is made, its pieces and arcs, and its measured max error (mm) from the exact profile."""
    part, outline = step_part(design)
    contour = outline.contour
    report["step_outline"] = {"curves": "chords" if step_chords(design) else "biarcs", "pieces": len(contour.bulges),
                              "arcs": int(contour.n_arcs), "max_error_mm": float(outline.max_error_mm)}
    return part


def printed_mesh(spec: Any, printed: Part, name: str | None = None) -> tuple[Any, Any]:
    """The printed part as a checked solid named ``name`` (the spec's by default), and trimesh's check of it; (None,
    None) when ``spec.output.formats`` asks for no STL or 3MF. Raises :class:`ExportError` for a solid that is not
    closed and outward."""
    if not {"stl", "3mf"} & set(spec.output.formats):
        return None, None
    from camgen.core.solids import checked_mesh

    return checked_mesh(printed, spec.name if name is None else name)


def cam_files(spec: Any, cut: Part, mesh: Any, plot: Callable[[str], Any], report: dict[str, Any],
              page: Callable[[], Any] | None = None, figures: tuple[str, ...] = ("svaj", "cam"),
              printed: Part | None = None) -> Bundle:
    """The files of any cam kind, named as this module says: ``cut`` drawn as the cut files, ``mesh`` (or None)
    as the printed ones, ``plot(kind)`` for each of ``figures`` (made only if written), ``report``, ``page()`` (the
    interactive page, made only if written; none without it), ``printed`` (the printed part, or None) as the exact
    STEP solid; only the formats ``spec.output.formats`` asks for. With
    ``output.tool_radius`` the report gains the cut part's ``routing`` check (:mod:`camgen.core.routing`)."""
    out, name = spec.output, spec.name
    formats = out.formats
    add_routing(report, [cut], out.tool_radius)
    items = [part_files(Drawing.of_part(cut), name), mesh_files(mesh, name),
             solid_files(((name, (printed,)),) if printed is not None else None, name),
             *tail(name, plot, figures, report, page)]
    return Bundle.of(items, WriteOptions(out.dxf_version, out.dxf, out.text), formats)


def cam_row(design: Any, report: dict[str, Any], thumbnail: Callable[[float], np.ndarray]) -> dict[str, Any]:
    """A cam's family row (see :meth:`camgen.kinds.base.Kind.family_row`): its checks' figures from ``report``, its
    files and ``thumbnail(tolerance)`` (a closed ring in mm, drawn at :data:`THUMBNAIL_TOLERANCE_MM` or the design's
    tolerance if coarser); the bore drawn in it is the kind's :meth:`~camgen.kinds.base.Kind.thumbnail_bore`."""
    ring = thumbnail(max(design.tolerance, THUMBNAIL_TOLERANCE_MM))
    return {"pressure_angle_max_deg": report["pressure_angle_max_deg"],
            "profile_rho_min_mm": report.get("profile_rho_min_mm"), "undercut": report["undercut"],
            "outline_vertices": report.get("outline_vertices"), "outline_max_error_mm": report["outline_max_error_mm"],
            "files": " ".join(sorted(report["files"].values())), "thumbnail": ring.round(3).tolist()}
