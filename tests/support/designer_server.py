"""Start ``camgen serve`` on a free port in a folder, as a user does, and stop it with Ctrl-C (SIGINT), checking
that it stopped cleanly: exit code 0, no process left, no temporary folder of its own left behind."""
from __future__ import annotations

import contextlib
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

from tests.conftest import ROOT


def _temporaries(folder: Path) -> set[str]:
    """The designer's temporary folders under ``folder`` (the server's own TMPDIR, made for it alone, so that another
    worker's designer never shows in it)."""
    return {p.name for p in folder.glob("camgen-designer-*")}


def gone(pid: int, seconds: float = 60.0) -> bool:
    """True once no process has the id ``pid`` (reaped: not even a zombie), within ``seconds``."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return True
        time.sleep(0.05)
    return False


def child_pids(pid: int) -> list[int]:
    """The ids of the processes whose parent is ``pid`` (read from /proc; zombies included, as they are not gone)."""
    found = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:                      # ended meanwhile
            continue
        if int(fields[1]) == pid:
            found.append(int(stat.parent.name))
    return found


@contextlib.contextmanager
def designer(folder: Path, template: str | None = None) -> Iterator[str]:
    """The address of ``camgen serve [template] --no-browser`` running in ``folder``, stopped by SIGINT after."""
    with designer_process(folder, template) as (url, _):
        yield url


@contextlib.contextmanager
def designer_process(folder: Path, template: str | None = None) -> Iterator[tuple[str, subprocess.Popen[str]]]:
    """:func:`designer`'s address and the server's process."""
    private = Path(tempfile.mkdtemp(prefix="designer-tmp-"))
    env = {**os.environ, "PYTHONPATH": str(ROOT), "TMPDIR": str(private)}
    args = [sys.executable, "-m", "camgen", "serve", *([template] if template else []), "--no-browser"]
    proc = subprocess.Popen(args, cwd=folder, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        found = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
        assert found, f"no address in {line!r}; stderr: {proc.stderr.read() if proc.poll() is not None else ''}"
        yield found.group(0), proc
    finally:
        proc.send_signal(signal.SIGINT)
        try:
            _, err = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
            raise AssertionError("the designer did not stop on Ctrl-C within 30 s") from None
    assert proc.returncode == 0, err
    assert "Traceback" not in err, err
    assert not _temporaries(private), "the designer left a temporary folder behind"
    shutil.rmtree(private)
