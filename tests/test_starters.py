"""`camgen new` and `linkgen new`: every kind's starter template builds as it is, with no warning; its comments
are the models' own descriptions; an existing file is never overwritten; bad kinds and names are refused."""
from __future__ import annotations

import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.starters import STARTERS as CAM_STARTERS
from camgen.spec import CamTable
from linkgen.cli import main as linkgen
from linkgen.mechanisms import MECHANISMS
from linkgen.starters import STARTERS as LINKAGE_STARTERS


def _run(program, args):
    result = CliRunner().invoke(program, [str(a) for a in args])
    return result.exit_code, result.output


@pytest.mark.parametrize("kind", sorted(CAM_STARTERS))
def test_every_cam_starter_builds_without_a_warning(tmp_path, kind):
    path = tmp_path / f"my-{kind}.toml"
    assert _run(camgen, ["new", kind, "-o", path]) == (0, f"wrote {path}\n")
    code, output = _run(camgen, ["build", path, "-o", tmp_path / "out"])
    assert code == 0, output
    assert "warning" not in output, output
    assert (tmp_path / "out" / f"my-{kind}.json").exists()


@pytest.mark.parametrize("kind", sorted(LINKAGE_STARTERS))
def test_every_linkage_starter_analyses_and_builds(tmp_path, kind):
    path = tmp_path / f"{kind}.toml"
    assert _run(linkgen, ["new", kind, "-o", path])[0] == 0
    code, output = _run(linkgen, ["analyze", path, "-o", tmp_path / "a"])
    assert code == 0 and "warning" not in output, output
    if kind != "whitworth":                              # its parts cannot be stacked (README)
        code, output = _run(linkgen, ["build", path, "-o", tmp_path / "b"])
        assert code == 0, output


def test_every_kind_has_a_starter():
    assert set(LINKAGE_STARTERS) == set(MECHANISMS)
    assert {"translating-roller", "knife-edge", "translating-flat", "oscillating-roller", "oscillating-flat",
            "plate", "grooved", "barrel", "conjugate", "geneva"} == set(CAM_STARTERS)


def test_comments_are_the_models_descriptions(tmp_path):
    path = tmp_path / "c.toml"
    _run(camgen, ["new", "translating-roller", "-o", path])
    lines = path.read_text().splitlines()
    info = CamTable.model_fields["base_radius"]
    line = next(x for x in lines if x.startswith("base_radius"))
    assert line.split("# ", 1)[1] == f"mm: {info.description}"
    assert 'name = "c"' in lines


def test_no_file_is_overwritten_and_bad_names_are_refused(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "plate.toml").write_text("mine\n")
    assert _run(camgen, ["new", "plate"]) == (2, "error: --output: plate.toml exists; give another file\n")
    assert (tmp_path / "plate.toml").read_text() == "mine\n"
    code, output = _run(camgen, ["new", "cylinder"])
    assert code == 2 and output.startswith("error: KIND: unknown value 'cylinder'; one of translating-roller")
    assert _run(linkgen, ["new", "four-bar", "-o", "a b.toml"]) == (
        2, "error: --output: 'a b' cannot name a template: letters, digits, '.', '_' and '-'\n")
    assert _run(linkgen, ["new", "four-bar", "-o", "no/such/x.toml"]) == (2, "error: --output: no folder no/such\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plate.toml"]
    code, output = _run(linkgen, ["new"])
    assert code == 0 and len(output.splitlines()) == len(LINKAGE_STARTERS)


def test_a_part_sharing_the_printable_pins_files_is_refused(tmp_path):
    """A slider named "pin" makes a block part "pin": its STL would be the printable pin's."""
    from pathlib import Path

    text = (Path(__file__).resolve().parent.parent / "templates" / "toggle-press.toml").read_text()
    path = tmp_path / "press.toml"
    path.write_text(text.replace("[linkage.sliders.ram]", "[linkage.sliders.pin]"))
    code, output = _run(linkgen, ["build", path, "-o", tmp_path / "o", "--set", "parts.pins=true"])
    assert (code, output) == (2, "error: parts.pins: a part named 'pin' would share its files with the printable "
                                 "pin; rename its link or slider\n")
    assert not (tmp_path / "o").exists()
