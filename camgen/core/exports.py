"""A package's public names loaded on first use: what ``camgen/__init__.py`` and ``linkgen/__init__.py`` share.

A package lists its names by the module that holds each (``_EXPORTS``), imports them under ``TYPE_CHECKING`` for
type checkers and editors, and at run time takes its module-level ``__getattr__`` and ``__dir__`` from
:func:`lazy_exports`, so that ``import camgen`` loads none of them.
"""
from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping, Sequence
from typing import Any


def lazy_exports(package: str, exports: Mapping[str, str],
                 names: Sequence[str]) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """The module-level ``__getattr__`` and ``__dir__`` of ``package``: a name of ``exports`` (``{name: module}``)
    imported from its module when first asked for, an ``AttributeError`` for any other; ``names`` (its ``__all__``)
    listed by ``dir()``."""

    def __getattr__(name: str) -> Any:
        if name in exports:
            return getattr(importlib.import_module(exports[name]), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return list(names)

    return __getattr__, __dir__
