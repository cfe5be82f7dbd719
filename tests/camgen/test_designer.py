"""The designer's server (``camgen serve``) without a browser: a websocket client as a tab. Refusals answer one
error each, write nothing and leave the server running; tabs are separate; the TOML it saves reads back equal."""
from __future__ import annotations

import contextlib
import json
import shutil
import tomllib

import pytest

from tests.conftest import ROOT
from tests.support.designer_server import designer

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
from websockets.sync.client import connect


def _folder(tmp_path, *names):
    for name in names:
        shutil.copy(ROOT / "templates" / f"{name}.toml", tmp_path / f"{name}.toml")
    return tmp_path


def _snapshot(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@contextlib.contextmanager
def _tab(url):
    """A tab's websocket, the state it opened with and the folder's listing."""
    with connect(url.replace("http", "ws") + "ws", max_size=None, open_timeout=30) as ws:
        first = json.loads(ws.recv(timeout=60))
        listing = first if first["kind"] == "files" else json.loads(ws.recv(timeout=60))
        yield ws, (first if first["kind"] == "state" else None), listing


def _ask(ws, message):
    ws.send(message if isinstance(message, (str, bytes)) else json.dumps(message))
    return json.loads(ws.recv(timeout=120))


def test_the_toml_it_writes_reads_back_to_every_template():
    from camgen.core.toml_text import dumps

    for path in sorted((ROOT / "templates").glob("*.toml")):
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
        assert tomllib.loads(dumps(raw)) == raw, path.name


def test_bad_requests_answer_one_error_each_and_write_nothing(tmp_path):
    folder = _folder(tmp_path, "rdrd")
    outside = tmp_path.parent / f"{tmp_path.name}-outside.toml"
    shutil.copy(folder / "rdrd.toml", outside)
    before = _snapshot(folder)
    with designer(folder, "rdrd.toml") as url:
        with _tab(url) as (ws, state, listing):
            _refusals(ws, state, listing, outside)
        assert not outside.with_name("escaped.toml").exists()
        assert _snapshot(folder) == before
    outside.unlink()


def _refusals(ws, state, listing, outside):
    """Each bad request of a tab answers one error and changes nothing; the tab is served after."""
    assert state["file"] == "rdrd.toml" and listing["files"] == ["rdrd.toml"]
    bad = [({"op": "open", "path": f"../{outside.name}"}, "path", "outside the folder"),
           ({"op": "open", "path": str(outside)}, "path", "outside the folder"),
           ({"op": "save", "path": "../escaped.toml"}, "path", "outside the folder"),
           ({"op": "save", "path": "notes.txt"}, "path", "give a .toml file"),
           ("this is not JSON", "message", "not JSON"),
           ("[1, 2]", "message", '"op"'),
           ({"op": "format-disk"}, "op", "no such operation"),
           ({"op": "set", "path": "cam.base_radius"}, "message", '"path" and "text"'),
           ({"op": "set", "path": "nothing[x].here", "text": "1"}, "nothing[x].here", "not a field"),
           ({"op": "drag", "joint": "G", "x": 1, "y": 2}, "joint", "no joint"),
           ("x" * (300 * 1024), "message", "at most 262144 bytes"),
           (b"\x00" * 10, "message", "send text")]
    for message, field, says in bad:
        got = _ask(ws, message)
        assert got["kind"] == "error", message
        assert got["field"] == field and says in got["message"], got
        assert got["message"].startswith("error: ") and "\n" not in got["message"]
    with pytest.raises(TimeoutError):                         # one answer each: nothing more is waiting
        ws.recv(timeout=0.5)
    again = _ask(ws, {"op": "set", "path": "cam.thickness", "text": "9"})   # still serving this tab
    assert again["kind"] == "state" and "thickness = 9" in again["text"]


def test_each_tab_is_its_own_design(tmp_path):
    folder = _folder(tmp_path, "rdrd")
    with designer(folder, "rdrd.toml") as url, _tab(url) as (one, _, _), _tab(url) as (two, _, _):
        _separate(one, two, folder)


def _separate(one, two, folder):
    """An edit in one tab is not in the other."""
    changed = _ask(one, {"op": "set", "path": "cam.thickness", "text": "12"})
    assert "thickness = 12" in changed["text"] and changed["can_undo"]
    other = _ask(two, {"op": "redo"})                       # the second tab has no edit of its own to redo
    assert other["kind"] == "error" and other["field"] == "history"
    saved = _ask(two, {"op": "save", "path": "second.toml"})
    assert saved == {"kind": "saved", "path": "second.toml"}
    assert (folder / "second.toml").read_bytes() == (folder / "rdrd.toml").read_bytes()


def test_a_missing_extra_is_one_line_naming_it(monkeypatch, tmp_path):
    import importlib.util

    from click.testing import CliRunner

    from camgen.cli import main

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "starlette" else real(name, *a))
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, ["serve", "--no-browser"])
    assert result.exit_code == 2
    assert result.output.strip().splitlines() == [
        "error: serve: the designer needs starlette: pip install 'camgen[serve]'"]
    assert list(tmp_path.iterdir()) == []


