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
    listed = ", ".join(allowed)
    if not isinstance(value, str):
        raise SpecError(f"must be one of {listed} (got {value!r})", field)
    close = difflib.get_close_matches(value, allowed, n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    raise SpecError(f"unknown value {value!r}{hint}; one of {listed}", field)
