"""linkgen: planar linkages, their kinematics up to the dead centres, and their parts.

Importable objects (loaded on first use)::

    import linkgen
    fb = linkgen.FourBar(ground=180, crank=80, coupler=200, rocker=150)
    fb.grashof.inversion                      # 'crank-rocker'
    fb.positions([0.5], "open").theta4        # rocker angle, rad

    spec = linkgen.LinkageSpec.from_toml("templates/crank-rocker.toml").with_changes({"linkage.crank": 60})
    design = linkgen.design(spec, angle=30, parts=True)     # kinematics, report, parts; no I/O
    written = linkgen.write(design, "out/crank-rocker")      # report, figures, sheet, assembly, meshes

Its errors are camgen's (:mod:`camgen.core.errors`): ``linkgen.SpecError is camgen.SpecError``. ``load_spec``,
``design_linkage`` and ``write_linkage`` are the names of an earlier release, kept for one more.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from camgen.core.exports import lazy_exports

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
    "load": "linkgen.api", "design": "linkgen.api", "write": "linkgen.api", "Written": "camgen.core.bundle",
    "CamgenError": "camgen.core.errors", "SpecError": "camgen.core.errors", "DesignError": "camgen.core.errors",
    "SolverError": "camgen.core.errors", "ExportError": "camgen.core.errors",
}

__all__ = list(_EXPORTS)

if TYPE_CHECKING:      # what an editor and mypy see: the same names, imported (at run time each loads on first use)
    from linkgen.kinematics.fourbar import FourBar as FourBar
    from linkgen.kinematics.grashof import classify as classify, classify_chain as classify_chain
    from linkgen.kinematics.slidercrank import SliderCrank as SliderCrank, ScotchYoke as ScotchYoke
    from linkgen.kinematics.quickreturn import CrankShaper as CrankShaper, Whitworth as Whitworth
    from linkgen.kinematics.straightline import straight_line as straight_line
    from linkgen.mechanisms import Mechanism as Mechanism, MECHANISMS as MECHANISMS
    from linkgen.spec import LinkageSpec as LinkageSpec, load_spec as load_spec, validate_spec as validate_spec
    from linkgen.linkage_design import (
        LinkageDesign as LinkageDesign, design_linkage as design_linkage, analyze as analyze)
    from linkgen.outputs import linkage_bundle as linkage_bundle, write_linkage as write_linkage
    from linkgen.kinematics.linkage import Linkage as Linkage
    from linkgen.synthesis import load_task as load_task, synthesize as synthesize, write_synthesis as write_synthesis
    from linkgen.api import load as load, design as design, write as write
    from camgen.core.bundle import Written as Written
    from camgen.core.errors import (
        CamgenError as CamgenError, SpecError as SpecError, DesignError as DesignError, SolverError as SolverError,
        ExportError as ExportError)


if not TYPE_CHECKING:       # mypy reads the imports above, and flags a name neither gives
    __getattr__, __dir__ = lazy_exports("linkgen", _EXPORTS, __all__)
