"""Frozen dataclasses made quickly where a design makes many small ones, and their values computed once."""
from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from typing import Any, Generic, TypeVar, overload

_T = TypeVar("_T")


@functools.cache
def record_maker(cls: type[_T]) -> Callable[..., _T]:
    """A maker of the frozen dataclass ``cls``'s instances without its generated ``__init__`` (one checked attribute
    set at a time) and without ``__post_init__``, made once a class: for classes without one, on hot paths where the
    values are known sound. A function taking the class's fields by keyword, each with a plain default optional
    (a field with a default factory is to be given), which makes an instance and sets its ``__dict__`` at once to
    the dict of its fields in their order. Python's own binding of the keywords refuses a field without a value or a
    name that is no field (a TypeError naming it), so the function checks nothing itself; its source is written out
    and run as dataclasses does a class's ``__init__`` (the names it uses besides the fields' prefixed, so that no
    field shadows them)."""
    fields = dataclasses.fields(cls)
    scope: dict[str, Any] = {"_records_new": object.__new__, "_records_set": object.__setattr__, "_records_cls": cls}
    params = []
    for f in fields:
        if f.default is dataclasses.MISSING:       # no default, or a default factory: to be given
            params.append(f.name)
        else:
            scope[f"_records_default_{f.name}"] = f.default
            params.append(f"{f.name}=_records_default_{f.name}")
    own = ", ".join(f"{f.name!r}: {f.name}" for f in fields)
    exec(f"def {cls.__name__}(*, {', '.join(params)}):\n"          # our own source, from the fields
         f"    _records_out = _records_new(_records_cls)\n"
         f"    _records_set(_records_out, '__dict__', {{{own}}})\n"
         f"    return _records_out\n", scope)
    return scope[cls.__name__]


class once(Generic[_T]):
    """A property computed when first read and kept in the instance's ``__dict__`` under its own name, so that later
    reads find it there and never call this descriptor: :class:`functools.cached_property` without the lock Python
    3.11's takes on every first computation (about 0.6 us each, several a design; Python 3.12 dropped it too). For
    the values of objects built and read by one thread, each a pure function of its instance (were two threads to
    race, each would compute the same value and one would be kept). A frozen dataclass's instance takes it: the
    value goes into its ``__dict__``, not through its ``__setattr__``; so does a template model's (see
    :class:`camgen.core.spec.Model`). The project's one cached property."""

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
