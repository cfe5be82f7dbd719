"""The bench's many-segment programs (issue 38 item 2): the reference cam's motion cut into 4 to 1024 segments whose
follower acceleration stays the reference's, so that the per-segment rows time the number of segments alone; and
what a design of many segments does in one pass over them (the outline put together, the jumps' angles rounded and
ordered) against the same made segment by segment."""
from __future__ import annotations

import math
import random

import numpy as np
import pytest

from camgen.api import design_cam
from camgen.bench import BASE, program_template
from camgen.flat import build_cam
from camgen.outline import _counter_clockwise, exact_outline, stretch
from camgen.spec import validate_spec


@pytest.mark.parametrize("segments", [4, 64, 256, 1024])
def test_a_bench_program_keeps_the_cycloidal_peak_acceleration(segments):
    """Cycloidal rise h over beta peaks at s'' = 2 pi h / beta^2: with h = 20 (4 / n)^2 mm and beta = 2 pi / n that
    is 160 / pi mm/rad^2 at every n; sampled at its peak (a quarter of each rise) and nowhere above."""
    spec = program_template(segments)
    assert len(spec.motion) == segments and math.isclose(sum(s.angle for s in spec.motion), 360.0)
    program = build_cam(spec).program
    beta = 2 * math.pi / segments
    starts = np.arange(0, segments, 4) * beta
    peaks = program.evaluate(starts + beta / 4)[2]
    np.testing.assert_allclose(peaks, 160 / math.pi, rtol=1e-12)
    theta = np.linspace(0.0, 2 * math.pi, 40 * segments, endpoint=False)
    assert np.abs(program.evaluate(theta)[2]).max() <= 160 / math.pi * (1 + 1e-12)


def test_a_bench_program_is_a_multiple_of_four_segments():
    with pytest.raises(ValueError, match="a multiple of 4"):
        program_template(6)


def _random_program(n: int, seed: int):
    """n segments (rise, dwell, return, dwell, ...) of random angles (0.5 to 3 parts, 360 degrees in all) and laws,
    each rise's lift a random part of the reference cam's acceleration, on a 5 mm roller: some of its stretches
    meet the tolerance at the first spacing, some only when densified (a second round)."""
    rng = random.Random(seed)
    laws = ["cycloidal", "harmonic", "polynomial-345", "modified-sine", "modified-trapezoid", "polynomial-4567"]
    angles = [rng.uniform(0.5, 3.0) for _ in range(n)]
    total = sum(angles)
    angles = [round(360.0 * a / total, 6) for a in angles]
    angles[-1] = round(360.0 - sum(angles[:-1]), 9)
    motion = []
    for q in range(n // 4):
        a = angles[4 * q:4 * q + 4]
        lift = rng.uniform(0.2, 0.9) * 20 * (a[0] / 120) ** 2
        motion += [{"type": "rise", "law": rng.choice(laws), "lift": lift, "angle": a[0]},
                   {"type": "dwell", "angle": a[1]},
                   {"type": "return", "law": rng.choice(laws), "lift": lift, "angle": a[2]},
                   {"type": "dwell", "angle": a[3]}]
    return validate_spec({**BASE, "follower": {**BASE["follower"], "roller_radius": 5.0}, "motion": motion})


def _one_by_one(cam, tolerance):
    """The outline made segment by segment (:func:`camgen.outline.stretch`, each alone), as a contour, and the
    largest of the segments' errors."""
    parts = [stretch(cam, i, tolerance, cam.contact_radius, "polylines") for i in range(len(cam.program.segments))]
    contour = _counter_clockwise(cam, np.concatenate([v for v, _, _ in parts]),
                                 np.concatenate([b for _, b, _ in parts]))
    return contour, max(e for _, _, e in parts)


@pytest.mark.parametrize("spec", [program_template(256), _random_program(160, 0), _random_program(160, 2)],
                         ids=["bench-256", "random-0", "random-2"])
def test_a_many_segment_outline_is_its_segments_outlines_one_after_another(monkeypatch, spec):
    """All stretches' chords and dwells' arcs made at once and put in order in one pass give the outline that each
    segment's own outline, made alone and laid one after another, gives: the same vertices within 1e-12 mm, the
    same bulges and the largest error; on the random programs the chords took a second round for some stretches."""
    import camgen.outline as outline

    rounds = []
    made = outline._in_order

    def counted(done, m):
        rounds.append(len(done))
        return made(done, m)

    monkeypatch.setattr(outline, "_in_order", counted)
    design = design_cam(spec)
    cam, tolerance = design.cam, spec.output.tolerance
    for got in (design.outline, exact_outline(cam, tolerance)):
        contour, error = _one_by_one(cam, tolerance)
        assert got.contour.vertices.shape == contour.vertices.shape
        assert np.abs(got.contour.vertices - contour.vertices).max() <= 1e-12
        assert np.array_equal(got.contour.bulges, contour.bulges)
        assert got.max_error_mm == pytest.approx(error, abs=1e-12)
    assert spec.motion[0].law == "cycloidal" or max(rounds) >= 2


def test_a_many_segment_programs_jumps_are_its_boundaries_rounded_in_order():
    """Every boundary's jerk jump of the 1 024-segment bench program, at round(degrees(theta), 9) % 360 of its
    boundary to the bit (Python's own rounding), in the order of angle then order."""
    program = build_cam(program_template(1024)).program
    jumps = program.jumps()
    ends = [seg.start + seg.beta for seg in program.segments]
    assert [j.at_deg for j in jumps] == sorted(round(math.degrees(t), 9) % 360.0 for t in ends)
    assert [(j.at_deg, j.order) for j in jumps] == sorted((j.at_deg, j.order) for j in jumps)
    assert {j.order for j in jumps} == {3} and all(type(j.at_deg) is float for j in jumps)


def test_angles_in_degrees_are_rounded_as_pythons_round_rounds_them():
    """The jumps' vectorised rounding to 1e-9 degrees is round(math.degrees(t), 9) % 360.0 to the bit: at random
    angles, at angles whose degrees lie a hair either side of a half of 1e-9 (where the scaled product's own
    rounding could choose the other integer), at whole and quarter degrees, signed zeros, tiny, huge and non-finite
    angles."""
    from camgen.program import _degrees

    rng = np.random.default_rng(38)
    nine = np.round(rng.uniform(0.0, 360.0, 20000), 9)
    halves = np.radians(np.concatenate([nine + 5e-10, nine - 5e-10, nine + 5.000000001e-10]))
    theta = np.concatenate([rng.uniform(-0.1, 7.0, 20000), halves, np.radians(np.arange(0.0, 361.0, 0.25)),
                            rng.uniform(-1e8, 1e8, 200), rng.uniform(-1e-8, 1e-8, 200),
                            [0.0, -0.0, 1e-300, -1e-300, 2 * math.pi, math.nextafter(2 * math.pi, 0.0), 1e300,
                             math.inf, -math.inf, math.nan]])
    got = _degrees(theta)
    expected = np.array([round(math.degrees(t), 9) % 360.0 for t in theta.tolist()])
    both_nan = np.isnan(got) & np.isnan(expected)
    assert np.array_equal(got.view(np.int64)[~both_nan], expected.view(np.int64)[~both_nan])
    assert np.array_equal(np.isnan(got), np.isnan(expected))
