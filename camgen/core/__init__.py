"""The shared layer of camgen and linkgen: everything both products use, nothing either product owns.

It imports nothing else of camgen and nothing of linkgen (an import-linter contract in
``pyproject.toml`` checks it). Its modules, from the bottom up:

* :mod:`~camgen.core.errors`: the error contract (one base class, one subclass a kind of failure);
* :mod:`~camgen.core.options`: option strings checked against their allowed values;
* :mod:`~camgen.core.reading`: a user's file read only when it is a regular file;
* :mod:`~camgen.core.spec`: the pydantic base of every spec, TOML reading, ``base`` includes,
  ``--set`` overrides, one-line messages with field paths;
* :mod:`~camgen.core.shapes`: plane geometry with exact arcs (contours, circles, open lines, text);
* :mod:`~camgen.core.parts`: flat parts, drawings with layers, and the allowances (kerf, printing
  clearance) applied to them in one place; :mod:`~camgen.core.features`: keyed bores, bolt circles;
* :mod:`~camgen.core.solids`: meshes from parts (extrusion, pins);
* :mod:`~camgen.core.figures`: matplotlib figures shared by both products (drawings, family overviews);
* :mod:`~camgen.core.writers`: one writer a format behind one registry;
* :mod:`~camgen.core.bundle`: a result's files, written all-or-nothing;
* :mod:`~camgen.core.family`: sweeps, jobs, Dask, resume, summaries;
* :mod:`~camgen.core.cli`: the command-line plumbing both commands share;
* :mod:`~camgen.core.bench`: what both benches share (timing, hard cases, results files).
"""
from __future__ import annotations

#: the project's version (both products share it); written into reports and family markers
VERSION = "0.2.0"
