"""One self-contained interactive HTML page a design: the mechanism running, its plots with a cursor, its figures.

A :class:`Page` is neutral data that camgen and linkgen assemble from a finished design and its report: a
:class:`Scene` (rigid :class:`Body` s turned and moved frame by frame, and :class:`Mover` s, polylines or circles
given frame by frame, all in mm with y up), :class:`Plot` s against the input, the report's key figures and
warnings, and the names of the other files written (added when the bundle is written, as the report's ``files``).
:func:`page_html` writes it as one HTML document: the drawing and the plots as inline SVG made here, the frames
as compact JSON and a few lines of JavaScript moving them with a slider and a play button; no server, no network.
:func:`family_html` puts the members of a family on one page at one scale, with a sortable table.

Nothing here computes kinematics: every pose is precomputed by the product (a few hundred frames).
"""
from __future__ import annotations

import html
import json
import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

#: frames a page's cycle is drawn at (one a degree for a full turn)
FRAMES = 360


@dataclass(frozen=True)
class Outline:
    """A polyline (n, 2) in mm in its body's frame, drawn in the CSS class ``style`` (``part``, ``hole``,
    ``groove``, ``pitch``, ``path``, ``ground``, ``guide``); closed or open."""

    points: np.ndarray
    style: str = "part"
    closed: bool = True


@dataclass(frozen=True)
class Body:
    """A rigid body: its outlines in its own frame and, frame by frame, its pose ``motion`` (frames, 3): turned by
    ``motion[:, 0]`` degrees counter-clockwise about its own origin, then moved by ``motion[:, 1:]`` mm; None for a
    body that stands still."""

    name: str
    outlines: tuple[Outline, ...]
    motion: np.ndarray | None = None


@dataclass(frozen=True)
class Mover:
    """Points given frame by frame in mm, ``points`` (frames, k, 2) (NaN where there is no pose): a polyline through
    them, or with ``radius`` > 0 a circle of that radius (mm) round each."""

    name: str
    points: np.ndarray
    style: str = "link"
    radius: float = 0.0
    closed: bool = False


@dataclass(frozen=True)
class Scene:
    """What the mechanism drawing shows: still and moving bodies, then movers drawn over them; ``view`` (x0, y0, x1,
    y1; mm) fixes the window, else it is the extent of everything over every frame."""

    bodies: tuple[Body, ...]
    movers: tuple[Mover, ...] = ()
    view: tuple[float, float, float, float] | None = None
    #: the rounding step (a power of ten; mm, and degrees for turns) of the frames' data the script moves them by;
    #: None: a 100000th of the drawing's size (and at most 1e-4 degrees)
    precision: float | None = None

    def bounds(self) -> tuple[float, float, float, float]:
        """The window (mm): ``view``, or the extent of every outline at every pose and every mover."""
        if self.view is not None:
            return self.view
        boxes = [_extent(_posed(o.points, b.motion)) for b in self.bodies for o in b.outlines]
        for m in self.movers:
            box = _extent(m.points.reshape(-1, 2))
            boxes.append((box[0] - m.radius, box[1] - m.radius, box[2] + m.radius, box[3] + m.radius))
        boxes = [b for b in boxes if all(math.isfinite(v) for v in b)]
        return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes), max(b[3] for b in boxes))


@dataclass(frozen=True)
class Plot:
    """One plot against the input: ``series`` (label, values a frame) in ``unit``, and horizontal reference lines
    ``marks`` (label, value), such as a limit."""

    title: str
    unit: str
    series: tuple[tuple[str, np.ndarray], ...]
    marks: tuple[tuple[str, float], ...] = ()


@dataclass(frozen=True)
class KeyFigure:
    """A figure of the report shown on the page: its ``label``, its dotted ``key`` in the report, its ``value`` as
    the report holds it, and its ``unit``."""

    label: str
    key: str
    value: Any
    unit: str = ""


@dataclass(frozen=True)
class Page:
    """An interactive page: ``inputs`` (frames,) the input's value at each frame, in ``input_unit`` (the slider's
    label), the ``scene`` moving through them, ``plots`` against them, the report's key ``figures``, its
    ``warnings``, ``notes`` saying what is not plotted and why, and the ``files`` written beside the page.
    ``cyclic``: the input turns round (play loops); else play runs to and fro over the range."""

    name: str
    title: str
    subtitle: str
    input_label: str
    input_unit: str
    inputs: np.ndarray
    scene: Scene
    plots: tuple[Plot, ...]
    figures: tuple[KeyFigure, ...]
    warnings: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    cyclic: bool = True
    files: dict[str, str] = field(default_factory=dict)

    def with_files(self, files: dict[str, str]) -> Page:
        """This page linking to ``files`` ({key: file name}), the bundle's files."""
        return replace(self, files=dict(files))

    def _repr_html_(self) -> str:
        return page_frame(self)


