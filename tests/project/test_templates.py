"""Every bundled template works as its comment says: cam templates build, linkage templates analyse."""
from __future__ import annotations

import json
import tomllib

import pytest
from tests.conftest import ROOT
from tests.support.golden import runs

TEMPLATES = sorted((ROOT / "templates").glob("*.toml"))


def _is_linkage(path) -> bool:
    from camgen.core.family import read_family

    raw, _ = read_family(path)
    return "linkage" in raw


@pytest.mark.parametrize("path", [p for p in TEMPLATES if "sweep" in tomllib.loads(p.read_text())],
                         ids=lambda p: p.name)
def test_bundled_family(path, bundled_builds):
    """`camgen family` or `linkgen family` on it (the run tests/project/test_golden.py compares, shared with it)."""
    [(program, args)] = runs(path)
    assert program == ("linkgen" if _is_linkage(path) else "camgen") and args[0] == "family"
    folder = bundled_builds.folder(path, program, args)
    rows = json.loads((folder / "summary.json").read_text())
    assert rows and all(r["status"] == "ok" for r in rows)


@pytest.mark.parametrize("path", [p for p in TEMPLATES if not {"sweep", "task"} & set(tomllib.loads(p.read_text()))],
                         ids=lambda p: p.name)
def test_bundled_template(path, bundled_builds):
    """`camgen build` (its default formats) or `linkgen analyze` on it, the first run tests/project/test_golden.py
    compares, shared with it. (Synthesis tasks, templates with a [task] table, are run by
    tests/synthesis/test_synthesis.py.)"""
    is_linkage = _is_linkage(path)
    program, args = runs(path)[0]
    assert (program, args[0]) == (("linkgen", "analyze") if is_linkage else ("camgen", "build"))
    folder = bundled_builds.folder(path, program, args)
    report = json.loads((folder / f"{path.stem}.json").read_text())
    if not is_linkage and report.get("cams") != {}:         # a machine of linkages only: its parts are linkgen's
        assert report["outline_max_error_mm"] <= report["tolerance_mm"]
        assert report["mesh"]["watertight"]
