"""Every kind refuses every other kind's keys by its own table: one line naming the key and the kind (and, for a
``[cam]`` key, the kinds whose table has it), exit code 2, nothing written.

The cases are generated from the registry (each kind's spec and the table it is chosen by), not listed by hand, so a
new kind's keys are tried on every other kind and every other kind's on it."""
from __future__ import annotations

import os
import re
import subprocess
import sys
import typing
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


# ---- the followers: every kind x every follower type it drives x every key that type's table lacks ----------------

#: a value for each key a follower's table may require, so that the table is whole but for the foreign key
_REQUIRED = {"roller_radius": 5.0, "pivot_distance": 110.0, "arm_length": 90.0}


def _members(kind: Any) -> list[Any]:
    """The follower tables ``kind``'s spec takes (its union's members, chosen by ``type``), or none for a kind
    without a follower (a Geneva drive)."""
    field = kind.spec.model_fields.get("follower")
    return [] if field is None else list(typing.get_args(field.annotation))


def _type_of(table: Any) -> str:
    """The ``type`` a follower table is chosen by."""
    (tag,) = typing.get_args(table.model_fields["type"].annotation)
    return tag


#: every key of any kind's follower tables, in the registry's order
FOLLOWER_KEYS = list(dict.fromkeys(key for kind in KINDS.values() for table in _members(kind)
                                   for key in table.model_fields))


def _follower_cases() -> list[tuple[str, str, str]]:
    """(kind, follower type, a key of some follower's table that this one lacks)."""
    return [(name, _type_of(table), key) for name, kind in KINDS.items() for table in _members(kind)
            for key in FOLLOWER_KEYS if key not in table.model_fields]


FOLLOWER_CASES = _follower_cases()


def _table_of(name: str, follower_type: str) -> Any:
    """The follower table of ``follower_type`` that kind ``name`` takes."""
    return next(t for t in _members(KINDS[name]) if _type_of(t) == follower_type)


def _follower_set(table: Any, extra: str) -> str:
    """A ``--set`` replacing the whole ``[follower]`` table: its type, the keys it requires, and ``extra``."""
    keys = [f'type = "{_type_of(table)}"'] + [f"{key} = {_REQUIRED[key]}" for key, info in table.model_fields.items()
                                               if key != "type" and info.is_required()]
    return "follower={" + ", ".join([*keys, extra]) + "}"


def test_the_follower_cases_cover_every_kind_and_type():
    """Every kind with a follower is tried with every type it drives; each type's own keys are tried on the tables
    that lack them (an arm's inertia on a translating roller, a spring on a groove's roller, an offset on a barrel's
    and a plate's roller, a conical roller on a disc's)."""
    driven = {(name, _type_of(t)) for name, kind in KINDS.items() for t in _members(kind)}
    assert {(n, t) for n, t, _ in FOLLOWER_CASES} == driven and len(driven) == 13
    for case in (("disc", "translating-roller", "inertia"), ("grooved", "translating-roller", "spring_rate"),
                 ("barrel", "translating-roller", "offset"), ("plate", "translating-roller", "offset"),
                 ("disc", "translating-roller", "roller_shape"), ("disc", "knife-edge", "roller_width"),
                 ("conjugate", "oscillating-roller", "face_margin")):
        assert case in FOLLOWER_CASES
    assert "geneva" not in {n for n, _, _ in FOLLOWER_CASES}


@pytest.mark.parametrize("name, follower_type, key", FOLLOWER_CASES,
                         ids=[f"{k}-on-{n}-{t}" for n, t, k in FOLLOWER_CASES])
def test_a_foreign_follower_key_is_one_line_naming_it_and_the_type(templates, tmp_path, name, follower_type, key):
    out = tmp_path / "out"
    table = _table_of(name, follower_type)
    result = CliRunner().invoke(main, ["build", str(templates[name]), "-o", str(out),
                                       "--set", _follower_set(table, f"{key} = 1")])
    assert result.exit_code == 2, result.output
    title = table.model_config["title"]
    assert title.startswith(("a ", "an ")) and follower_type in title
    head = f"error: follower.{key}: not a key of {title}"
    line = result.output
    assert line.startswith(head) and line.count("\n") == 1, line
    takes = line.rstrip("\n").split("; it takes: ")[1]
    assert takes.split(", ") == [k for k in table.model_fields if k != "type"]
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == []


def test_the_same_table_whole_builds(templates, tmp_path):
    """Without the foreign key, the replaced table validates: the refusal above is the key's, not the table's."""
    from camgen.spec import validate_spec
    from camgen.core.spec import read_template

    for name, kind in KINDS.items():
        for table in _members(kind):
            raw = read_template(templates[name], [_follower_set(table, "mass = 1")])
            assert validate_spec(raw).follower.type == _type_of(table)


#: every kind with a follower x every follower type of any kind that it does not drive
TYPE_CASES = [(name, t) for name, kind in KINDS.items() if _members(kind)
              for t in dict.fromkeys(_type_of(m) for k in KINDS.values() for m in _members(k))
              if t not in {_type_of(m) for m in _members(kind)}]


@pytest.mark.parametrize("name, follower_type", TYPE_CASES, ids=[f"{t}-on-{n}" for n, t in TYPE_CASES])
def test_a_follower_type_the_kind_does_not_drive_is_one_line(templates, tmp_path, name, follower_type):
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["build", str(templates[name]), "-o", str(out),
                                       "--set", f'follower={{type = "{follower_type}"}}'])
    assert result.exit_code == 2, result.output
    drives = [_type_of(m) for m in _members(KINDS[name])]
    either = " or ".join((", ".join(drives[:-1]), drives[-1]))
    assert result.output == f"error: follower.type: {KINDS[name].title} takes {either} (got {follower_type!r})\n"
    assert not out.exists()


@pytest.mark.parametrize("name", [n for n, k in KINDS.items() if k.table_key == CAM_TABLE and n != "disc"])
def test_a_kit_is_a_disc_cams_alone(templates, tmp_path, name):
    """Only a disc cam's spec has a ``[kit]``: on any other cam it is refused as a key of none of its tables."""
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["build", str(templates[name]), "-o", str(out), "--set", "kit.shaft=8"])
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: kit: unknown key") and result.output.count("\n") == 1, result.output
    assert "kit" not in KINDS[name].spec.model_fields and "kit" in KINDS["disc"].spec.model_fields
    assert not out.exists()
