"""Golden files by content: every bundled template built through the commands users run, each file's content
recorded as a fingerprint and compared within tolerances.

``python -m tests.support.golden [TEMPLATE.toml ...]`` writes ``tests/data/golden.json`` (all, or those templates'
entries only; run it when a change of the output is intended, and say so in the commit);
``tests/project/test_golden.py`` rebuilds every template and compares. Cam templates run ``camgen build``; linkage
templates run ``linkgen analyze`` and, with a ``[parts]`` table, ``linkgen build``; families run ``camgen family`` or
``linkgen family``.

What a fingerprint holds, by file type (numbers compared to :data:`ABS` plus :data:`REL` of their size):

* JSON reports and CSV tables: every value; numbers within the tolerance, everything else equal. Arrays of more
  than :data:`LONG` numbers are summarised (see :func:`_summary`).
* DXF: the units, the layers, and each entity's type, layer and geometry (a circle's centre and radius, a
  polyline's vertex count, closure, bounds, length and area with its arcs, a text's words and insertion point).
* SVG cut drawings (ours) and HTML pages: the text with its numbers taken out, exactly (by its SHA-256), and
  the numbers summarised; the page's embedded data as JSON.
* STL and 3MF: each body's volume, surface area and bounds, whether it is closed, the number of bodies and the
  3MF objects' names.
* Figures drawn by matplotlib (PNG, and SVG figures): by name only (their bytes follow matplotlib's and FreeType's
  versions).
* A family's resume markers: the member's input hash and the names of the files it lists.

Bits are not compared: they change with the platform and the library versions. The same run twice giving the same
bytes is tested on its own (tests/core/test_formats.py, tests/core/test_family.py).
"""
from __future__ import annotations

import hashlib
import io
import json
import math
import re
import sys
import tomllib
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from click.testing import CliRunner
from tests.conftest import ROOT

GOLDEN = ROOT / "tests" / "data" / "golden.json"
#: absolute (mm, or the report's unit) and relative tolerance of a recorded number
ABS = 1e-9
REL = 1e-9
#: absolute tolerance (degrees or mm) of where a smooth extreme lies (a key such as ``transmission_max_at_deg``): a
#: search by values finds it only to about the square root of the rounding error of the range searched, as the
#: function is flat there (about 2e-6 degrees seen between numpy versions), not to :data:`ABS`; a place in degrees
#: is compared round the turn (one found just under 360 degrees is as near one recorded just over 0)
AT = 1e-5
AT_KEY = re.compile(r"(?:^|[._])at(?:_[a-z]+)*_(?:deg|mm)$")
#: arrays of more numbers than this are summarised, not recorded number by number
LONG = 24
_NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")


def _raw(path: Path) -> dict:
    raw = tomllib.loads(path.read_text(encoding="utf-8"))
    if "base" in raw:
        base = _raw(path.parent / raw["base"])
        return {**base, **raw}
    return raw


def runs(path: Path) -> list[tuple[str, list[str]]]:
    """(program, arguments without -o) for each command a bundled template is meant for."""
    raw = _raw(path)
    if "task" in raw:
        return []                     # synthesis tasks: searches, run by tests/synthesis/test_synthesis.py
    linkage = "linkage" in raw
    program = "linkgen" if linkage else "camgen"
    if "sweep" in raw:
        return [(program, ["family", str(path), "--jobs", "1"])]
    if not linkage:
        return [("camgen", ["build", str(path)])]
    out = [("linkgen", ["analyze", str(path)])]
    if "parts" in raw:
        out.append(("linkgen", ["build", str(path)]))
    return out


def is_figure(path: Path) -> bool:
    """A file drawn by matplotlib (its bytes follow matplotlib's version)."""
    if path.suffix == ".png":
        return True
    return path.suffix == ".svg" and b"Matplotlib v" in path.read_bytes()[:1000]


# --------------------------------------------------------------------------------------------------- fingerprints

def _summary(numbers: list[float]) -> dict[str, Any]:
    """A long run of numbers as its count, least, largest, sum, sum of magnitudes and a sum weighted by position
    (which a reordering changes)."""
    n = len(numbers)
    return {"__numbers__": {"count": n, "min": min(numbers, default=0.0), "max": max(numbers, default=0.0),
                            "sum": math.fsum(numbers), "abs": math.fsum(abs(v) for v in numbers),
                            "weighted": math.fsum((i + 1) / n * v for i, v in enumerate(numbers))}}


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _data(value: Any) -> Any:
    """A JSON value with its long arrays of numbers summarised."""
    if isinstance(value, dict):
        return {k: _data(v) for k, v in value.items()}
    if isinstance(value, list):
        if _all_numbers(value):
            flat = list(_numbers_of(value))
            if len(flat) > LONG:
                return _summary(flat)
        return [_data(v) for v in value]
    return value


