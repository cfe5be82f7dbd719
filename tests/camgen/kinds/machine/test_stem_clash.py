"""A translating follower's stem as a clash body (issue 35 item 4, :mod:`camgen.kinds.machine.stem_parts`): a
lever's arm and a stem built to meet, the stem rising into the still arm, found at the angle computed here
independently (the stem's top corners against the arm's straight side, the cycloidal rise inverted) to 0.1 degree;
the slider-driven lifter and the bundled machines clash-free with every follower checked."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
from scipy.optimize import brentq


def _program(lift: float, rise: float, dwell: float, back: float, rest: float) -> str:
    """A cam's [[motion]] tables: a cycloidal rise of ``lift``, a dwell, a cycloidal return, a dwell (degrees)."""
    steps = (("rise", lift, rise), ("dwell", 0.0, dwell), ("return", lift, back), ("dwell", 0.0, rest))
    return "".join(f'\n[[cams.template.motion]]\ntype = "{kind}"\n'
                   + (f'law = "cycloidal"\nlift = {h}\n' if kind != "dwell" else "") + f"angle = {a}\n"
                   for kind, h, a in steps)


#: a lever (an oscillating roller on shaft "left") whose arm, still over phi in [0, 180] degrees (its program's
#: dwell: phase 180), lies across the line of the stem of a translating roller on shaft "right" (turned by a 1:1
#: gear pair, 125 mm away), which rises 30 mm (cycloidal, over the main shaft's first 120 degrees) into it
TEMPLATE = """name = "crossing"

[machine]
main = "left"
rpm = 30.0

[[shafts]]
name = "left"
at = [0.0, 0.0]

[[shafts]]
name = "right"
at = [100.0, -75.0]

[[gears]]
driver = "left"
driven = "right"
driver_teeth = 50
driven_teeth = 50
module = 2.5

[output]
formats = ["json"]

[[cams]]
name = "lever"
shaft = "left"
phase = 180.0

[cams.template.cam]
base_radius = 40.0
thickness = 6.0
bore = 8.0

[cams.template.follower]
type = "oscillating-roller"
roller_radius = 8.0
pivot_distance = 160.0
arm_length = 150.0
""" + _program(5.0, 60.0, 60.0, 60.0, 180.0) + """
[[cams]]
name = "lift"
shaft = "right"

[cams.template.cam]
base_radius = 30.0
thickness = 6.0
bore = 8.0

[cams.template.follower]
type = "translating-roller"
roller_radius = 5.0
""" + _program(30.0, 120.0, 60.0, 120.0, 60.0)
RIGHT = np.array([100.0, -75.0])
STROKE, WIDTH = 30.0, 8.0                       # the stem: 8 mm wide (no linkage to take a width from)
PRIME = 35.0                                    # the stem's roller centre at rest: base 30 + roller 5 over its shaft
ARM_HALF = 4.0                                  # the arm: a bar as wide as its roller (8 mm)


def _design(text: str):
    from camgen import api

    return api.design(api.validate(tomllib.loads(text)))


def _first_contact_deg() -> float:
    """The main shaft angle (degrees) at which the stem's top first comes within the arm's half width of the arm's
    centre line (the arm at rest: pivot C = 160 mm from its cam at +X of the roller's rest point (0, 48))."""
    rp, c, arm = 48.0, 160.0, 150.0
    py = (c * c - arm * arm + rp * rp) / (2 * rp)               # the pivot: |P| = c, |P - (0, rp)| = arm
    pivot = np.array([math.sqrt(c * c - py * py), py])
    u = (np.array([0.0, rp]) - pivot) / arm
    n = np.array([-u[1], u[0]])
    top = RIGHT[1] + PRIME + 2 * STROKE + WIDTH                 # the stem: twice its stroke plus its width long
    lifts = []
    for x in (RIGHT[0] - WIDTH / 2, RIGHT[0] + WIDTH / 2):
        gap = abs(float(n @ (np.array([x, top]) - pivot)))
        lifts.append((gap - ARM_HALF) / abs(n[1]))              # each mm of lift closes the gap by |n_y|
    s = min(lifts)
    assert 0.0 < s < STROKE

    def rise(deg: float) -> float:
        t = deg / 120.0
        return STROKE * (t - math.sin(2 * math.pi * t) / (2 * math.pi)) - s

    return brentq(rise, 0.0, 120.0, xtol=1e-12)


def test_a_stem_rising_into_a_lever_is_found_at_its_angle():
    design = _design(TEMPLATE)
    names = {b.name for b in design.bodies}
    assert {"cams.lift.stem", "cams.lift.roller", "cams.lever.arm"} <= names
    assert design.unchecked == ()
    expected = _first_contact_deg()
    assert 20.0 < expected < 100.0
    met = [c for c in design.clashes if {c.a, c.b} == {"cams.lever.arm", "cams.lift.stem"}]
    assert len(met) == 1
    assert abs(met[0].angle_deg - expected) <= 0.1
    assert len(design.clashes) == 1                              # the stem's roller and the cams stay clear


def test_the_stem_moves_with_the_lift():
    """The stem's outline: 8 mm wide on x = 100 mm, from the roller's centre up 68 mm with a round foot of 4 mm about
    it (the roller's axle; its lowest chord within the cam's tolerance of the arc), raised by the lift."""
    from camgen.kinds.machine.clash import outlines

    design = _design(TEMPLATE)
    stem = next(b for b in design.bodies if b.name == "cams.lift.stem")
    phi = np.radians([0.0, 60.0, 150.0])
    lift = np.array([0.0, 15.0, 30.0])                          # the cycloid's start, middle and top
    for shape, s in zip(outlines(stem, phi), lift, strict=True):
        x0, y0, x1, y1 = shape.bounds
        assert (x0, x1) == pytest.approx((96.0, 104.0), abs=1e-9)
        assert y1 == pytest.approx(RIGHT[1] + PRIME + s + 68.0, abs=1e-9)
        foot = RIGHT[1] + PRIME + s - WIDTH / 2
        assert foot - 1e-9 <= y0 <= foot + float(design.cam("lift").design.tolerance)
    assert stem.low == stem.high == 1

