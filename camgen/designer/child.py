"""A tab's synthesis in a process of its own, so that it shares no interpreter lock with the server's answers.

The process is started with multiprocessing's ``spawn`` context: a fresh interpreter that inherits none of the
server's threads, locks or sockets (``fork`` of a process running an event loop and worker threads can copy a lock
held by another thread; ``forkserver`` would leave a server process of its own behind to clean up). Its start (an
interpreter and linkgen's imports, well under a second) is small beside a search's seconds. Only plain data
crosses: the ``synthesize`` message in (validated again in the child, as the server validated it), the tab's
messages out over a queue (:class:`~camgen.designer.synthesis.Job`'s, candidates as JSON-ready dicts).

It stops when told (a flag the child's progress hook polls: within one generation of a search), and where it does
not within :data:`STOP_SECONDS`, it is terminated (then killed). A child whose server has gone (its parent process
changed) stops at its next generation too; it ignores Ctrl-C, which the server's stopping handles. No server
library here."""
from __future__ import annotations

import math
import multiprocessing
import os
import queue
import signal
import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from camgen.core.errors import CamgenError, SpecError
from camgen.designer.synthesis import Job, task_of

#: the longest a told child is waited for before it is terminated (s): a search stops within one generation
STOP_SECONDS = 5.0
#: the longest a terminated child is waited for before it is killed (s)
KILL_SECONDS = 2.0
#: how often the reader looks whether the child still runs, or overran its stop (s)
POLL_SECONDS = 0.1
#: the messages that end a synthesis
LAST = ("synthesized", "synthesis-cancelled", "error")


@dataclass
class _Told:
    """The child's stop flag: set by the server (``event``), or the server gone (its process no longer the
    child's parent)."""

    event: Any
    parent: int

    def is_set(self) -> bool:
        return bool(self.event.is_set()) or os.getppid() != self.parent

    def set(self) -> None:
        self.event.set()


def child_main(message: Mapping[str, Any], messages: Any, stop: Any, parent: int) -> None:
    """The child process: validate the ``synthesize`` ``message``, run the synthesis (:meth:`Job.run`), each of
    its messages put on ``messages``; ``stop`` the server's flag, ``parent`` the server's process id."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        spec = task_of(message)
    except CamgenError as exc:
        where = exc.field if isinstance(exc, SpecError) else None
        messages.put({"kind": "error", "push": True, "synthesis": True, "field": where,
                      "fields": [where] if where else [], "message": f"error: {exc}"})
        return
    Job(spec, messages.put, stop=_Told(stop, parent)).run()


class ChildJob:
    """One synthesis of a tab, in a child process: :meth:`start` it, :meth:`cancel` it; its messages are handed to
    ``emit`` (from a reader thread of the server) in the order the child sent them, the last one of :data:`LAST`.

    Parameters
    ----------
    message : mapping
        The tab's ``synthesize`` message (``task``, ``name``), already validated by the server.
    emit : callable
        Called from the reader thread with each message for the tab.
    target : callable
        The child's work, called there as ``target(message, messages, stop, parent)``: :func:`child_main` (a
        module-level function, which ``spawn`` imports by name in the child).
    """

    def __init__(self, message: Mapping[str, Any], emit: Callable[[dict[str, Any]], None],
                 target: Callable[[Mapping[str, Any], Any, Any, int], None] = child_main) -> None:
        context = multiprocessing.get_context("spawn")     # see the module's text for why
        self.message, self.emit = dict(message), emit
        self.messages = context.Queue()
        self.stop = context.Event()
        self.process = context.Process(target=target, name="camgen-synthesis", daemon=True,
                                       args=(self.message, self.messages, self.stop, os.getpid()))
        self.reader = threading.Thread(target=self._read, name="camgen-synthesis-reader", daemon=True)
        #: the latest candidates sent, by name: the templates the session opens
        self.found: dict[str, str] = {}
        self._shown: list[dict[str, Any]] = []
        self._told = math.inf
        self._ended = self._done = False

    @property
    def pid(self) -> int | None:
        """The child's process id (None before :meth:`start`)."""
        return self.process.pid

    def start(self) -> None:
        self.process.start()
        self.reader.start()

    def cancel(self) -> None:
        """Tell the child to stop (it does within one generation; past :data:`STOP_SECONDS` it is terminated)."""
        self.stop.set()
        self._told = min(self._told, time.monotonic())

    def running(self) -> bool:
        """True from :meth:`start` until the child's last message is handed on (its process may take a moment
        more to end: :meth:`join` waits for that too)."""
        return self.reader.is_alive() and not self._done

    def join(self, seconds: float) -> None:
        """Wait (at most ``seconds``) for the child to end and its messages to be handed on."""
        self.reader.join(seconds)

    def _hand(self, message: dict[str, Any]) -> None:
        self._done = message.get("kind") in LAST
        if "candidates" in message:
            self._shown = message["candidates"]
            self.found = {c["name"]: c["text"] for c in self._shown}
        self.emit(message)

    def _read(self) -> None:
        """Hand on the child's messages until its last; end the child that overruns its stop or ends unheard."""
        try:
            while True:
                try:
                    message = self.messages.get(timeout=POLL_SECONDS)
                except queue.Empty:
                    if time.monotonic() - self._told > STOP_SECONDS:
                        self._end(0.0)
                        self._hand({"kind": "synthesis-cancelled", "push": True, "candidates": self._shown,
                                    "message": f"synthesis stopped (it did not stop within {STOP_SECONDS:g} s of "
                                               "being told, so its process was ended)"})
                        return
                    if not self.process.is_alive() and self.messages.empty():
                        self._hand({"kind": "error", "push": True, "synthesis": True, "field": None, "fields": [],
                                    "message": "error: the synthesis' process ended without an answer (exit code "
                                               f"{self.process.exitcode})"})
                        return
                    continue
                self._hand(message)
                if self._done:
                    return
        finally:
            self._end(STOP_SECONDS)

    def _end(self, seconds: float) -> None:
        """The child ended (waited for ``seconds``, else terminated, else killed) and its queue closed; once."""
        if self._ended or self.process.pid is None:
            return
        self._ended = True
        self.process.join(seconds)
        if self.process.is_alive():
            self.process.terminate()
            self.process.join(KILL_SECONDS)
        if self.process.is_alive():
            self.process.kill()
            self.process.join(KILL_SECONDS)
        self.messages.close()
        self.messages.cancel_join_thread()
