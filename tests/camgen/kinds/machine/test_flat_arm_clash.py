"""An oscillating flat-faced follower's arm as a clash body (issue 35 item 4, :mod:`camgen.kinds.machine.flat_arm`):
a crank sweeping down onto the still arm found within 0.1 degree of the angle worked here in closed form (its
round tip reaching the arm's top edge); the arm's face through the follower's contact at every angle, touching its
cam there and meeting no part but at its joints at 720 angles."""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest
import shapely

from tests.camgen.kinds.machine.test_face_guide_clash import _cam, _machine
from tests.support.machine_meetings import assert_meet_only_at_joints, spans

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-flat-arm-clash")

#: the face's cam: base radius 95 mm, its pivot 160 mm from the cam's centre (so at (sqrt(160^2 - 95^2), 95)); the
#: arm swings 15 degrees (cycloidal over 120 degrees of the program), holds, returns over 120 and rests over the
#: program's last 60 degrees: main shaft angles 100 to 160 with the program starting at 160 degrees
BASE, PIVOT, PHASE = 95.0, 160.0, 160.0
#: the crank's shaft (the main one), 155 mm from the cam's (a 1:1 gear pair of 62 teeth, module 2.5): 135.93 mm up
CY = 135.93
CX = math.sqrt(155.0**2 - CY**2)
SWUNG = _machine("swung", "crank", {"crank": (CX, CY), "cam": (0.0, 0.0)}, 62, 2.5, [
    _cam("lift", "cam", {"type": "oscillating-flat", "base": BASE, "pivot_distance": PIVOT, "face_margin": 3.0},
         (("rise", 15.0, 120.0), ("dwell", 0, 60.0), ("return", 15.0, 120.0), ("dwell", 0, 60.0)), PHASE)], [
    {"name": "sweep", "shaft": "crank",
     "template": {"linkage": {"type": "linkage", "ground": ["O"], "input": {"link": "crank", "pivot": "O"},
                              "tracers": ["A"], "joints": {"O": [0.0, 0.0], "A": [0.0, 45.0]},
                              "links": {"crank": ["O", "A"]}},
                  "parts": {"width": 8.0, "thickness": 3.0, "pin_diameter": 3.0}}}])
PHI = np.arange(720) * (2 * math.pi / 720)


@pytest.fixture(scope="module")
def swung():
    from camgen import api

    return api.design(api.validate(copy.deepcopy(SWUNG)))


def test_a_crank_sweeping_onto_the_resting_arm_is_found_at_its_angle(swung):
    """At rest the face lies on y = 95 (it touches the base circle at (0, 95)) and the arm stands 8 mm over it (away
    from the cam), so its top edge is y = 103. The crank (45 mm, 8 mm wide, pointing up at phi = 0 and turning
    counter-clockwise about the main shaft) first reaches it with its round tip's lowest point: CY + 45 cos(phi) - 4
    = 103, while the arm rests (phi in 100..160) and over the edge's length (the tip's x between the pivot and the
    arm's far end)."""
    from camgen.kinds.machine.flat_arm import DEPTH_MM

    assert swung.unchecked == ()
    top = BASE + DEPTH_MM
    expected = math.degrees(math.acos((top + 4.0 - CY) / 45.0))
    assert 100.0 < expected < 160.0
    tip_x = CX - 45.0 * math.sin(math.radians(expected))
    assert 0.0 < tip_x < math.sqrt(PIVOT**2 - BASE**2) - 10.0
    met = {frozenset((c.a, c.b)): c.angle_deg for c in swung.clashes}
    first = met[frozenset(("linkages.sweep.crank", "cams.lift.arm"))]
    assert abs(first - expected) <= 0.1, (first, expected)
    assert first == min(met.values()) and len(met) == 1, met


def test_the_face_runs_through_the_contact_and_touches_its_cam(swung):
    """The cam's contact with the face (the follower's envelope, the joint's centre) lies on the arm's face edge
    (y = 0 in the arm's frame, to 1e-9 mm) between the pivot and the arm's far end at every one of 720 angles; the
    cam's outline comes within its chords (0.01 mm) of the arm and never overlaps it but in the joint's disc; the
    arm's pivot pin stands at the follower's pivot."""
    from camgen.kinds.machine import clash

    bodies, joints, _ = clash.machine_parts(swung)
    named = {b.name: b for b in bodies}
    arm, cam = named["cams.lift.arm"], named["cams.lift"]
    joint = next(j for j in joints if {j.a, j.b} == {"cams.lift", "cams.lift.arm"})
    m, t = arm.place(PHI)
    local = np.einsum("nji,nj->ni", m, joint.centre(PHI) - t)
    far = float(arm.outline[:, 0].max())
    assert np.abs(local[:, 1]).max() < 1e-9
    assert local[:, 0].min() > 0 and local[:, 0].max() < far
    gap = shapely.distance(clash.outlines(cam, PHI), clash.outlines(arm, PHI))
    assert gap.max() <= 0.012
    assert not clash._overlap(cam, arm, joint, PHI).any()
    pivot = (math.sqrt(PIVOT**2 - BASE**2), BASE)
    pin = next(j for j in joints if j.a == "cams.lift.arm" and j.b.startswith("pins."))
    assert pin.centre(PHI[:3]) == pytest.approx(np.tile(pivot, (3, 1)), abs=1e-9)
    assert t[0] == pytest.approx(pivot, abs=1e-9)


def test_the_swung_face_meets_no_part_but_at_its_joints_over_the_turn():
    """With the crank a layer up (over the arm's planes), every part of the machine at 720 angles meets no other
    but at its joints (heights from the assembly); no clash, nothing unchecked."""
    from camgen import api
    from camgen.kinds.machine import clash

    raw = copy.deepcopy(SWUNG)
    raw["linkages"][0]["layer"] = 1                                   # plane 3: it passes over the arm
    design = api.design(api.validate(raw))
    assert design.clashes == () and design.unchecked == ()
    bodies, joints, _ = clash.machine_parts(design)
    assert assert_meet_only_at_joints(bodies, joints, spans(design, bodies), PHI) >= 4
