"""The gallery: every bundled template built at docs build time, grouped by kind.

``{gallery}`` (a MyST directive) builds each bundled template (:mod:`camgen.core.examples`) once, with the command
that runs it, into ``<html output>/gallery-files/<name>/`` (two processes at a time; only the formats shown:
the cut drawing, the page, and for a cam its S-V-A-J figure as SVG), and writes for each: its one-line summary,
its figure and cut drawing, links to its interactive page and to its template, and the template's source.
A template that fails to build fails the docs build. ``CAMGEN_DOCS_GALLERY=0`` leaves the gallery out (a quick
build while writing pages); ``CAMGEN_DOCS_GALLERY_BUILT=FOLDER`` takes each template's files from ``FOLDER/<name>``,
built already with :func:`arguments` (the test suite builds them once for its plain-install check), instead of
building them again.
"""
from __future__ import annotations

import concurrent.futures
import multiprocessing
import os
import shutil
from pathlib import Path
from typing import Any

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

#: the groups, in order: (title, the kinds in it)
GROUPS = (
    ("Disc cams", ("disc",)), ("Plate cams", ("plate",)), ("Grooved face cams", ("grooved",)),
    ("Barrel cams", ("barrel",)), ("Conjugate cams", ("conjugate",)), ("Geneva drives", ("geneva",)),
    ("Machines: cams driving linkages", ("machine",)),
    ("Four-bars, slider-cranks, quick returns and straight-line linkages", ("mechanism",)),
    ("Any planar linkage: six-bars, legs, presses", ("linkage",)), ("Kits", ("kit",)),
    ("Families", ("family",)), ("Synthesis", ("synthesis",)),
)
#: the folder under the HTML output the builds go to
FILES = "gallery-files"
#: what a cam build writes for the gallery: its cut drawing, page, report and figures as SVG
CAM_FORMATS = '["cut-svg","html","json","svg"]'
#: what a linkage build writes: its sheet and assembly drawings, page and report (analysed: figures as SVG)
BUILD_FORMATS = '["cut-svg","html","json"]'
ANALYZE_FORMATS = '["html","json","svg"]'


def kind_of(path: Path, command: str) -> str:
    """The gallery group's kind of the template at ``path``: a cam kind, ``geneva``, ``mechanism`` (a dedicated
    linkage type), ``linkage`` (any planar linkage), ``kit``, ``family`` or ``synthesis``."""
    from camgen.core.spec import read_template

    if command == "family":
        return "family"
    if command == "synthesize":
        return "synthesis"
    raw = read_template(path)
    if "kit" in raw:
        return "kit"
    if "geneva" in raw:
        return "geneva"
    if "machine" in raw:
        return "machine"
    if "linkage" in raw:
        return "linkage" if raw["linkage"].get("type") == "linkage" else "mechanism"
    return str(raw.get("cam", {}).get("kind", "disc"))


def arguments(name: str, path: Path, program: str, command: str, folder: Path) -> list[str]:
    """The command line (after the program) that builds the template for the gallery."""
    if command == "family":
        return ["family", str(_family_template(path, program, folder)), "-o", str(folder), "--jobs", "1"]
    if command == "synthesize":
        return ["synthesize", str(path), "-o", str(folder), "--figures"]
    if program == "camgen":
        return ["build", str(path), "-o", str(folder), "--set", f"output.formats={CAM_FORMATS}"]
    formats = BUILD_FORMATS if command == "build" else ANALYZE_FORMATS
    return [command, str(path), "-o", str(folder), "--set", f"output.formats={formats}"]


def _family_template(path: Path, program: str, folder: Path) -> Path:
    """A template beside the family's folder that is the family with its members' formats those the gallery shows
    (a family command takes no ``--set``): its ``base`` is the bundled template."""
    from camgen.core.spec import read_template

    parts = "linkage" not in read_template(path) or "parts" in read_template(path)
    formats = '["cut-svg","html","json"]' if parts else '["html","json","svg"]'
    template = folder.parent / f"{folder.name}.gallery.toml"
    template.write_text(f"base = {str(path.resolve())!r}\n\n[output]\nformats = {formats}\n", encoding="utf-8")
    return template


def build(name: str, path: str, program: str, command: str, folder: str) -> tuple[str, int, str]:
    """Build one template into ``folder`` (run in a worker process): (name, exit code, output)."""
    from click.testing import CliRunner

    if program == "camgen":
        from camgen.cli import main
    else:
        from linkgen.cli import main
    shutil.rmtree(folder, ignore_errors=True)
    result = CliRunner().invoke(main, arguments(name, Path(path), program, command, Path(folder)))
    return name, result.exit_code, result.output


def _first(folder: Path, patterns: tuple[str, ...]) -> Path | None:
    for pattern in patterns:
        found = sorted(folder.glob(pattern))
        if found:
            return found[0]
    return None


def shown(name: str, folder: Path) -> dict[str, Path | None]:
    """The files an entry shows: its figure, its cut drawing and its page (None where the build has none)."""
    return {
        "figure": _first(folder, (f"{name}-svaj.svg", f"{name}-assembly.svg", f"{name}-motion.svg",
                                  f"{name}-timing.svg", f"{name}-transmission.svg", "*-1-curve.svg", "*-1-motion.svg",
                                  "*/*-assembly.svg", "*/*-svaj.svg", "*/*.svg", "*.svg")),
        "drawing": _first(folder, (f"{name}-cut.svg", f"{name}-sheet.svg", f"{name}-developed.svg", f"{name}-1-cut.svg",
                                   "*/*-cut.svg", "*/*-sheet.svg")),
        "page": _first(folder, (f"{name}.html", "overview.html", "*/*.html")),
    }


