"""A result's files: what is written, under which names, and writing them all-or-nothing.

A :class:`Bundle` lists :class:`Item` s, each a finished payload (a drawing, a mesh, a
report, a figure, a page or a function that makes it) and the files it becomes, one
:class:`Entry` a format. :func:`write_bundle` hands each payload to the writer of each
of its formats (:mod:`camgen.core.writers`) and nothing more. Every file is first
written to a hidden temporary name beside its target; only when all of them are
written are they renamed into place, so a failure leaves no half-written file and no
temporary behind.
"""
from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar, cast

from camgen.core.errors import ExportError, SpecError
from camgen.core.writers import WriteOptions, writer

#: a design: a frozen dataclass whose ``spec`` says which files it makes
D = TypeVar("D")


class Staging:
    """Collects temporary files and their final names; see :func:`staged`."""

    def __init__(self, directory: Path) -> None:
        self.directory = directory
        self.pending: list[tuple[Path, Path]] = []

    def write(self, name: str, write: Callable[[Path], object]) -> Path:
        """Call ``write(temporary path)`` (what it returns is ignored, e.g. the count of ``Path.write_text``); the
        file takes ``name`` when the whole stage commits."""
        final = self.directory / name
        temp = self.directory / f".{name}.{os.getpid()}.tmp"
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


def item(payload: Any, entries: Iterable[tuple[str, str, str]], formats: Iterable[str]) -> Item | None:
    """An :class:`Item` of ``(format, key, name)`` entries, keeping those whose format is in ``formats``;
    None when none is (then a lazy payload is never made)."""
    wanted = set(formats)
    kept = tuple(Entry(*e) for e in entries if e[0] in wanted)
    return Item(payload, kept) if kept else None


def tail(name: str, plot: Any, kinds: Iterable[str], report: dict[str, Any], page: Any,
         formats: Iterable[str]) -> list[Item | None]:
    """What every bundle ends with, in this order: the figures ``plot(kind)`` for each of ``kinds`` (made only if
    written) as ``<name>-<kind>.png`` and ``.svg``, the ``report`` as ``<name>.json`` and the interactive page
    ``page()`` (none when None) as ``<name>.html``."""
    formats = tuple(formats)
    return [*(item(lambda kind=kind: plot(kind), [("png", f"{kind}_png", f"{name}-{kind}.png"),
                                                  ("svg", f"{kind}_svg", f"{name}-{kind}.svg")], formats)
              for kind in kinds),
            item(Report(report), [("json", "json", f"{name}.json")], formats),
            item(page, [("html", "html", f"{name}.html")], formats) if page is not None else None]


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
    """

    items: tuple[Item, ...]
    options: WriteOptions = field(default_factory=WriteOptions)

    @classmethod
    def of(cls, items: Iterable[Item | None], options: WriteOptions | None = None) -> Bundle:
        """A bundle of the given items, dropping the Nones :func:`item` returns for unwanted files."""
        return cls(tuple(i for i in items if i is not None), options or WriteOptions())

    @property
    def files(self) -> dict[str, str]:
        """``{key: file name}`` of every file, in the order they are written."""
        return {e.key: e.name for i in self.items for e in i.entries}


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


def write_bundle(bundle: Bundle, directory: str | Path) -> dict[str, str]:
    """Write every file of ``bundle`` into ``directory``, all or nothing; return ``{key: file name}``.

    Parameters
    ----------
    bundle : Bundle
        The files to write.
    directory : str or Path
        The folder to write them into, created if missing.

    Returns
    -------
    dict of str to str
        Each file's key (as the report's ``files`` map names it) and its file name, in the order written.

    Raises
    ------
    ExportError
        The folder cannot be created or a file cannot be written; every file written by then is removed (and the
        folders this call created), so a failure leaves the disk as it was.
    """
    files = bundle.files
    with staged(directory) as stage:
        for it in bundle.items:
            payload = it.payload() if callable(it.payload) else it.payload
            if hasattr(payload, "with_files"):       # a report, a page: they name the bundle's files
                payload = payload.with_files(files)
            for entry in it.entries:
                write = writer(entry.format)
                stage.write(entry.name, lambda p, w=write, x=payload: w(x, p, bundle.options))
    return files
