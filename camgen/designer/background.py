"""A tab's work that outlasts one answer: its synthesis, one at a time, in a process of its own
(:mod:`camgen.designer.child`), its messages sent on the server's event loop as they come; stopped, and its process
waited for (else ended), when the tab cancels it or goes away. No server library here: ``send`` is the tab's
websocket."""
from __future__ import annotations

import asyncio
import json
from collections.abc import Awaitable, Callable
from typing import Any

from camgen.core.errors import CamgenError, SpecError
from camgen.designer.child import ChildJob
from camgen.designer.session import Session
from camgen.designer.synthesis import task_of

#: the operations a tab's background answers (the rest go to its session)
OPS = ("synthesize", "cancel")
#: the longest a job is waited for once told to stop (s): a search stops within one generation, and a child that
#: does not is ended within :data:`camgen.designer.child.STOP_SECONDS` and a kill's wait
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
    for once its answer is sent, :meth:`close` when the tab goes (the job stopped, its process ended).

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
        self.job: ChildJob | None = None
        self.pending: ChildJob | None = None
        self.forwarder = asyncio.create_task(self._forward())

    def running(self) -> bool:
        return self.job is not None and self.job.running()

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
        self.pending = ChildJob(message, self._emit)
        return {"kind": "synthesis-started", "name": spec.name, "task": spec.task.kind}

    def launch(self) -> None:
        """Start the job :meth:`answer` made (after its answer went out, so that the tab hears of it first)."""
        if self.pending is None:
            return
        self.job, self.pending = self.pending, None
        self.job.start()

    def _emit(self, message: dict[str, Any]) -> None:
        """From the job's reader thread: the candidates to the session, the message to the tab's queue."""
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
        """Stop the job (within one generation, else its process ended) and wait for it; stop forwarding."""
        job = self.job
        if job is not None:
            job.cancel()
        self.pending = None
        try:
            if job is not None:
                await asyncio.to_thread(job.join, JOIN_SECONDS)
        finally:
            self.forwarder.cancel()
