"""Reading a file a user names (a template, its ``base``, a table of loads or of a law's points) only when it is a
regular file: the one check before any read that camgen and linkgen share.

A FIFO, a terminal or a device would make a plain ``open()`` and ``read()`` wait for a writer, or read for ever.
:func:`read_regular` opens the file without blocking (``O_NONBLOCK``: a FIFO with no writer opens at once), checks
that it is a regular file on the descriptor itself (no window between the check and the read, a symbolic link
followed) and only then reads it, at most a stated number of bytes.
"""
from __future__ import annotations

import errno
import os
import stat
from pathlib import Path

#: what a file that is no regular file is, by its mode, for the message
_KINDS = ((stat.S_ISFIFO, "a FIFO"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"))


class NotRegularFile(OSError):
    """The file named is a FIFO, a device or a socket: never read (its ``strerror`` says which)."""


def read_regular(path: str | Path, limit: int) -> bytes:
    """The first ``limit`` + 1 bytes of the regular file ``path`` (one more than ``limit``, so that a caller can tell
    a file that is too large). Raises the operating system's errors as they are (FileNotFoundError,
    PermissionError, ...), IsADirectoryError for a folder and :class:`NotRegularFile` for a FIFO, a device or a
    socket, each an OSError with its ``strerror`` and ``filename``; no such file is ever read or waited on."""
    path = Path(path)
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    try:
        mode = os.fstat(fd).st_mode
        if stat.S_ISDIR(mode):
            raise IsADirectoryError(errno.EISDIR, "is a folder", str(path))
        if not stat.S_ISREG(mode):
            kind = next((name for test, name in _KINDS if test(mode)), "a special file")
            raise NotRegularFile(errno.EINVAL, f"{kind}, not a regular file", str(path))
        if getattr(os, "O_NONBLOCK", 0):
            os.set_blocking(fd, True)                   # a regular file's reads never block: as a plain open's
        with os.fdopen(fd, "rb", closefd=False) as stream:
            return stream.read(limit + 1)
    finally:
        os.close(fd)
