"""The bundled templates as examples: `camgen examples` and `linkgen examples` list them one line each, `new NAME`
copies one with the files it reads and never overwrites, and after a plain `pip install .` into a fresh venv every
one of them is found by name and runs, from a folder outside the checkout."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core import examples as bundled
from camgen.starters import starters as cam_starters
from linkgen.cli import main as linkgen
from linkgen.starters import STARTERS as LINKAGE_STARTERS
from tests.conftest import ROOT
from tests.support.plain_install import GROUP

#: runs command lines in forked processes of an interpreter
FORKED = ROOT / "tests" / "support" / "forked_commands.py"
TEMPLATES = sorted((ROOT / "templates").glob("*.toml"))


def _run(program, *args):
    result = CliRunner().invoke(program, [str(a) for a in args])
    return result.exit_code, result.output


def test_the_examples_are_the_checkouts_templates():
    found = bundled.examples()
    assert sorted(found) == sorted(p.stem for p in TEMPLATES)
    assert all(e.path.parent.resolve() == (ROOT / "templates").resolve() for e in found.values())


@pytest.mark.parametrize("program, main", [("camgen", camgen), ("linkgen", linkgen)])
def test_examples_lists_each_one_on_one_line(program, main):
    code, output = _run(main, "examples")
    assert code == 0
    lines = output.splitlines()
    mine = bundled.examples(program)
    assert [line.split()[0] for line in lines] == list(mine)
    for line, example in zip(lines, mine.values(), strict=True):
        assert line.split()[1] == example.command
        assert line.endswith(example.summary) and 0 < len(example.summary) <= bundled.SUMMARY_WIDTH


def test_the_command_an_examples_comment_names_is_the_one_it_is_run_with():
    import re

    for example in bundled.examples().values():
        header = "".join(line for line in example.path.read_text().splitlines(keepends=True) if line.startswith("#"))
        for program, command in re.findall(r"\b(camgen|linkgen) (build|analyze|family|synthesize)\b", header):
            assert program == example.program, example.name
            if command in ("family", "synthesize") or example.command in ("family", "synthesize"):
                assert command == example.command, example.name


def test_a_summary_is_the_first_sentence_or_its_head():
    assert bundled.summary("# A cam.\n# More.\nname = 'x'\n") == "A cam."
    long = "# " + "A Watt I six-bar: " + "x " * 80 + ".\n"
    assert bundled.summary(long) == "A Watt I six-bar"
    assert bundled.summary("# A pantograph (k = 2) " + "y " * 70 + ".\n") == "A pantograph"
    assert bundled.summary("name = 'x'\n") == ""


def test_new_copies_an_example_with_the_files_it_reads(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, output = _run(camgen, "new", "automaton-cams", "-o", "fam.toml")
    assert code == 0, output
    assert output.splitlines() == ["wrote fam.toml", "wrote rdrd.toml",
                                   "run it with:  camgen family fam.toml -o out/fam"]
    assert (tmp_path / "rdrd.toml").read_bytes() == (ROOT / "templates" / "rdrd.toml").read_bytes()
    copied = tomllib.loads((tmp_path / "fam.toml").read_text())
    original = tomllib.loads((ROOT / "templates" / "automaton-cams.toml").read_text())
    assert copied == {**original, "name": "fam"}                           # its name is the file's
    code, output = _run(camgen, "new", "table-law")
    csv = (ROOT / "templates" / "table-law.csv").read_bytes()
    assert code == 0 and (tmp_path / "table-law.csv").read_bytes() == csv
    code, output = _run(camgen, "build", "table-law.toml", "-o", "out", "--set", "output.formats=['json']")
    assert code == 0, output
    code, output = _run(camgen, "new", "speeds", "-o", "s.toml")             # rdrd.toml is there already, the same
    assert code == 0 and output.splitlines()[:1] == ["wrote s.toml"] and "rdrd.toml" not in output


def test_new_never_overwrites_a_file_an_example_reads(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "rdrd.toml").write_text("mine\n")
    code, output = _run(camgen, "new", "speeds", "-o", "s.toml")
    assert code == 2 and output.startswith("error: --output: rdrd.toml exists with other content")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rdrd.toml"] and (tmp_path / "rdrd.toml").read_text() == \
        "mine\n"
    assert _run(camgen, "new", "rdrd") == (2, "error: --output: rdrd.toml exists; give another file\n")


def test_a_kind_keeps_its_name_and_example_picks_the_example(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    clashes = sorted((set(cam_starters()) | set(LINKAGE_STARTERS)) & set(bundled.examples()))
    assert clashes == ["barrel", "conjugate", "counter", "gear-pair", "geared-fivebar", "grooved", "hoekens", "plate",
                       "ratchet", "slider-crank", "walking-toy"]
    _run(camgen, "new", "plate", "-o", "starter.toml")
    _run(camgen, "new", "plate", "--example", "-o", "example.toml")
    assert "Every key is explained" in (tmp_path / "starter.toml").read_text()
    assert (tmp_path / "example.toml").read_text().replace('name = "example"', 'name = "plate"') == \
        (ROOT / "templates" / "plate.toml").read_text().replace("templates/plate.toml", "example.toml")


def test_new_refuses_another_programs_example_and_an_unknown_name_in_one_line(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert _run(camgen, "new", "jansen") == (2, "error: NAME: 'jansen' is a linkgen example: linkgen new jansen\n")
    assert _run(linkgen, "new", "rdrd") == (2, "error: NAME: 'rdrd' is a camgen example: camgen new rdrd\n")
    code, output = _run(camgen, "new", "rdrdd")
    assert code == 2 and output.startswith("error: KIND: unknown value 'rdrdd'; one of translating-roller")
    assert "(did you mean the example 'rdrd'?): `camgen examples` lists them" in output
    code, output = _run(linkgen, "new", "nosuch", "--example")
    assert code == 2 and output.startswith("error: NAME: unknown value 'nosuch'; one of counter, crank-rocker")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
@pytest.mark.xdist_group(GROUP)
def test_every_example_runs_by_name_after_a_plain_install(plain_install):
    """Every bundled example, copied by name (``new NAME``) and run with its documented command line (the options
    the docs' gallery adds: the formats it shows) by the console scripts of a plain install, from a folder outside
    the checkout; and a starter built with every file."""
    runs = plain_install

    def run(*args: str) -> str:
        result = subprocess.run(args, cwd=runs.work, env=runs.env, capture_output=True, text=True, timeout=900)
        assert result.returncode == 0, f"{' '.join(args)}:\n{result.stdout}\n{result.stderr}"
        return result.stdout

    where = run(str(runs.bin / "python"), "-c", "import camgen, camgen.examples; print(camgen.__file__)")
    assert Path(where.strip()).is_relative_to(runs.bin.parent), where
    examples = list(bundled.examples().values())
    assert [r["line"].split()[:3] for r in runs.copies] == [[e.program, "new", e.name] for e in examples]
    failed = [f"{r['line']}: exit {r['code']}\n{r['output']}" for r in runs.copies + runs.runs if r["code"] != 0]
    assert not failed, "\n".join(failed)
    # each run line is the example's own (program, command, its copy), and wrote its folder
    for example, record in zip(examples, runs.runs, strict=True):
        program, command, template = record["line"].split()[:3]
        assert (program, command) == (example.program, example.command), record["line"]
        assert template in (str(runs.work / example.name / f"{example.name}.toml"),
                            str(runs.gallery / f"{example.name}.gallery.toml")), record["line"]
        assert any((runs.gallery / example.name).iterdir()), record["line"]
    run("linkgen", "new", "jansen", "-o", "j.toml")
    run("linkgen", "build", "j.toml")
    assert (runs.work / "out" / "j" / "j-sheet.dxf").is_file()
    listed = run("camgen", "examples").splitlines() + run("linkgen", "examples").splitlines()
    assert len(listed) == len(TEMPLATES)


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_the_forked_runner_gives_each_lines_exit_code_and_output(tmp_path, jobs):
    """The runner the plain-install test uses (on this interpreter's console scripts), one line at a time or two:
    a command that fails gives its own exit code and message, the ones around it theirs, in the lines' order."""
    lines = ["camgen --version", "camgen build nosuch.toml", "linkgen --help"]
    driver = subprocess.run([sys.executable, str(FORKED), str(tmp_path / "runs.json"), jobs], input="\n".join(lines),
                            cwd=tmp_path, capture_output=True, text=True, timeout=300,
                            env={k: v for k, v in os.environ.items() if k != "PYTHONPATH"})
    assert driver.returncode == 0, driver.stderr
    records = json.loads((tmp_path / "runs.json").read_text())
    assert [(r["line"], r["code"]) for r in records] == list(zip(lines, [0, 2, 0], strict=True))
    assert records[0]["output"].startswith("camgen, version ")
    assert "'nosuch.toml' does not exist" in records[1]["output"]
    assert records[2]["output"].startswith("Usage: linkgen ")
