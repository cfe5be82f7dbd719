"""Every bundled template gives the files recorded in tests/data/golden.json, by content within tolerances.

A change that alters an output on purpose re-records them with ``python -m tests.support.golden`` and says so in its
commit; any other difference is a regression. What is compared, and how closely, is :mod:`tests.support.golden`'s
docstring; bits are not (the determinism tests compare two runs byte for byte).
"""
from __future__ import annotations

import json
import math

import pytest

from tests.support.golden import ABS, GOLDEN, all_runs, differences, prints


RECORDED = json.loads(GOLDEN.read_text())
RUNS = {f"{program} {args[0]} {path.name}": (path, program, args) for path, program, args in all_runs()}


def test_every_bundled_template_is_recorded():
    assert sorted(RUNS) == sorted(RECORDED)


@pytest.mark.parametrize("run_id", sorted(RUNS))
def test_bundled_templates_give_the_recorded_files(bundled_builds, run_id):
    built = prints(bundled_builds.folder(*RUNS[run_id]))
    recorded = RECORDED[run_id]
    assert sorted(built) == sorted(recorded), run_id
    found = [f"{name}: {line}" for name, content in recorded.items() for line in differences(content, built[name])]
    assert not found, "\n".join(found[:40])


def _moved(value, by):
    """A fingerprint with every number but the counts moved by ``by`` (relative) and as much in mm."""
    if isinstance(value, dict):
        return {k: v if k == "count" else _moved(v, by) for k, v in value.items()}
    if isinstance(value, list):
        return [_moved(v, by) for v in value]
    if isinstance(value, float):
        return value * (1.0 + by) + math.copysign(by, value)
    return value


def _reworded(value):
    """A fingerprint with its first word (or flag) changed."""
    done = False

    def change(v):
        nonlocal done
        if isinstance(v, dict):
            return {k: change(x) for k, x in v.items()}
        if isinstance(v, list):
            return [change(x) for x in v]
        if not done and isinstance(v, (str, bool)):
            done = True
            return (not v) if isinstance(v, bool) else v + "x"
        return v

    out = change(value)
    assert done
    return out


@pytest.mark.parametrize("name", ["rdrd.dxf", "rdrd.json", "rdrd.stl", "rdrd-cut.svg", "rdrd.html", "rdrd.3mf"])
def test_the_comparison_takes_noise_and_finds_a_change(bundled_builds, name):
    """A fingerprint moved by a tenth of the tolerance still matches; moved by a thousand times it, or with a word
    changed, it does not."""
    built = prints(bundled_builds.folder(*RUNS["camgen build rdrd.toml"]))
    print_ = built[name]
    assert not list(differences(print_, _moved(print_, ABS / 10)))
    assert list(differences(print_, _moved(print_, ABS * 1e3)))
    assert list(differences(print_, _reworded(print_)))


def test_a_fingerprint_reads_a_polylines_arcs():
    """A closed polyline of two half circles (bulge 1) of radius 5: area 25 pi, length 10 pi."""
    from tests.support.golden import _polyline_area, _polyline_length

    points = [(0.0, 0.0, 1.0), (10.0, 0.0, 1.0)]
    assert math.isclose(_polyline_area(points, True), 25.0 * math.pi, rel_tol=1e-12)
    assert math.isclose(_polyline_length(points, True), 10.0 * math.pi, rel_tol=1e-12)
    square = [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (2.0, 2.0, 0.0), (0.0, 2.0, 0.0)]
    assert _polyline_area(square, True) == 4.0 and _polyline_length(square, True) == 8.0
