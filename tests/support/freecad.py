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