def key_figures(report: dict[str, Any], wanted: Iterable[tuple[str, str, str]]) -> tuple[KeyFigure, ...]:
    """The figures ``wanted`` (label, dotted key, unit) that ``report`` holds with a value (a scalar, or a list of
    them), in that order; a key's parts name a table's key or a list's index (``dyads.0.transmission_min_deg``)."""
    out = []
    for label, key, unit in wanted:
        value: Any = report
        for part in key.split("."):
            if isinstance(value, list) and part.isdigit() and int(part) < len(value):
                value = value[int(part)]
            else:
                value = value.get(part) if isinstance(value, dict) else None
        scalars = isinstance(value, list) and all(isinstance(v, (int, float, str)) for v in value)
        if value is not None and (scalars or not isinstance(value, (dict, list))):
            out.append(KeyFigure(label, key, value, unit))
    return tuple(out)


def pose_motion(turn_deg: np.ndarray, shift: np.ndarray | None = None) -> np.ndarray:
    """A body's ``motion`` (frames, 3) from its turns (degrees) and shifts (frames, 2; mm; none: 0)."""
    turn_deg = np.asarray(turn_deg, dtype=float)
    shift = np.zeros((len(turn_deg), 2)) if shift is None else np.asarray(shift, dtype=float)
    return np.column_stack([turn_deg, shift])


def _posed(points: np.ndarray, motion: np.ndarray | None) -> np.ndarray:
    """``points`` (n, 2) at every pose of ``motion``: (frames * n, 2)."""
    if motion is None:
        return points
    a = np.radians(motion[:, 0])[:, None]
    c, s = np.cos(a), np.sin(a)
    x, y = points[None, :, 0], points[None, :, 1]
    return np.stack([c * x - s * y + motion[:, 1:2], s * x + c * y + motion[:, 2:3]], axis=-1).reshape(-1, 2)


def _extent(points: np.ndarray) -> tuple[float, float, float, float]:
    finite = points[np.isfinite(points).all(axis=1)]
    if not len(finite):
        return (math.nan,) * 4
    return (float(finite[:, 0].min()), float(finite[:, 1].min()), float(finite[:, 0].max()), float(finite[:, 1].max()))


# ---------------------------------------------------------------------------------------------------------------
# writing

def _num(x: float, step: float) -> str:
    """``x`` rounded to a multiple of ``step`` (a power of ten), written short."""
    digits = max(0, -math.floor(math.log10(step)))
    text = f"{round(x, digits):.{digits}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _grid(scale: float) -> float:
    """The rounding step of coordinates in a drawing ``scale`` mm across: about 1/100000 of it, a power of ten."""
    return 10.0 ** math.floor(math.log10(max(scale, 1e-9) / 100000.0))


def _compact(values: np.ndarray, step: float) -> list[float | None]:
    """``values`` rounded to multiples of ``step`` for the page's JSON; NaN and infinities become null."""
    digits = max(0, -math.floor(math.log10(step)))
    flat = np.asarray(values, dtype=float).ravel()
    out: list[float | None] = []
    for v in np.round(flat, digits).tolist():
        out.append(None if not math.isfinite(v) else (int(v) if v == int(v) else v))
    return out


def _points(points: np.ndarray, step: float) -> str:
    return " ".join(f"{_num(x, step)},{_num(y, step)}" for x, y in points if math.isfinite(x) and math.isfinite(y))


def _path(outline: Outline, step: float) -> str:
    pts = outline.points
    d = "M" + " L".join(f"{_num(x, step)} {_num(y, step)}" for x, y in pts)
    return d + ("Z" if outline.closed else "")


def _transform(m: np.ndarray, step: float) -> str:
    return f"translate({_num(m[1], step)} {_num(m[2], step)}) rotate({_num(m[0], 1e-4)})"


