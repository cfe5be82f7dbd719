"""The architecture as code: the import-linter contracts in pyproject.toml hold, each is shown to catch a
forbidden import once, the layers name every module, the wildcards cover a module added later, and only
command-line modules print or exit."""
from __future__ import annotations

import ast
import os
import re
import shutil
import subprocess
import sys
import tomllib

import pytest

from tests.conftest import ROOT

CONFIG = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]
CONTRACTS = {c["id"]: c for c in CONFIG["contracts"]}
CLI_MODULES = {"camgen/cli.py", "camgen/core/cli.py", "linkgen/cli.py"}


def _lint(root, *contracts: str) -> subprocess.CompletedProcess:
    """lint-imports on the packages under ``root`` (their own copy, found first on the path), no cache."""
    code = ("import sys; from importlinter.cli import lint_imports; "
            f"sys.exit(lint_imports(config_filename='pyproject.toml', limit_to_contracts={tuple(contracts)!r}, "
            "no_cache=True, no_logo=True))")
    env = {**os.environ, "PYTHONPATH": str(root)}
    return subprocess.run([sys.executable, "-c", code], cwd=root, env=env, capture_output=True, text=True)


def test_the_contracts_hold():
    result = _lint(ROOT, *CONTRACTS)
    assert result.returncode == 0, result.stdout + result.stderr
    assert f"{len(CONTRACTS)} kept, 0 broken" in result.stdout


#: for each contract, one import that breaks it: (file, line to add)
BREAKS = {
    "core": ("camgen/core/errors.py", "import linkgen.cli"),
    "linkgen": ("linkgen/__init__.py", "import camgen.profile"),
    "kinematics": ("camgen/kinds/geneva/kinematics.py", "import pydantic"),    # a kind's, by the wildcard
    "kinds": ("camgen/kinds/plate/kind.py", "import camgen.kinds.disc.kind"),
    "cli": ("camgen/profile.py", "import click"),
    "flow": ("camgen/cam.py", "import camgen.outputs"),
    "linkgen-kinematics": ("linkgen/kinematics/fourbar.py", "import pydantic"),
    "linkgen-gears": ("linkgen/gears/involute.py", "import shapely"),
    "linkgen-flow": ("linkgen/parts.py", "import linkgen.linkage_design"),
}


@pytest.mark.parametrize("contract", sorted(BREAKS))
def test_each_contract_catches_a_forbidden_import(contract, tmp_path):
    assert set(BREAKS) == set(CONTRACTS)
    for package in ("camgen", "linkgen"):
        shutil.copytree(ROOT / package, tmp_path / package, ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    path, line = BREAKS[contract]
    target = tmp_path / path
    target.write_text(target.read_text() + f"\n{line}  # noqa\n")
    result = _lint(tmp_path, contract)
    assert result.returncode != 0 and "1 broken" in result.stdout, result.stdout + result.stderr


def _top_level(package: str) -> set[str]:
    """Every module and sub-package directly under ``package`` (dotted names)."""
    names = set()
    for path in (ROOT / package).iterdir():
        if path.name.startswith("_"):
            continue
        if path.suffix == ".py" or (path / "__init__.py").exists():
            names.add(f"{package}.{path.stem}")
    return names


def _layered(contract: str) -> set[str]:
    return {m.strip() for layer in CONTRACTS[contract]["layers"] for m in re.split(r"[|:]", layer)}


def test_the_layers_name_every_module():
    """Layers are an order, so they name modules; a new module must take its place in them as soon as it exists.
    The forbidden contracts name none: their wildcards cover a new module by themselves (next test)."""
    assert _layered("flow") == _top_level("camgen")
    assert _layered("linkgen-flow") == _top_level("linkgen")


#: for each wildcard contract, a module that does not exist yet, and the file that imports it
NEW_MODULE = {
    "core": ("camgen/brand_new.py", "camgen/core/errors.py", "import camgen.brand_new"),
    "linkgen": ("camgen/brand_new.py", "linkgen/kit.py", "import camgen.brand_new"),
    "kinematics": ("camgen/kinds/brand_new/page.py", "camgen/kinds/brand_new/kinematics.py",
                   "import camgen.kinds.brand_new.page"),
    "linkgen-kinematics": ("linkgen/brand_new.py", "linkgen/kinematics/fourbar.py", "import linkgen.brand_new"),
    "linkgen-gears": ("camgen/core/brand_new.py", "linkgen/gears/involute.py", "import camgen.core.brand_new"),
}


@pytest.mark.parametrize("contract", sorted(NEW_MODULE))
def test_a_new_module_is_covered_by_the_wildcards(contract, tmp_path):
    """No forbidden contract lists modules by hand: a module added tomorrow is forbidden as soon as it exists."""
    assert not any(m for c in NEW_MODULE for m in CONTRACTS[c]["forbidden_modules"]
                   if m.startswith(("camgen.", "linkgen.")) and "*" not in m)
    for package in ("camgen", "linkgen"):
        shutil.copytree(ROOT / package, tmp_path / package, ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    module, importer, line = NEW_MODULE[contract]
    for folder in (tmp_path / module).relative_to(tmp_path).parents:
        if folder.name and not (tmp_path / folder / "__init__.py").exists():
            (tmp_path / folder).mkdir(parents=True, exist_ok=True)
            (tmp_path / folder / "__init__.py").write_text("")
    (tmp_path / module).write_text('"""A module the contracts have never heard of."""\n')
    target = tmp_path / importer
    target.write_text((target.read_text() if target.exists() else "") + f"\n{line}  # noqa\n")
    result = _lint(tmp_path, contract)
    assert result.returncode != 0 and "1 broken" in result.stdout, result.stdout + result.stderr


def _calls(path) -> list[str]:
    """Names of the print and exit calls in a source file."""
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Call):
            f = node.func
            name = f.id if isinstance(f, ast.Name) else f"{getattr(f.value, 'id', '?')}.{f.attr}" \
                if isinstance(f, ast.Attribute) else ""
            if name in ("print", "exit", "quit", "sys.exit", "os._exit"):
                found.append(f"{path.relative_to(ROOT)}:{node.lineno} {name}")
    return found


def test_only_command_line_modules_print_or_exit():
    library = [p for pkg in ("camgen", "linkgen") for p in (ROOT / pkg).rglob("*.py")
               if p.relative_to(ROOT).as_posix() not in CLI_MODULES]
    assert len(library) > 40
    assert [c for p in library for c in _calls(p)] == []
    assert _calls(ROOT / "camgen" / "core" / "cli.py")          # the check sees a real exit
