"""The text writer: a finished text (a template written out as TOML) as a UTF-8 file, unchanged."""
from __future__ import annotations

from pathlib import Path
from typing import Any


def write_text(text: str, path: Path, options: Any = None) -> None:
    """Write ``text`` (finished: a template's TOML with its comments) to ``path``, UTF-8, as it is."""
    path.write_text(text, encoding="utf-8")


WRITERS = {"toml": write_text}
