"""A machine as files: each cam's and each linkage's own files (their kinds' bundles, named
``<machine>-<mount>...`` beside the machine's, or in a sub-folder ``<mount>/`` each with ``output.folders``, their
report keys under ``<mount>.``), the timing diagram
(``<name>-timing.png|svg`` and ``<name>-timing.csv``) and the machine's report ``<name>.json``. Only the formats
``output.formats`` asks for are made; nothing is written if any file fails.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from camgen.core.bundle import Bundle, Entry, Item, Report, item, mesh_files, solid_files
from camgen.kinds import spec_kind
from camgen.kinds.machine.design import MachineDesign
from camgen.kinds.machine.report import machine_report, timing_rows
from linkgen import api as linkgen_api


@dataclass(frozen=True)
class Scoped:
    """A sub-bundle's payload that names its bundle's files (a report): given the machine's ``files`` map, it
    sees only its own, their keys without the mount's ``prefix``."""

    payload: Any
    prefix: str
    folder: str = ""

    def with_files(self, files: dict[str, str]) -> Any:
        own = {k.removeprefix(self.prefix): v.removeprefix(self.folder) for k, v in files.items()
               if k.startswith(self.prefix)}
        return self.payload.with_files(own)


def _scoped(items: tuple[Item, ...], mount: str, formats: tuple[str, ...], folders: bool = False) -> list[Item]:
    """A sub-bundle's ``items`` with the entries of ``formats`` only, their keys under ``<mount>.`` (and with
    ``folders`` their files in the sub-folder ``<mount>/``, the names its own report lists relative to it)."""
    prefix, folder = f"{mount}.", f"{mount}/" if folders else ""
    out = []
    for it in items:
        entries = tuple(Entry(e.format, prefix + e.key, folder + e.name) for e in it.entries if e.format in formats)
        if entries:
            payload = Scoped(it.payload, prefix, folder) if hasattr(it.payload, "with_files") else it.payload
            out.append(Item(payload, entries))
    return out


def machine_bundle(design: MachineDesign) -> tuple[Bundle, dict[str, Any]]:
    """The files of a machine and its report (without the ``files`` map, which the bundle adds)."""
    out = design.spec.output
    formats, name = tuple(out.formats), design.spec.name
    items: list[Item | None] = []
    cams = []
    for cam in design.cams:
        bundle, cam_report = spec_kind(cam.design.spec).bundle(cam.design)
        items += _scoped(bundle.items, cam.name, formats, out.folders)
        cams.append(cam_report)
    for g in design.indexed:                            # each Geneva drive's own files
        items += _scoped(spec_kind(g.design.spec).bundle(g.design)[0].items, g.name, formats, out.folders)
    for m, made in design.written_linkages:             # without the parts the arm, the frame or a stem are
        items += _scoped(linkgen_api.bundle(made)[0].items, m.name, formats, out.folders)
    report = {**machine_report(design), **_parts_summary(cams)}
    from camgen.kinds.machine.machine_gears import gear_items

    items += gear_items(design, formats)
    if design.frame is not None:
        from camgen.kinds.machine.framekit import frame_items, frame_report

        report["frame"] = frame_report(design.frame, design)
        items += frame_items(design.frame, design, formats)
    from camgen.kinds.machine import assembly
    from camgen.kinds.machine.follower_parts import follower_items, followers_report

    report["followers"] = followers_report(design)
    items += follower_items(design, formats)

    report["assembly"] = assembly.assembly_report(design)
    for made in (mesh_files(lambda: assembly.meshes(design), f"{name}-assembly", "assembly", only=("3mf",)),
                 solid_files(lambda: assembly.solids(design), f"{name}-assembly", "assembly")):
        items.append(made.only(formats) if made is not None else None)

    def plot() -> Any:
        from camgen.kinds.machine.plots import timing_figure

        return timing_figure(design)

    items.append(item(plot, [("png", "timing_png", f"{name}-timing.png"), ("svg", "timing_svg",
                                                                          f"{name}-timing.svg")], formats))

    def posed() -> Any:
        from camgen.kinds.machine.plots import machine_figure

        return machine_figure(design)

    items.append(item(posed, [("png", "machine_png", f"{name}-machine.png"), ("svg", "machine_svg",
                                                                            f"{name}-machine.svg")], formats))
    items.append(item(lambda: timing_rows(design), [("csv", "timing_csv", f"{name}-timing.csv")],
                      ["csv"] if "json" in formats else []))
    items.append(item(Report(report), [("json", "json", f"{name}.json")], formats))

    def page() -> Any:
        from camgen.kinds.machine.page import machine_page

        return machine_page(design, report)

    items.append(item(page, [("html", "html", f"{name}.html")], formats))
    return Bundle.of(items, out.write_options), report


def _parts_summary(cams: list[dict[str, Any]]) -> dict[str, Any]:
    """What the machine's report says of its cams' parts together, from their own reports: the largest distance of
    an exported outline from the exact one and the finest tolerance (mm), and whether every printed cam's mesh is
    watertight (where one is made)."""
    if not cams:                                        # a machine of linkages only: their own reports say
        return {}
    out: dict[str, Any] = {"outline_max_error_mm": max(r.get("outline_max_error_mm", 0.0) for r in cams),
                           "tolerance_mm": min(r.get("tolerance_mm", float("inf")) for r in cams)}
    meshes = [r["mesh"] for r in cams if isinstance(r.get("mesh"), dict)]
    if meshes:
        out["mesh"] = {"watertight": all(m.get("watertight") for m in meshes), "cams": len(meshes)}
    return out


def machine_row(design: MachineDesign, report: dict[str, Any]) -> dict[str, Any]:
    """A family member's summary row: its cams' and linkages' counts, the torque and its files."""
    return {"cams": len(report["cams"]), "linkages": len(report["linkages"]) + len(report.get("cranked", {})),
            "shaft_torque_max_n_m": report["shaft_torque_n_m"]["max"],
            "files": " ".join(sorted(report["files"].values())), "thumbnail": []}
