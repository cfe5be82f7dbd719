"""FreeCAD's reading of our files, as the tests run it: ``freecadcmd`` on one of the scripts in tests/programs."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest
from tests.conftest import ROOT

PROGRAMS = ROOT / "tests" / "programs"


def freecad_check(kind: str, path: Path, expect) -> subprocess.CompletedProcess:
    """Run ``tests/programs/freecad_<kind>_check.py`` (``kind`` "dxf" or "step") on ``path`` with the ``expect``ed
    shapes (JSON, as the script reads them); skipped where FreeCAD is not installed."""
    program = shutil.which("freecadcmd")
    if program is None:
        pytest.skip("freecadcmd is not installed (Debian package freecad; .ci/run installs it)")
    env = {**os.environ, f"CAMGEN_{kind.upper()}": str(path), "CAMGEN_EXPECT": json.dumps(expect)}
    return subprocess.run([program, str(PROGRAMS / f"freecad_{kind}_check.py")], env=env, capture_output=True,
                          text=True, timeout=300)


def freecad_solids(paths: list[Path]) -> dict[str, list[dict]]:
    """The solids FreeCAD reads in each STEP file of ``paths``, all in one ``freecadcmd`` process
    (``tests/programs/freecad_step_solids.py``): {path as given: [{"valid", "volume" (mm^3), "box" (mm)}, ...]} in each
    file's order; skipped where FreeCAD is not installed, failed (with FreeCAD's words) where a file is not read."""
    program = shutil.which("freecadcmd")
    if program is None:
        pytest.skip("freecadcmd is not installed (Debian package freecad; .ci/run installs it)")
    env = {**os.environ, "CAMGEN_STEPS": json.dumps([str(p) for p in paths])}
    done = subprocess.run([program, str(PROGRAMS / "freecad_step_solids.py")], env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return json.loads(done.stdout.strip().splitlines()[-1])
