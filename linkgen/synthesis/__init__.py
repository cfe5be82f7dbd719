"""Synthesis: from the motion a user needs to ranked linkages that make it (``linkgen synthesize``).

The template's ``[task]`` states the requirement (:mod:`linkgen.synthesis.task`); each kind has its
method: ``crank-rocker`` and ``slider-crank`` (the classical construction over its free choice),
``function`` (Freudenstein at Chebyshev points), ``motion`` (the dyad form for two or three
positions) and ``path`` (differential evolution over the whole population at once, then a
polish). Every candidate is written as a linkgen template and re-analysed as written::

    from linkgen import synthesis
    spec = synthesis.load_task("templates/synth-line6.toml")
    result = synthesis.synthesize(spec, jobs=2)          # candidates, best first; no I/O
    result.candidates[0].row["error_mm2"]
    synthesis.write_synthesis(result, "out/line6")       # templates, reports, figures, summary
"""
from __future__ import annotations

import importlib
from typing import Any

_EXPORTS = {"load_task": "linkgen.synthesis.task", "validate_task": "linkgen.synthesis.task",
            "SynthesisSpec": "linkgen.synthesis.task", "synthesize": "linkgen.synthesis.run",
            "Synthesis": "linkgen.synthesis.run", "write_synthesis": "linkgen.synthesis.outputs"}

__all__ = list(_EXPORTS)


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'linkgen.synthesis' has no attribute {name!r}")
