"""The form of a template: one entry per field of the validated spec's models, read from their JSON schema
(description, unit, range, allowed values) with the value the template gives or the default it leaves."""
from __future__ import annotations

from collections.abc import Mapping
from functools import cache
from typing import Any

from pydantic import BaseModel

#: the JSON-schema keys a form entry keeps (what a field allows)
KEPT = ("description", "unit", "minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum", "enum", "const",
        "type", "default")


@cache
def _properties(model: type[BaseModel]) -> dict[str, Any]:
    """The JSON schema's ``properties`` of ``model`` (its fields by their names)."""
    props: dict[str, Any] = model.model_json_schema().get("properties", {})
    return props


def _allowed(schema: Mapping[str, Any]) -> dict[str, Any]:
    """What ``schema`` (one property) says of its values; the types of an ``anyOf`` gathered under ``type``."""
    out = {k: schema[k] for k in KEPT if k in schema}
    options = schema.get("anyOf", ())
    types = [o["type"] for o in options if "type" in o]
    if types and "type" not in out:
        out["type"] = types
    for o in options:
        for k in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum", "enum", "const"):
            if k in o and k not in out:
                out[k] = o[k]
    return out


def _plain(value: Any) -> Any:
    """``value`` as JSON gives it (tuples as lists)."""
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    return value if value is None or isinstance(value, (bool, int, float, str)) else str(value)


def _given(raw: Any, key: str | int) -> Any:
    """``raw[key]`` where the template gives it, else None."""
    if isinstance(raw, Mapping):
        return raw.get(key)
    if isinstance(raw, list) and isinstance(key, int) and key < len(raw):
        return raw[key]
    return None


def join(path: str, key: str | int) -> str:
    """A field's path as the spec's errors name it: ``motion[0].lift``, ``linkage.joints.G``."""
    if isinstance(key, int):
        return f"{path}[{key}]"
    return f"{path}.{key}" if path else key


def _walk(model: BaseModel, raw: Any, path: str, out: list[dict[str, Any]]) -> None:
    props = _properties(type(model))
    for name in type(model).model_fields:
        value = getattr(model, name)
        given = _given(raw, name)
        here = join(path, name)
        if isinstance(value, BaseModel):
            _walk(value, given, here, out)
        elif isinstance(value, (list, tuple)) and value and all(isinstance(v, BaseModel) for v in value):
            for i, v in enumerate(value):
                _walk(v, _given(given, i), join(here, i), out)
        elif isinstance(value, Mapping) and value and all(isinstance(v, BaseModel) for v in value.values()):
            for k, v in value.items():
                _walk(v, _given(given, k), join(here, k), out)
        elif isinstance(value, Mapping) and isinstance(given, Mapping) and given:
            item = _allowed(props.get(name, {}))
            for k in given:
                out.append({"path": join(here, str(k)), **item, "value": _plain(given[k]), "given": True})
        else:
            out.append({"path": here, **_allowed(props.get(name, {})),
                        "value": _plain(given if given is not None else value), "given": given is not None})


def form(spec: BaseModel, raw: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Every field of the validated ``spec`` whose raw template is ``raw``, in the models' order.

    Returns
    -------
    list of dict
        Each ``{"path": "motion[0].lift", "value": ..., "given": bool, "description": ..., "unit": "mm", ...}``:
        the path as a :class:`~camgen.core.errors.SpecError` names the field, the template's value (``given``) or
        the default, and what the field's JSON schema allows (``minimum``, ``maximum``, ``enum``, ``type``).
        A table of the user's own keys (``[linkage.joints]``) gives one entry per key.
    """
    out: list[dict[str, Any]] = []
    _walk(spec, raw, "", out)
    return out
