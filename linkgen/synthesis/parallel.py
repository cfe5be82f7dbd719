"""Independent pieces of work run in this process, on local processes (``jobs``) or on a Dask cluster.

Each piece carries its own seed, so the results are the same, in the same order, wherever they run.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from typing import Any

from camgen.core.family import _client


def where(jobs: int, scheduler: str | None) -> str:
    """Where :func:`run_all` runs, in words."""
    if scheduler is not None:
        return f"the Dask cluster at {scheduler}"
    return "this process" if jobs <= 1 else f"{jobs} local processes"


def run_all(func: Callable[[Any], Any], items: Sequence[Any], jobs: int = 1, scheduler: str | None = None) -> list:
    """``[func(item) for item in items]``, on ``jobs`` local processes or the Dask cluster at ``scheduler``
    (``func`` and the items must pickle); results in the items' order."""
    if scheduler is not None:
        client = _client(scheduler)
        with client:
            return client.gather(client.map(func, list(items), pure=False))
    if jobs > 1 and len(items) > 1:
        with ProcessPoolExecutor(max_workers=min(jobs, len(items))) as pool:
            return list(pool.map(func, items))
    return [func(item) for item in items]
