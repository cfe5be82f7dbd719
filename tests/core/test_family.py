"""Families: sweep expansion, parallel builds identical to serial ones, failures recorded, resuming, bad sweeps."""
from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.core.errors import SpecError
from camgen.core.family import members, read_family
from tests.conftest import ROOT

RDRD = ROOT / "templates" / "rdrd.toml"


def family_file(tmp_path, body: str, name: str = "fam.toml"):
    path = tmp_path / name
    shutil.copy(RDRD, tmp_path / "rdrd.toml")
    path.write_text(f'base = "rdrd.toml"\nname = "fam"\n{body}')
    return path


def test_expansion_products_ranges_zips_and_names(tmp_path):
    path = family_file(tmp_path, '[sweep]\n"follower.offset" = [0.0, 5.0]\n"follower.roller_radius" = '
                                 '{start = 6, stop = 10, step = 2}\n[sweep.zip]\n"motion.0.lift" = [10, 20]\n'
                                 '"motion.2.lift" = [10, 20]\n')
    raw, sweep = read_family(path)
    items = members(raw, sweep)
    assert len(items) == 2 * 3 * 2
    assert items[0].name == "fam-offset0-roller_radius6-0lift10-2lift10"
    assert items[-1].name == "fam-offset5-roller_radius10-0lift20-2lift20"
    assert len({m.name for m in items}) == len(items)
    assert [m.name for m in members(*read_family(path))] == [m.name for m in items]       # stable
    m = items[-1]
    assert m.raw["follower"]["roller_radius"] == 10 and m.raw["motion"][2]["lift"] == 20
    assert m.raw["cam"]["base_radius"] == 40.0                                            # from the base


def test_base_includes_merge_tables_and_replace_lists(tmp_path):
    family_file(tmp_path, "", name="mid.toml")
    (tmp_path / "mid.toml").write_text('base = "rdrd.toml"\nname = "mid"\n[cam]\nbore = 6.0\n')
    (tmp_path / "top.toml").write_text('base = "mid.toml"\n[cam]\nthickness = 5.0\n[sweep]\n"cam.bore" = [4, 6]\n')
    raw, sweep = read_family(tmp_path / "top.toml")
    assert (raw["name"], raw["cam"]["bore"], raw["cam"]["thickness"], raw["cam"]["base_radius"]) == \
        ("mid", 6.0, 5.0, 40.0)
    assert [m.raw["cam"]["bore"] for m in members(raw, sweep)] == [4, 6]


@pytest.mark.parametrize("body, words", [
    ('[sweep]\n"motion.0.lif" = [1, 2]\n', "member fam-lif1: motion[0].lif: unknown key"),
    ('[sweep]\n"cam.base_radius" = [-1, 40]\n',
     "member fam-base_radius-1: cam.base_radius: must be > 0 and <= 10000 mm"),
    ('[sweep]\n"cam.bore" = {start = 5, stop = 1, step = 1}\n', "sweep.cam.bore: a range needs"),
    ('[sweep.zip]\n"motion.0.lift" = [1, 2]\n"motion.2.lift" = [1]\n', "zipped lists must have equal lengths"),
    ('[sweep]\n"cam.bore" = []\n', "sweep.cam.bore: needs at least one value"),
    ('[sweep]\n"cam.bore" = {start = 0, stop = 1, step = 1e-320}\n', "sweep.cam.bore: a range of"),
    ('[sweep]\n"cam.bore" = {start = -1e308, stop = 1e308, step = 1}\n', "sweep.cam.bore: a range of"),
    ('[sweep]\n"cam.bore" = {start = 0, stop = true, step = 1}\n', "sweep.cam.bore: a range needs numbers"),
    ('[sweep]\n"cam.bore" = {start = 0, stop = 999, step = 1}\n"cam.thickness" = {start = 1, stop = 999, step = 1}\n',
     "sweep: the sweep makes 999000 members, more than 10000"),
    ('[sweep]\n"motion.0.lift" = [true, 20]\n', "motion[0].lift: must be a number, not true or false"),
])
def test_bad_sweeps_are_clear_errors_before_any_work(tmp_path, body, words):
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["family", str(family_file(tmp_path, body)), "-o", str(out)])
    assert result.exit_code == 2 and words in result.stderr
    assert not out.exists()


FIFTY = ('[output]\nformats = ["dxf", "json"]\n[sweep]\n"follower.offset" = [0.0, 2.0, 4.0, 6.0, 8.0]\n'
         '[sweep.zip]\n"motion.0.lift" = {start = 3, stop = 30, step = 3}\n'
         '"motion.2.lift" = {start = 3, stop = 30, step = 3}\n')


