"""A barrel cam's follower as a conservative clash body (issue 35 item 4, :func:`camgen.kinds.machine.barrel_parts.
follower`): its plan over the turn where the rules put it (a translating roller's, an arm's with its strip to the
pivot), on the drum's plane; a Geneva drive's crank sweeping into it found within 0.1 degree of the angle worked
here in closed form; with one plate, no clash, nothing unchecked and every part meeting no other but at its joints
at 720 angles, for both followers."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from tests.camgen.kinds.machine.test_barrel_mount import _design, _machine
from tests.conftest import ROOT
from tests.support.machine_meetings import assert_meet_only_at_joints, spans

PHI = np.arange(720) * (2 * math.pi / 720)
#: the bundled machine test's camshaft
SHAFT = np.array([5.0, 15.0])


@pytest.mark.parametrize(("template", "bounds"), [
    # pitch 30, groove 6: floor 27, rim 33; past it the 10 mm carrier; the 5 mm roller on the radial line y = 0
    ("barrel.toml", (27.0, -5.0, 43.0, 5.0)),
    # pitch 40, groove 8: floor 36, rim 44; the arm (80 mm, pivoted 79.4 mm from the axis) puts the roller at
    # y = 79.4 - 80 cos(psi), psi over +-10 degrees (a 20 degree swing): -0.6 to 0.6152...; its strip to the pivot
    # over the carrier reaches 79.4 + 5
    ("barrel-oscillating.toml", (36.0, 79.4 - 80.0 - 5.0, 54.0, 79.4 + 5.0)),
])
def test_the_followers_plan_is_still_where_the_rules_put_it(template, bounds):
    """The follower's plan, still at every angle, on the drum's plane (2, its layer 1), its bounds from the shaft
    those worked here; the roller's strip (from the floor out) as wide as the roller round every offset it takes."""
    import shapely

    from camgen.kinds.machine.clash import outlines

    design = _design(_machine(template, 0.0))
    assert design.unchecked == () and design.clashes == ()
    body = next(b for b in design.bodies if b.name == "cams.drum.follower")
    assert (body.low, body.high) == (2, 2)
    shapes = outlines(body, PHI[::60])
    for shape in shapes:
        assert shape.bounds == pytest.approx(tuple(np.array(bounds) + np.tile(SHAFT, 2)), abs=1e-9)
    if template == "barrel-oscillating.toml":
        top = 79.4 - 80.0 * math.cos(math.radians(10.0)) + 5.0       # the roller's strip, from the floor to the rim
        x0, y0 = SHAFT
        probe = shapely.box(x0 + 36.5, y0 + top + 0.01, x0 + 43.5, y0 + top + 1.0)
        assert not shapes[0].intersects(probe)
        assert shapes[0].contains(shapely.box(x0 + 36.5, y0 + top - 0.5, x0 + 43.5, y0 + top - 0.01))


def _crossed() -> tuple[dict, float]:
    """The bundled test machine's translating barrel (camshaft at (5, 15), layer 1: plane 2) with a Geneva drive on
    layer 1 whose driver shaft stands 98 mm along +X from the camshaft (a 1:1 gear pair of 49 teeth, module 2: it
    turns clockwise), its wheel 80 mm further, its pin on the centre line at the start (phase 0): its crank (the
    pin's circle 56.57 mm, 14 mm wide, plane 2), pointing at -phi, sweeps into the follower's outer end and passes
    the drum's rim 1.4 mm clear. The first angle: turning clockwise, the crank's leading side (7 mm off its line)
    reaches a corner of the follower at polar angle beta and distance d from the driver's axis when the crank points
    at beta + asin(7 / d); the least such phi over the corners within the crank's straight side."""
    raw = tomllib.loads(_machine("barrel.toml", 0.0))
    driver = SHAFT + np.array([98.0, 0.0])
    raw["machine"]["frame"] = "none"
    wheel = driver + np.array([80.0, 0.0])
    raw["shafts"] += [{"name": "driver", "at": list(driver)}, {"name": "wheel", "at": list(wheel)}]
    raw["gears"] = [{"driver": "camshaft", "driven": "driver", "driver_teeth": 49, "driven_teeth": 49,
                     "module": 2.0}]
    raw["genevas"] = [{"name": "index", "driver": "driver", "wheel": "wheel", "phase": 0.0, "layer": 1,
                       "template": str(ROOT / "templates" / "geneva4.toml")}]
    corners = SHAFT + np.array([[27.0, -5.0], [43.0, -5.0], [43.0, 5.0], [27.0, 5.0]]) - driver
    d = np.hypot(corners[:, 0], corners[:, 1])
    crank = 80.0 * math.sin(math.pi / 4)
    within = d < crank
    assert within.sum() == 2
    angles = -np.degrees(np.arctan2(corners[:, 1], corners[:, 0]) + np.arcsin(7.0 / d))
    return raw, float(np.min(np.mod(angles[within], 360.0)))


def test_a_crank_sweeping_into_the_follower_is_found_at_its_angle():
    """The Geneva's crank meets the follower first, at the angle worked here within 0.1 degree; then the pin it
    carries (inside its outline in plan) does; nothing else meets (the drum's rim stays clear)."""
    raw, expected = _crossed()
    from camgen import api

    design = api.design(api.validate(raw))
    met = {frozenset((c.a, c.b)): c.angle_deg for c in design.clashes}
    crank, pin = (frozenset(("cams.drum.follower", f"genevas.index.{w}")) for w in ("crank", "pin"))
    assert set(met) == {crank, pin}, met
    assert abs(met[crank] - expected) <= 0.1, (met, expected)
    assert met[pin] > met[crank]


@pytest.mark.slow
@pytest.mark.parametrize("template", ["barrel.toml", "barrel-oscillating.toml"])
def test_a_framed_barrel_meets_no_part_but_at_its_joints(template):
    """With one plate: no clash, nothing unchecked, and at 720 angles every part (the drum, its follower, the
    shaft) meets no other but at its joints, heights from the assembly (the follower as high as the drum)."""
    from camgen.kinds.machine import clash

    design = _design(_machine(template, 30.0))
    assert design.clashes == () and design.unchecked == ()
    bodies, joints, _ = clash.machine_parts(design, one_plate=True)
    span = spans(design, bodies)
    assert span["cams.drum.follower"] == span["cams.drum"]
    assert assert_meet_only_at_joints(bodies, joints, span, PHI) >= 3
