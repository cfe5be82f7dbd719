"""Linkage specs: a template (the TOML a user writes) validated into a frozen :class:`LinkageSpec`.

The ``[linkage]`` table's ``type`` picks the mechanism (:data:`linkgen.mechanisms.MECHANISMS`),
whose table model checks every other key, with the same one-line errors as camgen's
(``linkage.crank: must be > 0 mm (got -5)``). ``[parts]`` is a :class:`PartsTable` and
``[output]`` the shared :class:`camgen.core.spec.OutputTable`.
"""
from __future__ import annotations

import functools
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Annotated, Any, ClassVar

from pydantic import Field, create_model, model_validator

from camgen.core.errors import SpecError
from camgen.core.hardware import BOLTS
from camgen.core.kit import KitTable
from camgen.core.options import choose
from camgen.core.spec import (MAX_LENGTH_MM, Model, OutputTable, TemplateSpec, check_kind, length, name_field,
                              read_template, unit, validate)
from linkgen.dynamics.table import DynamicsTable
from linkgen.mechanisms import MECHANISMS, Mechanism
from linkgen.slack.table import SlackTable

#: the largest kerf and clearance (mm), as camgen's ``output.kerf`` and ``output.clearance``
MAX_ALLOWANCE_MM = 5.0
#: the fastest input (rpm), as camgen's ``cam.rpm``
MAX_RPM = 100_000.0
#: a side of the sheet (mm)
SheetSide = Annotated[float, Field(gt=0, le=MAX_LENGTH_MM)]


class LinkOverride(Model):
    width: float = length("this link's width")


class PartsTable(Model):
    """Parts to cut and print (``linkgen build``); lengths in mm. Holes are pin + clearance in diameter (printed),
    less the kerf (cut); a link's own table (``[parts.crank]``) overrides the width of that link."""

    width: float = length("bar width")
    thickness: float = length("plate thickness", le=1000.0)
    pin_diameter: float = length("pin diameter")
    clearance: float = Field(0.2, ge=0, le=MAX_ALLOWANCE_MM, description="pin clearance: holes are pin + clearance",
                             json_schema_extra=unit("mm"))
    kerf: float = Field(0.0, ge=0, le=MAX_ALLOWANCE_MM, description="laser kerf: cut holes shrink by it, outlines "
                        "grow by half", json_schema_extra=unit("mm"))
    margin: float = length("sheet: gap between parts beyond the kerf", 3.0, zero=True, le=1000.0)
    sheet: tuple[SheetSide, SheetSide] = Field((600.0, 400.0), description="sheet width and height",
                                               json_schema_extra=unit("mm"))
    sheet_rotations: float = Field(90.0, ge=0, le=360, description="parts on the sheet turn in steps of this "
                                   "(0: as drawn only); a divisor of 360", json_schema_extra=unit("degrees"))
    grain: bool = Field(False, description="keep the parts along the sheet's grain (its width): turned by 0 or 180 "
                        "degrees only")
    pins: bool = Field(False, description="also write a printable pin (cylinder with a head)")
    tolerance: float = Field(0.01, ge=1e-6, le=1, description="chord tolerance of meshes and sheets",
                             json_schema_extra=unit("mm"))
    ground: LinkOverride | None = None
    crank: LinkOverride | None = None
    coupler: LinkOverride | None = None
    rocker: LinkOverride | None = None
    rod: LinkOverride | None = None
    slider: LinkOverride | None = None
    links: dict[str, LinkOverride] = Field(default_factory=dict,
                                           description="per-link overrides by any link's name (general linkages): "
                                                       "[parts.links.foot] width = 12")

    @model_validator(mode="after")
    def _holes_leave_material(self) -> PartsTable:
        """Holes of pin + clearance (printed, and cut: the kerf takes as much off the hole as it adds to the
        outline) leave material in every bar, and the kerf leaves the cut holes open; each refusal names the field
        that is too large, with the range it must keep to."""
        pin, hole = self.pin_diameter, self.pin_diameter + self.clearance
        if pin >= self.width:
            raise ValueError(f"pin_diameter: holes of {hole:g} mm leave no material in bars {self.width:g} mm wide; "
                             f"must be > 0 and < the bar width (got {pin:g})")
        if hole >= self.width:
            raise ValueError(f"clearance: must be >= 0 and < {self.width - pin:g} mm (width - pin_diameter), so "
                             f"that holes of pin_diameter + clearance leave material in bars {self.width:g} mm wide "
                             f"(got {self.clearance:g})")
        if self.sheet_rotations > 0 and abs(360.0 / self.sheet_rotations - round(360.0 / self.sheet_rotations)) > 1e-9:
            raise ValueError(f"sheet_rotations: must be 0 or divide 360 degrees (e.g. 90, 45, 15) (got "
                             f"{self.sheet_rotations:g})")
        if self.kerf >= hole:
            raise ValueError(f"kerf: must be >= 0 and < {hole:g} mm (pin_diameter + clearance), or it closes the "
                             f"cut holes (got {self.kerf:g})")
        named = {k: getattr(self, k) for k in ("ground", "crank", "coupler", "rocker", "rod", "slider")}
        for name, override in {**named, **{f"links.{k}": v for k, v in self.links.items()}}.items():
            if override is not None and hole >= override.width:
                raise ValueError(f"{name}.width: holes of {hole:g} mm leave no material in a bar {override.width:g} "
                                 "mm wide")
        return self

    def width_of(self, link: str) -> float:
        """The width (mm) of the part named ``link``: its own table's (under ``links`` or by name), else ``width``."""
        override = self.links.get(link) or getattr(self, link, None)
        return override.width if isinstance(override, LinkOverride) else self.width


