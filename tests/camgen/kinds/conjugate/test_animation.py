"""``camgen animate`` of a conjugate pair: both cams turning, both rollers drawn where each cam's pitch curve puts
them (read from the pixels); one GIF of the asked frames and size, the same bytes twice."""
from __future__ import annotations

import math

import numpy as np

from camgen.followers.base import rotate
from camgen.kinds.conjugate.page import conjugate_page
from tests.conftest import ROOT
from tests.support.kind_animation import assert_animated, drawn, on_circle, page_frame

CONJUGATE = ROOT / "templates" / "conjugate.toml"


def test_conjugate_gif(tmp_path):
    assert_animated(CONJUGATE, tmp_path)


def test_both_rollers_ride():
    design, report, _ = page_frame(CONJUGATE, 12, 0)
    box = conjugate_page(design, report).scene.bounds()
    frames = drawn(CONJUGATE, 12, (320, 240))
    theta = 2 * math.pi * np.arange(12) / 12
    for d in design.cams:
        cam = d.cam
        centre = rotate(cam.pitch(theta).point, cam.follower.sense * theta)
        for k in (0, 3, 6):
            assert on_circle(frames[k], box, centre[k], cam.contact_radius) == 1.0
        assert on_circle(frames[0], box, centre[0] + [0.0, cam.contact_radius], cam.contact_radius) < 0.8
