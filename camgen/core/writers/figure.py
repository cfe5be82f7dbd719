"""The figure writer: a matplotlib figure as PNG or SVG, reproducibly (no dates, fixed SVG ids)."""
from __future__ import annotations

from pathlib import Path
from typing import IO, Any


def save(fig: Any, path: Path | IO[bytes], fmt: str) -> None:
    """Save ``fig`` as ``fmt`` (``"png"`` at 120 dpi or ``"svg"``): no date in the metadata, fixed SVG ids."""
    import matplotlib

    with matplotlib.rc_context({"svg.hashsalt": "camgen"}):
        fig.savefig(path, format=fmt, dpi=120, metadata={"Date": None} if fmt == "svg" else None)


WRITERS = {"png": lambda fig, path, options=None: save(fig, path, "png"),
           "svg": lambda fig, path, options=None: save(fig, path, "svg")}
