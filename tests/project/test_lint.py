"""The code is lint clean: ruff, with the rules and line length of pyproject.toml's [tool.ruff], finds nothing in
camgen, linkgen and the tests; and it is shown finding what it should in a file written to break those rules once
each, so that a clean run means the project's rules were read and applied, not that nothing was looked at."""
from __future__ import annotations

import importlib.util
import re
import shutil
import subprocess
import sys

import pytest

from tests.conftest import ROOT

pytestmark = pytest.mark.skipif(importlib.util.find_spec("ruff") is None,
                                reason="ruff is not installed: pip install '.[test]' (the test extra has it)")


def _ruff(cwd, *paths: str) -> subprocess.CompletedProcess:
    """``ruff check`` of ``paths`` under ``cwd`` (its pyproject.toml the configuration), no cache written."""
    return subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "--output-format", "concise", *paths],
                          cwd=cwd, capture_output=True, text=True)


def test_camgen_linkgen_and_the_tests_are_lint_clean():
    result = _ruff(ROOT, "camgen", "linkgen", "tests")
    assert result.returncode == 0, result.stdout + result.stderr


#: a module that breaks each rule once: its lines, and the (line, code) findings ruff must give, no others
BAD = ["from __future__ import annotations",
       "import os",                                                     # 2: imported, never used
       "",
       "",
       "def closures():",
       "    return [lambda: k for k in range(3)]",                      # 6: every closure sees the loop's last value
       "",
       "",
       "x = '" + "a" * 115 + "'",                                       # 9: 121 columns: the project's 120 is read
       "y = '" + "a" * 114 + "'",                                       # 120 columns, allowed (ruff's own 88 is not)
       "z = 'θ'"]                                                       # Greek letters allowed (RUF001 ignored)
FINDINGS = {(2, "F401"), (6, "B023"), (9, "E501")}


def test_ruff_applies_the_projects_rules(tmp_path):
    assert [len(line) for line in BAD[8:10]] == [121, 120]
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    (tmp_path / "bad.py").write_text("\n".join(BAD) + "\n", encoding="utf-8")
    result = _ruff(tmp_path, "bad.py")
    found = {(int(m[1]), m[2]) for m in re.finditer(r"^bad\.py:(\d+):\d+: ([A-Z]+\d+)", result.stdout, re.M)}
    assert result.returncode == 1 and found == FINDINGS, result.stdout + result.stderr
