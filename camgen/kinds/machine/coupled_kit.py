"""A machine's linkages' files as the machine writes them: without the parts other parts of the machine are, so that
a user does not make a part the machine does not use. No I/O.

* A coupled four-bar's crank is the follower's arm (the arm carries the crank pin's hole,
  :func:`camgen.kinds.machine.follower_parts.arm_holes`, and is cut and printed as the arm).
* With a frame (``machine.frame`` "one" or "two") every linkage's ground link is the frame, whose plates carry its
  fixed pivots' holes (:mod:`camgen.kinds.machine.frame`).
* A translating follower's stem carries the slider of the linkage it drives where that slider slides on the
  ground (:mod:`camgen.kinds.machine.stem_kit`): its block is the stem.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Any

from camgen.core.kit import BomLine

#: the four-bar's link that the follower's arm is; the link the frame is
CRANK, GROUND = "crank", "ground"


def without(design: Any, names: frozenset[str]) -> Any:
    """``design`` (a :class:`~linkgen.linkage_design.LinkageDesign` with parts) with the parts ``names`` left out:
    the nominal, cut and printed parts, and the cut sheets nested again without them (its report's parts and sheet
    too); the assembly drawing and the layers still show them where they are. A design without parts, or with none
    of them, is returned as it is."""
    from camgen.core.nesting import SheetRules, nest

    build = design.build
    if build is None or not any(p.name in names for p in build.parts):
        return design
    table = build.table
    cut = tuple(p for p in build.cut if p.name not in names)
    nested = nest(cut, SheetRules.of(table, table.kerf, "parts.sheet"))
    kept = replace(build, parts=tuple(p for p in build.parts if p.name not in names), cut=cut,
                   printed=tuple(p for p in build.printed if p.name not in names),
                   sheets=nested.drawings(table.tolerance), nesting=nested)
    return replace(design, build=kept)


def made_by_the_machine(design: Any, linkage: Any, coupled: bool) -> frozenset[str]:
    """The parts of ``linkage`` (a mounted linkage of machine ``design``) that other parts of the machine are (see
    the module's docstring): its crank where ``coupled`` (a four-bar on a follower's arm), its ground with a
    frame, the slider block a translating follower's stem carries (a linkage of ``design.slid`` whose cam has no
    arm, its input slider sliding on the ground)."""
    names = {CRANK} if coupled else set()
    if design.frame is not None:
        names.add(GROUND)
    slider = getattr(linkage, "ground_slider", None)        # a stem-driven linkage's (a SliderMotion's)
    if slider is not None and f"cams.{linkage.cam}.arm" not in {b.name for b in design.bodies}:
        names.add(slider.name)
    return frozenset(names)


def mounted(design: Any) -> tuple[tuple[Any, bool], ...]:
    """Each linkage of machine ``design`` and whether it is a coupled four-bar (its crank a follower's arm): the
    coupled four-bars, then those a shaft drives, then those a stem drives."""
    return (*((m, True) for m in design.linkages), *((m, False) for m in (*design.cranked, *design.slid)))


def machine_made(design: Any) -> tuple[tuple[Any, Any], ...]:
    """Each linkage of ``design`` (see :func:`mounted`) and its design as the machine writes it (:func:`without`
    the parts other parts of the machine are)."""
    return tuple((m, without(m.design, made_by_the_machine(design, m, coupled))) for m, coupled in mounted(design))


def bom_lines(design: Any) -> tuple[BomLine, ...]:
    """The kit's lines of the machine's cams, Geneva drives and linkages' parts, each made from its own files: a
    cam's plate (or each of a conjugate pair's, a barrel's drum printed), a Geneva's wheel, locking disc and crank,
    each link the machine writes (its ``written_linkages``, :func:`machine_made`), with its thickness and its holes."""
    from camgen.kinds.machine import barrel_parts, conjugate_parts

    lines = []
    for cam in design.cams:
        if barrel_parts.is_barrel(cam.design):
            lines.append(BomLine(cam.name, 1, f"barrel cam of cams.{cam.name} (its own files)", "fdm"))
            continue
        for suffix, part in conjugate_parts.plates(cam.design):
            lines.append(BomLine(f"{cam.name}{suffix}", 1, f"cam plate of cams.{cam.name}, {part.thickness:g} mm "
                                 "(its own files)", "laser or fdm"))
    for g in design.indexed:                                # each Geneva drive's wheel, locking disc and crank
        for name, part in g.design.cut.items():
            lines.append(BomLine(f"{g.name}-{name}", 1, f"Geneva {name} of genevas.{g.name}, "
                                 f"{part.thickness:g} mm (its own files)", "laser or fdm"))
    for m, made in design.written_linkages:
        if made.build is None:
            continue
        for part in made.build.cut:
            n = len(part.holes)
            lines.append(BomLine(f"{m.name}-{part.name}", 1, f"{part.name} of linkages.{m.name}, "
                                 f"{part.thickness:g} mm, {n} hole{'' if n == 1 else 's'} (its own files)",
                                 "laser or fdm"))
    return tuple(lines)
