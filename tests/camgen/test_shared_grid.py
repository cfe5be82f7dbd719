"""One evaluation serves the peaks' search and the outline's spacing.

A design searches its peaks on a grid of every moving segment, :data:`camgen.numeric.GRID` (129) points on a segment
of 45 degrees or more, fewer on a shorter one (down to 33: :func:`camgen.numeric.grid_counts`), and spaces its
outline's chords on grids of at most 65 points from each segment's start to its end: the same fractions, every second
point of the 129 (every point of a shorter grid). :func:`camgen.outline._shared_grid` reads the spacing's grids from
the search's own (a return's law variable runs from its end), and :meth:`camgen.cam.Cam.pitch_of` evaluates asks of
the very same arrays once.
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from camgen.analysis import analysis_maker
from camgen.bench import BASE, program_template
from camgen.flat import build_cam
from camgen.numeric import GRID
from camgen.outline import _AUX, _grids, _shared_grid, outline_maker
from camgen.spec import validate_spec

RDRD = Path(__file__).resolve().parents[2] / "templates" / "rdrd.toml"


def _moving(cam) -> list[tuple[int, None]]:
    return [(i, None) for i, seg in enumerate(cam.program.segments) if seg.kind != "dwell"]


def _design(cam, share: bool):
    """The analysis and the exact outline served together, as a design makes them (camgen.profile)."""
    return cam.serve([analysis_maker(cam), outline_maker(cam, 0.01, share=share)])


def _evaluated(monkeypatch: pytest.MonkeyPatch, cam) -> list[int]:
    """The count of points the follower's pitch geometry is made at, call by call (what :meth:`Cam.pitch_of`
    evaluates, after asks of the same arrays are made one)."""
    sizes: list[int] = []
    kind = type(cam.follower)
    pitch = kind.pitch

    def counted(self, theta, motion):
        sizes.append(int(np.asarray(theta).size))
        return pitch(self, theta, motion)

    monkeypatch.setattr(kind, "pitch", counted)
    return sizes


@pytest.mark.parametrize("share", [True, False])
def test_a_design_evaluates_each_moving_segment_once_in_its_first_round(monkeypatch, share):
    # 8 segments of 45 degrees: 4 moving (a grid of 129 each), 4 dwells (a translating roller is steady: its first
    # point; each dwell's outline one arc, its vertex and 7 probes), and the 8 ends and 8 starts; the outline on its
    # own grids adds 65 points on each moving segment
    cam = build_cam(program_template(8))
    sizes = _evaluated(monkeypatch, cam)
    _design(cam, share)
    assert sizes[0] == 4 * GRID + 4 + 4 * 8 + 2 * 8 + (0 if share else 4 * _AUX)


@pytest.mark.parametrize("segments, size", [(8, _AUX), (64, 33), (256, 33)])
def test_the_shared_grids_are_the_spacing_grids(segments, size):
    # a rise's grid runs with its law variable, a return's against it: both from the segment's start to its end;
    # 45-degree segments take every second point of GRID, 5.6- and 1.4-degree ones every point of their 33
    cam = build_cam(program_template(segments))
    stretches = _moving(cam)
    (index, v, truth), groups = _shared_grid(cam, stretches)
    assert truth is True
    theta, _ = cam.program._table.on(index, v, v.size)
    segments_ = cam.program.segments
    own = _grids([(segments_[i].start, segments_[i].end) for i, _ in stretches])
    assert len(groups) == len(own) == 1
    (members, pick), (own_members, own_grid) = groups[0], own[0]
    assert members.tolist() == own_members.tolist() == list(range(len(stretches)))
    assert pick.shape == own_grid.shape == (len(stretches), size)
    assert np.abs(theta.take(pick) - own_grid).max() <= 1e-12 * 2 * math.pi
    assert (np.diff(theta.take(pick), axis=1) > 0).all()


def test_segments_of_several_sizes_share_their_grids_size_by_size():
    # a 90-degree rise (129 points, 65 shared), a 10-degree return (33, every point) and a 4-degree rise (33)
    spec = validate_spec({**BASE, "motion": [
        {"type": "rise", "law": "cycloidal", "lift": 10.0, "angle": 90.0}, {"type": "dwell", "angle": 60.0},
        {"type": "return", "law": "cycloidal", "lift": 1.0, "angle": 10.0}, {"type": "dwell", "angle": 100.0},
        {"type": "rise", "law": "cycloidal", "lift": 0.1, "angle": 4.0}, {"type": "return", "law": "harmonic",
                                                                         "lift": 9.1, "angle": 96.0}]})
    cam = build_cam(spec)
    stretches = _moving(cam)
    (index, v, _), groups = _shared_grid(cam, stretches)
    _, _, sizes = cam.program.search_grid(cam.steady)
    assert sizes.tolist() == [129, 33, 33, 129] and v.size == 129 + 33 + 33 + 129 + 2      # two dwells' one point
    theta, _ = cam.program._table.on(index, v, v.size)
    own = {tuple(m.tolist()): g for m, g in _grids([(s.start, s.end) for s in (cam.program.segments[i]
                                                                              for i, _ in stretches)])}
    assert sorted(own) == sorted(tuple(m.tolist()) for m, _ in groups) == [(0, 3), (1, 2)]
    for members, pick in groups:
        np.testing.assert_allclose(theta.take(pick), own[tuple(members.tolist())], rtol=0, atol=1e-12 * 2 * math.pi)
    shared_analysis, shared = _design(cam, True)
    own_analysis, mine = _design(build_cam(spec), False)
    assert shared_analysis == own_analysis
    assert len(shared.contour.vertices) == len(mine.contour.vertices)
    assert np.abs(np.asarray(shared.contour.vertices) - np.asarray(mine.contour.vertices)).max() <= 1e-9
    assert shared.max_error_mm <= 0.01 and mine.max_error_mm <= 0.01


def test_what_cannot_share_asks_its_own_grids():
    cam = build_cam(program_template(8))
    stretches = _moving(cam)
    seg = cam.program.segments[0]
    assert _shared_grid(cam, [(0, (seg.start, 0.5 * (seg.start + seg.end))), *stretches[1:]]) is None   # a span
    assert _shared_grid(cam, stretches[1:]) is None                                   # not every moving segment
    pieces = validate_spec({**BASE, "motion": [
        {"type": "rise", "law": "modified-trapezoid", "lift": 20.0, "angle": 150.0}, {"type": "dwell", "angle": 60.0},
        {"type": "return", "law": "cycloidal", "lift": 20.0, "angle": 150.0}]})
    several = build_cam(pieces)                         # a law of several smooth pieces: no search grid of segments
    assert several.program.search_grid(several.steady) is None
    assert _shared_grid(several, _moving(several)) is None


@pytest.mark.parametrize("source", ["rdrd", 4, 64, 256, 1024])
def test_the_shared_outline_is_the_outline_on_its_own_grids(source):
    # the grids' points are the same fractions of the same segments (a return's from its law variable, within an
    # ulp of the angle): the same vertices within 1e-9 mm, the same errors, the same analysis
    spec = (validate_spec(tomllib.loads(RDRD.read_text())) if source == "rdrd" else program_template(source))
    shared_analysis, shared = _design(build_cam(spec), True)
    own_analysis, own = _design(build_cam(spec), False)
    assert shared_analysis == own_analysis
    a, b = shared.contour, own.contour
    assert len(a.vertices) == len(b.vertices)
    assert np.abs(np.asarray(a.vertices) - np.asarray(b.vertices)).max() <= 1e-9
    assert np.abs(np.asarray(a.bulges) - np.asarray(b.bulges)).max() <= 1e-12
    assert shared.max_error_mm == pytest.approx(own.max_error_mm, abs=1e-9)
    assert shared.max_error_mm <= 0.01
