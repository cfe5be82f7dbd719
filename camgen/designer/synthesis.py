"""A tab's synthesis (``linkgen synthesize`` in the background): the task the page sends validated as the command
line validates a template's ``[task]`` (its budget bounded as there), run in a process of its own
(:mod:`camgen.designer.child`) by :func:`linkgen.synthesis.run.synthesize` with its progress hook, the candidates
sent as they come, stopped within one generation when the tab cancels or goes away. No server library here:
messages out through ``emit``."""
from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol

from camgen.core.errors import CamgenError, SpecError
from camgen.core.toml_text import dumps

#: the least time between two progress messages to the tab (s): a search's generations take milliseconds
EVERY_SECONDS = 0.1
#: the candidate templates' base name where the page gives none
NAME = "synthesis"
#: every how many of a candidate's figure's path points the tab draws (its coupler curve)
CURVE_STEP = 4
#: the summary numbers shown of each candidate, where its row has them
SHOWN = ("error_mm2", "rank_score", "transmission_worst_deg", "ground", "crank", "coupler", "rocker", "rod")


def task_of(message: Mapping[str, Any]) -> Any:
    """The validated :class:`~linkgen.synthesis.task.SynthesisSpec` of a ``synthesize`` message: ``task`` the
    ``[task]`` table (``kind``, ``points`` ...), ``name`` the candidates' base name; refused in one line naming the
    field, as ``linkgen synthesize`` refuses the template (a budget past its limits included)."""
    from linkgen.synthesis import validate_task

    task, name = message.get("task"), message.get("name", NAME)
    if not isinstance(task, dict):
        raise SpecError('give the task as a JSON object ({"kind": "path", "points": [[x, y], ...], ...})', "task")
    return validate_task({"name": name, "task": task})


def candidate_json(offered: Any) -> dict[str, Any]:
    """One candidate as the tab shows it: its name, its template's TOML (what ``linkgen synthesize`` writes, less
    the comment) and its summary numbers; NaN-free."""
    row = {k: offered.row[k] for k in SHOWN if isinstance(offered.row.get(k), (int, float))
           and math.isfinite(offered.row[k])}
    paths = offered.sketch.paths
    curve = paths[0][1][::CURVE_STEP].round(6).tolist() if paths and len(paths[0][1]) else []
    return {"name": offered.name, "text": dumps(offered.template), "row": row,
            "curve": [xy for xy in curve if all(math.isfinite(v) for v in xy)]}


class Flag(Protocol):
    """A stop flag: a :class:`threading.Event`, a multiprocessing one, or one that also reads other signs."""

    def is_set(self) -> bool: ...

    def set(self) -> None: ...


@dataclass
class Job:
    """One synthesis of a tab, run by :meth:`run` (in the child process of :mod:`camgen.designer.child`, or any
    thread); :meth:`cancel` (or ``stop`` set) stops it within one generation of a search.

    Parameters
    ----------
    spec : SynthesisSpec
        The validated task (:func:`task_of`).
    emit : callable
        Called (from the thread running the job) with each message for the tab: ``progress`` (``fraction`` 0 to 1,
        ``stage``, ``candidates`` so far), then one of ``synthesized`` (the candidates and how the search went),
        ``synthesis-cancelled`` (the candidates found before) or ``error`` (the command line's line).
    """

    spec: Any
    emit: Callable[[dict[str, Any]], None]
    stop: Flag = field(default_factory=threading.Event)
    #: the latest candidates sent, by name: the templates :meth:`~camgen.designer.session.Session` opens
    found: dict[str, str] = field(default_factory=dict)
    _sent: float = -math.inf
    _shown: tuple[str, ...] = ()

    def cancel(self) -> None:
        self.stop.set()

    def _progress(self, progress: Any) -> bool:
        if self.stop.is_set():
            return False
        names = tuple(c.name for c in progress.best) + tuple(str(c.row.get("error_mm2")) for c in progress.best)
        now = time.monotonic()
        if names != self._shown or now - self._sent >= EVERY_SECONDS or progress.fraction >= 1.0:
            self._sent, self._shown = now, names
            self.emit(self._candidates("progress", progress.best, fraction=progress.fraction,
                                       stage=progress.stage))
        return not self.stop.is_set()

    def _candidates(self, kind: str, best: Any, **more: Any) -> dict[str, Any]:
        shown = [candidate_json(c) for c in best]
        self.found = {c["name"]: c["text"] for c in shown}
        return {"kind": kind, "push": True, "candidates": shown, **more}

    def run(self) -> None:
        """Synthesize, sending the tab each message (never raising: a failure is one error line to the tab)."""
        from linkgen.synthesis import synthesize
        from linkgen.synthesis.progress import Cancelled

        try:
            result = synthesize(self.spec, progress=self._progress)
        except Cancelled as exc:
            self.emit(self._candidates("synthesis-cancelled", exc.best, message=str(exc)))
        except CamgenError as exc:
            where = exc.field if isinstance(exc, SpecError) else None
            self.emit({"kind": "error", "push": True, "synthesis": True, "field": where,
                       "fields": [where] if where else [], "message": f"error: {exc}"})
        except Exception as exc:     # a fault of ours: one line to the tab, which goes on
            self.emit({"kind": "error", "push": True, "synthesis": True, "field": None, "fields": [],
                       "message": f"error: the synthesis failed ({type(exc).__name__}: {exc})"})
        else:
            search = {k: v for k, v in result.search.items() if isinstance(v, (int, float, str))}
            self.emit(self._candidates("synthesized", result.candidates, search=search))
