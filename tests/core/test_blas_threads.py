"""Both programs run every command with the BLAS libraries on one thread unless the user has chosen their threads
(camgen.core.cli.one_blas_thread): the environment is set before numpy and scipy load and restored after the
command, a user's own setting wins, and a synthesis finds the same candidates on one BLAS thread or two."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import click
import pytest

from camgen.core.cli import BLAS_THREADS, Commands
from tests.conftest import ROOT


@pytest.fixture
def clean_env(monkeypatch):
    """No BLAS thread variable set, as on a machine whose user set none."""
    for name in BLAS_THREADS:
        monkeypatch.delenv(name, raising=False)


def _group(seen: dict) -> click.Group:
    @click.group(cls=Commands)
    def cli() -> None:
        pass

    @cli.command()
    def look() -> None:
        seen.update({name: os.environ.get(name) for name in BLAS_THREADS})

    return cli


def test_a_command_runs_on_one_blas_thread_and_the_environment_is_restored(clean_env):
    seen: dict = {}
    with pytest.raises(SystemExit) as done:
        _group(seen).main(["look"])
    assert done.value.code == 0
    assert seen["OPENBLAS_NUM_THREADS"] == "1" and seen["MKL_NUM_THREADS"] == "1" and seen["OMP_NUM_THREADS"] is None
    assert not any(name in os.environ for name in BLAS_THREADS)


@pytest.mark.parametrize("name", ["OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"])
def test_a_users_own_thread_setting_is_left_alone(clean_env, monkeypatch, name):
    monkeypatch.setenv(name, "3")
    seen: dict = {}
    with pytest.raises(SystemExit):
        _group(seen).main(["look"])
    assert seen == {n: ("3" if n == name else None) for n in BLAS_THREADS}


#: a build in a fresh interpreter, then the BLAS libraries' thread counts as threadpoolctl reads them at its exit
_PROBE = """
import atexit, json, sys
from threadpoolctl import threadpool_info
atexit.register(lambda: print(json.dumps(sorted({i["internal_api"]: i["num_threads"]
                                                 for i in threadpool_info() if i["user_api"] == "blas"}.items()))))
from camgen.cli import main
main(["build", sys.argv[1], "-o", sys.argv[2], "--set", 'output.formats=["json"]'])
"""


@pytest.mark.parametrize("threads", [None, "2"])
def test_a_real_command_loads_numpy_and_scipy_on_one_thread_or_the_users(tmp_path, threads):
    """camgen build of the oscillating cam (numpy and scipy both loaded): every BLAS library on one thread, or on
    the two the user asked for with OPENBLAS_NUM_THREADS."""
    env = {k: v for k, v in os.environ.items() if k not in BLAS_THREADS}
    if threads:
        env["OPENBLAS_NUM_THREADS"] = threads
    run = subprocess.run([sys.executable, "-c", _PROBE, str(ROOT / "templates" / "oscillating.toml"),
                          str(tmp_path / "out")], cwd=ROOT, env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    libraries = dict(json.loads(run.stdout.splitlines()[-1]))
    assert libraries and set(libraries.values()) == {int(threads or 1)}


def _candidates(folder) -> list:
    """summary.json's candidates, every time figure left out."""
    def strip(value):
        if isinstance(value, dict):
            return {k: strip(v) for k, v in value.items() if "seconds" not in k}
        return [strip(v) for v in value] if isinstance(value, list) else value

    return strip(json.loads((folder / "summary.json").read_text())["candidates"])


def test_a_synthesis_finds_the_same_candidates_on_one_blas_thread_or_two(tmp_path):
    """linkgen synthesize of the bundled crank-rocker task (its least-squares polish the BLAS's work), by the
    command's default (one thread) and with OPENBLAS_NUM_THREADS=2: the same candidates, figure for figure."""
    env = {k: v for k, v in os.environ.items() if k not in BLAS_THREADS}
    for folder, extra in (("one", {}), ("two", {"OPENBLAS_NUM_THREADS": "2"})):
        run = subprocess.run([sys.executable, "-m", "linkgen", "synthesize",
                              str(ROOT / "templates" / "synth-crank-rocker.toml"), "-o", str(tmp_path / folder)],
                             cwd=ROOT, env=env | extra, capture_output=True, text=True, timeout=600)
        assert run.returncode == 0, run.stderr
    one, two = _candidates(tmp_path / "one"), _candidates(tmp_path / "two")
    assert one and one == two