def test_a_port_out_of_range_is_refused(tmp_path, monkeypatch):
    from click.testing import CliRunner

    from camgen.cli import main

    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, ["serve", "--no-browser", "--port", "70000"])
    assert result.exit_code == 2
    assert result.output.strip() == "error: --port: must be 0 to 65535 (got 70000)"


def test_only_requests_addressed_to_this_machine_are_answered(tmp_path):
    import urllib.error
    import urllib.request

    from websockets.exceptions import InvalidStatus

    folder = _folder(tmp_path, "rdrd")
    with designer(folder, "rdrd.toml") as url:
        with urllib.request.urlopen(url, timeout=30) as page:
            assert page.status == 200 and b"camgen designer" in page.read()
        other = urllib.request.Request(url, headers={"Host": "designer.example.com"})
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(other, timeout=30)
        assert refused.value.code == 403
        with pytest.raises(urllib.error.HTTPError) as missing:
            urllib.request.urlopen(url + "rdrd.toml", timeout=30)      # no route to the folder's files
        assert missing.value.code == 404
        with pytest.raises(InvalidStatus):                              # a page of another site
            connect(url.replace("http", "ws") + "ws", origin="http://designer.example.com", open_timeout=30)
        with _tab(url) as (_, state, _):                                # still serving
            assert state["file"] == "rdrd.toml"


def test_the_form_is_every_field_of_the_models_with_their_schema():
    from camgen import api
    from camgen.designer.form import form
    from camgen.spec import CamSpec

    raw = tomllib.loads((ROOT / "templates" / "rdrd.toml").read_text(encoding="utf-8"))
    spec = api.validate(raw)
    entries = {e["path"]: e for e in form(spec, raw)}
    cam = type(spec.cam)
    assert {p for p in entries if p.startswith("cam.")} == {f"cam.{k}" for k in cam.model_fields}
    schema = CamSpec.model_json_schema()
    segment = schema["$defs"][type(spec.motion[0]).__name__]["properties"]["angle"]
    assert entries["motion[1].angle"]["unit"] == segment["unit"] == "degrees"
    assert entries["motion[1].angle"]["maximum"] == segment["maximum"] == 360
    assert entries["motion[1].angle"]["exclusiveMinimum"] == 0
    assert entries["cam.thickness"]["value"] == 8.0 and entries["cam.thickness"]["given"]
    rotation = cam.model_fields["rotation"]
    assert entries["cam.rotation"]["enum"] == ["ccw", "cw"] and entries["cam.rotation"]["description"] == \
        rotation.description
    left_out = entries["cam.min_rho_margin"]
    assert not left_out["given"] and left_out["value"] == cam.model_fields["min_rho_margin"].default


def test_a_dragged_joint_takes_its_length_checks_along(tmp_path):
    import math

    from camgen.designer.session import Session

    folder = _folder(tmp_path, "jansen")
    session = Session(folder.resolve())
    start = session.handle({"op": "open", "path": "jansen.toml"})
    assert start["kind"] == "state" and not start["can_undo"]
    moved = session.handle({"op": "drag", "joint": "F", "x": -58.0, "y": -46.0, "final": True})
    assert moved["kind"] == "state" and moved["can_undo"]
    table = tomllib.loads(moved["text"])["linkage"]
    joints, checks = table["joints"], table["lengths"]
    for key in ("E-F", "D-F", "F-G"):                       # every check naming F: the new distance
        a, b = key.split("-")
        assert checks[key] == pytest.approx(math.dist(joints[a], joints[b]), rel=1e-15)
    assert checks["A-C"] == 50.0                            # the others as they were
    assert moved["scene"]["joints"]["F"] == pytest.approx([-58.0, -46.0], abs=1e-9)
    back = session.handle({"op": "undo"})
    assert back["text"] == (folder / "jansen.toml").read_text(encoding="utf-8")
    assert session.handle({"op": "redo"})["text"] == moved["text"]


