"""``camgen animate`` of a plate cam: the plate sliding under its roller, the roller drawn where the cam's own motion
puts it (read from the pixels), one GIF of the asked frames and size, the same bytes twice."""
from __future__ import annotations

import math

import numpy as np

from camgen.page import cam_page
from tests.conftest import ROOT
from tests.support.kind_animation import assert_animated, drawn, on_circle, page_frame

PLATE = ROOT / "templates" / "plate.toml"


def test_plate_gif(tmp_path):
    assert_animated(PLATE, tmp_path)


def test_roller_rides_the_lift():
    """Frame k of 12 is cam angle 30 k degrees: the roller's circle is drawn about (0, base + roller + s(theta)),
    s from the cam's program, to a pixel (1.35 mm here): a centre 3 pixels off, or the lift of another frame, is
    not on the drawn circle."""
    design, report, _ = page_frame(PLATE, 12, 0)
    box = cam_page(design, report).scene.bounds()
    frames = drawn(PLATE, 12, (320, 240))
    cam = design.cam
    theta = 2 * math.pi * np.arange(12) / 12
    s = cam.program.evaluate(theta)[0]
    y = cam.base_radius + cam.contact_radius + s
    mm = (box[2] - box[0]) / (0.96 * 320)
    for k in (0, 3, 6, 9):
        assert on_circle(frames[k], box, (0.0, y[k]), cam.contact_radius) == 1.0
        assert on_circle(frames[k], box, (0.0, y[k] + 3 * mm), cam.contact_radius) < 0.8
    assert on_circle(frames[0], box, (0.0, y[6]), cam.contact_radius) < 0.5     # 15 mm of lift apart
