"""The construction drawn (matplotlib's object API, imported only when it is drawn): the displacement diagram above,
its abscissa the reference circle's perimeter, its stations numbered; the construction below at the drawing's
scale: the reference circle divided into the same stations, the follower at each inverted position with its
displacement laid off, the pitch curve through the stations (a flat face's contact points) and the cam's profile.

Each station's number on the construction is an SVG element of its own id, ``station-<number>`` (the diagram's
``diagram-station-<number>``), so that a file can be read back station by station.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from camgen.construction.geometry import Construction, construct
from camgen.core.bundle import Item, figure_files
from camgen.core.figures import PREVIEW_TOLERANCE_MM, figure

#: the figure's width, the diagram's height, the margins (inches): left, right, top, between the panels, foot
_WIDTH, _DIAGRAM, _LEFT, _RIGHT, _TOP, _GAP, _FOOT = 10.0, 2.1, 0.75, 0.3, 1.05, 0.85, 0.95
#: the tallest the construction's panel is drawn (inches)
_MAX_PANEL = 9.0
#: the colours: the follower at its stations, the points laid off, the stations' numbers
_FOLLOWER, _POINT, _NUMBER = "C2", "C3", "0.15"
#: how the reference circle is named in the figure, by follower
_CIRCLE = {"translating-roller": "prime circle", "knife-edge": "base (prime) circle", "translating-flat": "base circle",
           "oscillating-roller": "prime circle", "oscillating-flat": "base circle"}


def construction_files(design: Any) -> tuple[Item, ...]:
    """The construction's files of ``design`` (a disc cam's) for the bundle: ``<name>-construction.png`` and
    ``.svg`` (report keys ``construction_png``, ``construction_svg``), drawn only when written. The disc kind's
    (:meth:`camgen.kinds.base.Kind.construction`): the other kinds refuse ``--construction`` in one line."""
    name = design.spec.name
    got = figure_files(lambda: construction_figure(design), f"{name}-construction", "construction")
    return (got,) if got is not None else ()


def construction_figure(design: Any) -> Any:
    """The construction of ``design`` (a disc cam's, see :func:`camgen.construction.geometry.construct`) with its
    profile as made (the nominal outline), titled by the design's name."""
    c = construct(design.cam)
    ring = design.outline.contour.flatten(max(design.tolerance, PREVIEW_TOLERANCE_MM))
    rotation = "ccw" if c.sense > 0 else "cw"
    return draw_construction(c, ring, f"{design.spec.name}: graphical construction ({c.follower} follower, "
                                      f"cam {rotation}, follower inverted {'cw' if c.sense > 0 else 'ccw'})")


def draw_construction(c: Construction, profile: np.ndarray, title: str) -> Any:
    """The figure of construction ``c`` with the cam's ``profile`` (m, 2) (mm, a closed ring) and ``title``."""
    fig = figure(_WIDTH, 8.0, layout=None)
    top = fig.add_axes((0, 0, 1, 1))
    _diagram(top, c)
    ax = fig.add_axes((0, 0, 1, 1))
    _construction(ax, c, profile)
    handles, labels = ax.get_legend_handles_labels()
    rows = math.ceil(len(labels) / 3)
    box = _box(ax)
    width = _WIDTH - _LEFT - _RIGHT
    panel = width * (box[3] - box[1]) / (box[2] - box[0])
    if panel > _MAX_PANEL:                              # a tall drawing: a narrower panel
        width *= _MAX_PANEL / panel
        panel = _MAX_PANEL
    foot = _FOOT + 0.22 * rows
    height = _TOP + _DIAGRAM + _GAP + panel + foot
    fig.set_size_inches(_WIDTH, height)
    full = _WIDTH - _LEFT - _RIGHT
    top.set_position((_LEFT / _WIDTH, (height - _TOP - _DIAGRAM) / height, full / _WIDTH, _DIAGRAM / height))
    ax.set_position(((_LEFT + (full - width) / 2) / _WIDTH, foot / height, width / _WIDTH, panel / height))
    ax.set_xlim(box[0], box[2])
    ax.set_ylim(box[1], box[3])
    ax.set_aspect("equal")
    fig.legend(handles, labels, loc="lower center", ncols=3, fontsize=8)
    fig.suptitle(title, fontsize=11, y=1 - 0.12 / height)
    return fig


def _box(ax: Any) -> tuple[float, float, float, float]:
    """The region of everything drawn on ``ax`` with a margin of 4 % (mm)."""
    x0, y0, x1, y1 = ax.dataLim.extents
    pad = 0.04 * max(x1 - x0, y1 - y0)
    return x0 - pad, y0 - pad, x1 + pad, y1 + pad


def _unit(c: Construction) -> str:
    return "mm" if c.lift_unit == "mm" else "deg"


def _diagram(ax: Any, c: Construction) -> None:
    """The displacement diagram: s against the arc along the reference circle (mm), the stations' ordinates (the
    displacements laid off) and numbers, the segments' starts marked, cam angle on the top axis."""
    st, curve = c.stations, c.curve
    x, perimeter = c.arc(st.theta), 2 * math.pi * c.radius
    ax.plot(c.arc(curve.theta), curve.s, color="C0", lw=1.2)
    ax.vlines(x, 0.0, st.s, color=_POINT, lw=0.8)
    ax.plot(x, st.s, "o", color=_POINT, ms=3)
    ax.axhline(0.0, color="0.5", lw=0.6)
    low = float(min(0.0, curve.s.min()))
    high = float(max(curve.s.max(), 1e-9))
    span = high - low
    for k, (at, start) in enumerate(zip(x, c.boundary, strict=True)):
        if start:
            ax.axvline(at, color="0.8", lw=0.6, zorder=0)
        ax.text(at, low - 0.06 * span, str(k), ha="center", va="top", fontsize=7, color=_NUMBER,
                fontweight="bold" if start else "normal", gid=f"diagram-station-{k}")
    ax.set_xlim(0.0, perimeter)
    ax.set_ylim(low - 0.3 * span, high + 0.12 * span)
    ax.set_yticks([t for t in ax.get_yticks() if low - 1e-9 * span <= t <= high + 1e-9 * span])  # none by the numbers
    ax.set_xlabel(f"arc along the {_CIRCLE[c.follower]} (mm): its perimeter 2π·{c.radius:.4g} = {perimeter:.4g} mm")
    what = "s" if c.lift_unit == "mm" else "ψ"
    ax.set_ylabel(f"{what} ({_unit(c)})")
    ax.grid(alpha=0.3)
    turn = ax.secondary_xaxis("top", functions=(lambda a: np.degrees(a / c.radius),
                                                 lambda d: np.radians(d) * c.radius))
    turn.set_xticks(range(0, 361, 30))
    turn.set_xlabel("cam angle θ (degrees)", fontsize=8)
    ax.set_title("displacement diagram (stations numbered, segment starts in bold)", fontsize=9, pad=22)


def _circle(ax: Any, radius: float, style: str, label: str, colour: str = "0.45") -> None:
    turn = np.linspace(0.0, 2 * math.pi, 361)
    ax.plot(radius * np.cos(turn), radius * np.sin(turn), style, color=colour, lw=0.7, label=label)


def _construction(ax: Any, c: Construction, profile: np.ndarray) -> None:
    """The construction in the cam's frame (mm): see the module docstring."""
    st = c.stations
    ring = np.vstack([profile, profile[:1]])
    ax.fill(ring[:, 0], ring[:, 1], color="0.9", zorder=0)
    ax.plot(ring[:, 0], ring[:, 1], color="k", lw=1.2, label="cam profile")
    _circle(ax, c.base_radius, ":", "base circle")
    if c.roller_radius > 0:
        _circle(ax, c.radius, "-.", "prime circle")
    if c.offset:
        _circle(ax, abs(c.offset), ":", f"offset circle (e = {c.offset:g} mm)", colour="C4")
    if c.pivot_distance is not None:
        _circle(ax, c.pivot_distance, ":", f"pivot circle (C = {c.pivot_distance:g} mm)", colour="C4")
    # the reference circle divided: a ray a station (an offset follower's to its foot on the offset circle)
    ends = st.foot if c.offset else st.circle
    for k, (x, y) in enumerate(ends):
        ax.plot([0.0, x], [0.0, y], color="0.7", lw=0.5, label="stations" if k == 0 else None, zorder=1)
    _followers(ax, c)
    ax.plot(*c.curve.point.T, "--", color="C0", lw=0.9,
            label="pitch curve through the stations" if c.roller_radius > 0 or c.follower == "knife-edge" else
            "profile touching the faces")
    _laid_off(ax, c)
    flat = c.follower in ("translating-flat", "oscillating-flat")
    ax.plot(*st.point.T, "o", color=_POINT, ms=3.5, zorder=4,
            label="contact points" if flat else "knife points" if c.follower == "knife-edge" else "roller centres")
    inward = 0.08 * c.radius
    for k, ((x, y), start) in enumerate(zip(st.circle, c.boundary, strict=True)):
        r = math.hypot(x, y)
        ax.text(x * (1 - inward / r), y * (1 - inward / r), str(k), ha="center", va="center", fontsize=7,
                color=_NUMBER, fontweight="bold" if start else "normal", gid=f"station-{k}", zorder=5)
    arrow = c.sense
    span = 0.3 * c.base_radius
    ax.annotate("", xy=(span * arrow, -0.25 * c.base_radius), xytext=(-span * arrow, -0.25 * c.base_radius),
                arrowprops={"arrowstyle": "->", "connectionstyle": f"arc3,rad={0.5 * arrow}", "color": "0.3"})
    ax.plot([0.0], [0.0], "+", color="k", ms=8)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.grid(alpha=0.25)


def _followers(ax: Any, c: Construction) -> None:
    """The follower at each station: its axis and roller, its face, or its arm on the pivot."""
    st = c.stations
    style = {"color": _FOLLOWER, "lw": 0.8}
    turn = np.linspace(0.0, 2 * math.pi, 73)
    lift = max(float(np.ptp(c.curve.along)), 0.1 * c.base_radius)
    flat = c.follower in ("translating-flat", "oscillating-flat")
    if flat:
        lo, hi = float(c.curve.along.min()), float(c.curve.along.max())
        margin = 0.15 * max(hi - lo, c.base_radius)
        if c.follower == "oscillating-flat":
            lo = 0.0                                     # the face from its pivot
        ends = (lo - margin * (c.follower == "translating-flat"), hi + margin)
    for k in range(st.theta.size):
        foot, d, point = st.foot[k], st.direction[k], st.point[k]
        label = "follower at each station" if k == 0 else None
        if flat:
            a, b = foot + ends[0] * d, foot + ends[1] * d
            ax.plot([a[0], b[0]], [a[1], b[1]], label=label, **style)
        elif c.pivot_distance is not None:               # the arm from its pivot
            ax.plot([foot[0], point[0]], [foot[1], point[1]], label=label, **style)
        else:                                            # the axis from its foot, past the roller
            start = foot if c.offset else st.circle[k]
            end = point + (c.roller_radius + 0.25 * lift) * d
            ax.plot([start[0], end[0]], [start[1], end[1]], label=label, **style)
        if c.roller_radius > 0:
            ax.plot(point[0] + c.roller_radius * np.cos(turn), point[1] + c.roller_radius * np.sin(turn),
                    color=_FOLLOWER, lw=0.6)
    if c.pivot_distance is not None:
        ax.plot(*st.foot.T, "^", color="C4", ms=5, label="pivot at each station")


def _laid_off(ax: Any, c: Construction) -> None:
    """Each station's displacement as it is transferred from the diagram: along a translating follower's axis from
    the reference circle (to the roller's centre, the knife's point or the face's foot), as the angle psi at an
    arm's pivot (an arc from the rest position, of the arm's radius for a roller)."""
    st = c.stations
    style = {"color": _POINT, "lw": 1.6, "solid_capstyle": "butt", "zorder": 3}
    label = f"displacement laid off ({'s' if c.lift_unit == 'mm' else 'ψ'} from the diagram)"
    for k in range(st.theta.size):
        start = st.circle[k]
        if c.pivot_distance is None:
            end = st.foot[k] if c.follower == "translating-flat" else st.point[k]
            ax.plot([start[0], end[0]], [start[1], end[1]], label=label if k == 0 else None, **style)
            continue
        pivot, rest = st.foot[k], start - st.foot[k]
        radius = float(np.hypot(*rest)) * (1.0 if c.roller_radius > 0 else 0.3)
        a0 = math.atan2(rest[1], rest[0])
        a1 = a0 + _angle_between(rest, st.direction[k])
        turn = np.linspace(a0, a1, 25)
        ax.plot(pivot[0] + radius * np.cos(turn), pivot[1] + radius * np.sin(turn), label=label if k == 0 else None,
                **style)


def _angle_between(a: np.ndarray, b: np.ndarray) -> float:
    """The signed angle (rad, counter-clockwise positive, within a half turn) from vector ``a`` to ``b``."""
    return math.atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1])
