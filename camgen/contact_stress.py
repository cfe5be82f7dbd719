"""Hertz line contact between a cam and its follower, and the materials people cut and print them from.

Two cylinders of radii R1, R2 (mm; a concave surface negative, a flat face infinite) pressed
together by F (N) along a contact length L (mm) touch on a strip of half-width
b = sqrt(4 F R / (pi L E*)) with the largest pressure p = sqrt(F E* / (pi L R)) (MPa), where
1/R = 1/R1 + 1/R2 and 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (E in MPa). Pure arithmetic on
numpy arrays; no spec, no files.

The materials' figures are indicative (room temperature, a first check, not a design
allowable): moduli and Poisson's ratios from handbooks, allowable contact pressures set
conservatively for repeated rolling contact. Use a supplier's data for a real design.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np


@dataclass(frozen=True)
class Material:
    """Young's modulus E (MPa), Poisson's ratio nu, allowable contact pressure (MPa) and a note."""

    modulus: float
    poisson: float
    allowable: float
    note: str


#: the names of :data:`MATERIALS`, written out for the type checker
MaterialName = Literal["steel", "aluminium", "pom", "nylon", "pla", "petg", "plywood", "acrylic"]
#: the materials ``cam.material`` and ``follower.material`` name
MATERIALS: dict[str, Material] = {
    "steel": Material(210_000.0, 0.30, 1000.0, "through-hardened carbon steel"),
    "aluminium": Material(70_000.0, 0.33, 300.0, "6061-T6"),
    "pom": Material(2_800.0, 0.35, 60.0, "acetal (POM, Delrin)"),
    "nylon": Material(2_500.0, 0.39, 50.0, "PA6, dry"),
    "pla": Material(3_500.0, 0.36, 30.0, "3D-printed PLA, 100 % infill"),
    "petg": Material(2_100.0, 0.38, 25.0, "3D-printed PETG, 100 % infill"),
    "plywood": Material(6_000.0, 0.30, 15.0, "birch plywood, load in the sheet's plane on a cut edge"),
    "acrylic": Material(3_200.0, 0.37, 40.0, "cast PMMA"),
}


def effective_modulus(a: Material, b: Material) -> float:
    """E* (MPa) of two materials in contact: 1 / ((1 - nu_a^2) / E_a + (1 - nu_b^2) / E_b)."""
    return 1.0 / ((1.0 - a.poisson ** 2) / a.modulus + (1.0 - b.poisson ** 2) / b.modulus)


def relative_curvature(*curvatures: np.ndarray | float) -> np.ndarray:
    """1/R (1/mm): the sum of the two surfaces' curvatures at the contact (convex positive, concave negative, a
    flat face 0)."""
    return np.asarray(sum(np.asarray(c, dtype=float) for c in curvatures), dtype=float)


def line_contact(force: np.ndarray, curvature: np.ndarray, length: float, e_star: float
                 ) -> tuple[np.ndarray, np.ndarray]:
    """The largest pressure (MPa) and the half-width of the contact strip (mm) for a normal ``force`` (N) on a line
    ``length`` mm long, of relative ``curvature`` 1/R (1/mm, > 0 where the surfaces touch on a line; 0 is two flat
    faces: no Hertz contact, pressure F / area taken as 0 here) and effective modulus ``e_star`` (MPa)."""
    f = np.maximum(np.asarray(force, dtype=float), 0.0)
    k = np.maximum(np.asarray(curvature, dtype=float), 0.0)
    pressure = np.sqrt(f * e_star * k / (math.pi * length))
    with np.errstate(divide="ignore", invalid="ignore"):
        width = np.where(k > 0, np.sqrt(4.0 * f / np.where(k > 0, k, 1.0) / (math.pi * length * e_star)), np.inf)
    return pressure, width
