"""A plain, non-editable ``pip install .`` of the checkout into a fresh venv, and every bundled example copied by
name and run in it from a folder outside the checkout, with the command line the docs' gallery builds it with.

Two checks need those runs: that every example runs after a plain install (tests/project/test_examples.py) and
that the docs' gallery shows every example built (tests/project/test_docs.py, which hands the folders to the
gallery through ``CAMGEN_DOCS_GALLERY_BUILT`` instead of building them a second time). Both are in the xdist group
:data:`GROUP`, so that one worker runs them one after the other and the runs are made once (a session fixture);
without xdist the same holds.

An example's line is its documented run line (``camgen build NAME.toml``, ``linkgen family NAME.toml ...``) with
the options the gallery adds (the formats it shows, a synthesis' ``--figures``): docs/_ext/gallery.py's
:func:`arguments`, so the gallery shown is the one these runs make.
"""
from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

from tests.conftest import ROOT

#: the xdist group of the checks that share the runs
GROUP = "plain-install"
#: runs command lines in forked processes of the venv's interpreter
FORKED = ROOT / "tests" / "support" / "forked_commands.py"
#: the longest a step may take (s): a pip install, or every example's run
TIMEOUT = 1800
#: the examples' lines run at a time (:func:`run_lines`): the two cores of the machines the suite runs on
JOBS = 2


@dataclass(frozen=True)
class ExampleRuns:
    """What the plain install and the examples' runs left.

    Parameters
    ----------
    bin : Path
        The venv's ``bin`` folder (its ``python``, ``camgen``, ``linkgen``).
    work : Path
        The folder the commands ran in (outside the checkout): ``<work>/<name>/<name>.toml`` each example's copy.
    env : dict
        The environment they ran with (the venv's bin first on PATH, no PYTHONPATH).
    copies : list
        The record of each ``new`` line (``{"line", "code", "output"}``), one an example, in the examples' order.
    runs : list
        The record of each example's run line, in the same order.
    gallery : Path
        ``<work>/gallery``: each example's output folder, ``<gallery>/<name>``.
    """

    bin: Path
    work: Path
    env: dict[str, str]
    copies: list[dict[str, Any]]
    runs: list[dict[str, Any]]
    gallery: Path


def gallery_extension() -> ModuleType:
    """docs/_ext/gallery.py, imported from its file (it is the docs' extension, not a package's module)."""
    spec = importlib.util.spec_from_file_location("camgen_docs_gallery", ROOT / "docs" / "_ext" / "gallery.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def venv_with_camgen(folder: Path) -> Path:
    """A fresh venv (the machine's packages visible to it, for the dependencies) with camgen installed into it by a
    plain, non-editable ``pip install .`` of the checkout; its bin folder.

    The venv is made without a pip of its own (``--without-pip``: seeding one costs about 5 CPU s) and this
    interpreter's pip installs into it (``pip --python``), which builds the wheel and installs it as the venv's own
    pip would."""
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", str(folder)], check=True)
    python = folder / "bin" / "python"
    subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "-q", str(ROOT)], check=True,
                   capture_output=True, timeout=TIMEOUT)
    return folder / "bin"


def run_lines(bin_folder: Path, work: Path, env: dict[str, str], lines: list[str], results: Path,
              jobs: int = JOBS) -> list[dict]:
    """Each command line run by the venv's console scripts in ``work``, each in a process of its own, ``jobs`` at a
    time (:mod:`tests.support.forked_commands`); their records, in the lines' order.

    The lines are independent of each other; the searches (``synthesize``), then the families, start first, so that
    the longest do not start last (this one chain is the test run's longest)."""
    order = sorted(range(len(lines)), key=lambda i: (" synthesize " not in lines[i], " family " not in lines[i], i))
    driver = subprocess.run([str(bin_folder / "python"), str(FORKED), str(results), str(jobs)],
                            input="\n".join(lines[i] for i in order), cwd=work, env=env, capture_output=True,
                            text=True, timeout=TIMEOUT)
    if driver.returncode != 0:
        raise RuntimeError(f"the forked runner failed:\n{driver.stderr}")
    started: list[dict] = json.loads(results.read_text())
    records: list[dict] = [{}] * len(lines)
    for index, record in zip(order, started, strict=True):
        records[index] = record
    results.write_text(json.dumps(records, indent=1), encoding="utf-8")
    return records


def example_runs(folder: Path) -> ExampleRuns:
    """Install camgen plainly into ``folder/venv``, copy every bundled example by name into ``folder/work/<name>``
    (``new NAME [--example]``) and run each with the gallery's command line into ``folder/work/gallery/<name>``."""
    from camgen.core import examples as bundled
    from camgen.starters import starters as cam_starters
    from linkgen.starters import STARTERS as LINKAGE_STARTERS

    gallery = gallery_extension()
    bin_folder = venv_with_camgen(folder / "venv")
    work = folder / "work"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env["PATH"] = f"{bin_folder}{os.pathsep}{env['PATH']}"
    starters = {"camgen": set(cam_starters()), "linkgen": set(LINKAGE_STARTERS)}
    examples = list(bundled.examples().values())
    copies = []
    for example in examples:
        (work / example.name).mkdir(parents=True)
        flag = ["--example"] if example.name in starters[example.program] else []
        copies.append(" ".join([example.program, "new", example.name, *flag, "-o", f"{example.name}/"
                                f"{example.name}.toml"]))
    copied = run_lines(bin_folder, work, env, copies, folder / "copies.json")
    (work / "gallery").mkdir()
    lines = [" ".join([example.program,
                       *gallery.arguments(example.name, work / example.name / f"{example.name}.toml",
                                          example.program, example.command, work / "gallery" / example.name)])
             for example in examples]
    ran = run_lines(bin_folder, work, env, lines, folder / "runs.json") if all(r["code"] == 0 for r in copied) \
        else []
    return ExampleRuns(bin_folder, work, env, copied, ran, work / "gallery")
