"""The figure writer: a matplotlib figure as PNG or SVG, reproducibly (no dates, fixed SVG ids)."""
from __future__ import annotations

from pathlib import Path
from typing import IO, Any


def save(fig: Any, path: Path | IO[bytes], fmt: str) -> None:
    """Save ``fig`` as ``fmt`` (``"png"`` at 120 dpi or ``"svg"``): no date in the metadata, fixed SVG ids.

    A figure laid out by a layout engine (constrained layout) keeps the layout its first file was drawn with: the
    next format of the same figure is written at the same axes' positions, not measured again (the layout re-measures
    every label each time, about half of a figure's writing time)."""
    import matplotlib

    with matplotlib.rc_context({"svg.hashsalt": "camgen"}):
        fig.savefig(path, format=fmt, dpi=120, metadata={"Date": None} if fmt == "svg" else None)
    if fig.get_layout_engine() is not None:
        fig.set_layout_engine("none")


WRITERS = {"png": lambda fig, path, options=None: save(fig, path, "png"),
           "svg": lambda fig, path, options=None: save(fig, path, "svg")}
