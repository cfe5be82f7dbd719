"""The straight-line linkages (Chebyshev, Hoekens, Roberts, Watt): their ``[linkage]`` table and report; being
four-bars, their figures, parts, thumbnail and sketch are the four-bar's (:mod:`linkgen.mechanisms.fourbar`).

Each is its canonical proportions scaled by ``size`` mm (see :mod:`linkgen.kinematics.straightline`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from camgen.core.parts import Drawing
from camgen.core.spec import Model
from linkgen.kinematics.straightline import StraightLine, straight_line
from linkgen.mechanisms.common import Figure, lengths_table, omega, types_of
from linkgen.mechanisms.fourbar import fourbar_figures, fourbar_layout, fourbar_sketch, fourbar_thumbnail, position
from linkgen.parts import Layout

if TYPE_CHECKING:
    from linkgen.spec import PartsTable


StraightLineTable = lengths_table(
    "StraightLineTable", "``[linkage]`` of a straight-line linkage: its type and the unit of its proportions (mm).",
    ("chebyshev", "hoekens", "roberts", "watt"), size="scale: the length that is 1 in the canonical proportions")


def straightline_report(table: Any, mech: StraightLine, angle: float | None) -> dict[str, Any]:
    """The proportions, Grashof class, the straightness of the useful stroke; with ``angle`` (degrees) the position
    of its assembly there."""
    s = mech.straightness()
    fb = mech.linkage
    report: dict[str, Any] = {
        "proportions": {"ground": fb.ground, "crank": fb.crank, "coupler": fb.coupler, "rocker": fb.rocker,
                        "point_distance": fb.point_distance, "point_angle_deg": round(math.degrees(fb.point_angle), 9),
                        "assembly": mech.assembly},
        "grashof_class": fb.grashof.grashof_class, "inversion": fb.grashof.inversion,
        "straightness": {"stroke_mm": s.stroke_mm, "error_mm": round(s.error_mm, 12),
                         "error_ratio": round(s.error_mm / s.stroke_mm, 12),
                         "input_from_deg": round(math.degrees(s.input_from), 6),
                         "input_to_deg": round(math.degrees(s.input_to), 6),
                         "start_mm": [round(v, 9) for v in s.start], "end_mm": [round(v, 9) for v in s.end]}}
    if angle is not None:
        pose = fb.positions(np.array([math.radians(angle)]), mech.assembly)
        report["positions"] = {mech.assembly: position(fb, pose, omega(table.rpm))}
    return report


@dataclass(frozen=True)
class StraightLineMechanism:
    """``chebyshev``, ``hoekens``, ``roberts``, ``watt``: a four-bar whose coupler point traces a near-straight line."""

    types: tuple[str, ...] = types_of(StraightLineTable)
    table: type[Model] = StraightLineTable

    def build(self, table: Any) -> StraightLine:
        return straight_line(table.type, table.size)

    def report(self, table: Any, kinematics: StraightLine, angle: float | None,
               method: str) -> dict[str, Any]:
        return straightline_report(table, kinematics, angle)

    def figures(self, name: str, table: Any, kinematics: StraightLine) -> tuple[Figure, ...]:
        return fourbar_figures(name, kinematics.linkage, kinematics.assembly)

    def layout(self, table: Any, kinematics: StraightLine, parts: PartsTable) -> Layout:
        # the parts are laid out and drawn on the open assembly, whatever the linkage's own (as linkgen always has)
        return fourbar_layout(kinematics.linkage, "open", parts)

    def family_row(self, table: Any, kinematics: StraightLine, report: dict[str, Any]) -> dict[str, Any]:
        """The straightness error as a column, and the tracing point's path."""
        return {"straightness_error_mm": report["straightness"]["error_mm"],
                **fourbar_thumbnail(kinematics.linkage, kinematics.assembly)}

    def sketch(self, table: Any, kinematics: StraightLine) -> Drawing:
        return fourbar_sketch(kinematics.linkage, kinematics.assembly)


REGISTER = (StraightLineMechanism(),)
