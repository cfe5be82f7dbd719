"""Writing output files all-or-nothing.

Every writer writes to a hidden temporary name beside its target; only when every
file of a build has been written are they renamed into place. A failure leaves no
half-written file and no temporary behind.
"""
from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

from camgen.errors import ExportError


class Staging:
    """Collects temporary files and their final names; see :func:`staged`."""

    def __init__(self, directory: Path) -> None:
        self.directory = directory
        self.pending: list[tuple[Path, Path]] = []

    def write(self, name: str, writer: Callable[[Path], None]) -> Path:
        """Call ``writer(temporary path)``; the file takes ``name`` when the whole stage commits."""
        final = self.directory / name
        temp = self.directory / f".{name}.{os.getpid()}.tmp"
        self.pending.append((temp, final))
        writer(temp)
        if not temp.exists():
            raise ExportError(f"{name}: the writer produced no file")
        return final

    def write_bytes(self, name: str, data: bytes) -> Path:
        return self.write(name, lambda p: p.write_bytes(data))


@contextmanager
def staged(directory: str | Path) -> Iterator[Staging]:
    """Stage files in ``directory`` (created if missing); rename them all into place on success."""
    directory = Path(directory)
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ExportError(f"cannot create output folder {directory}: {exc.strerror}") from None
    stage = Staging(directory)
    try:
        yield stage
    except BaseException:
        for temp, _ in stage.pending:
            temp.unlink(missing_ok=True)
        raise
    try:
        for temp, final in stage.pending:
            os.replace(temp, final)
    except OSError as exc:
        for temp, _ in stage.pending:
            temp.unlink(missing_ok=True)
        raise ExportError(f"cannot write to {directory}: {exc.strerror}") from None