def _all_numbers(value: Any) -> bool:
    if isinstance(value, list):
        return all(_all_numbers(v) for v in value)
    return _is_number(value) or value is None


def _numbers_of(value: Any) -> Iterator[float]:
    if isinstance(value, list):
        for v in value:
            yield from _numbers_of(v)
    elif _is_number(value):
        yield float(value)


def _text(text: str) -> dict[str, Any]:
    """Text with its numbers taken out (compared exactly, by its SHA-256) and the numbers summarised."""
    numbers = [float(m) for m in _NUMBER.findall(text)]
    return {"text": hashlib.sha256(_NUMBER.sub("#", text).encode()).hexdigest(), "numbers": _summary(numbers)}


def _dxf(path: Path) -> dict[str, Any]:
    import ezdxf
    from ezdxf import bbox

    doc = ezdxf.readfile(path)
    entities = []
    for e in doc.modelspace():
        kind = e.dxftype()
        row: dict[str, Any] = {"type": kind, "layer": e.dxf.layer, "color": e.dxf.get("color"),
                               "true_color": e.dxf.get("true_color")}
        if kind == "LWPOLYLINE":
            points = [(x, y, b) for x, y, _, _, b in e.get_points()]
            row |= {"vertices": len(points), "closed": bool(e.closed), "bulges": math.fsum(abs(b) for *_, b in points),
                    "area": _polyline_area(points, bool(e.closed)), "length": _polyline_length(points, bool(e.closed)),
                    "start": list(points[0][:2]) if points else None,
                    "bounds": _polyline_bounds(points, bool(e.closed))}
        elif kind == "CIRCLE":
            row |= {"centre": list(e.dxf.center)[:2], "radius": e.dxf.radius}
        elif kind == "ARC":
            row |= {"centre": list(e.dxf.center)[:2], "radius": e.dxf.radius, "angles": [e.dxf.start_angle,
                                                                                         e.dxf.end_angle]}
        elif kind == "LINE":
            row |= {"start": list(e.dxf.start)[:2], "end": list(e.dxf.end)[:2]}
        elif kind in ("TEXT", "MTEXT"):
            row |= {"text": e.dxf.text if kind == "TEXT" else e.text, "insert": list(e.dxf.insert)[:2],
                    "height": e.dxf.get("height") if kind == "TEXT" else e.dxf.get("char_height")}
        else:
            box = bbox.extents([e])
            row |= {"bounds": [*box.extmin[:2], *box.extmax[:2]] if box.has_data else None}
        entities.append(row)
    return {"units": doc.header.get("$INSUNITS"), "layers": sorted(layer.dxf.name for layer in doc.layers),
            "entities": entities}


def _polyline_area(points: list[tuple[float, float, float]], closed: bool) -> float:
    """The signed area (mm^2) inside a closed polyline whose spans may be arcs (bulge = tan of a quarter of the arc's
    angle, + counter-clockwise): the chords' shoelace plus each arc's segment."""
    if not closed or len(points) < 2:
        return 0.0
    total = []
    for (x0, y0, b), (x1, y1, _) in zip(points, points[1:] + points[:1], strict=True):
        total.append(0.5 * (x0 * y1 - x1 * y0))
        if b:
            angle = 4.0 * math.atan(b)
            chord = math.hypot(x1 - x0, y1 - y0)
            radius = chord / (2.0 * abs(math.sin(angle / 2.0))) if chord else 0.0
            total.append(0.5 * radius * radius * (angle - math.sin(angle)))
    return math.fsum(total)


def _polyline_length(points: list[tuple[float, float, float]], closed: bool) -> float:
    """The length (mm) of a polyline whose spans may be arcs."""
    pairs = zip(points, points[1:] + (points[:1] if closed else []), strict=False)
    out = []
    for (x0, y0, b), (x1, y1, _) in pairs:
        chord = math.hypot(x1 - x0, y1 - y0)
        angle = 4.0 * math.atan(b)
        out.append(chord if not b or not chord else chord * (angle / 2.0) / math.sin(angle / 2.0))
    return math.fsum(out)