def _files(root):
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


def test_fifty_cams_with_two_jobs_match_one_job_byte_for_byte(tmp_path):
    path = family_file(tmp_path, FIFTY)
    for jobs in (1, 2):
        result = CliRunner().invoke(main, ["family", str(path), "-o", str(tmp_path / f"j{jobs}"), "--jobs", str(jobs)])
        assert result.exit_code == 0, result.output
    one, two = _files(tmp_path / "j1"), _files(tmp_path / "j2")
    assert len(json.loads(one["summary.json"])) == 50
    assert one.keys() == two.keys() and all(one[k] == two[k] for k in one)


def test_failing_members_are_recorded_and_the_others_built(tmp_path):
    path = family_file(tmp_path, '[output]\nformats = ["json"]\n[sweep]\n"cam.base_radius" = [6, 40]\n'
                                 '[sweep.zip]\n"motion.0.angle" = [40, 120]\n"motion.1.angle" = [140, 60]\n')
    result = CliRunner().invoke(main, ["family", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    rows = {r["name"]: r for r in json.loads((tmp_path / "out" / "summary.json").read_text())}
    failed = [r for r in rows.values() if r["status"] == "failed"]
    assert failed and all(r["error"] for r in failed)
    assert any("undercut" in r["error"] or "leaves no material" in r["error"] for r in failed)
    assert sum(r["status"] == "ok" for r in rows.values()) >= 1
    csv = (tmp_path / "out" / "summary.csv").read_text().splitlines()
    assert csv[0].startswith("name,cam.base_radius,motion.0.angle,motion.1.angle,status,error")
    assert len(csv) == 1 + len(rows)


def test_an_interrupted_run_resumes_without_rebuilding_finished_members(tmp_path):
    path = family_file(tmp_path, '[output]\nformats = ["dxf", "json"]\n[sweep]\n"follower.offset" = [0.0, 3.0, 6.0]\n')
    out = tmp_path / "out"
    assert CliRunner().invoke(main, ["family", str(path), "-o", str(out)]).exit_code == 0
    done = sorted(p for p in out.iterdir() if p.is_dir())
    stamps = {p: (p / f"{p.name}.dxf").stat().st_mtime_ns for p in done}
    (done[1] / ".inputs").unlink()                    # as if the run was stopped before this member finished
    result = CliRunner().invoke(main, ["family", str(path), "-o", str(out)])
    assert result.exit_code == 0 and "3 members: 1 built, 0 failed, 2 already there;" in result.output, result.output
    assert (done[0] / f"{done[0].name}.dxf").stat().st_mtime_ns == stamps[done[0]]
    assert (done[2] / f"{done[2].name}.dxf").stat().st_mtime_ns == stamps[done[2]]
    assert (done[1] / ".inputs").exists()
    leftovers = [p for p in out.rglob(".*.tmp")]
    assert leftovers == []                            # no half-written file anywhere
    again = CliRunner().invoke(main, ["family", str(path), "-o", str(out)])
    assert again.exit_code == 0 and "3 members: 0 built, 3 already there;" in again.output, again.output


def test_changed_inputs_rebuild(tmp_path):
    path = family_file(tmp_path, '[output]\nformats = ["json"]\n[sweep]\n"follower.offset" = [0.0, 3.0]\n')
    out = tmp_path / "out"
    CliRunner().invoke(main, ["family", str(path), "-o", str(out)])
    path.write_text(path.read_text().replace('formats = ["json"]', 'formats = ["json"]\ntolerance = 0.005'))
    result = CliRunner().invoke(main, ["family", str(path), "-o", str(out)])
    assert "2 members: 2 built, 0 failed; summary" in result.output, result.output


def test_a_rerun_counts_the_failures_it_found_done_apart_from_its_own(tmp_path):
    """The undercut member fails on the first run and is found done (failed) on the second: nothing is built."""
    path = family_file(tmp_path, '[output]\nformats = ["json"]\n[sweep]\n"cam.base_radius" = [6.0]\n'
                                 '[sweep.zip]\n"motion.0.angle" = [40, 120]\n"motion.1.angle" = [140, 60]\n')
    out = tmp_path / "out"
    first = CliRunner().invoke(main, ["family", str(path), "-o", str(out)])
    assert first.exit_code == 0 and "2 members: 1 built, 1 failed; summary" in first.output, first.output
    again = CliRunner().invoke(main, ["family", str(path), "-o", str(out)])
    assert again.exit_code == 0, again.output
    assert "2 members: 0 built, 2 already there (1 of them failed); summary" in again.output, again.output
    assert re.search(r"^failed fam-base_radius6-0angle40-1angle140: ", again.output, re.M), again.output


def test_member_names_errors_for_collisions():
    with pytest.raises(SpecError, match="share a name"):
        members({"name": "x"}, {"a.b": ["1", 1]})


def test_a_dask_cluster_builds_the_same_bytes(tmp_path):
    """The same family on a LocalCluster on loopback (two worker processes) gives the files of one local job."""
    distributed = pytest.importorskip("dask.distributed", reason="dask.distributed is not installed")
    path = family_file(tmp_path, FIFTY)
    assert CliRunner().invoke(main, ["family", str(path), "-o", str(tmp_path / "local")]).exit_code == 0
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                                  processes=True) as cluster:
        result = CliRunner().invoke(main, ["family", str(path), "-o", str(tmp_path / "dask"),
                                           "--scheduler", cluster.scheduler_address])
    assert result.exit_code == 0, result.output
    local, remote = _files(tmp_path / "local"), _files(tmp_path / "dask")
    assert local.keys() == remote.keys() and all(local[k] == remote[k] for k in local)
    assert len(json.loads(remote["summary.json"])) == 50


def test_resume_rebuilds_a_member_whose_file_is_missing_or_damaged(tmp_path):
    path = family_file(tmp_path, '[output]\nformats = ["dxf", "json"]\n[sweep]\n"follower.offset" = [0.0, 3.0, 6.0]\n')
    out = tmp_path / "out"
    assert CliRunner().invoke(main, ["family", str(path), "-o", str(out)]).exit_code == 0
    clean = _files(out)
    first, second, third = sorted(p for p in out.iterdir() if p.is_dir())
    (first / f"{first.name}.dxf").unlink()                     # a deleted file
    (second / "row.json").write_text("{not json")               # a damaged row
    (third / f".{third.name}.dxf.4242.tmp").write_text("half")  # a killed run's temporary file
    result = CliRunner().invoke(main, ["family", str(path), "-o", str(out)])
    assert result.exit_code == 0 and "3 members: 2 built, 0 failed, 1 already there;" in result.output, result.output
    assert _files(out) == clean                                  # byte for byte what a clean run makes


#: how long (s) the test below lets Dask try to reach a scheduler that is not there (the command waits 10 s)
SCHEDULER_WAIT_SECONDS = 1.0


def test_an_unreachable_scheduler_is_one_line_and_writes_nothing(tmp_path, monkeypatch):
    distributed = pytest.importorskip("dask.distributed")
    client = distributed.Client

    def impatient(address, timeout):                # the same refusal, after 1 s of retries instead of 10
        assert timeout == 10
        return client(address, timeout=SCHEDULER_WAIT_SECONDS)

    monkeypatch.setattr(distributed, "Client", impatient)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["family", str(family_file(tmp_path, '[sweep]\n"cam.bore" = [8, 10]\n')),
                                       "-o", str(out), "--scheduler", "tcp://127.0.0.1:1"])
    assert result.exit_code == 2 and result.stderr.startswith("error: --scheduler: cannot reach")
    assert len(result.stderr.strip().splitlines()) == 1 and not out.exists()


