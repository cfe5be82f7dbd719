"""A linkage read from a DXF sketch drawn in any CAD or drawing program (ezdxf), as a ``type = "linkage"`` template.

The rules (also in docs/guides/import.md):

- a CIRCLE is a joint at its centre (circles whose centres lie within :data:`SAME_MM` mm are one joint);
- a LINE whose two ends fall on joints (within the circle's radius of its centre) is a binary link; an open
  LWPOLYLINE or POLYLINE is one rigid link of every joint its vertices fall on (a polyline through three circles
  is a ternary link); a closed one is a link of every joint inside it (an outline round its holes);
- the ground: the joints on layer ``ground`` (any case) or drawn in colour 1 (red), and every joint a line, polyline
  or outline on that layer (or red) touches;
- a slider: a closed four-sided polyline (a rectangle) round exactly one joint, lying on a LINE through that joint
  (the guide, on the ground) that is no link; the joint slides along the line;
- the input: the link on layer ``input`` (any case), turned about its ground joint; else the link of the first
  ground joint (in the file's order) that has one, turned about that joint;
- lengths in the file's units ($INSUNITS: unitless, inches, feet, mm, cm, m) converted to mm.

The project's own assembly drawing (``linkgen build``: its poses on layers ``DC1-...``, ``DC2-...``) is read at its
first pose; each part's outline is followed by its holes, and the first part is the frame (the ground).

What is not read is said, one line an item: a loose line, a circle on no link, an entity of another kind. No I/O
except reading the file named; the command writes the template.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from camgen.core.errors import SpecError

#: circles whose centres lie closer than this (mm) are one joint
SAME_MM = 1e-6
#: mm per drawing unit of each $INSUNITS code read (0: unitless, read as mm)
UNITS = {0: 1.0, 1: 25.4, 2: 304.8, 4: 1.0, 5: 10.0, 6: 1000.0}
#: the most entities a sketch may hold (a linkage template holds at most 200 joints and 100 links)
MAX_ENTITIES = 5000
_GROUND, _INPUT, _RED = "ground", "input", 1
_POSE = re.compile(r"^DC(\d+)-")


@dataclass(frozen=True)
class Sketch:
    """What a sketch draws: the raw ``[linkage]`` table of a general linkage (``type = "linkage"``, joints in mm),
    and ``notes``, one line for each entity not read."""

    linkage: dict[str, Any]
    notes: tuple[str, ...]
    hole: float = 0.0              # the smallest joint circle's diameter (mm)


@dataclass(frozen=True)
class _Entity:
    kind: str
    handle: str
    layer: str
    colour: int
    points: tuple[tuple[float, float], ...]     # a circle's centre; a line's or polyline's vertices (mm)
    radius: float = 0.0
    closed: bool = False

    @property
    def name(self) -> str:
        return f"{self.kind} #{self.handle} on layer {self.layer!r}"

    @property
    def ground(self) -> bool:
        return self.layer.lower() == _GROUND or self.colour == _RED


def _at(p: tuple[float, float]) -> str:
    return f"({p[0]:.6g}, {p[1]:.6g}) mm"


def read_sketch(path: Path) -> Sketch:
    """The linkage sketch in DXF file ``path`` (see the module docstring); a :class:`SpecError` naming ``sketch``
    for a file that is not a DXF, holds no joints, no links or no ground."""
    entities, notes = _entities(path)
    own = any(_POSE.match(e.layer) for e in entities)
    if own:
        first = min(int(m.group(1)) for e in entities if (m := _POSE.match(e.layer)))
        keep = [e for e in entities if (m := _POSE.match(e.layer)) and int(m.group(1)) == first]
        others = sorted({e.layer for e in entities if e not in keep})
        if others:
            notes.append(f"layers {', '.join(others)}: other poses and paths of the drawing, not read")
        entities = keep
    circles = [e for e in entities if e.kind == "CIRCLE"]
    if not circles:
        raise SpecError("no joints: draw each joint as a CIRCLE", "sketch")
    centres, joint_of = _joints(circles)
    links, ground, sliders, used, loose = _links(entities, circles, joint_of, centres, own)
    notes += loose
    for k, c in enumerate(circles):
        if joint_of[k] not in used and not (c.ground and joint_of[k] in ground):
            notes.append(f"{c.name} at {_at(c.points[0])} is on no link: not read")
    if not ground:
        raise SpecError("no ground: put the frame's joints (or a line between them) on layer 'ground', or draw them "
                        "in red (colour 1)", "sketch")
    moving = [m for m in links if not set(m[1]) <= ground]
    if not moving:
        raise SpecError("nothing to read: no line or polyline joins two joints, or every one is on the ground",
                        "sketch")
    hole = 2 * min(c.radius for c in circles)
    return Sketch(_table(centres, moving, ground, sliders), tuple(notes), hole)


def _entities(path: Path) -> tuple[list[_Entity], list[str]]:
    import ezdxf
    from ezdxf.entities import LWPolyline, Polyline

    try:
        doc = ezdxf.readfile(str(path))
    except (OSError, ezdxf.DXFError, UnicodeDecodeError, ValueError) as exc:
        raise SpecError(f"{path} is not a DXF file ezdxf reads ({str(exc).splitlines()[0] if str(exc) else exc!r})",
                        "sketch") from None
    code = int(doc.header.get("$INSUNITS", 0))
    if code not in UNITS:
        raise SpecError(f"$INSUNITS {code}: the units read are unitless (0), inches (1), feet (2), mm (4), cm (5) "
                        "and m (6)", "sketch")
    scale = UNITS[code]
    msp = doc.modelspace()
    if len(msp) > MAX_ENTITIES:
        raise SpecError(f"at most {MAX_ENTITIES} entities (this one has {len(msp)})", "sketch")
    out, notes = [], []
    for e in msp:
        kind, layer = e.dxftype(), e.dxf.get("layer", "0")
        colour = int(e.dxf.get("color", 256))
        handle = e.dxf.get("handle", "?")
        if kind == "CIRCLE":
            c = e.dxf.center
            out.append(_Entity(kind, handle, layer, colour, ((c.x * scale, c.y * scale),), e.dxf.radius * scale))
        elif kind == "LINE":
            a, b = e.dxf.start, e.dxf.end
            out.append(_Entity(kind, handle, layer, colour, ((a.x * scale, a.y * scale), (b.x * scale, b.y * scale))))
        elif isinstance(e, (LWPolyline, Polyline)):
            closed = bool(e.closed) if isinstance(e, LWPolyline) else bool(e.is_closed)
            pts = _outline(e, scale) if closed else tuple(
                (p[0] * scale, p[1] * scale) for p in (e.get_points("xy") if isinstance(e, LWPolyline)
                                                       else (v.dxf.location for v in e.vertices)))
            out.append(_Entity(kind, handle, layer, colour, pts, closed=closed))
        else:
            notes.append(f"{kind} #{handle} on layer {layer!r}: not a joint, link or slider, not read")
    return out, notes


def _outline(e: Any, scale: float) -> tuple[tuple[float, float], ...]:
    """A closed polyline's boundary (mm), its arcs (bulges) flattened to 0.01 drawing units."""
    from ezdxf import path as dxfpath

    return tuple((v.x * scale, v.y * scale) for v in dxfpath.make_path(e).flattening(0.01))


