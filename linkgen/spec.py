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

from camgen.errors import SpecError
from camgen.templates import NAME_PATTERN, Model, read_toml, unit, validate

LINKAGE_TYPES = ("four-bar", "slider-crank", "scotch-yoke", "whitworth", "crank-shaper",
                 "chebyshev", "hoekens", "roberts", "watt")
FORMATS = ("json", "png", "svg")


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


def _template(spec: type[Model]) -> type[Model]:
    class Template(Model):
        name: str = Field(pattern=NAME_PATTERN, description="linkage name, used for file names")
        linkage: spec  # type: ignore[valid-type]
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
    return validate_linkage(read_toml(path, overrides))
