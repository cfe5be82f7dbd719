"""camgen: disc and plate cams from motion requirements to files you can cut and print.

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

_EXPORTS = {
    # motion laws and programs
    "make_law": "camgen.laws", "from_conditions": "camgen.laws", "LAW_NAMES": "camgen.laws",
    "build_program": "camgen.program", "Program": "camgen.program", "Segment": "camgen.program",
    # followers
    "TranslatingRoller": "camgen.followers.translating_roller", "TranslatingFlat": "camgen.followers.translating_flat",
    "OscillatingRoller": "camgen.followers.oscillating_roller", "OscillatingFlat": "camgen.followers.oscillating_flat",
    "FOLLOWERS": "camgen.followers", "CAM_KINDS": "camgen.kinds",
    "PlateRoller": "camgen.followers.plate",
    # templates, cams, designs
    "load_spec": "camgen.spec", "validate_spec": "camgen.spec", "CamSpec": "camgen.spec",
    "build_cam": "camgen.cam", "Cam": "camgen.cam", "analyze": "camgen.analysis",
    "design_cam": "camgen.design", "CamDesign": "camgen.design", "size_cam": "camgen.sizing",
    "convergence": "camgen.convergence",
    # parts and exporters
    "Contour": "camgen.core.shapes", "Circle": "camgen.core.shapes", "Part": "camgen.core.parts",
    "Drawing": "camgen.core.parts", "Allowances": "camgen.core.parts",
    "write_dxf": "camgen.core.writers.dxf", "svg_document": "camgen.core.writers.svg",
    "extrude": "camgen.core.solids", "stl_bytes": "camgen.core.writers.stl",
    "threemf_bytes": "camgen.core.writers.threemf",
    "Bundle": "camgen.core.bundle", "write_bundle": "camgen.core.bundle", "cam_bundle": "camgen.outputs",
    "write_cam": "camgen.outputs",
    # families
    "read_family": "camgen.core.family", "members": "camgen.core.family", "run_family": "camgen.core.family",
    # errors
    "CamgenError": "camgen.core.errors", "SpecError": "camgen.core.errors", "DesignError": "camgen.core.errors",
    "SolverError": "camgen.core.errors", "ExportError": "camgen.core.errors",
}

__all__ = ["__version__", *_EXPORTS]


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'camgen' has no attribute {name!r}")
