"""A closed contour of lines and arcs moved outwards by a distance, exactly: its parallel curve.

A contour is in LWPOLYLINE form (vertices (n, 2) mm, bulges (n,): piece i runs from vertex i to vertex i + 1, the
last back to the first, an arc of bulge tan(included angle / 4) counter-clockwise positive, a line where 0), traversed
counter-clockwise. "Outwards" is to the right of the direction of travel (out of the material of an outline, into
the material round a hole traversed the same way). Each line moves along its normal, each arc keeps its centre and
changes its radius; where two pieces meet at a corner that the move opens (a convex corner moved outwards) an arc of
the distance's radius round the corner joins them, where it closes (a concave one) they are cut back to where they
cross. Tangent junctions stay tangent. Negative distances move inwards, with the roles of the corners swapped.
"""
from __future__ import annotations

import math

import numpy as np

from camgen.core.errors import DesignError

#: corners that turn by less than this (rad) are junctions of tangent pieces
TANGENT = 1e-9


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _unit(v: np.ndarray) -> np.ndarray:
    return v / float(np.hypot(*v))


class _Piece:
    """One piece: a line (centre None) or an arc (centre, radius, sweep > 0 counter-clockwise), start and end."""

    def __init__(self, start: np.ndarray, end: np.ndarray, bulge: float) -> None:
        self.start, self.end = start, end
        self.centre: np.ndarray | None = None
        self.sweep = 4.0 * math.atan(bulge)
        if abs(bulge) > 1e-12:
            chord = end - start
            length = float(np.hypot(*chord))
            normal = np.array([-chord[1], chord[0]]) / length
            self.centre = (start + end) / 2 + normal * (length / (2.0 * math.tan(self.sweep / 2)))
            self.radius = length / (2.0 * abs(math.sin(self.sweep / 2)))

    def tangent(self, at_end: bool) -> np.ndarray:
        """The unit direction of travel at the start or the end."""
        if self.centre is None:
            return _unit(self.end - self.start)
        radial = (self.end if at_end else self.start) - self.centre
        turn = np.array([-radial[1], radial[0]]) if self.sweep > 0 else np.array([radial[1], -radial[0]])
        return _unit(turn)

    def moved(self, distance: float) -> _Piece:
        """The piece moved ``distance`` to the right of its direction of travel (its ends only moved radially)."""
        out = _Piece.__new__(_Piece)
        out.sweep, out.centre = self.sweep, self.centre
        if self.centre is None:
            t = self.tangent(False)
            normal = np.array([t[1], -t[0]])
            out.start, out.end = self.start + distance * normal, self.end + distance * normal
            return out
        out.radius = self.radius + (distance if self.sweep > 0 else -distance)
        if not out.radius > 0:
            raise DesignError(f"an arc of radius {self.radius:.4g} mm closes when moved by {distance:g} mm")
        scale = out.radius / self.radius
        out.start = self.centre + (self.start - self.centre) * scale
        out.end = self.centre + (self.end - self.centre) * scale
        return out

    def bulge(self) -> float:
        """The bulge from its (possibly trimmed) start to its end, turning the way it always did; 0 for a line."""
        if self.centre is None:
            return 0.0
        a, b = self.start - self.centre, self.end - self.centre
        sweep = math.atan2(_cross(a, b), float(a @ b))
        if self.sweep > 0 and sweep <= 0:
            sweep += 2 * math.pi
        elif self.sweep < 0 and sweep >= 0:
            sweep -= 2 * math.pi
        return math.tan(sweep / 4.0)


