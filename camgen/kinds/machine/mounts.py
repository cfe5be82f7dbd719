"""Where a machine's mounts find their templates: a ``[[cams]]`` or ``[[linkages]]`` ``template`` given as a file's
path is read from the machine template's folder (as a ``base`` is), whatever the current folder; an absolute path
as it is. A machine given as a mapping (no file) reads them from the current folder. No I/O here: paths only.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

#: the machine's tables whose entries name a template by path (a ratchet names none: its wheel is inline)
MOUNT_TABLES = ("cams", "linkages", "genevas")


def beside(raw: dict[str, Any], folder: Path) -> dict[str, Any]:
    """``raw`` (a machine template read from a file in ``folder``) with each mount's relative ``template`` path
    joined onto ``folder``; everything else, and a malformed table (refused by validation), as it is."""
    out = dict(raw)
    for table in MOUNT_TABLES:
        entries = raw.get(table)
        if not isinstance(entries, list):
            continue
        out[table] = [_moved(entry, folder) for entry in entries]
    return out


def _moved(entry: Any, folder: Path) -> Any:
    """One mount with its ``template`` path (a non-empty string, not absolute) under ``folder``."""
    if not isinstance(entry, dict):
        return entry
    given = entry.get("template")
    if not isinstance(given, str) or not given.strip() or Path(given).is_absolute():
        return entry
    return {**entry, "template": str(folder / given)}


def folder_of(template: str | dict[str, Any]) -> Path | None:
    """The folder a mount's template file lies in (its table laws' files are read from there); None for an inline
    template (the current folder)."""
    return Path(template).parent if isinstance(template, str) else None
