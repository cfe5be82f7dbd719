"""A result's files: what is written, under which names, and writing them all-or-nothing.

A :class:`Bundle` lists :class:`Item` s, each a finished payload (a drawing, a mesh, a
report, a figure, a page or a function that makes it) and the files it becomes, one
:class:`Entry` a format. :func:`write_bundle` hands each payload to the writer of each
of its formats (:mod:`camgen.core.writers`) and nothing more. Every file is first
written to a hidden temporary name beside its target (in its sub-folder, for a name
that has one, ``"head/cam.dxf"``); only when all of them are written are they renamed
into place, so a failure leaves no half-written file, no temporary and no folder it
made behind.
"""
from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager, suppress
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeAlias, TypeVar, cast

from camgen.core.errors import ExportError, SpecError
from camgen.core.writers import REGISTRY, Role, WriteOptions, Writer, writer

if TYPE_CHECKING:
    from camgen.core.page import Page
    from camgen.core.parts import Drawing
    from camgen.core.solids import Mesh
    from camgen.core.writers.step import Solids

#: a design: a frozen dataclass whose ``spec`` says which files it makes
D = TypeVar("D")
#: a payload, or the function of no arguments that makes it when it is written
T = TypeVar("T")
Lazy: TypeAlias = "T | Callable[[], T]"


class Staging:
    """Collects temporary files and their final names; see :func:`staged`."""

    def __init__(self, directory: Path) -> None:
        self.directory = directory
        self.pending: list[tuple[Path, Path]] = []
        #: the sub-folders this stage created for names with a folder part, in the order created
        self.created: list[Path] = []

    def write(self, name: str, write: Callable[[Path], object]) -> Path:
        """Call ``write(temporary path)`` (what it returns is ignored, e.g. the count of ``Path.write_text``); the
        file takes ``name`` when the whole stage commits. ``name`` may hold sub-folders (``"head/cam.dxf"``, ``/``
        between them), created as needed (and removed again if the stage fails); never an absolute path or ``..``."""
        parts = Path(name).parts
        if not parts or Path(name).is_absolute() or ".." in parts:
            raise ExportError(f"{name}: a file's name must stay inside its output folder")
        final = self.directory / name
        temp = final.parent / f".{final.name}.{os.getpid()}.tmp"
        missing = _missing(final.parent)
        try:
            final.parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ExportError(f"cannot create folder {final.parent}: {exc.strerror or exc}") from None
        self.created += reversed(missing)
        self.pending.append((temp, final))
        try:
            write(temp)
        except ExportError:
            raise
        except OSError as exc:
            raise ExportError(f"cannot write {final}: {exc.strerror or exc}") from None
        if not temp.exists():
            raise ExportError(f"{name}: the writer produced no file")
        return final

    def write_bytes(self, name: str, data: bytes) -> Path:
        return self.write(name, lambda p: p.write_bytes(data))


def _missing(directory: Path) -> list[Path]:
    """``directory`` and those of its parents that do not exist yet, deepest first."""
    out = []
    for folder in (directory, *directory.parents):
        if folder.exists():
            break
        out.append(folder)
    return out


@contextmanager
def staged(directory: str | Path) -> Iterator[Staging]:
    """Stage files in ``directory`` (created if missing); rename them all into place on success.

    On failure every temporary file is removed, and so are the folders this call created: a failed
    run leaves the disk as it found it.
    """
    directory = Path(directory)
    created = _missing(directory)
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        _remove(created)
        raise ExportError(f"cannot create output folder {directory}: {exc.strerror}") from None
    stage = Staging(directory)
    try:
        yield stage
        for temp, final in stage.pending:
            os.replace(temp, final)
    except BaseException as exc:
        for temp, _ in stage.pending:
            temp.unlink(missing_ok=True)
        for folder in stage.created[::-1]:                  # deepest first; each empty once its temporaries went
            with suppress(OSError):
                folder.rmdir()
        _remove(created)
        if isinstance(exc, OSError) and not isinstance(exc, ExportError):
            raise ExportError(f"cannot write to {directory}: {exc.strerror}") from None
        raise


def _remove(folders: list[Path]) -> None:
    """Remove the (empty) ``folders``, deepest first; leave any that is not empty."""
    for folder in folders:
        try:
            folder.rmdir()
        except OSError:
            return


