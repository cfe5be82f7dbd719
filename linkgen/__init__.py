"""linkgen: planar linkages, their kinematics up to the dead centres, and their parts.

Importable objects (loaded on first use)::

    import linkgen
    fb = linkgen.FourBar(ground=180, crank=80, coupler=200, rocker=150)
    fb.grashof.inversion                      # 'crank-rocker'
    fb.positions([0.5], "open").theta4        # rocker angle, rad

    spec = linkgen.load_spec("templates/crank-rocker.toml")
    design = linkgen.design_linkage(spec, angle=30, parts=True)   # kinematics, report, parts; no I/O
    linkgen.write_linkage(design, "out/crank-rocker")            # report, figures, sheet, assembly, meshes
"""
from __future__ import annotations

import importlib
from typing import Any

_EXPORTS = {
    "FourBar": "linkgen.kinematics.fourbar", "classify": "linkgen.kinematics.grashof",
    "classify_chain": "linkgen.kinematics.grashof",
    "SliderCrank": "linkgen.kinematics.slidercrank", "ScotchYoke": "linkgen.kinematics.slidercrank",
    "CrankShaper": "linkgen.kinematics.quickreturn", "Whitworth": "linkgen.kinematics.quickreturn",
    "straight_line": "linkgen.kinematics.straightline",
    "Mechanism": "linkgen.mechanisms", "MECHANISMS": "linkgen.mechanisms",
    "LinkageSpec": "linkgen.spec", "load_spec": "linkgen.spec", "validate_spec": "linkgen.spec",
    "LinkageDesign": "linkgen.linkage_design", "design_linkage": "linkgen.linkage_design",
    "analyze": "linkgen.linkage_design",
    "linkage_bundle": "linkgen.outputs", "write_linkage": "linkgen.outputs",
    "Linkage": "linkgen.kinematics.linkage", "load_task": "linkgen.synthesis", "synthesize": "linkgen.synthesis",
    "write_synthesis": "linkgen.synthesis",
}

__all__ = list(_EXPORTS)


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'linkgen' has no attribute {name!r}")
