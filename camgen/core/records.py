"""Frozen dataclasses made quickly where a design makes many small ones."""
from __future__ import annotations

import dataclasses
import functools
from typing import Any, TypeVar

_T = TypeVar("_T")


def unchecked(cls: type[_T], **fields: Any) -> _T:
    """An instance of the frozen dataclass ``cls`` holding ``fields`` and the defaults of the fields not given, made
    without its generated ``__init__`` (one checked attribute set at a time) and without ``__post_init__``: for
    classes without one, on hot paths where the values are known sound. A field with neither a value nor a plain
    default, or a name that is no field, raises TypeError, as ``cls(...)`` would."""
    out = object.__new__(cls)
    own = out.__dict__
    defaults, names = _layout(cls)
    own.update(defaults)
    own.update(fields)
    if own.keys() != names:
        raise TypeError(f"{cls.__name__}: fields without a value {sorted(names - own.keys())}, "
                        f"not fields {sorted(own.keys() - names)}")
    return out


@functools.cache
def _layout(cls: type) -> tuple[dict[str, Any], frozenset[str]]:
    """The dataclass ``cls``'s fields' plain defaults (those with a default factory are left to be given) and every
    field's name (not its class variables')."""
    fields = dataclasses.fields(cls)
    return ({f.name: f.default for f in fields if f.default is not dataclasses.MISSING},
            frozenset(f.name for f in fields))