@dataclass(frozen=True)
class Entry:
    """One file: its ``format`` (see :data:`camgen.core.writers.FORMATS`), its ``key`` in the report's
    ``files`` map and its file ``name``."""

    format: str
    key: str
    name: str


@dataclass(frozen=True)
class Report:
    """A report payload: a JSON-ready dict; when written, the bundle's ``files`` map is added at its end."""

    data: dict[str, Any]

    def with_files(self, files: dict[str, str]) -> dict[str, Any]:
        """The report as written: its data with the bundle's ``files`` map at the end."""
        return {**self.data, "files": dict(files)}


@dataclass(frozen=True)
class Item:
    """A payload and the files it becomes. ``payload`` may be a function of no arguments that makes it
    (a figure): it is called once, only if one of the item's files is written."""

    payload: Any
    entries: tuple[Entry, ...]

    def only(self, formats: Iterable[str]) -> Item | None:
        """The item with only the files of ``formats`` (and of the formats written with one of them, such as a
        kit's CSV with the JSON report: :attr:`camgen.core.writers.Format.follows`); None when none is left."""
        wanted = set(formats)
        kept = tuple(e for e in self.entries if e.format in wanted or _follows(e.format) in wanted)
        return dataclasses.replace(self, entries=kept) if kept else None


def _follows(fmt: str) -> str | None:
    known = REGISTRY.get(fmt)
    return known.follows if known is not None else None


def item(payload: Any, entries: Iterable[tuple[str, str, str]], formats: Iterable[str]) -> Item | None:
    """An :class:`Item` of ``(format, key, name)`` entries, keeping those whose format is in ``formats``;
    None when none is (then a lazy payload is never made). The low-level form of the constructors below, which
    name the files from the formats' registry."""
    wanted = set(formats)
    kept = tuple(Entry(*e) for e in entries if e[0] in wanted)
    return Item(payload, kept) if kept else None


def files_of(role: Role, payload: Any, stem: str, key: str = "", only: Iterable[str] | None = None) -> Item | None:
    """``payload`` as the files of every registered format that writes its ``role``
    (:data:`camgen.core.writers.REGISTRY`, in its order), or of those of them in ``only``: each named ``stem``
    plus the format's ending for the role, its report key ``key`` joined by ``_`` to the format's key ending
    (``files_of("part", d, "cam-1", "cam1")``: ``cam-1.dxf`` as ``cam1_dxf``, ``cam-1-cut.svg`` as
    ``cam1_cut_svg``). None for a None payload (a file nobody asked to be made) or when no format is left."""
    if payload is None:
        return None
    allowed = None if only is None else set(only)
    entries = tuple(Entry(f.name, f"{key}_{f.files[role][1]}" if key else f.files[role][1], stem + f.files[role][0])
                    for f in REGISTRY.values() if role in f.files and (allowed is None or f.name in allowed))
    return Item(payload, entries) if entries else None


def part_files(drawing: Drawing | None, stem: str, key: str = "") -> Item | None:
    """A part's cut drawing (a :class:`~camgen.core.parts.Drawing`) as ``<stem>.dxf`` and ``<stem>-cut.svg``
    (keys ``<key>_dxf``, ``<key>_cut_svg``; ``dxf``, ``cut_svg`` without a key)."""
    return files_of("part", drawing, stem, key)


def sheet_files(drawing: Drawing | None, stem: str, key: str = "") -> Item | None:
    """A sheet's or an assembly's drawing as ``<stem>.dxf`` and ``<stem>.svg`` (keys ``<key>_dxf``, ``<key>_svg``):
    the same formats as a part's, the SVG without ``-cut`` since the whole file is the drawing."""
    return files_of("sheet", drawing, stem, key)


def mesh_files(mesh: Lazy[Mesh | Sequence[Mesh]] | None, stem: str, key: str = "",
               only: Iterable[str] | None = None) -> Item | None:
    """A checked mesh (or a function making placed meshes) as ``<stem>.stl`` and ``<stem>.3mf`` (keys ``<key>_stl``,
    ``<key>_3mf``), or only the formats of ``only``; None for no mesh."""
    return files_of("mesh", mesh, stem, key, only)


