"""The designer's web app (Starlette): the page at ``/`` and one websocket per tab at ``/ws``, each with its own
:class:`~camgen.designer.session.Session`; every message bounded in size and in the time its answer may take.

Starlette is imported here only: ``camgen serve`` needs the ``serve`` extra, nothing else does."""
from __future__ import annotations

import asyncio
import json
import threading
from importlib import resources
from pathlib import Path
from typing import Any

from camgen.designer.background import Background, background_op
from camgen.designer.session import Abandoned, Session

#: the largest message a tab may send (bytes of text); the server's websocket refuses a frame past 4 times it
MAX_MESSAGE = 256 * 1024
#: the longest an answer may take (s); past it the tab is told so and the session is left as it was
MAX_SECONDS = 60.0


def page_html() -> str:
    """The designer's page: one HTML file with its script and styles (no network beyond its own websocket)."""
    return resources.files("camgen.designer").joinpath("static/designer.html").read_text(encoding="utf-8")


def _too_big(size: int) -> dict[str, Any]:
    return {"kind": "error", "field": "message", "fields": [],
            "message": f"error: message: at most {MAX_MESSAGE} bytes (got {size})"}


async def answer(session: Session, text: str, seconds: float = MAX_SECONDS) -> dict[str, Any]:
    """The answer to one message ``text`` of a tab, computed in a worker thread so that the server goes on
    serving other tabs; past ``seconds`` an error, and the session left unchanged."""
    if len(text.encode("utf-8")) > MAX_MESSAGE:
        return _too_big(len(text.encode("utf-8")))
    try:
        message = json.loads(text)
    except ValueError:
        return {"kind": "error", "field": "message", "fields": [], "message": "error: message: not JSON"}
    abandoned = threading.Event()
    try:
        return await asyncio.wait_for(asyncio.to_thread(session.handle, message, abandoned), seconds)
    except (TimeoutError, Abandoned):
        abandoned.set()
        return {"kind": "error", "field": None, "fields": [],
                "message": f"error: the answer took longer than {seconds:g} s; nothing was changed"}
    except Exception as exc:          # a fault of ours: one line to the tab, which goes on (the session unchanged)
        return {"kind": "error", "field": None, "fields": [],
                "message": f"error: the designer failed on this message ({type(exc).__name__}: {exc}); "
                           "nothing was changed"}


def make_app(root: Path, template: str | None = None, port: int | None = None) -> Any:
    """The Starlette app serving the folder ``root`` (each tab opens ``template`` first, a path inside it). Only
    requests addressed to 127.0.0.1 or localhost (``port`` the one served) are answered: a page of another site
    cannot drive the designer through the browser."""
    from starlette.applications import Starlette
    from starlette.responses import HTMLResponse, PlainTextResponse
    from starlette.routing import Route, WebSocketRoute
    from starlette.websockets import WebSocket, WebSocketDisconnect

    hosts = {"127.0.0.1", "localhost"} if port is None else {f"127.0.0.1:{port}", f"localhost:{port}"}
    origins = {f"http://{h}" for h in hosts}

    def local(headers: Any) -> bool:
        return headers.get("host", "") in hosts or port is None

    async def index(request: Any) -> Any:
        if not local(request.headers):
            return PlainTextResponse("the designer answers on 127.0.0.1 only", status_code=403)
        return HTMLResponse(page_html(), headers={"Cache-Control": "no-store",
                                                  "Content-Security-Policy": "default-src 'self' 'unsafe-inline'; "
                                                  "connect-src 'self' ws: ; frame-src 'self' data: blob:; "
                                                  "img-src 'self' data: blob:"})

    async def socket(ws: WebSocket) -> None:
        origin = ws.headers.get("origin")
        if not local(ws.headers) or (origin is not None and port is not None and origin not in origins):
            await ws.close(code=1008)
            return
        await ws.accept()
        session = Session(root)                          # this tab's own design: nothing shared between tabs
        sending = asyncio.Lock()                         # answers and a synthesis' messages, one at a time

        async def send(reply: dict[str, Any]) -> None:
            async with sending:
                await ws.send_json(reply)

        background = Background(session, send)           # its synthesis: stopped when the tab goes
        try:
            greetings = ([json.dumps({"op": "open", "path": template})] if template is not None else []) + [
                json.dumps({"op": "list"})]
            for text in greetings:                       # what the tab is shown unasked: the template, the folder
                await send({**await answer(session, text), "greeting": True})
            while True:
                event = await ws.receive()
                if event["type"] == "websocket.disconnect":
                    return
                received = event.get("text")
                if received is None:
                    data = event.get("bytes") or b""
                    reply = _too_big(len(data)) if len(data) > MAX_MESSAGE else {
                        "kind": "error", "field": "message", "fields": [], "message": "error: message: send text"}
                elif (asked := background_op(received, MAX_MESSAGE)) is not None:
                    reply = await background.answer(asked)
                else:
                    reply = await answer(session, received)
                await send(reply)
                background.launch()
        except WebSocketDisconnect:
            return
        finally:
            await background.close()

    return Starlette(routes=[Route("/", index), WebSocketRoute("/ws", socket)])
