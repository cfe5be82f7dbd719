"""A translating follower's flat face and its stem's guide as clash bodies (issue 35 item 4,
:mod:`camgen.kinds.machine.stem_guide`): a face rising into a still lever's arm and a crank sweeping into a still
guide, each found within 0.1 degree of the angle computed here independently (the face's outer corner against the
arm's side, the cycloidal rise inverted; the crank's leading side against the rail's corners); the face's and the
guide's outlines where the rules put them."""
from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest
from scipy.optimize import brentq

from tests.conftest import ROOT

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-face-guide-clash")


def _motion(steps) -> list[dict]:
    """A cam's [[motion]] tables: (kind, lift mm, angle degrees) each, cycloidal where it moves."""
    return [{"type": kind, "angle": a, **({"law": "cycloidal", "lift": h} if kind != "dwell" else {})}
            for kind, h, a in steps]


def _cam(name: str, shaft: str, follower: dict, steps, phase: float = 0.0, **output) -> dict:
    """A cam mount on ``shaft``: a 6 mm disc on an 8 mm bore, its base radius in ``follower`` (``base``)."""
    base = follower.pop("base")
    return {"name": name, "shaft": shaft, "phase": phase,
            "template": {"cam": {"base_radius": base, "thickness": 6.0, "bore": 8.0}, "follower": follower,
                         "motion": _motion(steps), **({"output": output} if output else {})}}


def _machine(name: str, main: str, shafts: dict[str, tuple[float, float]], teeth: int, module: float,
             cams: list[dict], linkages: list[dict] = ()) -> dict:
    """A machine of two shafts (``main`` first) joined by a 1:1 gear pair, reporting as JSON."""
    driver, driven = shafts
    return {"name": name, "machine": {"main": main, "rpm": 30.0},
            "shafts": [{"name": k, "at": list(at)} for k, at in shafts.items()],
            "gears": [{"driver": driver, "driven": driven, "driver_teeth": teeth, "driven_teeth": teeth,
                       "module": module}],
            "output": {"formats": ["json"]}, "cams": cams, "linkages": list(linkages)}


#: the flat face's shaft: 170 mm from the lever's (a 1:1 gear pair of 68 teeth, module 2.5), 12 mm up
FY = 12.0
FX = math.sqrt(170.0**2 - FY**2)
#: a lever (an oscillating roller, still over phi in [0, 180] degrees: its program's last dwell, phase 180) whose
#: arm lies over the left end of a translating flat face, which rises 15 mm (cycloidal over the main shaft's first
#: 120 degrees) into it; its return of 90 degrees sets the face's left end (the contact's least position). The
#: lever's outlines are made to 0.001 mm: the arm's side, a chord between its round ends' points, then lies within
#: 0.004 mm of the exact one (0.022 mm at 0.01 mm, which the face's slow, grazing approach turns into 0.1 degree)
FACED = _machine("faced", "left", {"left": (0.0, 0.0), "right": (FX, FY)}, 68, 2.5, [
    _cam("lever", "left", {"type": "oscillating-roller", "base": 40.0, "roller_radius": 8.0,
                           "pivot_distance": 160.0, "arm_length": 150.0},
         (("rise", 5.0, 60.0), ("dwell", 0, 60.0), ("return", 5.0, 60.0), ("dwell", 0, 180.0)), 180.0,
         tolerance=0.001),
    _cam("lift", "right", {"type": "translating-flat", "base": 30.0, "face_margin": 3.0},
         (("rise", 15.0, 120.0), ("dwell", 0, 60.0), ("return", 15.0, 90.0), ("dwell", 0, 90.0)))])
