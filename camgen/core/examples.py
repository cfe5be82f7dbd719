"""The bundled example templates (``camgen examples``, ``linkgen examples``, ``camgen new NAME``): where they are, what
each is, which command runs it, and copying one out with the files it reads.

They are the checkout's top-level ``templates/`` folder, which the wheel installs as the package ``camgen.examples``
(``setup.py``): an installed camgen finds them there, and one run from a checkout (not installed) in ``templates/``
beside its ``camgen/``. A template may read other files by relative paths (a ``base`` template it starts from, a
table law's CSV ``file``, a follower's ``load_table``); :func:`copy_example` writes those beside the copy, so that
the copy works as the original does.
"""
from __future__ import annotations

import importlib.util
import os
import re
import tomllib
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from camgen.core.errors import SpecError

#: the longest one-line summary of an example (characters)
SUMMARY_WIDTH = 120


def folder() -> Path:
    """The folder holding the bundled templates: the installed package ``camgen.examples``, else (camgen run from
    a checkout) the checkout's ``templates/``.

    Raises
    ------
    SpecError
        Neither is there (a copy of camgen without its examples).
    """
    spec = importlib.util.find_spec("camgen.examples")
    if spec is not None and spec.submodule_search_locations:
        return Path(next(iter(spec.submodule_search_locations)))
    checkout = Path(__file__).resolve().parents[2] / "templates"
    if checkout.is_dir():
        return checkout
    raise SpecError("the bundled templates are not installed with this camgen (no camgen.examples package)",
                    "examples")


@dataclass(frozen=True)
class Example:
    """One bundled template.

    Attributes
    ----------
    name : str
        Its name: the file's stem (``jansen`` for ``jansen.toml``).
    path : Path
        The template file.
    summary : str
        What it is, in one line: the first sentence of its opening comment, or that sentence's head.
    program : str
        ``"camgen"`` or ``"linkgen"``: the command that takes it.
    command : str
        The sub-command that runs it: ``"build"``, ``"analyze"`` (a linkage without a ``[parts]`` table),
        ``"family"`` (a template with a ``[sweep]`` table) or ``"synthesize"`` (a synthesis task, a ``[task]``
        table).
    """

    name: str
    path: Path
    summary: str
    program: str
    command: str

    def run_line(self, template: str) -> str:
        """The command line that runs ``template`` (a copy of this example), e.g. ``linkgen build j.toml``;
        a family or a synthesis writes into ``out/<stem>``."""
        folder_option = f" -o out/{Path(template).stem}" if self.command in ("family", "synthesize") else ""
        return f"{self.program} {self.command} {template}{folder_option}"


def summary(text: str) -> str:
    """A template's one-line summary from its text: the first sentence of its opening comment lines if it fits in
    :data:`SUMMARY_WIDTH` characters, else that sentence up to its first ``": "``, else up to its first ``" ("``,
    else its first line."""
    lines = []
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        lines.append(line[1:].strip())
    if not lines:
        return ""
    joined = " ".join(line for line in lines if line)
    match = re.match(r"(.*?[.!?])(\s|$)", joined)
    sentence = match.group(1) if match else joined
    if len(sentence) <= SUMMARY_WIDTH:
        return sentence
    for mark in (": ", " ("):
        head = sentence.split(mark, 1)[0]
        if len(head) < len(sentence) and len(head) <= SUMMARY_WIDTH:
            return head
    return lines[0][:SUMMARY_WIDTH]


def _read(path: Path) -> dict[str, Any]:
    with path.open("rb") as stream:
        return tomllib.load(stream)


def _kind(path: Path) -> tuple[str, str]:
    """(program, command) of the template at ``path``, from its tables and those of the templates it is based on."""
    keys: set[str] = set()
    seen: set[Path] = set()
    while path not in seen:
        seen.add(path)
        raw = _read(path)
        keys |= set(raw)
        if not isinstance(raw.get("base"), str):
            break
        path = (path.parent / raw["base"]).resolve()
    if "task" in keys:
        return "linkgen", "synthesize"
    if "sweep" in keys:
        return "linkgen" if "linkage" in keys else "camgen", "family"
    if "linkage" in keys:
        return "linkgen", "build" if "parts" in keys else "analyze"
    return "camgen", "build"


def examples(program: str | None = None) -> dict[str, Example]:
    """The bundled templates by name, sorted; only ``program``'s (``"camgen"`` or ``"linkgen"``) when given."""
    found = {}
    for path in sorted(folder().glob("*.toml")):
        owner, command = _kind(path)
        if program is None or owner == program:
            found[path.stem] = Example(path.stem, path, summary(path.read_text(encoding="utf-8")), owner, command)
    return found


def references(path: Path) -> list[str]:
    """The files the template at ``path`` reads by relative paths, relative to its folder, and those they read in
    turn: its ``base``, each ``motion[i].file`` and a ``follower.load_table`` given as a file."""
    found: list[str] = []
    todo = [path]
    while todo:
        current = todo.pop()
        for name in _named_files(_read(current)):
            if Path(name).is_absolute():
                continue
            relative = os.path.relpath(current.parent / name, path.parent)
            if relative not in found:
                found.append(relative)
                if name.endswith(".toml"):
                    todo.append(current.parent / name)
    return found


def _named_files(raw: Mapping[str, Any]) -> Iterator[str]:
    if isinstance(raw.get("base"), str):
        yield raw["base"]
    for segment in raw.get("motion", ()) if isinstance(raw.get("motion"), list) else ():
        if isinstance(segment, Mapping) and isinstance(segment.get("file"), str):
            yield segment["file"]
    follower = raw.get("follower")
    if isinstance(follower, Mapping) and isinstance(follower.get("load_table"), str):
        yield follower["load_table"]


def copy_text(example: Example, target: Path) -> str:
    """The example's text as a copy at ``target`` holds it: its ``name`` is the target's stem (as a starter's is),
    and its comments name the copy instead of ``templates/<name>.toml`` and its files' folder ``out/<stem>/``."""
    text = example.path.read_text(encoding="utf-8")
    text = re.sub(rf"templates/{re.escape(example.name)}\.toml", target.name, text)
    text = re.sub(rf"out/{re.escape(example.name)}(?![\w.-])", f"out/{target.stem}", text)
    return re.sub(r'(?m)\A((?:[^\[\n][^\n]*\n|\n)*?)name = "[^"\n]*"', rf'\g<1>name = "{target.stem}"', text, count=1)


def copy_plan(example: Example, target: Path) -> list[tuple[Path, bytes]]:
    """What copying ``example`` to ``target`` writes: (path, content) for the template and each file it reads (the
    same relative path from the copy), leaving out a file that is there already with the same content.

    Raises
    ------
    SpecError
        On ``--output``: the target exists, or a file it reads is there with other content (nothing is ever
        overwritten).
    """
    if target.exists():
        raise SpecError(f"{target} exists; give another file", "--output")
    plan = [(target, copy_text(example, target).encode("utf-8"))]
    for name in references(example.path):
        source, destination = example.path.parent / name, target.parent / name
        content = source.read_bytes()
        if destination.exists():
            if destination.read_bytes() != content:
                raise SpecError(f"{destination} exists with other content, and {target.name} reads it: write the "
                                "copy into another folder", "--output")
            continue
        plan.append((destination, content))
    return plan
