"""Shared fixtures: the issue's reference template as a raw mapping."""
from __future__ import annotations

import copy
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

RDRD = {
    "name": "rdrd",
    "cam": {"base_radius": 40.0, "thickness": 8.0, "bore": 10.0, "rotation": "ccw"},
    "follower": {"type": "translating-roller", "roller_radius": 10.0, "offset": 5.0},
    "motion": [
        {"type": "rise", "law": "cycloidal", "lift": 20.0, "angle": 120.0},
        {"type": "dwell", "angle": 60.0},
        {"type": "return", "law": "harmonic", "lift": 20.0, "angle": 120.0},
        {"type": "dwell", "angle": 60.0},
    ],
    "output": {"tolerance": 0.01},
}


@pytest.fixture
def raw() -> dict:
    """A fresh deep copy of the rdrd template mapping."""
    return copy.deepcopy(RDRD)


def template(overrides: dict | None = None, **changes):
    """A validated template: rdrd with dotted-key ``overrides`` applied."""
    from camgen.spec import validate_spec
    from camgen.core.spec import apply_overrides

    return validate_spec(apply_overrides(RDRD, list((overrides or {}).items())))
