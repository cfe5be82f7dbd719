"""Timing for the benches: medians of repeated runs in this process (never asserted by a test)."""
from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from typing import Any


def timed(func: Callable[[], Any], repeats: int) -> tuple[Any, float]:
    """``func()``'s result and the median of ``repeats`` wall times (seconds)."""
    times, result = [], None
    for _ in range(max(1, repeats)):
        start = time.perf_counter()
        result = func()
        times.append(time.perf_counter() - start)
    return result, statistics.median(times)
