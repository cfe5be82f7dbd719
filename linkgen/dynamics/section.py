"""A flat part's section properties, exact for its arcs: area, centroid and polar second moment about the centroid.

A contour of lines and arcs (:class:`camgen.core.shapes.Contour`) bounds the polygon of its vertices plus, for each
arc, the circular segment between its chord and the arc (signed: a segment that bulges inwards takes area away).
Each region's integrals are in closed form: the polygon as the triangles (0, p_i, p_i+1) from the origin, a segment
as its sector less the triangle of its centre and chord. A part is its outline less its holes (circles, slots). The
mass properties follow for a plate of uniform thickness and density: m = rho t A, the centre at the centroid, and
I_G = rho t J_G (mm^4 x kg/mm^3 = kg*mm^2).

Units: mm, mm^2, mm^3 (first moments), mm^4; the part's own frame.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camgen.core.parts import Part
from camgen.core.shapes import Circle, Contour, Shape


@dataclass(frozen=True)
class Section:
    """A plane region's area A (mm^2), first moments (Sx, Sy) = the integrals of x and y (mm^3) and polar second
    moment Jo about the origin = the integral of x^2 + y^2 (mm^4); signed by the boundary's orientation
    (counter-clockwise positive). Sections add and subtract."""

    area: float
    first: tuple[float, float]
    polar: float

    def __add__(self, other: Section) -> Section:
        return Section(self.area + other.area, (self.first[0] + other.first[0], self.first[1] + other.first[1]),
                       self.polar + other.polar)

    def __neg__(self) -> Section:
        return Section(-self.area, (-self.first[0], -self.first[1]), -self.polar)

    def __sub__(self, other: Section) -> Section:
        return self + (-other)

    @property
    def centroid(self) -> tuple[float, float]:
        """(x, y) mm; the origin for an empty region."""
        if self.area == 0:
            return 0.0, 0.0
        return self.first[0] / self.area, self.first[1] / self.area

    @property
    def polar_about_centroid(self) -> float:
        """The polar second moment about the centroid (mm^4): Jo - A |G|^2 (parallel axes)."""
        gx, gy = self.centroid
        return self.polar - self.area * (gx * gx + gy * gy)


def _triangle(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> Section:
    """The signed triangle a -> b -> c (arrays (k, 2) of k triangles, summed)."""
    area = 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    centre = (a + b + c) / 3.0
    sq = (np.einsum("ij,ij->i", a, a) + np.einsum("ij,ij->i", b, b) + np.einsum("ij,ij->i", c, c)
          + np.einsum("ij,ij->i", a, b) + np.einsum("ij,ij->i", b, c) + np.einsum("ij,ij->i", c, a))
    return Section(float(area.sum()), (float((area * centre[:, 0]).sum()), float((area * centre[:, 1]).sum())),
                   float((area * sq / 6.0).sum()))


def contour_section(contour: Contour) -> Section:
    """The region a contour bounds, exact for its arcs (signed: negative for a clockwise contour)."""
    p = contour.vertices
    q = np.roll(p, -1, axis=0)
    out = _triangle(np.zeros_like(p), p, q)
    idx, centres, radii, sweeps = contour.arcs()
    if not len(idx):
        return out
    starts = p[idx]
    t0 = np.arctan2(starts[:, 1] - centres[:, 1], starts[:, 0] - centres[:, 0])
    t1 = t0 + sweeps
    area = 0.5 * radii**2 * sweeps
    rel = np.column_stack([np.sin(t1) - np.sin(t0), np.cos(t0) - np.cos(t1)]) * (radii**3 / 3.0)[:, None]
    own = radii**4 * sweeps / 4.0
    first = rel + centres * area[:, None]
    polar = own + 2.0 * np.einsum("ij,ij->i", centres, rel) + np.einsum("ij,ij->i", centres, centres) * area
    sector = Section(float(area.sum()), (float(first[:, 0].sum()), float(first[:, 1].sum())), float(polar.sum()))
    return out + sector - _triangle(centres, starts, q[idx])


def circle_section(circle: Circle) -> Section:
    """A full disc (counter-clockwise): A = pi r^2, Jo = pi r^4 / 2 + A |c|^2."""
    area = math.pi * circle.radius**2
    cx, cy = circle.centre
    return Section(area, (area * cx, area * cy), area * circle.radius**2 / 2 + area * (cx * cx + cy * cy))


def shape_section(shape: Shape) -> Section:
    """A hole's region, counted positive whichever way its contour runs."""
    if isinstance(shape, Circle):
        return circle_section(shape)
    section = contour_section(shape)
    return -section if section.area < 0 else section


def part_section(part: Part) -> Section:
    """A part's outline less its holes (mm, the part's frame)."""
    out = shape_section(part.outline)
    for hole in part.holes:
        out = out - shape_section(hole)
    return out
