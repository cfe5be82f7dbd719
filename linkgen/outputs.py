"""A linkage design as files: its report and figures, and with parts the cut sheet, assembly and meshes (a bundle).

Names: ``<name>.json`` (the report, with the parts section when there are parts), ``<name>-<kind>.png|svg`` (the
mechanism's figures), and with parts ``<name>-sheet.dxf|svg`` (the cut parts nested on one sheet;
``<name>-sheet-1.dxf|svg``, ``-sheet-2``, ... when they need several) and ``<name>-assembly.dxf|svg|png`` (cut
files, kerf applied; the SVGs are the ``cut-svg`` format), ``<name>-<part>.stl|3mf`` and ``<name>-pin.stl|3mf``
(printed), ``<name>.step`` (every printed part, a pin at each pivot point and the spacers as exact solids named
after them, as assembled; only when asked), ``<name>.html`` (the interactive page, for every linkage linkgen can
draw as a general one). Only the formats the spec's ``output.formats`` asks for are made; nothing is written if any
file fails. Everything written is computed by the design; meshes are made here from its printed parts.
"""
from __future__ import annotations

from functools import partial
from pathlib import Path
from typing import Any

from camgen.core.bundle import (
    Bundle, Item, animation_file, figure_files, mesh_files, page_file, report_file, sheet_files, solid_files,
    write_bundle)
from camgen.core.errors import SpecError
from camgen.core.kit import bom_item, placed_meshes
from camgen.core.nesting import sheet_kinds
from camgen.core.parts import Placed
from camgen.core.writers import DEFAULT_FORMATS, FIGURE_FORMATS, REGISTRY
from linkgen.linkage_design import LinkageDesign, design_linkage
from linkgen.kit import placed_solids
from linkgen.parts import LinkageBuild
from linkgen.spec import validate_spec

#: report keys every family's summary carries, where the mechanism reports them
SUMMARY_KEYS = ("grashof_class", "inversion", "transmission_min_deg", "transmission_max_deg", "time_ratio",
                "stroke_mm", "input_range_deg")


def default_frames(design: LinkageDesign) -> Any:
    """One cycle of ``design`` as ``linkgen animate`` draws it with its defaults (the ``gif`` of ``output.formats``):
    (frames, height, width, 3) uint8; a :class:`SpecError` for a linkage it does not animate."""
    from camgen.core.animation import DEFAULT_FRAMES, DEFAULT_SIZE
    from linkgen.animation import design_frames

    return design_frames(design, DEFAULT_FRAMES, DEFAULT_SIZE)


def linkage_bundle(design: LinkageDesign) -> Bundle:
    """The files of ``design`` that ``output.formats`` asks for: parts first (when built), then figures, then the
    report.

    Parameters
    ----------
    design : LinkageDesign
        A design from :func:`linkgen.linkage_design.design_linkage`.

    Returns
    -------
    Bundle
        The files, each made only when written (:func:`camgen.core.bundle.write_bundle`): the parts' sheet,
        assembly and solids (and a kit's), the figures, the JSON report and the page.

    Raises
    ------
    SpecError
        Naming ``output.formats``: ``"step"`` asked of a design made without parts.
    """
    spec = design.spec
    formats, name = spec.output.formats, spec.name
    report = linkage_report(design)
    items: list[Item | None] = []
    if design.build is None:
        _refuse_parts_formats(spec)
    if design.kit is not None:
        kit = design.kit
        items += _parts_items(name, kit.build, formats)
        items.append(mesh_files(lambda: placed_meshes(placed_solids(kit, kit.pose), 0), f"{name}-kit", "kit",
                                only=("3mf",)))
        items.append(bom_item(name, kit.bom))
    elif design.build is not None:
        items += _parts_items(name, design.build, formats)
    items += [figure_files(draw, f"{name}-{kind}", kind) for kind, draw in design.figures()]
    items.append(report_file(report, name))
    items.append(animation_file(partial(default_frames, design) if "gif" in formats else None, name))
    items.append(page_file(design.page(report) if "html" in formats else None, name))
    return Bundle.of(items, spec.output.write_options, formats)


def linkage_report(design: LinkageDesign) -> dict[str, Any]:
    """The report of ``design`` as ``<name>.json`` holds it but for its ``files``: the design's, then its parts'
    section (and its kit's) when it has parts."""
    if design.kit is not None:
        return {**design.report, **design.kit.build.report, "kit": design.kit.report}
    if design.build is not None:
        return {**design.report, **design.build.report}
    return design.report


def write_linkage(design: LinkageDesign, directory: str | Path) -> dict[str, str]:
    """Write the files of ``design`` into ``directory``, all or nothing.

    Parameters
    ----------
    design : LinkageDesign
        A design from :func:`linkgen.linkage_design.design_linkage`.
    directory : str or Path
        The folder to write into (made if missing).

    Returns
    -------
    dict of str
        The names of the files written, by key (``"json"``, ``"html"``, ``"sheet_dxf"``, ...).

    Raises
    ------
    SpecError
        ``output.formats`` asks for parts' files (``"step"``, ``"stl"``) of a design made without parts.
    ExportError
        A file could not be written.
    """
    return write_bundle(linkage_bundle(design), directory)


#: the roles of a format that writes parts (a part's or sheet's drawing, a mesh, solids)
_PART_ROLES = {"part", "sheet", "mesh", "solids"}


