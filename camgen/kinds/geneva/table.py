"""The Geneva drive's template: a ``[geneva]`` table (no follower and no motion program: its motion is the
Geneva law), ``name`` and ``[output]``, validated into a frozen :class:`GenevaSpec`.

Every bad value is one :class:`~camgen.core.errors.SpecError` naming the field and its allowed range, e.g.
``geneva.slots: must be >= 3 and <= 36 (got 2)``; dimensions that leave no part (a slot too wide for the
wheel, a locking disc out of its range, a bore too large) are named the same way (see
:meth:`camgen.kinds.geneva.geometry.GenevaGeometry.check`).
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cached_property
from pathlib import Path
from typing import Any, ClassVar

from pydantic import ConfigDict, Field, model_validator

from camgen.core.errors import SpecError
from camgen.core.spec import CutOutputTable, Model, TemplateSpec, length, name_field, unit, validate
from camgen.kinds.geneva.geometry import GenevaGeometry

#: the most slots a wheel may have
MAX_SLOTS = 36
#: the default locking disc: its radius is the crank radius less this many pin diameters (a common proportion)
LOCK_PINS = 1.5


class GenevaTable(Model):
    """The drive: slots, centre distance, pin and clearances; optional sizes of the locking disc, crank and bores."""

    model_config = ConfigDict(title="a Geneva drive")

    slots: int = Field(ge=3, le=MAX_SLOTS, description="number of slots in the wheel")
    centre_distance: float = length("distance between the driver's and the wheel's axes")
    pin_diameter: float = length("diameter of the driver's pin")
    slot_clearance: float = length("the slots' width less the pin's diameter", 0.2, zero=True, le=5.0)
    lock_clearance: float = length("gap between the locking disc and the wheel's locking arcs", 0.2, zero=True,
                                   le=5.0)
    lock_radius: float | None = length("locking disc radius (default: crank radius - 1.5 pin diameters)", None)
    crank_width: float | None = length("width of the crank bar (default: twice the pin diameter)", None)
    thickness: float = length("plate thickness of each part", le=1000.0)
    driver_bore: float = length("driver's bore diameter, 0 for none", 0.0, zero=True)
    wheel_bore: float = length("wheel's bore diameter, 0 for none", 0.0, zero=True)
    rpm: float | None = Field(None, gt=0, le=100_000, description="driver speed for the wheel's rates in time",
                              json_schema_extra=unit("rpm"))


class GenevaSpec(TemplateSpec):
    """A whole Geneva template, validated.

    Made by :func:`camgen.spec.validate_spec` or :func:`camgen.spec.load_spec` from a template with a
    ``[geneva]`` table (every key: the template reference); frozen.

    Parameters
    ----------
    name : str
        The drive's name, used for its files: letters, digits, ``.``, ``_``, ``-``.
    geneva : GenevaTable
        The drive: slots, centre distance, pin, clearances, bores, speed.
    output : CutOutputTable, optional
        Formats, tolerance, kerf, clearance and the cut sheet.
    """

    #: its kind's name (the registry's key, :data:`camgen.kinds.KINDS`)
    kind: ClassVar[str] = "geneva"
    product: ClassVar[str] = "camgen"
    noun: ClassVar[str] = "a Geneva drive"
    name: str = name_field("drive")
    geneva: GenevaTable
    output: CutOutputTable = CutOutputTable()

    @classmethod
    def validate_raw(cls, raw: Mapping[str, Any], folder: Path | None = None) -> GenevaSpec:
        """The drive of the raw template ``raw``; a cam's template (a ``[cam]`` table) refused naming ``template``
        (a Geneva drive writes every format and reads no files, so nothing else is to check)."""
        if "cam" in raw:
            raise SpecError(f"a cam, not {cls.noun}", "template")
        return validate(cls, raw)

    @model_validator(mode="after")
    def _parts_exist(self) -> "GenevaSpec":
        self.geometry.check()
        return self

    @cached_property
    def geometry(self) -> GenevaGeometry:
        """The parts' dimensions, defaults filled in."""
        g = self.geneva
        pin = g.pin_diameter
        lock = g.lock_radius if g.lock_radius is not None else (
            g.centre_distance * math.sin(math.pi / g.slots) - LOCK_PINS * pin)
        crank = g.crank_width if g.crank_width is not None else max(2 * pin, g.driver_bore + pin)
        return GenevaGeometry(g.slots, g.centre_distance, pin, g.slot_clearance, g.lock_clearance, lock, crank,
                              g.driver_bore, g.wheel_bore)

