"""One writer a format, behind one registry, for every product.

A writer serialises one finished payload into one file and computes nothing: no
kinematics, no searches, no template reading. Formats and the payload each takes:

=========  ==================================================  ===========================
format     file                                                payload
=========  ==================================================  ===========================
dxf        DXF (flavour and version from :class:`WriteOptions`)  :class:`~camgen.core.parts.Drawing`
cut-svg    SVG in mm for laser software (hairline strokes)     :class:`~camgen.core.parts.Drawing`
stl        binary STL                                          :class:`~camgen.core.solids.Mesh`
3mf        3MF package (millimetres)                           :class:`~camgen.core.solids.Mesh`
json       the report, ``indent=2``, no NaN                    ``dict``
png, svg   a figure (matplotlib)                               ``matplotlib.figure.Figure``
html       the design's interactive page, self-contained       :class:`~camgen.core.page.Page`
step       STEP AP214 (mm), exact solids, each part named      ``(name, parts)`` pairs (see
                                                               :mod:`~camgen.core.writers.step`)
csv        a table, with the JSON report                       rows (dicts), or a finished text
toml       a template, with the JSON report                    a finished text
gif        one cycle as ``animate`` writes it by default        frames (n, height, width, 3) uint8
           (``<name>-animation.gif``; only when asked)
=========  ==================================================  ===========================

Each format is one :class:`Format` line of :data:`REGISTRY`: its writer's module and how its files are named for
each payload role; :mod:`camgen.core.bundle`'s constructors name every bundle's files from it, and the tuples below
and the type of ``output.formats`` are derived from it. Writers are imported only when a file of their format is
written, so a JSON-only build never loads ezdxf, trimesh or matplotlib. ``step`` is an optional format: it needs
the ``step`` extra (Open CASCADE through OCP) and is never written unless ``output.formats`` names it.
"""
from __future__ import annotations

import importlib
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, cast, get_args

#: what a format's writer takes, by the role it plays in a bundle: a part's drawing (its cut files), a sheet's or an
#: assembly's drawing, a mesh (or placed meshes), exact solids, a figure, a report, a page, rows of a table, a text
Role = Literal["part", "sheet", "mesh", "solids", "figure", "report", "page", "rows", "text", "animation"]


@dataclass(frozen=True)
class Format:
    """One output format: what ``output.formats`` calls it, its writer and how its files are named.

    Attributes
    ----------
    name : str
        The format's name in ``output.formats`` (``"dxf"``, ``"cut-svg"``).
    module : str
        The module holding its writer (``WRITERS[name]``), imported only when a file of the format is written: a
        name under :mod:`camgen.core.writers` (``"dxf"``) or a full dotted path.
    files : mapping of Role to (str, str)
        For each payload role the format writes: the file name's ending after the stem (``"-cut.svg"``) and the
        report key's ending after the key's prefix (``"cut_svg"``, joined with ``_``: ``"cam1_cut_svg"``).
    extra : (str, str, str), optional
        For an optional format: the module it needs, what that module is, and the install command.
    follows : str, optional
        The format it is written with, for one nobody chooses on its own (a kit's CSV goes with the JSON report).
    """

    name: str
    module: str
    files: Mapping[Role, tuple[str, str]]
    extra: tuple[str, str, str] | None = None
    follows: str | None = None

    def writer(self) -> Writer:
        """The format's writer: ``writer(payload, path, options)``."""
        module = self.module if "." in self.module else f"camgen.core.writers.{self.module}"
        return cast(Writer, importlib.import_module(module).WRITERS[self.name])


#: every format, one line each, in the order a payload's files are listed; the formats' tuples, the extras and the
#: type of ``output.formats`` are derived from it (:func:`register` adds one, e.g. a plugin's)
REGISTRY: dict[str, Format] = {f.name: f for f in (
    Format("dxf", "dxf", {"part": (".dxf", "dxf"), "sheet": (".dxf", "dxf")}),
    Format("cut-svg", "svg", {"part": ("-cut.svg", "cut_svg"), "sheet": (".svg", "svg")}),
    Format("stl", "stl", {"mesh": (".stl", "stl")}),
    Format("3mf", "threemf", {"mesh": (".3mf", "3mf")}),
    Format("json", "report", {"report": (".json", "json")}),
    Format("png", "figure", {"figure": (".png", "png")}),
    Format("svg", "figure", {"figure": (".svg", "svg")}),
    Format("html", "html", {"page": (".html", "html")}),
    Format("step", "step", {"solids": (".step", "step")},
           extra=("OCP", "Open CASCADE through OCP", "pip install 'camgen[step]'")),
    Format("csv", "report", {"rows": (".csv", "csv")}, follows="json"),
    Format("toml", "text", {"text": (".toml", "toml")}, follows="json"),
    Format("gif", "animation", {"animation": ("-animation.gif", "gif")}),
)}


