"""Every kind refuses every other kind's keys by its own table: one line naming the key and the kind (and, for a
``[cam]`` key, the kinds whose table has it), exit code 2, nothing written.

The cases are generated from the registry (each kind's spec and the table it is chosen by), not listed by hand, so a
new kind's keys are tried on every other kind and every other kind's on it."""
from __future__ import annotations

import os
import re
import subprocess
import sys
from typing import Any

import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.kinds import KINDS
from camgen.kinds.base import CAM_TABLE
from camgen.starters import starter
from tests.conftest import ROOT


def _table(kind: Any) -> Any:
    """The model of the table ``kind`` is chosen by (a cam's ``[cam]``, a Geneva drive's ``[geneva]``)."""
    return kind.spec.model_fields[kind.table_key].annotation


def _cases() -> list[tuple[str, str, str]]:
    """(kind, a key of another kind's table that its own lacks, the first kind that has it), each key once a kind."""
    cases = []
    for name, kind in KINDS.items():
        seen = set(_table(kind).model_fields)
        for other, owner in KINDS.items():
            for key in _table(owner).model_fields:
                if key not in seen:
                    seen.add(key)
                    cases.append((name, key, other))
    return cases


CASES = _cases()


def _owners(key: str) -> list[Any]:
    """The kinds whose own table has ``key``, in the registry's order."""
    return [kind for kind in KINDS.values() if key in _table(kind).model_fields]


def _check_line(line: str, name: str, key: str) -> None:
    """``line`` is the refusal of ``key`` on ``name``: it names the key under the kind's table and the kind, says
    which kinds take the key (a cam kind by its ``cam.kind``, another by its table), and lists what the kind takes:
    its table's keys but the one choosing it."""
    kind = KINDS[name]
    head = f"error: {kind.table_key}.{key}: not a key of {kind.title} (a key of "
    assert line.startswith(head) and line.count("\n") == 1, line
    note, takes = line[len(head):].rstrip("\n").split("); it takes: ")
    cams = [o.name for o in _owners(key) if o.table_key == CAM_TABLE]
    assert re.findall(r'"([\w-]+)"', note) == cams
    assert ("cam.kind = " in note) == bool(cams)
    for other in _owners(key):
        if other.table_key != CAM_TABLE:
            assert f"[{other.table_key}], {other.title}" in note
    assert takes.split(", ") == [k for k in _table(kind).model_fields if k not in ("kind", "type")]


@pytest.fixture(scope="module")
def templates(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """Each kind's first starter template, written to a file."""
    folder = tmp_path_factory.mktemp("kinds")
    out = {}
    for name, kind in KINDS.items():
        path = folder / f"{name}.toml"
        path.write_text(starter(next(iter(kind.starters)), name))
        out[name] = path
    return out


def test_the_cases_cover_every_kind_both_ways():
    """Every kind is tried with foreign keys and has keys tried on others: a disc key on a Geneva drive, a barrel
    key on a disc, a Geneva key on a conjugate pair..."""
    assert {name for name, _, _ in CASES} == set(KINDS) == {other for _, _, other in CASES}
    assert ("disc", "pitch_radius", "barrel") in CASES and ("geneva", "base_radius", "disc") in CASES
    assert ("plate", "bore", "disc") in CASES and ("conjugate", "slots", "geneva") in CASES
    assert len(CASES) > 60


def test_every_kind_names_itself_as_its_table_does():
    """The kind's title (the registry's, for its other messages) is its table's (the model's, for a foreign key)."""
    for kind in KINDS.values():
        assert _table(kind).model_config["title"] == kind.title


@pytest.mark.parametrize("name, key, other", CASES, ids=[f"{k}-on-{n}" for n, k, _ in CASES])
def test_a_foreign_key_is_one_line_naming_it_and_the_kind(templates, tmp_path, name, key, other):
    out = tmp_path / "out"
    kind = KINDS[name]
    result = CliRunner().invoke(main, ["build", str(templates[name]), "-o", str(out),
                                       "--set", f"{kind.table_key}.{key}=1"])
    assert result.exit_code == 2, result.output
    _check_line(result.output, name, key)
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == []


@pytest.mark.parametrize("name, key", [("disc", "pitch_radius"), ("barrel", "base_radius"), ("geneva", "rim")])
def test_through_python_m_camgen(templates, tmp_path, name, key):
    """The same through ``python -m camgen`` in a process of its own: stderr one line, exit 2, nothing written."""
    out = tmp_path / "out"
    kind = KINDS[name]
    result = subprocess.run([sys.executable, "-m", "camgen", "build", str(templates[name]), "-o", str(out),
                             "--set", f"{kind.table_key}.{key}=1"], capture_output=True, text=True, timeout=120,
                            cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert result.returncode == 2 and result.stdout == ""
    _check_line(result.stderr, name, key)
    assert not out.exists()
