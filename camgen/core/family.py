"""Part families: a template with a ``[sweep]`` table becomes many members, built in parallel and resumable.

Sweep table (any template, camgen's or linkgen's)::

    base = "rdrd.toml"                 # optional: start from another template (path relative to this one)
    [sweep]
    "motion.0.lift" = [10, 15, 20]     # a list of values
    "follower.roller_radius" = {start = 6, stop = 10, step = 2}   # a range, stop included
    [sweep.zip]                        # keys that change together (equal-length lists): one factor
    "motion.0.angle" = [100, 120]
    "motion.1.angle" = [80, 60]

The family is the product of the factors. A member's name is the template's name
followed by each swept key's short name and value (``rdrd-lift10-roller_radius6``):
stable, and safe as a file name. Every member is validated before any work starts,
so a bad key or value is one clear error. A member that fails while building (an
undercut, a linkage that cannot be assembled) is recorded with its one-line reason
and the others go on. Each member's folder ends with ``.inputs`` holding the hash of
its inputs and of each of its files, written last: a re-run skips a member only when
its inputs and all its files are as that run left them.
"""
from __future__ import annotations

import csv
import hashlib
import io
import itertools
import json
import math
import os
import re
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterable, Mapping
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

from pydantic import Field, field_validator

from camgen.core import VERSION as __version__
from camgen.core.errors import CamgenError, SpecError
from camgen.core.bundle import staged
from camgen.core.writers import FIGURE_FORMATS
from camgen.core.writers.figure import save
from camgen.core.spec import Model, SheetSide, apply_overrides, read_template, unit, validate

MARKER = ".inputs"