def test_a_failure_of_any_kind_is_recorded_and_the_family_goes_on(tmp_path):
    from camgen.core.family import members as expand
    from camgen.core.family import run_family

    def builder(raw, folder):
        if raw["follower"]["offset"] == 3.0:
            raise PermissionError(13, "Permission denied", str(folder / "x.dxf"))
        if raw["follower"]["offset"] == 6.0:
            raise ZeroDivisionError("division by zero")
        return {}

    raw, sweep = read_family(family_file(tmp_path, '[sweep]\n"follower.offset" = [0.0, 3.0, 6.0]\n'))
    rows = run_family(expand(raw, sweep), tmp_path / "out", builder)
    assert [r["status"] for r in rows] == ["ok", "failed", "failed"]
    assert rows[1]["error"].startswith("cannot write") and "Permission denied" in rows[1]["error"]
    assert rows[2]["error"] == "ZeroDivisionError: division by zero"


def _children(pid: int) -> list[str]:
    """The processes whose parent is ``pid`` (read from /proc)."""
    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if fields[1] == str(pid):
            out.append(stat.parent.name)
    return out


def _running(pid: str) -> bool:
    """Whether process ``pid`` still runs (an ended one waiting to be reaped, a zombie, does not)."""
    try:
        return (Path("/proc") / pid / "stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.parametrize("signame", ["SIGKILL", "SIGTERM"])
def test_killing_a_family_leaves_no_worker_and_a_rerun_finishes_it(tmp_path, signame):
    """SIGKILL (or SIGTERM, what a scheduler or `kill` sends) of the command mid-run: its workers end, the re-run
    clears the temporary files and gives the same bytes as an undisturbed run. 40 variants: enough that the signal,
    sent once 3 have started, lands before the last (20 were once all done first)."""
    import os
    import signal
    import subprocess
    import sys
    import time

    body = ('[output]\nformats = ["dxf", "stl", "json"]\n[sweep]\n'
            '"follower.offset" = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]\n'
            '[sweep.zip]\n"motion.0.lift" = {start = 5, stop = 25, step = 5}\n'
            '"motion.2.lift" = {start = 5, stop = 25, step = 5}\n')
    path = family_file(tmp_path, body)
    out, clean = tmp_path / "out", tmp_path / "clean"
    cmd = [sys.executable, "-m", "camgen", "family", str(path), "--jobs", "2", "-o"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen([*cmd, str(out)], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and len(list(out.glob("*/.inputs"))) < 3:
        time.sleep(0.05)
    children = _children(proc.pid)
    proc.send_signal(getattr(signal, signame))
    proc.wait()
    deadline = time.monotonic() + 30                                  # each worker notices within 0.2 s when idle
    while time.monotonic() < deadline and any(_running(pid) for pid in children):
        time.sleep(0.1)
    alive = [pid for pid in children if _running(pid)]
    assert children and alive == []                                  # the workers ended with their parent
    assert len(list(out.glob("*/.inputs"))) < 40                      # it was stopped part of the way
    assert subprocess.run([*cmd, str(out)], env=env).returncode == 0
    assert subprocess.run([*cmd, str(clean)], env=env).returncode == 0
    assert list(out.rglob(".*.tmp")) == []
    assert _files(out) == _files(clean)


def test_the_sheet_table_is_a_model_and_every_key_documented():
    """The family's [sheet] table is validated by its model (camgen.core.family.SheetTable): errors name
    sheet.<key>, defaults fill what is not given (tests/project/test_docs.py checks the template reference lists every
    key)."""
    from camgen.core.family import SheetTable, split_family

    _, sweep, table = split_family({"name": "f", "sheet": {"rotations": 45}, "sweep": {"cam.bore": [8, 10]}})
    assert sweep == {"cam.bore": [8, 10]} and table == SheetTable(size=(600.0, 400.0), margin=3.0, rotations=45.0)
    assert split_family({"name": "f", "sweep": {}})[2] is None
    for sheet, words in (({"size": [100.0, 0.0]}, "sheet.size[1]: must be > 0"), ({"margin": 1e4}, "sheet.margin"),
                         ({"rotations": 1e-12}, "sheet.rotations: must be 0 or divide 360"),
                         ({"grain": "yes please"}, "sheet.grain")):
        with pytest.raises(SpecError, match=re.escape(words)):
            split_family({"name": "f", "sheet": sheet, "sweep": {}})


@pytest.mark.parametrize("count, workers", [(200, 2), (1000, 2), (57, 3), (5, 2), (1, 1), (0, 2)])
def test_batches_cover_the_family_in_order_and_shrink_so_the_workers_end_together(count, workers):
    """The batches are the members in order, each of 1 to PROGRESS_CHUNK, never growing; handed out greedily to
    ``workers`` equal workers (the next batch to the first one free), the last worker ends at most one member
    after the first (batches of 8 left one building up to 8 members alone) and within one of an even split."""
    import heapq

    from camgen.core.family import PROGRESS_CHUNK, _batches

    work = [(i,) for i in range(count)]
    batches = _batches(work, workers)
    sizes = [len(b) for b in batches]
    assert [m for b in batches for m in b] == work
    assert all(1 <= s <= PROGRESS_CHUNK for s in sizes) and sizes == sorted(sizes, reverse=True)
    ends = [0] * workers                                    # each worker's end, in members built
    for size in sizes:
        heapq.heappush(ends, heapq.heappop(ends) + size)
    assert max(ends) - min(ends) <= 1
    assert max(ends) <= -(-count // workers) + 1            # within a member of an even split
    if count == 200 and workers == 2:
        assert sizes == [8] * 22 + [6, 5, 4, 3, 2, 1, 1, 1, 1]      # 31 hand-overs, not 200
