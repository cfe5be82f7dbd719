"""``camgen animate`` of a barrel cam: a side view of the developed groove sliding past the roller, the roller drawn
at the developed pitch curve's height (read from the pixels); one GIF, the same bytes twice."""
from __future__ import annotations

import math

import numpy as np

from camgen.kinds.barrel.page import barrel_page
from tests.conftest import ROOT
from tests.support.kind_animation import assert_animated, drawn, on_circle, page_frame

BARREL = ROOT / "templates" / "barrel.toml"


def test_barrel_gif(tmp_path):
    assert_animated(BARREL, tmp_path)


def test_roller_on_the_developed_pitch_curve():
    """Frame k of 12 is cam angle 30 k degrees: the roller's circle is drawn about (0, y(theta)), y the developed
    pitch curve's height there (the base's 15 mm + s(theta))."""
    design, report, _ = page_frame(BARREL, 12, 0)
    box = barrel_page(design, report).scene.bounds()
    frames = drawn(BARREL, 12, (320, 240))
    cam = design.cam
    theta = 2 * math.pi * np.arange(12) / 12
    y = cam.pitch(theta).point[:, 1]
    r = cam.contact_radius
    for k in (0, 3, 6):
        assert on_circle(frames[k], box, (0.0, y[k]), r) == 1.0
    assert on_circle(frames[0], box, (0.0, y[6]), r) < 0.5
