"""Cam templates: the validated, frozen description of one cam.

A template is a TOML file (or the same mapping from Python). :func:`load_template`
reads it, merges ``--set`` overrides into the raw mapping, then validates it all at
once; every problem becomes a :class:`~camgen.errors.SpecError` whose message names
the field, what is allowed and what was given, e.g.
``motion[2].angle: must be > 0 degrees (got -30)``.
"""
from __future__ import annotations

import copy
import tomllib
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from camgen.errors import SpecError
from camgen.laws import LAW_NAMES, LAW_PARAMS

LawName = Literal[LAW_NAMES]  # type: ignore[valid-type]
FORMATS = ("dxf", "stl", "json", "png", "svg")
#: every law parameter key a segment may carry
LAW_PARAMS_ALL = sorted({k for keys in LAW_PARAMS.values() for k in keys})


def _unit(unit: str) -> dict[str, str]:
    return {"unit": unit}


class _Model(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid", allow_inf_nan=False, strict=False)


class CamSpec(_Model):
    """The cam body."""

    base_radius: float = Field(gt=0, description="base circle radius", json_schema_extra=_unit("mm"))
    thickness: float = Field(gt=0, description="plate thickness (STL extrusion)", json_schema_extra=_unit("mm"))
    bore: float = Field(0.0, ge=0, description="bore diameter, 0 for none", json_schema_extra=_unit("mm"))
    rotation: Literal["ccw", "cw"] = Field("ccw", description="sense of rotation seen from +Z")
    allow_undercut: bool = Field(False, description="export the cutter's envelope instead of refusing an undercut")


class FollowerSpec(_Model):
    """The follower."""

    type: Literal["translating-roller"] = Field(description="follower type")
    roller_radius: float = Field(gt=0, description="roller radius", json_schema_extra=_unit("mm"))
    offset: float = Field(0.0, description="follower axis offset, + to the right (+X)", json_schema_extra=_unit("mm"))


class SegmentSpec(_Model):
    """One segment of the motion program; law parameters sit beside the law name."""

    type: Literal["rise", "dwell", "return"] = Field(description="segment type")
    angle: float = Field(gt=0, le=360, description="cam angle of the segment", json_schema_extra=_unit("degrees"))
    lift: float | None = Field(None, gt=0, description="follower travel (rise and return)",
                               json_schema_extra=_unit("mm"))
    law: LawName | None = Field(None, description="motion law (rise and return)")  # type: ignore[valid-type]
    ratio: float | None = Field(None, gt=0, description="parabolic: acceleration ratio a1/a2")
    form: Literal["blended", "drafted"] | None = Field(None, description="modified-uniform: form")
    blend: float | None = Field(None, gt=0, le=0.5, description="modified-uniform blended: blend fraction of the angle")
    blend_law: Literal["cycloidal", "parabolic"] | None = Field(None, description="modified-uniform blended: blends")
    conditions: list[tuple[float, int, float]] | None = Field(
        None, description="polynomial: [u, derivative order, value] in normalised units")
    degree: int | None = Field(None, ge=1, description="polynomial: degree (default: conditions - 1)")

    @model_validator(mode="after")
    def _fits_type(self) -> "SegmentSpec":
        params = {k for k in LAW_PARAMS_ALL if getattr(self, k) is not None}
        if self.type == "dwell":
            extra = sorted(({"lift", "law"} | params) & self.model_fields_set)
            if extra:
                raise ValueError(f"{extra[0]}: a dwell takes only 'angle'")
            return self
        if self.lift is None:
            raise ValueError(f"lift: required for a {self.type} (mm, > 0)")
        if self.law is None:
            raise ValueError(f"law: required for a {self.type}; one of {', '.join(LAW_NAMES)}")
        allowed = set(LAW_PARAMS[self.law])
        for key in sorted(params - allowed):
            takes = ", ".join(LAW_PARAMS[self.law]) or "none"
            raise ValueError(f"{key}: not a parameter of law '{self.law}' (its parameters: {takes})")
        if self.law == "polynomial" and self.conditions is None:
            raise ValueError("conditions: required for law 'polynomial' ([[u, order, value], ...])")
        return self

    def law_params(self) -> dict[str, Any]:
        """The law parameters given for this segment."""
        return {k: getattr(self, k) for k in LAW_PARAMS.get(self.law or "", ()) if getattr(self, k) is not None}


class OutputSpec(_Model):
    """What to write and how accurately."""

    tolerance: float = Field(0.01, ge=1e-6, le=1.0, description="max distance of the exported outline from the "
                             "exact cam surface", json_schema_extra=_unit("mm"))
    formats: tuple[Literal[FORMATS], ...] = Field(FORMATS, min_length=1,  # type: ignore[valid-type]
                                                  description="files to write")


class CamTemplate(_Model):
    """A whole cam template."""

    name: str = Field(pattern=r"^[A-Za-z0-9][A-Za-z0-9._-]{0,99}$", description="part name, used for file names")
    cam: CamSpec
    follower: FollowerSpec
    motion: list[SegmentSpec] = Field(min_length=1, description="segments in order from theta = 0")
    output: OutputSpec = OutputSpec()

    @model_validator(mode="after")
    def _whole(self) -> "CamTemplate":
        total = sum(seg.angle for seg in self.motion)
        if abs(total - 360.0) > 1e-9:
            raise ValueError(f"motion: segment angles add up to {total:.6g} degrees; they must add up to 360")
        prime = self.cam.base_radius + self.follower.roller_radius
        if not abs(self.follower.offset) < prime:
            raise ValueError(f"follower.offset: |offset| must be < the prime radius {prime:.6g} mm "
                             f"(base_radius + roller_radius; got {self.follower.offset:.6g} mm)")
        return self

    @property
    def prime_radius(self) -> float:
        return self.cam.base_radius + self.follower.roller_radius


# ---------------------------------------------------------------- loading and errors

def parse_overrides(pairs: Iterable[str]) -> list[tuple[str, Any]]:
    """``key=value`` strings as (dotted key, value); values are read as TOML values, else kept as text."""
    out = []
    for pair in pairs:
        key, sep, text = pair.partition("=")
        if not sep or not key.strip():
            raise SpecError(f"expected key=value, e.g. motion.0.lift=25 (got {pair!r})", "--set")
        try:
            value = tomllib.loads(f"v = {text.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            value = text.strip()
        out.append((key.strip(), value))
    return out


def apply_overrides(raw: Mapping[str, Any], overrides: Iterable[tuple[str, Any]]) -> dict[str, Any]:
    """A copy of the raw template with each dotted key set (list items by index: ``motion.0.lift``)."""
    data = copy.deepcopy(dict(raw))
    for key, value in overrides:
        node: Any = data
        parts = key.split(".")
        for depth, part in enumerate(parts):
            last = depth == len(parts) - 1
            where = ".".join(parts[: depth + 1])
            if isinstance(node, list):
                if not part.isdigit() or int(part) >= len(node):
                    raise SpecError(f"no item {part} in '{'.'.join(parts[:depth]) or key}' "
                                    f"(it has {len(node)} items, indexed from 0)", f"--set {key}")
                index: Any = int(part)
            elif isinstance(node, dict):
                index = part
            else:
                raise SpecError(f"'{'.'.join(parts[:depth])}' is a value, not a table", f"--set {key}")
            if last:
                node[index] = value
            else:
                if isinstance(node, dict) and index not in node:
                    node[index] = {}
                node = node[index]
                if not isinstance(node, (dict, list)):
                    raise SpecError(f"'{where}' is a value, not a table", f"--set {key}")
    return data


def validate_template(raw: Mapping[str, Any]) -> CamTemplate:
    """A :class:`CamTemplate` from a raw mapping, or a one-line :class:`SpecError`."""
    try:
        return CamTemplate.model_validate(raw)
    except ValidationError as exc:
        raise _first_error(exc) from None


def load_template(path: str | Path, overrides: Iterable[str] = ()) -> CamTemplate:
    """Read, override and validate a TOML template."""
    path = Path(path)
    try:
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise SpecError(f"no such file: {path}", "template") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise SpecError(f"{path} is not valid TOML: {exc}", "template") from None
    return validate_template(apply_overrides(raw, parse_overrides(overrides)))


_WORDS = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<", "less_than_equal": "<="}


def _path(loc: tuple) -> str:
    text = ""
    for part in loc:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text


def _unwrap(annotation: Any) -> Any:
    """The model inside ``Optional[...]`` and ``list[...]`` annotations (or the annotation itself)."""
    for _ in range(3):
        args = [a for a in getattr(annotation, "__args__", ()) if a is not type(None)]
        if hasattr(annotation, "model_fields") or not args:
            break
        annotation = args[0]
    return annotation


def _field(loc: tuple) -> Any:
    """The pydantic FieldInfo at ``loc`` in a CamTemplate, or None."""
    model: Any = CamTemplate
    info = None
    for part in loc:
        if isinstance(part, int):
            continue
        fields = getattr(model, "model_fields", None)
        if not fields or part not in fields:
            return None
        info = fields[part]
        model = _unwrap(info.annotation)
    return info


def _first_error(exc: ValidationError) -> SpecError:
    err = exc.errors(include_url=False)[0]
    loc, kind, ctx = tuple(err["loc"]), err["type"], err.get("ctx", {})
    given = err.get("input")
    info = _field(loc)
    unit = ((info.json_schema_extra or {}) if info is not None else {}).get("unit", "")
    got = f" (got {given!r})" if not isinstance(given, (dict, list)) else ""
    if kind in _WORDS:
        bound = ctx[{"greater_than": "gt", "greater_than_equal": "ge", "less_than": "lt",
                     "less_than_equal": "le"}[kind]]
        bounds = [f"{_WORDS[k]} {getattr(m, a)}" for k, a in (("greater_than", "gt"), ("greater_than_equal", "ge"),
                                                               ("less_than", "lt"), ("less_than_equal", "le"))
                  for m in (info.metadata if info is not None else []) if getattr(m, a, None) is not None]
        rule = " and ".join(bounds) if bounds else f"{_WORDS[kind]} {bound}"
        msg = f"must be {rule}{' ' + unit if unit else ''}{got}"
    elif kind == "finite_number":
        msg = f"must be a finite number{' of ' + unit if unit else ''}{got}"
    elif kind == "missing":
        what = info.description if info is not None and info.description else "a value"
        msg = f"missing: give {what}{' in ' + unit if unit else ''}"
    elif kind == "extra_forbidden":
        parent = _field(loc[:-1])
        model = _unwrap(parent.annotation) if parent is not None else CamTemplate
        keys = ", ".join(getattr(model, "model_fields", {}))
        msg = f"unknown key; known keys here: {keys}"
    elif kind == "literal_error":
        msg = f"must be one of {ctx.get('expected')}{got}"
    elif kind in ("float_type", "float_parsing", "int_type", "int_parsing", "int_from_float"):
        msg = f"must be a {'whole ' if kind.startswith('int') else ''}number{' of ' + unit if unit else ''}{got}"
    elif kind == "too_short":
        msg = f"needs at least {ctx.get('min_length')} item(s)"
    elif kind == "string_pattern_mismatch":
        msg = f"must be letters, digits, '.', '_' or '-', starting with a letter or digit{got}"
    elif kind == "value_error":
        text = str(ctx.get("error", err["msg"]))
        head, sep, rest = text.partition(": ")
        if sep and " " not in head:  # the validator named a field below loc
            loc = loc + tuple(int(p) if p.isdigit() else p for p in head.replace("[", ".").replace("]", "")
                              .split("."))
            text = rest
        return SpecError(text, _path(loc) or None)
    else:
        msg = f"{err['msg'][0].lower()}{err['msg'][1:]}{got}"
    return SpecError(msg, _path(loc) or None)

