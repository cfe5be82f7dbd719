"""A Geneva drive as files: each part's cut drawing, the printed wheel and driver, the report and the plots.

Names: ``<name>-wheel.dxf``, ``<name>-lock.dxf``, ``<name>-crank.dxf`` and their ``-cut.svg`` (cut files, kerf
applied); ``<name>-wheel.stl|3mf`` and ``<name>-driver.stl|3mf`` (the crank with the locking disc on top, one
solid; clearance applied); ``<name>.step`` when asked (both as assembled, :func:`step_solids`); ``<name>.json``;
``<name>-motion.png|svg`` and ``<name>-assembly.png|svg``; ``<name>.html`` (the interactive page).
Only the formats ``output.formats`` asks for are made; nothing is written if any file fails.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.core.bundle import Bundle, mesh_files, part_files, sheet_files, solid_files, tail
from camgen.core.errors import ExportError
from camgen.core.nesting import SheetRules, nest, sheet_kinds
from camgen.core.parts import Drawing, Placed
from camgen.core.routing import add_routing
from camgen.kinds.geneva.design import PARTS, GenevaDesign
from camgen.kinds.geneva.page import geneva_page
from camgen.kinds.geneva.report import geneva_report


def _solids(design: GenevaDesign) -> dict[str, Any]:
    """The printed wheel and driver as checked meshes: {name: (mesh, its checks)}."""
    from camgen.core.solids import check_mesh, extrude, stack, volume_check

    printed = design.printed
    pieces = {"wheel": [printed["wheel"]], "driver": [printed["crank"], printed["lock"]]}
    out = {}
    for name, parts in pieces.items():
        mesh = extrude(parts[0]) if len(parts) == 1 else stack(parts, f"{design.spec.name}-driver")
        check = check_mesh(mesh)
        if not check.ok:
            raise ExportError(f"{mesh.name}: the mesh is not a closed outward solid ({check})")
        out[name] = (mesh, {"watertight": check.watertight, "winding_consistent": check.winding_consistent,
                            "volume_mm3": check.volume_mm3, "triangles": check.triangles, "bodies": check.bodies,
                            **volume_check(parts, check.volume_mm3)})
    return out


def geneva_bundle(design: GenevaDesign) -> tuple[Bundle, dict[str, Any]]:
    """The files of a Geneva drive and its report (without the ``files`` map, which the bundle adds)."""
    out = design.spec.output
    formats, name = out.formats, design.spec.name
    solids = _solids(design) if {"stl", "3mf"} & set(formats) else {}
    report = geneva_report(design, {k: v[1] for k, v in solids.items()})
    add_routing(report, [design.cut[part] for part in PARTS], out.tool_radius)
    nested = nest(tuple(design.cut[part] for part in PARTS), SheetRules.of(out, out.kerf, "output.sheet"))
    report["sheet"] = nested.report

    def plot(kind: str) -> Any:
        from camgen.kinds.geneva import plots

        return plots.motion_figure(design) if kind == "motion" else plots.assembly_figure(design)

    items = [part_files(Drawing.of_part(design.cut[part]), f"{name}-{part}", part) for part in PARTS]
    items += [sheet_files(drawing, f"{name}-{kind}", kind) for kind, drawing in sheet_kinds(nested.drawings(
        out.tolerance))]
    items += [mesh_files(mesh, f"{name}-{solid}", solid) for solid, (mesh, _) in solids.items()]
    items.append(solid_files(lambda: step_solids(design), name))
    items += tail(name, plot, ("motion", "assembly"), report, lambda: geneva_page(design, report))
    return Bundle.of(items, out.write_options, formats), report


def step_solids(design: GenevaDesign) -> tuple[Placed, Placed]:
    """The STEP file's two solids as assembled in the middle of the dwell (driver angle alpha = 180 degrees, the
    locking disc holding the wheel, as the assembly figure's third panel): the driver (``<name>-driver``, the crank
    with the locking disc on top) on its axis at the origin, turned by alpha; the wheel (``<name>-wheel``) on its
    axis at (centre distance, 0), turned by 180 degrees - beta (its angle at alpha) and standing on the crank, in the
    locking disc's plane."""
    g, printed, name = design.geometry, design.printed, design.spec.name
    alpha = math.pi
    beta = float(g.law.motion(np.array([alpha]))[0, 0])
    return (Placed(f"{name}-wheel", (printed["wheel"],), math.pi - beta,
                   (g.centre_distance, 0.0, printed["crank"].thickness)),
            Placed(f"{name}-driver", (printed["crank"], printed["lock"]), alpha))


#: chord tolerance (mm) of the wheel drawn in a family's overview: a thumbnail an inch wide
THUMBNAIL_TOLERANCE_MM = 0.2


def geneva_row(design: GenevaDesign, report: dict[str, Any]) -> dict[str, Any]:
    """A family member's summary row: the key figures, its files and the wheel as a thumbnail."""
    m, a = report["motion"], report["assembly"]
    ring = design.parts["wheel"].outline.flatten(max(design.tolerance, THUMBNAIL_TOLERANCE_MM))
    return {"velocity_ratio_max": m["velocity_ratio_max"], "acceleration_ratio_max": m["acceleration_ratio_max"],
            "lock_clearance_min_mm": a["lock_clearance_min_mm"], "pin_clearance_min_mm": a["pin_clearance_min_mm"],
            "files": " ".join(sorted(report["files"].values())), "thumbnail": ring.round(3).tolist()}