def _scene_svg(scene: Scene, frame: int, box: tuple[float, float, float, float], css: str = "scene") -> str:
    """The scene at ``frame`` as an SVG element in mm, y up, within ``box`` (x0, y0, x1, y1)."""
    x0, y0, x1, y1 = box
    step = _grid(max(x1 - x0, y1 - y0))
    parts = [f'<svg class="{css}" viewBox="{_num(x0, step)} {_num(-y1, step)} {_num(x1 - x0, step)} '
             f'{_num(y1 - y0, step)}" preserveAspectRatio="xMidYMid meet" role="img">'
             '<g transform="scale(1,-1)">']
    for i, body in enumerate(scene.bodies):
        pose = "" if body.motion is None else f' transform="{_transform(body.motion[frame], step)}"'
        parts.append(f'<g class="body" data-body="{i}"{pose}><title>{html.escape(body.name)}</title>')
        parts += [f'<path class="{o.style}" d="{_path(o, step)}"/>' for o in body.outlines]
        parts.append("</g>")
    for i, m in enumerate(scene.movers):
        pts = m.points[frame]
        if m.radius > 0:
            circles = "".join(f'<circle class="{m.style}" cx="{_num(x, step)}" cy="{_num(y, step)}" '
                              f'r="{_num(m.radius, step)}"/>' for x, y in np.nan_to_num(pts, nan=0.0))
            parts.append(f'<g data-mover="{i}"><title>{html.escape(m.name)}</title>{circles}</g>')
        else:
            tag = "polygon" if m.closed else "polyline"
            parts.append(f'<{tag} class="{m.style}" data-mover="{i}" points="{_points(pts, step)}">'
                         f'<title>{html.escape(m.name)}</title></{tag}>')
    parts.append("</g></svg>")
    return "".join(parts)


def _scene_data(scene: Scene, box: tuple[float, float, float, float]) -> dict[str, Any]:
    step = _grid(max(box[2] - box[0], box[3] - box[1])) if scene.precision is None else scene.precision
    bodies = [None if b.motion is None else _compact(b.motion, min(step, 1e-4)) for b in scene.bodies]
    movers = [{"k": int(m.points.shape[1]), "r": m.radius > 0, "d": _compact(m.points, step)} for m in scene.movers]
    return {"bodies": bodies, "movers": movers}


def _ticks(lo: float, hi: float, count: int = 5) -> list[float]:
    """Round tick values covering [lo, hi]."""
    if not hi > lo:
        return [lo]
    raw = (hi - lo) / count
    base = 10.0 ** math.floor(math.log10(raw))
    step = next(m * base for m in (1, 2, 2.5, 5, 10) if m * base >= raw)
    first = math.ceil(lo / step - 1e-9) * step
    return [first + k * step for k in range(int((hi - first) / step + 1e-9) + 1)]


def _label(v: float) -> str:
    return f"{v:.6g}" if v != 0 else "0"


#: a plot's size in its SVG units (px at 100 %) and its margins: left, right, top, bottom
_W, _H, _ML, _MR, _MT, _MB = 560, 170, 62, 12, 22, 28


