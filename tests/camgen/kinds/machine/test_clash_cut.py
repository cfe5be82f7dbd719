"""The clash check's joints, cut out of a body in its own frame (camgen/kinds/machine/clash.py ``_cut``), against
the overlap worked as it is defined: at every sampled angle of every bundled machine, each pair meeting at a joint
overlaps by the area of (A and B) less the joint's disc, the disc drawn where the joint's centre is at that angle.
The two differ only in where the disc's polygon of 128 chords stands, so their areas agree to twice the area
between a circle and such a polygon, and the check's answers (an area over AREA_TOL_MM2) agree wherever the area is
not within that of the tolerance."""
from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from camgen.api import design_cam, load_spec
from camgen.kinds.machine import clash, frame
from tests.camgen.kinds.machine.test_machine import BUNDLED
from tests.conftest import ROOT



def _polygon_gap(radius: float) -> float:
    """The area (mm^2) between a circle of ``radius`` and its inscribed polygon of 128 chords (quad_segs 32)."""
    return math.pi * radius**2 - 64 * radius**2 * math.sin(2 * math.pi / 128)


@pytest.mark.parametrize("name", BUNDLED)
def test_each_joint_s_overlap_is_the_pairs_less_the_disc_where_it_stands(name):
    made = design_cam(load_spec(ROOT / "templates" / f"{name}.toml"))
    spec = made.spec
    bodies, joints, _ = clash.machine_parts(made, one_plate=spec.machine.frame == "one")
    if spec.machine.frame == "two":
        bodies, joints = frame.with_top_plate(bodies, joints)
    by_name = {b.name: b for b in bodies}
    phi = np.arange(spec.machine.clash_samples) * (2 * math.pi / spec.machine.clash_samples)
    cut = inside = checked = 0
    for joint in joints:
        a, b = by_name[joint.a], by_name[joint.b]
        if a.high < b.low or b.high < a.low:
            continue
        checked += 1
        pa, pb = clash.outlines(a, phi), clash.outlines(b, phi)
        disc = shapely.buffer(shapely.points(joint.centre(phi)), joint.radius, quad_segs=32)
        both = shapely.intersection(pa, pb)
        defined = shapely.area(shapely.difference(both, disc))
        inside += int(np.any(shapely.area(both) > clash.AREA_TOL_MM2))
        pieces = clash._cut(a, b, joint, phi, None)
        if pieces is None:
            continue
        cut += 1
        worked = shapely.area(shapely.intersection(*pieces))
        gap = 2 * _polygon_gap(joint.radius)
        assert np.max(np.abs(worked - defined)) <= gap + 1e-9, (joint.a, joint.b)
        answer = clash._overlap(a, b, joint, phi, (pa, pb))
        clear = np.abs(defined - clash.AREA_TOL_MM2) > gap
        assert np.array_equal(answer[clear], (defined > clash.AREA_TOL_MM2)[clear]), (joint.a, joint.b)
    # the cut is taken at every joint (a pin or a roller's centre stands still in a body's frame) and some pairs do
    # overlap inside their joint's disc (the comparison is not of empty shapes only)
    assert cut == checked >= 1 and inside >= 1, (cut, checked, inside)