def solid_files(solids: Lazy[Solids] | None, stem: str, key: str = "") -> Item | None:
    """Exact solids (``(name, parts)`` pairs or placed solids, see :mod:`camgen.core.writers.step`, or a function
    making them) as ``<stem>.step`` (key ``<key>_step``, ``step`` without a key)."""
    return files_of("solids", solids, stem, key)


def figure_files(make: Callable[[], Any], stem: str, key: str = "", only: Iterable[str] | None = None
                 ) -> Item | None:
    """The figure ``make()`` draws (called once, only if written) as ``<stem>.png`` and ``<stem>.svg`` (keys
    ``<key>_png``, ``<key>_svg``), or only the formats of ``only`` (a PNG beside a drawing's SVG of the same stem)."""
    return files_of("figure", make, stem, key, only)


def report_file(report: dict[str, Any], stem: str, key: str = "", listing: bool = True) -> Item | None:
    """``report`` as ``<stem>.json`` (key ``json``, or ``<key>_json``), with the bundle's ``files`` map added at
    its end unless ``listing`` is False."""
    return files_of("report", Report(report) if listing else report, stem, key)


def page_file(page: Lazy[Page | str] | None, stem: str) -> Item | None:
    """The interactive page (a :class:`~camgen.core.page.Page` or a function making one) as ``<stem>.html`` (key
    ``html``); None for no page."""
    return files_of("page", page, stem)


def animation_file(make: Callable[[], Any] | None, stem: str) -> Item | None:
    """One cycle's frames (a function making them, called only if written) as ``<stem>-animation.gif`` (key
    ``gif``): the file ``animate`` writes with its defaults; None for no animation."""
    return files_of("animation", make, stem)


def rows_file(rows: Sequence[Mapping[str, Any]] | str, stem: str, key: str = "") -> Item | None:
    """A table (dicts with the same keys, or a finished CSV text) as ``<stem>.csv`` (key ``<key>_csv``), written
    with the JSON report; None when it has no rows."""
    return files_of("rows", rows, stem, key) if len(rows) else None


def text_file(text: str, stem: str, key: str = "") -> Item | None:
    """A finished text (a template's TOML) as ``<stem>.toml`` (key ``<key>_toml``), written with the JSON report."""
    return files_of("text", text, stem, key)


def tail(name: str, plot: Any, kinds: Iterable[str], report: dict[str, Any], page: Any,
         formats: Iterable[str] | None = None) -> list[Item | None]:
    """What every bundle ends with, in this order: the figures ``plot(kind)`` for each of ``kinds`` (made only if
    written) as ``<name>-<kind>.png`` and ``.svg``, the ``report`` as ``<name>.json`` and the interactive page
    ``page()`` (none when None) as ``<name>.html``; only those of ``formats`` when given (else
    :meth:`Bundle.of` keeps the wanted ones)."""
    items = [*(figure_files(partial(plot, kind), f"{name}-{kind}", kind) for kind in kinds),
             report_file(report, name), page_file(page, name)]
    if formats is None:
        return items
    formats = tuple(formats)
    return [i.only(formats) if i is not None else None for i in items]


@dataclass(frozen=True)
class Bundle:
    """The files a result is written as, in order, and the writers' options.

    Parameters
    ----------
    items : tuple of Item
        Each payload (or the function that makes it, called only when one of its files is written) with the
        files it becomes.
    options : WriteOptions, optional
        The writers' settings (DXF version and flavour, text mode).
    offered : frozenset of str, optional
        Formats its payloads can be written as beyond those of ``items`` (the ones :meth:`of` left out).
    """

    items: tuple[Item, ...]
    options: WriteOptions = field(default_factory=WriteOptions)
    offered: frozenset[str] = frozenset()

    @classmethod
    def of(cls, items: Iterable[Item | None], options: WriteOptions | None = None,
           formats: Iterable[str] | None = None) -> Bundle:
        """A bundle of the given items, dropping the Nones the constructors return for files not made; with
        ``formats``, only their files (:meth:`Item.only`), the others still :attr:`offers`."""
        given = [i for i in items if i is not None]
        offered = frozenset(e.format for i in given for e in i.entries)
        if formats is not None:
            wanted = tuple(formats)
            given = [k for k in (i.only(wanted) for i in given) if k is not None]
        return cls(tuple(given), options or WriteOptions(), offered)

    def plus(self, items: Iterable[Item | None], formats: Iterable[str] | None = None) -> Bundle:
        """This bundle with ``items`` after its own (only the files of ``formats`` of them, when given), offering
        what both offer."""
        more = Bundle.of(items, self.options, formats)
        return Bundle(self.items + more.items, self.options, self.offers | more.offered)

    @property
    def files(self) -> dict[str, str]:
        """``{key: file name}`` of every file, in the order they are written."""
        return {e.key: e.name for i in self.items for e in i.entries}

    @property
    def offers(self) -> frozenset[str]:
        """Every format this bundle's payloads can be written as (those :meth:`of` left out included)."""
        return self.offered | {e.format for i in self.items for e in i.entries}

    def require(self, formats: Iterable[str]) -> None:
        """Refuse, naming ``output.formats``, the first of ``formats`` this bundle does not offer (a format asked
        by name of a design that has no payload for it, such as ``"stl"`` of a linkage designed without parts)."""
        offers = self.offers
        for fmt in formats:
            if fmt not in offers and _follows(fmt) is None:
                raise SpecError(f"{fmt!r}: this design has no {fmt} file to write; give formats of "
                                f"{', '.join(f for f in REGISTRY if f in offers and _follows(f) is None)}",
                                "output.formats")


