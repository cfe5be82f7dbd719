"""Fixtures shared by the machine kind's tests: each bundled machine designed once a run.

A bundled machine's design (``api.design(api.validate(template))`` of an unchanged template) is a frozen result
that the tests only read; designing the walking toy takes seconds, and several modules check the same one. The
modules that read :func:`bundled_design` carry the xdist group :data:`DESIGNS` (``--dist loadgroup``), so one worker
designs each machine once for all of them.
"""
from __future__ import annotations

import tomllib
from collections.abc import Callable

import pytest

from tests.conftest import ROOT

#: the xdist group of the modules that read :func:`bundled_design`
DESIGNS = "bundled-machine-designs"


@pytest.fixture(scope="session")
def bundled_design() -> Callable[[str], object]:
    """``design(name)``: the design of bundled template ``templates/NAME.toml`` as written, made at most once a run
    (per process); read it, never change it."""
    from camgen import api

    made: dict[str, object] = {}

    def design(name: str) -> object:
        if name not in made:
            raw = tomllib.loads((ROOT / "templates" / f"{name}.toml").read_text(encoding="utf-8"))
            made[name] = api.design(api.validate(raw))
        return made[name]

    return design