#: every format ``output.formats`` can name without an extra, in the order their files are listed
FORMATS: tuple[str, ...] = ()
#: the figures drawn by matplotlib: written on request (``output.figures``, ``--figures``, or named in
#: ``output.formats``), since drawing them costs more than the rest of a build; the page plots the same curves
FIGURE_FORMATS: tuple[str, ...] = ()
#: what a build writes unless ``output.formats`` says otherwise: every format but the figures and the animation
DEFAULT_FORMATS: tuple[str, ...] = ()
#: formats a bundle writes only when asked and only with an optional extra installed: {format: (the module it
#: needs, what that module is, the install command)}
EXTRAS: dict[str, tuple[str, str, str]] = {}
#: the keys of :data:`EXTRAS`
OPTIONAL_FORMATS: tuple[str, ...] = ()
#: the keys of the bundled :data:`EXTRAS`, written out for the type checker
OptionalFormat = Literal["step"]


def _derive() -> None:
    """Set the tuples above from :data:`REGISTRY`."""
    global FORMATS, FIGURE_FORMATS, DEFAULT_FORMATS, EXTRAS, OPTIONAL_FORMATS
    lines = REGISTRY.values()
    FORMATS = tuple(f.name for f in lines if f.extra is None and f.follows is None)
    FIGURE_FORMATS = tuple(f.name for f in lines if "figure" in f.files)
    DEFAULT_FORMATS = tuple(f for f in FORMATS if f not in FIGURE_FORMATS and "animation" not in REGISTRY[f].files)
    EXTRAS = {f.name: f.extra for f in lines if f.extra is not None}
    OPTIONAL_FORMATS = tuple(EXTRAS)


def register(fmt: Format) -> Format:
    """Add ``fmt`` to :data:`REGISTRY` (after the others; one of the same name is replaced) and return it.

    The tuples of formats and the type of ``output.formats`` follow; modules that have already read them
    (:mod:`camgen.core.spec` when imported) keep what they read, so a plugin registers its format before it loads
    the specs. Every bundle writes ``fmt`` for the payload roles it names (``fmt.files``), when asked for it."""
    REGISTRY[fmt.name] = fmt
    _derive()
    return fmt


_derive()
DxfFlavour = Literal["polyline-bulge", "lines-arcs", "segments"]
DXF_FLAVOURS: tuple[DxfFlavour, ...] = get_args(DxfFlavour)
DxfVersion = Literal["R2010", "R12"]
DXF_VERSIONS: tuple[DxfVersion, ...] = get_args(DxfVersion)
#: how engraved text is written: TEXT entities (SVG <text>), or the glyphs' outlines for laser software that drops text
TextMode = Literal["text", "outline"]
TEXT_MODES: tuple[TextMode, ...] = get_args(TextMode)


@dataclass(frozen=True)
class WriteOptions:
    """Settings of the writers that are the user's choice, not the result's (the tolerance travels with the
    drawing, the allowances with the part)."""

    dxf_version: DxfVersion = "R2010"
    dxf_flavour: DxfFlavour = "polyline-bulge"
    text: TextMode = "text"


Writer = Callable[[Any, Path, WriteOptions], None]


def missing_extra(formats: Iterable[str]) -> str | None:
    """Why one of ``formats`` cannot be written here (its extra is not installed), in one line; None when all
    can. Imports the extra's module (once) to find out."""
    for fmt in formats:
        if fmt in EXTRAS:
            module, what, command = EXTRAS[fmt]
            try:
                importlib.import_module(module)
            except ImportError:
                return (f"{fmt!r} needs the optional {fmt} extra ({what}), which is not installed: {command} "
                        f"(from a checkout: pip install '.[{fmt}]')")
    return None


def writer(fmt: str) -> Writer:
    """The writer of format ``fmt`` (one of :data:`REGISTRY`): ``writer(fmt)(payload, path, options)``."""
    return REGISTRY[fmt].writer()
