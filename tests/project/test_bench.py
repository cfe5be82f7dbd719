"""``camgen bench --quick`` and ``linkgen bench --quick`` (run once a run, by the installed scripts: the
``quick_benches`` fixture): every figure is produced, every error is below its tolerance, peers are reported."""
from __future__ import annotations

import json

import pytest
from tests.conftest import BENCHES


@pytest.mark.slow
@pytest.mark.xdist_group(BENCHES)
def test_quick_bench_produces_every_figure(quick_benches):
    folder = quick_benches["camgen"]
    assert {p.name for p in folder.iterdir()} == {"RESULTS.md", "results.json", "speed-vs-error.png"}
    r = json.loads((folder / "results.json").read_text())
    ours = [row for row in r["outlines"] if row["method"].startswith("camgen")]
    assert len(ours) == 4 * 2 * 3                          # four standard cams, two modes, three tolerances
    assert all(0 < row["max_error_mm"] <= row["tolerance_mm"] and row["seconds"] > 0 for row in ours)
    naive = [row for row in r["outlines"] if row["method"].startswith("naive")]
    assert len(naive) == 2 and all(row["max_error_mm"] > 0 for row in naive)
    assert r["mechanism"]["status"] == "measured" or r["mechanism"]["status"].startswith("not installed")
    assert [row["cams_per_second"] > 0 and row["cpu_seconds"] > 0 for row in r["throughput"][:2]] == [True, True]
    assert r["peak_memory_mb"] > 0
    assert r["hard_cases"] and not [c for c in r["hard_cases"] if c["outcome"].startswith("WRONG")]
    text = (folder / "RESULTS.md").read_text()
    assert "## Hard cases" in text and "## Throughput" in text and "CPU seconds (workers included)" in text
    _speed_rows(r, text, {"design_cam: checks and outline (in-process)", "camgen build, every default output",
                          "camgen build --figures (the defaults and the PNG and SVG figures)",
                          "camgen build, dxf stl json", "camgen laws"})


def _speed_rows(r: dict, text: str, whats: set[str]) -> None:
    """Each speed row next to its reference measured in the same run, as a ratio with its spread (no time is
    asserted: only that each was measured)."""
    rows = {row["what"]: row for row in r["speed"]}
    assert whats <= set(rows)
    for row in rows.values():
        assert row["reference"] and row["runs"] >= 1 and row["seconds"] > 0 and row["reference_seconds"] > 0
        assert 0 < row["ratio_min"] <= row["ratio"] <= row["ratio_max"]
        assert row["ratio"] == pytest.approx(row["seconds"] / row["reference_seconds"], rel=1.0)
    assert "## Speed against yardsticks measured in the same run" in text and "x (" in text


@pytest.mark.slow
@pytest.mark.xdist_group(BENCHES)
def test_quick_linkgen_bench(quick_benches):
    folder = quick_benches["linkgen"]
    assert {p.name for p in folder.iterdir()} == {"RESULTS.md", "results.json"}
    r = json.loads((folder / "results.json").read_text())
    methods = {row["method"] for row in r["linkages"]}
    assert any(m.startswith("pylinkage") for m in methods)                              # measured, or said missing
    assert all(row.get("status") for row in r["linkages"] if row["seconds"] is None)   # never skipped silently
    assert all(row["max_error_mm"] < 1e-6 for row in r["linkages"] if row.get("max_error_mm") is not None)
    assert r["hard_cases"] and not [c for c in r["hard_cases"] if c["outcome"].startswith("WRONG")]
    general = {(row["linkage"], row["method"]): row for row in r["general"]}
    # the general solver against the four-bar's closed form and Jansen's leg against 50 digits
    assert general[("four-bar", "linkgen general solver (positions)")]["max_error_mm"] < 1e-9
    assert general[("jansen", "linkgen general solver (positions)")]["max_error_mm"] < 1e-9
    peer = [row for (name, _), row in general.items() if name == "jansen" and "pylinkage" in row["method"]]
    assert peer and (peer[0].get("status") or peer[0]["max_error_mm"] < 1e-6)
    # synthesis: each published problem solved, our error not worse than plain differential evolution's
    assert len(r["synthesis"]) == 4 and "## Synthesis" in (folder / "RESULTS.md").read_text()
    # the published problems: each paper's linkage scored beside ours, ours no worse (re-checked independently in
    # tests/synthesis/test_synthesis_published.py)
    assert [row["key"] for row in r["published"]] == ["mkh1"]                 # quick: the one that builds the atlas
    assert all(0 < row["ours_error"] <= row["published_error"] for row in r["published"])
    assert "## Published path problems" in (folder / "RESULTS.md").read_text()
    _speed_rows(r, (folder / "RESULTS.md").read_text(), {
        "four-bar positions, 100 000 crank angles", "kinetostatics of Jansen's leg, 3 600 crank angles",
        "forward dynamics of Jansen's leg, 10 turns from rest",
        "linkgen build crank-rocker, every default output"})                  # quick: the other commands left out


def test_ratio_row_leaves_its_warm_pairs_out():
    """``warm`` pairs run first, untimed: the row's figures are the later pairs' alone (median, spread, count)."""
    from camgen.core.bench import ratio_row

    ours, theirs = iter([9.0, 9.0, 2.0, 4.0, 6.0]), iter([1.0, 1.0, 1.0, 2.0, 1.0])
    row = ratio_row("a", "b", lambda: next(ours), lambda: next(theirs), 3, warm=2)
    assert (row["runs"], row["seconds"], row["reference_seconds"]) == (3, 4.0, 1.0)
    assert (row["ratio_min"], row["ratio"], row["ratio_max"]) == (2.0, 2.0, 6.0)
    assert next(ours, None) is None and next(theirs, None) is None      # every measure called once, no more


def test_plain_yardstick_has_the_fewest_vertices_that_meet_the_tolerance():
    """The yardstick's vertex count is the least that meets 0.01 mm, measured independently: its polygon against
    camgen's exact surface of the same cam (not the yardstick's own closed form) meets 0.01 mm, one vertex fewer
    does not."""
    import math

    import numpy as np

    from camgen.bench import _plain_surface, _template, plain_outline, plain_vertices
    from camgen.convergence_study import contour_error
    from camgen.core.shapes import Contour
    from camgen.flat import build_cam

    cam = build_cam(_template("cycloidal"))
    n = plain_vertices(0.01)
    assert len(plain_outline(0.01)) == n
    fewer = _plain_surface(np.linspace(0.0, 2 * math.pi, n - 1, endpoint=False))
    assert contour_error(cam, Contour(plain_outline(0.01)), 1e-3) <= 0.01 < contour_error(cam, Contour(fewer), 1e-3)
