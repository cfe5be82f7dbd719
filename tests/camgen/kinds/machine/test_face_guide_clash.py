"""A translating follower's flat face and its stem's guide as clash bodies (issue 35 item 4,
:mod:`camgen.kinds.machine.stem_guide`): a face rising into a still lever's arm and a crank sweeping into a still
guide, each found within 0.1 degree of the angle computed here independently (the face's outer corner against the
arm's side, the cycloidal rise inverted; the crank's leading side against the rail's corners); the face's and the
guide's outlines where the rules put them."""
from __future__ import annotations

import json
import math
import tomllib

import numpy as np
import pytest
from scipy.optimize import brentq

from tests.conftest import ROOT


def _program(steps) -> str:
    """A cam's [[motion]] tables: (kind, lift mm, angle degrees) each, cycloidal where it moves."""
    return "".join(f'\n[[cams.template.motion]]\ntype = "{kind}"\n'
                   + (f'law = "cycloidal"\nlift = {h}\n' if kind != "dwell" else "") + f"angle = {a}\n"
                   for kind, h, a in steps)


#: the flat face's shaft: 170 mm from the lever's (a 1:1 gear pair of 68 teeth, module 2.5), 12 mm up
FY = 12.0
FX = math.sqrt(170.0**2 - FY**2)
#: a lever (as tests/camgen/kinds/machine/test_stem_clash.py's: still over phi in [0, 180] degrees) whose arm lies
#: over the left end of a translating flat face, which rises 15 mm (cycloidal over the main shaft's first 120
#: degrees) into it; its return of 90 degrees sets the face's left end (the contact's least position). The lever's
#: outlines are made to 0.001 mm: the arm's side, a chord between its round ends' points, then lies within 0.004 mm
#: of the exact one (0.022 mm at 0.01 mm, which the face's slow, grazing approach turns into 0.1 degree)
FACED = f"""name = "faced"

[machine]
main = "left"
rpm = 30.0

[[shafts]]
name = "left"
at = [0.0, 0.0]

[[shafts]]
name = "right"
at = [{FX!r}, {FY!r}]

[[gears]]
driver = "left"
driven = "right"
driver_teeth = 68
driven_teeth = 68
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

[cams.template.output]
tolerance = 0.001
""" + _program((("rise", 5.0, 60.0), ("dwell", 0, 60.0), ("return", 5.0, 60.0), ("dwell", 0, 180.0))) + """
[[cams]]
name = "lift"
shaft = "right"

[cams.template.cam]
base_radius = 30.0
thickness = 6.0
bore = 8.0

[cams.template.follower]
type = "translating-flat"
face_margin = 3.0
""" + _program((("rise", 15.0, 120.0), ("dwell", 0, 60.0), ("return", 15.0, 90.0), ("dwell", 0, 90.0)))

#: a crank (45 mm, 8 mm wide, drawn pointing up, turning counter-clockwise with the main shaft at (42, 56)) that
#: sweeps down across the guide of a translating roller (radius 5 mm, base 30 mm, still at lift 0 over the main
#: shaft's first 180 degrees) on a shaft 70 mm away (a 1:1 gear pair of 35 teeth, module 2)
SWEPT = """name = "swept"

[machine]
main = "crank"
rpm = 30.0

[[shafts]]
name = "crank"
at = [42.0, 56.0]

[[shafts]]
name = "cam"
at = [0.0, 0.0]

[[gears]]
driver = "crank"
driven = "cam"
driver_teeth = 35
driven_teeth = 35
module = 2.0

[output]
formats = ["json"]

[[cams]]
name = "lift"
shaft = "cam"

[cams.template.cam]
base_radius = 30.0
thickness = 6.0
bore = 8.0

[cams.template.follower]
type = "translating-roller"
roller_radius = 5.0
""" + _program((("dwell", 0, 180.0), ("rise", 10.0, 60.0), ("dwell", 0, 60.0), ("return", 10.0, 60.0))) + """
[[linkages]]
name = "sweep"
shaft = "crank"

[linkages.template.linkage]
type = "linkage"
ground = ["O"]
input = { link = "crank", pivot = "O" }
tracers = ["A"]

[linkages.template.linkage.joints]
O = [0.0, 0.0]
A = [0.0, 45.0]

[linkages.template.linkage.links]
crank = ["O", "A"]

[linkages.template.parts]
width = 8.0
thickness = 3.0
pin_diameter = 3.0
"""


def _design(text: str):
    from camgen import api

    return api.design(api.validate(tomllib.loads(text)))


@pytest.fixture(scope="module")
def faced():
    return _design(FACED)


@pytest.fixture(scope="module")
def swept():
    return _design(SWEPT)


def _face_left_end() -> float:
    """The face's left end (mm, x): the axis, less the most negative s' (the 90-degree cycloidal return's peak
    speed, 2 h / beta per radian), less the margin."""
    return FX - 2 * 15.0 / math.radians(90.0) - 3.0


def _face_contact_deg() -> float:
    """The main shaft angle (degrees) at which the face's top (3 mm over its contact line, at 12 + 30 + s) meets
    the still arm's lower side (half its 8 mm width under the line from its roller's rest point (0, 48) to its
    pivot: |P| = 160, |P - (0, 48)| = 150) at the face's left end."""
    rp, c, arm = 48.0, 160.0, 150.0
    py = (c * c - arm * arm + rp * rp) / (2 * rp)
    pivot = np.array([math.sqrt(c * c - py * py), py])
    x = _face_left_end()
    slope = (pivot[1] - rp) / pivot[0]
    lower = rp + slope * x - 4.0 * math.hypot(1.0, slope)
    s = lower - (FY + 30.0 + 3.0)
    assert 0.0 < s < 15.0

    def rise(deg: float) -> float:
        t = deg / 120.0
        return 15.0 * (t - math.sin(2 * math.pi * t) / (2 * math.pi)) - s

    return brentq(rise, 0.0, 120.0, xtol=1e-12)