#: the largest load (N, or N*m for a torque)
MAX_LOAD = 1e7


class LoadTable(Model):
    """A load the linkage holds (``[[loads]]``): a force (N, x and y in the drawing's frame) at a joint, or a
    torque (N*m, counter-clockwise) on a link. The report gives the input's effort that holds them
    (:mod:`linkgen.kinematics.statics`)."""

    point: str | None = Field(None, description="the joint the force acts at")
    force: tuple[float, float] | None = Field(None, description="the force: x, y", json_schema_extra=unit("N"))
    link: str | None = Field(None, description="the link the torque acts on")
    torque: float | None = Field(None, description="the torque, counter-clockwise", json_schema_extra=unit("N*m"))

    @model_validator(mode="after")
    def _one_kind(self) -> LoadTable:
        if (self.point is None) != (self.force is None) or (self.link is None) != (self.torque is None) or \
                (self.point is None) == (self.link is None):
            raise ValueError("give point and force (a force at a joint), or link and torque (a torque on a link)")
        for key, value in (("force", self.force or ()), ("torque", () if self.torque is None else (self.torque,))):
            if not all(abs(v) <= MAX_LOAD for v in value):
                got = ", ".join(f"{v:g}" for v in value)
                raise ValueError(f"{key}: must be at most {MAX_LOAD:g} in size (got {got})")
        return self


class LinkageSpec(TemplateSpec):
    """A validated linkage template. Each mechanism has its own subclass (:func:`spec_model`), whose ``linkage``
    is that mechanism's table and whose :attr:`mechanism` is the mechanism.

    Made by :func:`validate_spec` or :func:`load_spec` from a template (every key: the template reference); frozen.

    Parameters
    ----------
    name : str
        The linkage's name, used for its files: letters, digits, ``.``, ``_``, ``-``.
    linkage : Model
        The mechanism's ``[linkage]`` table: its type, lengths (mm) and input.
    parts : PartsTable or None, optional
        The ``[parts]`` table ``linkgen build`` makes parts from.
    loads : tuple of LoadTable, optional
        The ``[[loads]]`` the linkage holds (at most 100).
    output : OutputTable, optional
        Formats and the files' flavours.
    kit : KitTable or None, optional
        The frame and hardware round the linkage.
    dynamics : DynamicsTable or None, optional
        The links' materials and masses, speed, gravity and springs: the report's ``dynamics`` section.
    slack : SlackTable or None, optional
        The joints' play and the links' length tolerances whose band the report gives (needs ``[parts]``).
    """

    name: str = name_field("linkage")
    linkage: Model
    parts: PartsTable | None = None
    loads: tuple[LoadTable, ...] = Field((), max_length=100, description="loads the linkage holds")
    output: OutputTable = OutputTable()
    kit: KitTable | None = None
    dynamics: DynamicsTable | None = None
    slack: SlackTable | None = None

    #: the mechanism registered for ``linkage.type``
    mechanism: ClassVar[Any] = None
    product: ClassVar[str] = "linkgen"
    noun: ClassVar[str] = "a linkage"

    @classmethod
    def validate_raw(cls, raw: Mapping[str, Any], folder: Path | None = None) -> LinkageSpec:
        """The spec of the raw template ``raw``, of the mechanism its ``linkage.type`` names (:func:`validate_spec`;
        a linkage template names no files, so ``folder`` is not read)."""
        return validate_spec(raw)

    @model_validator(mode="after")
    def _bounded(self) -> LinkageSpec:
        """Every length of the ``[linkage]`` table (mm) at most ten metres in size and its speed (rpm) at most
        :data:`MAX_RPM`, so that the kinematics' numbers stay finite (the least length is every template's,
        :data:`~camgen.core.spec.MIN_LENGTH_MM`)."""
        for key, info in type(self.linkage).model_fields.items():
            value, extra = getattr(self.linkage, key), info.json_schema_extra
            unit_name = extra.get("unit") if isinstance(extra, dict) else None
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                continue
            if unit_name == "mm" and not abs(value) <= MAX_LENGTH_MM:
                rule = f"at most {MAX_LENGTH_MM:g} mm in size"
            elif unit_name == "rpm" and not value <= MAX_RPM:
                rule = f"> 0 and <= {MAX_RPM:g} rpm"
            else:
                continue
            raise ValueError(f"linkage.{key}: must be {rule} (got {value!r})")
        if self.kit is not None:
            bolt = self.kit.hardware
            if self.parts is None:
                raise ValueError("kit: a kit mounts the linkage's parts: add a [parts] table")
            if self.parts.pin_diameter != bolt.diameter:
                sizes = ", ".join(f"{b.name} for {b.diameter:g} mm" for b in BOLTS.values())
                raise ValueError(f"kit.bolt: the pins are {bolt.name} bolts, so parts.pin_diameter must be "
                                 f"{bolt.diameter:g} mm (got {self.parts.pin_diameter:g}); bolts: {sizes}")
        return self

    @model_validator(mode="after")
    def _slack_fits(self) -> LinkageSpec:
        """A ``[slack]`` table takes its holes from ``[parts]``, whose clearance must be less than the pin."""
        if self.slack is not None:
            self.slack.play(self.parts)
        return self