def _plot_svg(plot: Plot, inputs: np.ndarray, frame: int, input_label: str) -> str:
    """One plot as SVG: axes, ticks, each series as a polyline with a marker and the cursor at ``frame``."""
    xs = np.asarray(inputs, dtype=float)
    ys = [np.asarray(v, dtype=float) for _, v in plot.series]
    finite = np.concatenate([y[np.isfinite(y)] for y in ys] + [np.array([v for _, v in plot.marks], dtype=float)])
    lo, hi = (float(finite.min()), float(finite.max())) if len(finite) else (0.0, 1.0)
    if hi - lo < 1e-12 * max(1.0, abs(hi)):
        lo, hi = lo - 1.0, hi + 1.0
    pad = 0.06 * (hi - lo)
    lo, hi = lo - pad, hi + pad
    x0, x1 = float(xs[0]), float(xs[-1])
    px = lambda x: _ML + (x - x0) / (x1 - x0) * (_W - _ML - _MR)            # noqa: E731
    py = lambda y: _MT + (hi - y) / (hi - lo) * (_H - _MT - _MB)            # noqa: E731
    out = [f'<svg class="plot" viewBox="0 0 {_W} {_H}" data-x0="{_ML}" data-x1="{_W - _MR}">',
           f'<text class="ptitle" x="{_ML}" y="14">{html.escape(plot.title)} ({html.escape(plot.unit)})</text>',
           f'<rect class="frame" x="{_ML}" y="{_MT}" width="{_W - _ML - _MR}" height="{_H - _MT - _MB}"/>']
    for t in _ticks(lo, hi, 4):
        y = py(t)
        out.append(f'<line class="grid" x1="{_ML}" x2="{_W - _MR}" y1="{y:.1f}" y2="{y:.1f}"/>'
                   f'<text class="tick" x="{_ML - 4}" y="{y + 3.5:.1f}" text-anchor="end">{_label(t)}</text>')
    for t in _ticks(x0, x1, 8):
        x = px(t)
        out.append(f'<line class="grid" x1="{x:.1f}" x2="{x:.1f}" y1="{_MT}" y2="{_H - _MB}"/>'
                   f'<text class="tick" x="{x:.1f}" y="{_H - _MB + 13}" text-anchor="middle">{_label(t)}</text>')
    if lo < 0 < hi:
        out.append(f'<line class="zero" x1="{_ML}" x2="{_W - _MR}" y1="{py(0):.1f}" y2="{py(0):.1f}"/>')
    for label, value in plot.marks:
        y = py(value)
        out.append(f'<line class="mark" x1="{_ML}" x2="{_W - _MR}" y1="{y:.1f}" y2="{y:.1f}"><title>'
                   f'{html.escape(label)}</title></line>')
    for k, ((label, _), y) in enumerate(zip(plot.series, ys, strict=True)):
        clipped = np.clip(np.where(np.isfinite(y), y, np.nan), lo, hi)
        pts = " ".join(f"{px(x):.1f},{py(v):.1f}" if math.isfinite(v) else f"{px(x):.1f},{py(lo):.1f}"
                       for x, v in zip(xs, clipped, strict=True))
        out.append(f'<polyline class="series s{k}" points="{pts}"><title>{html.escape(label)}</title></polyline>')
    cx = px(float(xs[frame]))
    out.append(f'<line class="cursor" x1="{cx:.1f}" x2="{cx:.1f}" y1="{_MT}" y2="{_H - _MB}"/>')
    if len(plot.series) > 1:
        legend = "".join(f'<tspan class="l{k}">{"  " if k else ""}— {html.escape(label)}</tspan>'
                         for k, (label, _) in enumerate(plot.series))
        out.append(f'<text class="legend" x="{_W - _MR}" y="14" text-anchor="end">{legend}</text>')
    out.append(f'<text class="tick" x="{_W - _MR}" y="{_H - 2}" text-anchor="end">{html.escape(input_label)}</text>')
    out.append("</svg>")
    return "".join(out)


def _value(v: Any) -> str:
    if isinstance(v, list):
        return ", ".join(_value(x) for x in v)
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def _figures_table(figures: Sequence[KeyFigure]) -> str:
    rows = "".join(f'<tr data-key="{html.escape(f.key)}"><th>{html.escape(f.label)}</th>'
                   f'<td class="num">{html.escape(_value(f.value))}</td><td>{html.escape(f.unit)}</td></tr>'
                   for f in figures)
    return f'<table class="figures">{rows}</table>'


def _list(items: Iterable[str], css: str, empty: str) -> str:
    items = list(items)
    if not items:
        return f'<p class="{css} none">{html.escape(empty)}</p>'
    return f'<ul class="{css}">' + "".join(f"<li>{html.escape(i)}</li>" for i in items) + "</ul>"


def _files(files: dict[str, str], own: str) -> str:
    links = [f'<li><a href="{html.escape(name)}">{html.escape(name)}</a></li>' for key, name in files.items()
             if name != own]
    if not links:
        return '<p class="none">no other files written (a design shown before it is written)</p>'
    return '<ul class="files">' + "".join(links) + "</ul>"


def _shown(page: Page, frame: int) -> str:
    return f"{_label(round(float(page.inputs[frame]), 4))} {page.input_unit}"


#: what the animate control says where no GIF was written beside the page
ANIMATE_HOW = ('no animation written beside this page: add "gif" to output.formats and build again, or run camgen '
               'animate (a cam, a Geneva drive, a machine) or linkgen animate (a linkage) on the template')


