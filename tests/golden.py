"""Golden files: every bundled template built through the commands users run, each file's SHA-256 recorded.

``python -m tests.golden [TEMPLATE.toml ...]`` writes ``tests/data/golden.json`` (all, or those
templates' entries only; run it when a change of the
output is intended, and say so in the commit); ``tests/test_golden.py`` rebuilds every
template and compares. Cam templates run ``camgen build``; linkage templates run
``linkgen analyze`` and, with a ``[parts]`` table, ``linkgen build``; families run
``camgen family`` or ``linkgen family``.

Figures drawn by matplotlib (PNG, and SVG figures) are recorded but compared only when
``strict`` is asked: their bytes follow matplotlib's and FreeType's versions, which CI
does not pin. Every file we serialise ourselves (DXF, cut SVG, STL, 3MF, JSON, CSV,
family markers) is compared byte for byte.
"""
from __future__ import annotations

import hashlib
import json
import sys
import tomllib
from pathlib import Path

from click.testing import CliRunner

ROOT = Path(__file__).resolve().parent.parent
GOLDEN = ROOT / "tests" / "data" / "golden.json"


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
        return []                     # synthesis tasks: searches, run by tests/test_synthesis.py
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


def build_all(root: Path, names: tuple[str, ...] = ()) -> dict[str, dict[str, str]]:
    """Build every bundled template (or those of file ``names``) under ``root``; {run id: {relative file: sha256}}."""
    from camgen.cli import main as camgen
    from linkgen.cli import main as linkgen

    programs = {"camgen": camgen, "linkgen": linkgen}
    out: dict[str, dict[str, str]] = {}
    for path in sorted((ROOT / "templates").glob("*.toml")):
        if names and path.name not in names:
            continue
        for program, args in runs(path):
            run_id = f"{program} {args[0]} {path.name}"
            folder = root / run_id.replace(" ", "_")
            result = CliRunner().invoke(programs[program], [*args, "-o", str(folder)])
            if result.exit_code != 0:
                raise RuntimeError(f"{run_id}: exit {result.exit_code}: {result.output}")
            out[run_id] = {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
                           + (" figure" if is_figure(p) else "")
                           for p in sorted(folder.rglob("*")) if p.is_file()}
    return out


def main(names: tuple[str, ...] = ()) -> None:
    """Record every template's files, or with ``names`` (``toggle-press.toml ...``) re-record those only and keep
    the other entries as they are."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        hashes = build_all(Path(tmp), names)
    if names:
        kept = {k: v for k, v in json.loads(GOLDEN.read_text()).items() if k.rsplit(" ", 1)[-1] not in names}
        hashes = {**kept, **hashes}
    GOLDEN.parent.mkdir(parents=True, exist_ok=True)
    GOLDEN.write_text(json.dumps(hashes, indent=1, sort_keys=True) + "\n")
    print(f"wrote {GOLDEN}: {sum(len(v) for v in hashes.values())} files from {len(hashes)} runs", file=sys.stderr)


if __name__ == "__main__":
    main(tuple(sys.argv[1:]))