@dataclass(frozen=True)
class Member:
    """One member: its name, the swept values (key -> value) and its full raw template."""

    name: str
    values: tuple[tuple[str, Any], ...]
    raw: dict

    @property
    def inputs_hash(self) -> str:
        text = json.dumps({"raw": self.raw, "version": __version__}, sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()


def read_family(path: str | Path) -> tuple[dict, dict]:
    """The raw template (its ``base`` merged in) and its sweep table (the family's ``[sheet]`` table, which is no
    member's, left out: :func:`split_family`).

    Parameters
    ----------
    path : str or Path
        The family template, a TOML file with a ``[sweep]`` table.

    Returns
    -------
    tuple of dict
        The raw template without its ``[sweep]`` and ``[sheet]`` tables, and the sweep table.

    Raises
    ------
    SpecError
        The file (or its ``base``) cannot be read or is no TOML, its ``sweep`` is not a table, or its ``[sheet]``
        table fails validation.
    """
    raw, sweep, _ = split_family(read_template(path))
    return raw, sweep


def split_family(template: Mapping[str, Any]) -> tuple[dict, dict, Any]:
    """A family template read (:func:`camgen.core.spec.read_template`) as the members' raw template, its sweep
    table and its ``[sheet]`` table validated (:class:`SheetTable`; None without one)."""
    raw = dict(template)
    sheet = raw.pop(SHEET, None)
    sweep = raw.pop("sweep", {})
    if not isinstance(sweep, Mapping):
        raise SpecError("must be a table of key = values", "sweep")
    return raw, dict(sweep), None if sheet is None else validate(_SheetTemplate, {SHEET: sheet}).sheet


#: the most members a family may have, and values a range may give: a bound on work, checked before any is made
MAX_MEMBERS = 10_000


def _number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _values(key: str, spec: Any) -> list:
    if isinstance(spec, list):
        if not spec:
            raise SpecError("needs at least one value", f"sweep.{key}")
        if len(spec) > MAX_MEMBERS:
            raise SpecError(f"a list of {len(spec)} values is more than {MAX_MEMBERS}", f"sweep.{key}")
        return spec
    if isinstance(spec, Mapping) and set(spec) == {"start", "stop", "step"}:
        start, stop, step = (spec[k] for k in ("start", "stop", "step"))
        if not all(_number(v) for v in (start, stop, step)) or step <= 0 or stop < start:
            raise SpecError(f"a range needs numbers start <= stop and step > 0 (got {dict(spec)})", f"sweep.{key}")
        count = (stop - start) / step + 1e-9                # may overflow to inf for a tiny step: refused below
        if not count < MAX_MEMBERS:
            raise SpecError(f"a range of {count + 1:.3g} values is more than {MAX_MEMBERS}", f"sweep.{key}")
        return [round(start + i * step, 12) for i in range(math.floor(count) + 1)]
    raise SpecError("must be a list of values or {start, stop, step}", f"sweep.{key}")


def factors(sweep: Mapping[str, Any]) -> list[list[tuple[tuple[str, Any], ...]]]:
    """Each factor of the product: a list of alternatives, each a tuple of (key, value) set together."""
    out = []
    for key, spec in sweep.items():
        if key == "zip":
            if not isinstance(spec, Mapping) or not spec:
                raise SpecError("must be a table of key = [values] of equal length", "sweep.zip")
            columns = {k: _values(f"zip.{k}", v) for k, v in spec.items()}
            lengths = {len(v) for v in columns.values()}
            if len(lengths) != 1:
                raise SpecError(f"zipped lists must have equal lengths (got {sorted(lengths)})", "sweep.zip")
            out.append([tuple(zip(columns, row, strict=True)) for row in zip(*columns.values(), strict=True)])
        else:
            out.append([((key, value),) for value in _values(key, spec)])
    total = math.prod(len(f) for f in out)
    if total > MAX_MEMBERS:
        raise SpecError(f"the sweep makes {total} members, more than {MAX_MEMBERS}; sweep fewer values", "sweep")
    return out


def _short_names(keys: Iterable[str]) -> dict[str, str]:
    keys = list(keys)
    last = {k: k.split(".")[-1] for k in keys}
    clashing = {k for k in keys if list(last.values()).count(last[k]) > 1}
    return {k: "".join(k.split(".")[-2:]) if k in clashing else last[k] for k in keys}


def _safe(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]", "_", text)


def members(raw: dict, sweep: Mapping[str, Any]) -> list[Member]:
    """The family's members, in product order (the first key varies slowest).

    Parameters
    ----------
    raw : dict
        The raw template the members vary (:func:`read_family`'s first).
    sweep : mapping
        The sweep table: each key a list of values or a range (``{start, stop, step}``, stop included), and a
        ``zip`` table of keys that change together.

    Returns
    -------
    list of Member
        Each member's name (the template's name and the swept keys and values, safe as a file name), its swept
        values and its raw template with them set; not validated.

    Raises
    ------
    SpecError
        Naming ``sweep.<key>`` (or ``sweep.zip``): an empty list, a range that is not start <= stop with step > 0,
        zipped lists of unequal lengths, more than 10 000 values; naming ``sweep``: more than 10 000 members, or
        two that would share a name.
    """
    name = str(raw.get("name", "family"))
    facs = factors(sweep)
    keys = [k for fac in facs for k, _ in fac[0]]
    short = _short_names(keys)
    out = []
    for combo in itertools.product(*facs):
        values = tuple(kv for group in combo for kv in group)
        label = "-".join(f"{short[k]}{v:g}" if isinstance(v, (int, float)) and not isinstance(v, bool)
                         else f"{short[k]}{v}" for k, v in values)
        member_name = _safe(f"{name}-{label}")
        if len(member_name) > 100:
            member_name = f"{member_name[:80]}-{hashlib.sha256(member_name.encode()).hexdigest()[:12]}"
        member_raw = apply_overrides(raw, [(k, v) for k, v in values])
        member_raw["name"] = member_name
        out.append(Member(member_name, values, member_raw))
    if len({m.name for m in out}) != len(out):
        raise SpecError("two members would share a name; give distinct values", "sweep")
    return out


def check_all(items: list[Member], validate: Callable[[dict], Any]) -> list[Any]:
    """Validate every member before any work: the first problem is one clear error naming the member; the
    members' specs."""
    specs = []
    for m in items:
        try:
            specs.append(validate(m.raw))
        except SpecError as exc:
            raise SpecError(f"member {m.name}: {exc}", "sweep") from None
    return specs


def _figures_asked(specs: list[Any]) -> bool:
    """Whether any member draws figures (``"png"`` or ``"svg"`` in its ``output.formats``, as ``output.figures``
    puts them): the family's overview figure (PNG) is drawn with them."""
    return any(set(FIGURE_FORMATS) & set(getattr(getattr(s, "output", None), "formats", ())) for s in specs)


Builder = Callable[[dict, Path], dict]


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _done(member: Member, folder: Path) -> dict | None:
    """The row of a member an earlier run finished, if its marker, row and every file it lists are intact."""
    try:
        marker = json.loads((folder / MARKER).read_text())
        if marker["inputs"] != member.inputs_hash:
            return None
        if any(_sha256(folder / name) != digest for name, digest in marker["files"].items()):
            return None
        return json.loads((folder / "row.json").read_text())
    except (OSError, ValueError, KeyError, TypeError):        # missing, damaged or from an older version
        return None


def _clear_temporaries(folder: Path) -> None:
    """Remove the temporary files an interrupted run left (``.<name>.<pid>.tmp``)."""
    for temp in folder.glob(".*.tmp"):
        temp.unlink(missing_ok=True)


def _failure(exc: BaseException) -> str:
    """A member's failure in one line: the project's message, or the kind of failure and what it said."""
    if isinstance(exc, CamgenError):
        return str(exc)
    if isinstance(exc, OSError):
        return f"cannot write {exc.filename or 'a file'}: {exc.strerror or exc}"
    return f"{type(exc).__name__}: {exc}"


def _run_one(builder: Builder, member: Member, root: Path) -> dict:
    """Build one member into ``root/<name>`` unless a finished earlier build is there, intact.

    A failure of any kind is recorded in the member's row; the marker, written last, records the hash
    of the inputs and of every file, so a deleted or changed file makes the next run build it again.
    """
    folder = root / member.name
    if folder.is_dir():
        _clear_temporaries(folder)
    previous = _done(member, folder)
    if previous is not None:
        return {**previous, "reused": True}
    row = {"name": member.name, **{k: v for k, v in member.values}}
    try:
        figures = builder(member.raw, folder)
        row.update({"status": "ok", "error": "", **figures})
    except Exception as exc:                              # recorded, and the family goes on
        row.update({"status": "failed", "error": " ".join(_failure(exc).split())})
    folder.mkdir(parents=True, exist_ok=True)
    with staged(folder) as stage:
        stage.write("row.json", lambda p: p.write_text(json.dumps(row, sort_keys=True, default=str)))
    files = {p.name: _sha256(p) for p in sorted(folder.iterdir()) if p.is_file() and p.name != MARKER
             and not p.name.startswith(".")} | {"row.json": _sha256(folder / "row.json")}
    marker = {"inputs": member.inputs_hash, "files": dict(sorted(files.items()))}
    with staged(folder) as stage:                      # written last: the member is complete
        stage.write(MARKER, lambda p: p.write_text(json.dumps(marker, indent=1) + "\n"))
    return {**row, "reused": False}


def _run_one_packed(args: tuple) -> dict:
    return _run_one(*args)


def _run_batch(batch: list[tuple]) -> list[dict]:
    """A batch of members built one after the other in one worker (one task, one hand-over, the worker's modules
    imported once for all of them): their rows in the batch's order."""
    return [_run_one(*args) for args in batch]


def _batches(work: list[tuple], workers: int) -> list[list[tuple]]:
    """``work`` cut, in order, into batches for ``workers`` that shrink as the work runs out (guided
    self-scheduling): each batch a ``2 * workers``-th of the members not yet handed out, at most
    ``PROGRESS_CHUNK`` (so that the progress bar moves) and at least one. The last batches are single members,
    so the workers finish within about a member of each other: equal batches of 8 left one worker building up to
    8 members alone at the end (a 25th batch of a family of 200 on two workers: 4 % of its time)."""
    share = 2 * max(1, workers)
    batches, i = [], 0
    while i < len(work):
        size = min(PROGRESS_CHUNK, -(-(len(work) - i) // share))
        batches.append(work[i:i + size])
        i += size
    return batches


def _end_with_parent() -> None:
    """In a worker process: end it as soon as the process that started it is gone, however that ended."""
    parent = os.getppid()

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.2)
        os.kill(os.getpid(), signal.SIGKILL)

    threading.Thread(target=watch, daemon=True).start()


def _client(address: str) -> Any:
    """A Dask client of the scheduler at ``address``, or a one-line error naming ``--scheduler``."""
    try:
        from dask.distributed import Client
    except ImportError:
        raise SpecError("needs dask.distributed: pip install 'camgen[dask]'", "--scheduler") from None
    try:
        return Client(address, timeout=10)
    except (OSError, TimeoutError, ValueError) as exc:
        raise SpecError(f"cannot reach a Dask scheduler at {address}: {exc}", "--scheduler") from None


#: the most members a local worker is handed at once: the progress bar moves each time a batch is done (a batch of
#: a family's eighth a worker, as before, held it still for minutes in a family of thousands), and a batch of 8
#: keeps the cost of handing out work (under a millisecond a batch) small beside building its members
PROGRESS_CHUNK = 8


def run_family(items: list[Member], root: str | Path, builder: Builder, jobs: int = 1,
               progress: bool | None = None, scheduler: str | None = None) -> list[dict]:
    """Build every member (``jobs`` local processes, or the Dask cluster at ``scheduler``), resuming where a
    previous run stopped; rows sorted by name. Workers write into ``root``, which they must share; local
    workers end when this process ends, however it ends.

    Parameters
    ----------
    items : list of Member
        The members (:func:`members`).
    root : str or Path
        The family's folder: each member is built into ``root/<member>/``.
    builder : callable
        ``builder(raw, folder)`` builds one member's raw template into its folder and returns its key figures (a
        dict); anything it raises is recorded in that member's row.
    jobs : int, optional
        Local worker processes (1: in this process).
    progress : bool or None, optional
        Show a progress bar on the standard error; None: only where it is a terminal.
    scheduler : str or None, optional
        The address of a Dask scheduler to run the members on instead (the ``dask`` extra).

    Returns
    -------
    list of dict
        One row a member, sorted by name: its name and swept values, ``status`` (``"ok"`` or ``"failed"``), the
        one-line ``error``, the builder's figures, and ``reused`` (an intact earlier build was kept).
    """
    from tqdm import tqdm

    root = Path(root)
    client = _client(scheduler) if scheduler is not None else None
    root.mkdir(parents=True, exist_ok=True)
    _clear_temporaries(root)
    bar = tqdm(total=len(items), unit="part", disable=not sys.stderr.isatty() if progress is None else not progress)
    rows = []
    work = [(builder, m, root) for m in items]
    if client is not None:
        from dask.distributed import as_completed

        with client:                        # batches, not members: one task a batch for the scheduler to place
            workers = sum(client.nthreads().values())
            for future in as_completed(client.map(_run_batch, _batches(work, workers), pure=False)):
                done = future.result()
                rows += done
                bar.update(len(done))
    elif jobs <= 1:
        for args in work:
            rows.append(_run_one_packed(args))
            bar.update()
    else:
        with ProcessPoolExecutor(max_workers=jobs, initializer=_end_with_parent) as pool:
            for done in pool.map(_run_batch, _batches(work, jobs)):
                rows += done
                bar.update(len(done))
    bar.close()
    return sorted(rows, key=lambda r: r["name"])


#: a row's keys that the summary's files leave out: the overview's thumbnail (its ring, its kind, the bore drawn in
#: it) and whether an earlier run built the member
_NOT_COLUMNS = {"reused", "thumbnail", "thumbnail_kind", "thumbnail_bore"}


def write_summary(rows: list[dict], root: str | Path, keys: list[str], overview: Any = None,
                  page: str | None = None) -> list[str]:
    """summary.csv and summary.json (one row per member), the overview figure as PNG and the family's page
    (``overview.html``, see :func:`family_page`), all-or-nothing."""
    columns = ["name", *keys, "status", "error"]
    extra = sorted({k for r in rows for k in r} - set(columns) - _NOT_COLUMNS)
    columns += extra
    clean = [{k: r.get(k, "") for k in columns} for r in rows]
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=columns)
    writer.writeheader()
    for r in clean:
        writer.writerow({k: json.dumps(v) if isinstance(v, (list, dict)) else v for k, v in r.items()})
    written = []
    with staged(root) as stage:
        written.append(stage.write("summary.csv", lambda p: p.write_text(text.getvalue())).name)
        written.append(stage.write("summary.json", lambda p: p.write_text(
            json.dumps(clean, indent=2, default=str) + "\n")).name)
        if overview is not None:
            written.append(stage.write("overview.png", lambda p: save(overview, p, "png")).name)
        if page is not None:
            written.append(stage.write("overview.html", lambda p: p.write_text(page, encoding="utf-8")).name)
    return written


#: a row's keys that are no figure of the member (the family's page leaves them out of its table)
_NOT_FIGURES = {"name", "status", "error", "files", *_NOT_COLUMNS}


def family_page(title: str, rows: list[dict], root: str | Path, keys: list[str]) -> str | None:
    """The family's page (:func:`camgen.core.page.family_html`) from the members' own pages in ``root``, their
    swept ``keys`` and their rows; None when no member wrote a page (``output.formats`` without html)."""
    from camgen.core.page import Member, family_html

    root = Path(root)
    members = []
    for r in rows:
        own = f"{r['name']}.html"
        path = root / r["name"] / own
        written = r.get("status") == "ok" and own in str(r.get("files", "")).split() and path.is_file()
        members.append(Member(r["name"], f"{r['name']}/{own}" if written else None, {k: r.get(k) for k in keys}, r,
                              path.read_text(encoding="utf-8") if written else None))
    if not any(m.page for m in members):
        return None
    figures = sorted({k for r in rows for k in r} - _NOT_FIGURES - set(keys))
    return family_html(title, members, [*keys, "status", *figures])


def build_family(template: str | Path, root: str | Path, validate: Callable[[dict], Any], builder: Builder,
                 jobs: int = 1, scheduler: str | None = None,
                 nestable: Callable[[Any], str | None] | None = None,
                 thumbnail_bore: Callable[[Any], float] | None = None) -> list[dict]:
    """Everything ``family`` does: expand, validate every member, build (or resume), write the summary, and with a
    ``[sheet]`` table the members' cut parts nested on sheets (:func:`write_family_sheet`). ``nestable`` (a member's
    spec -> why the sheet cannot nest its cut part, None where it can) is checked for every member before any is
    built (see :func:`check_sheet`); ``thumbnail_bore`` (a member's spec -> the bore, mm, drawn about the centre of
    its thumbnail in the overview; None: none) is the overview's alone, not the members' files."""
    raw, sweep, table = split_family(read_template(template))
    items = members(raw, sweep)
    specs = check_all(items, validate)
    if table is not None:
        check_sheet(items, specs, nestable)
    figures = _figures_asked(specs)
    rows = run_family(items, root, builder, jobs, scheduler=scheduler)
    keys = [k for k, _ in items[0].values]
    title = f"{raw.get('name')}: {len(rows)} members"
    overview = None
    if figures:
        from camgen.core.figures import overview_figure

        bores = {m.name: thumbnail_bore(s) for m, s in zip(items, specs, strict=True)} if thumbnail_bore else {}
        shown = [{**r, "thumbnail_bore": bores.get(r["name"], 0.0)} for r in rows]     # the overview's, not the files'
        overview = overview_figure(shown, title)
    write_summary(rows, root, keys, overview, family_page(title, rows, root, keys))
    if table is not None:
        write_family_sheet(str(raw.get("name", "family")), items, rows, root, table)
    return rows


#: the family template's table of its cut sheet
SHEET = "sheet"


def check_sheet(items: list[Member], specs: list[Any], nestable: Callable[[Any], str | None] | None) -> None:
    """Before any member is built: refuse, naming ``sheet``, a ``[sheet]`` table whose members do not each write one
    cut part ``<member>.dxf`` to nest (``nestable``: a spec -> why not, None where it does; None for a product whose
    members nest their parts on sheets of their own)."""
    if nestable is None:
        raise SpecError("these members nest their parts on sheets of their own (parts.sheet); a family's [sheet] "
                        "table nests camgen's cams", SHEET)
    for member, spec in zip(items, specs, strict=True):
        why = nestable(spec)
        if why is not None:
            raise SpecError(f"member {member.name}: {why}", SHEET)


class SheetTable(Model):
    """A family template's ``[sheet]`` table: the sheet the members' cut parts are nested on."""

    size: tuple[SheetSide, SheetSide] = Field((600.0, 400.0), description="sheet width and height",
                                              json_schema_extra=unit("mm"))
    margin: float = Field(3.0, ge=0, le=1000.0, description="gap between parts beyond the largest member's kerf",
                          json_schema_extra=unit("mm"))
    rotations: float = Field(90.0, ge=0, le=360.0, description="rotation step, 0 (as drawn only) or a divisor "
                             "of 360 of at least 1", json_schema_extra=unit("degrees"))
    grain: bool = Field(False, description="keep the grain: parts turn by 0 or 180 degrees only")

    @field_validator("rotations")
    @classmethod
    def _divides_a_turn(cls, step: float) -> float:
        # at least 1 degree: each rotation is a layout tried (1e-12 divides 360 to rounding: 3.6e14 of them)
        if step != 0 and (step < 1.0 or abs(360 / step - round(360 / step)) >= 1e-9):
            raise ValueError(f"must be 0 or divide 360 degrees in steps of at least 1 (e.g. 90, 45, 15) "
                             f"(got {step!r})")
        return step


class _SheetTemplate(Model):
    """What validates the ``[sheet]`` table, so that its errors name ``sheet.<key>``."""

    sheet: SheetTable


def write_family_sheet(name: str, items: list[Member], rows: list[dict], root: str | Path,
                       table: SheetTable) -> list[str]:
    """The cut parts of every member built (each member's ``<member>.dxf``, read back) nested on sheets of the
    ``[sheet]`` table (:mod:`camgen.core.nesting`, gap: the largest member's ``output.kerf`` + ``margin``), written
    as ``<name>-sheet.dxf`` (``-sheet-1``, ``-sheet-2``, ... for several) with ``<name>-sheet.json`` (the layout and
    its utilisation against shelf packing); all or nothing. Raises :class:`SpecError` (``sheet.size``) for a part
    no sheet holds, before any sheet is written."""
    from camgen.core.nesting import SheetRules, nest, rotations_of, sheet_kinds
    from camgen.core.writers.dxf import write_dxf

    root = Path(root)
    ok = {r["name"] for r in rows if r.get("status") == "ok"}
    parts = tuple(part for m in items if m.name in ok and (root / m.name / f"{m.name}.dxf").is_file()
                  for part in [read_cut_part(root / m.name / f"{m.name}.dxf", m.name)])
    if not parts:
        raise SpecError("the members wrote no cut file to nest: add \"dxf\" to output.formats", SHEET)
    kerf = max(float((m.raw.get("output") or {}).get("kerf", 0.0)) for m in items)
    rules = SheetRules(table.size, kerf + table.margin, rotations_of(table.rotations, table.grain), f"{SHEET}.size")
    nested = nest(parts, rules)
    tolerance = min(p.tolerance for p in parts)
    written = []
    with staged(root) as stage:
        for kind, drawing in sheet_kinds(nested.drawings(tolerance)):
            written.append(stage.write(f"{name}-{kind}.dxf", partial(write_dxf, drawing)).name)
        written.append(stage.write(f"{name}-sheet.json", lambda p: p.write_text(
            json.dumps(nested.report, indent=1) + "\n")).name)
    return written


#: chord tolerance (mm) for reading back outlines written as lines and arcs or as chords (``output.dxf``)
READ_TOLERANCE_MM = 0.001


def read_cut_part(path: Path, name: str) -> Any:
    """A member's cut file read back as a :class:`camgen.core.parts.Part` named ``name``: its ``OUTLINE`` and
    ``HOLES`` (bulged polylines and circles exactly; outlines written as lines and arcs, or chords, as a polygon
    within READ_TOLERANCE_MM) and its ``ENGRAVE`` marks and texts; thickness 0 (a sheet is flat)."""
    import ezdxf
    import numpy as np
    import shapely
    from ezdxf import path as dxfpath
    from ezdxf.entities import LWPolyline

    from camgen.core.parts import LAYER_ENGRAVE, LAYER_HOLES, LAYER_OUTLINE, Part
    from camgen.core.shapes import Circle, Contour, Polyline, Text

    msp = ezdxf.readfile(path).modelspace()
    contours: dict[str, list] = {LAYER_OUTLINE: [], LAYER_HOLES: []}
    pieces: dict[str, list] = {LAYER_OUTLINE: [], LAYER_HOLES: []}
    marks: list = []
    for e in msp:
        layer, kind = e.dxf.layer, e.dxftype()
        if layer == LAYER_ENGRAVE and kind == "TEXT":
            marks.append((layer, Text(e.dxf.text, tuple(e.dxf.insert)[:2], e.dxf.height, e.dxf.rotation)))
        elif isinstance(e, LWPolyline):
            pts = np.array([(x, y, b) for x, y, _, _, b in e.get_points("xyseb")])
            if layer in contours and e.closed:
                contours[layer].append(Contour(pts[:, :2], pts[:, 2]))
            elif layer == LAYER_ENGRAVE:
                pts = np.vstack([pts, pts[:1]]) if e.closed else pts
                marks.append((layer, Polyline(pts[:, :2], pts[:-1, 2])))
        elif kind == "CIRCLE" and layer == LAYER_HOLES:
            contours[layer].append(Circle(tuple(e.dxf.center)[:2], e.dxf.radius))
        elif layer in pieces and kind in ("LINE", "ARC", "POLYLINE"):
            pieces[layer].append(shapely.LineString(
                [v[:2] for v in dxfpath.make_path(e).flattening(READ_TOLERANCE_MM)]))
    for layer, lines in pieces.items():
        for poly in shapely.polygonize(lines).geoms if lines else ():
            ring = np.array(shapely.orient_polygons(poly).exterior.coords)[:-1]
            contours[layer].append(Contour(ring))
    if len(contours[LAYER_OUTLINE]) != 1:
        raise SpecError(f"{path.name} holds {len(contours[LAYER_OUTLINE])} outlines, not one part", SHEET)
    outline = contours[LAYER_OUTLINE][0]
    if outline.area < 0:
        outline = outline.reversed()
    return Part(name, outline, tuple(contours[LAYER_HOLES]), 0.0, READ_TOLERANCE_MM, tuple(marks))
