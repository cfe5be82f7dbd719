"""Synthesis in the designer's server, a websocket client as a tab: it runs in the background (another tab drags
meanwhile), one at a time a tab, its budget bounded as the command line bounds it (the same line), cancelled on
asking, and a tab that disconnects mid-synthesis stops it: its child process ends (checked by its pid), the server
goes on and stops cleanly, and Ctrl-C leaves no child behind."""
from __future__ import annotations

import contextlib
import json
import threading
import time
from pathlib import Path

import pytest

from tests.conftest import ROOT
from tests.support.designer_server import child_pids, designer, designer_process, gone
from tests.camgen.test_designer import _ask, _folder, _snapshot, _tab

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")

#: a search long enough to be under way when the tests act (cancelled long before it ends)
LONG = {"kind": "path", "points": [[0, 0], [10, 2], [20, 8], [28, 18], [32, 30]], "starts": 4,
        "generations": 2000}


def _progress(ws):
    """The first progress message of a search under way (past its first generation)."""
    while True:
        m = json.loads(ws.recv(timeout=120))
        assert m["kind"] == "progress", m
        if "generation" in m["stage"]:
            return m


def _next(ws):
    """The next message that is not a search's progress."""
    while True:
        m = json.loads(ws.recv(timeout=120))
        if m["kind"] != "progress":
            return m


def _children():
    """The synthesis processes of this process (the server served on a thread of it)."""
    import multiprocessing

    return [p for p in multiprocessing.active_children() if p.name == "camgen-synthesis"]


@contextlib.contextmanager
def _served(folder):
    """The designer's app served by uvicorn on a thread of this process (so that its threads can be counted)."""
    import uvicorn

    from camgen.designer.app import MAX_MESSAGE, make_app
    from camgen.designer.serve import listen

    sock = listen(0)
    port = sock.getsockname()[1]
    server = uvicorn.Server(uvicorn.Config(make_app(folder.resolve(), None, port), log_level="warning",
                                           lifespan="off", ws_max_size=4 * MAX_MESSAGE))
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    end = time.monotonic() + 30
    while not server.started and time.monotonic() < end:
        time.sleep(0.02)
    try:
        yield f"http://127.0.0.1:{port}/"
    finally:
        server.should_exit = True
        thread.join(30)
        sock.close()


def test_another_tab_drags_while_a_synthesis_runs_and_a_tab_runs_one_at_a_time(tmp_path):
    folder = _folder(tmp_path, "jansen")
    with designer(folder, "jansen.toml") as url, _tab(url) as (a, _, _), _tab(url) as (b, state, _):
        assert _ask(a, {"op": "synthesize", "task": LONG}) == {"kind": "synthesis-started", "name": "synthesis",
                                                                 "task": "path"}
        first = _progress(a)
        assert first["stage"].startswith("search 1 of 4, generation ") and 0 < first["fraction"] < 0.25
        moved = _ask(b, {"op": "drag", "joint": "G", "x": state["scene"]["drawn"]["G"][0] + 5.0,
                         "y": state["scene"]["drawn"]["G"][1], "final": True})
        assert moved["kind"] == "state" and moved["can_undo"]
        # the search went on meanwhile: a later generation, not yet done
        later = _progress(a)
        assert first["fraction"] < later["fraction"] < 0.25
        a.send(json.dumps({"op": "synthesize", "task": LONG}))
        assert _next(a) == {"kind": "error", "synthesis": True, "field": "synthesize", "fields": ["synthesize"],
                            "message": "error: synthesize: one synthesis at a time in a tab: cancel the one "
                                       "running first"}
        a.send(json.dumps({"op": "cancel"}))
        assert _next(a) == {"kind": "cancelling"}
        last = _next(a)
        assert last["kind"] == "synthesis-cancelled" and last["push"] and last["candidates"] == []
        assert last["message"] == "synthesis cancelled (0 candidates found before it stopped)"
        assert _ask(a, {"op": "cancel"})["message"] == "error: cancel: no synthesis is running in this tab"
        # and a tab that goes away mid-synthesis, abruptly: the server goes on, then stops cleanly
        with _tab(url) as (c, _, _):
            assert _ask(c, {"op": "synthesize", "task": LONG})["kind"] == "synthesis-started"
            _progress(c)
            c.socket.close()
        assert _ask(b, {"op": "undo"})["kind"] == "state"


