"""Sphinx configuration of the camgen / linkgen documentation (built by tests/project/test_docs.py, warnings as errors).

Pages are Markdown (myst-parser); the API reference is autodoc with napoleon (numpydoc docstrings); the CLI
reference is sphinx-click; the template-key reference and the gallery are this folder's own extensions in _ext/,
generated from the code at build time. Nothing is fetched from the network (no intersphinx, no linkcheck).
"""
from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent))             # document the checkout's code, not another installed copy

from camgen.core import VERSION  # noqa: E402

project = "camgen / linkgen"
author = "the camgen authors"
copyright = "the camgen authors, MIT licence"
version = release = VERSION

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx_click",
    "template_reference",
    "gallery",
    "public_api",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]
root_doc = "index"

myst_enable_extensions = ["colon_fence", "deflist"]
myst_heading_anchors = 3
smartquotes = False                               # "disc" in a key table is TOML: straight quotes

html_theme = "furo"
html_title = f"camgen / linkgen {VERSION}"
html_static_path = ["_static"]
html_css_files = ["gallery.css"]

# every internal reference must resolve; names from other projects (numpy, pathlib, pydantic, ...) are not
# documented here, and nothing is fetched to resolve them
nitpicky = True
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|np|pathlib|collections|typing|typing_extensions|pydantic|pydantic_core|annotated_types|"
               r"click|shapely|ezdxf|trimesh|matplotlib|dask|enum|dataclasses|concurrent|io|os|builtins|abc|"
               r"datetime)(\..*)?"),
    (r"py:.*", r"(Path|Any|Callable|Iterable|Iterator|Mapping|Sequence|MutableMapping|Literal|ClassVar|TypeVar|"
               r"Protocol|NDArray|ArrayLike|Self|BaseModel|Figure|Axes|ndarray|float64|_PydanticGeneralMetadata|"
               r"optional|array|array-like|callable|iterable|mapping|sequence|generator|Generator)"),
    # typing's Annotated in the kinds' tables' field types (length(), unit()), which autodoc qualifies by the module
    (r"py:class", r"camgen\.tables\.Annotated"),
]

autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_preserve_defaults = True                  # a default as written (MECHANISMS), not its repr
autodoc_default_options = {"exclude-members": "model_config, model_fields, model_computed_fields"}
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False
napoleon_preprocess_types = True


def _exists(target: str, module: str | None) -> bool:
    """Whether ``target`` names an object of camgen or linkgen: dotted from the top, or a name (or attribute path)
    in ``module``, the module the reference was written in."""
    import importlib

    def walk(start: object, parts: list[str]) -> bool:
        obj = start
        for part in parts:
            if not hasattr(obj, part):
                return False
            obj = getattr(obj, part)
        return True

    parts = target.split(".")
    for cut in range(len(parts), 0, -1):
        name = ".".join(parts[:cut])
        if name.split(".")[0] in ("camgen", "linkgen"):
            try:
                return walk(importlib.import_module(name), parts[cut:])
            except ImportError:
                continue
    if module:
        try:
            if walk(importlib.import_module(module), parts):
                return True
        except ImportError:
            pass
    # a name a module imports only for its annotations (under TYPE_CHECKING): defined in some module of ours
    _import_all()
    return any(walk(loaded, parts) for key, loaded in list(sys.modules.items())
               if key.split(".")[0] in ("camgen", "linkgen") and loaded is not None)


def _import_all() -> None:
    """Import every module of camgen and linkgen once (a name imported for annotations only is found in its own)."""
    import importlib
    import pkgutil

    import camgen
    import linkgen

    if getattr(_import_all, "done", False):
        return
    for package in (camgen, linkgen):
        for info in pkgutil.walk_packages(package.__path__, f"{package.__name__}."):
            if not info.name.endswith("__main__"):
                importlib.import_module(info.name)
    _import_all.done = True


def _unlinked(app, env, node, contnode):
    """A reference to an object of camgen or linkgen that exists but has no page of its own (a record type a
    public function returns, a private helper a docstring names) is shown as code, unlinked; a reference to
    something that does not exist still fails the build."""
    if node.get("refdomain") != "py":
        return None
    if _exists(node["reftarget"].lstrip("~."), node.get("py:module")):
        return contnode
    return None


def _plain_docstring(app, what, name, obj, options, lines):
    """Docstrings written for readers of the code, made safe for reST before napoleon reads them: ``|x|`` (an
    absolute value) is not a substitution, and a property's first line is not read as "type: description"."""
    import re

    for i, line in enumerate(lines):
        if "|" in line and not line.lstrip().startswith(("+-", "+=")):
            pieces = re.split(r"(``.*?``)", line)
            lines[i] = "".join(p if p.startswith("``") else p.replace("|", r"\|") for p in pieces)
    if what in ("property", "attribute"):
        _KEPT[name] = list(lines)


#: property and attribute docstrings as written: napoleon would read their first line's "...: ..." as a type
_KEPT: dict[str, list[str]] = {}


def _as_written(app, what, name, obj, options, lines):
    """A property's or attribute's docstring back as written, after napoleon (which reads "A bound (mm) on ...:
    the outline's ..." as a type and a description): they are prose, with no numpydoc sections."""
    if name in _KEPT:
        lines[:] = _KEPT.pop(name)


def setup(app):
    app.connect("missing-reference", _unlinked)
    app.connect("autodoc-process-docstring", _plain_docstring, priority=400)
    app.connect("autodoc-process-docstring", _as_written, priority=600)
