"""Cam design's per-segment work as one vectorised pass over all segments (issue 38 item 2): each pass gives what
the per-segment path gives, within 1e-9 (mm or rad), on a program of many segments."""
from __future__ import annotations

import numpy as np
import pytest

from camgen import numeric, outline
from camgen.bench import program_template
from camgen.profile import design_cam


def _row_by_row(index, aux, cum, tolerance, factor):
    """The per-segment path: :func:`camgen.outline._spaced` of each row alone."""
    theta = [outline._spaced(i, a, c, tolerance, f) for i, a, c, f in zip(index, aux, cum, factor, strict=True)]
    return np.concatenate(theta), [t.size for t in theta]


def _vertex_by_vertex(a, lo, hi):
    """The per-peak path: :func:`camgen.numeric._vertex` of each peak alone, NaN for None."""
    found = [numeric._vertex(*map(float, row), float(low), float(high))
             for row, low, high in zip(a, lo, hi, strict=True)]
    return np.array([np.nan if t is None else t for t in found])


def _breadth_by_breadth(a2, a4, step, size):
    """The per-peak path: :func:`camgen.numeric._breadth` of each peak alone."""
    return np.array([numeric._breadth(*map(float, v)) for v in zip(a2, a4, step, size, strict=True)])


def test_chord_spacing_of_all_rows_is_each_rows_alone():
    """Random grids and counts of chords, with runs of equal counts (no chords needed there), a row needing none at
    all, and factors that round up: the same vertices as row by row."""
    rng = np.random.default_rng(38)
    aux = np.sort(rng.uniform(0.0, 3.0, (40, 65)), axis=1)
    density = rng.uniform(0.0, 5.0, (40, 64))
    density[3, 10:30] = 0.0
    density[7] = 0.0
    cum = np.zeros((40, 65))
    cum[:, 1:] = np.cumsum(density, axis=1)
    factor = rng.uniform(0.5, 3.0, 40).tolist()
    got, sizes = outline._spaced_rows(list(range(40)), aux, cum, 0.01, factor)
    want, want_sizes = _row_by_row(list(range(40)), aux, cum, 0.01, factor)
    assert sizes == want_sizes
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)


def test_chord_spacing_refuses_what_a_row_refuses():
    aux = np.tile(np.linspace(0.0, 1.0, 65), (2, 1))
    cum = np.tile(np.linspace(0.0, 1.0, 65), (2, 1))
    cum[1] *= 1e9
    with pytest.raises(Exception, match=r"motion\[5\] would need 1e\+09 vertices"):
        outline._spaced_rows([4, 5], aux, cum, 0.01, [1.0, 1.0])


@pytest.mark.parametrize("segments", [4, 64, 256])
def test_a_program_of_many_segments_is_the_per_segment_paths(segments, monkeypatch):
    """The design's outline and its analysis with the passes over all segments (chord spacing, peak estimates)
    against the per-segment paths, within 1e-9 mm."""
    spec = program_template(segments)
    fast = design_cam(spec)
    monkeypatch.setattr(outline, "_spaced_rows", _row_by_row)
    monkeypatch.setattr(numeric, "_vertices", _vertex_by_vertex)
    monkeypatch.setattr(numeric, "_breadths", _breadth_by_breadth)
    slow = design_cam(spec)
    a, b = fast.outline.contour.flatten(0.01), slow.outline.contour.flatten(0.01)
    assert a.shape == b.shape
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-9)
    assert fast.outline.max_error_mm == pytest.approx(slow.outline.max_error_mm, abs=1e-9)
    assert fast.analysis.pressure_angle_max_deg == pytest.approx(slow.analysis.pressure_angle_max_deg, abs=1e-9)


def test_peak_estimates_of_all_candidates_are_each_ones_alone():
    """The quartic vertices and breadths of every grid peak at once against the scalar ones, with coefficients that
    divide by zero (no maximum: None, here NaN) among them."""
    rng = np.random.default_rng(2)
    a = rng.normal(size=(5000, 4))
    a[::7, 1] = 0.0
    a[::11] = 0.0
    a[::13, 3] = 0.0
    lo = rng.uniform(-2.0, 0.0, 5000)
    hi = lo + rng.uniform(0.0, 3.0, 5000)
    want = _vertex_by_vertex(a, lo, hi)
    got = numeric._vertices(a, lo, hi)
    assert np.isnan(want).any() and np.array_equal(np.isnan(got), np.isnan(want))
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)
    step, size = rng.uniform(1e-3, 1e-1, 5000), rng.uniform(0.1, 1.0, 5000)
    want_b = _breadth_by_breadth(a[:, 1], a[:, 3], step, size)
    np.testing.assert_allclose(numeric._breadths(a[:, 1], a[:, 3], step, size), want_b, rtol=0, atol=1e-12)
