"""A registry both products build theirs with: entries by the names they answer to, read-only, a name that two
entries claim refused (camgen's cam kinds, :data:`camgen.kinds.KINDS`; linkgen's mechanisms,
:data:`linkgen.mechanisms.MECHANISMS`)."""
from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from types import MappingProxyType
from typing import TypeVar

from camgen.core.errors import SpecError

T = TypeVar("T")


def registry(entries: Iterable[T], names: Callable[[T], Iterable[str]], field: str, what: str,
             base: Mapping[str, T] | None = None) -> Mapping[str, T]:
    """A read-only ``{name: entry}`` of ``base`` and then ``entries``, in order, each entry under every name
    ``names(entry)`` gives.

    Parameters
    ----------
    entries : iterable
        The entries to add, in the order their names are listed.
    names : callable
        An entry's names (a cam kind's ``(name,)``, a mechanism's ``types``).
    field : str
        The template field the names are values of (``cam.kind``, ``linkage.type``), for the message.
    what : str
        What an entry is, for the message (``a cam kind``).
    base : mapping, optional
        A registry to start from (left as it is).

    Raises
    ------
    SpecError
        A name that two entries claim: ``<field>: '<name>' already names <what>``.
    """
    out = dict(base or {})
    for entry in entries:
        for name in names(entry):
            if name in out:
                raise SpecError(f"{name!r} already names {what}", field)
            out[name] = entry
    return MappingProxyType(out)
