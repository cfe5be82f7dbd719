"""The library's calls, the command line's and the family's: each asks the kind registry (:data:`camgen.kinds.KINDS`)
what a spec or design is, so that none of them names a kind::

    import camgen
    spec = camgen.CamSpec.from_toml("templates/rdrd.toml").with_changes({"motion.0.lift": 25})
    design = camgen.design(spec)                                    # every check and the geometry, no I/O
    written = camgen.write(design, "out/rdrd-25", formats=["dxf", "stl"])   # all or nothing
    written.files["dxf"], written.report["files"]

Nothing here prints or exits; a problem is a :class:`~camgen.core.errors.CamgenError` in one line.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol, cast

from camgen.core.bundle import Item, Written, with_formats, write_bundle
from camgen.core.errors import SpecError
from camgen.core.spec import TemplateSpec
from camgen.kinds import spec_kind
from camgen.kinds.base import SizeReport
from camgen.spec import CamSpec, load_spec, validate_spec

if TYPE_CHECKING:
    from camgen.kinds.geneva.table import GenevaSpec


class Design(Protocol):
    """What :func:`design` gives for every kind (a disc or plate cam's :class:`~camgen.flat.FlatCamDesign`, a
    grooved, barrel or conjugate cam's design, a Geneva drive's): frozen, everything computed, nothing written."""

    @property
    def spec(self) -> CamSpec | GenevaSpec:
        """The validated template it was designed from."""
        ...

    @property
    def tolerance(self) -> float:
        """The chord tolerance (mm) its curves were made to."""
        ...

    @property
    def warnings(self) -> tuple[str, ...]:
        """What the console prints after the summary: each a line in the user's terms."""
        ...

    def _repr_svg_(self) -> str:
        """The part (or parts) as drawn, for Jupyter."""
        ...

    def _repr_html_(self) -> str | None:
        """The interactive page, for Jupyter; None where ``output.formats`` leaves out html."""
        ...


def load(path: str | Path, overrides: Iterable[str] = ()) -> CamSpec | GenevaSpec:
    """The validated spec of the template file ``path`` with ``"key=value"`` ``overrides`` merged in (see
    :func:`camgen.spec.load_spec`; :meth:`CamSpec.from_toml <camgen.core.spec.TemplateSpec.from_toml>` is the same
    for a cam only)."""
    return _named(load_spec(path, overrides))


def validate(raw: Mapping[str, Any]) -> CamSpec | GenevaSpec:
    """The validated spec of the raw template ``raw`` (see :func:`camgen.spec.validate_spec`)."""
    return _named(validate_spec(raw))


def _named(spec: TemplateSpec) -> CamSpec | GenevaSpec:
    """The spec the registry gave, typed as the library's callers read it: a cam's or a Geneva drive's (another
    registered kind's, a machine's or a plugin's, has their ``name`` and ``output`` too)."""
    return cast("CamSpec | GenevaSpec", spec)


def design(spec: TemplateSpec) -> Design:
    """The design of ``spec`` by its kind: every check and all the geometry, nothing written.

    Parameters
    ----------
    spec : CamSpec or GenevaSpec
        A validated spec (:func:`load`, :meth:`CamSpec.from_toml <camgen.core.spec.TemplateSpec.from_toml>`) of any
        registered kind.

    Returns
    -------
    Design
        The kind's design: a disc or plate cam's :class:`~camgen.flat.FlatCamDesign`, a grooved cam's, a barrel's, a
        conjugate pair's or a Geneva drive's own, which :func:`write` writes alike.

    Raises
    ------
    DesignError
        The spec is valid but its part cannot be made as asked (an undercut, a cusp, no wall round the bore); the
        message names the key to change and by how much.
    """
    made: Design = spec_kind(spec).design(spec)
    return made


