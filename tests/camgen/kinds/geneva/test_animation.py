"""``camgen animate`` of a Geneva drive: the driver turning from alpha = -180 degrees, its pin drawn on the crank
circle where the driver's angle puts it (read from the pixels), the wheel indexing; one GIF, the same bytes twice."""
from __future__ import annotations

import math

import numpy as np

from camgen.kinds.geneva.page import geneva_page
from tests.conftest import ROOT
from tests.support.kind_animation import assert_animated, drawn, on_circle, page_frame

GENEVA = ROOT / "templates" / "geneva4.toml"


def test_geneva_gif(tmp_path):
    assert_animated(GENEVA, tmp_path)


def test_pin_on_the_driver():
    """Frame k of 12 is driver angle alpha = -180 + 30 k degrees: the pin's circle is drawn about crank_radius
    (cos alpha, sin alpha); the wheel stands still while the pin is out of its slots (frames 0 and 1 alike about
    the wheel) and turns while it is in one (frame 6: alpha = 0, the pin on the line of centres)."""
    design, report, _ = page_frame(GENEVA, 12, 0)
    page = geneva_page(design, report)
    box = page.scene.bounds()
    frames = drawn(GENEVA, 12, (320, 240))
    g = design.geometry
    alpha = -math.pi + 2 * math.pi * np.arange(12) / 12
    pin = g.crank_radius * np.column_stack([np.cos(alpha), np.sin(alpha)])
    radius = float(page.scene.movers[0].radius)
    assert radius > 0
    for k in (0, 5, 6, 7):
        assert on_circle(frames[k], box, pin[k], radius) == 1.0
        assert on_circle(frames[k], box, pin[(k + 3) % 12], radius) < 0.5
    law = g.law.motion(alpha)[0]
    assert law[5] != law[7]                 # the wheel indexes as the pin passes alpha = 0
