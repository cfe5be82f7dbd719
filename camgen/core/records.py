"""Values of frozen records computed once."""
from __future__ import annotations

from collections.abc import Callable
from typing import Any, Generic, TypeVar, overload

_T = TypeVar("_T")


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
