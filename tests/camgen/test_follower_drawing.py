"""Each follower draws itself (:class:`camgen.followers.base.Follower`): its page's movers and still outlines and its
cam figure's lines are what the page and the figure drew before, when they held a branch a follower type.

The reference, tests/data/follower_drawing.json, was recorded from main before the change by
tests/support/follower_drawing.py (the same extraction as here); each drawing is compared point for point within 1e-9
mm."""
from __future__ import annotations

import json

import numpy as np
import pytest

from camgen.followers.drawing import Follower, Stroke
from tests.support.follower_drawing import DATA, STARTERS, drawing

RECORDED = json.loads(DATA.read_text())


def _same(now: list, then: list, what: str) -> None:
    a, b = np.asarray(now, float), np.asarray(then, float)
    assert a.shape == b.shape, (what, a.shape, b.shape)
    assert np.array_equal(np.isnan(a), np.isnan(b)), what
    assert np.nanmax(np.abs(a - b), initial=0.0) <= 1e-9, what


def test_the_reference_covers_every_follower_type():
    from camgen.followers import FOLLOWERS

    assert set(FOLLOWERS) <= set(RECORDED) == set(STARTERS)


@pytest.mark.parametrize("name", STARTERS)
def test_a_follower_draws_what_the_page_and_the_figure_drew(name):
    now, then = drawing(name), RECORDED[name]
    assert [(o["style"], o["closed"]) for o in now["still"]] == [(o["style"], o["closed"]) for o in then["still"]]
    for i, (a, b) in enumerate(zip(now["still"], then["still"], strict=True)):
        _same(a["points"], b["points"], f"{name}: still {i} ({a['style']})")
    assert [(m["name"], m["style"], m["radius"]) for m in now["movers"]] == \
        [(m["name"], m["style"], m["radius"]) for m in then["movers"]]
    for a, b in zip(now["movers"], then["movers"], strict=True):
        _same(a["points"], b["points"], f"{name}: mover {a['name']}")
    assert [(f["label"], f["marker"]) for f in now.get("figure", [])] == \
        [(f["label"], f["marker"]) for f in then.get("figure", [])]
    for a, b in zip(now.get("figure", []), then.get("figure", []), strict=True):
        _same(a["points"], b["points"], f"{name}: figure line {a['label']!r} {a['marker']}")


def test_every_built_follower_is_a_follower():
    """The five followers and the plate's roller answer the protocol, and a
    sketch is plain numpy: (frames, k, 2) points a stroke."""
    from camgen.kinds import kind_of
    from camgen.spec import validate_spec
    from camgen.starters import starter
    import tomllib

    for name in STARTERS:
        spec = validate_spec(tomllib.loads(starter(name, name)))
        design = kind_of(spec.kind).design(spec)
        cam = design.profile.cam if spec.kind == "grooved" else design.cam
        follower = cam.follower
        assert isinstance(follower, Follower), name
        theta = np.radians(np.arange(0.0, 360.0, 30.0))
        strokes = follower.sketch(theta, cam.pitch(theta), 100.0, (-20.0, 20.0), follower.contact_radius)
        assert strokes and all(isinstance(s, Stroke) and s.points.ndim == 3 and s.points.shape[0] == 12
                               and s.points.shape[2] == 2 for s in strokes), name
