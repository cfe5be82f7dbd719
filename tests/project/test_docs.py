"""The documentation: every tutorial runs as written, and the site builds with warnings as errors, its template
reference listing every key of every model with its unit and range, its CLI reference every command and option,
its gallery every bundled template.

A tutorial runs in an empty folder, its blocks in order: a ``{code-block}`` with a ``:caption:`` is written as that
file, a ``sh`` block runs in bash (``set -euo pipefail``), ``python`` blocks run in one namespace; ``text`` blocks
are output shown to the reader and not run. ``camgen``, ``linkgen`` and ``python`` are the checkout's.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
import typing
from html.parser import HTMLParser
from pathlib import Path

import pytest

from tests.conftest import ROOT
from tests.support.plain_install import GROUP

DOCS = ROOT / "docs"
TUTORIALS = sorted(p for p in (DOCS / "tutorials").glob("*.md") if p.name != "index.md")
FENCE = re.compile(r"^```(?P<info>[^\n]*)\n(?P<body>.*?)^```[ \t]*$", re.M | re.S)


def blocks(page: Path) -> list[tuple[str, str | None, str]]:
    """The code blocks of a MyST page: (language, caption or None, content), in order."""
    out = []
    for match in FENCE.finditer(page.read_text(encoding="utf-8")):
        info, body = match["info"].strip(), match["body"]
        caption = None
        directive = re.match(r"\{code-block\}\s*(\S+)", info)
        if directive:
            language = directive.group(1)
            lines = body.splitlines(keepends=True)
            options = []
            while lines and lines[0].startswith(":"):
                options.append(lines.pop(0))
            if lines and not lines[0].strip():
                lines.pop(0)
            body = "".join(lines)
            caption = next((o.split(":", 2)[2].strip() for o in options if o.startswith(":caption:")), None)
        elif info.startswith("{"):
            continue                                     # another directive (toctree, raw, ...)
        else:
            language = info.split()[0] if info else ""
        out.append((language, caption, body))
    return out


def checkout_commands(folder: Path) -> Path:
    """A folder of ``camgen``, ``linkgen`` and ``python`` scripts running the checkout's code."""
    folder.mkdir()
    for name, command in (("camgen", "-m camgen"), ("linkgen", "-m linkgen"), ("python", "")):
        script = folder / name
        script.write_text(f'#!/bin/sh\nexec "{sys.executable}" {command} "$@"\n')
        script.chmod(0o755)
    return folder


@pytest.fixture
def checkout_env(tmp_path, monkeypatch):
    """The environment a tutorial runs in: the checkout's commands first on PATH, its code first on PYTHONPATH."""
    bin_folder = checkout_commands(tmp_path / "bin")
    monkeypatch.setenv("PATH", f"{bin_folder}{os.pathsep}{os.environ['PATH']}")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])]))
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    return work


def test_every_tutorial_has_runnable_blocks():
    assert {p.stem for p in TUTORIALS} == {"automaton-cam", "walking-leg", "linkage-from-task", "cam-family-dask",
                                           "step-solid", "scripting"}
    for page in TUTORIALS:
        languages = {language for language, _, _ in blocks(page)}
        assert languages <= {"sh", "python", "toml", "text"}, (page.name, languages)
        assert "sh" in languages and "python" in languages, page.name
        assert all(caption for language, caption, _ in blocks(page) if language == "toml"), page.name


@pytest.mark.parametrize("page", TUTORIALS, ids=[p.stem for p in TUTORIALS])
def test_tutorial_runs_as_written(page, checkout_env):
    namespace: dict[str, typing.Any] = {"__name__": "__tutorial__"}
    for number, (language, caption, body) in enumerate(blocks(page), 1):
        where = f"{page.name}, block {number}"
        if caption is not None:
            (checkout_env / caption).write_text(body, encoding="utf-8")
        elif language == "sh":
            result = subprocess.run(["bash", "-c", "set -euo pipefail\n" + body], cwd=checkout_env, text=True,
                                    capture_output=True, timeout=600)
            assert result.returncode == 0, f"{where}:\n{body}\n{result.stdout}\n{result.stderr}"
        elif language == "python":
            exec(compile(body, where, "exec"), namespace)


