"""``synthesize``: a validated task to its ranked candidates, each re-analysed as the template written. No I/O."""
from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from camgen.core.errors import CamgenError, SpecError
from linkgen.synthesis import (burmester_motion, crank_rocker, fourier_path, function, motion, path, sixbar,
                               slider_crank, stephenson2)
from linkgen.synthesis.candidates import Candidate, Offered, offer, ranked
from linkgen.synthesis.parallel import where
from linkgen.synthesis.progress import Cancelled, Progress, ProgressHook
from linkgen.synthesis.task import SynthesisSpec

#: the analytic methods by task kind (path generation, a search, is called with the jobs and scheduler)
METHODS: dict[str, Callable[[Any], tuple[list[Candidate], dict[str, Any]]]] = {
    "crank-rocker": crank_rocker.solve, "slider-crank": slider_crank.solve, "function": function.solve,
    "motion": motion.solve, "burmester": burmester_motion.solve}
#: how close (relative to the largest) two candidates' numbers may be before the worse is left out as a copy: a
#: search's polished designs are copies within 1e-3; an analytic family's neighbours are offered 10 % apart
COPIES = {"path": 1e-3, "motion": 0.05, "burmester": 0.05, "crank-rocker": 0.1, "slider-crank": 0.1}
LENGTH_KEYS = ("ground", "crank", "coupler", "rocker", "rod")
#: the share of a path search's progress its generations take (the candidates' ranking and writing the rest)
SEARCH_SHARE = 0.99

#: the task's field that sets where and how big its linkages are: a candidate whose template is refused is blamed on
#: it (the methods offer only what a template holds; this names the task, not the template, if one slips through)
SCALE_FIELDS = {"path": "task.points", "motion": "task.positions", "crank-rocker": "task.rocker",
                "slider-crank": "task.stroke", "function": "task.ground", "burmester": "task.positions"}


@dataclass(frozen=True)
class Synthesis:
    """A task's outcome: the spec, the candidates offered (best first) and how they were found."""

    spec: SynthesisSpec
    candidates: tuple[Offered, ...]
    search: dict[str, Any]

    def summary(self) -> dict[str, Any]:
        """What ``summary.json`` holds: the task, how the search went and one row a candidate, best first."""
        task = self.spec.task
        return {"name": self.spec.name, "kind": task.kind, "task": task.model_dump(mode="json"),
                "search": self.search, "candidates": [c.row for c in self.candidates]}


def _offered(spec: SynthesisSpec, found: list[Candidate]) -> tuple[Offered, ...]:
    """The best of ``found`` as written: ranked, copies left out, each with its template and report."""
    task = spec.task
    best = ranked(found, getattr(task, "candidates", 1), COPIES.get(task.kind, 0.1))
    parts = None if spec.parts is None else spec.parts.model_dump(mode="json", exclude_none=True)
    try:
        return offer(spec.name, best, parts, lambda c: [c.row[k] for k in LENGTH_KEYS if k in c.row]
                     + list(c.row.get("link_lengths", {}).values()))
    except CamgenError as exc:
        field = SCALE_FIELDS[task.kind]
        raise SpecError(f"a linkage found cannot be written as a template ({exc}): change {field[5:]}",
                        field) from None


class _Follow:
    """The ``progress`` hook as the path search's report: the candidates offered anew only when more are found,
    :class:`Cancelled` raised (with the best so far) when the hook returns False."""

    def __init__(self, spec: SynthesisSpec, hook: ProgressHook) -> None:
        self.spec, self.hook, self.count = spec, hook, 0
        self.best: tuple[Offered, ...] = ()

    def search(self, fraction: float, stage: str, found: list[Candidate]) -> None:
        """A search's report: its fraction as SEARCH_SHARE of the whole (the ranking and writing follow)."""
        self(SEARCH_SHARE * fraction, stage, found)

    def __call__(self, fraction: float, stage: str, found: list[Candidate]) -> None:
        if len(found) != self.count:
            self.count, self.best = len(found), _offered(self.spec, found) if found else ()
        if not self.hook(Progress(fraction, stage, self.best)):
            raise Cancelled(self.best)


def synthesize(spec: SynthesisSpec, jobs: int = 1, scheduler: str | None = None,
               progress: ProgressHook | None = None) -> Synthesis:
    """The candidates of a validated synthesis spec, best first.

    Parameters
    ----------
    spec : SynthesisSpec
        A validated task (:func:`linkgen.synthesis.task.load_task`).
    jobs : int
        Local processes a path search runs on.
    scheduler : str, optional
        The address of a Dask scheduler (``tcp://host:8786``) a path search runs on instead; the analytic methods
        (crank-rocker, slider-crank, function and motion generation) always run here.
    progress : callable, optional
        Called with a :class:`~linkgen.synthesis.progress.Progress` (the fraction done, the stage, the best
        candidates so far) as the synthesis goes: after each generation of a four-bar path search run here
        (``jobs`` 1, no scheduler), else between stages (before the method, after it, once its candidates are
        offered). It returns True to go on, False to stop; it changes none of the results.

    Returns
    -------
    Synthesis
        The candidates, each checked for branch, order and Grashof defects, with its template and report;
        :func:`linkgen.synthesis.outputs.write_synthesis` writes them.

    Raises
    ------
    Cancelled
        ``progress`` returned False: within one generation of a search run here; its ``best`` holds the
        candidates found before.
    """
    task = spec.task
    clock = time.perf_counter()
    follow = None if progress is None else _Follow(spec, progress)
    if follow is not None:
        follow(0.0, f"{task.kind} synthesis started", [])
    if task.kind == "path":
        if getattr(task, "linkage", "four-bar") == "stephenson2":
            found, info = stephenson2.solve(task, jobs, scheduler)
        elif getattr(task, "linkage", "four-bar") != "four-bar":
            found, info = sixbar.solve(task, jobs, scheduler)
        elif getattr(task, "method", "evolution") == "fourier":
            found, info = fourier_path.solve(task)
            if jobs > 1 or scheduler:
                info["ran_on"] += " (the Fourier method runs here: --jobs and --scheduler serve the evolution)"
        else:
            found, info = path.solve(task, jobs, scheduler, None if follow is None else follow.search)
    else:
        found, info = METHODS[task.kind](task)
        info["ran_on"] = "this process" + (" (an analytic method: --jobs and --scheduler serve path searches)"
                                           if jobs > 1 or scheduler else "")
    if follow is not None:
        follow(SEARCH_SHARE if task.kind == "path" else 0.5,
               f"{len(found)} linkages found; ranking and writing the best", found if follow.count else [])
    offered = _offered(spec, found)
    if progress is not None and not progress(Progress(1.0, f"{len(offered)} candidates offered", offered)):
        raise Cancelled(offered)
    info = {**info, "seconds": round(time.perf_counter() - clock, 3), "ran_on": info.get("ran_on",
                                                                                        where(jobs, scheduler)),
            "bound": info.get("bound", [])}
    return Synthesis(spec, offered, info)

