"""Files in sub-folders of a bundle's output folder (camgen.core.bundle): written all or nothing, the folders a
failed run made removed again, names that would leave the folder refused; a machine's mounts each in a sub-folder
(output.folders), its report's files map naming every file written and each mount's report its own files."""
from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core.bundle import staged
from camgen.core.errors import ExportError
from tests.camgen.kinds.machine.test_machine import AUTOMATON


def _tree(folder) -> set[str]:
    return {p.relative_to(folder).as_posix() for p in folder.rglob("*")}


def test_files_in_sub_folders_are_renamed_into_place_together(tmp_path):
    out = tmp_path / "out"
    with staged(out) as stage:
        stage.write("a/b/one.txt", lambda p: p.write_text("1"))
        stage.write("c/two.txt", lambda p: p.write_text("2"))
        stage.write("three.txt", lambda p: p.write_text("3"))
        assert not (out / "a" / "b" / "one.txt").exists()       # staged, not yet in place
    assert _tree(out) == {"a", "a/b", "a/b/one.txt", "c", "c/two.txt", "three.txt"}
    assert (out / "a" / "b" / "one.txt").read_text() == "1"


def test_a_failure_leaves_no_file_and_no_folder_it_made(tmp_path):
    out = tmp_path / "out"
    (out / "kept").mkdir(parents=True)
    (out / "kept" / "old.txt").write_text("old")

    def broken(path):
        raise ExportError("the writer failed")

    with pytest.raises(ExportError, match="the writer failed"), staged(out) as stage:
        stage.write("kept/new.txt", lambda p: p.write_text("new"))
        stage.write("a/b/one.txt", lambda p: p.write_text("1"))
        stage.write("c/two.txt", broken)
    assert _tree(out) == {"kept", "kept/old.txt"}


@pytest.mark.parametrize("name", ["../escape.txt", "a/../../escape.txt", "/tmp/absolute.txt"])
def test_a_name_that_leaves_the_folder_is_refused(tmp_path, name):
    with pytest.raises(ExportError, match="must stay inside its output folder"), staged(tmp_path / "out") as stage:
        stage.write(name, lambda p: p.write_text("x"))
    assert not (tmp_path / "out").exists() and not (tmp_path / "escape.txt").exists()


@pytest.fixture(scope="module")
def folders(tmp_path_factory):
    out = tmp_path_factory.mktemp("folders") / "out"
    result = CliRunner().invoke(camgen, ["build", str(AUTOMATON), "-o", str(out), "--set", "output.folders=true",
                                         "--set", 'output.formats=["dxf", "stl", "json"]'])
    assert result.exit_code == 0, result.output
    return out, json.loads((out / "automaton.json").read_text())


def test_each_mount_writes_into_its_own_folder(folders):
    out, report = folders
    files = set(report["files"].values())
    assert files == {p for p in _tree(out) if (out / p).is_file()}
    assert {p.partition("/")[0] for p in files if "/" in p} == {"head", "jaw", "arm", "arm-bars"}
    assert {"automaton.json", "automaton-frame.dxf", "automaton-kit.csv", "head/automaton-head.dxf",
            "arm-bars/automaton-arm-bars-sheet.dxf"} <= files


def test_each_mounts_report_lists_its_own_files_beside_it(folders):
    out, report = folders
    for mount in ("head", "jaw", "arm", "arm-bars"):
        own = json.loads((out / mount / f"automaton-{mount}.json").read_text())["files"]
        assert set(own.values()) == {p.name for p in (out / mount).iterdir()}, mount
        mine = {k.removeprefix(f"{mount}."): v.removeprefix(f"{mount}/") for k, v in report["files"].items()
                if k.startswith(f"{mount}.")}
        assert own == mine, mount
