"""A tab's work that outlasts one answer: its synthesis, one at a time, on a thread of its own, its messages sent
on the server's event loop as they come; stopped, and its thread waited for, when the tab cancels it or goes away.
No server library here: ``send`` is the tab's websocket."""
from __future__ import annotations

import asyncio
import json
import threading
from collections.abc import Awaitable, Callable
from typing import Any

from camgen.core.errors import CamgenError, SpecError
from camgen.designer.session import Session
from camgen.designer.synthesis import Job, task_of

#: the operations a tab's background answers (the rest go to its session)
OPS = ("synthesize", "cancel")
#: the longest a job's thread is waited for once told to stop (s): a search stops within one generation
JOIN_SECONDS = 30.0


def background_op(text: str, limit: int) -> dict[str, Any] | None:
    """The message ``text`` where it is one of :data:`OPS` (a JSON object of at most ``limit`` bytes), else None
    (the session answers it, refusals included)."""
    if len(text.encode("utf-8")) > limit:
        return None
    try:
        message = json.loads(text)
    except ValueError:
        return None
    return message if isinstance(message, dict) and message.get("op") in OPS else None


def _error(exc: CamgenError) -> dict[str, Any]:
    where = exc.field if isinstance(exc, SpecError) else None
    return {"kind": "error", "synthesis": True, "field": where, "fields": [where] if where else [],
            "message": f"error: {exc}"}


class Background:
    """One tab's synthesis: :meth:`answer` a ``synthesize`` or ``cancel`` message, :meth:`launch` the job asked
    for once its answer is sent, :meth:`close` when the tab goes (the job stopped, its thread joined).

    Parameters
    ----------
    session : Session
        The tab's session: its ``candidates`` follow the job's, for the ``candidate`` operation to open.
    send : callable
        Sends one message to the tab (a coroutine function); called on the event loop only.
    """

    def __init__(self, session: Session, send: Callable[[dict[str, Any]], Awaitable[None]]) -> None:
        self.session, self.send = session, send
        self.loop = asyncio.get_running_loop()
        self.queue: asyncio.Queue[dict[str, Any]] = asyncio.Queue()
        self.job: Job | None = None
        self.thread: threading.Thread | None = None
        self.pending: Job | None = None
        self.forwarder = asyncio.create_task(self._forward())

    def running(self) -> bool:
        return self.thread is not None and self.thread.is_alive()

    async def answer(self, message: dict[str, Any]) -> dict[str, Any]:
        """The answer to a ``synthesize`` (the job made, not yet started) or ``cancel`` message."""
        if message["op"] == "cancel":
            if not self.running() or self.job is None:
                return _error(SpecError("no synthesis is running in this tab", "cancel"))
            self.job.cancel()
            return {"kind": "cancelling"}
        if self.running():
            return _error(SpecError("one synthesis at a time in a tab: cancel the one running first",
                                    "synthesize"))
        try:
            spec = await asyncio.to_thread(task_of, message)
        except CamgenError as exc:
            return _error(exc)
        self.pending = Job(spec, self._emit)
        return {"kind": "synthesis-started", "name": spec.name, "task": spec.task.kind}

    def launch(self) -> None:
        """Start the job :meth:`answer` made (after its answer went out, so that the tab hears of it first)."""
        if self.pending is None:
            return
        self.job, self.pending = self.pending, None
        self.thread = threading.Thread(target=self.job.run, name="camgen-synthesis", daemon=True)
        self.thread.start()

    def _emit(self, message: dict[str, Any]) -> None:
        """From the job's thread: the candidates to the session, the message to the tab's queue."""
        job = self.job
        if job is not None and "candidates" in message:
            self.session.candidates = job.found          # replaced whole: the session only reads it
        try:
            self.loop.call_soon_threadsafe(self.queue.put_nowait, message)
        except RuntimeError:                              # the loop has closed: nobody to tell, so stop
            if job is not None:
                job.cancel()

    async def _forward(self) -> None:
        """Send the job's messages in order; once the tab cannot be sent to, stop the job."""
        while True:
            message = await self.queue.get()
            try:
                await self.send(message)
            except Exception:                              # the tab has gone (its socket closed under us)
                if self.job is not None:
                    self.job.cancel()
                return

    async def close(self) -> None:
        """Stop the job (within one generation) and wait for its thread; stop forwarding."""
        if self.job is not None:
            self.job.cancel()
        self.pending = None
        thread = self.thread
        try:
            if thread is not None:
                await asyncio.to_thread(thread.join, JOIN_SECONDS)
        finally:
            self.forwarder.cancel()
