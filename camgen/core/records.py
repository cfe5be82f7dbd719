"""Frozen dataclasses made quickly where a design makes many small ones, and their values computed once."""
from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from typing import Any, Generic, TypeVar, overload

_T = TypeVar("_T")


def unchecked(cls: type[_T], **fields: Any) -> _T:
    """An instance of the frozen dataclass ``cls`` holding ``fields`` and the defaults of the fields not given, made
    without its generated ``__init__`` (one checked attribute set at a time) and without ``__post_init__``: for
    classes without one, on hot paths where the values are known sound. A field with neither a value nor a plain
    default, or a name that is no field, raises TypeError, as ``cls(...)`` would. The instance's ``__dict__`` is the
    dict of its fields made here (the defaults first, as before), set at once: no dict filled key by key."""
    out = _new(cls)
    defaults, names = _layout(cls)
    own = defaults | fields if defaults else fields     # a call's keyword arguments are a fresh dict: its own
    if own.keys() != names:
        raise TypeError(f"{cls.__name__}: fields without a value {sorted(names - own.keys())}, "
                        f"not fields {sorted(own.keys() - names)}")
    _set(out, "__dict__", own)
    return out


#: object's own constructor and attribute setter (a frozen dataclass's refuses to set)
_new, _set = object.__new__, object.__setattr__


@functools.cache
def _layout(cls: type) -> tuple[dict[str, Any], frozenset[str]]:
    """The dataclass ``cls``'s fields' plain defaults (those with a default factory are left to be given) and every
    field's name (not its class variables')."""
    fields = dataclasses.fields(cls)
    return ({f.name: f.default for f in fields if f.default is not dataclasses.MISSING},
            frozenset(f.name for f in fields))


class once(Generic[_T]):
    """A property computed when first read and kept in the instance's ``__dict__`` under its own name, so that later
    reads find it there and never call this descriptor: :class:`functools.cached_property` without the lock Python
    3.11's takes on every first computation (about 0.6 us each, several a design; Python 3.12 dropped it too). For
    the values of objects built and read by one thread, each a pure function of its instance (were two threads to
    race, each would compute the same value and one would be kept). A frozen dataclass's instance takes it: the
    value goes into its ``__dict__``, not through its ``__setattr__``."""

    def __init__(self, func: Callable[[Any], _T]) -> None:
        self.func = func
        self.name = func.__name__
        self.__doc__ = func.__doc__

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    @overload
    def __get__(self, instance: None, owner: type | None = None) -> once[_T]: ...

    @overload
    def __get__(self, instance: object, owner: type | None = None) -> _T: ...

    def __get__(self, instance: object | None, owner: type | None = None) -> once[_T] | _T:
        if instance is None:
            return self
        value = instance.__dict__[self.name] = self.func(instance)
        return value
