"""Option strings (a law's name, a follower type, an assembly) checked against the values they may take.

One helper for every such option, so a typo always gets the same kind of message, naming
the field, the closest valid value and all of them::

    >>> choose("cycloid", ("harmonic", "cycloidal"), "law")
    Traceback (most recent call last):
    ...
    camgen.core.errors.SpecError: law: unknown value 'cycloid' (did you mean 'cycloidal'?); one of harmonic, cycloidal
"""
from __future__ import annotations

import difflib
from collections.abc import Iterable

from camgen.core.errors import SpecError


def choose(value: object, options: Iterable[str], field: str) -> str:
    """``value`` if it is one of ``options``; otherwise a :class:`SpecError` on ``field`` listing them."""
    allowed = tuple(options)
    if isinstance(value, str) and value in allowed:
        return value
    raise SpecError(not_one_of(value, allowed), field)


def not_one_of(value: object, options: Iterable[str]) -> str:
    """What to say of ``value``, which is none of ``options``: the closest of them for a string (a typo), and all of
    them. The one message of every enumerated value, whether a registry checks it (:func:`choose`) or a template
    model does (:func:`camgen.core.spec.validate`)."""
    allowed = tuple(options)
    listed = ", ".join(allowed)
    if not isinstance(value, str):
        return f"must be one of {listed} (got {value!r})"
    close = difflib.get_close_matches(value, allowed, n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    return f"unknown value {value!r}{hint}; one of {listed}"
