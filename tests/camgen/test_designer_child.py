"""A tab's synthesis in a child process (camgen/designer/child.py): its messages equal those of the same synthesis
run in this process, a cancel stops it within a generation and its process is gone (by its pid), and a child that
does not stop when told is terminated."""
from __future__ import annotations

import os
import time

import pytest

from tests.support.designer_server import gone

#: a short search (as the browser test runs it) and a long one, cancelled long before it ends
SHORT = {"kind": "path", "points": [[0, 0], [10, 2], [20, 8], [28, 18], [32, 30]], "starts": 1, "generations": 40,
         "seed": 3, "candidates": 2}
LONG = {**SHORT, "starts": 4, "generations": 2000}


def _until(messages, kind_or_test, seconds=120.0):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if any(kind_or_test(m) for m in list(messages)):
            return
        time.sleep(0.02)
    raise AssertionError(f"not seen within {seconds} s: {[m['kind'] for m in messages]}")


def stubborn(message, messages, stop, parent):
    """A child that says it has started and then never looks at its stop flag (for the test of terminating it)."""
    messages.put({"kind": "progress", "push": True, "candidates": [], "fraction": 0.0, "stage": "stuck"})
    while True:
        time.sleep(1.0)


def test_a_synthesis_in_the_child_equals_the_same_synthesis_in_this_process():
    from camgen.designer.child import ChildJob
    from camgen.designer.synthesis import Job, task_of

    here: list[dict] = []
    Job(task_of({"task": SHORT}), here.append).run()
    there: list[dict] = []
    job = ChildJob({"task": SHORT}, there.append)
    job.start()
    pid = job.pid
    assert pid is not None and pid != os.getpid()
    job.join(300)
    assert not job.running()
    # progress as it comes (how many messages depends on the time a generation takes: at most one per 0.1 s),
    # then the same last message but for the search's own wall time
    for got in (here, there):
        assert [m["kind"] for m in got[:-1]] == ["progress"] * (len(got) - 1) and len(got) > 1
        fractions = [m["fraction"] for m in got[:-1]]
        assert fractions == sorted(fractions) and fractions[-1] == 1.0
    assert here[-1]["kind"] == "synthesized" and len(here[-1]["candidates"]) == 2
    assert {k: v for k, v in here[-1].items() if k != "search"} == {k: v for k, v in there[-1].items() if k != "search"}
    assert {k: v for k, v in here[-1]["search"].items() if k != "seconds"} == {
        k: v for k, v in there[-1]["search"].items() if k != "seconds"}
    assert job.found == {c["name"]: c["text"] for c in here[-1]["candidates"]}
    assert job.process.exitcode == 0 and gone(pid)


def test_a_cancel_stops_the_child_within_a_generation_and_its_process_isgone():
    from camgen.designer.child import ChildJob

    seen: list[dict] = []
    job = ChildJob({"task": LONG}, seen.append)
    job.start()
    _until(seen, lambda m: m["kind"] == "progress" and "generation" in m["stage"])
    job.cancel()
    job.join(60)
    assert not job.running()
    assert seen[-1]["kind"] == "synthesis-cancelled", seen[-1]
    assert seen[-1]["message"] == "synthesis cancelled (0 candidates found before it stopped)"
    assert job.process.exitcode == 0                     # it stopped by itself: not terminated
    assert gone(job.pid)


def test_a_child_that_does_not_stop_when_told_is_terminated(monkeypatch):
    from camgen.designer import child

    monkeypatch.setattr(child, "STOP_SECONDS", 0.5)
    seen: list[dict] = []
    job = child.ChildJob({"task": LONG}, seen.append, target=stubborn)
    job.start()
    _until(seen, lambda m: m.get("stage") == "stuck")
    job.cancel()
    job.join(30)
    assert not job.running()
    assert seen[-1]["kind"] == "synthesis-cancelled" and seen[-1]["message"].startswith(
        "synthesis stopped (it did not stop within 0.5 s of being told, so its process was ended)")
    assert job.process.exitcode == -15                   # SIGTERM
    assert gone(job.pid)


def test_a_task_the_child_cannot_validate_is_one_error_line():
    from camgen.designer.child import ChildJob

    seen: list[dict] = []
    job = ChildJob({"task": "path"}, seen.append)
    job.start()
    job.join(120)
    assert [m["kind"] for m in seen] == ["error"]
    assert seen[0]["message"].startswith("error: task: give the task as a JSON object")
    assert gone(job.pid)


@pytest.fixture(autouse=True)
def _no_child_left():
    import multiprocessing

    yield
    assert not [p for p in multiprocessing.active_children() if p.name == "camgen-synthesis"]
