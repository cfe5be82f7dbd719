"""The library's calls, the command line's and the family's: each asks the kind registry (:data:`camgen.kinds.KINDS`)
what a spec or design is, so that none of them names a kind::

    from camgen import api
    spec = api.load("templates/rdrd.toml", ["motion.0.lift=25"])   # checked, no geometry yet
    design = api.design(spec)                                       # every check and the geometry, no I/O
    report = api.write(design, "out/rdrd-25")                        # the files, all or nothing, and the report

Nothing here prints or exits; a problem is a :class:`~camgen.core.errors.CamgenError` in one line.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from camgen.core.bundle import Bundle, Item, write_bundle
from camgen.core.errors import SpecError
from camgen.kinds import spec_kind
from camgen.kinds.base import SizeReport
from camgen.spec import load_spec, validate_spec


def load(path: str | Path, overrides: Iterable[str] = ()) -> Any:
    """The validated spec of the template file ``path`` with ``"key=value"`` ``overrides`` merged in (see
    :func:`camgen.spec.load_spec`)."""
    return load_spec(path, overrides)


def validate(raw: Mapping[str, Any]) -> Any:
    """The validated spec of the raw template ``raw`` (see :func:`camgen.spec.validate_spec`)."""
    return validate_spec(raw)


def design(spec: Any) -> Any:
    """The design of ``spec`` by its kind: every check and all the geometry, nothing written.

    Parameters
    ----------
    spec : object
        A validated spec (:func:`load`, :func:`validate`) of any registered kind.

    Returns
    -------
    object
        The kind's design: a disc or plate cam's :class:`~camgen.flat.FlatCamDesign`, a grooved cam's, a barrel's, a
        conjugate pair's or a Geneva drive's own, which :func:`write` writes alike.

    Raises
    ------
    DesignError
        The spec is valid but its part cannot be made as asked (an undercut, a cusp, no wall round the bore); the
        message names the key to change and by how much.
    """
    return spec_kind(spec).design(spec)


def write(design: Any, directory: str | Path, extra: Iterable[Item] = ()) -> dict[str, Any]:
    """Write the files of ``design`` (of any kind) into ``directory``, all or nothing, and the files of the
    ``extra`` items after them (a figure asked for on the command line).

    Parameters
    ----------
    design : object
        A design from :func:`design`.
    directory : str or Path
        The folder to write into (made if missing). Every file is written under a temporary name and renamed only
        when all are complete, so a failure leaves nothing behind.
    extra : iterable of Item
        More files to write after the design's own.

    Returns
    -------
    dict
        The report, as ``<name>.json`` holds it, with ``files``: each file's name by its key.

    Raises
    ------
    ExportError
        A file could not be written.
    """
    bundle, report = spec_kind(design.spec).bundle(design)
    bundle = Bundle.of((*bundle.items, *extra), bundle.options)
    return {**report, "files": write_bundle(bundle, directory)}


#: the name scripts have written the files with (``camgen.write_cam``)
write_cam = write


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
    report = write(made, folder)
    return spec_kind(made.spec).family_row(made, report)