def _joints(circles: list[_Entity]) -> tuple[list[tuple[float, float]], list[int]]:
    """The joints (mm) and each circle's joint: centres within :data:`SAME_MM` are one."""
    centres: list[tuple[float, float]] = []
    joint_of = []
    for c in circles:
        p = c.points[0]
        k = next((j for j, q in enumerate(centres) if math.dist(p, q) <= SAME_MM), None)
        if k is None:
            centres.append(p)
            k = len(centres) - 1
        joint_of.append(k)
    return centres, joint_of


def _on(p: tuple[float, float], circles: list[_Entity], joint_of: list[int]) -> int | None:
    """The joint whose circle ``p`` falls on (within its radius of the centre, the nearest), or None."""
    best = None
    for k, c in enumerate(circles):
        d = math.dist(p, c.points[0])
        if d <= max(c.radius, SAME_MM) and (best is None or d < best[0]):
            best = (d, joint_of[k])
    return None if best is None else best[1]


def _links(entities: list[_Entity], circles: list[_Entity], joint_of: list[int], centres: list[tuple[float, float]],
           own: bool) -> tuple[list[tuple[str, tuple[int, ...]]], set[int], list[dict[str, Any]], set[int], list[str]]:
    """Links (their layer and joints, in file order), the ground joints, the sliders, the joints on a link, and
    the notes of what was not read."""
    from shapely.geometry import Point, Polygon

    links: list[tuple[str, list[int]]] = []
    ground = {joint_of[k] for k, c in enumerate(circles) if c.ground}
    notes: list[str] = []
    guides, blocks = [], []
    circle_at = {id(c): k for k, c in enumerate(circles)}
    current: list[int] | None = None
    for e in entities:
        if e.kind == "CIRCLE":
            if own and current is not None:
                j = joint_of[circle_at[id(e)]]
                if j not in current:
                    current.append(j)
            continue
        if own and e.closed:                      # the project's drawing: an outline, then its holes
            current = []
            links.append((e.layer, current))
            continue
        if e.closed:
            shape = Polygon(e.points).buffer(SAME_MM)
            inside = tuple(dict.fromkeys(joint_of[k] for k, c in enumerate(circles)
                                         if shape.contains(Point(c.points[0]))))
            if len(inside) >= 2:
                links.append((e.layer, list(inside)))
            elif len(inside) == 1 and len(_corners(e.points)) == 4:
                blocks.append((e, inside[0]))
            else:
                notes.append(f"{e.name}: a closed outline round {len(inside)} joints (a link holds two or more, a "
                             "slider's rectangle one), not read")
            continue
        on = [_on(p, circles, joint_of) for p in e.points]
        joints = tuple(dict.fromkeys(j for j in on if j is not None))
        if e.kind == "LINE" and len(joints) < 2:
            guides.append(e)
            continue
        if len(joints) < 2:
            missed = [p for p, j in zip(e.points, on, strict=True) if j is None]
            notes.append(f"{e.name} is loose: its point {_at(missed[0])} falls on no joint, not read")
            continue
        links.append((e.layer, list(joints)))
    found = [(layer, tuple(pts)) for layer, pts in links]
    if own and found:                               # the frame is the project's first part
        ground |= set(found[0][1])
    ground |= {j for layer, pts in found if layer.lower() == _GROUND for j in pts}
    ground |= {j for e in entities if e.kind != "CIRCLE" and e.colour == _RED and not own
               for j in (_on(p, circles, joint_of) for p in e.points) if j is not None}
    sliders, taken = _sliders(blocks, guides, centres)
    for g in guides:
        if id(g) not in taken:
            notes.append(f"{g.name} is loose: it joins no two joints and guides no slider, not read")
    used = {j for _, pts in found for j in pts} | {s["joint"] for s in sliders}
    return found, ground, sliders, used, notes


