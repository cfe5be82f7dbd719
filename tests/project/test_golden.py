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


def test_a_place_in_degrees_is_compared_round_the_turn():
    """A smooth extreme's place found just under 360 degrees matches one recorded just over 0 (a flat extreme at
    the turn's start, placed within the search's noise either side), as it does within the place's tolerance
    anywhere; half a turn away, or a place in mm 360 away, does not."""
    assert not list(differences({"transmission_min_at_deg": 6.9e-7}, {"transmission_min_at_deg": 359.999999445}))
    assert not list(differences({"a.limit_at_deg": 359.9999995}, {"a.limit_at_deg": 2e-7}))
    assert list(differences({"transmission_min_at_deg": 0.0}, {"transmission_min_at_deg": 180.0}))
    assert list(differences({"transmission_min_at_deg": 0.0}, {"transmission_min_at_deg": 359.99}))
    assert list(differences({"stroke_at_mm": 0.0}, {"stroke_at_mm": 360.0}))


def test_a_fingerprint_reads_a_polylines_arcs():
    """A closed polyline of two half circles (bulge 1) of radius 5: area 25 pi, length 10 pi."""
    from tests.support.golden import _polyline_area, _polyline_length

    points = [(0.0, 0.0, 1.0), (10.0, 0.0, 1.0)]
    assert math.isclose(_polyline_area(points, True), 25.0 * math.pi, rel_tol=1e-12)
    assert math.isclose(_polyline_length(points, True), 10.0 * math.pi, rel_tol=1e-12)
    square = [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (2.0, 2.0, 0.0), (0.0, 2.0, 0.0)]
    assert _polyline_area(square, True) == 4.0 and _polyline_length(square, True) == 8.0


def test_a_fingerprint_bounds_a_polylines_arcs_exactly():
    """The bounds of a polyline with arcs are the arcs' own, not a flattening's: the two half circles above are a
    circle of radius 5 round (5, 0); a slot of two half circles either way; a quarter arc clockwise (bulge
    -tan(pi/8)) from (0, 5) to (5, 0) round the origin reaches no further than its ends; the same quarter
    counter-clockwise is the other three quarters of the circle. Each against a dense sampling of the exact arc."""
    from tests.support.golden import _polyline_bounds

    def sampled(x0, y0, x1, y1, cx, cy, sweep):
        start, radius = math.atan2(y0 - cy, x0 - cx), math.hypot(x0 - cx, y0 - cy)
        t = [start + sweep * k / 200_000 for k in range(200_001)]
        xs, ys = [cx + radius * math.cos(a) for a in t], [cy + radius * math.sin(a) for a in t]
        return [min(xs), min(ys), max(xs), max(ys)]

    assert _polyline_bounds([(0.0, 0.0, 1.0), (10.0, 0.0, 1.0)], True) == pytest.approx([0, -5, 10, 5], abs=1e-12)
    slot = [(0.0, 0.0, 0.0), (20.0, 0.0, 1.0), (20.0, 8.0, 0.0), (0.0, 8.0, 1.0)]
    assert _polyline_bounds(slot, True) == pytest.approx([-4, 0, 24, 8], abs=1e-12)
    b = math.tan(math.pi / 8)
    cw = _polyline_bounds([(0.0, 5.0, -b), (5.0, 0.0, 0.0)], False)
    assert cw == pytest.approx(sampled(0, 5, 5, 0, 0, 0, -math.pi / 2), abs=1e-9) and cw == pytest.approx([0, 0, 5, 5])
    ccw = _polyline_bounds([(0.0, 5.0, 1.0 / b), (5.0, 0.0, 0.0)], False)
    assert ccw == pytest.approx(sampled(0, 5, 5, 0, 0, 0, 1.5 * math.pi), abs=1e-9)
    assert ccw == pytest.approx([-5, -5, 5, 5], abs=1e-12)
