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
=========  ==================================================  ===========================

Writers are imported only when a file of their format is written, so a JSON-only
build never loads ezdxf, trimesh or matplotlib. ``step`` is an optional format: it needs the ``step`` extra
(Open CASCADE through OCP) and is never written unless ``output.formats`` names it.
"""
from __future__ import annotations

import importlib
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, get_args

#: every format a bundle can write, in the order their files are listed
Format = Literal["dxf", "cut-svg", "stl", "3mf", "json", "png", "svg", "html"]
FORMATS: tuple[Format, ...] = get_args(Format)
#: the figures drawn by matplotlib: written on request (``output.figures``, ``--figures``, or named in
#: ``output.formats``), since drawing them costs more than the rest of a build; the page plots the same curves
FIGURE_FORMATS = ("png", "svg")
#: what a build writes unless ``output.formats`` says otherwise: every format but the figures
DEFAULT_FORMATS = tuple(f for f in FORMATS if f not in FIGURE_FORMATS)
DxfFlavour = Literal["polyline-bulge", "lines-arcs", "segments"]
DXF_FLAVOURS: tuple[DxfFlavour, ...] = get_args(DxfFlavour)
DxfVersion = Literal["R2010", "R12"]
DXF_VERSIONS: tuple[DxfVersion, ...] = get_args(DxfVersion)
#: how engraved text is written: TEXT entities (SVG <text>), or the glyphs' outlines for laser software that drops text
TextMode = Literal["text", "outline"]
TEXT_MODES: tuple[TextMode, ...] = get_args(TextMode)

#: formats a bundle writes only when asked and only with an optional extra installed: {format: (the module it
#: needs, what that module is, the install command)}
EXTRAS = {"step": ("OCP", "Open CASCADE through OCP", "pip install 'camgen[step]'")}
#: the keys of :data:`EXTRAS`, written out for the type checker
OptionalFormat = Literal["step"]
OPTIONAL_FORMATS = tuple(EXTRAS)

_MODULES = {"dxf": "dxf", "cut-svg": "svg", "stl": "stl", "3mf": "threemf", "json": "report", "png": "figure",
            "svg": "figure", "html": "html", "step": "step", "csv": "report"}


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
    """The writer of format ``fmt`` (one of :data:`FORMATS`): ``writer(fmt)(payload, path, options)``."""
    module = importlib.import_module(f"camgen.core.writers.{_MODULES[fmt]}")
    return module.WRITERS[fmt]