def _corners(points: tuple[tuple[float, float], ...]) -> list[tuple[float, float]]:
    """The distinct vertices of a closed polyline (its closing vertex, if repeated, counted once)."""
    pts = list(dict.fromkeys((round(x, 9), round(y, 9)) for x, y in points))
    return pts


def _sliders(blocks: list[tuple[_Entity, int]], guides: list[_Entity], centres: list[tuple[float, float]]
             ) -> tuple[list[dict[str, Any]], set[int]]:
    """Each rectangle round one joint on a guide line through that joint: the slider (its joint and the guide's
    direction in degrees, in [0, 180))."""
    out, taken = [], set()
    for block, joint in blocks:
        p = centres[joint]
        for g in guides:
            a, b = g.points
            d = (b[0] - a[0], b[1] - a[1])
            length = math.hypot(*d)
            if length == 0:
                continue
            off = abs(d[0] * (p[1] - a[1]) - d[1] * (p[0] - a[0])) / length
            if off <= 1e-6 * max(1.0, length):
                out.append({"joint": joint, "angle": math.degrees(math.atan2(d[1], d[0])) % 180.0,
                            "name": block.handle})
                taken.add(id(g))
                break
    return out, taken


def _table(centres: list[tuple[float, float]], moving: list[tuple[str, tuple[int, ...]]],
           ground: set[int], sliders: list[dict[str, Any]]) -> dict[str, Any]:
    """The raw ``[linkage]`` table: joints renamed O1, O2, ... (ground, in file order) and A, B, ... (moving)."""
    order = [j for j in range(len(centres)) if j in ground] + [j for j in range(len(centres)) if j not in ground]
    used = {j for _, pts in moving for j in pts} | ground | {s["joint"] for s in sliders}
    order = [j for j in order if j in used]
    label, g, m = {}, 0, 0
    for j in order:
        if j in ground:
            g += 1
            label[j] = f"O{g}"
        else:
            label[j] = _letter(m)
            m += 1
    crank = next((i for i, (layer, _) in enumerate(moving) if layer.lower() == _INPUT), None)
    first_ground = [j for j in order if j in ground]
    if crank is None:
        crank = next((i for j in first_ground for i, (_, pts) in enumerate(moving) if j in pts), None)
    if crank is None:
        raise SpecError("no input: no link turns about a ground joint (put the crank on layer 'input')", "sketch")
    pivot = next((j for j in first_ground if j in moving[crank][1]), None)
    if pivot is None:
        raise SpecError("the link on layer 'input' holds no ground joint to turn about", "sketch")
    link_names = []
    k = 0
    for i in range(len(moving)):
        if i == crank:
            link_names.append("crank")
        else:
            k += 1
            link_names.append(f"link{k}")
    table: dict[str, Any] = {
        "type": "linkage",
        "ground": [label[j] for j in first_ground],
        "input": {"link": "crank", "pivot": label[pivot]},
        "joints": {label[j]: [float(centres[j][0]), float(centres[j][1])] for j in order},
        "links": {n: [label[j] for j in pts] for n, (_, pts) in zip(link_names, moving, strict=True)},
    }
    if sliders:
        table["sliders"] = {f"S{i + 1}": {"point": label[s["joint"]], "angle": s["angle"]}
                            for i, s in enumerate(sliders)}
    return table


def _letter(k: int) -> str:
    """A, B, ..., Z, then J27, J28, ... (O is kept for the ground)."""
    letters = "ABCDEFGHIJKLMNPQRSTUVWXYZ"
    return letters[k] if k < len(letters) else f"J{k + 1}"


def sketch_template(sketch: Sketch, name: str) -> dict[str, Any]:
    """The raw template of ``sketch``: ``name``, its ``[linkage]`` (tracing up to two moving joints off the crank)
    and a ``[parts]`` table for ``linkgen build``: pins as wide as the smallest circle drawn (at least 1 mm, at most
    20), bars three pins wide, plates 3 mm thick."""
    table = dict(sketch.linkage)
    crank = set(table["links"]["crank"])
    table["tracers"] = [p for p in table["joints"] if p not in table["ground"] and p not in crank][:2]
    pin = round(min(max(sketch.hole, 1.0), 20.0), 3)
    return {"name": name, "linkage": table, "parts": {"width": 3 * pin, "thickness": 3.0, "pin_diameter": pin}}
