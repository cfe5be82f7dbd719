"""The bench's many-segment programs (issue 38 item 2): the reference cam's motion cut into 4 to 1024 segments whose
follower acceleration stays the reference's, so that the per-segment rows time the number of segments alone."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.bench import program_template
from camgen.flat import build_cam


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
