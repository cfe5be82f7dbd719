"""The README's promises: its Python example runs, and its key table documents every template key."""
from __future__ import annotations

import re

import pytest

from camgen.spec import CamTable, FollowerTable, HubTable, OutputTable, SegmentTable
from tests.conftest import ROOT

README = (ROOT / "README.md").read_text()


def test_readme_opens_with_the_two_commands():
    blocks = re.findall(r"```sh\n(.*?)```", README, re.S)
    assert blocks[0].splitlines() == ["pip install . && camgen build templates/rdrd.toml",
                                      "pip install '.[test]' && python -m pytest -q -n auto"]
    assert "pip install '.[test]' && python -m pytest -q -n auto" in (ROOT / ".ci" / "run").read_text()


@pytest.mark.parametrize("prefix, model", [("cam", CamTable), ("follower", FollowerTable),
                                           ("motion[i]", SegmentTable), ("hub", HubTable), ("output", OutputTable)])
def test_every_template_key_is_documented(prefix, model):
    for key in model.model_fields:
        assert f"| `{prefix}.{key}` |" in README, f"{prefix}.{key} is not in the README's key table"


def test_every_linkage_key_is_documented():
    from linkgen.mechanisms import MECHANISMS

    for table in {m.table for m in MECHANISMS.values()}:
        for key in table.model_fields:
            assert f"| `linkage.{key}` |" in README, f"linkage.{key} is not in the README's linkgen key table"


def test_every_parts_key_is_documented():
    from linkgen.spec import PartsTable

    for key in PartsTable.model_fields:
        assert f"`parts.{key}`" in README, f"parts.{key} is not in the README"


def test_python_example_runs(tmp_path, monkeypatch):
    code = "\n".join(re.findall(r"```python\n(.*?)```", README, re.S))
    (tmp_path / "templates").mkdir()
    (tmp_path / "templates" / "rdrd.toml").write_text((ROOT / "templates" / "rdrd.toml").read_text())
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {})
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["rdrd-10", "rdrd-15", "rdrd-20"]
