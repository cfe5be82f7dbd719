"""The options of an animation both products write: frame count, size, speed, format, checked here once, each
refusal naming its option, so that both commands say the same thing. Light (no numpy), as the commands read the
bounds when they start; the frames are drawn by :mod:`camgen.core.frames`, written by
:mod:`camgen.core.writers.animation`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from camgen.core.errors import SpecError

#: the frame counts an animation may have (inclusive): 720 frames are half a degree a step
FRAMES = (2, 720)
#: each side of a frame in pixels (inclusive, even: MP4 and WebM encode colour at half resolution)
PIXELS = (32, 1920)
#: the frame rates an animation may play at (frames per second, inclusive)
FPS = (1.0, 60.0)
#: an animation's defaults (the ``animate`` commands', and the ``gif`` an ``output.formats`` asks a build for): frames
#: in the cycle, (width, height) pixels, frames per second
DEFAULT_FRAMES = 72
DEFAULT_SIZE = (640, 480)
DEFAULT_FPS = 24.0
#: the formats an animation may be written as
FORMATS = ("gif", "mp4", "webm")


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
