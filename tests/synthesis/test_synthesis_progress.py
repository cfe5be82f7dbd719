"""The synthesis' progress and cancel hook: every generation of a path search reported, the fraction rising to 1,
the best candidates so far those the finished result offers; a False stops it within one generation with what was
found; the hook changes nothing (a fixed seed writes byte-identical files through the command and with a hook)."""
from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from linkgen.synthesis import synthesize, validate_task, write_synthesis
from linkgen.synthesis.progress import Cancelled, Progress
from tests.conftest import ROOT

LINE6 = ROOT / "templates" / "synth-line6.toml"
#: a short timed path search: two searches of 40 generations
PATH = {"name": "p", "task": {"kind": "path", "points": [[0, 0], [10, 2], [20, 8], [28, 18], [32, 30]],
                              "link_range": [4, 60], "starts": 2, "generations": 40, "seed": 11, "candidates": 2}}


def _files(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()
            and p.name != "summary.json"}


def test_every_generation_is_reported_and_the_last_report_is_the_result():
    seen: list[Progress] = []
    result = synthesize(validate_task(PATH), progress=lambda p: seen.append(p) or True)
    fractions = [p.fraction for p in seen]
    assert fractions[0] == 0.0 and fractions[-1] == 1.0
    assert fractions == sorted(fractions)
    generations = [p for p in seen if "generation" in p.stage]
    # scipy calls back once a generation it runs (it may stop a search early once converged; never more)
    assert 2 <= len(generations) <= 2 * 40
    assert {p.stage.split(",")[0] for p in generations} == {"search 1 of 2", "search 2 of 2"}
    # nothing found before the first search is polished; the last report offers the result's candidates
    first = next(i for i, p in enumerate(seen) if p.stage == "search 1 of 2 polished")
    assert all(p.best == () for p in seen[:first])
    assert [c.template for c in seen[-1].best] == [c.template for c in result.candidates]
    assert seen[-1].best[0].row["error_mm2"] == result.candidates[0].row["error_mm2"]


def test_false_stops_the_search_within_one_generation_with_what_was_found():
    seen: list[Progress] = []

    def stop_in_second_search(p: Progress) -> bool:
        seen.append(p)
        return not p.stage.startswith("search 2 of 2, generation 3 ")

    with pytest.raises(Cancelled) as caught:
        synthesize(validate_task(PATH), progress=stop_in_second_search)
    assert seen[-1].stage == "search 2 of 2, generation 3 of 40"          # no report after the one that said stop
    assert 0.5 * 0.99 < seen[-1].fraction < 0.6 * 0.99
    # the first search's candidates came with the refusal: as the finished first search alone would offer them
    alone = synthesize(validate_task({**PATH, "task": {**PATH["task"], "starts": 1}}))
    assert caught.value.best and caught.value.best[0].row["error_mm2"] == pytest.approx(
        alone.candidates[0].row["error_mm2"], rel=1e-12)
    n = len(caught.value.best)
    assert str(caught.value) == f"synthesis cancelled ({n} candidate{'s' if n != 1 else ''} found before it stopped)"


def test_an_analytic_method_reports_its_stages_and_stops_between_them():
    raw = {"name": "cr", "task": {"kind": "crank-rocker", "rocker": 40.0, "swing": 45.0, "candidates": 2}}
    seen: list[Progress] = []
    result = synthesize(validate_task(raw), progress=lambda p: seen.append(p) or True)
    assert [p.fraction for p in seen] == [0.0, 0.5, 1.0]
    assert [c.template for c in seen[-1].best] == [c.template for c in result.candidates]
    with pytest.raises(Cancelled) as caught:
        synthesize(validate_task(raw), progress=lambda p: p.fraction < 0.5)
    assert caught.value.best == ()


def test_the_hook_changes_no_file_the_command_writes(tmp_path):
    """A fixed seed: the command line's files, and the library's with a hook, byte for byte (summary.json holds
    the seconds the search took, so its candidates are compared instead)."""
    from linkgen.cli import main

    out = tmp_path / "cli"
    done = CliRunner().invoke(main, ["synthesize", str(LINE6), "-o", str(out), "--set", "task.starts=2",
                                     "--set", "task.generations=60", "--set", "task.candidates=2"])
    assert done.exit_code == 0, done.output
    from linkgen.synthesis import load_task

    spec = load_task(LINE6, ["task.starts=2", "task.generations=60", "task.candidates=2"])
    calls: list[float] = []
    hooked = synthesize(spec, progress=lambda p: calls.append(p.fraction) or True)
    write_synthesis(hooked, tmp_path / "lib")
    assert len(calls) > 10
    assert _files(out) and _files(out) == _files(tmp_path / "lib")
    want = json.loads((out / "summary.json").read_text())["candidates"]
    assert json.loads((tmp_path / "lib" / "summary.json").read_text())["candidates"] == want