def test_without_a_template_a_tab_opens_one_of_the_folder(tmp_path):
    folder = _folder(tmp_path, "rdrd", "jansen")
    with designer(folder) as url, _tab(url) as (ws, state, listing):
        assert state is None and listing["files"] == ["jansen.toml", "rdrd.toml"]
        opened = _ask(ws, {"op": "open", "path": "jansen.toml"})
        assert opened["kind"] == "state" and opened["program"] == "linkgen" and opened["scene"]["joints"]["G"]


def test_a_frame_past_the_websockets_limit_closes_that_tab_only(tmp_path):
    from websockets.exceptions import ConnectionClosed

    folder = _folder(tmp_path, "rdrd")
    before = _snapshot(folder)
    with designer(folder, "rdrd.toml") as url:
        with _tab(url) as (ws, _, _):
            ws.send("x" * (2 << 20))
            with pytest.raises(ConnectionClosed) as closed:
                ws.recv(timeout=60)
            assert closed.value.rcvd is not None and closed.value.rcvd.code == 1009     # "message too big"
        with _tab(url) as (ws, state, _):                                          # the server goes on
            assert state["file"] == "rdrd.toml"
    assert _snapshot(folder) == before


def test_a_file_a_template_reads_must_lie_in_the_folder_too(tmp_path):
    from camgen.designer.session import Session

    for name in ("table-law.toml", "table-law.csv", "speeds.toml"):
        shutil.copy(ROOT / "templates" / name, tmp_path / name)
    (tmp_path.parent / "law-outside.csv").write_text("0, 0\n1, 1\n", encoding="utf-8")
    session = Session(tmp_path.resolve())
    opened = session.handle({"op": "open", "path": "table-law.toml"})
    assert opened["kind"] == "state"
    refused = session.handle({"op": "set", "path": "motion[0].file", "text": "../law-outside.csv"})
    assert refused["field"] == "motion[0].file" and "lies outside the folder" in refused["message"]
    assert session.handle({"op": "undo"})["kind"] == "error"              # the refusal was no step
    family = Session(tmp_path.resolve()).handle({"op": "open", "path": "speeds.toml"})
    assert family["field"] == "base" and family["message"].startswith("error: base: the designer edits one design")


def test_an_answer_past_its_time_limit_changes_nothing(tmp_path):
    import asyncio

    from camgen.designer.app import answer
    from camgen.designer.session import Session

    folder = _folder(tmp_path, "jansen")
    session = Session(folder.resolve())
    late = asyncio.run(answer(session, json.dumps({"op": "open", "path": "jansen.toml"}), seconds=1e-4))
    assert late["kind"] == "error" and "took longer than 0.0001 s" in late["message"]
    with session.lock:                                   # the abandoned answer has finished, changing nothing
        assert session.texts == [] and session.at == -1 and session.design is None
    opened = asyncio.run(answer(session, json.dumps({"op": "open", "path": "jansen.toml"})))
    assert opened["kind"] == "state"


def test_the_bench_times_a_drag_step_of_jansens_leg(tmp_path):
    from camgen.designer.bench import STEPS, drag_row

    import multiprocessing
    import re

    for busy, during in ((False, ""), (True, ", a synthesis running in another tab")):
        row = drag_row(tmp_path / f"designer-{busy}", busy=busy)
        assert re.fullmatch(rf"designer: one drag step of Jansen's leg \(median of {STEPS}{during}; max "
                            r"\d+\.\d ms\)", row["what"]), row["what"]
        assert row["seconds"] > 0 and row["cams_per_second"] is None      # a time measured, none asserted
        assert not [p for p in multiprocessing.active_children() if p.name == "camgen-synthesis"]