def _animate(files: dict[str, str]) -> str:
    """The animate control: a link offering the GIF written beside the page (the bundle's file of key ``gif``, as
    ``animate`` writes it with its defaults), or a disabled button saying how to make one."""
    name = files.get("gif")
    if name is not None:
        return f'<a id="animate" class="animate" href="{html.escape(name)}" download="{html.escape(name)}">Animate</a>'
    return (f'<button id="animate" type="button" disabled title="{html.escape(ANIMATE_HOW)}">Animate</button>'
            f'<span class="animate-how">{html.escape(ANIMATE_HOW)}</span>')


def _controls(page: Page) -> str:
    n = len(page.inputs)
    return (f'<div class="controls"><button id="play" type="button">Play</button>'
            f'<label for="frame">{html.escape(page.input_label)}</label>'
            f'<input id="frame" type="range" min="0" max="{n - 1}" step="1" value="0">'
            f'<output id="shown">{html.escape(_shown(page, 0))}</output>{_animate(page.files)}</div>')


def _data(page: Page, box: tuple[float, float, float, float]) -> dict[str, Any]:
    """What the page's script reads: the inputs, the scene's frames (rounded for a drawing as large as ``box``), and
    the figures as the report holds them."""
    values = np.asarray(page.inputs, dtype=float)
    return {"unit": page.input_unit, "cyclic": page.cyclic, "inputs": _compact(values, 1e-4),
            "scenes": [_scene_data(page.scene, box)], "figures": {f.key: f.value for f in page.figures}}


def _embed(data: dict[str, Any]) -> str:
    """``data`` as JSON safe inside a <script> element."""
    text = json.dumps(data, separators=(",", ":"), allow_nan=False, ensure_ascii=False)
    return text.replace("</", "<\\/")


def _padded(box: tuple[float, float, float, float], by: float = 0.04) -> tuple[float, float, float, float]:
    w, h = box[2] - box[0], box[3] - box[1]
    m = by * max(w, h, 1e-6)
    return (box[0] - m, box[1] - m, box[2] + m, box[3] + m)


def page_body(page: Page) -> str:
    """The page's <body> content (without the script's data)."""
    view = _padded(page.scene.bounds())
    scene = replace(page.scene, view=view)
    plots = "".join(_plot_svg(p, page.inputs, 0, f"{page.input_label} ({page.input_unit})") for p in page.plots)
    notes = "".join(f'<p class="note">{html.escape(n)}</p>' for n in page.notes)
    return (f'<header><h1>{html.escape(page.title)}</h1><p class="sub">{html.escape(page.subtitle)}</p></header>'
            f'<main><section class="stage">{_scene_svg(scene, 0, view)}{_controls(page)}</section>'
            f'<section class="plots">{plots}{notes}</section>'
            f'<section class="facts"><h2>Key figures</h2>{_figures_table(page.figures)}'
            f'<h2>Warnings</h2>{_list(page.warnings, "warnings", "none")}'
            f'<h2>Files</h2>{_files(page.files, page.name + ".html")}</section></main>')


def _document(title: str, body: str, data: dict[str, Any]) -> str:
    return ("<!DOCTYPE html>\n"
            f'<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width">'
            f'<meta name="generator" content="camgen"><title>{html.escape(title)}</title>'
            f"<style>{CSS}</style></head><body>{body}"
            f'<script type="application/json" id="page-data">{_embed(data)}</script>'
            f"<script>{SCRIPT}</script></body></html>\n")


def page_html(page: Page) -> str:
    """``page`` as one self-contained HTML document (inline SVG, CSS, JSON and script; nothing fetched)."""
    return _document(page.title, page_body(page), _data(page, _padded(page.scene.bounds())))


def page_frame(page: Page, height_px: int = 900) -> str:
    """``page`` inline in a notebook: an <iframe> holding the document (its script and styles kept to itself)."""
    return (f'<iframe srcdoc="{html.escape(page_html(page), quote=True)}" style="width:100%;height:{height_px}px;'
            f'border:1px solid #ccc" sandbox="allow-scripts" title="{html.escape(page.title)}"></iframe>')


def bundle_frame(bundle: Any) -> str | None:
    """The page a bundle (:class:`camgen.core.bundle.Bundle`) writes as html, inline for a notebook (see
    :func:`page_frame`); None when it writes no page. Only the page is made, not the bundle's other files."""
    for it in bundle.items:
        if any(entry.format == "html" for entry in it.entries):
            page = it.payload() if callable(it.payload) else it.payload
            return page_frame(page)
    return None


# ---------------------------------------------------------------------------------------------------------------
# families

