"""camgen: disc, plate and grooved cams from motion requirements, and Geneva drives, to files you can cut and print.

The objects a script composes are importable from here; heavy modules load only when
a name is first used (``import camgen`` stays fast)::

    import camgen
    spec = camgen.CamSpec.from_toml("templates/rdrd.toml").with_changes({"motion.0.lift": 25, "motion.2.lift": 25})
    design = camgen.design(spec)                                    # checks and geometry, no I/O
    written = camgen.write(design, "out/rdrd-25", formats=["dxf", "stl"])   # the files, all or nothing

``load_spec``, ``design_cam`` and ``write_cam`` are the names of an earlier release, kept for one more.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from camgen.core import VERSION as __version__
from camgen.core.exports import lazy_exports

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
    "camgen.core.spec": ("TemplateSpec",),
    "camgen.spec": ("load_spec", "validate_spec", "CamSpec"),
    "camgen.cam": ("Cam",),
    "camgen.analysis": ("analyze",),
    "camgen.profile": ("Profile",),
    "camgen.flat": ("build_cam", "CamDesign"),
    "camgen.sizing": ("size_cam",),
    "camgen.convergence_study": ("convergence",),
    "camgen.kinds.grooved.design": ("design_grooved", "GroovedDesign"),
    "camgen.kinds.geneva.kinematics": ("GenevaLaw",),
    "camgen.kinds.geneva.table": ("GenevaSpec",),
    "camgen.kinds.geneva.design": ("design_geneva", "GenevaDesign"),
    "camgen.kinds.machine.spec": ("MachineSpec",),
    "camgen.outputs": ("cam_bundle",),
    "camgen.api": ("load", "design", "write", "Design", "write_cam", "design_cam"),
    "camgen.core.shapes": ("Contour", "Circle"),
    "camgen.core.parts": ("Part", "Drawing", "Allowances"),
    "camgen.core.writers.dxf": ("write_dxf",),
    "camgen.core.writers.svg": ("svg_document",),
    "camgen.core.solids": ("extrude",),
    "camgen.core.writers.stl": ("stl_bytes",),
    "camgen.core.writers.threemf": ("threemf_bytes",),
    "camgen.core.bundle": ("Bundle", "write_bundle", "Written"),
    "camgen.core.family": ("read_family", "members", "run_family"),
    "camgen.core.errors": ("CamgenError", "SpecError", "DesignError", "SolverError", "ExportError"),
}
_EXPORTS = {name: module for module, names in _MODULES.items() for name in names}

__all__ = ["__version__", *_EXPORTS]

if TYPE_CHECKING:      # what an editor and mypy see: the same names, imported (at run time each loads on first use)
    from camgen.laws import make_law as make_law, from_conditions as from_conditions, LAW_NAMES as LAW_NAMES
    from camgen.program import build_program as build_program, Program as Program, Segment as Segment
    from camgen.followers import FOLLOWERS as FOLLOWERS
    from camgen.followers.translating_roller import TranslatingRoller as TranslatingRoller
    from camgen.followers.translating_flat import TranslatingFlat as TranslatingFlat
    from camgen.followers.oscillating_roller import OscillatingRoller as OscillatingRoller
    from camgen.followers.oscillating_flat import OscillatingFlat as OscillatingFlat
    from camgen.followers.plate import PlateRoller as PlateRoller
    from camgen.kinds import KINDS as KINDS
    from camgen.core.spec import TemplateSpec as TemplateSpec
    from camgen.spec import load_spec as load_spec, validate_spec as validate_spec, CamSpec as CamSpec
    from camgen.cam import Cam as Cam
    from camgen.analysis import analyze as analyze
    from camgen.profile import Profile as Profile
    from camgen.flat import build_cam as build_cam, CamDesign as CamDesign
    from camgen.sizing import size_cam as size_cam
    from camgen.convergence_study import convergence as convergence
    from camgen.kinds.grooved.design import design_grooved as design_grooved, GroovedDesign as GroovedDesign
    from camgen.kinds.geneva.kinematics import GenevaLaw as GenevaLaw
    from camgen.kinds.geneva.table import GenevaSpec as GenevaSpec
    from camgen.kinds.geneva.design import design_geneva as design_geneva, GenevaDesign as GenevaDesign
    from camgen.kinds.machine.spec import MachineSpec as MachineSpec
    from camgen.outputs import cam_bundle as cam_bundle
    from camgen.api import load as load, design as design, write as write, Design as Design, write_cam as write_cam
    from camgen.api import design_cam as design_cam
    from camgen.core.shapes import Contour as Contour, Circle as Circle
    from camgen.core.parts import Part as Part, Drawing as Drawing, Allowances as Allowances
    from camgen.core.writers.dxf import write_dxf as write_dxf
    from camgen.core.writers.svg import svg_document as svg_document
    from camgen.core.solids import extrude as extrude
    from camgen.core.writers.stl import stl_bytes as stl_bytes
    from camgen.core.writers.threemf import threemf_bytes as threemf_bytes
    from camgen.core.bundle import Bundle as Bundle, write_bundle as write_bundle, Written as Written
    from camgen.core.family import read_family as read_family, members as members, run_family as run_family
    from camgen.core.errors import (
        CamgenError as CamgenError, SpecError as SpecError, DesignError as DesignError, SolverError as SolverError,
        ExportError as ExportError)


if not TYPE_CHECKING:       # mypy reads the imports above, and flags a name neither gives
    __getattr__, __dir__ = lazy_exports("camgen", _EXPORTS, __all__)
