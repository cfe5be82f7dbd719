"""What the mechanism modules share: the fields of their ``[linkage]`` tables (and whole tables of lengths), the
report's number formats, and the refusal of parts a mechanism does not make.

Lengths are mm, speeds rpm; the report gives angles in degrees in [0, 360), counter-clockwise
from the ground line (+X), and rounds to 1e-9 so that its JSON is stable.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, Literal, NoReturn, get_args

from pydantic import Field, create_model

from camgen.core.errors import SpecError
from camgen.core.spec import Model, unit

#: a figure's kind (its files are ``<name>-<kind>.png|svg``) and a function of no arguments drawing it
Figure = tuple[str, Callable[[], Any]]


def length(description: str) -> Any:
    """A required length field (mm, > 0)."""
    return Field(gt=0, description=description, json_schema_extra=unit("mm"))


def rpm() -> Any:
    """The input speed field (rpm, > 0; 60 unless given): velocities and accelerations are given at it."""
    return Field(60.0, gt=0, description="input speed", json_schema_extra=unit("rpm"))


def lengths_table(name: str, doc: str, types: tuple[str, ...], **lengths: str) -> type[Model]:
    """A ``[linkage]`` table model of nothing but lengths, named ``name`` with docstring ``doc``: ``type`` (one of
    ``types``), then each of ``lengths`` (required, mm, > 0; the value is its description) in order, then ``rpm``."""
    fields: dict[str, Any] = {key: (float, length(description)) for key, description in lengths.items()}
    return create_model(name, __base__=Model, __doc__=doc, type=(Literal[types], ...), **fields, rpm=(float, rpm()))


def types_of(table: type[Model]) -> tuple[str, ...]:
    """The ``linkage.type`` values a table model accepts (its ``type`` literal)."""
    return get_args(table.model_fields["type"].annotation)


def omega(speed: float) -> float:
    """An input speed of ``speed`` rpm in rad/s."""
    return speed * 2 * math.pi / 60


def deg(x: float) -> float:
    """An angle of ``x`` radians in degrees in [0, 360), rounded to 1e-9."""
    return round(math.degrees(x) % 360.0, 9) % 360.0


def num(x: float) -> float | None:
    """A JSON number, or None where the value is unbounded (at a toggle)."""
    return round(float(x), 9) if math.isfinite(x) else None


def no_parts(kind: str) -> NoReturn:
    """Refuse ``[parts]`` for a mechanism of type ``kind`` that has none."""
    reason = {"whitworth": ": its crank sweeps over the slotted link's pivot and its rod over the crank pin's slot, "
                            "which no stack of plates keeps clear"}.get(kind, "")
    raise SpecError(f"no parts are made for {kind}{reason}", "linkage.type")
