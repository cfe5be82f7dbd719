"""Every bundled template works as its comment says: cam templates build, linkage templates analyse."""
from __future__ import annotations

import json
import tomllib

import pytest
from click.testing import CliRunner

from tests.conftest import ROOT

TEMPLATES = sorted((ROOT / "templates").glob("*.toml"))


def _is_linkage(path) -> bool:
    from camgen.core.family import read_family

    raw, _ = read_family(path)
    return "linkage" in raw


@pytest.mark.parametrize("path", [p for p in TEMPLATES if "sweep" in tomllib.loads(p.read_text())],
                         ids=lambda p: p.name)
def test_bundled_family(path, tmp_path):
    from camgen.cli import main as camgen
    from linkgen.cli import main as linkgen

    main = linkgen if _is_linkage(path) else camgen
    result = CliRunner().invoke(main, ["family", str(path), "-o", str(tmp_path), "--jobs", "2"])
    assert result.exit_code == 0, result.output
    rows = json.loads((tmp_path / "summary.json").read_text())
    assert rows and all(r["status"] == "ok" for r in rows)


@pytest.mark.parametrize("path", [p for p in TEMPLATES if not {"sweep", "task"} & set(tomllib.loads(p.read_text()))],
                         ids=lambda p: p.name)
def test_bundled_template(path, tmp_path):
    """(Synthesis tasks, templates with a [task] table, are run by tests/synthesis/test_synthesis.py.)"""
    is_linkage = _is_linkage(path)
    if is_linkage:
        from linkgen.cli import main

        args = ["analyze", str(path), "--json", "-o", str(tmp_path)]
    else:
        from camgen.cli import main

        args = ["build", str(path), "-o", str(tmp_path), "--set", "output.formats=['json','dxf','stl']"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / f"{path.stem}.json").read_text())
    if not is_linkage and report.get("cams") != {}:         # a machine of linkages only: its parts are linkgen's
        assert report["outline_max_error_mm"] <= report["tolerance_mm"]
        assert report["mesh"]["watertight"]