def on_screen(drawing: Path) -> Path:
    """A copy of a cut drawing for the screen, beside it (``<name>.screen.svg``): its hairlines (a laser's cut lines,
    0.01 mm) drawn a pixel and a half wide whatever the scale; the drawing itself is the file as written."""
    import re

    text = drawing.read_text(encoding="utf-8")
    style = "<style>* { vector-effect: non-scaling-stroke; stroke-width: 1.5px; }</style>"
    screen = drawing.with_name(f"{drawing.stem}.screen.svg")
    screen.write_text(re.sub(r"(<svg\b[^>]*>)", lambda m: m.group(1) + style, text, count=1), encoding="utf-8")
    return screen


def _built(bundled: dict[str, Any], root: Path) -> list[str]:
    """Build every example into ``root/<name>``, two processes at a time; what failed, one line each."""
    jobs = [(e.name, str(e.path), e.program, e.command, str(root / e.name)) for e in bundled.values()]
    jobs.sort(key=lambda job: job[3] != "synthesize")                 # the slowest first
    workers = max(1, min(2, os.cpu_count() or 1))
    context = multiprocessing.get_context("spawn")
    failed = []
    with concurrent.futures.ProcessPoolExecutor(workers, mp_context=context) as pool:
        for name, code, output in pool.map(build, *zip(*jobs, strict=True)):
            if code != 0:
                failed.append(f"{name}: {output.strip()}")
    return failed


def _copied(bundled: dict[str, Any], built: Path, root: Path) -> list[str]:
    """Copy each example's files built already (``built/<name>``) into ``root/<name>``; the examples without."""
    failed = []
    for name in bundled:
        if not (built / name).is_dir():
            failed.append(f"{name}: no folder {built / name} (CAMGEN_DOCS_GALLERY_BUILT)")
            continue
        shutil.rmtree(root / name, ignore_errors=True)
        shutil.copytree(built / name, root / name)
    return failed


class Gallery(SphinxDirective):
    """``{gallery}``: every bundled template, built, grouped by kind."""

    def run(self) -> list[nodes.Node]:
        from camgen.core.examples import examples

        if os.environ.get("CAMGEN_DOCS_GALLERY") == "0":             # a quick build while writing pages
            return [nodes.paragraph("", "(The gallery is left out of this build: CAMGEN_DOCS_GALLERY=0.)")]
        bundled = examples()
        root = Path(self.env.app.outdir) / FILES
        root.mkdir(parents=True, exist_ok=True)
        built = os.environ.get("CAMGEN_DOCS_GALLERY_BUILT")
        failed = _copied(bundled, Path(built), root) if built else _built(bundled, root)
        if failed:
            raise self.error("the gallery's builds failed:\n" + "\n".join(failed))
        kinds = {e.name: kind_of(e.path, e.command) for e in bundled.values()}
        out: list[nodes.Node] = []
        for title, members in GROUPS:
            section = nodes.section(ids=[nodes.make_id(f"gallery-{title}")])
            section += nodes.title(title, title)
            for example in bundled.values():
                if kinds[example.name] in members:
                    section += self.entry(example, root / example.name)
            out.append(section)
        missing = sorted(n for n, k in kinds.items() if not any(k in members for _, members in GROUPS))
        if missing:
            raise self.error(f"no gallery group for {', '.join(missing)}")
        return out

    def entry(self, example: Any, folder: Path) -> nodes.Node:
        """One template's entry: name, summary, pictures, links, source."""
        for reference in [example.path.name, *_references(example.path)]:
            target = folder / reference
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(example.path.parent / reference, target)
        files = shown(example.name, folder)
        if files["figure"] == files["drawing"]:
            files["figure"] = None                                  # a family's member: its one drawing
        if files["drawing"] is not None:
            files["drawing"] = on_screen(files["drawing"])
        box = nodes.container(classes=["gallery-entry"], ids=[nodes.make_id(f"example-{example.name}")])
        box += nodes.rubric(example.name, example.name)
        box += nodes.paragraph(example.summary, example.summary)

        def href(path: Path) -> str:
            return f"{FILES}/{path.relative_to(folder.parent).as_posix()}"

        pictures = "".join(f'<figure class="gallery-picture"><img src="{href(p)}" alt="{example.name} {what}" '
                           f'loading="lazy"><figcaption>{what}</figcaption></figure>'
                           for what, p in (("figure", files["figure"]), ("cut drawing", files["drawing"]))
                           if p is not None)
        if pictures:
            box += nodes.raw("", f'<div class="gallery-pictures">{pictures}</div>', format="html")
        links = [f'<a href="{href(folder / example.path.name)}">template</a>']
        if files["page"] is not None:
            links.insert(0, f'<a href="{href(files["page"])}">interactive page</a>')
        command = example.run_line(f"{example.name}.toml")
        flag = "--example " if example.name in _kinds(example.program) else ""
        box += nodes.raw("", f'<p class="gallery-links">{" · ".join(links)} · <code>{example.program} new '
                             f'{flag}{example.name}</code> then <code>{command}</code></p>', format="html")
        box += nodes.raw("", f"<details><summary>{example.path.name}</summary>", format="html")
        source = example.path.read_text(encoding="utf-8")
        block = nodes.literal_block(source, source, language="toml")
        box += block
        box += nodes.raw("", "</details>", format="html")
        return box


def _kinds(program: str) -> set[str]:
    """The starter kinds of ``program``: an example of the same name is copied by ``new --example NAME``."""
    if program == "camgen":
        from camgen.starters import starters

        return set(starters())
    from linkgen.starters import STARTERS

    return set(STARTERS)


def _references(path: Path) -> list[str]:
    from camgen.core.examples import references

    return references(path)


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("gallery", Gallery)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
