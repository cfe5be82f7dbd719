"""camgen: disc and plate cams from motion requirements to files you can cut and print.

The objects a script composes are importable from here; heavy modules load only when
a name is first used (``import camgen`` stays fast)::

    import camgen
    spec = camgen.load_template("templates/rdrd.toml", ["motion.0.lift=25", "motion.2.lift=25"])
    design = camgen.design_cam(spec)          # checks and geometry, no I/O
    camgen.write_cam(design, "out/rdrd-25")    # DXF, SVG, STL, 3MF, JSON, plots
"""
from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.1.0"

_EXPORTS = {
    # motion laws and programs
    "make_law": "camgen.laws", "from_conditions": "camgen.laws", "LAW_NAMES": "camgen.laws",
    "build_program": "camgen.program", "Program": "camgen.program", "Segment": "camgen.program",
    # followers
    "TranslatingRoller": "camgen.followers.translating", "TranslatingFlat": "camgen.followers.translating",
    "OscillatingRoller": "camgen.followers.oscillating", "OscillatingFlat": "camgen.followers.oscillating",
    "PlateRoller": "camgen.followers.plate",
    # templates, cams, designs
    "load_template": "camgen.spec", "validate_template": "camgen.spec", "CamTemplate": "camgen.spec",
    "build_cam": "camgen.cam", "Cam": "camgen.cam", "analyse": "camgen.analysis",
    "design_cam": "camgen.design", "CamDesign": "camgen.design", "size_cam": "camgen.sizing",
    "convergence": "camgen.convergence",
    # parts and exporters
    "Contour": "camgen.parts.drawing", "Circle": "camgen.parts.drawing", "Part": "camgen.parts.drawing",
    "Drawing": "camgen.parts.drawing", "write_dxf": "camgen.parts.dxf", "svg_document": "camgen.parts.svg",
    "extrude": "camgen.parts.mesh", "stl_bytes": "camgen.parts.stl", "threemf_bytes": "camgen.parts.threemf",
    "write_cam": "camgen.outputs",
    # families
    "read_family": "camgen.family", "members": "camgen.family", "run_family": "camgen.family",
    # errors
    "CamgenError": "camgen.errors", "SpecError": "camgen.errors", "DesignError": "camgen.errors",
}

__all__ = ["__version__", *_EXPORTS]


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'camgen' has no attribute {name!r}")