def test_the_reference_states_the_base_radius_range_its_validator_keeps():
    """cam.base_radius takes a number or "auto", so its bounds live in a validator, not in the field's metadata: the
    note the reference prints gives them, and they are where validation draws the line."""
    import math

    from camgen.core.errors import SpecError
    from camgen.core.spec import validate
    from camgen.kinds.conjugate.table import ConjugateTable

    for key in ("base_radius", "second_base_radius"):
        note = ConjugateTable.model_fields[key].json_schema_extra["allowed"]
        low, high = (float(x) for x in re.search(r"> (\S+) and <= ([^\s,;]+)", note).groups())
        raw = {"kind": "conjugate", "base_radius": 40.0, "thickness": 8.0}
        for good in (high, "auto", math.nextafter(low, math.inf) + 1e-6):
            assert validate(ConjugateTable, {**raw, key: good})
        for bad in (math.nextafter(high, math.inf), low, -1.0):
            with pytest.raises(SpecError, match=rf"^{key}: must be > {low:g} and <= {high:g} mm"):
                validate(ConjugateTable, {**raw, key: bad})


def test_the_law_defaults_the_reference_states_are_the_laws_own():
    """A law parameter left out takes the law's own default (its factory's): the reference's default column says it,
    from the field's note, and the note must be that default."""
    import inspect

    from camgen.laws import REGISTRY
    from camgen.spec import SegmentTable

    checked = 0
    for name, (factory, keys) in REGISTRY.items():
        parameters = inspect.signature(factory).parameters
        for key in keys:
            default = parameters[key].default
            if default is inspect.Parameter.empty or default is None:
                continue
            stated = SegmentTable.model_fields[key].json_schema_extra["absent"]
            assert stated == (f'"{default}"' if isinstance(default, str) else f"{default:g}"), (name, key, stated)
            checked += 1
    assert checked == 8


def test_the_solid_tolerance_note_quotes_the_barrels_limit():
    from camgen.kinds.barrel.design import SINGLE_STEPS
    from camgen.core.spec import CutOutputTable

    assert f"at least {SINGLE_STEPS} single-precision steps" in \
        CutOutputTable.model_fields["tolerance"].json_schema_extra["allowed"]


def test_the_block_reader_finds_files_commands_and_code(tmp_path):
    page = tmp_path / "p.md"
    page.write_text("text\n\n```{code-block} toml\n:caption: a.toml\n\nx = 1\n```\n\n```sh\necho hi\n```\n\n"
                    "```{toctree}\nx\n```\n\n```python\nprint(1)\n```\n\n```text\nout\n```\n")
    assert blocks(page) == [("toml", "a.toml", "x = 1\n"), ("sh", None, "echo hi\n"), ("python", None, "print(1)\n"),
                            ("text", None, "out\n")]


class _Tables(HTMLParser):
    """The template-key tables of a built page: each a list of rows, a row a list of its cells' text."""

    def __init__(self) -> None:
        super().__init__()
        self.tables: list[list[list[str]]] = []
        self._inside = False
        self._cell: list[str] | None = None

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        classes = (dict(attrs).get("class") or "").split()
        if tag == "table" and "template-keys" in classes:
            self._inside = True
            self.tables.append([])
        elif self._inside and tag == "tr" and "template-key" in classes:
            self.tables[-1].append([])
        elif self._inside and tag == "td" and self.tables[-1]:
            self._cell = []

    def handle_endtag(self, tag: str) -> None:
        if tag == "td" and self._cell is not None:
            self.tables[-1][-1].append(" ".join("".join(self._cell).split()))
            self._cell = None
        elif tag == "table":
            self._inside = False

    def handle_data(self, data: str) -> None:
        if self._cell is not None:
            self._cell.append(data)


