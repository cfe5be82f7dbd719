"""A coupled four-bar's files as the machine writes them: without its crank, which the follower's arm is (the arm
carries the crank pin's hole, :func:`camgen.kinds.machine.follower_parts.arm_holes`, and is cut and printed as the
arm), so that a user does not make a part the machine does not use. No I/O.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Any

#: the four-bar's link that the follower's arm is
CRANK = "crank"


def without_crank(design: Any) -> Any:
    """``design`` (a :class:`~linkgen.linkage_design.LinkageDesign` with parts) with its crank left out of its parts:
    the nominal, cut and printed parts, and the cut sheets nested again without it (its report's parts and sheet
    too); the assembly drawing and the layers still show it where it is. A design without parts is returned as it
    is."""
    from camgen.core.nesting import SheetRules, nest

    build = design.build
    if build is None or all(p.name != CRANK for p in build.parts):
        return design
    table = build.table
    cut = tuple(p for p in build.cut if p.name != CRANK)
    nested = nest(cut, SheetRules.of(table, table.kerf, "parts.sheet"))
    kept = replace(build, parts=tuple(p for p in build.parts if p.name != CRANK), cut=cut,
                   printed=tuple(p for p in build.printed if p.name != CRANK),
                   sheets=nested.drawings(table.tolerance), nesting=nested)
    return replace(design, build=kept)
