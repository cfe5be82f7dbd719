"""``synthesize``: a validated task to its ranked candidates, each re-analysed as the template written. No I/O."""
from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from camgen.core.errors import CamgenError, SpecError
from linkgen.synthesis import burmester_motion, crank_rocker, fourier_path, function, motion, path, sixbar, slider_crank
from linkgen.synthesis.candidates import Candidate, Offered, offer, ranked
from linkgen.synthesis.parallel import where
from linkgen.synthesis.task import SynthesisSpec

#: the analytic methods by task kind (path generation, a search, is called with the jobs and scheduler)
METHODS: dict[str, Callable[[Any], tuple[list[Candidate], dict[str, Any]]]] = {
    "crank-rocker": crank_rocker.solve, "slider-crank": slider_crank.solve, "function": function.solve,
    "motion": motion.solve, "burmester": burmester_motion.solve}
#: how close (relative to the largest) two candidates' numbers may be before the worse is left out as a copy: a
#: search's polished designs are copies within 1e-3; an analytic family's neighbours are offered 10 % apart
COPIES = {"path": 1e-3, "motion": 0.05, "burmester": 0.05, "crank-rocker": 0.1, "slider-crank": 0.1}
LENGTH_KEYS = ("ground", "crank", "coupler", "rocker", "rod")

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


def synthesize(spec: SynthesisSpec, jobs: int = 1, scheduler: str | None = None) -> Synthesis:
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

    Returns
    -------
    Synthesis
        The candidates, each checked for branch, order and Grashof defects, with its template and report;
        :func:`linkgen.synthesis.outputs.write_synthesis` writes them.
    """
    task = spec.task
    clock = time.perf_counter()
    if task.kind == "path":
        if getattr(task, "linkage", "four-bar") != "four-bar":
            found, info = sixbar.solve(task, jobs, scheduler)
        elif getattr(task, "method", "evolution") == "fourier":
            found, info = fourier_path.solve(task)
            if jobs > 1 or scheduler:
                info["ran_on"] += " (the Fourier method runs here: --jobs and --scheduler serve the evolution)"
        else:
            found, info = path.solve(task, jobs, scheduler)
    else:
        found, info = METHODS[task.kind](task)
        info["ran_on"] = "this process" + (" (an analytic method: --jobs and --scheduler serve path searches)"
                                           if jobs > 1 or scheduler else "")
    best = ranked(found, getattr(task, "candidates", 1), COPIES.get(task.kind, 0.1))
    parts = None if spec.parts is None else spec.parts.model_dump(mode="json", exclude_none=True)
    try:
        offered = offer(spec.name, best, parts, lambda c: [c.row[k] for k in LENGTH_KEYS if k in c.row]
                        + list(c.row.get("link_lengths", {}).values()))
    except CamgenError as exc:
        field = SCALE_FIELDS[task.kind]
        raise SpecError(f"a linkage found cannot be written as a template ({exc}): change {field[5:]}",
                        field) from None
    info = {**info, "seconds": round(time.perf_counter() - clock, 3), "ran_on": info.get("ran_on",
                                                                                        where(jobs, scheduler)),
            "bound": info.get("bound", [])}
    return Synthesis(spec, offered, info)