@pytest.mark.parametrize(("task", "field"), [
    ({**LONG, "generations": 1_000_000}, "task.generations"),
    ({**LONG, "starts": 64, "generations": 10_000}, "task.generations"),
    ({"kind": "path", "points": [[0, 0], [1, 1]]}, "task.points"),
    ({"kind": "crank-rocker", "rocker": 40.0, "swing": 45.0, "samples": 10**6}, "task.samples")])
def test_a_task_the_command_line_refuses_is_refused_in_its_line(tmp_path, task, field):
    from click.testing import CliRunner

    from camgen.core.toml_text import dumps
    from linkgen.cli import main

    (tmp_path / "t.toml").write_text(dumps({"name": "synthesis", "task": task}), encoding="utf-8")
    done = CliRunner().invoke(main, ["synthesize", str(tmp_path / "t.toml"), "-o", str(tmp_path / "out")])
    assert done.exit_code == 2
    line = done.stderr.strip()
    folder = tmp_path / "served"
    folder.mkdir()
    before = _snapshot(folder)
    with designer(folder) as url, _tab(url) as (ws, _, _):
        refused = _ask(ws, {"op": "synthesize", "task": task})
        assert refused["kind"] == "error" and refused["field"] == field
        assert refused["message"] == line and line.startswith(f"error: {field}: ")
        assert _ask(ws, {"op": "synthesize", "task": "path"})["message"].startswith("error: task: give the task as")
        assert _ask(ws, {"op": "candidate", "name": "x-1"})["message"] == (
            "error: candidate: no candidate 'x-1' of this tab's synthesis (offered: none yet: run a synthesis)")
    assert _snapshot(folder) == before


def test_a_disconnect_mid_synthesis_ends_its_child_and_the_server_goes_on(tmp_path):
    import tempfile

    folder = _folder(tmp_path, "jansen")
    temporaries = set(Path(tempfile.gettempdir()).glob("camgen-designer-*"))
    with _served(folder) as url:
        assert not _children()
        with _tab(url) as (ws, _, _):
            assert _ask(ws, {"op": "synthesize", "task": LONG})["kind"] == "synthesis-started"
            _progress(ws)
            (child,) = _children()
            ws.socket.close()                            # gone without a word
        assert gone(child.pid), "the synthesis went on after its tab disconnected"
        assert not _children()
        with _tab(url) as (ws, _, _):
            opened = _ask(ws, {"op": "open", "path": "jansen.toml"})
            assert opened["kind"] == "state"
            dragged = _ask(ws, {"op": "drag", "joint": "G", "x": opened["scene"]["drawn"]["G"][0] + 5.0,
                                "y": opened["scene"]["drawn"]["G"][1]})
            assert dragged["kind"] == "preview"
    assert set(Path(tempfile.gettempdir()).glob("camgen-designer-*")) <= temporaries
    assert (folder / "jansen.toml").read_bytes() == (ROOT / "templates" / "jansen.toml").read_bytes()


def test_ctrl_c_during_a_synthesis_stops_the_server_cleanly_and_leaves_no_process(tmp_path):
    """The tab still open and its synthesis running when the server is stopped: exit code 0, no traceback, no
    temporary folder (the checks of :func:`tests.support.designer_server.designer`), and none of the server's
    child processes (the synthesis', multiprocessing's resource tracker) left, by their pids."""
    from websockets.sync.client import connect

    folder = _folder(tmp_path, "jansen")
    # the tab closes only after the server has stopped (the stack exits last)
    with contextlib.ExitStack() as later, designer_process(folder, "jansen.toml") as (url, server):
        ws = later.enter_context(connect(url.replace("http", "ws") + "ws", max_size=None, open_timeout=30))
        json.loads(ws.recv(timeout=60))
        json.loads(ws.recv(timeout=60))
        assert _ask(ws, {"op": "synthesize", "task": LONG})["kind"] == "synthesis-started"
        _progress(ws)
        children = child_pids(server.pid)
        commands = [Path(f"/proc/{pid}/cmdline").read_bytes() for pid in children]
        assert any(b"spawn_main" in c for c in commands), commands
    assert children and all(gone(pid) for pid in children), "a process of the server outlived it"
    assert (folder / "jansen.toml").read_bytes() == (ROOT / "templates" / "jansen.toml").read_bytes()