def _refuse_parts_formats(spec: Any) -> None:
    """Refuse, naming ``output.formats``, a parts' format asked of a design made without parts (``linkgen analyze``,
    or a template without ``[parts]``): STEP whenever it is named, DXF, cut SVG, STL and 3MF when the template or
    ``--set`` names them in a list other than the default (which has them: a design without parts then just writes
    none; ``--figures`` adds the figures to it)."""
    formats = spec.output.formats
    named = set(formats) - set(FIGURE_FORMATS) != set(DEFAULT_FORMATS) - set(FIGURE_FORMATS)
    asked = [f for f in formats if f in REGISTRY and set(REGISTRY[f].files) & _PART_ROLES and (named or f == "step")]
    if asked:
        names = ", ".join(f"'{f}'" for f in asked)
        verb = "writes" if len(asked) == 1 else "write"
        raise SpecError(f"{names} {verb} the linkage's parts, which `linkgen build` makes from the [parts] table; "
                        f"leave {names} out here", "output.formats")


def _parts_items(name: str, build: LinkageBuild, formats: Any) -> list[Item | None]:
    """Sheet and assembly drawings, the assembly as a figure, a mesh a printed part and an optional pin."""
    table = build.table
    items = [sheet_files(drawing, f"{name}-{kind}", kind)
             for kind, drawing in (*sheet_kinds(build.sheets), ("assembly", build.assembly))]

    def assembly_figure() -> Any:
        from camgen.core.figures import drawing_figure

        return drawing_figure(build.assembly, f"{name}: assembly at the dead centres, with the path")

    items.append(figure_files(assembly_figure, f"{name}-assembly", "assembly", only=("png",)))
    items.append(solid_files(_step_solids(build), name))
    if {"stl", "3mf"} & set(formats):
        from camgen.core.solids import closed, extrude, pin, spacer

        meshes = [(part.name, extrude(part)) for part in build.printed]
        if table.pins:
            top = max(build.layers.values()) + 1
            foot = build.allowances.elephant_foot
            meshes.append(("pin", pin(table.pin_diameter, top * table.thickness + 1.0, table.tolerance, foot)))
            inner, outer = build.spacer_diameters
            for run in sorted({run for _, _, run, _ in build.spacers}):
                meshes.append((f"spacer-{run}",
                               spacer(inner, outer, run * table.thickness, table.tolerance, foot)))
        names = [part_name for part_name, _ in meshes]
        for part_name in {n for n in names if names.count(n) > 1}:
            raise SpecError(f"a part named {part_name!r} would share its files with the printable {part_name}; "
                            "rename its link or slider", "parts.pins")
        for part_name, mesh in meshes:
            closed(mesh, f"{name}-{part_name}")
            items.append(mesh_files(mesh, f"{name}-{part_name}", part_name))
    return items


def _step_solids(build: LinkageBuild) -> tuple[Placed, ...]:
    """The STEP file's solids (see :mod:`camgen.core.writers.step`), as assembled at the first dead centre the
    assembly drawing shows (its ``DC1-...`` layer; the motion's first pose where it shows none): every printed part
    turned and moved as drawn there, standing at its layer's height (layer x thickness); with pins, a pin at every
    pivot point (``pin-<joint>``: its shank, as long as the stack of layers and 1 mm more, under a head 1.8 x as
    wide and half a diameter high, the head resting on the highest part it joins) and a spacer on each run of empty
    layers a pin crosses (``spacer-<joint>-<layer>``, from that layer up), the shapes of their meshes as exact discs
    and rings."""
    from camgen.core.kit import disc

    table, pose = build.table, build.pose
    t = table.thickness

    def at(joint: str) -> tuple[float, float]:
        x, y = pose.joints[joint][1][0]
        return float(x), float(y)

    solids = [Placed(part.name, (part,), float(pose.angles[part.name][0]),
                     (*(float(v) for v in pose.origins[part.name][0]), build.layers[part.name] * t))
              for part in build.printed]
    if table.pins:
        d, tol = table.pin_diameter, table.tolerance
        length = (max(build.layers.values()) + 1) * t + 1.0
        pin = (disc("pin", d, 0.0, length, tol).part(0.0, 0.0),
               disc("pin-head", 1.8 * d, 0.0, d / 2, tol).part(0.0, 0.0))
        for pivot in build.pivots:
            joint = pivot.joints[0]
            solids.append(Placed(f"pin-{joint}", pin, 0.0, (*at(joint), (pivot.high + 1) * t - length)))
        inner, outer = build.spacer_diameters
        for joint, _, run, first in build.spacers:
            ring = disc(f"spacer-{joint}-{first}", outer, inner, run * t, tol).part(0.0, 0.0)
            solids.append(Placed(ring.name, (ring,), 0.0, (*at(joint), first * t)))
    return tuple(solids)


def build_member(raw: dict, folder: Path) -> dict[str, Any]:
    """Design one family member (with its parts when it has a [parts] table) into ``folder``; its summary row."""
    spec = validate_spec(raw)
    design = design_linkage(spec, parts=spec.parts is not None)
    files = write_linkage(design, folder)
    row = {**{k: design.report[k] for k in SUMMARY_KEYS if k in design.report},
           "files": " ".join(sorted(files.values()))}
    return {**row, **design.family_row()}
