"""Searches that several synthesis modules check, each run once a session (their tests share one xdist group, so one
worker runs the search)."""
from __future__ import annotations

import pytest

from tests.conftest import ROOT

#: the bundled figure-eight task (a Watt I six-bar path search)
FIGURE_EIGHT = ROOT / "templates" / "synth-figure-eight.toml"
#: the xdist group of every test that takes :func:`figure_eight_found`
FIGURE_EIGHT_GROUP = "figure-eight-search"


@pytest.fixture(scope="session")
def figure_eight_found():
    """The bundled figure-eight task with one start at its own budget (seed 1, 300 generations), synthesized once:
    tests/synthesis/test_figure_eight.py and the bundled-templates test of tests/synthesis/test_synthesis.py."""
    from linkgen.synthesis import load_task, synthesize

    return synthesize(load_task(FIGURE_EIGHT, ["task.starts=1"]))