def _expected_bounds(info: typing.Any) -> list[str]:
    """A field's bounds as the reference must state them (``> 0``, ``<= 10000``), read from its metadata here."""
    out = []
    for item in info.metadata:
        for attr, sign in (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<=")):
            value = getattr(item, attr, None)
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                out.append(f"{sign} {value:g}")
    return out


def _members(annotation: typing.Any) -> list[typing.Any]:
    if typing.get_origin(annotation) in (typing.Union, __import__("types").UnionType):
        return [a for a in typing.get_args(annotation) if a is not type(None)]
    return [annotation]


def _holds_tables(annotation: typing.Any) -> bool:
    """Whether a field holds only tables (a model, a list or tuple of them, a table of them): a section, not a
    row."""
    from pydantic import BaseModel

    def table(a: typing.Any) -> bool:
        if typing.get_origin(a) is typing.Annotated:       # a tagged union's member
            return table(typing.get_args(a)[0])
        if isinstance(a, type) and issubclass(a, BaseModel):
            return True
        args = [x for x in typing.get_args(a) if x is not Ellipsis]
        if typing.get_origin(a) in (list, tuple):
            return bool(args) and all(table(x) for x in args)
        if typing.get_origin(a) is dict:
            return table(args[1])
        return False

    return all(table(m) for m in _members(annotation))


def _literal_values(annotation: typing.Any) -> list[str]:
    out = []
    for member in _members(annotation):
        for a in (member, *typing.get_args(member)):
            if typing.get_origin(a) is typing.Literal:
                out += [f'"{v}"' if isinstance(v, str) else str(v) for v in typing.get_args(a)]
    return out


def _every_model() -> list[type]:
    """Every template model of the code: each subclass of camgen.core.spec.Model defined in camgen or linkgen,
    every module imported first (so that a new table cannot be left out of the reference unnoticed)."""
    import importlib
    import pkgutil

    import camgen
    import linkgen
    from camgen.core.spec import Model

    for package in (camgen, linkgen):
        for info in pkgutil.walk_packages(package.__path__, f"{package.__name__}."):
            if not info.name.endswith("__main__"):
                importlib.import_module(info.name)

    def below(cls: type) -> list[type]:
        return [c for sub in cls.__subclasses__() for c in (sub, *below(sub))]

    return sorted({m for m in below(Model) if m.__module__.split(".")[0] in ("camgen", "linkgen")},
                  key=lambda m: (m.__module__, m.__qualname__))


@pytest.mark.slow
@pytest.mark.xdist_group(GROUP)
def test_the_docs_build_with_warnings_as_errors(tmp_path, plain_install):
    """The site as CI builds it (warnings are errors, nothing fetched; one build, as it takes minutes), then its
    generated pages checked against the code. Its gallery is the examples as the plain-install check ran them
    (built once a run, with the gallery's own command lines: :mod:`tests.support.plain_install`)."""
    site = tmp_path / "site"
    result = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-E", "-q", "-b", "html",
                             str(DOCS), str(site)], capture_output=True, text=True, timeout=1200,
                            env={**os.environ, "PYTHONPATH": str(ROOT),
                                 "CAMGEN_DOCS_GALLERY_BUILT": str(plain_install.gallery)})
    assert result.returncode == 0, result.stderr[-6000:]
    template_reference_lists_every_key_with_its_unit_and_range(site)
    cli_reference_lists_every_command_and_option(site)
    gallery_shows_every_bundled_template(site)


