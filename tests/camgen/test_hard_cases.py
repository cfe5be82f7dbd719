"""Hard designs: each ends in a correct, finite, within-tolerance result or a clear refusal, never garbage."""
from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from camgen.api import design_cam
from camgen.core.errors import DesignError, SpecError
from tests.conftest import template


def assert_sound(design):
    """Finite, valid, counter-clockwise and within its measured tolerance."""
    c = design.outline.contour
    tol = design.spec.output.tolerance
    assert np.isfinite(c.vertices).all() and np.isfinite(c.bulges).all()
    assert shapely.Polygon(c.flatten(tol)).is_valid and c.area > 0
    assert 0 <= design.outline.max_error_mm <= tol
    a = design.analysis
    for value in (a.pressure_angle_max_deg, a.pitch_rho_min_mm, a.profile_rho_min_mm):
        assert math.isfinite(value)
    assert 0 <= a.pressure_angle_max_deg <= 90


@pytest.mark.parametrize("angles", [(1.0, 179.0, 120.0, 60.0), (358.0, 1.0, 0.5, 0.5)],
                         ids=["rise over 1 degree", "rise over 358, return over 0.5"])
def test_extreme_segment_angles_are_refused_or_enveloped(angles):
    ov = {f"motion.{i}.angle": a for i, a in enumerate(angles)}
    with pytest.raises(DesignError, match=r"undercut at .* the largest roller that fits is"):
        design_cam(template(ov))
    design = design_cam(template({**ov, "cam.allow_undercut": True}))
    assert design.outline.envelope
    assert_sound(design)


def test_lift_ten_times_the_base_radius():
    design = design_cam(template({"motion.0.lift": 400.0, "motion.2.lift": 400.0}))
    assert_sound(design)
    assert design.cam.program.max_lift == 400.0
    assert any("pressure angle peaks" in w for w in design.warnings)


@pytest.mark.parametrize("offset, rotation", [(50 - 1e-9, "ccw"), (-(50 - 1e-9), "cw"), (-(50 - 1e-9), "ccw")])
def test_offset_within_1e_9_of_the_prime_radius(offset, rotation):
    design = design_cam(template({"follower.offset": offset, "cam.rotation": rotation}))
    assert_sound(design)
    assert design.analysis.pressure_angle_max_deg > 89.9   # the follower axis nearly grazes the prime circle


def test_offset_equal_to_the_prime_radius_is_refused():
    with pytest.raises(SpecError, match=r"follower.offset: \|offset\| must be < the prime radius 50 mm"):
        template({"follower.offset": 50.0})


@pytest.mark.parametrize("m", [3, 5, 7, 9])
def test_high_degree_polynomial_laws_in_a_cam(m):
    """Degrees 7 to 19: 2m + 2 conditions (m derivatives zero at each end)."""
    conds = [[0, k, 0] for k in range(m + 1)] + [[1, 0, 1]] + [[1, k, 0] for k in range(1, m + 1)]
    design = design_cam(template({"motion.0.law": "polynomial", "motion.0.conditions": conds}))
    assert_sound(design)
    assert design.cam.program.segments[0].law.degree == 2 * m + 1
    assert not [j for j in design.jumps if j.at_deg in (0.0, 120.0)]  # s', s'', s''' all zero at both ends


def test_tiny_dwell_tiny_roller_tight_tolerance_and_huge_cam():
    assert_sound(design_cam(template({"motion.1.angle": 1e-7, "motion.0.angle": 180 - 1e-7})))
    assert_sound(design_cam(template({"follower.roller_radius": 1e-6})))
    tight = design_cam(template({"output.tolerance": 1e-6}))
    assert_sound(tight)
    huge = design_cam(template({"cam.base_radius": 1e4, "motion.0.lift": 1e-3, "motion.2.lift": 1e-3}))
    assert_sound(huge)