def _meet(first: _Piece, second: _Piece, near: np.ndarray) -> np.ndarray:
    """Where ``first`` (extended: its line or circle) crosses ``second``, the crossing nearest ``near``."""
    candidates: list[np.ndarray] = []
    if first.centre is None and second.centre is None:
        d1, d2 = first.end - first.start, second.end - second.start
        det = _cross(d1, d2)
        if abs(det) > 1e-300:
            s = _cross(second.start - first.start, d2) / det
            candidates.append(first.start + s * d1)
    elif first.centre is None or second.centre is None:
        line, arc = (first, second) if first.centre is None else (second, first)
        assert arc.centre is not None
        d = _unit(line.end - line.start)
        f = line.start - arc.centre
        b, c = float(f @ d), float(f @ f) - arc.radius**2
        disc = b * b - c
        if disc >= 0:
            root = math.sqrt(disc)
            candidates += [line.start + (-b - root) * d, line.start + (-b + root) * d]
    else:
        assert first.centre is not None and second.centre is not None
        v = second.centre - first.centre
        dist = float(np.hypot(*v))
        if dist > 0:
            along = (first.radius**2 - second.radius**2 + dist**2) / (2 * dist)
            h2 = first.radius**2 - along**2
            if h2 >= 0:
                u = v / dist
                n = np.array([-u[1], u[0]])
                base = first.centre + along * u
                candidates += [base + math.sqrt(h2) * n, base - math.sqrt(h2) * n]
    if not candidates:
        raise DesignError("two pieces of the outline no longer meet once moved")
    return min(candidates, key=lambda p: float(np.hypot(*(p - near))))


def offset_contour(vertices: np.ndarray, bulges: np.ndarray, distance: float) -> tuple[np.ndarray, np.ndarray]:
    """The counter-clockwise contour (``vertices`` (n, 2) mm, ``bulges`` (n,)) moved outwards by ``distance`` mm
    (inwards when negative): its vertices and bulges, an arc of radius |distance| added at each corner the move
    opens; the contour itself for a distance of 0.

    Raises
    ------
    DesignError
        A piece shrinks to nothing or turns round (the distance is larger than a feature of the outline: an arc's
        radius on the side it moves to, a piece between two corners it closes).
    """
    if distance == 0:
        return np.asarray(vertices, dtype=float), np.asarray(bulges, dtype=float)
    v = np.asarray(vertices, dtype=float)
    n = len(v)
    pieces = [_Piece(v[i], v[(i + 1) % n], float(bulges[i])) for i in range(n)]
    moved = [p.moved(distance) for p in pieces]
    corners: list[tuple[float, np.ndarray] | None] = []      # an arc to insert after piece i, or None
    for i in range(n):
        before, after = pieces[i], pieces[(i + 1) % n]
        t_in, t_out = before.tangent(True), after.tangent(False)
        turn = math.atan2(_cross(t_in, t_out), float(t_in @ t_out))
        corner = before.end
        if abs(turn) < TANGENT:
            joint = (moved[i].end + moved[(i + 1) % n].start) / 2
            moved[i].end, moved[(i + 1) % n].start = joint, joint.copy()
            corners.append(None)
        elif turn * distance > 0:
            corners.append((math.tan(turn / 4.0), corner))
        else:
            joint = _meet(moved[i], moved[(i + 1) % n], corner)
            moved[i].end, moved[(i + 1) % n].start = joint, joint.copy()
            corners.append(None)
    out_v: list[np.ndarray] = []
    out_b: list[float] = []
    for i, (old, new) in enumerate(zip(pieces, moved, strict=True)):
        if new.centre is None:
            if float((new.end - new.start) @ (old.end - old.start)) <= 0:
                raise DesignError(f"a straight piece of the outline {float(np.hypot(*(old.end - old.start))):.4g} mm "
                                  f"long vanishes when the outline moves by {distance:g} mm")
            bulge = 0.0
        else:
            bulge = new.bulge()
            if abs(4 * math.atan(bulge)) > abs(old.sweep) + 1e-9 and abs(old.sweep) < math.pi:
                raise DesignError(f"an arc of the outline of radius {old.radius:.4g} mm turns round when the outline "
                                  f"moves by {distance:g} mm")
        out_v.append(new.start)
        out_b.append(bulge)
        opened = corners[i]
        if opened is not None:
            out_v.append(new.end)
            out_b.append(opened[0])
    return np.array(out_v), np.array(out_b)