#: a crank (45 mm, 8 mm wide, drawn pointing up, turning counter-clockwise with the main shaft at (42, 56)) that
#: sweeps down across the guide of a translating roller (radius 5 mm, base 30 mm, still at lift 0 over the main
#: shaft's first 180 degrees) on a shaft 70 mm away (a 1:1 gear pair of 35 teeth, module 2)
SWEPT = _machine("swept", "crank", {"crank": (42.0, 56.0), "cam": (0.0, 0.0)}, 35, 2.0, [
    _cam("lift", "cam", {"type": "translating-roller", "base": 30.0, "roller_radius": 5.0},
         (("dwell", 0, 180.0), ("rise", 10.0, 60.0), ("dwell", 0, 60.0), ("return", 10.0, 60.0)))], [
    {"name": "sweep", "shaft": "crank",
     "template": {"linkage": {"type": "linkage", "ground": ["O"], "input": {"link": "crank", "pivot": "O"},
                              "tracers": ["A"], "joints": {"O": [0.0, 0.0], "A": [0.0, 45.0]},
                              "links": {"crank": ["O", "A"]}},
                  "parts": {"width": 8.0, "thickness": 3.0, "pin_diameter": 3.0}}}])


def _design(raw: dict):
    from camgen import api

    return api.design(api.validate(copy.deepcopy(raw)))


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


def test_the_face_meets_its_cam_at_the_contact(faced):
    """The joint of the face and its cam follows the contact along the face: (axis + s', 12 + 30 + s), s' per
    radian of the cycloidal rise (15 mm over 120 degrees) and return (15 mm over 90), at angles through the turn."""
    from camgen.kinds.machine import clash

    _, joints, _ = clash.machine_parts(faced)
    joint = next(j for j in joints if {j.a, j.b} == {"cams.lift", "cams.lift.face"})
    deg = np.array([0.0, 30.0, 60.0, 90.0, 150.0, 200.0, 240.0, 300.0])
    rising, back = deg < 120.0, (deg >= 180.0) & (deg < 270.0)
    u = np.where(rising, deg / 120.0, np.where(back, (deg - 180.0) / 90.0, 0.0))
    bump = u - np.sin(2 * np.pi * u) / (2 * np.pi)
    s = 15.0 * np.where(rising, bump, np.where(back, 1.0 - bump, np.where(deg < 180.0, 1.0, 0.0)))
    rate = 15.0 * (1.0 - np.cos(2 * np.pi * u))
    s1 = np.where(rising, rate / math.radians(120.0), np.where(back, -rate / math.radians(90.0), 0.0))
    assert joint.centre(np.radians(deg)) == pytest.approx(np.column_stack([FX + s1, FY + 30.0 + s]), abs=1e-9)


def _rail_corners() -> np.ndarray:
    """The right rail's corners (mm): 0.2 mm clear of the 8 mm stem on x = 0, 3 mm wide, from 1 mm over the roller's
    top at the top of the stroke (30 + 5 + 10 + 5 + 1) to the stem's top at lift 0 (the roller's centre at 35 plus
    its length, twice the stroke plus its width: 28); then its one lug (the rail, 12 mm, is shorter than two): 7.4 mm
    square (the M3 clearance hole, 3.4 mm, with 2 mm of wall each side) on its outer side, in its middle."""
    x0, x1, y0, y1 = 4.2, 7.2, 51.0, 63.0
    lug = 3.4 + 4.0
    ym = (y0 + y1) / 2
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1],
                     [x1 + lug, ym - lug / 2], [x1 + lug, ym + lug / 2]])


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
    """Both rails where the rules put them at every angle, from the frame up to the stem's plane, never meeting the
    stem or the roller over the turn (the clash check names neither pair)."""
    from camgen.kinds.machine.clash import outlines

    rails = {b.name: b for b in swept.bodies if ".guide." in b.name}
    assert sorted(rails) == ["cams.lift.guide.left", "cams.lift.guide.right"]
    x0, y0 = _rail_corners()[0]
    y1 = _rail_corners()[2][1]
    x1 = _rail_corners()[4][0]                              # the lug's outer side
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    for name, (a, b) in (("cams.lift.guide.right", (x0, x1)), ("cams.lift.guide.left", (-x1, -x0))):
        assert (rails[name].low, rails[name].high) == (0, 1)      # standing on the frame up to the stem's plane
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
