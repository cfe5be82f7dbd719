"""The type hints hold: mypy, with the settings of pyproject.toml's [tool.mypy] (the pydantic plugin), over camgen
and linkgen finds no errors (issue 31's goal); and it is shown finding what it should
in a file written to break those settings once each, so that no errors means the project's settings were read and
applied. Each Literal written out for mypy names exactly its registry's entries.

A failure lists mypy's findings. mypy's findings also move with numpy's and pydantic's own hints, which CI installs
anew: a new one is fixed where it is found (an annotation, a narrowing), not silenced.
"""
from __future__ import annotations

import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import get_args

import pytest

from camgen.contact_stress import MATERIALS, MaterialName
from camgen.core.hardware import BEARINGS, BOLTS, BearingName, BoltName
from camgen.core.kit import BearingChoice, CamKitTable, KitTable
from camgen.core.spec import OutputTable
from camgen.core.writers import EXTRAS, FORMATS, OptionalFormat
from camgen.followers import FOLLOWERS, FollowerName
from camgen.laws import REGISTRY, LawName
from linkgen.dynamics.materials import PINS, SHEETS, PinName, SheetName
from linkgen.dynamics.table import DynamicsTable
from tests.conftest import ROOT

needs_mypy = pytest.mark.skipif(importlib.util.find_spec("mypy") is None,
                                reason="mypy is not installed: pip install '.[test]' (the test extra has it)")



def _mypy(cwd, *args: str) -> subprocess.CompletedProcess:
    """``python -m mypy`` with ``args`` under ``cwd`` (its pyproject.toml the configuration)."""
    return subprocess.run([sys.executable, "-m", "mypy", *args], cwd=cwd, capture_output=True, text=True)


def _count(result: subprocess.CompletedProcess) -> int:
    """The error count of mypy's summary line; a crash or a usage error (exit 2, no summary) fails."""
    found = re.search(r"^(?:Found (\d+) errors? in \d+ files?|Success: no issues found) ", result.stdout, re.M)
    assert result.returncode in (0, 1) and found, result.stdout + result.stderr
    return int(found[1] or 0)


def _findings(result: subprocess.CompletedProcess) -> list[tuple[str, str]]:
    """Each error of mypy's output as (file, error code), in its order; all of them, as its summary counts."""
    found = [(m[1], m[2]) for m in re.finditer(r"^([\w./-]+\.py):\d+: error: .*\[([a-z-]+)\]$", result.stdout, re.M)]
    assert len(found) == _count(result), result.stdout + result.stderr
    return found


#: a script using the API as the issue writes it, which the type checker must pass and type
SCRIPT = '''\
import camgen
import linkgen

spec = camgen.CamSpec.from_toml("rdrd.toml").with_changes({"motion.0.lift": 25})
design = camgen.design(spec)
reveal_type(design)
written = camgen.write(design, "out", formats=["dxf", "stl"])
reveal_type(written.files)
linkage = linkgen.design(linkgen.LinkageSpec.from_toml("crank-rocker.toml"), angle=30, parts=True)
reveal_type(linkage)
reveal_type(linkgen.write(linkage, "out").report)
try:
    camgen.load("geneva4.toml")
except linkgen.SpecError as error:
    reveal_type(error)
'''
#: what mypy says of that script, and of a file that misspells a name (an error, not Any)
REVEALED = {"script.py": ['note: Revealed type is "camgen.api.Design"',
                          'note: Revealed type is "dict[str, pathlib.Path]"',
                          'note: Revealed type is "linkgen.linkage_design.LinkageDesign"',
                          'note: Revealed type is "dict[str, Any]"',
                          'note: Revealed type is "camgen.core.errors.SpecError"'],
            "typo.py": ['error: Module has no attribute "desing"  [attr-defined]']}