def template_reference_lists_every_key_with_its_unit_and_range(site: Path) -> None:
    """Every model's keys are one of the page's tables, row for row: type, unit, each bound and allowed value,
    required or not, and the description, as the model's fields give them."""
    parser = _Tables()
    parser.feed((site / "reference" / "templates.html").read_text(encoding="utf-8"))
    tables = parser.tables
    assert tables and all(len(row) == 6 for table in tables for row in table)   # key, type, unit, allowed, ...
    models = _every_model()
    assert {"DiscTable", "PlateTable", "GroovedTable", "BarrelTable", "ConjugateTable", "TranslatingRollerTable",
            "PlateKnifeEdgeTable", "DrivenOscillatingRollerTable", "BarrelTranslatingRollerTable",
            "SegmentTable", "HubTable", "GenevaTable", "CouponTable", "SheetTable", "KitTable", "CamKitTable",
            "FourBarTable", "LinkageTable", "PartsTable", "LoadTable", "PathTask"} <= \
        {m.__name__ for m in models}

    def problems(model: type, table: list[list[str]]) -> list[str]:
        rows = {row[0].split(".")[-1]: row for row in table}
        out = []
        for name, info in model.model_fields.items():
            if _holds_tables(info.annotation):
                continue
            row = rows.get(name)
            extra = info.json_schema_extra if isinstance(info.json_schema_extra, dict) else {}
            if row is None:
                out.append(f"{name}: no row")
                continue
            if row[2] != extra.get("unit", ""):
                out.append(f"{name}: unit {row[2]!r}")
            out += [f"{name}: no {b!r}" for b in _expected_bounds(info) + _literal_values(info.annotation)
                    if b not in row[3]]
            if (row[4] == "required") != info.is_required():
                out.append(f"{name}: default {row[4]!r}")
            if extra.get("allowed") and " ".join(extra["allowed"].split()) not in row[3]:
                out.append(f"{name}: no note {extra['allowed']!r}")
            if info.default is None and extra.get("absent") and row[4] != " ".join(extra["absent"].split()):
                out.append(f"{name}: default {row[4]!r}, not the note {extra['absent']!r}")
            if row[5] != " ".join((info.description or "").split()):
                out.append(f"{name}: description {row[5]!r}")
        return out

    checked = 0
    for model in models:
        keys = {name for name, info in model.model_fields.items() if not _holds_tables(info.annotation)}
        if not keys:
            continue                                    # a model of tables only: its tables are checked
        same = [t for t in tables if {row[0].split(".")[-1] for row in t} == keys]
        if not same and model.__subclasses__():
            continue                                    # a base of other tables only: theirs hold its keys
        findings = [problems(model, t) for t in same]
        assert any(not f for f in findings), (f"{model.__module__}.{model.__qualname__}: no table of its keys "
                                               f"{sorted(keys)} in the template reference", findings)
        checked += len(keys)
    assert checked > 200


def cli_reference_lists_every_command_and_option(site: Path) -> None:
    import click

    from camgen.cli import main as camgen
    from linkgen.cli import main as linkgen

    page = (site / "reference" / "cli.html").read_text(encoding="utf-8")
    for program, group in (("camgen", camgen), ("linkgen", linkgen)):
        for name, command in group.commands.items():
            assert f'id="{program}-{name}"' in page, f"{program} {name} is not in the CLI reference"
            for param in command.params:
                if isinstance(param, click.Option):
                    for opt in param.opts:
                        assert f'id="cmdoption-{program}-{name}-{opt.lstrip("-")}"' in page, \
                            f"{program} {name} {opt}"
                else:
                    assert f'id="cmdoption-{program}-{name}-arg-{param.human_readable_name}"' in page, \
                        f"{program} {name} {param.name}"


def gallery_shows_every_bundled_template(site: Path) -> None:
    from camgen.core.examples import examples

    page = (site / "gallery.html").read_text(encoding="utf-8")
    for example in examples().values():
        assert f'id="example-{example.name}"' in page, example.name
        folder = site / "gallery-files" / example.name
        assert (folder / example.path.name).is_file(), example.name
        pictures = re.findall(rf'src="(gallery-files/{re.escape(example.name)}/[^"]+)"', page)
        assert pictures and all((site / p).is_file() for p in pictures), example.name
        links = re.findall(rf'href="(gallery-files/{re.escape(example.name)}/[^"]+\.html)"', page)
        assert all((site / link).is_file() for link in links), example.name