@dataclass(frozen=True)
class Written:
    """What writing a design gave (``camgen.write``, ``linkgen.write``).

    Attributes
    ----------
    report : dict
        The report, as ``<name>.json`` holds it (with ``files``: each file's name by its key).
    files : dict of str to Path
        Each file written, by its key (``"dxf"``, ``"json"``, ``"sheet_dxf"``...), in the order written.
    """

    report: dict[str, Any]
    files: dict[str, Path]

    @classmethod
    def of(cls, report: dict[str, Any], names: dict[str, str], directory: str | Path) -> Written:
        """The report of the files ``names`` (``{key: file name}``) written into ``directory``."""
        return cls({**report, "files": names}, {key: Path(directory) / name for key, name in names.items()})


def with_formats(design: D, formats: Iterable[str] | None) -> D:
    """``design`` (a frozen dataclass with a ``spec``) with its spec's ``output.formats`` set to ``formats`` and
    ``output.figures`` off, so that those are exactly the files its bundle makes, the spec validated again (a format
    its kind does not write is refused in one line); ``design`` itself for None. Nothing is designed again: no
    design depends on its formats."""
    if formats is None:
        return design
    if isinstance(formats, str):
        raise SpecError(f"give a list of formats, e.g. [{formats!r}] (got {formats!r})", "formats")
    spec = cast(Any, design).spec.with_changes({"output.formats": list(formats), "output.figures": False})
    return cast(D, dataclasses.replace(cast(Any, design), spec=spec))


def write_bundle(bundle: Bundle, directory: str | Path, formats: Iterable[str] | None = None) -> dict[str, str]:
    """Write every file of ``bundle`` into ``directory``, all or nothing; return ``{key: file name}``.

    Parameters
    ----------
    bundle : Bundle
        The files to write.
    directory : str or Path
        The folder to write them into, created if missing.
    formats : iterable of str, optional
        Write only the files of these formats, each of which the bundle must offer (:meth:`Bundle.require`).

    Returns
    -------
    dict of str to str
        Each file's key (as the report's ``files`` map names it) and its file name, in the order written.

    Raises
    ------
    SpecError
        Naming ``output.formats``: one of ``formats`` that the bundle does not offer; nothing is written.
    ExportError
        The folder cannot be created or a file cannot be written; every file written by then is removed (and the
        folders this call created), so a failure leaves the disk as it was.
    """
    if formats is not None:
        formats = tuple(formats)
        bundle.require(formats)
        bundle = Bundle.of(bundle.items, bundle.options, formats)
    files = bundle.files
    with staged(directory) as stage:
        for it in bundle.items:
            payload = it.payload() if callable(it.payload) else it.payload
            if hasattr(payload, "with_files"):       # a report, a page: they name the bundle's files
                payload = payload.with_files(files)
            for entry in it.entries:
                stage.write(entry.name, _writing(writer(entry.format), payload, bundle.options))
    return files


def _writing(write: Writer, payload: Any, options: WriteOptions) -> Callable[[Path], None]:
    """The function :meth:`Staging.write` calls: ``write`` of ``payload`` with ``options`` to a path."""
    return lambda path: write(payload, path, options)
