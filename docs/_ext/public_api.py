"""The Python API reference of a package's public names, from its ``__all__``.

``{public-api} camgen`` documents every name ``camgen.__all__`` exports, grouped by the module that defines it,
with autodoc (the docstrings, numpydoc style through napoleon): so a name added to the package's exports is on
this page without an edit here, and the page can list nothing the package does not export. A name one package
exports from another (linkgen's errors, camgen's) is shown without its members and indexed on its own package's page.
"""
from __future__ import annotations

import importlib
import inspect
from typing import Any

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles


def public(package: str) -> dict[str, list[tuple[str, Any]]]:
    """``package``'s exported names by the module that defines them (``__version__`` left out), in export order."""
    module = importlib.import_module(package)
    out: dict[str, list[tuple[str, Any]]] = {}
    for name in module.__all__:
        if name.startswith("__"):
            continue
        obj = getattr(module, name)
        home = getattr(obj, "__module__", None) if (inspect.isclass(obj) or inspect.isfunction(obj)) else None
        if home is None or not home.startswith(package.split(".")[0]):
            home = _defining_module(package, name)
        out.setdefault(home, []).append((name, obj))
    return out


def _defining_module(package: str, name: str) -> str:
    """Where a package's lazily exported ``name`` is loaded from (its ``_EXPORTS`` map)."""
    exports = importlib.import_module(package)._EXPORTS
    return exports[name]


def directive_of(obj: Any) -> str:
    """The autodoc directive for ``obj``: a class, a function, or data."""
    if inspect.isclass(obj):
        return "autoclass"
    if callable(obj):
        return "autofunction"
    return "autodata"


class PublicApi(SphinxDirective):
    """``{public-api} PACKAGE``: a section a module, each exported name documented by autodoc."""

    required_arguments = 1

    def run(self) -> list[nodes.Node]:
        package = self.arguments[0]
        lines: list[str] = []
        for module, names in public(package).items():
            lines += [f"``{module}``", "-" * (len(module) + 4), "", f".. currentmodule:: {module}", ""]
            for name, obj in names:
                lines.append(f".. {directive_of(obj)}:: {name}")
                if not module.startswith(package.split(".")[0] + "."):
                    lines.append("   :no-index:")           # another package's (linkgen's errors): indexed there
                elif inspect.isclass(obj):
                    lines.append("   :members:")
                if directive_of(obj) == "autodata":
                    lines += ["   :no-value:", "   :annotation:"]
                lines.append("")
        container = nodes.section()
        nested_parse_with_titles(self.state, StringList(lines, source=f"public-api {package}"), container)
        return container.children


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("public-api", PublicApi)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
