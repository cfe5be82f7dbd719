"""Each bundled template's commands run once per test run: a cache of the folders they wrote, shared by the tests
that assert on the same command's output (tests/project/test_golden.py, tests/project/test_templates.py).

The cache lives in the run's base temporary folder, which pytest-xdist's workers share: a command is run into a
private folder and renamed into place when it is done (a rename is atomic), so a reader never sees half a build, two
workers that race for the same command both get a complete folder. A worker that loses the race
throws its own copy away and uses the one in place (the two are the same command's output). A worker that asks
for a command another is running waits for it (a lock file per command, ``fcntl.flock``) instead of running it again
on the same cores. Without xdist the run's base folder is used the same way.

The folders are read only by convention: a test that writes next to the files, or changes them, must run its own
command into its ``tmp_path`` instead.
"""
from __future__ import annotations

import fcntl
import hashlib
import os
import shutil
import uuid
from dataclasses import dataclass
from pathlib import Path

from tests.support.golden import run, run_id_of

#: the cache's folder under the run's base temporary folder
CACHE = "bundled-builds"


def run_base(basetemp: Path) -> Path:
    """The run's base temporary folder, which every worker of the run shares, given this process' own
    (``tmp_path_factory.getbasetemp()``): under xdist a worker's is ``<run's base>/popen-gwN``."""
    return basetemp.parent if os.environ.get("PYTEST_XDIST_WORKER") else basetemp


def shared_root(basetemp: Path) -> Path:
    """The folder the cache lives in, given this process' base temporary folder (see :func:`run_base`)."""
    return run_base(basetemp) / CACHE


@dataclass(frozen=True)
class Builds:
    """The folders of bundled templates' commands, each run at most once per run (see the module's docstring).

    Parameters
    ----------
    root : Path
        The cache's folder (:func:`shared_root`); created when needed.
    """

    root: Path

    def folder(self, path: Path, program: str, args: list[str]) -> Path:
        """The folder ``program args -o FOLDER`` wrote for template ``path`` (as :func:`tests.support.golden.run`
        names it), running the command if no process of this run has yet.

        Raises ``RuntimeError`` with the command's output if it exits with a code other than 0 (then nothing is
        cached, and the next caller runs it again and fails the same way).
        """
        run_id = run_id_of(path, program, args)
        key = hashlib.sha256("\0".join([program, str(path), *args]).encode()).hexdigest()[:16]
        done = self.root / f"{run_id.replace(' ', '_')}-{key}"
        if not done.is_dir():
            self.root.mkdir(parents=True, exist_ok=True)
            with (self.root / f".{key}.lock").open("w") as lock:
                fcntl.flock(lock, fcntl.LOCK_EX)        # a worker asking for a command another runs waits for it
                self._run(done, path, program, args)
        return done / run_id.replace(" ", "_")

    def _run(self, done: Path, path: Path, program: str, args: list[str]) -> None:
        """Run the command into a private folder and rename it to ``done``, unless another worker has."""
        if not done.is_dir():
            part = self.root / f".part-{uuid.uuid4().hex}"
            try:
                run(path, program, args, part)
                try:
                    part.rename(done)
                except OSError:                         # another worker finished the same command first
                    if not done.is_dir():
                        raise
            finally:
                shutil.rmtree(part, ignore_errors=True)
