"""Every bundled template works as its comment says: cam templates build, linkage templates analyse."""
from __future__ import annotations

import json
import tomllib

import pytest
from click.testing import CliRunner

from tests.conftest import ROOT

TEMPLATES = sorted((ROOT / "templates").glob("*.toml"))


@pytest.mark.parametrize("path", TEMPLATES, ids=lambda p: p.name)
def test_bundled_template(path, tmp_path):
    is_linkage = "linkage" in tomllib.loads(path.read_text())
    if is_linkage:
        from linkgen.cli import main

        args = ["analyze", str(path), "--json", "-o", str(tmp_path)]
    else:
        from camgen.cli import main

        args = ["build", str(path), "-o", str(tmp_path), "--set", "output.formats=['json','dxf','stl']"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / f"{path.stem}.json").read_text())
    if not is_linkage:
        assert report["outline_max_error_mm"] <= report["tolerance_mm"]
        assert report["mesh"]["watertight"]
