"""Frames of an animation both products draw: one figure redrawn per step of a cycle, returned as pixel arrays.

Pure: nothing is written here (the encoders are :mod:`camgen.core.writers.animation`). The options a user gives
(frame count, size, speed, format) are checked here once, each refusal naming its option, so that both commands
say the same thing.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.figures import figure

#: the frame counts an animation may have (inclusive): 720 frames are half a degree a step
FRAMES = (2, 720)
#: each side of a frame in pixels (inclusive, even: MP4 and WebM encode colour at half resolution)
PIXELS = (32, 1920)
#: the frame rates an animation may play at (frames per second, inclusive)
FPS = (1.0, 60.0)
#: the formats an animation may be written as
FORMATS = ("gif", "mp4", "webm")
#: the figure's resolution (dots per inch): a frame of W x H pixels is a figure of W/DPI x H/DPI inches
DPI = 100


@dataclass(frozen=True)
class AnimationOptions:
    """What an animation is asked to be: ``frames`` per cycle, ``size`` (width, height) in pixels, ``fps`` frames a
    second and ``format`` (``"gif"``, ``"mp4"`` or ``"webm"``). Made by :func:`animation_options`, which checks
    them."""

    frames: int
    size: tuple[int, int]
    fps: float
    format: str


def parse_size(text: str) -> tuple[int, int]:
    """The (width, height) in pixels of ``text`` as ``WxH`` (e.g. ``640x480``); a :class:`SpecError` naming
    ``--size`` otherwise."""
    lo, hi = PIXELS
    w, sep, h = text.lower().partition("x")
    if sep and w.strip().isdigit() and h.strip().isdigit():
        size = int(w), int(h)
        if all(lo <= v <= hi and v % 2 == 0 for v in size):
            return size
    raise SpecError(f"must be WIDTHxHEIGHT in pixels, each an even number from {lo} to {hi} (got {text!r})", "--size")


def animation_options(frames: int, size: str, fps: float, fmt: str) -> AnimationOptions:
    """The checked options of an animation (see :class:`AnimationOptions`); a :class:`SpecError` naming the option
    (``--frames``, ``--size``, ``--fps``, ``--format``) that is out of its bounds."""
    if not FRAMES[0] <= frames <= FRAMES[1]:
        raise SpecError(f"must be a whole number of frames from {FRAMES[0]} to {FRAMES[1]} (got {frames})", "--frames")
    if not (math.isfinite(fps) and FPS[0] <= fps <= FPS[1]):
        raise SpecError(f"must be from {FPS[0]:g} to {FPS[1]:g} frames per second (got {fps:g})", "--fps")
    if fmt not in FORMATS:
        raise SpecError(f"must be one of {', '.join(FORMATS)} (got {fmt!r})", "--format")
    missing = video_missing(fmt)
    if missing is not None:
        raise SpecError(missing, "--format")
    return AnimationOptions(frames, parse_size(size), float(fps), fmt)


def video_missing(fmt: str) -> str | None:
    """Why format ``fmt`` cannot be written here (MP4 and WebM need imageio and imageio-ffmpeg, the ``anim``
    extra), or None."""
    from importlib.util import find_spec

    if fmt == "gif" or (find_spec("imageio") is not None and find_spec("imageio_ffmpeg") is not None):
        return None
    return f"{fmt} needs imageio and imageio-ffmpeg: pip install 'camgen[anim]', or write --format gif"


def cycle(n: int, full_turn: bool, lo: float, hi: float) -> np.ndarray:
    """The ``n`` input values of one cycle, the last one step before the first comes again: a full turn from
    ``lo`` (rad, ``hi`` ignored) in steps of 2 pi / n, or forth and back between ``lo`` and ``hi`` (rad or mm) as
    lo + (hi - lo) (1 - cos(2 pi k / n)) / 2, which slows to a stop at both ends as a rocker or a ram does."""
    k = np.arange(n) / n
    if full_turn:
        return lo + 2 * math.pi * k
    return lo + (hi - lo) * (1 - np.cos(2 * math.pi * k)) / 2


def render(draw: Callable[[Any, int], None], n: int, size: tuple[int, int],
           box: tuple[float, float, float, float]) -> np.ndarray:
    """Frames ``0 .. n-1`` as an array (n, height, width, 3) of uint8 RGB: each frame the axes are cleared,
    ``draw(ax, k)`` draws frame ``k`` in mm, and the view is the fixed region ``box`` (x0, y0, x1, y1 mm, equal
    scale, centred), so that frames line up. One figure of ``size`` pixels is reused for every frame."""
    width, height = size
    fig = figure(width / DPI, height / DPI, layout=None)
    fig.set_dpi(DPI)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
    x0, y0, x1, y1 = _fitted(box, width / height)
    out = np.empty((n, height, width, 3), dtype=np.uint8)
    for k in range(n):
        ax.clear()
        draw(ax, k)
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.set_axis_off()
        fig.canvas.draw()
        out[k] = np.asarray(fig.canvas.buffer_rgba())[:height, :width, :3]
    return out


def _fitted(box: tuple[float, float, float, float], aspect: float) -> tuple[float, float, float, float]:
    """``box`` widened (or heightened) about its centre to the proportions ``aspect`` (width / height) of the
    frame, so that one mm is as many pixels across as up."""
    x0, y0, x1, y1 = box
    w, h = x1 - x0, y1 - y0
    w, h = max(w, h * aspect), max(h, w / aspect)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    return cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2


def bounds(*points: np.ndarray, margin: float = 0.06) -> tuple[float, float, float, float]:
    """The region (x0, y0, x1, y1 mm) holding every point of ``points`` (arrays (..., 2) mm) with ``margin`` of its
    larger side round it."""
    xy = np.concatenate([np.asarray(p, dtype=float).reshape(-1, 2) for p in points])
    xy = xy[np.isfinite(xy).all(axis=1)]
    (x0, y0), (x1, y1) = xy.min(axis=0), xy.max(axis=0)
    pad = margin * max(x1 - x0, y1 - y0, 1.0)
    return float(x0 - pad), float(y0 - pad), float(x1 + pad), float(y1 + pad)
