"""What every kind declares (see :mod:`camgen.kinds`): the :class:`Kind` protocol the registry holds, the defaults of
:class:`KindBase`, and the records a kind hands back: its starter templates (:class:`Starter`) and what ``camgen
size`` prints for it (:class:`SizeReport`).

A kind is the one place that knows how its spec is designed, bundled, summarised and sized: the command line, the
family, the page and the starters ask the registry, never the kind's name. Its methods import its design and output
modules when first called, so that the registry stays light (a cam's build loads nothing of the Geneva drive).
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Generic, Protocol, TypeVar

from camgen.core.errors import SpecError
from camgen.core.writers import FORMATS, OPTIONAL_FORMATS

if TYPE_CHECKING:
    from pathlib import Path

    from camgen.core.bundle import Bundle, Item
    from camgen.sizing import Sizing

#: a kind's spec (a validated template) and its design
S = TypeVar("S")
D = TypeVar("D")

#: a kind's frames function: (design, its report, frame count, (width, height) pixels) -> (n, height, width, 3)
#: uint8 frames
Animator = Callable[[Any, dict[str, Any], int, tuple[int, int]], Any]
#: the table a cam's kind is named in (``cam.kind``); a kind with a table of its own (a Geneva drive's
#: ``[geneva]``) is chosen by that table instead
CAM_TABLE = "cam"
#: every format a cam's bundle can write, the optional ones included
ALL_FORMATS = frozenset((*FORMATS, *OPTIONAL_FORMATS))
#: what a family's ``[sheet]`` nests, for the messages of the kinds it does not
NESTED = "a family's [sheet] nests disc, plate and grooved cams"


@dataclass(frozen=True)
class Starter:
    """A starter template ``camgen new NAME`` writes.

    Attributes
    ----------
    what : str
        What it is; its first line is what ``camgen new`` lists.
    tables : tuple of (str, mapping)
        Its tables in order, as :func:`camgen.core.starter.render` takes them (``("cam", {...})``,
        ``("[motion]", {...})`` for one ``[[motion]]`` entry).
    rules : mapping of str to str
        Comments of its own: under a table's heading (``"cam"``) the kind's rule, for a ``table.key`` what that key
        means for this kind; they name only keys the kind takes.
    """

    what: str
    tables: tuple[tuple[str, Mapping[str, Any]], ...]
    rules: Mapping[str, str]


@dataclass(frozen=True)
class SizeReport:
    """What ``camgen size`` prints for a spec: the size that decides, in mm (:class:`~camgen.sizing.Sizing`),
    ``figures`` the JSON adds to the sizing's own, and ``notes``: lines the console prints after its own line."""

    sizing: Sizing
    figures: Mapping[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()


class Kind(Protocol[S, D]):
    """One kind of cam (or drive): ``S`` the type of its spec, ``D`` of its design."""

    @property
    def name(self) -> str:
        """The registry's key: ``cam.kind``'s value (``"disc"``), or for a kind with its own table that table's name."""
        ...

    @property
    def title(self) -> str:
        """How a message names it: ``"a disc cam"``, ``"a Geneva drive"``."""
        ...

    @property
    def table_key(self) -> str:
        """The template's table it is chosen by: :data:`CAM_TABLE` (by ``cam.kind``), or a table of its own."""
        ...

    @property
    def followers(self) -> tuple[str, ...]:
        """The follower types it drives (none for a Geneva drive)."""
        ...

    @property
    def formats(self) -> frozenset[str]:
        """The output formats its bundle offers; ``output.formats`` is checked against them when the template is
        validated, before anything is designed."""
        ...

    @property
    def unsized(self) -> str:
        """Why ``camgen size`` has nothing to size, where :meth:`size` gives None."""
        ...

    @property
    def spec(self) -> type[S]:
        """The model its template validates into (imported on first use)."""
        ...

    @property
    def starters(self) -> Mapping[str, Starter]:
        """Its ``camgen new`` entries by name (a disc cam has one a follower type)."""
        ...

    def design(self, spec: S) -> D:
        """Every check and all the geometry of ``spec``, nothing written; a :class:`~camgen.core.errors.DesignError`
        naming the key to change where the part cannot be made."""
        ...

    def bundle(self, design: D) -> tuple[Bundle, dict[str, Any]]:
        """The files ``design.spec.output.formats`` asks for, made but not written, and the report without its
        ``files`` map (which the bundle adds)."""
        ...

    def summary(self, design: D, report: dict[str, Any]) -> list[str]:
        """The lines ``camgen build`` prints of a design whose report (with its files) is ``report``."""
        ...

    def size(self, spec: S) -> SizeReport | None:
        """The smallest size meeting the spec's limits (``camgen size``), or None where the kind has nothing to
        size (:attr:`unsized` says why)."""
        ...

    def family_row(self, design: D, report: dict[str, Any]) -> dict[str, Any]:
        """A family member's summary row beyond its name and status: its key figures, ``files`` and a ``thumbnail``
        (a closed ring, mm), as the member's ``row.json`` holds it."""
        ...

    def thumbnail_bore(self, spec: S) -> float:
        """The bore (mm) a family's overview draws about the centre of a member's thumbnail; 0 for none. From the
        spec, not the row: the overview's figure, not the member's files."""
        ...

    def construction(self, design: D) -> tuple[Item, ...]:
        """The files of its graphical construction (``camgen build --construction``), drawn only when written; a
        one-line :class:`~camgen.core.errors.SpecError` naming ``--construction`` for a kind that has none."""
        ...

    def sheet_refusal(self, spec: S) -> str | None:
        """Why a family's ``[sheet]`` cannot nest this member's cut part, or None where it writes one to nest."""
        ...

    def format_refusal(self, fmt: str) -> str:
        """What to say of ``fmt``, a format in ``output.formats`` that is not one of :attr:`formats`."""
        ...

    def beside(self, raw: dict[str, Any], folder: Path) -> dict[str, Any]:
        """The raw template ``raw`` read from a file in ``folder`` with the files it names by a relative path made
        to lie beside it (before validation; a template of its kind without such files as it is)."""
        ...

    def animation(self, design: D, n: int, size: tuple[int, int], report: dict[str, Any] | None = None) -> Any:
        """The ``n`` frames of one cycle of ``design`` (``camgen animate``), ``size`` (width, height) pixels, as an
        array (n, height, width, 3) of uint8 drawn by the kind's own ``animation.py`` (from ``report``, the design's
        report where the caller has made it, else made here); a one-line :class:`~camgen.core.errors.SpecError`
        naming ``cam.kind`` for a kind that is not animated."""
        ...


@dataclass(frozen=True)
class Operations(Generic[S, D]):
    """What a kind does with its specs and designs (:meth:`KindBase.operations` hands it out, importing the modules
    that do it): ``design`` (spec -> design), ``bundle`` (design -> files and report), ``summary`` (design, report ->
    the console's lines), ``family_row`` (design, report -> a family member's row) and ``size`` (spec -> the
    smallest size meeting its limits; None: the kind has nothing to size)."""

    design: Callable[[S], D]
    bundle: Callable[[D], tuple[Bundle, dict[str, Any]]]
    summary: Callable[[D, dict[str, Any]], list[str]]
    family_row: Callable[[D, dict[str, Any]], dict[str, Any]]
    size: Callable[[S], SizeReport] | None = None


def default_animation(kind: Kind[Any, Any], design: Any, report: dict[str, Any]) -> Item | None:
    """The ``gif`` file of ``design`` (its report ``report``) where its ``output.formats`` asks for one: one cycle
    as ``camgen animate`` writes it with its defaults (the frames drawn only when written); None otherwise."""
    if "gif" not in design.spec.output.formats:
        return None
    from camgen.core.animation import DEFAULT_FRAMES, DEFAULT_SIZE
    from camgen.core.bundle import animation_file

    return animation_file(lambda: kind.animation(design, DEFAULT_FRAMES, DEFAULT_SIZE, report), design.spec.name)


class KindBase(ABC, Generic[S, D]):
    """The defaults of a :class:`Kind`: chosen by ``cam.kind``, every format, no construction, no starter, not nested
    on a family's sheet; its design, files, console lines, family row and size are its :meth:`operations`'. A kind
    sets :attr:`name` and :attr:`title` and writes :attr:`spec` and :meth:`operations` (an instance that lacks one
    cannot be made)."""

    name: str
    title: str
    table_key: str = CAM_TABLE
    formats: frozenset[str] = ALL_FORMATS
    starters: Mapping[str, Starter] = MappingProxyType({})

    @property
    def unsized(self) -> str:
        return f"{self.title} has no base radius to size"

    @property
    def followers(self) -> tuple[str, ...]:
        """The follower types its spec's ``follower`` union takes (:func:`camgen.tables.followers.follower_types`)."""
        from camgen.tables.followers import follower_types

        return follower_types(self.spec)

    @property
    @abstractmethod
    def spec(self) -> type[S]:
        """The model its template validates into."""

    @abstractmethod
    def operations(self) -> Operations[S, D]:
        """What it does with its specs and designs, the modules that do it imported here (when first asked, so that
        the registry stays light)."""

    def design(self, spec: S) -> D:
        return self.operations().design(spec)

    def bundle(self, design: D) -> tuple[Bundle, dict[str, Any]]:
        bundle, report = self.operations().bundle(design)
        return bundle.plus([default_animation(self, design, report)]), report

    def summary(self, design: D, report: dict[str, Any]) -> list[str]:
        return self.operations().summary(design, report)

    def family_row(self, design: D, report: dict[str, Any]) -> dict[str, Any]:
        return self.operations().family_row(design, report)

    def size(self, spec: S) -> SizeReport | None:
        sizer = self.operations().size
        return None if sizer is None else sizer(spec)

    def construction(self, design: D) -> tuple[Item, ...]:
        raise SpecError(f"the graphical construction is drawn for a disc cam, not {self.title}", "--construction")

    def thumbnail_bore(self, spec: S) -> float:
        return 0.0

    def sheet_refusal(self, spec: S) -> str | None:
        return f"{self.title} has no cut part of its own to nest; {NESTED}"

    def animation(self, design: D, n: int, size: tuple[int, int], report: dict[str, Any] | None = None) -> Any:
        frames = self.animator()
        if frames is None:
            raise SpecError(f"{self.title} is not animated", "cam.kind")
        return frames(design, self.operations().bundle(design)[1] if report is None else report, n, size)

    def animator(self) -> Animator | None:
        """The frames function of its ``animation.py`` (imported here, when first asked): ``frames(design, report,
        n, size)``, the design's report as its bundle makes it; None for a kind that is not animated."""
        return None

    def format_refusal(self, fmt: str) -> str:
        return f"{self.title} writes no {fmt!r} file; give formats of {', '.join(sorted(self.formats))}"

    def beside(self, raw: dict[str, Any], folder: Path) -> dict[str, Any]:
        return raw
