"""``camgen animate`` of a grooved cam: the cam turning with its groove round the roller, the roller drawn where
the island's pitch curve puts it (read from the pixels), one GIF of the asked frames and size, one turn."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.followers.base import rotate
from camgen.kinds.grooved.page import grooved_page
from tests.conftest import ROOT
from tests.support.kind_animation import assert_animated, drawn, on_circle, page_frame

GROOVED = ROOT / "templates" / "grooved.toml"


def test_grooved_gif(tmp_path):
    assert_animated(GROOVED, tmp_path)


def test_roller_in_the_groove():
    """Frame k of 12 turns the cam by 30 k degrees in its sense: the roller's circle is drawn about the pitch point
    turned with it, R(sense theta) p(theta), on the in-line follower's axis at prime radius + s(theta)."""
    design, report, _ = page_frame(GROOVED, 12, 0)
    box = grooved_page(design, report).scene.bounds()
    frames = drawn(GROOVED, 12, (320, 240))
    cam = design.profile.cam
    theta = 2 * math.pi * np.arange(12) / 12
    centre = rotate(cam.pitch(theta).point, cam.follower.sense * theta)
    s = cam.program.evaluate(theta)[0]
    assert centre[:, 0] == pytest.approx(np.zeros(12), abs=1e-9)                   # in line: on x = 0
    assert centre[:, 1] == pytest.approx(cam.base_radius + cam.contact_radius + s, abs=1e-9)
    r = cam.contact_radius
    for k in (0, 4, 8):
        assert on_circle(frames[k], box, centre[k], r) == 1.0
    assert on_circle(frames[0], box, centre[0] + np.array([0.0, 0.5 * r]), r) < 0.8
