"""The materials a linkage's parts and pins are made of: density, how the parts are made, and what a hole and a pin
may carry.

Densities (kg/m^3) are typical datasheet figures: birch plywood 680 (Metsä Wood, WISA birch plywood: 680 kg/m^3),
MDF 750 (the middle of EN 622-5's 700-800 kg/m^3 for standard MDF), cast acrylic (PMMA) 1190 (Röhm, PLEXIGLAS GS
datasheet), aluminium 2700 (EN AW-6061, EN 573/EN 755), steel 7850 (EN 10025 structural steel), brass 8500
(CuZn39Pb3, EN 12164), PLA 1240 (NatureWorks Ingeo 4043D datasheet) and PETG 1270 (Eastman Eastar/Spectar
copolyesters datasheet). Printed parts (PLA, PETG) weigh their solid's mass times ``dynamics.infill``.

What a hole may carry: the allowable bearing pressure p = F / (d t) on a hole of diameter d in a plate t thick is a
round strength of the material divided by a safety factor: the yield strength for the metals (EN AW-6061-T6 276 MPa,
S235 235 MPa; safety factor 2), the compressive strength for wood and plastics (birch plywood 30 MPa along the face
grain, MDF 18 MPa, cast acrylic 100 MPa, printed PLA 45 MPa and PETG 40 MPa: printed parts are weaker than moulded
ones, and a hole's walls are solid perimeters, so the infill does not lower it; safety factor 3, for scatter,
creep and a notch at every hole). A pin's allowable shear stress tau = F / (n pi d^2 / 4) is 0.6 of its yield (the
shear yield, near 1/sqrt(3) of the tensile) over the same factors: a steel pin as a property class 8.8 bolt (yield
640 MPa), brass 250 MPa, aluminium 276 MPa, a printed PLA or PETG pin 45 or 40 MPa. They are guides for a model, not
a design code's figures: give your own as ``dynamics.allowable_bearing`` and ``dynamics.allowable_shear``.
"""
from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Literal


@dataclass(frozen=True)
class Material:
    """A material: ``density`` (kg/m^3), how its parts are ``made`` (``cut`` on a laser: the kerf applies; ``printed``:
    the printed holes), ``strength`` (MPa: yield, or compressive strength, see the module's note) and the
    ``safety`` factor its allowables divide it by."""

    name: str
    density: float
    made: Literal["cut", "printed"]
    strength: float
    safety: float

    @property
    def allowable_bearing(self) -> float:
        """The bearing pressure a hole in a plate of it may carry (MPa): strength / safety."""
        return self.strength / self.safety

    @property
    def allowable_shear(self) -> float:
        """The shear stress a pin of it may carry (MPa): 0.6 strength / safety."""
        return 0.6 * self.strength / self.safety


#: the parts' materials, by the name ``dynamics.material`` takes
SHEETS = MappingProxyType({m.name: m for m in (
    Material("plywood", 680.0, "cut", 30.0, 3.0),
    Material("mdf", 750.0, "cut", 18.0, 3.0),
    Material("acrylic", 1190.0, "cut", 100.0, 3.0),
    Material("aluminium", 2700.0, "cut", 276.0, 2.0),
    Material("steel", 7850.0, "cut", 235.0, 2.0),
    Material("pla", 1240.0, "printed", 45.0, 3.0),
    Material("petg", 1270.0, "printed", 40.0, 3.0),
)})

#: the pins' materials, by the name ``dynamics.pins`` takes (a printed pin, ``parts.pins = true``: PLA or PETG)
PINS = MappingProxyType({m.name: m for m in (
    Material("steel", 7850.0, "cut", 640.0, 2.0),
    Material("brass", 8500.0, "cut", 250.0, 2.0),
    *(SHEETS[name] for name in ("aluminium", "pla", "petg")),    # a pin of the sheets' own aluminium or plastics
)})

#: the names of :data:`SHEETS` and of :data:`PINS`, written out for the type checker (tests/project/test_types.py checks
#: that each names exactly its table's entries, in order)
SheetName = Literal["plywood", "mdf", "acrylic", "aluminium", "steel", "pla", "petg"]
PinName = Literal["steel", "brass", "aluminium", "pla", "petg"]

#: the printed spacers' material (the kit's spacers are printed: ``fdm`` in its bill of materials)
SPACER = SHEETS["pla"]
