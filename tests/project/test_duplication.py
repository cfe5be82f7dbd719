"""No block of six or more lines stands twice in camgen/ or linkgen/, verbatim or with other names.

Each logical line is reduced to its shape: names, strings and numbers become placeholders,
keywords, operators and the builtins' names stay; comments, docstrings, imports, declarations
of data classes and fields (``@dataclass``, ``name: type = ...``) and lines of literals only are
passed over. Any run of six shapes that stands in two places is a copy
that one piece of code should serve (the project's ``duplicates`` command finds the same).
"""
from __future__ import annotations

import builtins
import io
import itertools
import keyword
import tokenize
from collections import defaultdict
from pathlib import Path

from tests.conftest import ROOT

RUN = 6
#: names that keep their spelling in a shape: the language's own and the modules every file uses
KEPT = set(dir(builtins)) | {"self", "cls", "np", "math", "dataclass"}
#: a run standing in more places than this is a common shape (dataclass fields, option lists), not a copy
COMMON = 8


def shapes(path: Path) -> list[tuple[int, str]]:
    """(first line number, shape) of every logical line that counts, in order."""
    out: list[tuple[int, str]] = []
    line: list[str] = []
    start = 0
    for tok in tokenize.generate_tokens(io.StringIO(path.read_text()).readline):
        if tok.type in (tokenize.NEWLINE, tokenize.ENDMARKER):
            if _counts(line):
                out.append((start, " ".join(line)))
            line = []
            continue
        if not line:
            start = tok.start[0]
        if tok.type == tokenize.NAME:
            line.append(tok.string if keyword.iskeyword(tok.string) or tok.string in KEPT else "N")
        elif tok.type == tokenize.STRING:
            line.append("S")
        elif tok.type == tokenize.NUMBER:
            line.append("0")
        elif tok.type == tokenize.OP:
            line.append(tok.string)
    return out


def _counts(line: list[str]) -> bool:
    """Whether a logical line is code that could be a copy: not an import, a docstring, a declaration of a
    data class or of its fields (``@dataclass``, ``name: type``) or a line of literals only."""
    if not line or line[0] in ("import", "from") or line[:2] == ["@", "dataclass"] or line == ["S"]:
        return False
    if len(line) > 1 and line[0] == "N" and line[1] == ":":
        return False
    return "N" in line or any(keyword.iskeyword(t) for t in line)


def duplicated_runs(files: list[Path]) -> list[str]:
    """Every run of RUN shapes standing in two to COMMON places, as ``a.py:10 ~ b.py:40``."""
    places: dict[tuple[str, ...], list[tuple[Path, int, int]]] = defaultdict(list)
    for path in files:
        rows = shapes(path)
        for k in range(len(rows) - RUN + 1):
            key = tuple(shape for _, shape in rows[k:k + RUN])
            spots = places[key]
            if not (spots and spots[-1][0] == path and k - spots[-1][1] < RUN):   # one repeating line
                spots.append((path, k, rows[k][0]))
    return [f"{a.relative_to(ROOT)}:{la} ~ {b.relative_to(ROOT)}:{lb}"
            for spots in places.values() if 1 < len(spots) <= COMMON
            for (a, _, la), (b, _, lb) in itertools.pairwise(spots)]


def test_no_block_of_six_lines_stands_twice():
    files = sorted(p for pkg in ("camgen", "linkgen") for p in (ROOT / pkg).rglob("*.py"))
    assert len(files) > 40
    assert duplicated_runs(files) == []


def test_the_check_finds_a_renamed_copy(tmp_path):
    code = ("def area(width, height):\n    w = float(width)\n    h = float(height)\n    if w <= 0:\n"
            "        raise ValueError('width')\n    if h <= 0:\n        raise ValueError('height')\n    return w * h\n")
    (tmp_path / "a.py").write_text(code)
    (tmp_path / "b.py").write_text(code.replace("width", "span").replace("area", "surface"))
    global ROOT
    root, ROOT = ROOT, tmp_path
    try:
        assert len(duplicated_runs([tmp_path / "a.py", tmp_path / "b.py"])) >= 1
    finally:
        ROOT = root