def _polyline_bounds(points: list[tuple[float, float, float]], closed: bool) -> list[float] | None:
    """The exact bounds (mm) of a polyline whose spans may be arcs: its vertices and each arc's points at 0, 90,
    180 and 270 degrees that lie within its sweep. (A flattened path's bounds follow the flattening's own
    placement of points, which moves with ezdxf's version by up to its tolerance.)"""
    if not points:
        return None
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    spans = zip(points, points[1:] + (points[:1] if closed else []), strict=False)
    for (x0, y0, b), (x1, y1, _) in spans:
        if not b or (x0, y0) == (x1, y1):
            continue
        sweep = 4.0 * math.atan(b)                                  # + counter-clockwise, from (x0, y0)
        k = (1.0 - b * b) / (4.0 * b)                                # the centre: the chord's middle + k x its left
        cx, cy = 0.5 * (x0 + x1) - k * (y1 - y0), 0.5 * (y0 + y1) + k * (x1 - x0)
        radius, start = math.hypot(x0 - cx, y0 - cy), math.atan2(y0 - cy, x0 - cx)
        for quarter in range(4):
            phi = quarter * math.pi / 2.0
            turned = (phi - start) % math.tau if sweep > 0 else (start - phi) % math.tau
            if turned <= abs(sweep):
                xs.append(cx + radius * math.cos(phi))
                ys.append(cy + radius * math.sin(phi))
    return [min(xs), min(ys), max(xs), max(ys)]


def _mesh(mesh: Any) -> dict[str, Any]:
    """A mesh's bodies: count, and the whole's volume, area, bounds and closure."""
    return {"bodies": len(mesh.split(only_watertight=False)), "volume": float(mesh.volume),
            "area": float(mesh.area), "bounds": [float(v) for v in mesh.bounds.ravel()],
            "closed": bool(mesh.is_watertight)}


def _stl(path: Path) -> dict[str, Any]:
    import trimesh

    return _mesh(trimesh.load_mesh(path, file_type="stl", process=True))


def _threemf(path: Path) -> dict[str, Any]:
    import trimesh

    with zipfile.ZipFile(path) as archive:
        names = sorted(archive.namelist())
    scene = trimesh.load(io.BytesIO(path.read_bytes()), file_type="3mf", force="scene")
    objects = {name: _mesh(geometry) for name, geometry in sorted(scene.geometry.items())}
    return {"entries": names, "objects": objects}


def _json(path: Path) -> Any:
    return _data(json.loads(path.read_text(encoding="utf-8")))


def _csv(path: Path) -> Any:
    import csv

    rows = list(csv.reader(path.read_text(encoding="utf-8").splitlines()))
    return [[float(cell) if _NUMBER.fullmatch(cell) else cell for cell in row] for row in rows]


def _html(path: Path) -> dict[str, Any]:
    """A page: its embedded data (JSON) and the rest as text with its numbers taken out."""
    text = path.read_text(encoding="utf-8")
    found = re.search(r'(<script type="application/json" id="page-data">)(.*?)(</script>)', text, re.S)
    if not found:
        return {"page": _text(text)}
    rest = text[:found.start(2)] + text[found.end(2):]
    return {"data": _data(json.loads(found.group(2))), "page": _text(rest)}


def _marker(path: Path) -> dict[str, Any]:
    """A family member's resume marker: its input hash, and the files it lists by name."""
    data = json.loads(path.read_text(encoding="utf-8"))
    return {"inputs": data.get("inputs"), "files": sorted(data.get("files", {}))}


def fingerprint(path: Path) -> Any:
    """The content of one written file, as :mod:`tests.support.golden` compares it (see the module's docstring)."""
    if is_figure(path):
        return "figure"
    kind = path.suffix.lower()
    if path.name == ".inputs":
        return _marker(path)
    readers = {".json": _json, ".csv": _csv, ".dxf": _dxf, ".stl": _stl, ".3mf": _threemf, ".html": _html,
               ".svg": lambda p: _text(p.read_text(encoding="utf-8"))}
    if kind not in readers:
        raise ValueError(f"{path}: no fingerprint for {kind or 'a file without a suffix'} files")
    return readers[kind](path)


# --------------------------------------------------------------------------------------------------- comparison

def _close(a: float, b: float, slack: float = 0.0) -> bool:
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    if math.isinf(a) or math.isinf(b):
        return a == b
    return abs(a - b) <= ABS + slack + REL * max(abs(a), abs(b))


def differences(recorded: Any, built: Any, where: str = "") -> Iterator[str]:
    """Where ``built`` departs from ``recorded`` beyond the tolerances (each a line naming the place)."""
    if isinstance(recorded, dict) and "__numbers__" in recorded and isinstance(built, dict) and "__numbers__" in built:
        yield from _summaries(recorded["__numbers__"], built["__numbers__"], where)
    elif isinstance(recorded, dict) and isinstance(built, dict):
        if sorted(recorded) != sorted(built):
            yield f"{where}: keys {sorted(set(recorded) ^ set(built))} differ"
        for key in recorded.keys() & built.keys():
            yield from differences(recorded[key], built[key], f"{where}.{key}" if where else str(key))
    elif isinstance(recorded, list) and isinstance(built, list):
        if len(recorded) != len(built):
            yield f"{where}: {len(built)} items, recorded {len(recorded)}"
            return
        for i, (r, b) in enumerate(zip(recorded, built, strict=True)):
            yield from differences(r, b, f"{where}[{i}]")
    elif _is_number(recorded) and _is_number(built):
        slack = AT if AT_KEY.search(where) else 0.0
        value = float(built)
        if slack and where.endswith("_deg"):        # a place on a turn: 359.9999994 is 6e-7 degrees from 6e-7
            value = float(recorded) + math.remainder(value - float(recorded), 360.0)
        if not _close(float(recorded), value, slack):
            yield f"{where}: {built!r}, recorded {recorded!r}"
    elif recorded != built:
        yield f"{where}: {_shown(built)}, recorded {_shown(recorded)}"


