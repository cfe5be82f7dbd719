"""The animation of a Geneva drive: the driver (crank, pin, locking disc) turning at constant speed from alpha = -180
degrees and the wheel indexing and dwelling, the pin entering and leaving its slots, as its page shows it. Pure: its
page's scene drawn frame by frame (:mod:`camgen.core.scene_frames`), nothing written.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.core.scene_frames import scene_frames
from camgen.kinds.geneva.page import geneva_page


def geneva_frames(design: Any, report: dict[str, Any], n: int, size: tuple[int, int]) -> np.ndarray:
    """``n`` frames (a divisor of 360) of one cycle of ``design``, whose report is ``report``, ``size`` (width,
    height) pixels: (n, height, width, 3) uint8."""
    return scene_frames(geneva_page(design, report), n, size, "a Geneva drive")
