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
its inputs, written last: a re-run skips members whose hash matches.
"""
from __future__ import annotations

import csv
import hashlib
import io
import itertools
import json
import math
import re
import sys
from collections.abc import Callable, Iterable, Mapping
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from camgen.core import VERSION as __version__
from camgen.core.errors import CamgenError, SpecError
from camgen.core.bundle import staged
from camgen.core.writers.figure import save
from camgen.core.spec import apply_overrides, read_template

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
    """The raw template (its ``base`` merged in) and its sweep table."""
    raw = read_template(path)
    sweep = raw.pop("sweep", {})
    if not isinstance(sweep, Mapping):
        raise SpecError("must be a table of key = values", "sweep")
    return raw, dict(sweep)


def _values(key: str, spec: Any) -> list:
    if isinstance(spec, list):
        if not spec:
            raise SpecError("needs at least one value", f"sweep.{key}")
        return spec
    if isinstance(spec, Mapping) and set(spec) == {"start", "stop", "step"}:
        start, stop, step = (spec[k] for k in ("start", "stop", "step"))
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in (start, stop, step)) or step <= 0 \
                or stop < start:
            raise SpecError(f"a range needs finite start <= stop and step > 0 (got {dict(spec)})", f"sweep.{key}")
        n = math.floor((stop - start) / step + 1e-9) + 1
        if n > 100_000:
            raise SpecError(f"a range of {n} values is more than 100000", f"sweep.{key}")
        return [round(start + i * step, 12) for i in range(n)]
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
    return out


def _short_names(keys: Iterable[str]) -> dict[str, str]:
    keys = list(keys)
    last = {k: k.split(".")[-1] for k in keys}
    clashing = {k for k in keys if list(last.values()).count(last[k]) > 1}
    return {k: "".join(k.split(".")[-2:]) if k in clashing else last[k] for k in keys}


def _safe(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]", "_", text)


def members(raw: dict, sweep: Mapping[str, Any]) -> list[Member]:
    """The family's members, in product order (the first key varies slowest)."""
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


def check_all(items: list[Member], validate: Callable[[dict], Any]) -> None:
    """Validate every member before any work: the first problem is one clear error naming the member."""
    for m in items:
        try:
            validate(m.raw)
        except SpecError as exc:
            raise SpecError(f"member {m.name}: {exc}", "sweep") from None


Builder = Callable[[dict, Path], dict]


def _run_one(builder: Builder, member: Member, root: Path) -> dict:
    """Build one member into ``root/<name>`` unless its inputs hash says it is already there."""
    folder = root / member.name
    row = {"name": member.name, **{k: v for k, v in member.values}}
    marker = folder / MARKER
    if marker.exists() and marker.read_text().strip() == member.inputs_hash:
        previous = json.loads((folder / "row.json").read_text())
        return {**previous, "reused": True}
    try:
        figures = builder(member.raw, folder)
        row.update({"status": "ok", "error": "", **figures})
    except CamgenError as exc:
        row.update({"status": "failed", "error": str(exc)})
    folder.mkdir(parents=True, exist_ok=True)
    with staged(folder) as stage:
        stage.write("row.json", lambda p: p.write_text(json.dumps(row, sort_keys=True, default=str)))
    with staged(folder) as stage:                      # written last: the member is complete
        stage.write(MARKER, lambda p: p.write_text(member.inputs_hash + "\n"))
    return {**row, "reused": False}


def _run_one_packed(args: tuple) -> dict:
    return _run_one(*args)


def run_family(items: list[Member], root: str | Path, builder: Builder, jobs: int = 1,
               progress: bool | None = None, scheduler: str | None = None) -> list[dict]:
    """Build every member (``jobs`` local processes, or the Dask cluster at ``scheduler``), resuming where a
    previous run stopped; rows sorted by name. Workers write into ``root``, which they must share."""
    from tqdm import tqdm

    root = Path(root)
    root.mkdir(parents=True, exist_ok=True)
    bar = tqdm(total=len(items), unit="part", disable=not sys.stderr.isatty() if progress is None else not progress)
    rows = []
    work = [(builder, m, root) for m in items]
    if scheduler is not None:
        try:
            from dask.distributed import Client, as_completed
        except ImportError:
            raise SpecError("needs dask.distributed: pip install 'camgen[dask]'", "--scheduler") from None
        with Client(scheduler) as client:
            for future in as_completed(client.map(_run_one_packed, work, pure=False)):
                rows.append(future.result())
                bar.update()
    elif jobs <= 1:
        for args in work:
            rows.append(_run_one_packed(args))
            bar.update()
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            for row in pool.map(_run_one_packed, work, chunksize=max(1, len(work) // (8 * jobs))):
                rows.append(row)
                bar.update()
    bar.close()
    return sorted(rows, key=lambda r: r["name"])


def write_summary(rows: list[dict], root: str | Path, keys: list[str], overview: Any = None) -> list[str]:
    """summary.csv and summary.json (one row per member), and the overview figure as PNG, all-or-nothing."""
    columns = ["name", *keys, "status", "error"]
    extra = sorted({k for r in rows for k in r} - set(columns) - {"reused", "thumbnail", "thumbnail_kind"})
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
    return written


def build_family(template: str | Path, root: str | Path, validate: Callable[[dict], Any], builder: Builder,
                 jobs: int = 1, scheduler: str | None = None) -> list[dict]:
    """Everything ``family`` does: expand, validate every member, build (or resume), write the summary."""
    from camgen.core.figures import overview_figure

    raw, sweep = read_family(template)
    items = members(raw, sweep)
    check_all(items, validate)
    rows = run_family(items, root, builder, jobs, scheduler=scheduler)
    write_summary(rows, root, [k for k, _ in items[0].values],
                  overview_figure(rows, f"{raw.get('name')}: {len(rows)} members"))
    return rows
