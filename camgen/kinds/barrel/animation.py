"""The animation of a barrel cam: a side view of the developed groove (the drum's surface unrolled at its pitch radius,
not the projected drum) sliding by -pitch_radius theta past the roller, as its page shows it. Pure: its page's scene
drawn frame by frame (:mod:`camgen.core.scene_frames`), nothing written.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.core.scene_frames import scene_frames
from camgen.kinds.barrel.page import barrel_page


def barrel_frames(design: Any, report: dict[str, Any], n: int, size: tuple[int, int]) -> np.ndarray:
    """``n`` frames (a divisor of 360) of one cycle of ``design``, whose report is ``report``, ``size`` (width,
    height) pixels: (n, height, width, 3) uint8."""
    return scene_frames(barrel_page(design, report), n, size, "a barrel cam")
