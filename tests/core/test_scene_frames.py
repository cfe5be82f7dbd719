"""A page's scene drawn as an animation (:mod:`camgen.core.scene_frames`): frame k of n is the page's frame
k * 360 / n, poses applied as the page applies them, and a count that does not divide 360 refused on --frames."""
from __future__ import annotations

import numpy as np
import pytest

from camgen.core.errors import SpecError
from camgen.core.page import Body, Outline, Page, Scene, pose_motion
from camgen.core.scene_frames import frame_indices, scene_frames

SQUARE = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])


def _page(outline: np.ndarray) -> Page:
    """A page of 360 frames turning ``outline`` one degree a frame about the origin, in a fixed 6 x 6 mm view."""
    turn = pose_motion(np.arange(360.0))
    scene = Scene((Body("square", (Outline(outline, "part"),), turn),), view=(-3.0, -3.0, 3.0, 3.0))
    return Page("t", "t", "", "angle", "deg", np.arange(360.0), scene, (), ())


def test_frame_k_is_the_pages_frame_k_360_over_n():
    assert frame_indices(360, 8, "x").tolist() == [0, 45, 90, 135, 180, 225, 270, 315]
    with pytest.raises(SpecError, match=r"^--frames: x's animation shows its page's 360 frames: give one of 2, 3, "):
        frame_indices(360, 7, "x")


def test_the_poses_are_the_pages():
    """A square turned a quarter turn looks the same: at 4 frames (0, 90, 180, 270 degrees) every frame is the
    first; at 8 frames the odd ones (45 degrees on) differ. An arrow-like shape differs at a quarter turn."""
    four = scene_frames(_page(SQUARE), 4, (64, 64), "x").astype(float)
    assert all(np.abs(four[k] - four[0]).mean() < 0.5 for k in range(4))          # edge pixels may round
    eight = scene_frames(_page(SQUARE), 8, (64, 64), "x").astype(float)
    assert np.abs(eight[1] - eight[0]).mean() > 1.0 and np.abs(eight[2] - eight[0]).mean() < 0.5
    arrow = scene_frames(_page(np.array([[-1.0, -1.0], [2.0, 0.0], [-1.0, 1.0]])), 4, (64, 64), "x").astype(float)
    assert np.abs(arrow[1] - arrow[0]).mean() > 1.0
    assert four.shape == (4, 64, 64, 3) and four.dtype == float
