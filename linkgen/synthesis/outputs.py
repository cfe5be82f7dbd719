"""A synthesis as files, all or nothing: each candidate's template, report and figure, and the summary.

``DIR/summary.json`` (``{"candidates": [...]}``, best first, with the task and the search),
``DIR/summary.csv`` (one row a candidate), and per candidate ``<name>-<rank>.toml`` (a template
``linkgen analyze`` and ``linkgen build`` take as it is), ``<name>-<rank>.json`` (the report of
``linkgen analyze`` on it, with the synthesis' row) and, when asked, ``<name>-<rank>-curve.png|svg``.
"""
from __future__ import annotations

import csv
import io
import json
from functools import partial
from pathlib import Path
from typing import Any

from camgen.core.bundle import Bundle, Item, figure_files, report_file, rows_file, text_file, write_bundle
from camgen.core.toml_text import dumps
from linkgen.synthesis.candidates import Offered
from linkgen.synthesis.run import Synthesis


def summary_csv(rows: list[dict[str, Any]]) -> str:
    """The candidates' rows as CSV: every key any row has, in the order first seen; lists and tables as JSON."""
    columns: list[str] = []
    for row in rows:
        columns += [k for k in row if k not in columns]
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=columns)
    writer.writeheader()
    for row in rows:
        writer.writerow({k: json.dumps(v) if isinstance(v, (list, dict)) else v for k, v in row.items()})
    return text.getvalue()


def _comment(c: Offered, summary: dict[str, Any]) -> str:
    """The candidate's template's comment: where it comes from (``summary``: the synthesis' summary) and the
    commands that analyse it and make its parts."""
    angle = c.row.get("input_directions", c.row.get("input_angles", [None]))[0]
    at = "" if angle is None else f" --angle {angle:.6f}"
    return (f"{c.name}: candidate {c.row['rank']} of `linkgen synthesize` for {summary['name']} "
            f"({summary['kind']})\nanalyse: linkgen analyze {c.name}.toml{at}    parts: linkgen build "
            f"{c.name}.toml")


def write_synthesis(result: Synthesis, directory: str | Path, figures: bool = False) -> list[str]:
    """Write every file of ``result`` into ``directory`` (created if missing), all or nothing.

    Parameters
    ----------
    result : Synthesis
        The candidates from :func:`linkgen.synthesis.run.synthesize`.
    directory : str or Path
        The folder: a template, a report (and a figure) a candidate, and ``summary.csv`` and ``summary.json``.
    figures : bool
        Also draw each candidate's figure as PNG and SVG (off by default, as ``linkgen build``'s ``--figures``).

    Returns
    -------
    list of str
        The names of the files written.

    Raises
    ------
    ExportError
        The folder cannot be created or a file cannot be written; nothing is left written then.
    """
    return list(write_bundle(synthesis_bundle(result, figures), directory).values())


def synthesis_bundle(result: Synthesis, figures: bool = False) -> Bundle:
    """The files of ``result``, made but not written: per candidate its template (``toml``), its report
    (``json``, without a ``files`` map) and, with ``figures``, its figure (``png``, ``svg``, drawn only when
    written), each keyed
    ``<name>-<rank>_<format>`` (the figure's ``<name>-<rank>-curve_<format>``); then ``summary.json`` and
    ``summary.csv`` (keys ``summary_json``, ``summary_csv``)."""
    from linkgen.synthesis.plots import candidate_figure

    summary = result.summary()
    items: list[Item | None] = []
    for c in result.candidates:
        report = {**c.report, "synthesis": {"task": summary["task"], **c.row}}
        figure = partial(candidate_figure, f"{c.name}: {_figure_title(c.row)}", c.sketch)
        items += [text_file(dumps(c.template, _comment(c, summary)), c.name, c.name),
                  report_file(report, c.name, c.name, listing=False),
                  figure_files(figure, f"{c.name}-curve", f"{c.name}-curve") if figures else None]
    items += [report_file(summary, "summary", "summary", listing=False),
              rows_file(summary_csv(summary["candidates"]), "summary", "summary")]
    return Bundle.of(items)


def _figure_title(row: dict[str, Any]) -> str:
    """The candidate's key figure for its figure's title."""
    for key, label in (("error_mm2", "error {:.4g} mm²"), ("structural_error_percent", "structural error {:.4g} %"),
                       ("transmission_worst_deg", "worst transmission angle {:.2f}°")):
        if key in row:
            return label.format(row[key])
    return ""