@functools.cache
def spec_model(mechanism: Mechanism) -> type[LinkageSpec]:
    """The :class:`LinkageSpec` of templates of ``mechanism`` (made once a mechanism)."""
    model = create_model(f"{mechanism.table.__name__}Spec", __base__=LinkageSpec, linkage=(mechanism.table, ...))
    model.mechanism = mechanism
    model.noun = f"a {mechanism.types[0]} linkage"
    return model


def validate_spec(raw: Mapping[str, Any], mechanisms: Mapping[str, Mechanism] = MECHANISMS) -> LinkageSpec:
    """The spec of a raw template, its ``[linkage]`` validated by the mechanism ``mechanisms`` registers for its
    type; a one-line :class:`SpecError` otherwise.

    Parameters
    ----------
    raw : mapping
        The template as TOML reads it: ``{"name": ..., "linkage": {"type": ..., ...}, "parts": {...}, ...}``.
    mechanisms : mapping of str to Mechanism, optional
        The registry to look ``linkage.type`` up in; by default every mechanism linkgen has.

    Returns
    -------
    LinkageSpec
        The validated, frozen spec (its ``linkage`` the mechanism's own table).

    Raises
    ------
    SpecError
        No ``[linkage]`` table or type, an unknown type (with the closest one), or the first problem of the
        template, in one line naming the key.
    """
    linkage = raw.get("linkage")
    if not isinstance(linkage, Mapping):
        raise SpecError("missing: give a [linkage] table with its type and lengths", "linkage")
    kind = linkage.get("type")
    if kind is None:
        raise SpecError(f"missing: one of {', '.join(mechanisms)}", "linkage.type")
    return validate(spec_model(mechanisms[choose(kind, mechanisms, "linkage.type")]), raw)


def load_spec(path: str | Path, overrides: Iterable[str] = (),
              mechanisms: Mapping[str, Mechanism] = MECHANISMS) -> LinkageSpec:
    """Read a TOML linkage template, merge ``key=value`` overrides, validate.

    Parameters
    ----------
    path : str or Path
        The template file (its ``base``, if any, relative to it).
    overrides : iterable of str
        ``"key=value"`` strings as ``--set`` takes them (``"linkage.crank=60"``), merged in before validation.
    mechanisms : mapping
        The mechanisms by ``linkage.type`` (:data:`linkgen.mechanisms.MECHANISMS`).

    Returns
    -------
    LinkageSpec
        The validated spec; ``spec.linkage`` is its mechanism's table.

    Raises
    ------
    SpecError
        The file cannot be read, is another command's template, or fails validation (one line naming the key).
    """
    raw = read_template(path, overrides)
    check_kind(raw, "linkgen")
    return validate_spec(raw, mechanisms)
