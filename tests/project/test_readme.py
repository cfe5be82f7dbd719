"""The README's promises: it opens with the two commands, stays short (at most 200 lines), its examples run as
written, and its links lead to files that exist. (Every template key is documented by the generated reference,
checked by tests/project/test_docs.py.)"""
from __future__ import annotations

import os
import re
import subprocess
import sys

from tests.conftest import ROOT
from tests.project.test_docs import checkout_commands

README = (ROOT / "README.md").read_text()


def test_readme_opens_with_the_two_commands():
    blocks = re.findall(r"```sh\n(.*?)```", README, re.S)
    assert blocks[0].splitlines() == ["pip install . && camgen build templates/rdrd.toml",
                                      "pip install '.[test]' && python -m pytest -q -n auto"]
    assert "pip install '.[test]' && python -m pytest -q -n auto" in (ROOT / ".ci" / "run").read_text()


def test_readme_is_at_most_200_lines():
    assert len(README.splitlines()) <= 200


def test_readme_examples_run_as_written(tmp_path):
    """Every file it shows (a ```toml block after "`NAME.toml`:") is written, then every sh block after the two
    commands and every python block runs, in order, in an empty folder with the checkout's commands; the error line
    it quotes is the one the command prints."""
    bin_folder = checkout_commands(tmp_path / "bin")
    work = tmp_path / "work"
    work.mkdir()
    env = {**os.environ, "PATH": f"{bin_folder}{os.pathsep}{os.environ['PATH']}", "PYTHONPATH": str(ROOT)}
    files = dict(re.findall(r"`([\w.-]+\.toml)`:\n\n```toml\n(.*?)```", README, re.S))
    assert list(files) == ["cam.toml"]
    for name, text in files.items():
        (work / name).write_text(text)
    ran = 0
    for language, body in re.findall(r"```(sh|python)\n(.*?)```", README, re.S)[1:]:
        command = ["bash", "-c", "set -euo pipefail\n" + body] if language == "sh" else [sys.executable, "-c", body]
        result = subprocess.run(command, cwd=work, env=env, capture_output=True, text=True, timeout=600)
        assert result.returncode == 0, f"{body}\n{result.stdout}\n{result.stderr}"
        ran += 1
    assert ran == 4
    assert (work / "out" / "cam" / "cam.dxf").is_file() and (work / "out" / "leg" / "leg-sheet.dxf").is_file()
    assert (work / "out" / "swing" / "summary.csv").is_file()
    quoted = re.search(r"`(camgen build [^`]+)` says\n`(error: [^`]+)`", README)
    result = subprocess.run(["bash", "-c", quoted.group(1)], cwd=work, env=env, capture_output=True, text=True)
    assert (result.returncode, result.stderr.strip()) == (2, quoted.group(2))


def test_readme_links_lead_to_files():
    links = re.findall(r"\]\(([^)#]+)\)", README) + re.findall(r'src="([^"]+)"', README)
    local = [link for link in links if "://" not in link]
    assert len(local) >= 15
    for link in local:
        assert (ROOT / link).exists(), link
