"""linkgen: planar linkages, their kinematics up to the dead centres, and their parts.

Importable objects (loaded on first use)::

    import linkgen
    fb = linkgen.FourBar(ground=180, crank=80, coupler=200, rocker=150)
    fb.grashof.inversion                      # 'crank-rocker'
    fb.positions([0.5], "open").theta4        # rocker angle, rad
"""
from __future__ import annotations

import importlib
from typing import Any

_EXPORTS = {
    "FourBar": "linkgen.fourbar", "classify": "linkgen.grashof", "classify_chain": "linkgen.grashof",
    "SliderCrank": "linkgen.slidercrank", "ScotchYoke": "linkgen.slidercrank",
    "CrankShaper": "linkgen.quickreturn", "Whitworth": "linkgen.quickreturn",
    "straight_line": "linkgen.straightline",
    "load_linkage": "linkgen.spec", "validate_linkage": "linkgen.spec",
    "analyze": "linkgen.analyze", "build_parts": "linkgen.build", "write_analysis": "linkgen.outputs",
}

__all__ = list(_EXPORTS)


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'linkgen' has no attribute {name!r}")
