"""The HTML writer: a design's interactive page (:class:`camgen.core.page.Page`) as one self-contained document."""
from __future__ import annotations

from pathlib import Path
from typing import Any

from camgen.core.page import page_html


def write_html(page: Any, path: Path, options: Any = None) -> None:
    """Write ``page`` (a :class:`~camgen.core.page.Page`, or a finished document as text) to ``path``."""
    path.write_text(page if isinstance(page, str) else page_html(page), encoding="utf-8")


WRITERS = {"html": write_html}