@dataclass(frozen=True)
class Member:
    """A family member on the family's page: its ``name``, the ``link`` to its own page (relative; None when it
    wrote none), its swept values, its summary ``row`` (status, error, key figures) and its page's text (None when
    it failed or wrote no page)."""

    name: str
    link: str | None
    swept: dict[str, Any]
    row: dict[str, Any]
    page: str | None


def _sort_key(member: Member) -> tuple:
    """Members by their swept values in order (numbers as numbers), then by name."""
    key = []
    for v in member.swept.values():
        key.append((0, float(v), "") if isinstance(v, (int, float)) and not isinstance(v, bool) else (1, 0.0, str(v)))
    return (*key, member.name)


_SCENE = re.compile(r'<svg class="scene" viewBox="([^"]+)"(.*?)</svg>', re.S)
_DATA = re.compile(r'<script type="application/json" id="page-data">(.*?)</script>', re.S)


def read_page(text: str) -> tuple[tuple[float, float, float, float], str, dict[str, Any], list[str]]:
    """What a family's page takes from a member's page (as :func:`page_html` wrote it): its drawing's window (x0,
    y0, x1, y1; mm), the drawing's SVG after its viewBox, the script's data and the warnings."""
    scene, data = _SCENE.search(text), _DATA.search(text)
    if scene is None or data is None:
        raise ValueError("not a page written by camgen.core.page")
    x, top, w, h = (float(v) for v in scene.group(1).split())
    warnings = re.search(r'<ul class="warnings">(.*?)</ul>', text, re.S)
    items = re.findall(r"<li>(.*?)</li>", warnings.group(1), re.S) if warnings else []
    return ((x, -top - h, x + w, -top), scene.group(2), json.loads(data.group(1).replace("<\\/", "</")),
            [html.unescape(i) for i in items])