def write(design: Design, directory: str | Path, formats: Iterable[str] | None = None,
          extra: Iterable[Item] = ()) -> Written:
    """Write the files of ``design`` (of any kind) into ``directory``, all or nothing, and the files of the
    ``extra`` items after them (a figure asked for on the command line).

    Parameters
    ----------
    design : Design
        A design from :func:`design`.
    directory : str or Path
        The folder to write into (made if missing). Every file is written under a temporary name and renamed only
        when all are complete, so a failure leaves nothing behind.
    formats : iterable of str, optional
        The formats to write (``["dxf", "stl"]``), instead of the spec's ``output.formats``.
    extra : iterable of Item
        More files to write after the design's own.

    Returns
    -------
    Written
        The report, as ``<name>.json`` holds it (with ``files``: each file's name by its key), and each file's path.

    Raises
    ------
    SpecError
        A format the design's kind does not write, or one it has nothing to write as (``"step"`` of a cam made
        with no printed part), naming ``output.formats``.
    ExportError
        A file could not be written.
    """
    design = with_formats(design, formats)
    bundle, report = spec_kind(design.spec).bundle(design)
    if formats is not None:
        bundle.require(design.spec.output.formats)
    return Written.of(report, write_bundle(bundle.plus(extra), directory), directory)


def design_cam(spec: TemplateSpec) -> Any:
    """The design of the cam ``spec`` describes, by its kind (see :mod:`camgen.kinds`; a Geneva drive's too, see
    :mod:`camgen.kinds.geneva`): every check and all the geometry, nothing written; :func:`camgen.api.design` is the
    same call (the name of an earlier release, kept for one more).

    Parameters
    ----------
    spec : CamSpec or GenevaSpec
        A validated template (:func:`camgen.spec.load_spec`, :func:`camgen.spec.validate_spec`).

    Returns
    -------
    object
        A disc or plate cam's :class:`~camgen.flat.FlatCamDesign`; a grooved cam's, a barrel's, a conjugate pair's or
        a Geneva drive's own design, which :func:`camgen.api.write` writes alike.

    Raises
    ------
    DesignError
        The spec is valid but its part cannot be made as asked: an undercut, a cusp, no wall round the bore; the
        message names the key to change and by how much.
    """
    return spec_kind(spec).design(spec)


def write_cam(design: Design, directory: str | Path) -> dict[str, Any]:
    """The files of ``design`` written into ``directory`` as :func:`write` writes them, and the report: the name
    scripts have written them with (``camgen.write_cam``), kept for one release."""
    return write(design, directory).report


def summary(design: Any, report: dict[str, Any]) -> list[str]:
    """The lines ``camgen build`` prints of ``design``, whose written report is ``report``."""
    return spec_kind(design.spec).summary(design, report)


def size(spec: Any) -> SizeReport:
    """The smallest size meeting ``spec``'s limits (``camgen size``); a one-line :class:`SpecError` naming
    ``template`` for a kind that has nothing to size (a barrel cam, a Geneva drive)."""
    kind = spec_kind(spec)
    sized = kind.size(spec)
    if sized is None:
        raise SpecError(kind.unsized, "template")
    return sized


def construction(design: Any) -> tuple[Item, ...]:
    """The files of ``design``'s graphical construction (``camgen build --construction``); a one-line
    :class:`SpecError` naming ``--construction`` for a kind that has none."""
    return spec_kind(design.spec).construction(design)


def sheet_refusal(spec: Any) -> str | None:
    """Why a family's ``[sheet]`` cannot nest this member's cut part, or None where the member writes one
    (``<name>.dxf``: a disc, plate or grooved cam with "dxf" in its formats)."""
    return spec_kind(spec).sheet_refusal(spec)


def thumbnail_bore(spec: Any) -> float:
    """The bore (mm) a family's overview draws about the centre of this member's thumbnail (0 for none: a barrel
    cam's thumbnail is its groove unrolled, a Geneva drive's its wheel)."""
    return spec_kind(spec).thumbnail_bore(spec)


def build_member(raw: dict[str, Any], folder: Path) -> dict[str, Any]:
    """Build one family member from its raw template into ``folder``: its summary row (the kind's figures, its
    files and a thumbnail)."""
    made = design(validate(raw))
    report = write(made, folder).report
    return spec_kind(made.spec).family_row(made, report)