def test_a_face_rising_into_a_lever_is_found_at_its_angle(faced):
    """The face meets the arm first at the angle computed here (then the arm's pivot pin, standing over the face's
    travel); the face rides its cam and carries its stem without a clash; nothing goes unchecked."""
    assert faced.unchecked == ()
    expected = _face_contact_deg()
    met = {frozenset((c.a, c.b)): c.angle_deg for c in faced.clashes}
    assert abs(met[frozenset(("cams.lever.arm", "cams.lift.face"))] - expected) <= 0.1, (met, expected)
    assert all("cams.lift.face" in pair for pair in met), met
    assert min(met.values()) == met[frozenset(("cams.lever.arm", "cams.lift.face"))]


def test_the_face_spans_its_contact_and_moves_with_the_lift(faced):
    """The face: from its left end to the axis + the rise's peak s' (2 h / beta) + the margin, 3 mm deep over its
    contact line y = 12 + 30 + s, on the cam's plane and the stem's."""
    from camgen.kinds.machine.clash import outlines

    face = next(b for b in faced.bodies if b.name == "cams.lift.face")
    right = FX + 2 * 15.0 / math.radians(120.0) + 3.0
    phi = np.radians([0.0, 60.0, 120.0])
    for shape, s in zip(outlines(face, phi), (0.0, 7.5, 15.0), strict=True):
        assert shape.bounds == pytest.approx((_face_left_end(), FY + 30.0 + s, right, FY + 33.0 + s), abs=1e-6)
    assert (face.low, face.high) == (0, 1)


def _rail_corners() -> np.ndarray:
    """The right rail's corners (mm): 0.2 mm clear of the 8 mm stem on x = 0, 3 mm wide, from 1 mm over the roller's
    top at the top of the stroke (30 + 5 + 10 + 5 + 1) to the stem's top at lift 0 (the roller's centre at 35 plus
    its length, twice the stroke plus its width: 28)."""
    x0, x1, y0, y1 = 4.2, 7.2, 51.0, 63.0
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])


def test_a_crank_sweeping_into_the_guide_is_found_at_its_angle(swept):
    """The crank, pointing up at phi = 0 and turning counter-clockwise about (42, 56), first meets the right rail
    where its leading side (4 mm from its centre line) reaches the rail's nearest corner: at the least of
    atan2(corner - pivot) - asin(4 / |corner - pivot|) - 90 degrees."""
    pivot = np.array([42.0, 56.0])
    v = _rail_corners() - pivot
    d = np.hypot(v[:, 0], v[:, 1])
    assert (d < 45.0 - 4.0).all()                          # on the crank's straight side
    expected = float(np.min(np.mod(np.degrees(np.arctan2(v[:, 1], v[:, 0]) - np.arcsin(4.0 / d)) - 90.0, 360.0)))
    met = {frozenset((c.a, c.b)): c.angle_deg for c in swept.clashes}
    first = met[frozenset(("cams.lift.guide.right", "linkages.sweep.crank"))]
    assert abs(first - expected) <= 0.1, (first, expected)
    assert first == min(met.values())                      # the rail, standing out past the stem, is met first


def test_the_guide_stands_still_beside_the_stem(swept):
    """Both rails where the rules put them at every angle, on the stem's plane, never meeting the stem or the roller
    over the turn (the clash check names neither pair)."""
    from camgen.kinds.machine.clash import outlines

    rails = {b.name: b for b in swept.bodies if ".guide." in b.name}
    assert sorted(rails) == ["cams.lift.guide.left", "cams.lift.guide.right"]
    x0, y0 = _rail_corners()[0]
    x1, y1 = _rail_corners()[2]
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    for name, (a, b) in (("cams.lift.guide.right", (x0, x1)), ("cams.lift.guide.left", (-x1, -x0))):
        assert rails[name].low == rails[name].high == 1
        for shape in outlines(rails[name], phi):
            assert shape.bounds == pytest.approx((a, y0, b, y1), abs=1e-9)
    pairs = {frozenset((c.a, c.b)) for c in swept.clashes}
    for rail in rails:
        assert not pairs & {frozenset((rail, "cams.lift.stem")), frozenset((rail, "cams.lift.roller"))}


MACHINES = sorted(p for p in (ROOT / "templates").glob("*.toml") if "shafts" in tomllib.loads(p.read_text()))


@pytest.mark.parametrize("path", MACHINES, ids=lambda p: p.name)
def test_the_bundled_machines_meet_no_clash_with_every_part_checked(path, bundled_builds):
    """Each bundled machine's report (the build tests/project/test_golden.py compares, shared with it): no clash,
    nothing left unchecked, and a face and a guide for each translating follower it has (flat faces too)."""
    from tests.support.golden import runs

    program, args = runs(path)[0]
    report = json.loads((bundled_builds.folder(path, program, args) / f"{path.stem}.json").read_text())
    assert report["clashes"] == [] and report["clash_check"]["not_checked"] == []
    raw = tomllib.loads(path.read_text())
    parts = set(report["poses"][0]["parts"])
    for cam in raw.get("cams", []):
        kind = cam["template"].get("follower", {}).get("type", "")
        if kind.startswith("translating"):
            assert {f"cams.{cam['name']}.guide.left", f"cams.{cam['name']}.guide.right"} <= parts
        if kind == "translating-flat":
            assert f"cams.{cam['name']}.face" in parts
