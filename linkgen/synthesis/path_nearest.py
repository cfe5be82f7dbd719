"""The nearest candidates of a path task no linkage meets: those that break the binding requirement least.

Where no design of any search keeps every hard constraint (:mod:`linkgen.synthesis.path`), each
search's final population still ranks its designs by how far they break them (BIG (1 +
violation)): the few that break them least are kept (``closest``). Here they become candidates:
each is made a linkage at its crank angles (pivot and coupler point by least squares, as the
search does), left out if it has a branch, order or Grashof defect or does not fit a template, and
given in its row the requirement that binds (the hard one the best of them falls shortest of) and
by how much, in the task's units: degrees for ``min_transmission``, mm for
the ground region, the coupler range, the crank's Grashof margin and the link ratio, mm^2 (of the
squared reach) for ``link_range``; and every requirement it breaks (``violations``). Those that break
only the binding one are offered where there are any. They are ranked by that shortfall, least
first, and a ``bound``
line (``note:`` on the command line) says so. They are not polished: a polish keeps the constraints,
and none can be kept.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from linkgen.synthesis.candidates import Candidate
from linkgen.synthesis.path import _ASKED, Problem, _candidate, angles, project, shortfalls

#: the hard requirements (the search ranks a design breaking one behind every other by how far it does; the
#: others, a penalty, are left where the search left them, and are in the row's ``violations``)
HARD = ("task.link_range", "task.crank", "task.link_ratio", "task.min_transmission")
#: each field's shortfall (dimensionless in the search) in the task's units: factor (a power of the scale) and unit
UNITS = {"task.link_range": (2, "mm^2"), "task.crank": (1, "mm"), "task.link_ratio": (1, "mm"),
         "task.ground_region": (1, "mm"), "task.coupler_range": (1, "mm")}


def violations(base: np.ndarray, th: np.ndarray, p: Problem, task: Any, worst_deg: float) -> dict[str, float]:
    """How far a design (``base`` (9,) at crank angles ``th`` (n,), worst transmission ``worst_deg``) breaks each
    requirement it breaks, in the task's units (see the module)."""
    out = {}
    for field, amount in shortfalls(base, th, p).items():
        if amount <= 0:
            continue
        if field == "task.min_transmission":
            out[field] = max(0.0, task.min_transmission - worst_deg)
        elif field in UNITS:
            out[field] = amount * p.scale ** UNITS[field][0]
        else:
            out[field] = math.inf
    return out


def unit(field: str) -> str:
    """The unit a field's shortfall is given in."""
    return "degrees" if field == "task.min_transmission" else UNITS.get(field, (0, ""))[1]


def nearest_candidates(task: Any, runs: list[dict[str, Any]], p: Problem, tried: int
                       ) -> tuple[list[Candidate], list[str]]:
    """The nearest candidates (see the module) from the searches' ``runs`` and the line that names the binding
    requirement; no candidates (and no line) where each of them has a defect."""
    _, short = min((r["nearest"] for r in runs), key=lambda n: n[0])
    hard = {k: v for k, v in short.items() if k in HARD and math.isfinite(v)}
    if not any(hard.values()):
        return [], []
    field = max(hard, key=lambda k: hard[k])
    out = []
    for run in runs:
        for x in run["closest"]:
            v = np.array(x, dtype=float)[:, None]
            th = angles(v, p)
            base = project(v, th, p)[:, 0]
            if not np.all(np.isfinite(base)):
                continue
            c = _candidate(base.tolist(), 1.0 if v[5, 0] >= 0 else -1.0, th[0].tolist(), p, task.crank)
            if c is None:
                continue
            broken = violations(base, th[0], p, task, c.row["transmission_worst_deg"])
            if field not in broken or not math.isfinite(broken[field]):
                continue
            row = {**c.row, "bound_by": field, "violation": broken[field], "violation_unit": unit(field),
                   "violations": broken}
            out.append(Candidate(c.linkage, row, broken[field], c.signature, c.sketch))
    if not out:
        return [], []
    clear = [c for c in out if set(c.row["violations"]) == {field}]
    out = clear or out                      # those that break the binding requirement alone, where there are
    least = min(c.score for c in out)
    asked, hint = _ASKED[field]
    return out, [f"{field}: no linkage found that {asked.format(mu=task.min_transmission)} ({tried} designs "
                 f"tried); the nearest are offered, ranked by how far they break it (the least by {least:.4g} "
                 f"{unit(field)}; each row's violation says): {hint}"]
