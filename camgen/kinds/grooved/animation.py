"""The animation of a grooved cam: the cam turning with its groove round the roller, both flanks drawn (the island and
the outer flank), as its page shows it. Pure: its page's scene drawn frame by frame
(:mod:`camgen.core.scene_frames`), nothing written.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.core.scene_frames import scene_frames
from camgen.kinds.grooved.page import grooved_page


def grooved_frames(design: Any, report: dict[str, Any], n: int, size: tuple[int, int]) -> np.ndarray:
    """``n`` frames (a divisor of 360) of one cycle of ``design``, whose report is ``report``, ``size`` (width,
    height) pixels: (n, height, width, 3) uint8."""
    return scene_frames(grooved_page(design, report), n, size, "a grooved cam")
