"""The tool-radius check for CNC routing: where an outline is more concave than a round cutter can follow.

A router's cutter of radius r cannot cut a concave boundary whose radius of curvature is below r: it leaves
material there. Every closed shape of a part is read with the material on its left (the outline
counter-clockwise, holes clockwise), and its concave places are:

* its concave arcs (exact, from the :class:`~camgen.core.shapes.Contour` bulges): radius the arc's, at the arc's
  middle; a hole's circle: radius the circle's, at its centre;
* its concave corners, where one piece meets the next turning away from the material: radius 0, unless the
  two pieces are chords of a curve within the part's tolerance t. Chords of length L within t of a circle of
  radius R turn by L / R where they meet, with L^2 / (8 R) <= t, so a joint of pieces L1, L2 turning by at most
  4 t (1 / L1 + 1 / L2) (with a margin of 1.5 for chords sampled at the limit) is read as a point of a curve of
  radius (L1 + L2) / (2 turn), which is R for chords of a circle; a sharper turn is a corner.

Lengths in mm, angles in radians; pure numpy.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from camgen.core.parts import Part
from camgen.core.shapes import Circle, Contour, Shape

#: a joint turning by less than this (rad) is tangent (arcs and lines meeting smoothly, to rounding)
TANGENT_RAD = 1e-7
#: the margin on the turn chords of a curve within the tolerance may make where they meet
CHORD_MARGIN = 1.5


@dataclass(frozen=True)
class Concave:
    """A concave place of a part's boundary: the ``part``'s name, where (``x``, ``y`` mm, the part's frame), its
    radius of curvature (mm; 0 for a sharp corner) and ``what`` it is: ``"arc"``, ``"hole"``, ``"corner"`` or
    ``"chords"`` (chords of a concave curve)."""

    part: str
    x: float
    y: float
    radius: float
    what: str

    def as_dict(self) -> dict[str, float | str]:
        """The place as the report lists it (mm, rounded to the nanometre)."""
        return {"part": self.part, "x_mm": round(self.x, 6), "y_mm": round(self.y, 6),
                "radius_mm": round(self.radius, 9), "what": self.what}


def _tangents(contour: Contour) -> tuple[np.ndarray, np.ndarray]:
    """Each piece's unit tangent (k, 2) where it starts and where it ends: an arc of included angle a starts at its
    chord's direction turned by -a/2 and ends turned by +a/2."""
    p, q = contour.vertices, np.roll(contour.vertices, -1, axis=0)
    angle = 4.0 * np.arctan(contour.bulges)
    chord = np.arctan2(q[:, 1] - p[:, 1], q[:, 0] - p[:, 0])
    start, end = chord - angle / 2, chord + angle / 2
    return np.column_stack([np.cos(start), np.sin(start)]), np.column_stack([np.cos(end), np.sin(end)])


def concave_places(shape: Shape, tolerance: float, part: str, hole: bool) -> list[Concave]:
    """The concave places of one closed ``shape`` of ``part`` (an outline, or a hole if ``hole``); ``tolerance``
    (mm) is the chords' (see the module)."""
    if isinstance(shape, Circle):
        return [Concave(part, shape.centre[0], shape.centre[1], shape.radius, "hole")] if hole else []
    contour = shape if (shape.area > 0) != hole else shape.reversed()    # the material on the left
    places = []
    idx, centre, radius, angle = contour.arcs()
    for i, c, r, a in zip(idx, centre, radius, angle, strict=True):
        if a < 0:                                                        # clockwise: away from the material
            start = contour.vertices[i] - c
            mid = math.atan2(start[1], start[0]) + a / 2
            places.append(Concave(part, c[0] + r * math.cos(mid), c[1] + r * math.sin(mid), float(r), "arc"))
    starts, ends = _tangents(contour)
    before = np.roll(ends, 1, axis=0)
    turn = np.arctan2(before[:, 0] * starts[:, 1] - before[:, 1] * starts[:, 0], np.einsum("ij,ij->i", before, starts))
    lengths = np.linalg.norm(np.roll(contour.vertices, -1, axis=0) - contour.vertices, axis=1)
    for i in np.flatnonzero(turn < -TANGENT_RAD):
        l1, l2, bend = lengths[i - 1], lengths[i], -turn[i]
        chords = bend <= CHORD_MARGIN * 4 * tolerance * (1 / l1 + 1 / l2)
        x, y = contour.vertices[i]
        places.append(Concave(part, float(x), float(y), float((l1 + l2) / (2 * bend)) if chords else 0.0,
                              "chords" if chords else "corner"))
    return places


def part_places(part: Part) -> list[Concave]:
    """Every concave place of ``part``: its outline's, its holes', then its pockets' (a groove's flanks)."""
    out = concave_places(part.outline, part.tolerance, part.name, hole=False)
    for shape in part.holes:
        out += concave_places(shape, part.tolerance, part.name, hole=True)
    for pocket in part.pockets:                  # a pocket's rim bounds material outside it, its island inside
        out += concave_places(pocket.outer, part.tolerance, part.name, hole=True)
        if pocket.inner is not None:
            out += concave_places(pocket.inner, part.tolerance, part.name, hole=False)
    return out


def tool_check(parts: Sequence[Part], tool_radius: float) -> dict:
    """The report's ``routing`` block for ``parts`` and a cutter of ``tool_radius`` mm: the tool radius, each part's
    smallest concave radius (None for a part with no concave place), and every place whose radius is below the
    tool's (``fails``, see :meth:`Concave.as_dict`)."""
    smallest: dict[str, float | None] = {}
    fails = []
    for part in parts:
        places = part_places(part)
        smallest[part.name] = round(min(p.radius for p in places), 9) if places else None
        fails += [p.as_dict() for p in places if p.radius < tool_radius]
    return {"tool_radius_mm": tool_radius, "smallest_concave_radius_mm": smallest, "fails": fails}


def tool_warning(routing: dict) -> str | None:
    """The console's warning for a ``routing`` block (see :func:`tool_check`), None when every place passes."""
    fails = routing["fails"]
    if not fails:
        return None
    worst = min(fails, key=lambda f: f["radius_mm"])
    return (f"output.tool_radius: {len(fails)} concave place(s) tighter than the tool's {routing['tool_radius_mm']:g} "
            f"mm radius, which a router cannot cut (smallest {worst['radius_mm']:.4g} mm, a {worst['what']} of "
            f"{worst['part']} at ({worst['x_mm']:.3f}, {worst['y_mm']:.3f}) mm); the report's routing.fails lists "
            "them all")


def add_routing(report: dict, parts: Sequence[Part], tool_radius: float) -> None:
    """With a ``tool_radius`` (mm) above 0, add the ``routing`` block of ``parts`` (see :func:`tool_check`) to the
    ``report`` being assembled, and its warning, if any, to the report's ``warnings``; with 0, leave it as it is."""
    if tool_radius <= 0:
        return
    report["routing"] = tool_check(parts, tool_radius)
    warning = tool_warning(report["routing"])
    if warning is not None:
        report.setdefault("warnings", []).append(warning)