def family_html(title: str, members: Sequence[Member], columns: Sequence[str]) -> str:
    """The family's page: every member's mechanism at one common scale (each drawing as wide as the widest),
    sorted by the swept values, one slider and play button driving them all frame by frame, and a table of
    ``columns`` of the members' rows with their warnings, sortable by any column (click its head)."""
    ordered = sorted(members, key=_sort_key)
    read = {m.name: read_page(m.page) for m in ordered if m.page is not None}
    span = max((max(b[2] - b[0], b[3] - b[1]) for b, _, _, _ in read.values()), default=1.0)
    step = _grid(span)
    cards, scenes, first = [], [], None
    for m in ordered:
        swept = ", ".join(f"{k} = {_value(v)}" for k, v in m.swept.items())
        name = f'<a href="{html.escape(m.link)}">{html.escape(m.name)}</a>' if m.link else html.escape(m.name)
        head = f'<h3>{name}</h3><p class="sub">{html.escape(swept)}</p>'
        if m.name not in read:
            why = m.row.get("error") or "no page written"
            cards.append(f'<div class="card failed">{head}<p class="warnings">{html.escape(str(why))}</p></div>')
            continue
        box, svg, data, warnings = read[m.name]
        first = first or data
        cx, cy = (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
        view = f"{_num(cx - span / 2, step)} {_num(-cy - span / 2, step)} {_num(span, step)} {_num(span, step)}"
        scenes.append(data["scenes"][0])
        count = f'{len(warnings)} warning{"s" if len(warnings) != 1 else ""}'
        cards.append(f'<div class="card"><svg class="scene" viewBox="{view}"{svg}</svg>{head}'
                     f'<p class="sub">{count}</p></div>')
    header = "".join(f'<th data-col="{i}">{html.escape(c)}</th>'
                     for i, c in enumerate(["member", *columns, "warnings"]))
    rows = []
    for m in ordered:
        link = f'<a href="{html.escape(m.link)}">{html.escape(m.name)}</a>' if m.link else html.escape(m.name)
        cells = [f"<td>{link}</td>"]
        for c in (*columns,):
            v = m.row.get(c, m.swept.get(c))
            num = isinstance(v, (int, float)) and not isinstance(v, bool)
            text = "" if v is None else _value(v)
            cells.append(f'<td{" class=num" if num else ""} data-v="{html.escape(str(v if v is not None else ""))}">'
                         f"{html.escape(text)}</td>")
        warnings = read[m.name][3] if m.name in read else []
        cells.append(f'<td data-v="{len(warnings)}">{html.escape("; ".join(warnings))}</td>')
        rows.append("<tr>" + "".join(cells) + "</tr>")
    controls = ""
    if first is not None:
        controls = ('<div class="controls"><button id="play" type="button">Play</button><label for="frame">input'
                    f'</label><input id="frame" type="range" min="0" max="{len(first["inputs"]) - 1}" step="1" '
                    f'value="0"><output id="shown"></output></div>')
    body = (f'<header><h1>{html.escape(title)}</h1><p class="sub">{len(members)} members, drawn at one scale '
            f'({_label(round(span, 3))} mm across each drawing), sorted by their swept values</p></header>'
            f'<main class="family">{controls}<section class="cards">{"".join(cards)}</section>'
            f'<section class="facts"><h2>Members</h2><table class="members sortable"><thead><tr>{header}</tr></thead>'
            f'<tbody>{"".join(rows)}</tbody></table></section></main>')
    data = {"unit": first["unit"] if first else "", "cyclic": first["cyclic"] if first else True,
            "inputs": first["inputs"] if first else [0], "scenes": scenes, "figures": {}}
    return _document(title, body, data)


CSS = """
body{font:14px/1.4 system-ui,sans-serif;margin:0;color:#222;background:#fafafa}
header{padding:10px 18px;background:#fff;border-bottom:1px solid #ddd}h1{font-size:20px;margin:0}
h2{font-size:15px;margin:14px 0 6px}h3{font-size:14px;margin:4px 0 0}.sub{color:#555;margin:2px 0}
main{display:grid;grid-template-columns:minmax(320px,1fr) minmax(320px,600px);gap:14px;padding:14px}
main.family{display:block}.stage{grid-row:span 2;align-self:start;position:sticky;top:0;background:#fff;
border:1px solid #ddd;padding:8px}
svg.scene{width:100%;height:auto;max-height:70vh;display:block;background:#fff}
svg.scene path,svg.scene polyline,svg.scene polygon,svg.scene circle{vector-effect:non-scaling-stroke;
stroke-width:1.5px;stroke-linejoin:round;fill:none}
.part{fill:#d9e6f2!important;stroke:#1f4e79}.hole{fill:#fff!important;stroke:#1f4e79}
.groove{fill:#f3c6f3!important;stroke:#a020a0}.second{fill:rgba(253,208,162,.6)!important;stroke:#e6550d}.wall{stroke:#a020a0}.island{fill:#d9e6f2!important;stroke:#1f4e79}
.pitch{stroke:#888;stroke-dasharray:4 3}.path{stroke:#999}.tracer{stroke:#d62728!important;stroke-width:1px!important}
.ground{fill:#ccc!important;stroke:#444}.guide{stroke:#444;stroke-dasharray:6 3}.wheel{fill:#cfe3f7!important;
stroke:#1f77b4}.lock{fill:#fde0c2!important;stroke:#e6550d}.crank{stroke:#666;stroke-dasharray:3 2}
.follower{stroke:#2a7f2a;stroke-width:3px!important}.roller{fill:#bfe3bf!important;stroke:#2a7f2a}
.link{stroke:#1f4e79;stroke-width:4px!important;stroke-linecap:round}.plate{fill:rgba(31,78,121,.15)!important;
stroke:#1f4e79}.joint{fill:#fff!important;stroke:#222}.pin{fill:#d62728!important;stroke:#900}
.controls{display:flex;gap:10px;align-items:center;padding:8px 0}.controls input{flex:1}
button{font:inherit;padding:4px 14px}output{min-width:90px;text-align:right;font-variant-numeric:tabular-nums}
.plots{display:flex;flex-direction:column;gap:6px}svg.plot{width:100%;height:auto;background:#fff;
border:1px solid #ddd}svg.plot .frame{fill:none;stroke:#999}.grid{stroke:#eee}.zero{stroke:#aaa}
.mark{stroke:#d62728;stroke-dasharray:5 3}.series{fill:none;stroke-width:1.5}.s0{stroke:#1f77b4}
.s1{stroke:#ff7f0e}.s2{stroke:#2ca02c}.s3{stroke:#9467bd}.l0{fill:#1f77b4}.l1{fill:#ff7f0e}.l2{fill:#2ca02c}
.l3{fill:#9467bd}.cursor{stroke:#d62728;stroke-width:1.5}.tick,.legend{font-size:10px;fill:#555}
.ptitle{font-size:12px;font-weight:600;fill:#222}
.facts{background:#fff;border:1px solid #ddd;padding:4px 12px;overflow-x:auto}
table{border-collapse:collapse}th,td{padding:2px 8px;border-bottom:1px solid #eee;text-align:left}
td.num{text-align:right;font-variant-numeric:tabular-nums}.warnings li,p.warnings{color:#a40000}
.none{color:#777!important}.note{color:#555;font-style:italic;margin:2px 4px}
.animate{padding:4px 14px;border:1px solid #888;border-radius:3px;text-decoration:none;color:inherit}
.animate-how{color:#555;font-size:12px;flex-basis:100%}.controls{flex-wrap:wrap}
.cards{display:flex;flex-wrap:wrap;gap:10px}.card{background:#fff;border:1px solid #ddd;padding:6px;width:230px}
.card svg.scene{height:200px}.card.failed{background:#fff0f0}table.sortable th{cursor:pointer;user-select:none}
"""

SCRIPT = """
(function(){
"use strict";
var D=JSON.parse(document.getElementById("page-data").textContent);
var slider=document.getElementById("frame"),shown=document.getElementById("shown"),play=document.getElementById("play");
var scenes=document.querySelectorAll("svg.scene"),plots=document.querySelectorAll("svg.plot");
var n=D.inputs.length,frame=0,dir=1,timer=null;
function fmt(v){return v===null?"-":String(Math.round(v*1e4)/1e4);}
function setPoints(el,d,at,k){var p=[];for(var j=0;j<k;j++){var x=d[at+2*j],y=d[at+2*j+1];
 if(x===null||y===null){el.style.visibility="hidden";return;}p.push(x+","+y);}
 el.style.visibility="";el.setAttribute("points",p.join(" "));}
function show(i){
 frame=i;
 D.scenes.forEach(function(s,k){var svg=scenes[k];if(!svg)return;
  s.bodies.forEach(function(m,j){if(!m)return;var g=svg.querySelector('[data-body="'+j+'"]');
   g.setAttribute("transform","translate("+m[3*i+1]+" "+m[3*i+2]+") rotate("+m[3*i]+")");});
  s.movers.forEach(function(m,j){var el=svg.querySelector('[data-mover="'+j+'"]'),at=i*m.k*2;
   if(!m.r){setPoints(el,m.d,at,m.k);return;}
   var cs=el.querySelectorAll("circle");for(var c=0;c<m.k;c++){var x=m.d[at+2*c],y=m.d[at+2*c+1];
    cs[c].style.visibility=(x===null||y===null)?"hidden":"";if(x!==null&&y!==null){cs[c].setAttribute("cx",x);
    cs[c].setAttribute("cy",y);}}});});
 plots.forEach(function(svg){var x0=+svg.dataset.x0,x1=+svg.dataset.x1,x=x0+(x1-x0)*(n>1?i/(n-1):0);
  svg.querySelectorAll(".cursor").forEach(function(c){c.setAttribute("x1",x);c.setAttribute("x2",x);});});
 if(slider)slider.value=i;
 if(shown)shown.textContent=fmt(D.inputs[i])+" "+D.unit;
}
function step(){var i=frame+dir;
 if(D.cyclic){i=(i+n)%n;}else if(i<0||i>=n){dir=-dir;i=frame+dir;}
 show(Math.max(0,Math.min(n-1,i)));}
if(slider)slider.addEventListener("input",function(){show(+slider.value);});
if(play)play.addEventListener("click",function(){
 if(timer){clearInterval(timer);timer=null;play.textContent="Play";}
 else{timer=setInterval(step,1000/60);play.textContent="Pause";}});
document.querySelectorAll("table.sortable").forEach(function(t){
 t.querySelectorAll("th").forEach(function(th){th.addEventListener("click",function(){
  var c=+th.dataset.col,body=t.tBodies[0],rows=Array.prototype.slice.call(body.rows),up=th.dataset.up!=="1";
  rows.sort(function(a,b){var x=a.cells[c].dataset.v||a.cells[c].textContent,
   y=b.cells[c].dataset.v||b.cells[c].textContent,nx=parseFloat(x),ny=parseFloat(y);
   var r=(!isNaN(nx)&&!isNaN(ny))?nx-ny:String(x).localeCompare(String(y));return up?r:-r;});
  th.dataset.up=up?"1":"0";rows.forEach(function(r){body.appendChild(r);});});});});
window.camgenPage={show:show,frames:n};
show(0);
})();
"""
