"""camgen: disc, plate and grooved cams from motion requirements, and Geneva drives, to files you can cut and print.

The objects a script composes are importable from here; heavy modules load only when
a name is first used (``import camgen`` stays fast)::

    import camgen
    spec = camgen.load_spec("templates/rdrd.toml", ["motion.0.lift=25", "motion.2.lift=25"])
    design = camgen.design_cam(spec)          # checks and geometry, no I/O
    camgen.write_cam(design, "out/rdrd-25")    # DXF, SVG, STL, 3MF, JSON, plots
"""
from __future__ import annotations

import importlib
from typing import Any

from camgen.core import VERSION as __version__

#: the public names, by the module that holds them
_MODULES = {
    "camgen.laws": ("make_law", "from_conditions", "LAW_NAMES"),
    "camgen.program": ("build_program", "Program", "Segment"),
    "camgen.followers": ("FOLLOWERS",),
    "camgen.followers.translating_roller": ("TranslatingRoller",),
    "camgen.followers.translating_flat": ("TranslatingFlat",),
    "camgen.followers.oscillating_roller": ("OscillatingRoller",),
    "camgen.followers.oscillating_flat": ("OscillatingFlat",),
    "camgen.followers.plate": ("PlateRoller",),
    "camgen.kinds": ("KINDS",),
    "camgen.spec": ("load_spec", "validate_spec", "CamSpec"),
    "camgen.cam": ("Cam",),
    "camgen.analysis": ("analyze",),
    "camgen.profile": ("design_cam", "Profile"),
    "camgen.flat": ("build_cam", "CamDesign"),
    "camgen.sizing": ("size_cam",),
    "camgen.convergence_study": ("convergence",),
    "camgen.grooved.design": ("design_grooved", "GroovedDesign"),
    "camgen.geneva.kinematics": ("GenevaLaw",),
    "camgen.geneva.spec": ("GenevaSpec",),
    "camgen.geneva.design": ("design_geneva", "GenevaDesign"),
    "camgen.outputs": ("cam_bundle",),
    "camgen.api": ("write_cam",),
    "camgen.core.shapes": ("Contour", "Circle"),
    "camgen.core.parts": ("Part", "Drawing", "Allowances"),
    "camgen.core.writers.dxf": ("write_dxf",),
    "camgen.core.writers.svg": ("svg_document",),
    "camgen.core.solids": ("extrude",),
    "camgen.core.writers.stl": ("stl_bytes",),
    "camgen.core.writers.threemf": ("threemf_bytes",),
    "camgen.core.bundle": ("Bundle", "write_bundle"),
    "camgen.core.family": ("read_family", "members", "run_family"),
    "camgen.core.errors": ("CamgenError", "SpecError", "DesignError", "SolverError", "ExportError"),
}
_EXPORTS = {name: module for module, names in _MODULES.items() for name in names}

__all__ = ["__version__", *_EXPORTS]


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'camgen' has no attribute {name!r}")
