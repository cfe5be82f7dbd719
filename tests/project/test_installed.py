"""The installed console scripts, as users run them: from a folder outside the checkout, on the installed
package (``pip install .`` puts it in site-packages; the tests themselves import the checkout)."""
from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import BENCHES, ROOT


def _script(name: str) -> str:
    path = shutil.which(name, path=str(Path(sys.executable).parent)) or shutil.which(name)
    assert path, f"the {name} console script is not installed: pip install '.[test]'"
    return path


def _run(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    result = subprocess.run(args, cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    return result


@pytest.fixture
def outside(tmp_path):
    """A working folder outside the checkout, with the installed package's location checked."""
    assert not tmp_path.is_relative_to(ROOT)
    where = subprocess.run([sys.executable, "-c", "import camgen, linkgen; print(camgen.__file__, linkgen.__file__)"],
                           cwd=tmp_path, capture_output=True, text=True, check=True).stdout.split()
    assert not any(Path(w).is_relative_to(ROOT) for w in where), f"not an installed package: {where}"
    return tmp_path


def test_installed_camgen_build(outside):
    _run(outside, _script("camgen"), "build", str(ROOT / "templates" / "rdrd.toml"))
    report = json.loads((outside / "out" / "rdrd" / "rdrd.json").read_text())
    assert report["outline_max_error_mm"] <= report["tolerance_mm"] and report["mesh"]["watertight"]
    written = {p.name for p in (outside / "out" / "rdrd").iterdir()}
    assert {"rdrd.dxf", "rdrd.stl", "rdrd.3mf", "rdrd-cut.svg"} <= written


def test_installed_linkgen_build(outside):
    _run(outside, _script("linkgen"), "build", str(ROOT / "templates" / "crank-rocker.toml"))
    report = json.loads((outside / "out" / "crank-rocker" / "crank-rocker.json").read_text())
    assert report["inversion"] == "crank-rocker" and report["layer_order"][0] == "ground"


@pytest.mark.slow
@pytest.mark.xdist_group(BENCHES)
def test_installed_benches(quick_benches):
    """Both quick benches run by the installed scripts from outside the checkout (their figures are checked in
    tests/project/test_bench.py, on the same run)."""
    where = subprocess.run([sys.executable, "-c", "import camgen, linkgen; print(camgen.__file__, linkgen.__file__)"],
                           cwd=quick_benches["camgen"], capture_output=True, text=True, check=True).stdout.split()
    assert not any(Path(w).is_relative_to(ROOT) for w in where), f"not an installed package: {where}"
    assert (quick_benches["camgen"] / "RESULTS.md").exists()
    assert (quick_benches["linkgen"] / "RESULTS.md").exists()