#: a module that breaks each setting once: its lines, and the (line, code) findings mypy must give, no others
BAD = ["from typing import override",                  # 1: new in Python 3.12; python_version 3.11 is read
       "",
       "import shapely",                               # 3: no hints, no stubs: passed by the overrides, unsaid
       "from pydantic import BaseModel, Field",
       "",
       "",
       "class Table(BaseModel):",
       "    width: float = Field(1.0, alias='w')",
       "    depth = 2.0",                                 # 9: the pydantic plugin refuses an unannotated field
       "",
       "",
       "Table(w='wide')",                               # 12: init_typed: the constructor checks its arguments
       "Table(width=3.0)",                              # the plugin knows a field by its name as well as its alias
       "kept: int = 1  # type: ignore[assignment]"]     # 14: warn_unused_ignores
FINDINGS = {(1, "attr-defined"), (9, "pydantic-field"), (12, "arg-type"), (14, "unused-ignore")}


@pytest.mark.slow                                     # about 40-80 s of mypy over both packages and the scripts
@needs_mypy
def test_mypy_finds_no_errors_types_the_api_and_applies_the_settings(tmp_path):
    """One analysis of both packages (mypy's cache, then shared by the two runs, in the checkout's ``.mypy_cache``):

    - over camgen, linkgen and two scripts: the packages have no error; the script that uses the API has none and its
      designs have their types, not Any; the misspelt name is an error. (The scripts are matched by file name: mypy's
      cache may report them under the folder of the run that first saw them.)
    - over a file written to break each setting once, under a copy of pyproject.toml: exactly those findings, so
      that no errors means the project's settings were read and applied.
    """
    (tmp_path / "script.py").write_text(SCRIPT)
    (tmp_path / "typo.py").write_text("import camgen\n\ncamgen.desing\n")
    result = _mypy(ROOT, "camgen", "linkgen", str(tmp_path / "script.py"), str(tmp_path / "typo.py"))
    scripts = {name: [line.split(": ", 1)[1].replace("builtins.", "") for line in result.stdout.splitlines()
                      if Path(line.split(":", 1)[0]).name == name] for name in REVEALED}
    assert scripts == REVEALED, result.stdout
    new = [finding for finding in _findings(result) if Path(finding[0]).name not in REVEALED]
    assert not new, f"mypy finds {len(new)} errors; fix them:\n{result.stdout}"

    settings = tmp_path / "settings"
    settings.mkdir()
    shutil.copy(ROOT / "pyproject.toml", settings / "pyproject.toml")
    (settings / "bad.py").write_text("\n".join(BAD) + "\n", encoding="utf-8")
    result = _mypy(settings, "--cache-dir", str(ROOT / ".mypy_cache"), "bad.py")
    found = {(int(m[1]), m[2]) for m in re.finditer(r"^bad\.py:(\d+): error: .*\[([a-z-]+)\]$", result.stdout, re.M)}
    assert _count(result) == len(FINDINGS) and found == FINDINGS, result.stdout + result.stderr


#: each Literal written out for the type checker: the registry whose names it must be, in their order
ALIASES = {"LawName": (LawName, tuple(REGISTRY)), "FollowerName": (FollowerName, tuple(FOLLOWERS)),
           "MaterialName": (MaterialName, tuple(MATERIALS)), "BoltName": (BoltName, tuple(BOLTS)),
           "BearingName": (BearingName, tuple(BEARINGS)), "BearingChoice": (BearingChoice, (*BEARINGS, "none")),
           "OptionalFormat": (OptionalFormat, tuple(EXTRAS)), "SheetName": (SheetName, tuple(SHEETS)),
           "PinName": (PinName, tuple(PINS))}


@pytest.mark.parametrize("name", ALIASES)
def test_a_written_out_literal_names_its_registry(name):
    alias, names = ALIASES[name]
    assert get_args(alias) == names


def test_the_tables_take_the_registries_names():
    """The models built on the aliases accept every registered name, in the registries' order."""
    assert get_args(get_args(OutputTable.model_fields["formats"].annotation)[0]) == FORMATS + tuple(EXTRAS)
    assert get_args(KitTable.model_fields["bolt"].annotation) == tuple(BOLTS)
    assert get_args(CamKitTable.model_fields["bearing"].annotation) == (*BEARINGS, "none")
    assert get_args(DynamicsTable.model_fields["material"].annotation) == tuple(SHEETS)
    assert get_args(DynamicsTable.model_fields["pins"].annotation) == tuple(PINS)