def _shown(value: Any) -> str:
    text = repr(value)
    return text if len(text) < 80 else text[:77] + "..."


def _summaries(recorded: dict[str, Any], built: dict[str, Any], where: str) -> Iterator[str]:
    """Two summaries of a run of numbers: the same count, least and largest within the tolerance, and the sums
    within the tolerance of each number they add."""
    if recorded["count"] != built["count"]:
        yield f"{where}: {built['count']} numbers, recorded {recorded['count']}"
        return
    slack = ABS * recorded["count"] + REL * max(recorded["abs"], built["abs"])
    for key in ("min", "max"):
        if not _close(recorded[key], built[key]):
            yield f"{where}: {key} {built[key]!r}, recorded {recorded[key]!r}"
    for key in ("sum", "abs", "weighted"):
        if not _close(recorded[key], built[key], slack):
            yield f"{where}: {key} of the numbers {built[key]!r}, recorded {recorded[key]!r}"


# --------------------------------------------------------------------------------------------------- recording

def run_id_of(path: Path, program: str, args: list[str]) -> str:
    """The name of one command on a bundled template, as :data:`GOLDEN` keys it (``camgen build rdrd.toml``)."""
    return f"{program} {args[0]} {path.name}"


def run(path: Path, program: str, args: list[str], root: Path) -> Path:
    """Run one command on a bundled template into a folder under ``root`` (named after its run id); that folder.

    Raises ``RuntimeError`` with the command's output when it exits with a code other than 0.
    """
    from camgen.cli import main as camgen
    from linkgen.cli import main as linkgen

    run_id = run_id_of(path, program, args)
    folder = root / run_id.replace(" ", "_")
    result = CliRunner().invoke({"camgen": camgen, "linkgen": linkgen}[program], [*args, "-o", str(folder)])
    if result.exit_code != 0:
        raise RuntimeError(f"{run_id}: exit {result.exit_code}: {result.output}")
    return folder


def prints(folder: Path) -> dict[str, Any]:
    """{file relative to ``folder``: fingerprint} of every file a command wrote into ``folder``."""
    return {p.relative_to(folder).as_posix(): fingerprint(p) for p in sorted(folder.rglob("*")) if p.is_file()}


def build(path: Path, program: str, args: list[str], root: Path) -> tuple[str, dict[str, Any]]:
    """Run one command on a bundled template into a folder under ``root``: (run id, {relative file: fingerprint})."""
    return run_id_of(path, program, args), prints(run(path, program, args, root))


def all_runs(names: tuple[str, ...] = ()) -> list[tuple[Path, str, list[str]]]:
    """(template, program, arguments) of every bundled template's commands (or those of file ``names``)."""
    return [(path, program, args) for path in sorted((ROOT / "templates").glob("*.toml"))
            if not names or path.name in names for program, args in runs(path)]


def build_all(root: Path, names: tuple[str, ...] = ()) -> dict[str, dict[str, Any]]:
    """Build every bundled template (or those of file ``names``) under ``root``; {run id: {relative file:
    fingerprint}}."""
    return dict(build(path, program, args, root) for path, program, args in all_runs(names))


def main(names: tuple[str, ...] = ()) -> None:
    """Record every template's files, or with ``names`` (``toggle-press.toml ...``) re-record those only and keep
    the other entries as they are."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        prints = build_all(Path(tmp), names)
    if names:
        kept = {k: v for k, v in json.loads(GOLDEN.read_text()).items() if k.rsplit(" ", 1)[-1] not in names}
        prints = {**kept, **prints}
    GOLDEN.parent.mkdir(parents=True, exist_ok=True)
    GOLDEN.write_text(json.dumps(prints, indent=None, sort_keys=True, separators=(",", ":")) + "\n")
    print(f"wrote {GOLDEN}: {sum(len(v) for v in prints.values())} files from {len(prints)} runs", file=sys.stderr)


if __name__ == "__main__":
    main(tuple(sys.argv[1:]))
