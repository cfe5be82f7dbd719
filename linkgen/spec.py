"""Linkage templates: one validated, frozen model per linkage type.

The ``[linkage]`` table's ``type`` picks the model; every other key is checked by
it, with the same one-line errors as camgen's (``linkage.crank: must be > 0 mm
(got -5)``).
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, Literal

from pydantic import Field

from camgen.core.errors import SpecError
from camgen.core.spec import NAME_PATTERN, Model, read_template, unit, validate

LINKAGE_TYPES = ("four-bar", "slider-crank", "scotch-yoke", "whitworth", "crank-shaper",
                 "chebyshev", "hoekens", "roberts", "watt")
FORMATS = ("json", "png", "svg", "cut-svg", "dxf", "stl", "3mf")


def _length(description: str) -> Any:
    return Field(gt=0, description=description, json_schema_extra=unit("mm"))


def _rpm() -> Any:
    return Field(60.0, gt=0, description="input speed", json_schema_extra=unit("rpm"))


class FourBarSpec(Model):
    type: Literal["four-bar"]
    ground: float = _length("ground link: input pivot to output pivot")
    crank: float = _length("input link")
    coupler: float = _length("coupler")
    rocker: float = _length("output link")
    point_distance: float = Field(0.0, ge=0, description="coupler point: distance from the crank pin",
                                  json_schema_extra=unit("mm"))
    point_angle: float = Field(0.0, description="coupler point: angle from the coupler line, counter-clockwise",
                               json_schema_extra=unit("degrees"))
    assembly: Literal["open", "crossed"] = Field("open", description="assembly branch")
    input: Literal["crank", "rocker"] = Field("crank", description="driven link")
    rpm: float = _rpm()


class SliderCrankSpec(Model):
    type: Literal["slider-crank"]
    crank: float = _length("crank")
    rod: float = _length("connecting rod")
    offset: float = Field(0.0, description="slider line above the crank pivot", json_schema_extra=unit("mm"))
    rpm: float = _rpm()


class ScotchYokeSpec(Model):
    type: Literal["scotch-yoke"]
    crank: float = _length("crank")
    rpm: float = _rpm()


class WhitworthSpec(Model):
    type: Literal["whitworth"]
    crank: float = _length("driving crank")
    ground: float = _length("crank pivot to slotted-link pivot (< crank)")
    arm: float = _length("ram-driving arm on the slotted link")
    rod: float = _length("connecting rod from the arm to the ram")
    rpm: float = _rpm()


class CrankShaperSpec(Model):
    type: Literal["crank-shaper"]
    crank: float = _length("driving crank")
    ground: float = _length("crank pivot to lever pivot (> crank)")
    lever: float = _length("lever pivot to the ram line")
    rpm: float = _rpm()


class StraightLineSpec(Model):
    type: Literal["chebyshev", "hoekens", "roberts", "watt"]
    size: float = _length("scale: the length that is 1 in the canonical proportions")
    rpm: float = _rpm()


class LinkOutputSpec(Model):
    formats: tuple[Literal[FORMATS], ...] = Field(FORMATS, min_length=1,  # type: ignore[valid-type]
                                                  description="files to write")


class LinkOverride(Model):
    width: float = Field(gt=0, description="this link's width", json_schema_extra=unit("mm"))


class PartsTableSpec(Model):
    """Parts to cut and print (``linkgen build``)."""

    width: float = _length("bar width")
    thickness: float = _length("plate thickness")
    pin_diameter: float = _length("pin diameter")
    clearance: float = Field(0.2, ge=0, description="pin clearance: holes are pin + clearance",
                             json_schema_extra=unit("mm"))
    kerf: float = Field(0.0, ge=0, description="laser kerf: cut holes shrink by it, outlines grow by half",
                        json_schema_extra=unit("mm"))
    margin: float = Field(3.0, ge=0, description="sheet: gap between parts beyond the kerf",
                          json_schema_extra=unit("mm"))
    sheet: tuple[float, float] = Field((600.0, 400.0), description="sheet width and height",
                                       json_schema_extra=unit("mm"))
    pins: bool = Field(False, description="also write a printable pin (cylinder with a head)")
    tolerance: float = Field(0.01, ge=1e-6, le=1, description="chord tolerance of meshes and sheets",
                             json_schema_extra=unit("mm"))
    ground: LinkOverride | None = None
    crank: LinkOverride | None = None
    coupler: LinkOverride | None = None
    rocker: LinkOverride | None = None
    rod: LinkOverride | None = None
    slider: LinkOverride | None = None


def _template(spec: type[Model]) -> type[Model]:
    class Template(Model):
        name: str = Field(pattern=NAME_PATTERN, description="linkage name, used for file names")
        linkage: spec  # type: ignore[valid-type]
        parts: PartsTableSpec | None = None
        output: LinkOutputSpec = LinkOutputSpec()

    Template.__name__ = f"{spec.__name__}Template"
    return Template


SPECS: Mapping[str, type[Model]] = {
    "four-bar": FourBarSpec, "slider-crank": SliderCrankSpec, "scotch-yoke": ScotchYokeSpec,
    "whitworth": WhitworthSpec, "crank-shaper": CrankShaperSpec,
    **{name: StraightLineSpec for name in ("chebyshev", "hoekens", "roberts", "watt")},
}
TEMPLATES: Mapping[type[Model], type[Model]] = {spec: _template(spec) for spec in set(SPECS.values())}


def validate_linkage(raw: Mapping[str, Any]) -> Any:
    """The template model for ``raw['linkage']['type']``, validated; a one-line :class:`SpecError` otherwise."""
    linkage = raw.get("linkage")
    if not isinstance(linkage, Mapping):
        raise SpecError("missing: give a [linkage] table with its type and lengths", "linkage")
    kind = linkage.get("type")
    if kind is None:
        raise SpecError(f"missing: one of {', '.join(LINKAGE_TYPES)}", "linkage.type")
    if kind not in SPECS:
        raise SpecError(f"must be one of {', '.join(LINKAGE_TYPES)} (got {kind!r})", "linkage.type")
    return validate(TEMPLATES[SPECS[kind]], raw)


def load_linkage(path: str | Path, overrides: Iterable[str] = ()) -> Any:
    """Read a TOML linkage template, merge ``key=value`` overrides, validate."""
    return validate_linkage(read_template(path, overrides))
