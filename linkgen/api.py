"""The library's calls for scripts, in the shape of camgen's (:mod:`camgen.api`)::

    import linkgen
    spec = linkgen.LinkageSpec.from_toml("templates/crank-rocker.toml").with_changes({"linkage.crank": 60})
    design = linkgen.design(spec, angle=30, parts=True)     # kinematics, report and parts, no I/O
    written = linkgen.write(design, "out/crank-rocker", formats=["json", "dxf"])   # all or nothing

Nothing here prints or exits; a problem is a :class:`~camgen.core.errors.CamgenError` in one line.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from camgen.core.bundle import Bundle, Written, with_formats, write_bundle
from linkgen.linkage_design import LinkageDesign, design_linkage
from linkgen.outputs import linkage_bundle, linkage_report
from linkgen.spec import LinkageSpec, load_spec, validate_spec


def load(path: str | Path, overrides: Iterable[str] = ()) -> LinkageSpec:
    """The validated spec of the linkage template file ``path`` with ``"key=value"`` ``overrides`` merged in (see
    :func:`linkgen.spec.load_spec`)."""
    return load_spec(path, overrides)


def validate(raw: Mapping[str, Any]) -> LinkageSpec:
    """The validated spec of the raw linkage template ``raw`` (see :func:`linkgen.spec.validate_spec`)."""
    return validate_spec(raw)


def design(spec: LinkageSpec, angle: float | None = None, parts: bool = False) -> LinkageDesign:
    """The design of ``spec``: kinematics, report and, with ``parts``, the parts of its ``[parts]`` table; nothing
    written (:func:`linkgen.linkage_design.design_linkage`, positions solved in closed form).

    Parameters
    ----------
    spec : LinkageSpec
        A validated template (:func:`load`, :meth:`LinkageSpec.from_toml <camgen.core.spec.TemplateSpec.from_toml>`).
    angle : float, optional
        The input's angle (degrees; mm for a slide input): adds every position there to the report.
    parts : bool
        Also make the parts (as ``linkgen build`` does).

    Returns
    -------
    LinkageDesign
        The design; ``design.report`` is the report as ``linkgen analyze`` gives it.

    Raises
    ------
    SpecError
        ``angle`` lies outside the input's reach, or ``parts`` is asked for without a ``[parts]`` table.
    DesignError
        The parts cannot be made as asked.
    """
    return design_linkage(spec, angle, parts=parts)


def write(design: LinkageDesign, directory: str | Path, formats: Iterable[str] | None = None) -> Written:
    """Write the files of ``design`` into ``directory``, all or nothing.

    Parameters
    ----------
    design : LinkageDesign
        A design from :func:`design`.
    directory : str or Path
        The folder to write into (made if missing); a failure leaves nothing behind.
    formats : iterable of str, optional
        The formats to write (``["json", "dxf"]``), instead of the spec's ``output.formats``.

    Returns
    -------
    Written
        The report, as ``<name>.json`` holds it (with ``files``: each file's name by its key), and each file's path.

    Raises
    ------
    SpecError
        A format the design cannot write (``"step"`` or ``"dxf"`` of a design made without parts), naming
        ``output.formats``.
    ExportError
        A file could not be written.
    """
    design = with_formats(design, formats)
    bundle = linkage_bundle(design)
    if formats is not None:
        bundle.require(design.spec.output.formats)
    return Written.of(linkage_report(design), write_bundle(bundle, directory), directory)


def bundle(design: LinkageDesign) -> tuple[Bundle, dict[str, Any]]:
    """The files of ``design`` that its ``output.formats`` asks for, made but not written, and its report (as
    ``linkgen analyze`` gives it, without the ``files`` map): what a camgen machine writes of a linkage it
    drives, beside its own files."""
    return linkage_bundle(design), linkage_report(design)
